"""The pilot: the phase sequencing (:mod:`.pilot`) over the transition table (:mod:`.phases`), one
controller per phase grouped by phase (:mod:`.ground`, :mod:`.taxi`, :mod:`.takeoff`, :mod:`.enroute`,
:mod:`.flare`, :mod:`.go_around`, :mod:`.rollout`; the table :mod:`.controllers`), the shared loops
(:mod:`.autopilot`, :mod:`.control`, :mod:`.energy`) and the step climb (:mod:`.step_climb`). May import
:mod:`flightmode.sim.flight.jsbsim` and :mod:`flightmode.sim.flight.aircraft`, which never import it.
Nothing is imported here at package import time."""
