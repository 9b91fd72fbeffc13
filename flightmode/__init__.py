"""flightmode: physics-simulated, labelled sensor data for a package in an airliner, and the
flight-mode detector that switches a GSM tracker off in flight.

The installed package maps the repository's rooms into one namespace: :mod:`flightmode.scenarios`,
:mod:`flightmode.sim` (``.flight`` and ``.sensor``), :mod:`flightmode.detector`,
:mod:`flightmode.nav` and :mod:`flightmode.viz`. Importing ``flightmode`` imports nothing heavy; the
pipeline API is loaded on first use.
"""

from __future__ import annotations

__version__ = "0.1.0"
