"""Aircraft profiles: the schema (:mod:`.profile`: :class:`~.profile.AircraftProfile`, with the pilot's
:mod:`.tuning` and the real-traffic :mod:`.performance` figures), one module per type (:mod:`.b737`,
:mod:`.a320`, :mod:`.fokker100`, :mod:`.b787_8`) and the lookup (:func:`.registry.get_profile`). Imports
only flightmode's base modules. Nothing is imported here at package import time."""
