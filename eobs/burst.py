"""One e-obs acceleration burst: the typed unit every other e-obs module reads and writes.

Seed 003 section 4.1: the tag records acceleration in bursts (ACC BYTE COUNT samples every ACC
interval); section 5.2 and Table 1: the enabled axes are recorded in alphabetical order (X, Y, Z;
any non-empty subset), samples interleaved one per axis; section 5.4: the raw samples are "digital
readings between 0 and 4095", made at the per-axis sampling frequency "starting with the first
sample at the time described in the field 'start-timestamp'" (but see :mod:`flightmode.eobs.timing`
for the start delay of older tags).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flightmode.eobs.tag import ADC_MAX_COUNT, ADC_MIN_COUNT
from flightmode.errors import SensorError, did_you_mean

# seed 003 section 5.2, Table 1: every non-empty subset of X, Y, Z, in alphabetical order
AXES_SETS = ("XYZ", "XY", "XZ", "YZ", "X", "Y", "Z")
UINT32_MAX = 2**32 - 1


def check_axes(axes: str) -> str:
    """``axes`` if it is one of Table 1's sequences (seed 003 section 5.2), else SensorError."""
    if axes not in AXES_SETS:
        raise SensorError(
            f"acceleration axes {axes!r}: must be X, Y and/or Z in alphabetical order (seed 003 Table 1): "
            f"one of {', '.join(AXES_SETS)}{did_you_mean(axes, AXES_SETS)}"
        )
    return axes


@dataclass(frozen=True, slots=True, eq=False)
class AccBurst:
    """One burst of raw ADC counts.

    tag_id: the tag (decoder file: ``tag-serial-number``; Movebank export: ``tag-local-identifier``
        or, where the export has none, ``individual-local-identifier``).
    start_time: the burst's start timestamp, ``numpy.datetime64`` in ns, UTC.
    axes: the enabled axes in alphabetical order ('XYZ', 'XY', 'XZ', 'YZ', 'X', 'Y' or 'Z').
    rate_hz: sampling frequency per axis (seed 003 sections 4.2 and 5.4).
    raw: (n, len(axes)) integer counts 0..4095; row k is the k-th sample of every enabled axis.
    checksum: ``eobs:key-bin-checksum``, an unsigned 32-bit integer (seed 003 section 5.4 does not say
        how it is computed; simulated bursts carry 0).
    """

    tag_id: str
    start_time: np.datetime64
    axes: str
    rate_hz: float
    raw: np.ndarray
    checksum: int

    def __post_init__(self) -> None:
        if not isinstance(self.tag_id, str) or not self.tag_id:
            raise SensorError(f"burst tag id {self.tag_id!r}: must be a non-empty string")
        try:
            # numpy's stubs reject np.datetime64(datetime64, unit), numpy's documented unit conversion
            # (fixed in numpy/numpy#31883: unused-ignore keeps a numpy with the fix quiet)
            t = np.datetime64(self.start_time, "ns")  # type: ignore[call-overload, unused-ignore]
        except (TypeError, ValueError) as e:
            raise SensorError(f"burst start time {self.start_time!r}: not a time ({e})") from None
        if np.isnat(t):
            raise SensorError("burst start time is NaT")
        object.__setattr__(self, "start_time", t)
        check_axes(self.axes)
        rate = float(self.rate_hz)
        if not (math.isfinite(rate) and rate > 0):
            raise SensorError(
                f"burst sampling frequency per axis {self.rate_hz!r} Hz: must be a finite number > 0"
            )
        object.__setattr__(self, "rate_hz", rate)
        raw = np.asarray(self.raw)
        if raw.dtype.kind not in "iu":
            raise SensorError(f"burst raw counts: must be integers, got dtype {raw.dtype}")
        if raw.ndim != 2 or raw.shape[1] != len(self.axes) or raw.shape[0] < 1:
            raise SensorError(
                f"burst raw counts: shape must be (n >= 1, {len(self.axes)}) for axes {self.axes!r}, got {raw.shape}"
            )
        bad = np.flatnonzero((raw < ADC_MIN_COUNT) | (raw > ADC_MAX_COUNT))
        if bad.size:
            raise SensorError(
                f"burst raw counts: value {raw.ravel()[bad[0]]} (interleaved sample #{bad[0] + 1}) is outside "
                f"the ADC's {ADC_MIN_COUNT}-{ADC_MAX_COUNT} (seed 003 section 5.4)"
            )
        raw = raw.astype(np.int16)  # a copy: 12-bit counts fit, and the caller's array stays theirs
        raw.flags.writeable = False
        object.__setattr__(self, "raw", raw)
        if (
            isinstance(self.checksum, bool)
            or not isinstance(self.checksum, (int, np.integer))
            or not (0 <= int(self.checksum) <= UINT32_MAX)
        ):
            raise SensorError(
                f"burst checksum {self.checksum!r}: must be an unsigned 32-bit integer (0-{UINT32_MAX})"
            )
        object.__setattr__(self, "checksum", int(self.checksum))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, AccBurst):
            return NotImplemented
        return (
            self.tag_id == other.tag_id
            and self.start_time == other.start_time
            and self.axes == other.axes
            and self.rate_hz == other.rate_hz
            and self.checksum == other.checksum
            and np.array_equal(self.raw, other.raw)
        )

    __hash__ = None  # type: ignore[assignment]  # holds an array

    @property
    def n_samples(self) -> int:
        """Samples per axis (N of seed 003 section 11)."""
        return int(self.raw.shape[0])

    @property
    def total_rate_hz(self) -> float:
        """Sampling frequency of all axes together: per axis times the number of axes (section 4.2)."""
        return self.rate_hz * len(self.axes)

    @property
    def duration_s(self) -> float:
        """n / f: the span the burst's samples cover at its per-axis rate (section 10's 792 / 100 Hz)."""
        return self.n_samples / self.rate_hz

    def axis(self, name: str) -> np.ndarray:
        """The counts of one axis ('X', 'Y' or 'Z'), shape (n,)."""
        if name not in self.axes:
            raise SensorError(f"axis {name!r} is not recorded in this burst (axes {self.axes!r})")
        return self.raw[:, self.axes.index(name)]

    def interleaved(self) -> np.ndarray:
        """The counts in recording order X Y Z X Y Z ... (section 5.2), shape (n * len(axes),)."""
        return self.raw.ravel()
