"""Detection methods by name: a view of the detector registry (the entry-point group
``flightmode.detectors``, :mod:`flightmode.detector.interface`), which holds seed 000's moving
variance (``nmv``, ``emv``), the redundant rule with a barometer (``nmv+baro``, ``emv+baro``), the
two-source combinator, seed 001's nine (in)activity detectors, and any plugin. There is no table
here: a row is read from the registered factory (its ``kind``, ``title`` and ``channels``). A lookup
of an unknown name raises :class:`~flightmode.errors.DetectorError` with the nearest name; there is
no default. Importing this module imports no detector (and no NumPy).

    >>> from flightmode.detector import methods
    >>> methods.get("emv").kind, methods.get("ared").needs_gyro
    ('moving_variance', True)
"""

from __future__ import annotations

from dataclasses import dataclass

from flightmode.detector import interface


@dataclass(frozen=True, slots=True)
class Method:
    """One registered detector: ``kind`` as its factory declares it (``moving_variance``,
    ``redundant``, ``activity``, ``pressure``, ``two_source``; ``plugin`` when it says none);
    ``base``: the name; ``needs_gyro``: it reads the gyroscope with its default parameters;
    ``doc``: its title (or the first line of its docstring); ``source``: where it was loaded from."""

    name: str
    kind: str
    base: str
    needs_gyro: bool
    doc: str
    source: str = ""


def names() -> tuple[str, ...]:
    """Every registered detector's name, sorted."""
    return interface.names()


def get(name: str) -> Method:
    """The detector called ``name`` (case-insensitive when one name matches), or ``package.module:make``;
    a DetectorError naming the nearest otherwise."""
    loaded = interface.load(name, what="--method")
    f = loaded.factory
    doc = str(getattr(f, "title", "") or (getattr(f, "__doc__", "") or "").strip().split("\n")[0])
    return Method(
        loaded.name,
        str(getattr(f, "kind", "plugin")),
        loaded.name,
        any(c in interface.GYRO_CHANNELS for c in loaded.channels),
        doc,
        loaded.source,
    )


__all__ = ["Method", "get", "names"]
