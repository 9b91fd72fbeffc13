"""The one small error hierarchy of flightmode.

Every room raises a subclass of :class:`FlightmodeError`; a message names what is wrong (the file,
the key path, the value), what is allowed, and how to fix it, with the nearest valid name for a
misspelling (:func:`did_you_mean`). The command line prints one on one line and exits with status 2.

    FlightmodeError
    +-- ScenarioError        a scenario (file, built-in name, override) that cannot be flown as written
    +-- AircraftError        an aircraft with no profile, or a model JSBSim cannot load
    +-- FlightDivergedError  a flight that failed: NaN, divergence, a crash, an exceeded limit
    +-- SensorError          a sensor preset, parameter or stream that cannot be sensed as asked
    |   +-- CarrierError     a carrier (the bag's life) that cannot be laid on the flight
    +-- DetectorError        detector parameters or an input stream the detector cannot use
    +-- NavError             a path estimate that cannot be made from the input given
    +-- InputDataError       a file or folder that is not what flightmode wrote (run folder, Parquet)
    +-- DatasetError         a dataset that cannot be made as asked (its folder, its options, its cluster)
    +-- FlightTimeoutError   a flight that exceeded a dataset's per-flight wall-time limit
    +-- ClusterError         a Dask scheduler that does not answer or has no worker
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable


class FlightmodeError(Exception):
    """Base of every error flightmode raises on purpose."""


class ScenarioError(FlightmodeError):
    """A scenario that cannot be flown as written."""


class AircraftError(FlightmodeError):
    """An aircraft model that flightmode has no profile for, or that JSBSim cannot load."""


class FlightDivergedError(FlightmodeError):
    """A simulated flight that failed: NaN, divergence, a crash, an exceeded limit.

    Carries the phase and simulated time at which it happened and, for a limit, which one: ``kind``
    (a stable key, one per limit: the rows of docs/failures.md), the ``quantity`` that broke it (its
    name and unit), its ``value`` and the ``limit`` it broke (None where a failure has no number).
    """

    def __init__(
        self,
        cause: str,
        *,
        phase: str,
        t_s: float,
        kind: str | None = None,
        quantity: str | None = None,
        value: float | None = None,
        limit: float | None = None,
    ) -> None:
        self.cause = cause
        self.phase = phase
        self.t_s = t_s
        self.kind = kind
        self.quantity = quantity
        self.value = value
        self.limit = limit
        super().__init__(f"flight failed in phase '{phase}' at t = {t_s:.2f} s: {cause}")

    def __reduce__(self):  # picklable across processes (Dask workers) despite keyword-only arguments
        return (
            _flight_diverged,
            (self.cause, self.phase, self.t_s, self.kind, self.quantity, self.value, self.limit),
        )


def _flight_diverged(
    cause: str,
    phase: str,
    t_s: float,
    kind: str | None = None,
    quantity: str | None = None,
    value: float | None = None,
    limit: float | None = None,
) -> FlightDivergedError:
    return FlightDivergedError(
        cause, phase=phase, t_s=t_s, kind=kind, quantity=quantity, value=value, limit=limit
    )


class SensorError(FlightmodeError):
    """A sensor preset, parameter or input stream that cannot be sensed as asked."""


class CarrierError(SensorError):
    """A carrier specification that cannot be laid on the flight."""


class DetectorError(FlightmodeError):
    """Detector parameters or an input stream that the detector cannot use."""


class NavError(FlightmodeError):
    """A path estimate that cannot be made from the input given."""


class InputDataError(FlightmodeError):
    """A file or folder that is not what flightmode wrote, or is damaged."""


class DatasetError(FlightmodeError):
    """A dataset that cannot be made as asked (its folder, its options, its cluster)."""


class FlightTimeoutError(FlightmodeError):
    """A flight that took longer than the dataset's per-flight wall-time limit."""


class ClusterError(FlightmodeError):
    """A Dask cluster that cannot be used: a scheduler that does not answer, or has no worker."""


def did_you_mean(name: str, allowed: Iterable[str]) -> str:
    """Return ' (did you mean "x"?)' for the closest allowed name, or '' when none is close."""
    close = difflib.get_close_matches(str(name), [str(a) for a in allowed], n=1, cutoff=0.5)
    return f' (did you mean "{close[0]}"?)' if close else ""


def first_nonfinite(x, axis: int = 0) -> int | None:
    """The index along ``axis`` (the samples) of the first sample holding a NaN or an infinity in any
    of its values, or None when every value is finite: the one test behind each room's "NaN or inf at
    sample i" message."""
    import numpy as np

    ok = np.isfinite(np.asarray(x, dtype=float))
    if ok.all():
        return None
    bad = ~ok
    if bad.ndim > 1:
        bad = np.moveaxis(bad, axis, 0).reshape(bad.shape[axis], -1).any(axis=1)
    return int(np.flatnonzero(bad)[0])
