"""Runway and taxiway roughness felt through the gear: ISO 8608 random profiles under each wheel,
turned into the strut-force changes JSBSim's own gear would feel on them.

JSBSim's terrain is one flat elevation, so its gear rolls as on glass. Here each surface the aircraft
rolls on (origin taxiway, origin runway, destination runway, destination taxiway) gets a seeded
random profile along its path, and each gear group (nose, left main, right main) feels the profile
under its wheels as an extra vertical force, so that JSBSim computes the heave, pitch and roll
response with its own mass, inertia and gear.

Profile (ISO 8608:2016, "Mechanical vibration - Road surface profiles - Reporting of measured
data", Table C.2): displacement PSD Gd(n) = Gd(n0) (n / n0)^-2, n0 = 0.1 cycle/m, classes A..H at
geometric-mean Gd(n0) = 16e-6, 64e-6, 256e-6, ... m^3 (x4 per class). Synthesis: complex Gaussian
Fourier coefficients of a periodic profile (2^15 samples 0.1 m apart: 3.3 km, longer than any
takeoff roll or rollout; a long taxi route wraps round seamlessly), so the profile is Gaussian with
that PSD in expectation, over wavelengths 0.5-120 m: 120 m is the longest straightedge of the Boeing
bump method of FAA AC 150/5380-9 (2009), whose straightedges start at two 0.25 m survey increments,
0.5 m, about an airliner tyre's footprint length (it envelops shorter bumps). At 5-90 m/s the band
spans 0.04-180 Hz, past both ends of the rigid-body response. The nose wheel runs on the centreline,
the mains on two tracks a track width B apart; the three are parallel lines of one isotropic random
surface (Dodds and Robson, "The description of road surface roughness", J. Sound Vib. 31(2), 1973):
for Gd ~ n^-2 two tracks d apart have coherence rho(n) = z K1(z), z = 2 pi n d (the isotropic 2-D
spectrum integrated across the track; K1 the modified Bessel function), so long waves lift both mains
together (heave, pitch) and short ones rock the wings (roll). Identical tracks would have no roll;
independent ones would halve the heave of long waves.

Class: runways A, taxiways A (:data:`RUNWAY_CLASS`, :data:`TAXIWAY_CLASS`; :class:`RunwayRoughness`
is the per-surface attribute). Runways are far smoother than roads: NASA's criterion (Morris and Hall,
"Recent studies of runway roughness", NASA conference on aircraft operating problems, 1965) keeps the
cockpit's vertical acceleration within +-0.4 g even on the worst acceptable runway, and a good runway
shakes the CG by a few hundredths of g on the roll. ISO's smoothest class, A, gives about 0.015-0.02 g
RMS at the CG of the 737 and A320 on the takeoff roll and rollout, cockpit peaks below 0.2 g
(tests/sim/test_roughness.py); class B doubles every figure. No public figure read separates taxiways
from runways, so both are A (taxiing is gentler for its speed alone).

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

Datum: each wheel's force is k (w - d) + D(w_dot), d its datum: the wheel's own height through a
first-order lag of :data:`DATUM_TAU_S` (d = w where it starts rolling, so the force starts at 0). The
struts carry what the ground does slowly, as the real ones do on a slope; the force carries the
bumps. A fixed datum (the ground where the wheel started) let the profile's long waves build static
forces of thousands of lbf over a taxi route (6,400 lbf lifting an A320's nose wheel: 3/4 of its
static load); at the stand JSBSim's contact then held a 2.6 Hz rocking of 0.025 g after the engines
stopped (3 of 20 A320 flights of a validated dataset, seed 000 Table 2's rest spread 15-18 times the
paper's). Stopped
(below :data:`ROLLING_MIN_MPS`), the wheels stay where they are on the profile and the force decays
with the datum.

Timing: Python works only at the pilot's ticks and only on the ground, from taxi-out to the stand. At
each tick it writes the force *knots* of the tick's interval, 1/40 s apart (one knot at the runway's
40 Hz ticks, four at the taxiway's 10 Hz), into a ring of :data:`RING` slots in the model; JSBSim
interpolates them linearly at every step (``interpolate1d`` of ``simulation/sim-time-sec``), and
consecutive ticks' knots follow on, so a tick writes only its new knots. Each knot is the profile
averaged over the distance rolled between knots (prefix sums): a box filter matched to the speed, so
that no short wave aliases into the rigid-body band, which keeps the force within about 10 Hz.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from array import array
from dataclasses import dataclass

import numpy as np

from flightmode.errors import AircraftError, ScenarioError, did_you_mean
from flightmode.labels import FLIGHT_PHASES
from flightmode.sim.flight.jsbsim_adapter import LENGTH_UNITS_M, xml_sub
from flightmode.units import FT_M, LBF_N

# ISO 8608:2016 Table C.2: geometric mean of each class's Gd(n0), m^3 (n0 = 0.1 cycle/m)
ISO_8608_N0 = 0.1
ISO_8608_GD_N0_M3 = {c: 16e-6 * 4.0**i for i, c in enumerate("ABCDEFGH")}

RUNWAY_CLASS = "A"
TAXIWAY_CLASS = "A"
BAND_M = (0.5, 120.0)  # shortest and longest wavelength synthesized (module docstring)
DX_M = 0.1  # profile sample spacing
PERIOD_SAMPLES = 2**15  # 3,277 m: longer than any takeoff roll or rollout; taxi routes wrap seamlessly
KNOT_S = 1.0 / 40.0  # time between force knots
MAX_KNOTS = 4  # knots per tick (10 Hz ticks: four)
RING = 8  # knot slots in the model, written round and round (> MAX_KNOTS)
GROUPS = ("nose", "left", "right")
_MASK = PERIOD_SAMPLES - 1
_RING_MASK = RING - 1
GEAR_LEVEL_M = 0.6  # BOGEY contacts within this of the lowest one are gear (not tail, engine, wingtip)
TYRE_DEFLECTION_M = 0.08  # tyre deflection under static load (module docstring)
SQUARE_DAMPING_RATE_MPS = 0.1  # a square-law damper counts as linear at this strut rate in the tyre lag
# Each wheel's datum follows its height with this time constant (module docstring, Datum): the force is
# the profile's change, not its level. Waves longer than 2 pi v tau (63 m at a 5 m/s taxi, 880 m on a
# 70 m/s roll) are slopes the aircraft stands on; at 0.2 Hz the leak keeps 93 % of the force, above
# 1 Hz all of it
DATUM_TAU_S = 2.0
# below this ground speed the wheels are at rest on the profile: no new profile comes under them. A
# stopped aircraft still rocks on its struts at a few mm/s; counted as rolling (a speed's magnitude
# never runs backwards), that would creep the wheels along the profile and step the force at every
# 0.1 m sample crossed. At 0.1 m/s a wheel crosses one sample a second: slower than a tyre's footprint
# would notice
ROLLING_MIN_MPS = 0.1


@dataclass(frozen=True, slots=True)
class RunwayRoughness:
    """The roughness of one surface: its ISO 8608 class and the random stream its profile comes from."""

    iso_class: str
    stream: str

    def __post_init__(self) -> None:
        if self.iso_class not in ISO_8608_GD_N0_M3:
            raise ScenarioError(
                f"roughness class '{self.iso_class}'{did_you_mean(self.iso_class, ISO_8608_GD_N0_M3)}: "
                f"ISO 8608 classes are {', '.join(ISO_8608_GD_N0_M3)}"
            )

    @property
    def gd_n0_m3(self) -> float:
        return ISO_8608_GD_N0_M3[self.iso_class]


# the surfaces of a flight, and the phases on each (other phases: no roughness; before taxi-out the
# aircraft stands or is pushed at a walking pace, 0.003 g RMS on these profiles, the accelerometers'
# noise; the profile's datum is where it first rolls)
SURFACES = {
    "origin/taxiway": RunwayRoughness(TAXIWAY_CLASS, "roughness/origin/taxiway"),
    "origin/runway": RunwayRoughness(RUNWAY_CLASS, "roughness/origin/runway"),
    "destination/runway": RunwayRoughness(RUNWAY_CLASS, "roughness/destination/runway"),
    "destination/taxiway": RunwayRoughness(TAXIWAY_CLASS, "roughness/destination/taxiway"),
}
PHASE_SURFACE = {p: None for p in FLIGHT_PHASES} | {
    "taxi_out": "origin/taxiway",
    "takeoff_roll": "origin/runway",
    "initial_climb": "origin/runway",
    "flare": "destination/runway",
    "rollout": "destination/runway",
    "taxi_in": "destination/taxiway",
    "shutdown": "destination/taxiway",
    "parked": "destination/taxiway",
}


# ------------------------------------------------------------------------------------ profiles
def displacement_psd_m3(n_cpm, gd_n0_m3: float) -> np.ndarray:
    """ISO 8608 eq. (4) with w = 2: Gd(n) = Gd(n0) (n / n0)^-2 (m^3; n in cycle/m)."""
    n = np.asarray(n_cpm, dtype=float)
    return gd_n0_m3 * (n / ISO_8608_N0) ** -2.0


def track_coherence(n_cpm, separation_m: float) -> np.ndarray:
    """Coherence of two parallel tracks ``separation_m`` apart on an isotropic surface whose track
    PSD falls as n^-2: rho = z K1(z), z = 2 pi n d (module docstring; 1 at z = 0; K1: the modified
    Bessel function of the second kind, scipy.special.k1)."""
    from scipy.special import k1

    z = 2.0 * math.pi * np.abs(np.asarray(n_cpm, dtype=float)) * separation_m
    rho = np.ones_like(z)
    pos = z > 0.0
    rho[pos] = z[pos] * k1(z[pos])
    return np.clip(rho, 0.0, 1.0)


def synthesize_tracks(
    gd_n0_m3: float,
    rng: np.random.Generator,
    track_m: float,
    *,
    n_samples: int = PERIOD_SAMPLES,
    dx_m: float = DX_M,
    band_m=BAND_M,
) -> np.ndarray:
    """Three parallel profiles (3, n_samples), m: the centreline (nose wheel) and the left and right
    main-gear tracks ``track_m`` apart, periodic with period n_samples * dx_m, zero mean.

    Per frequency, with Z0, Z1, Z2 independent complex Gaussians: centre = Z0, left/right =
    r1 Z0 + sqrt(1 - r1^2) (b Z1 +- c Z2), r1 = rho(B/2), b^2 - c^2 = (rho(B) - r1^2) / (1 - r1^2),
    b^2 + c^2 = 1, so that each track has Gd and the pairs the isotropic coherences. Deterministic:
    the same generator state gives the same tracks.
    """
    period_m = n_samples * dx_m
    k = np.arange(math.ceil(period_m / band_m[1]), math.floor(period_m / band_m[0]) + 1)  # in-band bins
    if k[0] < 1 or k[-1] > n_samples // 2:
        raise ValueError(f"band {band_m} m not inside (2 dx, period) = ({2 * dx_m}, {period_m}) m")
    n = k / period_m  # cycle/m
    # one-sided PSD -> Fourier coefficient scale: variance Gd dn per bin, half in cos and half in sin
    amp = 0.5 * n_samples * np.sqrt(displacement_psd_m3(n, gd_n0_m3) / period_m)
    z = rng.standard_normal((3, 2, n.size))
    z = z[:, 0] + 1j * z[:, 1]  # unit variance in cos and in sin
    r1 = track_coherence(n, 0.5 * track_m)
    r2 = track_coherence(n, track_m)
    one_r1 = np.maximum(1.0 - r1 * r1, 0.0)
    q = np.divide(r2 - r1 * r1, one_r1, out=np.ones_like(n), where=one_r1 > 1e-12)
    q = np.clip(q, -1.0, 1.0)
    side = np.sqrt(one_r1)
    b, c = side * np.sqrt(0.5 * (1.0 + q)), side * np.sqrt(0.5 * (1.0 - q))
    coef = np.zeros((3, n_samples // 2 + 1), dtype=complex)
    coef[0, k] = amp * z[0]
    common = r1 * z[0] + b * z[1]
    coef[1, k] = amp * (common + c * z[2])
    coef[2, k] = amp * (common - c * z[2])
    return np.fft.irfft(coef, n=n_samples, axis=-1)


# ------------------------------------------------------------------------ the model's gear forces
_SPRING_UNITS = {"LBS/FT": LBF_N / FT_M, "N/M": 1.0}
_DAMP_UNITS = {"LBS/FT/SEC": LBF_N / FT_M, "N/M/SEC": 1.0}
_DAMP2_UNITS = {"LBS/FT2/SEC2": LBF_N / FT_M**2, "N/M2/SEC2": 1.0}


def _number(el: ET.Element | None, what: str) -> float:
    try:
        return float(el.text)
    except (AttributeError, TypeError, ValueError):
        raise AircraftError(
            f"gear contact has no numeric {what}: cannot couple runway roughness to it"
        ) from None


def _converted(el: ET.Element, units: dict[str, float], default: str, what: str) -> float:
    unit = el.get("unit", default)
    if unit not in units:
        raise AircraftError(f"gear contact {what} in unit '{unit}'; allowed: {', '.join(units)}")
    return _number(el, what) * units[unit]


def _damping(el: ET.Element | None) -> tuple[float, float]:
    """(linear N s/m, square N s^2/m^2) of a damping_coeff element (JSBSim: linear unless type SQUARE)."""
    if el is None:
        return 0.0, 0.0
    if el.get("type") == "SQUARE":
        return 0.0, _converted(el, _DAMP2_UNITS, "LBS/FT2/SEC2", "square damping")
    return _converted(el, _DAMP_UNITS, "LBS/FT/SEC", "damping"), 0.0


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
        xyz = [_number(loc.find(a), f"location {a}") * scale for a in "xyz"]
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
        loc = [0.0, 0.0, 0.0]
        for _, c, xyz in rs:
            if c.find("strut_force") is not None or c.find("spring_coeff") is None:
                raise AircraftError(
                    f"gear contact '{c.get('name')}' has no spring_coeff: cannot couple roughness"
                )
            ki = _converted(c.find("spring_coeff"), _SPRING_UNITS, "LBS/FT", "spring")
            dl, dq = _damping(c.find("damping_coeff"))
            reb = c.find("damping_coeff_rebound")
            bl, bq = (dl, dq) if reb is None else _damping(reb)
            k, cl, cq, rl, rq = k + ki, cl + dl, cq + dq, rl + bl, rq + bq
            loc = [a + ki * b for a, b in zip(loc, xyz)]
        out[g] = {
            "spring": k,
            "damp": cl,
            "damp2": cq,
            "rebound": rl,
            "rebound2": rq,
            "x": loc[0] / k,
            "y": loc[1] / k,
            "z": loc[2] / k,
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
    location are declared as ``roughness/<group>/...`` properties for :class:`GearRoughness`."""
    groups = gear_groups(root)
    ext = root.find("external_reactions")
    if ext is None:
        ext = ET.Element("external_reactions")
        children = list(root)
        idx = next((i + 1 for i, c in enumerate(children) if c.tag == "ground_reactions"), len(children))
        root.insert(idx, ext)
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


# ------------------------------------------------------------------------------ in the step loop
class _Surface:
    """One surface's three tracks as flat arrays for per-tick lookups: heights h and prefix sums
    C (C[i] = h[0] + ... + h[i-1]; zero-mean periodic profile, so C wraps seamlessly)."""

    __slots__ = ("c", "h")

    def __init__(self, tracks: np.ndarray):
        self.h = [array("d", t.tobytes()) for t in tracks]
        c = np.zeros_like(tracks)
        np.cumsum(tracks[:, :-1], axis=1, out=c[:, 1:])
        self.c = [array("d", t.tobytes()) for t in c]


class GearRoughness:
    """Sets the roughness forces of a model loaded with :func:`add_gear_roughness` at each pilot
    tick (:meth:`tick`), from the flight's random ``streams`` (one stream per surface,
    :data:`SURFACES`; a profile is made when the aircraft first rolls on its surface).

    Make it with the aircraft at rest on its gear: each group's static load (spring times
    compression) sets its tyre stiffness (:data:`TYRE_DEFLECTION_M`)."""

    def __init__(self, ac, streams, fdm_hz: float, surfaces: dict[str, RunwayRoughness] | None = None):
        pm = ac.fdm.get_property_manager()

        def node(prop: str):
            nd = pm.get_node(prop, False)
            if nd is None:
                raise AircraftError(
                    f"the model has no property '{prop}': load it with roughness.add_gear_roughness"
                )
            return nd

        def get(p):
            return node(p).get_double_value()

        self.surfaces = SURFACES if surfaces is None else surfaces
        self.streams = streams
        self.dt_s = 1.0 / fdm_hz
        self.wheelbase_m = get("roughness/left/x") - get("roughness/nose/x")
        self.track_m = get("roughness/right/y") - get("roughness/left/y")
        self.offset = [self.wheelbase_m / DX_M, 0.0, 0.0]  # nose ahead of the mains, in samples
        self.k = [get(f"roughness/{g}/spring") / LBF_N for g in GROUPS]  # lbf per m of profile
        self.law = [
            tuple(get(f"roughness/{g}/{key}") / LBF_N for key in ("damp", "damp2", "rebound", "rebound2"))
            for g in GROUPS
        ]
        # the tyre in series with the strut (massless wheel): the strut sees the profile through a
        # first-order lag tau = c / (k_tyre + k); k_tyre = static load / TYRE_DEFLECTION_M
        self.tau_s = []
        for g in GROUPS:
            units = [int(get(f"roughness/{g}/unit{j}")) for j in range(int(get(f"roughness/{g}/n-units")))]
            comp_m = sum(get(f"gear/unit[{u}]/compression-ft") for u in units) / len(units) * FT_M
            if comp_m <= 0.0:
                raise AircraftError(
                    f"the {g} gear carries no load: make GearRoughness with the aircraft at rest on its gear"
                )
            k_si = get(f"roughness/{g}/spring")
            k_tyre = k_si * comp_m / TYRE_DEFLECTION_M
            cl, cq, rl, rq = (get(f"roughness/{g}/{key}") for key in ("damp", "damp2", "rebound", "rebound2"))
            c_eff = 0.5 * (cl + rl + (cq + rq) * SQUARE_DAMPING_RATE_MPS)
            self.tau_s.append(c_eff / (k_tyre + k_si))
        self._knots = [
            [node(f"roughness/{g}/f{j}-lbf").set_double_value for j in range(RING)] for g in GROUPS
        ]
        self._active = node("roughness/active").set_double_value
        self._t0 = node("roughness/t0-sec").set_double_value
        self._knot_s = node("roughness/knot-sec").set_double_value
        self._time = node("simulation/sim-time-sec").get_double_value
        ix = ac.index
        self._ivn, self._ive, self._iwow = ix["v_north_mps"], ix["v_east_mps"], ix["wow"]
        self._profiles: dict[str, _Surface] = {}
        self._on: str | None = None  # the surface rolled on (None: inactive)
        self._prof: _Surface | None = None
        self._s = 0.0  # main gear's position along the surface, samples
        # per group: last knot boundary (sample index) and its prefix sum, wheel height (the
        # tyre-filtered profile, m), last knot (lbf), datum (the wheel height through DATUM_TAU_S, m)
        self._state = [[0, 0.0, 0.0, 0.0, 0.0] for _ in GROUPS]
        self._every = 0
        self._m, self._inv_dtk, self._dtk_dx, self._dtk, self._beta = 1, 0.0, 0.0, 0.0, 0.0
        self._n = 0  # knots written since the ring's restart (the last one is in slot n mod RING)
        self._anchor = True  # restart the ring at the next tick
        self._alpha = [0.0, 0.0, 0.0]
        self._groups: list[tuple] = []

    def profile(self, surface: str) -> _Surface:
        prof = self._profiles.get(surface)
        if prof is None:
            spec = self.surfaces[surface]
            tracks = synthesize_tracks(spec.gd_n0_m3, self.streams.rng(spec.stream), self.track_m)
            prof = self._profiles[surface] = _Surface(tracks)
        return prof

    def tick(self, x, phase: str, every: int) -> None:
        """Knots for the next ``every`` steps from the state row ``x`` (SI, jsbsim_adapter order)."""
        surface = PHASE_SURFACE[phase]
        if surface is None or x[self._iwow] < 0.5:
            if self._on is not None:
                self._active(0.0)
                self._on = None
            return
        if surface != self._on:
            self._switch(surface)
        if every != self._every:
            self._set_every(every)
        if self._anchor:
            self._reanchor()
        m, n, inv_dtk, beta = self._m, self._n, self._inv_dtk, self._beta
        v = math.hypot(x[self._ivn], x[self._ive])
        ds = v * self._dtk_dx if v >= ROLLING_MIN_MPS else 0.0  # samples rolled per knot
        s = self._s
        if m == 1:  # one knot a tick (40 Hz ticks on the runway): the loop below, unrolled
            slot = (n + 1) & _RING_MASK
            for h, c, k, cl, cq, rl, rq, a, off, knots, st in self._groups:
                i0, c0, w, f, datum = st
                i = int(s + off + 0.5 + ds) & _MASK
                n_in = (i - i0) & _MASK
                c1 = c[i]
                w1 = w + a * (((c1 - c0) / n_in if n_in else h[i]) - w)
                datum += beta * (w1 - datum)
                r = (w1 - w) * inv_dtk
                f = k * (w1 - datum) + (cl * r + cq * r * r if r > 0.0 else rl * r - rq * r * r)
                knots[slot](f)
                st[0] = i
                st[1] = c1
                st[2] = w1
                st[3] = f
                st[4] = datum
            self._s = s + ds
            self._n = n + 1
            return
        for h, c, k, cl, cq, rl, rq, a, off, knots, st in self._groups:
            i0, c0, w, f, datum = st
            b = s + off + 0.5
            for j in range(1, m + 1):
                i = int(b + j * ds) & _MASK
                n_in = (i - i0) & _MASK
                c1 = c[i]
                # the profile averaged over the distance rolled in the knot interval, through the tyre
                w1 = w + a * (((c1 - c0) / n_in if n_in else h[i]) - w)
                datum += beta * (w1 - datum)
                r = (w1 - w) * inv_dtk
                f = k * (w1 - datum) + (cl * r + cq * r * r if r > 0.0 else rl * r - rq * r * r)
                knots[(n + j) & _RING_MASK](f)
                i0, c0, w = i, c1, w1
            st[0], st[1], st[2], st[3], st[4] = i0, c0, w, f, datum
        self._s = s + m * ds
        self._n = n + m

    def _set_every(self, every: int) -> None:
        """Knot spacing for ticks ``every`` steps apart: ``m`` knots a tick, as near :data:`KNOT_S`
        as divides the tick (a new spacing restarts the ring)."""
        span = every * self.dt_s
        m = min(MAX_KNOTS, max(1, round(span / KNOT_S)))
        dtk = span / m
        self._every, self._m, self._inv_dtk, self._dtk_dx = every, m, 1.0 / dtk, dtk / DX_M
        self._beta = 1.0 - math.exp(-dtk / DATUM_TAU_S)
        if dtk != self._dtk:
            self._dtk = dtk
            self._alpha = [1.0 - math.exp(-dtk / tau) for tau in self.tau_s]
            self._anchor = True
            self._bind()

    def _reanchor(self) -> None:
        """Restart the ring: knot 0 (the force now) at the next step's time, ``knot-sec`` apart.
        JSBSim advances its clock before it computes the external forces of a step, so the next step
        computes them at now + dt. Between restarts the knots of consecutive ticks follow on: a
        tick's first knot is the last one written (m knot spacings span the tick exactly)."""
        self._t0(self._time() + self.dt_s)
        self._knot_s(self._dtk)
        for knots, st in zip(self._knots, self._state):
            knots[0](st[3])
        self._n = 0
        self._anchor = False

    def _bind(self) -> None:
        """The per-group constants and state the tick loop reads, for the current surface and spacing."""
        if self._prof is None:
            return
        p = self._prof
        self._groups = [
            (
                p.h[g],
                p.c[g],
                self.k[g],
                *self.law[g],
                self._alpha[g],
                self.offset[g],
                self._knots[g],
                self._state[g],
            )
            for g in range(3)
        ]

    def _switch(self, surface: str) -> None:
        """Start rolling on ``surface`` from its start, continuous in force: each group's wheel keeps
        its height above its datum from the previous surface (0 when starting from rest or touching
        down, so the force starts at 0 and the datum is the ground where the wheel stood)."""
        moving = self._on is not None
        prof = self.profile(surface)
        for g, st in enumerate(self._state):
            i = int(self.offset[g] + 0.5) & _MASK
            rel = st[2] - st[4] if moving else 0.0
            st[0], st[1], st[2], st[4] = i, prof.c[g][i], prof.h[g][i], prof.h[g][i] - rel
            if not moving:
                st[3] = 0.0  # the force starts from 0
        if not moving:
            self._active(1.0)
            self._anchor = True
        self._on, self._prof, self._s = surface, prof, 0.0
        self._bind()


__all__ = [
    "BAND_M",
    "ISO_8608_GD_N0_M3",
    "ISO_8608_N0",
    "PHASE_SURFACE",
    "RUNWAY_CLASS",
    "SURFACES",
    "TAXIWAY_CLASS",
    "GearRoughness",
    "RunwayRoughness",
    "add_gear_roughness",
    "displacement_psd_m3",
    "gear_groups",
    "synthesize_tracks",
    "track_coherence",
]
