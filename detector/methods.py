"""The table of detection methods by name, as ``flightmode detect --method`` and the sweep take them:
seed 000's moving variance (``nmv``, ``emv``), the redundant rule with a barometer (``nmv+baro``,
``emv+baro``: :mod:`flightmode.detector.pressure`), and seed 001's nine (in)activity detectors
(:mod:`flightmode.detector.activity.registry`) with seed 000's decision rule. A lookup of an unknown
name raises :class:`~flightmode.errors.DetectorError` with the nearest name; there is no default.
Importing this module imports no detector (and no NumPy).

    >>> from flightmode.detector import methods
    >>> methods.get("emv").kind, methods.get("ared").needs_gyro
    ('moving_variance', True)
"""

from __future__ import annotations

from dataclasses import dataclass

from flightmode.errors import DetectorError, did_you_mean


@dataclass(frozen=True, slots=True)
class Method:
    """One row: ``kind`` says which evaluation runs it (``moving_variance``: seed 000 eq. 1-9;
    ``redundant``: the moving variance AND the pressure source; ``activity``: a seed 001 detector);
    ``base``: the moving variance of a redundant rule, or the seed 001 detector's name;
    ``needs_gyro``: it reads the gyroscope whatever its input signal."""

    name: str
    kind: str
    base: str
    needs_gyro: bool
    doc: str


def _table() -> dict[str, Method]:
    from flightmode.detector.activity import registry

    rows = [
        Method("nmv", "moving_variance", "nmv", False, "seed 000's normal moving variance (eq. 1-2)"),
        Method("emv", "moving_variance", "emv", False, "seed 000's exponential moving variance (eq. 3-5)"),
        Method("nmv+baro", "redundant", "nmv", False, "NMV, and the barometer to resume"),
        Method("emv+baro", "redundant", "emv", False, "EMV, and the barometer to resume"),
    ]
    for name in registry.NAMES:
        d = registry.get(name)
        rows.append(Method(name, "activity", name, d.needs_gyro, f"{d.title} ({d.equations})"))
    return {m.name: m for m in rows}


def names() -> tuple[str, ...]:
    """Every method name, in the table's order."""
    return tuple(_table())


def get(name: str) -> Method:
    """The method called ``name`` (case-insensitive); a DetectorError naming the nearest otherwise."""
    table = _table()
    key = name.strip().lower()
    if key not in table:
        activity = [n for n, m in table.items() if m.kind == "activity"]
        raise DetectorError(
            f"--method {name!r}: use 'nmv' or 'emv' (seed 000) or one of seed 001's detectors: "
            f"{', '.join(activity)}; or nmv+baro, emv+baro (the redundant rule with a barometer)"
            f"{did_you_mean(key, tuple(table))}"
        )
    return table[key]


__all__ = ["Method", "get", "names"]
