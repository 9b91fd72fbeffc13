"""Continuous atmospheric turbulence: a Dryden gust field whose intensity comes from eddy dissipation
rate (EDR) draws, fed to JSBSim as gust velocities (``atmosphere/gust-*-fps``) at every FDM step.

Why not JSBSim's own MIL-F-8785C model: above 2000 ft it only knows seven fixed intensity curves
(probability-of-exceedance indices), so a continuous, drawn background intensity cannot be set; and
its random numbers come from JSBSim's generator rather than the run's named streams. The filters
here are the same discrete Dryden forms JSBSim's Milspec model uses (MIL-STD-1797A as given in
Yeager, NASA CR-206937, 1998, eq. 30-32), with MIL-F-8785C's scale lengths and low-altitude model:

- below 1000 ft: L_w = h, L_u = h / (0.177 + 0.000823 h)^1.2, sigma_w = 0.1 W20 and
  sigma_u = sigma_w / (0.177 + 0.000823 h)^0.4 (h in ft; MIL-F-8785C 3.7.3.3, Fig. 10-11), with W20
  the wind speed at 20 ft;
- above 2000 ft: L_u = L_w = 1750 ft and sigma_u = sigma_w (MIL-F-8785C 3.7.2.1); in between, linear;
- AR(1) updates per step T: x_u <- (1 - T/tau_u) x_u + sigma_u sqrt(2 T / tau_u) n,
  x_v and x_w the same with 2 T / tau and sqrt(4 T / tau), tau = L / V (Yeager eq. 30-32).

Intensity above 2000 ft from EDR (eps^(1/3), m^(2/3) s^-1): matching the von Karman vertical
spectrum's inertial-range asymptote (MIL-HDBK-1797: sigma^2 (8 / 3 pi) (1.339 L)^(-5/3) L k^(-5/3))
to Kolmogorov's transverse spectrum (4/3 x 18/55 x 1.5 eps^(2/3) k^(-5/3), Pope, Turbulent Flows,
2000, sec. 6.5) gives sigma_w = 1.12 EDR L^(1/3): with L = 1750 ft, sigma_w = 9.1 EDR m/s.

What is drawn (:func:`draw_atmosphere`, per flight, from the flight's ``turbulence`` stream):

- the background EDR of the mid levels (2000 ft to FL200) and of the upper levels (above FL200), each
  from Sharman and Pearson's upper-level climatology (J. Appl. Meteor. Climatol. 56, 2017:
  ln EDR ~ N(-2.572, 0.5067)) restricted below the ICAO light threshold (EDR 0.1): air that is
  never perfectly still, rarely felt;
- the wind at 20 ft, which sets the boundary layer's gustiness: a Rayleigh distribution of mean
  4.5 m/s (the European Wind Atlas' open-terrain climatology, Troen and Petersen, 1989, shape 2);
- for every turbulence patch of the scenario, an EDR inside its category's ICAO Annex 3 band (peak
  EDR for a medium aircraft: light 0.1-0.2, moderate 0.2-0.45, severe 0.45-0.7), unless the
  scenario fixes it;
- the convective boundary layer (drawn last, so that it moves none of the draws above): the
  convective velocity scale w* uniform in 0-2 m/s (0 at night and over cold ground, 1-2 m/s on a
  sunny day: Stull, An Introduction to Boundary Layer Meteorology, 1988, sec. 4.2 and 11.1) and the
  mixed layer's depth z_i uniform in 500-2000 m (Stull, sec. 1.6 and 11.1, daytime). Both ranges are
  assumptions spanning Stull's typical values, not a climatology. Inside the mixed layer the
  convective variances add to the mechanical ones above: sigma_w^2 = 1.8 w*^2 (z/z_i)^(2/3)
  (1 - 0.8 z/z_i)^2 (Lenschow, Wyngaard and Pennell, J. Atmos. Sci. 37, 1980, eq. 3; largest, 0.68 w*,
  at 0.31 z_i) and sigma_u^2 = sigma_v^2 = 0.36 w*^2 (Stull, sec. 11.1: sigma_u about 0.6 w*).
  The mechanical model alone made the air below 2000 ft calmer than calm cruise on every built-in
  (validate's 30 s load-factor std ratio 0.47-0.67, against >= 1), where low-level air is usually rougher.

Uncertain parameter (:data:`UNCERTAIN`, overridden by a scenario's ``[model]`` table): the drawn
background EDR's scale ``turbulence.background_scale`` (1 in 0.33-1): calm cruise here is 2-3 times
rougher than a real A320's recorded one, and calm cruise is where a detector must not see static air.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import cast

import numpy as np

from flightmode.uncertain import Uncertain, value_of
from flightmode.units import FT_M

L_HIGH_M = 1750.0 * FT_M  # MIL-F-8785C 3.7.2.1: scale length above 2000 ft
EDR_TO_SIGMA_W = 1.12 * L_HIGH_M ** (1.0 / 3.0)  # m/s per unit EDR (module docstring): 9.1
# ICAO Annex 3 (Appendix 4, 2018 amendment) peak-EDR bands for a medium aircraft, and an upper
# bound for "severe" draws
EDR_BANDS = {"light": (0.1, 0.2), "moderate": (0.2, 0.45), "severe": (0.45, 0.7)}
EDR_LN_MEAN, EDR_LN_STD = -2.572, 0.5067  # Sharman and Pearson (2017), upper-level climatology
SURFACE_WIND_MEAN_MPS = 4.5  # Troen and Petersen (1989), open terrain: Rayleigh (Weibull k = 2)
MID_TOP_M = 20_000.0 * FT_M  # the mid levels end at FL200
W_STAR_RANGE_MPS = (0.0, 2.0)  # convective velocity scale (module docstring)
Z_I_RANGE_M = (500.0, 2000.0)  # mixed-layer depth (module docstring)
BACKGROUND_SCALE = Uncertain(
    "turbulence.background_scale",
    1.0,
    0.33,
    1.0,
    "1",
    "assumption: validate's calm-cruise load-factor spread is 2-3 times an A320 QAR's (issue 50); "
    "the Sharman and Pearson (2017) climatology is of all flights, not of the calm ones; x 0.33 "
    "matches the QAR, x 1 the climatology",
    "calm air above 2000 ft: the drawn background EDR (cruise's quiet, the in-flight windows)",
)
UNCERTAIN = (BACKGROUND_SCALE,)


@dataclass(frozen=True, slots=True)
class Atmosphere:
    """One flight's turbulence draws (:func:`draw_atmosphere`)."""

    w20_mps: float  # wind speed at 20 ft above ground: the boundary layer's gust intensity
    edr_mid: float  # background EDR, 2000 ft to FL200
    edr_upper: float  # background EDR above FL200
    patch_edr: tuple[float, ...] = ()  # the EDR of each turbulence patch of the plan, in order
    w_star_mps: float = 0.0  # convective velocity scale of the mixed layer
    z_i_m: float = 1000.0  # mixed-layer depth above ground


def _truncated_lognormal(rng: np.random.Generator, upper: float) -> float:
    """A draw of the EDR climatology conditioned on EDR < upper (inverse transform: no rejection
    loop, one uniform per draw)."""
    # the standard normal's CDF and its inverse from scipy.special (what scipy.stats.norm's cdf and
    # ppf compute, bit for bit, without importing scipy.stats: 0.4 s of a fresh process's flight)
    from scipy.special import ndtr, ndtri

    p_max = ndtr((math.log(upper) - EDR_LN_MEAN) / EDR_LN_STD)
    return float(math.exp(EDR_LN_MEAN + EDR_LN_STD * ndtri(rng.uniform(0.0, p_max))))


def draw_atmosphere(
    rng: np.random.Generator,
    patches=(),
    *,
    w20_mps: float | None = None,
    background_edr: float | None = None,
    w_star_mps: float | None = None,
    overrides: Mapping[str, float] | None = None,
) -> Atmosphere:
    """Draw one flight's turbulence (module docstring). ``patches``: the plan's turbulence segments
    (``severity`` and an optional ``edr``); ``w20_mps`` / ``background_edr`` / ``w_star_mps`` fix
    those draws. The draws are always made in the same order, so fixing one never moves the others.
    ``overrides``: the run's uncertain parameters (:data:`UNCERTAIN`: the drawn background EDR is
    multiplied by ``turbulence.background_scale``; a fixed ``background_edr`` is used as given)."""
    w20 = float(rng.rayleigh(SURFACE_WIND_MEAN_MPS / math.sqrt(math.pi / 2.0)))
    k = value_of(BACKGROUND_SCALE, overrides)
    mid = _truncated_lognormal(rng, EDR_BANDS["light"][0]) * k
    upper = _truncated_lognormal(rng, EDR_BANDS["light"][0]) * k
    edrs = []
    for seg in patches:
        lo, hi = EDR_BANDS[seg.severity]
        u = rng.uniform(lo, hi)
        edrs.append(float(u if getattr(seg, "edr", None) is None else seg.edr))
    w_star = float(rng.uniform(*W_STAR_RANGE_MPS))
    z_i = float(rng.uniform(*Z_I_RANGE_M))
    if w20_mps is not None:
        w20 = float(w20_mps)
    if background_edr is not None:
        mid = upper = float(background_edr)
    if w_star_mps is not None:
        w_star = float(w_star_mps)
    return Atmosphere(w20, mid, upper, tuple(edrs), w_star, z_i)


def convective_sigmas(h_m: float, w_star_mps: float, z_i_m: float) -> tuple[float, float]:
    """(sigma_u, sigma_w) of the convective mixed layer at height ``h_m`` (module docstring); zero above it."""
    if w_star_mps <= 0.0 or h_m >= z_i_m:
        return 0.0, 0.0
    x = max(h_m, 0.0) / z_i_m
    return 0.6 * w_star_mps, w_star_mps * math.sqrt(1.8 * x ** (2.0 / 3.0)) * (1.0 - 0.8 * x)


def dryden_parameters(
    h_m: float, sigma_high_mps: float, w20_mps: float, w_star_mps: float = 0.0, z_i_m: float = 1000.0
) -> tuple[float, float, float, float]:
    """(L_u, L_w, sigma_u, sigma_w) in m and m/s at height ``h_m`` above ground (module docstring):
    MIL-F-8785C's low-altitude model below 1000 ft, ``sigma_high_mps`` with L = 1750 ft above
    2000 ft, linear in between, with the convective mixed layer's variances added below ``z_i_m``.
    Heights below 10 ft are taken as 10 ft (as JSBSim does)."""
    lu, lw, su, sw = _mechanical(h_m, sigma_high_mps, w20_mps)
    cu, cw = convective_sigmas(h_m, w_star_mps, z_i_m)
    return lu, lw, math.hypot(su, cu), math.hypot(sw, cw)


def _mechanical(h_m: float, sigma_high_mps: float, w20_mps: float) -> tuple[float, float, float, float]:
    h_ft = max(h_m / FT_M, 10.0)
    if h_ft <= 1000.0:
        k = 0.177 + 0.000823 * h_ft
        sig_w = 0.1 * w20_mps
        return (h_ft / k**1.2) * FT_M, h_ft * FT_M, sig_w / k**0.4, sig_w
    if h_ft <= 2000.0:
        f = (h_ft - 1000.0) / 1000.0
        length = (1000.0 + 750.0 * f) * FT_M
        sig = 0.1 * w20_mps + f * (sigma_high_mps - 0.1 * w20_mps)
        return length, length, sig, sig
    return L_HIGH_M, L_HIGH_M, sigma_high_mps, sigma_high_mps


def background_edr(alt_m: float, edr_mid: float, edr_upper: float) -> float:
    """The calm background's EDR at an altitude above sea level: the mid levels' below FL200
    (:data:`MID_TOP_M`), the upper levels' above (the pilot's gust feed, and validate's boundary-layer
    anchor, which must take the same one)."""
    return edr_mid if alt_m < MID_TOP_M else edr_upper


# the height of the convective sigma_w's maximum, as a fraction of z_i: d/dx [x^(1/3) (1 - 0.8 x)] = 0
# at x = 1 / 3.2 (Lenschow et al. 1980, eq. 3, as in convective_sigmas)
CONVECTIVE_PEAK_FRACTION = 1.0 / 3.2


def low_to_high_sigma_w_ratio(w20_mps: float, w_star_mps: float, edr_background: float) -> float:
    """How much rougher the drawn air is near the ground than the calm air aloft: the boundary layer's
    roughest vertical gust intensity (MIL-F-8785C's mechanical sigma_w = 0.1 W20 below 1000 ft, combined
    with the convective mixed layer's peak, 0.68 w*; an upper estimate between 1000 and 2000 ft, where
    the mechanical part blends towards the background) over the calm background's sigma_w = 9.1 EDR.
    Under 1 the field the flight drew is calmer low than high (light wind, no sun): low-altitude gusts
    scale with the surface wind (MIL-F-8785C 3.7.3.3), and on a still night an approach is smoother
    than cruise."""
    z_i = 1000.0  # any depth: the peak's value does not depend on it
    _, conv_w = convective_sigmas(CONVECTIVE_PEAK_FRACTION * z_i, w_star_mps, z_i)
    return math.hypot(0.1 * w20_mps, conv_w) / (EDR_TO_SIGMA_W * edr_background)


# f(b0, a1, x, z0) -> y: :func:`_first_order_filter`'s filter
FirstOrderFilter = Callable[[float, float, np.ndarray, float], np.ndarray]


def _first_order_filter() -> FirstOrderFilter:
    """``f(b0, a1, x, z0)``: y[n] = b0 x[n] + a1 y[n-1], started from the state ``z0`` (the value that
    ``a1 y[-1]`` adds to the first output), as ``scipy.signal.lfilter([b0], [1, -a1], x, zi=[z0])[0]``.

    It calls lfilter's own C core (``scipy.signal._sigtools._linear_filter``, the routine lfilter hands
    every filter with a denominator to) without lfilter's argument checks, which cost three quarters of a
    120-sample filter (16 us against 4.5 us, measured alone). In a flight, where JSBSim's stepping between
    two blocks leaves the processor's caches cold, a block took 440 us through lfilter and 280 us
    through this. The output is lfilter's, bit for bit (the same routine on the same float64 arrays;
    tests/sim/test_gust_field.py checks it); a SciPy without that core falls back to lfilter itself."""
    try:
        from scipy.signal._sigtools import _linear_filter
    except ImportError:  # pragma: no cover - a SciPy that moved its core: the public route
        from scipy.signal import lfilter

        return lambda b0, a1, x, z0: lfilter([b0], [1.0, -a1], x, zi=[z0])[0]
    array = np.array
    return lambda b0, a1, x, z0: _linear_filter(array([b0]), array([1.0, -a1]), x, -1, array([z0]))[0]


class GustField:
    """Gust velocities for JSBSim, generated a block of ``block_steps`` FDM steps at a time with the
    state carried across blocks (vectorised: scipy.signal.lfilter's core, :func:`_first_order_filter`).
    The height, airspeed, heading and intensity are taken at the start of each block (they change little
    in a second)."""

    def __init__(self, fdm_hz: float, rng: np.random.Generator, block_steps: int = 120):
        self.dt = 1.0 / fdm_hz
        self.rng = rng
        self.n = block_steps
        self.state = np.zeros(3)  # x_u, x_v, x_w (m/s)
        self._filter: FirstOrderFilter | None = None  # _first_order_filter(), made at the first block

    def reset(self) -> None:
        self.state[:] = 0.0

    def block(
        self,
        h_agl_m: float,
        tas_mps: float,
        heading_rad: float,
        sigma_high_mps: float,
        atmosphere: Atmosphere,
    ) -> np.ndarray:
        """(block_steps, 3) gust velocity, north/east/down, m/s, in the flight's drawn ``atmosphere``
        (its surface wind and mixed layer)."""
        north, east, down = self._ned(h_agl_m, tas_mps, heading_rad, sigma_high_mps, atmosphere)
        return np.stack([north, east, down], axis=1)

    def block_fps(
        self,
        h_agl_m: float,
        tas_mps: float,
        heading_rad: float,
        sigma_high_mps: float,
        atmosphere: Atmosphere,
    ) -> tuple[list[float], list[float], list[float]]:
        """The next block as :meth:`block` gives it, in ft/s, as three lists (north, east, down): what
        the flight loop writes to JSBSim one float at a time. The same values as ``block(...) / FT_M``,
        bit for bit, without the (n, 3) array (small-array work costs more than the filtering here)."""
        north, east, down = self._ned(h_agl_m, tas_mps, heading_rad, sigma_high_mps, atmosphere)
        return (north / FT_M).tolist(), (east / FT_M).tolist(), (down / FT_M).tolist()

    def _ned(self, h_agl_m, tas_mps, heading_rad, sigma_high_mps, atmosphere):
        """The next block's gust velocity, m/s: three (block_steps,) arrays, north, east and down."""
        if self._filter is None:
            self._filter = _first_order_filter()
        filt = self._filter
        lu, lw, su, sw = dryden_parameters(
            h_agl_m, sigma_high_mps, atmosphere.w20_mps, atmosphere.w_star_mps, atmosphere.z_i_m
        )
        tv = self.dt * max(tas_mps, 10.0)
        st = self.state
        noise = self.rng.standard_normal((3, self.n))
        # Yeager (1998) eq. 30-32: u first-order in tau_u; v and w with 2 T / tau
        au, av, aw = 1.0 - tv / lu, 1.0 - 2.0 * tv / lu, 1.0 - 2.0 * tv / lw
        u = filt(su * math.sqrt(2.0 * tv / lu), au, noise[0], au * st[0])
        v = filt(su * math.sqrt(4.0 * tv / lu), av, noise[1], av * st[1])
        w = filt(sw * math.sqrt(4.0 * tv / lw), aw, noise[2], aw * st[2])
        st[0], st[1], st[2] = u[-1], v[-1], w[-1]
        c, s = math.cos(heading_rad), math.sin(heading_rad)
        return c * u - s * v, s * u + c * v, w  # u along the heading, v to its right


def sigma_high_mps(edr: float) -> float:
    """sigma_w above 2000 ft for an EDR (module docstring)."""
    return EDR_TO_SIGMA_W * edr


Gusts = tuple[list[float], list[float], list[float]]  # a run of steps' gusts (ft/s): north, east, down


class GustFeed:
    """Feeds a :class:`GustField` to a JSBSim aircraft: its ``atmosphere/gust-{north,east,down}-fps``
    properties are written before every FDM step while the air is turbulent (the pilot decides when
    and how strong: :attr:`Pilot.gust_sigma_mps`), and zeroed once when it stops. The writes are the
    flight loop's (``set(node, value)`` on :attr:`nodes`, north, east, down): one per step and axis,
    with no call in between."""

    PROPS = ("atmosphere/gust-north-fps", "atmosphere/gust-east-fps", "atmosphere/gust-down-fps")

    def __init__(self, ac, field: GustField, atmosphere: Atmosphere, ix: dict):
        self.nodes = [ac.node(p) for p in self.PROPS]
        self.set = type(self.nodes[0]).set_double_value
        self.field, self.atmosphere, self.ix = field, atmosphere, ix
        self.buffer: Gusts = ([], [], [])  # ft/s, north, east, down
        self.pos = 0
        self.on = False

    def take(self, n: int, x, sigma_high_mps: float) -> Gusts:
        """The next ``n`` steps' gusts (ft/s): three lists, north, east and down, generating blocks from
        the state row ``x`` as needed."""
        ix = self.ix
        pos = self.pos
        if len(self.buffer[0]) - pos < n:
            rest = [b[pos:] for b in self.buffer]
            while len(rest[0]) < n:
                g = self.field.block_fps(
                    x[ix["agl_m"]], x[ix["tas_mps"]], x[ix["psi_rad"]], sigma_high_mps, self.atmosphere
                )
                for r, col in zip(rest, g):
                    r.extend(col)
            self.buffer, pos = cast(Gusts, tuple(rest)), 0
        self.pos = pos + n
        self.on = True
        return cast(Gusts, tuple(b[pos : pos + n] for b in self.buffer))

    def stop(self) -> None:
        if self.on:
            for node in self.nodes:
                self.set(node, 0.0)
            self.on = False
            self.field.reset()
            self.buffer, self.pos = ([], [], []), 0
