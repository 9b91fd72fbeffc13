"""JSBSim surgery: the only ``import jsbsim`` in flightmode. The adapter (:mod:`.adapter`: SI channels,
the one place JSBSim's imperial properties are converted), the stock models and their sanitised private
copy (:mod:`.model_copy`), the edits made to that copy (:mod:`.model_edits`, the gear's struts
:mod:`.gear`, the runway roughness forces :mod:`.roughness_model`) with their XML helpers
(:mod:`.model_xml`), and the roughness knots fed at the pilot's ticks (:mod:`.roughness`). Imports only
flightmode's base modules and :mod:`flightmode.sim.flight.runway_roughness`; never the pilot or the
flight loop. Nothing is imported here at package import time."""
