"""The table of seed 001's nine (in)activity detectors: name -> detector (section 2, in the seed's
order). A lookup of an unknown name raises :class:`~flightmode.errors.DetectorError` with the nearest
name; there is no default detector. Importing this module imports no detector (and no NumPy): an
entry resolves its module on first use.

    >>> from flightmode.detector.activity import registry
    >>> registry.get("ltsd").family, registry.get("ltsd").equations
    ('spectrum', 'seed 001, eq. (6)-(7)')
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass

from flightmode.errors import DetectorError, did_you_mean

_PKG = "flightmode.detector.activity"
FLEXIBLE = ("acc", "gyr", "sum", "product")  # = common.SIGNALS (kept here so no NumPy is imported)


@dataclass(frozen=True, slots=True)
class Detector:
    """One row of the table. ``parameters``: the keyword parameters of ``detect`` that have no
    default (besides ``threshold``); ``signals``: the allowed ``signal`` values, () for a fixed input;
    ``needs_gyro``: needs ``gyr_dps`` whatever the signal; ``nonnegative``: the merit is >= 0 (and so
    must the threshold be)."""

    name: str
    title: str
    family: str  # module: magnitude, spectrum or memory
    equations: str
    stream_class: str
    parameters: tuple[str, ...]
    signals: tuple[str, ...]
    needs_gyro: bool
    merit_unit: str
    nonnegative: bool = True

    @property
    def module(self):
        return importlib.import_module(f"{_PKG}.{self.family}")

    @property
    def detect(self):
        """The batch function ``detect_<name>(t_s, acc_g, gyr_dps=None, *, threshold, ...)``."""
        return getattr(self.module, f"detect_{self.name}")

    @property
    def stream(self):
        """The streaming class (``push(t_s, acc_g, gyr_dps=None) -> ActivityResult``)."""
        return getattr(self.module, self.stream_class)


_TABLE = (
    Detector(
        "amvd",
        "Acceleration Moving Variance Detector",
        "magnitude",
        "seed 001, eq. (1)",
        "AMVDStream",
        ("window",),
        (),
        False,
        "g^2",
    ),
    Detector(
        "amd",
        "Acceleration Magnitude Detector",
        "magnitude",
        "seed 001, eq. (2)",
        "AMDStream",
        ("window", "sigma_acc_g"),
        (),
        False,
        "noise variances",
    ),
    Detector(
        "ared",
        "Angular Rate Energy Detector",
        "magnitude",
        "seed 001, eq. (3)",
        "AREDStream",
        ("window", "sigma_gyr_dps"),
        (),
        True,
        "noise variances",
    ),
    Detector(
        "shod",
        "Stance Hypothesis Optimal Detector",
        "magnitude",
        "seed 001, eq. (4)",
        "SHODStream",
        ("window", "sigma_acc_g", "sigma_gyr_dps"),
        (),
        True,
        "noise variances",
    ),
    Detector(
        "frd",
        "Filtered Rectifier Detector",
        "magnitude",
        "seed 001, eq. (5)",
        "FRDStream",
        (),
        FLEXIBLE,
        False,
        "the signal's unit",
    ),
    Detector(
        "ltsd",
        "Long Term Spectral Detector",
        "spectrum",
        "seed 001, eq. (6)-(7)",
        "LTSDStream",
        ("window", "shift"),
        FLEXIBLE,
        False,
        "dB",
        nonnegative=False,
    ),
    Detector(
        "fsd",
        "Framed Spectrum Detector",
        "spectrum",
        "seed 001, eq. (8)",
        "FSDStream",
        ("window", "shift"),
        FLEXIBLE,
        False,
        "dB",
        nonnegative=False,
    ),
    Detector(
        "mbgtd",
        "Memory-Based Graph Theoretic Detector",
        "memory",
        "seed 001, eq. (9)-(10)",
        "MBGTDStream",
        ("window",),
        FLEXIBLE,
        False,
        "the signal's unit",
    ),
    Detector(
        "mbcd",
        "Memory-Based CUSUM Detector",
        "memory",
        "seed 001, eq. (12)-(14)",
        "MBCDStream",
        ("window", "bandwidth"),
        FLEXIBLE,
        False,
        "nats (log-likelihood ratio)",
    ),
)

NAMES: tuple[str, ...] = tuple(d.name for d in _TABLE)
_BY_NAME = {d.name: d for d in _TABLE}


def get(name: str) -> Detector:
    """The detector called ``name`` (case-insensitive: "SHOD" is "shod"), or DetectorError."""
    key = str(name).lower()
    if key not in _BY_NAME:
        raise DetectorError(
            f"no (in)activity detector {name!r}: use one of {', '.join(NAMES)}{did_you_mean(key, NAMES)}"
        )
    return _BY_NAME[key]


def all_detectors() -> tuple[Detector, ...]:
    return _TABLE
