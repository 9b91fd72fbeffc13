"""Main gear that turns a touchdown sink speed into a realistic load factor.

JSBSim's stock airliner models give their main struts stiff linear springs (static deflection of a
few inches) and linear dampers. At first contact the strut force jumps to c v, and the stiff spring
then stops the aircraft within a few inches: the A320 touched down at 3.0 g at its centre of gravity
at 8 ft/s and the 787-8 at 5.4 g at 3 ft/s, where real landings at those sink speeds stay near
1.1-1.5 g. A real oleo-pneumatic strut has a long, soft stroke (a static deflection near a foot) and an
orifice that damps with the square of the stroke speed (Currey, "Aircraft Landing Gear Design:
Principles and Practices", AIAA 1988, ch. 5), so a gentle touchdown is gentle and a hard one hard.

Each main-gear contact (the braked ones) of the private model copy gets:

- a spring giving a static deflection of ``STATIC_DEFLECTION_M`` under its share of the reference
  landing weight (the mains carry ``MAIN_SHARE`` of it);
- JSBSim's quadratic compression damping (``<damping_coeff type="SQUARE">``, force c2 v^2), with c2
  set so that a landing at the certification sink speed (10 ft/s, 14 CFR 25.473(a)) at the reference
  landing mass reaches 2.6 g at the CG: the Airbus A320 maintenance manual's hard-landing mark, which
  pairs exactly those two figures (2.6 g or 10 ft/s). c2 is found on a one-degree-of-freedom model of
  a main gear carrying its share of the mass, with the wing's lift still equal to the weight at
  touchdown (n = 1 + F / W): :func:`peak_load_factor`. The model then gives about 1.15 g at 1 ft/s,
  1.3 g at 2 ft/s, 1.5 g at 4 ft/s and 2.0 g at 8 ft/s;
- rebound damping as the model had it (linear): a strut damps its extension hard and must not bounce.

The nose gear keeps its stock spring and gets the same quadratic damping, scaled to the weight it
carries (:func:`soften_nose_gear`); a type whose stock nose spring is too stiff for its length gets
a softer one at the same stance (:func:`set_nose_strut`, the 787-8).

The aircraft then sits lower on its gear than the stock model: the pilot measures its settled height
after the gear has settled (:func:`flightmode.sim.flight.simulate.fly`).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from functools import lru_cache
from typing import cast

from flightmode.errors import AircraftError
from flightmode.sim.flight.jsbsim.model_xml import LENGTH_UNITS_M
from flightmode.units import FT_M, G0_MPS2, LBF_N

DESIGN_SINK_FPS = 10.0  # 14 CFR 25.473(a): limit descent velocity at the design landing weight
STATIC_DEFLECTION_M = 0.35  # airliner main struts: a stroke of some 0.4-0.5 m, most of it used at rest
HARD_LANDING_G = 2.6  # Airbus A320 AMM: hard landing at 2.6 g at the CG, or at 10 ft/s
MAIN_SHARE = 0.92  # of the weight on the main gear (the nose gear carries some 6-10 %)
G_FPS2 = G0_MPS2 / FT_M


def main_gear(root: ET.Element) -> list[ET.Element]:
    """The main-gear contacts of a JSBSim model: the BOGEY contacts with wheel brakes (brake group
    LEFT or RIGHT). Some models (the A320) declare their structural contact points as BOGEYs too."""
    mains = [
        c
        for c in root.iterfind("ground_reactions/contact")
        if c.get("type") == "BOGEY" and (c.findtext("brake_group") or "").strip() in ("LEFT", "RIGHT")
    ]
    if len(mains) < 2:
        raise AircraftError("the model has fewer than two braked gear contacts: cannot tell its main gear")
    return mains


def peak_load_factor(
    sink_fps: float, weight_lbf: float, k_lbf_per_ft: float, c2: float, n_main: int
) -> float:
    """Peak vertical load factor at the CG of a touchdown at ``sink_fps`` on ``n_main`` identical
    struts (spring k, quadratic damper c2), each carrying its share of ``MAIN_SHARE`` of the weight,
    with lift equal to weight: n = 1 + n_main F_max / W (module docstring)."""
    from scipy.integrate import solve_ivp

    m = MAIN_SHARE * weight_lbf / n_main / G_FPS2  # slugs per strut

    def force(x: float, xd: float) -> float:
        return max(0.0, k_lbf_per_ft * x + c2 * xd * abs(xd))

    def rhs(t, y):
        return [y[1], -force(y[0], y[1]) / m]

    def stop(t, y):  # the stroke turns back
        return y[1]

    # solve_ivp reads these attributes of an event function; mypy knows no attributes of a function
    stop.terminal, stop.direction = True, -1  # type: ignore[attr-defined]
    sol = solve_ivp(rhs, (0.0, 3.0), [0.0, sink_fps], events=stop, max_step=2e-3, rtol=1e-8, atol=1e-10)
    f_max = max(force(x, xd) for x, xd in zip(sol.y[0], sol.y[1]))
    return 1.0 + n_main * f_max / weight_lbf


@lru_cache(maxsize=32)
def main_strut(
    landing_mass_kg: float, n_main: int, hard_landing_g: float = HARD_LANDING_G
) -> tuple[float, float]:
    """(k in lbf/ft, c2 in lbf per (ft/s)^2) of each main strut (module docstring)."""
    from scipy.optimize import brentq

    weight = landing_mass_kg * G0_MPS2 / LBF_N
    k = MAIN_SHARE * weight / n_main / (STATIC_DEFLECTION_M / FT_M)
    spring_only = peak_load_factor(DESIGN_SINK_FPS, weight, k, 0.0, n_main)
    if spring_only >= hard_landing_g:
        raise AircraftError(
            f"hard-landing threshold {hard_landing_g} g below what the spring alone gives ({spring_only:.2f} g)"
        )
    c2 = brentq(
        lambda c: peak_load_factor(DESIGN_SINK_FPS, weight, k, c, n_main) - hard_landing_g,
        0.0,
        50.0 * weight,
        xtol=1e-6 * weight,
    )
    return k, c2


def nose_gear(root: ET.Element) -> ET.Element:
    """The nose-gear contact of a JSBSim model: its one steerable BOGEY contact (the structural
    contact points some models declare as BOGEYs do not steer)."""
    steer = [
        c
        for c in root.iterfind("ground_reactions/contact")
        if c.get("type") == "BOGEY" and float(c.findtext("max_steer") or 0.0) > 0.0
    ]
    if len(steer) != 1:
        raise AircraftError(
            f"the model has {len(steer)} steerable gear contacts, not one: cannot tell its nose gear"
        )
    return steer[0]


def soften_main_gear(root: ET.Element, landing_mass_kg: float) -> tuple[float, float]:
    """Give the model's main gear the strut of the module docstring, in place. Returns (k, c2)."""
    mains = main_gear(root)
    k, c2 = main_strut(landing_mass_kg, len(mains))
    for c in mains:
        _set_damper(c, c2)
        spring = cast(ET.Element, c.find("spring_coeff"))  # the profiles' models all have one
        spring.attrib = {"unit": "LBS/FT"}
        spring.text = f"{k:.3f}"
    return k, c2


def soften_nose_gear(root: ET.Element, landing_mass_kg: float) -> float:
    """Give the model's nose gear an orifice damper, in place: quadratic compression damping, the main
    struts' c2 scaled to the weight the nose carries (1 - ``MAIN_SHARE``); the stock spring and rebound
    damping stay. The stock nose struts damp linearly, and the force of a linear damper jumps to c v at
    contact: the 787-8's (80,000 lbf/(ft/s)) turned the nose wheels' contact after a normal touchdown
    into a 2.2 g peak at the CG, above the main-gear touchdown's 1.3 g. Its stiff spring is kept: the
    aircraft's stance and its response to taxiway roughness (seed 000 Table 4's ground-phase cells)
    are the stock model's. Returns c2."""
    mains = main_gear(root)
    _, c2_main = main_strut(landing_mass_kg, len(mains))
    c2 = c2_main * (1.0 - MAIN_SHARE) / (MAIN_SHARE / len(mains))
    _set_damper(nose_gear(root), c2)
    return c2


def set_nose_strut(root: ET.Element, landing_mass_kg: float, static_deflection_m: float) -> float:
    """Give the model's nose gear a spring of ``static_deflection_m`` under its share (1 - ``MAIN_SHARE``)
    of the reference landing weight, in place, and lower its contact point by the added deflection, so
    the aircraft stands at the stock model's attitude at that weight (a longer strut with a longer
    stroke). For a model whose stock nose spring is too stiff for its length (AircraftProfile
    ``nose_static_deflection_m``). Returns the spring (lbf/ft)."""
    nose = nose_gear(root)
    # the profiles' models have these elements and numbers
    spring = cast(ET.Element, nose.find("spring_coeff"))
    if spring.get("unit", "LBS/FT") != "LBS/FT":
        raise AircraftError(f"nose spring in {spring.get('unit')}, not LBS/FT: cannot resize it")
    load_lbf = landing_mass_kg * (1.0 - MAIN_SHARE) * G0_MPS2 / LBF_N
    k = load_lbf / (static_deflection_m / FT_M)
    added_m = static_deflection_m - load_lbf / float(cast(str, spring.text)) * FT_M
    z = cast(ET.Element, nose.find("location/z"))
    unit = cast(ET.Element, nose.find("location")).get("unit", "IN")
    if unit not in LENGTH_UNITS_M:
        raise AircraftError(f"nose gear location in '{unit}'; allowed: {', '.join(LENGTH_UNITS_M)}")
    z.text = f"{float(cast(str, z.text)) - added_m / LENGTH_UNITS_M[unit]:.5f}"
    spring.attrib = {"unit": "LBS/FT"}
    spring.text = f"{k:.3f}"
    return k


def _set_damper(contact: ET.Element, c2: float) -> None:
    """Quadratic compression damping c2 on ``contact``; its rebound keeps the model's linear damping."""
    damp = cast(ET.Element, contact.find("damping_coeff"))  # the profiles' models all have one
    if contact.find("damping_coeff_rebound") is None:
        reb = ET.SubElement(contact, "damping_coeff_rebound", unit=damp.get("unit", "LBS/FT/SEC"))
        reb.text = damp.text
    damp.attrib = {"type": "SQUARE", "unit": "LBS/FT2/SEC2"}
    damp.text = f"{c2:.3f}"
