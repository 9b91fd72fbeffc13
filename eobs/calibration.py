"""Six-orientation calibration of an e-obs tag and raw counts to g (seed 003 sections 3, 6 and 7).

Section 6: ``a_i = (n_i - n_i,zerog) * c_i * g`` per axis i, along the tag's own axes.

Section 7: lay the tag still in six orientations A-F, "the same as shown above in the images of
chapter 3" (A: Z reads -1 g, B: Z +1 g, C: X -1 g, D: X +1 g, E: Y +1 g, F: Y -1 g, for the new
tags); for each axis, from its mean reading at -1 g and at +1 g,

    n_zerog = (n_-1g + n_+1g) / 2,        c = 2 / (n_+1g - n_-1g)

(the note's example: (1345 + 2255) / 2 = 1800, 2 / (2255 - 1345) = 0.0022). The note reads the
readings off a plot; we take the mean count of each static recording. The other four orientations
also give the zero-g count ("it is the measured", a garbled sentence of the note: the value read in
A, B, E, F); we use the +-1 g pair, the formula the note writes down.

Old tags (numbers up to 2241) have the Y axis reversed (section 2 and the NOTE in section 7): in
orientation E their own Y reads -1 g. :func:`calibrate` takes the six recordings keyed by what the
tag's own axis felt ('+x', '-x', '+y', '-y', '+z', '-z'); :func:`recordings_from_orientations` maps
the note's letters A-F to those keys for a given tag number, swapping E and F for old tags. So a
:class:`Calibration` always holds positive slopes along the tag's own axes, and :func:`to_g` turns
old tags' Y into the newer tags' right-handed frame only when asked (``frame='right-handed'``).

Units: section 6's formula ends in m/s^2, ``a_i = (n_i - n_i,zerog) * c_i * g`` with the note's own
g = 9.81 m/s^2 (section 6's table, "Standard gravitational acceleration on the Earth's surface",
and section 3). :func:`to_g` stops at g; :func:`to_mps2` goes on to m/s^2 with the note's 9.81 by
default (:data:`EOBS_G_MPS2`), or any other g, e.g. ``scipy.constants.g`` (9.80665, the standard
gravity the rest of flightmode uses: 0.034 % smaller, far inside the tags' +-5 % gain spread).

Nominal constants (zero 2048; 0.0022 g/count for tags > 2241, 0.001 / 0.0027 for older tags by their
sensitivity setting: section 6) are used when no calibration is given, with a
:class:`NominalCalibrationWarning` and ``nominal=True`` on the result: section 3 warns "the whole
system is not calibrated or adjusted, so the real values might differ".

Calibration files are small TOML (read with ``tomllib``, written with ``tomli_w``)::

    tag_number = 2242        # optional
    nominal = false
    [X]
    zero_count = 1800.0
    slope_g_per_count = 0.002197802197802198
    [Y] ...
    [Z] ...
"""

from __future__ import annotations

import math
import os
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import cast

import numpy as np

from flightmode.eobs.burst import AccBurst
from flightmode.eobs.tag import (
    ADC_MAX_COUNT,
    AXES,
    NOMINAL_ZERO_COUNT,
    check_tag_number,
    nominal_slope_g_per_count,
    tag_number_from_id,
    y_sign,
)
from flightmode.errors import InputDataError, SensorError, did_you_mean

EOBS_G_MPS2 = 9.81  # seed 003 section 6's table (and section 3): "g = 9.81 m/s^2"
RECORDING_KEYS = ("+x", "-x", "+y", "-y", "+z", "-z")  # the tag's own axis at +1 g / -1 g
# seed 003 chapter 3's images, in section 7's order A-F, for tags from 2242: (axis, g on it)
ORIENTATIONS = {
    "A": ("z", -1),
    "B": ("z", +1),
    "C": ("x", -1),
    "D": ("x", +1),
    "E": ("y", +1),
    "F": ("y", -1),
}
FRAMES = ("tag", "right-handed")


class NominalCalibrationWarning(UserWarning):
    """Counts were converted with section 6's nominal constants, not a calibration of the tag."""


@dataclass(frozen=True, slots=True)
class Calibration:
    """Per axis X, Y, Z: zero-g count and slope (g per count), along the tag's own axes."""

    zero_count: tuple[float, float, float]
    slope_g_per_count: tuple[float, float, float]
    tag_number: int | None = None
    nominal: bool = False

    def __post_init__(self) -> None:
        z = tuple(float(v) for v in self.zero_count)
        c = tuple(float(v) for v in self.slope_g_per_count)
        if len(z) != 3 or len(c) != 3:
            raise SensorError("calibration: need three zero-g counts and three slopes (X, Y, Z)")
        for axis, zi, ci in zip(AXES, z, c):
            if not (math.isfinite(zi) and 0 <= zi <= ADC_MAX_COUNT):
                raise SensorError(f"calibration {axis}: zero-g count {zi} must lie in 0-{ADC_MAX_COUNT}")
            if not (math.isfinite(ci) and ci > 0):
                raise SensorError(f"calibration {axis}: slope {ci} g/count must be > 0")
        if self.tag_number is not None:
            check_tag_number(self.tag_number)
        object.__setattr__(self, "zero_count", z)
        object.__setattr__(self, "slope_g_per_count", c)


def nominal_calibration(tag_number: int, sensitivity: str | None = None) -> Calibration:
    """Section 6's nominal constants for the tag (old tags need 'high' or 'low')."""
    c = nominal_slope_g_per_count(tag_number, sensitivity)
    return Calibration((NOMINAL_ZERO_COUNT,) * 3, (c, c, c), tag_number, nominal=True)


def recordings_from_orientations(by_letter: dict[str, np.ndarray], tag_number: int) -> dict[str, np.ndarray]:
    """Section 7's recordings keyed A-F (chapter 3's orientations) -> keyed by the tag's own axis and
    sign; for tags up to 2241 E and F swap on Y (the reversed axis)."""
    _check_keys(by_letter, tuple(ORIENTATIONS), "orientation")
    s = y_sign(tag_number)
    out = {}
    for letter, (axis, g) in ORIENTATIONS.items():
        if axis == "y":
            g *= s
        out[f"{'+' if g > 0 else '-'}{axis}"] = by_letter[letter]
    return out


def _check_keys(d: dict, allowed: tuple[str, ...], what: str) -> None:
    for k in d:
        if k not in allowed:
            raise SensorError(
                f"unknown {what} {k!r}{did_you_mean(str(k), allowed)}; expected {', '.join(allowed)}"
            )
    missing = [k for k in allowed if k not in d]
    if missing:
        raise SensorError(f"missing {what} recording(s) {', '.join(missing)}; section 7 needs all six")


def calibrate(recordings: dict[str, np.ndarray], tag_number: int | None = None) -> Calibration:
    """Zero-g count and slope per axis from six static recordings (section 7).

    recordings: '+x', '-x', '+y', '-y', '+z', '-z' -> raw counts of shape (n, 3) (X, Y, Z columns),
    the tag still with that own axis at +1 g or -1 g (for the note's letters A-F use
    :func:`recordings_from_orientations`)."""
    _check_keys(recordings, RECORDING_KEYS, "recording")
    means = {}
    for k in RECORDING_KEYS:
        r = np.asarray(recordings[k])
        if r.ndim != 2 or r.shape[1] != 3 or r.shape[0] < 1 or r.dtype.kind not in "iuf":
            raise SensorError(
                f"recording {k!r}: need raw counts of shape (n >= 1, 3) for X, Y, Z, got {r.shape}"
            )
        means[k] = r.astype(float).mean(axis=0)
    zero, slope = [], []
    for j, axis in enumerate("xyz"):
        up, down = means[f"+{axis}"][j], means[f"-{axis}"][j]
        if not up > down:
            hint = (
                " (tags up to 2241 have Y reversed: map A-F with recordings_from_orientations and the tag number)"
                if axis == "y"
                else ""
            )
            raise SensorError(
                f"calibration {axis.upper()}: the +1 g mean {up:.1f} is not above the -1 g mean {down:.1f}: "
                f"the recordings are swapped or not static{hint}"
            )
        zero.append((up + down) / 2)  # section 7: n_zerog = (n_-1g + n_+1g) / 2
        slope.append(2.0 / (up - down))  # section 7: c = 2 / (n_+1g - n_-1g)
    return Calibration(tuple(zero), tuple(slope), tag_number)


@dataclass(frozen=True, slots=True, eq=False)
class AccelerationG:
    """A burst in g: (n, n_axes) along ``axes`` in ``frame``; ``nominal`` if section 6's nominal
    constants were used instead of a calibration."""

    acc_g: np.ndarray
    axes: str
    frame: str
    nominal: bool


def to_g(
    burst: AccBurst,
    calibration: Calibration | None = None,
    *,
    tag_number: int | None = None,
    sensitivity: str | None = None,
    frame: str = "tag",
) -> AccelerationG:
    """Counts to g with section 6's formula: ``(n - n_zerog) * c`` per axis.

    calibration None: the nominal constants of the tag (its number from ``tag_number``, or the burst's
    tag id when that is a number; old tags need ``sensitivity``), with a NominalCalibrationWarning.
    frame 'tag': along the tag's own axes; 'right-handed': old tags' Y negated, so every tag reads in
    the newer tags' right-handed frame (section 2)."""
    if frame not in FRAMES:
        raise SensorError(f"frame {frame!r}{did_you_mean(frame, FRAMES)}; one of {', '.join(FRAMES)}")
    number = tag_number if tag_number is not None else (calibration.tag_number if calibration else None)
    if number is None and (calibration is None or frame == "right-handed"):
        number = tag_number_from_id(burst.tag_id)
    nominal = calibration is None
    if calibration is None:
        assert number is not None  # found above: no calibration needs the tag number
        calibration = nominal_calibration(number, sensitivity)
        warnings.warn(
            f"tag {number}: converting counts with the nominal constants (zero 2048, "
            f"{calibration.slope_g_per_count[0]} g/count; seed 003 section 6), not a calibration of the tag",
            NominalCalibrationWarning,
            stacklevel=2,
        )
    idx = [AXES.index(a) for a in burst.axes]
    zero = np.array(calibration.zero_count)[idx]
    slope = np.array(calibration.slope_g_per_count)[idx]
    acc = (burst.raw.astype(float) - zero) * slope
    if frame == "right-handed" and "Y" in burst.axes:
        assert number is not None  # found above: the right-handed frame needs the tag number
        acc[:, burst.axes.index("Y")] *= y_sign(number)
    return AccelerationG(acc, burst.axes, frame, nominal)


@dataclass(frozen=True, slots=True, eq=False)
class AccelerationMps2:
    """A burst in m/s^2: (n, n_axes) along ``axes`` in ``frame``; ``g_mps2`` the g it was scaled by;
    ``nominal`` as :class:`AccelerationG`'s."""

    acc_mps2: np.ndarray
    axes: str
    frame: str
    nominal: bool
    g_mps2: float


def to_mps2(
    burst: AccBurst,
    calibration: Calibration | None = None,
    *,
    tag_number: int | None = None,
    sensitivity: str | None = None,
    frame: str = "tag",
    g_mps2: float = EOBS_G_MPS2,
) -> AccelerationMps2:
    """Counts to m/s^2 as seed 003 section 6 writes it: ``a_i = (n_i - n_i,zerog) * c_i * g``, with
    the note's g = 9.81 m/s^2 unless ``g_mps2`` is given (module docstring); the other arguments
    as :func:`to_g`'s."""
    if not (math.isfinite(g_mps2) and g_mps2 > 0):
        raise SensorError(f"g = {g_mps2!r} m/s^2: must be a positive number (the note's is {EOBS_G_MPS2})")
    a = to_g(burst, calibration, tag_number=tag_number, sensitivity=sensitivity, frame=frame)
    nominal = a.nominal or (calibration is not None and calibration.nominal)  # a nominal Calibration passed
    return AccelerationMps2(a.acc_g * g_mps2, a.axes, a.frame, nominal, float(g_mps2))  # section 6


# ------------------------------------------------------------------------------------------------ TOML


def calibration_to_toml(cal: Calibration) -> str:
    import tomli_w

    doc: dict = {}
    if cal.tag_number is not None:
        doc["tag_number"] = cal.tag_number
    doc["nominal"] = cal.nominal
    for axis, z, c in zip(AXES, cal.zero_count, cal.slope_g_per_count):
        doc[axis] = {"zero_count": z, "slope_g_per_count": c}
    return tomli_w.dumps(doc)


def calibrate_movebank(files: Mapping[str, str | os.PathLike], tag_number: int | None = None) -> Calibration:
    """:func:`calibrate` on six Movebank e-obs files (``flightmode eobs calibrate``): ``files`` maps
    '+x', '-x', '+y', '-y', '+z', '-z' to a file whose bursts all hold the tag still in that
    orientation, each burst of all three axes (XYZ); an InputDataError names a file that is not."""
    from flightmode.eobs.movebank import read_movebank

    recs = {}
    for key, path in files.items():
        bursts = [r.burst for r in read_movebank(path).rows if r.burst is not None]
        if not bursts or any(b.axes != "XYZ" for b in bursts):
            raise InputDataError(f"{path}: the {key} recording needs bursts of all three axes (XYZ)")
        recs[key] = np.concatenate([b.raw for b in bursts])
    return calibrate(recs, tag_number)


def write_calibration(cal: Calibration, path: str | os.PathLike) -> Path:
    from flightmode.atomic import write_text

    return write_text(calibration_to_toml(cal), Path(path), mkdir=False)


def read_calibration(path: str | os.PathLike) -> Calibration:
    """A calibration TOML (module docstring); InputDataError naming the file, key and value."""
    import tomllib

    path = Path(path)
    try:
        doc = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as e:
        raise InputDataError(f"{path}: cannot read ({e.strerror})") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
        raise InputDataError(f"{path}: not TOML ({e})") from None
    return calibration_from_dict(doc, str(path))


def calibration_from_dict(doc: dict, source: str = "<calibration>") -> Calibration:
    top = ("tag_number", "nominal", *AXES)
    for k in doc:
        if k not in top:
            raise InputDataError(
                f"{source}: unknown key {k!r}{did_you_mean(k, top)}; allowed: {', '.join(top)}"
            )
    tag = doc.get("tag_number")  # optional key: absent means the tag is not named
    if tag is not None and (isinstance(tag, bool) or not isinstance(tag, int) or tag < 1):
        raise InputDataError(f"{source}: tag_number = {tag!r}: must be an integer >= 1")
    if "nominal" not in doc or not isinstance(doc["nominal"], bool):
        raise InputDataError(f"{source}: nominal = {doc.get('nominal')!r}: must be true or false")
    zero, slope = [], []
    for axis in AXES:
        t = doc.get(axis)
        if not isinstance(t, dict):
            raise InputDataError(f"{source}: [{axis}]: missing table with zero_count and slope_g_per_count")
        for k in t:
            if k not in ("zero_count", "slope_g_per_count"):
                raise InputDataError(
                    f"{source}: {axis}.{k}: unknown key{did_you_mean(k, ('zero_count', 'slope_g_per_count'))}"
                )
        z, c = t.get("zero_count"), t.get("slope_g_per_count")
        if isinstance(z, bool) or not isinstance(z, (int, float)) or not 0 <= z <= ADC_MAX_COUNT:
            raise InputDataError(
                f"{source}: {axis}.zero_count = {z!r}: must be a number in 0-{ADC_MAX_COUNT}"
            )
        if isinstance(c, bool) or not isinstance(c, (int, float)) or not (math.isfinite(c) and c > 0):
            raise InputDataError(
                f"{source}: {axis}.slope_g_per_count = {c!r}: must be a number > 0 (g per count)"
            )
        zero.append(float(z))
        slope.append(float(c))
    # one value per axis of AXES: three each
    zero3 = cast("tuple[float, float, float]", tuple(zero))
    slope3 = cast("tuple[float, float, float]", tuple(slope))
    return Calibration(zero3, slope3, tag, doc["nominal"])
