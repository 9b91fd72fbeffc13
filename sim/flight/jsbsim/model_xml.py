"""Reading and writing JSBSim model XML: the one set of helpers the model surgery shares (the private
copy's tug, :mod:`~flightmode.sim.flight.jsbsim.model_copy`; the gear,
:mod:`~flightmode.sim.flight.jsbsim.gear`; the model edits,
:mod:`~flightmode.sim.flight.jsbsim.model_edits`; the roughness forces,
:mod:`~flightmode.sim.flight.jsbsim.roughness_model`).

A JSBSim model file gives each length, spring and damper its unit in a ``unit`` attribute (JSBSim
reference manual, "Units"); these helpers turn them into SI once, on reading.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

from flightmode.errors import AircraftError
from flightmode.units import FT_M, IN_M, LBF_N

LENGTH_UNITS_M = {"IN": IN_M, "FT": FT_M, "M": 1.0}  # the length units of a JSBSim model file, in metres
SPRING_UNITS = {"LBS/FT": LBF_N / FT_M, "N/M": 1.0}  # a contact's spring_coeff, to N/m
DAMP_UNITS = {"LBS/FT/SEC": LBF_N / FT_M, "N/M/SEC": 1.0}  # a linear damping_coeff, to N s/m
DAMP2_UNITS = {"LBS/FT2/SEC2": LBF_N / FT_M**2, "N/M2/SEC2": 1.0}  # a SQUARE damping_coeff, to N s^2/m^2


def xml_sub(parent: ET.Element, tag: str, text: str | None = None, **attrib) -> ET.Element:
    """A new child ``tag`` of ``parent`` with ``attrib`` and, if given, ``text``: one way for the model
    edits (the private copy's pushback force, :mod:`~flightmode.sim.flight.jsbsim.roughness_model`,
    :mod:`~flightmode.sim.flight.jsbsim.model_edits`) to write JSBSim XML."""
    el = ET.SubElement(parent, tag, attrib)
    if text is not None:
        el.text = text
    return el


def external_reactions(root: ET.Element) -> ET.Element:
    """The model's ``external_reactions`` element, made empty if there is none: external_reactions
    must come after ground_reactions in the document."""
    ext = root.find("external_reactions")
    if ext is None:
        ext = ET.Element("external_reactions")
        children = list(root)
        idx = next((i + 1 for i, c in enumerate(children) if c.tag == "ground_reactions"), len(children))
        root.insert(idx, ext)
    return ext


def xml_number(el: ET.Element | None, what: str) -> float:
    """The number in ``el``'s text (an :class:`AircraftError` naming ``what`` if there is none)."""
    try:
        if el is None or el.text is None:
            raise ValueError(what)
        return float(el.text)
    except ValueError:
        raise AircraftError(
            f"gear contact has no numeric {what}: cannot couple runway roughness to it"
        ) from None


def xml_converted(el: ET.Element, units: dict[str, float], default: str, what: str) -> float:
    """``el``'s number in SI: times ``units[el's unit attribute]`` (``default`` when it has none)."""
    unit = el.get("unit", default)
    if unit not in units:
        raise AircraftError(f"gear contact {what} in unit '{unit}'; allowed: {', '.join(units)}")
    return xml_number(el, what) * units[unit]


def damping(el: ET.Element | None) -> tuple[float, float]:
    """(linear N s/m, square N s^2/m^2) of a damping_coeff element (JSBSim: linear unless type SQUARE)."""
    if el is None:
        return 0.0, 0.0
    if el.get("type") == "SQUARE":
        return 0.0, xml_converted(el, DAMP2_UNITS, "LBS/FT2/SEC2", "square damping")
    return xml_converted(el, DAMP_UNITS, "LBS/FT/SEC", "damping"), 0.0


__all__ = [
    "DAMP2_UNITS",
    "DAMP_UNITS",
    "LENGTH_UNITS_M",
    "SPRING_UNITS",
    "damping",
    "external_reactions",
    "xml_converted",
    "xml_number",
    "xml_sub",
]
