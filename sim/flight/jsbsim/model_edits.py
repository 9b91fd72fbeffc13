"""flightmode's changes to the stock JSBSim models, each applied to the private copy of the model's
XML (:func:`flightmode.sim.flight.jsbsim.model_copy.private_model_copy`) and each with its reason:

- every type: the main gear's strut (:func:`flightmode.sim.flight.jsbsim.gear.soften_main_gear`): the stock
  stiff springs and linear dampers made touchdowns 2-5 times too hard; and the nose gear's damper,
  quadratic like the mains', scaled to its share of the weight, its stock spring kept
  (:func:`flightmode.sim.flight.jsbsim.gear.soften_nose_gear`): the stock linear one turned the nose wheels'
  contact into the landing's highest load (2.2 g on the 787-8);
- every type: wing-tip contact points inside the span (:func:`place_wing_tip_contacts`). The stock
  Fokker 100 puts its wing's STRUCTURE contacts 1,105 in (28.1 m) either side of the centreline, its
  whole span (the model's own wingspan: 92.13 ft), so its "wing tip" met the runway at 3.8 deg of bank
  in a gusty flare, a one-step 3.75 g spike; at the tip (14.0 m) it needs about twice the bank. The
  787-8's sit at its half span (2 % outside) and stay; the 737 model has no wing contacts and the
  A320's wing tips are BOGEY contacts, which this does not look at;
- 787-8: a softer nose strut at the stock stance (:func:`flightmode.sim.flight.jsbsim.gear.set_nose_strut`,
  profile ``nose_static_deflection_m``): its stiff stock spring put the cockpit, 23 m ahead of the CG,
  over NASA's 0.4 g on class A runways;
- A320: the elevator's nose-up travel from 25 to 35 degrees. The stock model has no trimmable
  horizontal stabiliser and trims with its elevator alone: on a 3-degree approach with 25 degrees of
  flap it already needs 22 of its 25 degrees of nose-up elevator, so it cannot flare. The real
  A320 trims with its stabiliser (13.5 degrees nose-up) and keeps its 30 degrees of elevator for
  manoeuvre (Airbus A320 FCOM, flight controls description); the extra travel stands in for the
  stabiliser's authority. The model's elevator coefficients are linear in the deflection, so the
  extension changes nothing below 25 degrees.
- 737: the ground spoilers' lift loss spread over their whole travel (:func:`spread_spoiler_lift_loss`).
  The stock table loses its full 40 % of lift at 10 % of the spoilers' travel, reached 0.06 s after
  the first wheel contact (the panels take 0.6 s to open): the centre of gravity's load factor fell
  from 1.1 to 0.55-0.75 g within a tenth of a second after a light touchdown, a drop the
  accelerometer records and no airliner shows. Small spoiler deflections barely change a wing's lift
  (near the stall they even raise it: Lindsay and Walsh 2018, "Experimental investigation of spoiler
  deployment on wing stall", Open Journal of Fluid Dynamics 8, 308-320), and the stock Fokker 100
  model's lift loss is linear in the spoilers' position; the edit keeps the 737's 40 % at full
  travel and makes it grow linearly to there.
- A320: ground spoilers (:func:`add_ground_spoilers`). The stock model has a speedbrake (drag only)
  and no spoiler lift term, so its wing kept lifting after touchdown and its nose could only be let
  fall (4.9-6.4 deg/s) or held up by the elevator. The real A320 extends all its spoiler panels as
  ground spoilers at touchdown (Airbus A320 FCOM, flight controls: ground spoiler function); the edit
  gives the model the stock 737's lift dump: the same 0.6 s travel and 40 % of the wing's lift lost at
  full travel, grown linearly (as :func:`spread_spoiler_lift_loss` makes the 737's). Lift only: the
  737's spoiler drag is not added (the A320's speedbrake already gives its rollout drag).
- A320: the nose tyre's side-force peak (:func:`set_nose_side_friction`). JSBSim takes a tyre's
  side-force peak (its Pacejka curve's ``Peak``) from the contact's ``static_friction``. The stock
  A320 pairs 0.5 static with 0.8 dynamic on every gear, the reverse of the stock 737 and Fokker 100
  (0.80 static, 0.50 dynamic); with its nose gear carrying about 5 % of the weight, the nose wheel
  could build the yaw rate at only 1.7-2.1 deg/s^2 (0.5 s means, 6 pattern taxis), so its turns were
  flown at 5-7 deg/s where real taxi tracks reach 4.8-9.1 (sim.flight.taxi_stats) and half its
  taxi legs turned slower than the slowest real one. The edit gives the nose tyre the other models'
  0.80: 2.2-3.9 deg/s^2, turns at the default 7-10 deg/s.
"""

from __future__ import annotations

import functools
import math
import xml.etree.ElementTree as ET
from typing import cast

from flightmode.errors import AircraftError
from flightmode.sim.flight.jsbsim.gear import nose_gear, set_nose_strut, soften_main_gear, soften_nose_gear
from flightmode.sim.flight.jsbsim.model_xml import LENGTH_UNITS_M, xml_sub


def extend_elevator_nose_up(root: ET.Element, nose_up_deg: float) -> None:
    """Move the nose-up end of the elevator's travel (the ``range`` minimum of the FCS's
    ``aerosurface_scale`` elements that map the pitch command to the elevator angle, and the
    ``domain`` minimum of those that normalise it back) to ``-nose_up_deg``."""
    changed = 0
    for scale in root.iterfind(".//flight_control//aerosurface_scale"):
        name = (scale.get("name") or "").lower()
        if "elevator" not in name:
            continue
        for tag in ("range", "domain"):
            el = scale.find(f"{tag}/min")
            if el is not None and float(cast(str, el.text)) < 0 and ("control" in name or tag == "domain"):
                el.text = f"{-nose_up_deg:g}"
                changed += 1
    if changed == 0:
        raise AircraftError("no elevator aerosurface_scale found to extend")


def spread_spoiler_lift_loss(root: ET.Element) -> None:
    """Stretch the spoiler lift tables (those of ``fcs/spoiler-pos-norm``) so that their last breakpoint
    falls at full travel, the lift factors unchanged: a loss that saturated at 10 % of the travel
    then grows linearly over all of it."""
    changed = 0
    for table in root.iterfind(".//aerodynamics//table"):
        var = table.find("independentVar")
        data = table.find("tableData")
        if var is None or data is None or (var.text or "").strip() != "fcs/spoiler-pos-norm":
            continue
        rows = [
            [float(v) for v in line.split()]
            for line in cast(str, data.text).strip().splitlines()
            if line.strip()
        ]
        last = rows[-1][0]
        if last <= 0.0 or any(len(r) != 2 for r in rows):
            raise AircraftError(f"unexpected spoiler lift table {rows}: expected (position, factor) rows")
        data.text = "\n" + "\n".join(f"{r[0] / last:.4f}\t{r[1]:.4f}" for r in rows) + "\n"
        changed += 1
    if changed == 0:
        raise AircraftError("no spoiler lift table (fcs/spoiler-pos-norm) found to spread")


def set_nose_side_friction(root: ET.Element, peak: float) -> None:
    """Set the nose gear's ``static_friction`` (JSBSim's tyre side-force peak) to ``peak``."""
    el = nose_gear(root).find("static_friction")
    if el is None:
        raise AircraftError("the nose gear has no static_friction to set")
    el.text = f" {peak:g} "


GROUND_SPOILER_LIFT_FACTOR = (
    0.6  # the wing's lift with the ground spoilers fully out: the stock 737 model's figure
)
GROUND_SPOILER_TRAVEL_S = 0.6  # the panels' full travel: the stock 737 model's


def add_ground_spoilers(root: ET.Element) -> None:
    """Give a model without ground spoilers the 737's lift dump: a spoiler channel
    (``fcs/spoiler-cmd-norm`` to ``fcs/spoiler-pos-norm`` over ``GROUND_SPOILER_TRAVEL_S``) and a lift
    factor falling linearly with their position to ``GROUND_SPOILER_LIFT_FACTOR`` at full travel,
    applied to the wing's lift (the LIFT axis's ``CLalpha``, as the 737 applies its own to its wing
    terms, not to the elevator's). Lift only: no drag term is added (the A320's rollout drag stays its
    speedbrake's)."""
    if any((el.text or "").strip() == "fcs/spoiler-pos-norm" for el in root.iter("output")) or any(
        fn.get("name") == "aero/function/kCLsp" for fn in root.iter("function")
    ):
        raise AircraftError(
            "the model already has spoilers (fcs/spoiler-pos-norm or aero/function/kCLsp): "
            "edit its own instead of adding a second set"
        )
    fcs, aero = root.find("flight_control"), root.find("aerodynamics")
    wing = (
        None
        if aero is None
        else aero.find("axis[@name='LIFT']/function[@name='aero/coefficient/CLalpha']/product")
    )
    if fcs is None or aero is None or wing is None:  # (no aero means no wing)
        raise AircraftError(
            "no flight_control, or no LIFT axis with a CLalpha product, to add ground spoilers to"
        )
    kin = xml_sub(
        xml_sub(fcs, "channel", name="Ground spoilers (flightmode)"), "kinematic", name="Ground spoilers"
    )
    xml_sub(kin, "input", "fcs/spoiler-cmd-norm")
    traverse = xml_sub(kin, "traverse")
    for pos, t in ((0, 0), (1, GROUND_SPOILER_TRAVEL_S)):
        setting = xml_sub(traverse, "setting")
        xml_sub(setting, "position", str(pos))
        xml_sub(setting, "time", str(t))
    xml_sub(kin, "output", "fcs/spoiler-pos-norm")
    fn = ET.Element("function", name="aero/function/kCLsp")
    xml_sub(fn, "description", "Change_in_lift_due_to_ground_spoilers (flightmode)")
    table = xml_sub(fn, "table")
    xml_sub(table, "independentVar", "fcs/spoiler-pos-norm")
    xml_sub(table, "tableData", f"\n0.0\t1.0\n1.0\t{GROUND_SPOILER_LIFT_FACTOR}\n")
    aero.insert(0, fn)  # before the axes that use it, where the 737 keeps its own
    xml_sub(wing, "property", "aero/function/kCLsp")


def place_wing_tip_contacts(root: ET.Element) -> None:
    """Bring any STRUCTURE contact point beyond the wing tips (more than 5 % outside half the model's
    ``wingspan``) to the tip, keeping its side: a contact there is the wing tip's, placed at the full
    span instead of half of it."""
    span = root.find("metrics/wingspan")
    unit = None if span is None else span.get("unit", "FT").upper()
    if span is None or unit not in LENGTH_UNITS_M:  # (no span means no unit)
        raise AircraftError(
            f"the model's metrics/wingspan is missing or in '{unit}'; allowed: {', '.join(LENGTH_UNITS_M)}"
        )
    half_m = float(cast(str, span.text)) * LENGTH_UNITS_M[unit] / 2.0
    for contact in root.iterfind("ground_reactions/contact[@type='STRUCTURE']"):
        loc = contact.find("location")
        y = None if loc is None else loc.find("y")
        loc_unit = None if loc is None else loc.get("unit", "IN").upper()
        if y is None or loc_unit not in LENGTH_UNITS_M:
            raise AircraftError(
                f"contact {contact.get('name')!r}: no location y in {', '.join(LENGTH_UNITS_M)}"
            )
        y_m = float(cast(str, y.text)) * LENGTH_UNITS_M[loc_unit]
        if abs(y_m) > 1.05 * half_m:
            y.text = f" {math.copysign(half_m, y_m) / LENGTH_UNITS_M[loc_unit]:.2f} "


def edits_for(profile) -> tuple:
    """The model edits of a type (module docstring), as functions of the XML root."""
    edits = [
        functools.partial(soften_main_gear, landing_mass_kg=profile.ref_landing_mass_kg),
        functools.partial(soften_nose_gear, landing_mass_kg=profile.ref_landing_mass_kg),
        place_wing_tip_contacts,
    ]
    if profile.elevator_nose_up_deg is not None:
        edits.append(functools.partial(extend_elevator_nose_up, nose_up_deg=profile.elevator_nose_up_deg))
    if profile.spread_spoiler_lift:
        edits.append(spread_spoiler_lift_loss)
    if profile.add_ground_spoilers:
        edits.append(add_ground_spoilers)
    if profile.nose_static_deflection_m is not None:
        edits.append(
            functools.partial(
                set_nose_strut,
                landing_mass_kg=profile.ref_landing_mass_kg,
                static_deflection_m=profile.nose_static_deflection_m,
            )
        )
    if profile.nose_side_friction is not None:
        edits.append(functools.partial(set_nose_side_friction, peak=profile.nose_side_friction))
    return tuple(edits)
