"""Runway roughness written into a JSBSim model: the gear groups read from the model's contacts, and
one external force per group whose magnitude JSBSim interpolates from knots that
:class:`~flightmode.sim.flight.jsbsim.roughness.GearRoughness` writes at the pilot's ticks (the
profiles: :mod:`flightmode.sim.flight.runway_roughness`).

Coupling (JSBSim's FGLGear::ComputeVerticalStrutForce): a strut of spring k and damper law D pushes
with k delta + D(delta_dot), delta its compression; ground raised by h under the wheel compresses it h
more. JSBSim's gear has no tyre: its wheel is the end of the strut. A real leg's tyre (stiffness k_t)
in series with the strut's damper c lets the strut follow the ground only below about
(k_t + k) / (2 pi c), a few Hz, and carries what is above it on the tyre; so the wheel height w is the
profile through a first-order lag tau = c / (k_t + k) (massless wheel), and each group's extra force is
k w + D(w_dot), with D the contact's own law (linear or square, compression or rebound coefficient by
the sign of w_dot). k_t is the group's static load over :data:`TYRE_DEFLECTION_M` (0.08 m: a ~0.3 m
airliner tyre section deflects about a third of its height at rated load, recalled from tyre design
practice): tau = 0.02-0.1 s for the mains of these models (1.6-8 Hz). The force is a LOCAL-frame
(earth-vertical, as the gear's ground-normal reaction) external force at the group's mean contact
location, times the group's weight on wheels: it acts only while that wheel is on the ground. Spring,
damping and locations are read from the contact elements of the model copy, after flightmode's own
gear edits. The nose runs a wheelbase ahead of the mains.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

from flightmode.errors import AircraftError
from flightmode.sim.flight.jsbsim.model_xml import (
    LENGTH_UNITS_M,
    SPRING_UNITS,
    damping,
    external_reactions,
    xml_converted,
    xml_number,
    xml_sub,
)

KNOT_S = 1.0 / 40.0  # time between force knots
RING = 8  # knot slots in the model, written round and round (> roughness.MAX_KNOTS)
GEAR_LEVEL_M = 0.6  # BOGEY contacts within this of the lowest one are gear (not tail, engine, wingtip)


def gear_groups(root: ET.Element) -> dict[str, dict]:
    """The model's wheels in three groups (nose, left, right main), each with its summed spring
    (N/m), damping law (compression and rebound, linear and square), k-weighted structural location
    (m) and the indices of its contacts (``gear/unit[i]``).

    Gear contacts are the BOGEY contacts within :data:`GEAR_LEVEL_M` of the lowest one (some stock
    models, the A320's, give tail, engine and wingtip bumpers the BOGEY type too); the nose group is
    those forward of the middle of their x range, the mains split by the sign of y."""
    gr = root.find("ground_reactions")
    contacts = [] if gr is None else gr.findall("contact")
    rows = []
    for i, c in enumerate(contacts):
        if c.get("type") != "BOGEY":
            continue
        loc = c.find("location")
        if loc is None:
            raise AircraftError(f"gear contact '{c.get('name')}' has no location")
        scale = LENGTH_UNITS_M.get(loc.get("unit", "IN"))
        if scale is None:
            raise AircraftError(
                f"gear contact location unit '{loc.get('unit')}'; allowed: {', '.join(LENGTH_UNITS_M)}"
            )
        xyz = [xml_number(loc.find(a), f"location {a}") * scale for a in "xyz"]
        rows.append((i, c, xyz))
    if not rows:
        raise AircraftError("the model has no BOGEY gear contact to couple runway roughness to")
    z_low = min(r[2][2] for r in rows)
    gear = [r for r in rows if r[2][2] <= z_low + GEAR_LEVEL_M]
    xs = [r[2][0] for r in gear]
    x_mid = 0.5 * (min(xs) + max(xs))
    members = {
        "nose": [r for r in gear if r[2][0] < x_mid],
        "left": [r for r in gear if r[2][0] >= x_mid and r[2][1] < 0.0],
        "right": [r for r in gear if r[2][0] >= x_mid and r[2][1] >= 0.0],
    }
    out = {}
    for g, rs in members.items():
        if not rs:
            raise AircraftError(
                f"the model's gear has no {g} group (contacts: "
                f"{', '.join(str(r[1].get('name')) for r in gear)})"
            )
        k = cl = cq = rl = rq = 0.0
        moment = [0.0, 0.0, 0.0]  # sum of k * location
        for _, c, xyz in rs:
            spring = c.find("spring_coeff")
            if c.find("strut_force") is not None or spring is None:
                raise AircraftError(
                    f"gear contact '{c.get('name')}' has no spring_coeff: cannot couple roughness"
                )
            ki = xml_converted(spring, SPRING_UNITS, "LBS/FT", "spring")
            dl, dq = damping(c.find("damping_coeff"))
            reb = c.find("damping_coeff_rebound")
            bl, bq = (dl, dq) if reb is None else damping(reb)
            k, cl, cq, rl, rq = k + ki, cl + dl, cq + dq, rl + bl, rq + bq
            moment = [a + ki * b for a, b in zip(moment, xyz)]
        out[g] = {
            "spring": k,
            "damp": cl,
            "damp2": cq,
            "rebound": rl,
            "rebound2": rq,
            "x": moment[0] / k,
            "y": moment[1] / k,
            "z": moment[2] / k,
            "units": [r[0] for r in rs],
        }
    return out


def _prop(parent: ET.Element, name: str) -> None:
    xml_sub(parent, "property", name)


def _knot_index(parent: ET.Element) -> None:
    """u mod RING, u = (sim time - t0) / knot spacing (JSBSim's ``mod`` is an integer modulo)."""

    def u(p: ET.Element) -> None:
        q = xml_sub(p, "quotient")
        dt = xml_sub(q, "difference")
        _prop(dt, "simulation/sim-time-sec")
        _prop(dt, "roughness/t0-sec")
        _prop(q, "roughness/knot-sec")

    diff = xml_sub(parent, "difference")
    u(diff)
    prod = xml_sub(diff, "product")
    xml_sub(prod, "value", str(RING))
    q = xml_sub(xml_sub(prod, "floor"), "quotient")
    u(q)
    xml_sub(q, "value", str(RING))


def add_gear_roughness(root: ET.Element) -> None:
    """Add the roughness forces to a JSBSim model tree, in place (after ``ground_reactions``, in
    its ``external_reactions``): one LOCAL-frame upward force per gear group, of magnitude the
    linear interpolation of a ring of :data:`RING` knots ``roughness/<group>/f<j>-lbf`` at
    u = (sim time - ``roughness/t0-sec``) / ``roughness/knot-sec`` modulo :data:`RING`, times the
    group's weight on wheels and ``roughness/active``. The group's spring, damping, contacts and
    location are declared as ``roughness/<group>/...`` properties for
    :class:`~flightmode.sim.flight.jsbsim.roughness.GearRoughness`."""
    groups = gear_groups(root)
    ext = external_reactions(root)
    decl = {"roughness/active": 0.0, "roughness/t0-sec": 0.0, "roughness/knot-sec": KNOT_S}
    for g, d in groups.items():
        for key in ("spring", "damp", "damp2", "rebound", "rebound2", "x", "y", "z"):
            decl[f"roughness/{g}/{key}"] = d[key]
        decl[f"roughness/{g}/n-units"] = len(d["units"])
        for j, u in enumerate(d["units"]):
            decl[f"roughness/{g}/unit{j}"] = u
        for j in range(RING):
            decl[f"roughness/{g}/f{j}-lbf"] = 0.0
    for i, (name, value) in enumerate(decl.items()):
        el = ET.Element("property", value=repr(float(value)))
        el.text = name
        ext.insert(i, el)  # declarations first
    for g, d in groups.items():
        force = xml_sub(ext, "force", name=f"roughness-{g}", frame="LOCAL")
        ifthen = xml_sub(xml_sub(force, "function", name=f"roughness/{g}/force-lbf"), "ifthen")
        cond = xml_sub(ifthen, "product")
        _prop(cond, "roughness/active")
        wow = cond if len(d["units"]) == 1 else xml_sub(cond, "max")
        for i in d["units"]:
            _prop(wow, f"gear/unit[{i}]/WOW")
        interp = xml_sub(
            ifthen, "interpolate1d"
        )  # the ring of knots, linearly, round from the last to the first
        _knot_index(interp)
        for j in range(RING + 1):
            xml_sub(interp, "value", str(j))
            _prop(interp, f"roughness/{g}/f{j % RING}-lbf")
        xml_sub(ifthen, "value", "0")
        loc = xml_sub(force, "location", unit="M")
        for a in "xyz":
            xml_sub(loc, a, f"{d[a]:.4f}")
        direc = xml_sub(force, "direction")
        for a, v in zip("xyz", ("0", "0", "-1")):  # LOCAL (north, east, down): up
            xml_sub(direc, a, v)


__all__ = ["GEAR_LEVEL_M", "KNOT_S", "RING", "add_gear_roughness", "gear_groups"]
