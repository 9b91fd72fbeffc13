"""Flying, in three subpackages and the modules beside them:

- :mod:`.jsbsim`: JSBSim surgery, the only ``import jsbsim`` (the adapter, the model copy and its edits,
  the gear, the runway roughness forces);
- :mod:`.aircraft`: the aircraft profiles (schema, one module per type, the lookup);
- :mod:`.pilot`: the pilot (phase sequencing, transition table, per-phase controllers, autopilot);
- here: the flight loop (:mod:`.simulate`), the FlightTrack (:mod:`.track`), the flight plan
  (:mod:`.plan`) and each flight's draws (:mod:`.draws`), geodesy, the atmosphere, turbulence, cabin
  pressure, runway roughness profiles, taxi routes and the real taxi figures, flight metrics.

Inside: the pilot and the flight loop import :mod:`.jsbsim` and :mod:`.aircraft`, never the reverse.
Never imports the sensor side. Nothing is imported here at package import time."""
