"""Cabin and hold pressure: the pressurisation schedule of a type, the weather at the airports, and
the pressure a bag feels, as pure functions over a flight's arrays (time, altitude, phase).

Everything is computed in *pressure altitude* (the ISA altitude of a pressure,
:func:`flightmode.sim.flight.atmosphere.pressure_altitude_m`): flight levels, the certification
rule's "cabin pressure altitude" and the controllers' schedules are all pressure altitudes.

Chain, per sample (vectorised; the only recursion, the outflow-valve lag, is ``scipy.signal.lfilter``):

1. **Ambient** (:func:`ambient_pressure_pa`): the static pressure at the aircraft's geometric altitude
   under the airport's QNH and an ISA temperature deviation (:class:`Weather`), the departure airport's
   weather up to liftoff, the arrival's from touchdown, blended linearly in time in between.
2. **Schedule** (the controller's target cabin altitude):

   - door open (``gate``, ``parked``) and every other ground phase: ambient;
   - ``takeoff_roll``: pre-pressurisation, the cabin driven ``prepress_psi`` above field pressure
     at ``prepress_rate_fpm``, every type (A320 FCOM DSC 21-20-10, quoted verbatim on PPRuNe: 0.1 psi
     at 400 ft/min before rotation; the 737 FCOM 2.40.4 "slightly pressurizing the cabin" and the 787
     FCOM 2.30.1 "a small positive pressurization prior to rotation" give no number, so the 737, 787
     and Fokker 100 borrow the A320's: *assumption*);
   - airborne, climb side: from the pre-pressurised departure field up to the cruise cabin altitude in
     proportion to the aircraft's progress from the field to the planned cruise level (the
     proportional auto-schedule of the 737's controller; Airbus's "fixed pre-programmed law");
   - cruise cabin altitude ``C = min(max_cabin, h(p(FL) + dp_max))``: the cabin as low as the maximum
     differential allows at the planned level, never above the type's maximum cabin altitude
     (14 CFR 25.841(a): 8,000 ft; 787: 6,000 ft), never below the lower pre-pressurised field;
   - airborne, descent side (from the first ``descent``/``approach`` sample): from ``C`` down to the
     *landing pressure*, the arrival field + ``cabin.landing_residual_psi``, again in proportion to
     the aircraft's altitude, except that the last 2N of that schedule (N =
     ``cabin.landing_level_height_ft`` above the field) is squeezed into N..2N: the cabin reaches its
     landing pressure while the aircraft is still N above the field and holds it through the final
     approach and the flare (737 FCOM 2.40.5: "proportional descent to slightly below the selected
     LAND ALT ... programs the cabin to land slightly pressurized"; 787 FCOM 2.30.2: "cabin altitude
     decreases to slightly below the FMC planned landing altitude. This ensures that the airplane
     lands pressurized"; A320: the landing field's pressure "just prior to landing"). Above 2N the
     schedule is the proportional one it always was, but the descent rate limit (below) may start the
     cabin down earlier to meet the earlier target: on the built-ins the cabin changes from 2.5-3 min
     before touchdown (A320, 737, Fokker 100), on the 787's long haul (300 ft/min, a slow final
     descent) from 13 min before it, by up to 4.8 hPa;
   - after touchdown (the first ground sample after the last airborne one), per type: the landing
     pressure held until the vent starts, then ambient at the venting rate: A320 from touchdown at
     ``release_rate_fpm`` = 500 ft/min (A320 FCOM DSC-21-20-30, as paraphrased: "any remaining cabin
     pressure is released at 500 ft/min" from touchdown, the outflow valve fully open 55 s after
     landing); 787 from touchdown over ``cabin.vent_787_s`` (FCOM 2.30.2: "At touchdown, both outflow
     valves open"); 737 from the start of the taxi-in over ``cabin.vent_737_s`` (FCOM 2.40.5: "While
     taxiing in, the controller drives the outflow valve slowly to the full open position"); Fokker
     100 as the A320 (*assumption*: no description read).
3. **Rate limits** on the schedule: cabin climb at most ``climb_rate_fpm``, cabin descent at most
   ``descent_rate_fpm``, raised (up to ``descent_rate_max_fpm``) when the descent is too short for the
   default rate ("optimised" descent rate). Both are exact closed forms, not loops: a rise limit
   ``c1[k] = min(s[k], c1[k-1] + r dt)`` unrolls to ``c1 = R + cummin(s - R)`` with ``R`` the
   cumulative allowed rise; the fall limit is the same recursion run backwards in time, so the cabin
   starts down early enough to meet the landing target (the controller knows the landing field).
   The result is the largest cabin altitude at or below the schedule that respects both limits.
   Then the structural limits: cabin pressure at most ambient + ``dp_max`` (safety valve) and at least
   ambient (negative-pressure relief).
4. **Outflow-valve dynamics**: the cabin pressure follows the scheduled pressure through a first-order
   lag of time constant ``ofv_tau_s`` (``lfilter``, started in steady state). A lag of a rate-limited
   pressure never exceeds the input's largest pressure rate (its step response is monotone); in
   altitude the rate can exceed the limit by the density ratio across the lag, a fraction
   ``r tau / H_rho`` (H_rho ~ 9.8 km, the density scale height): 0.16 % at 300 ft/min and 5 s.
   A lagged schedule at the maximum differential overshoots it by ~0.01 psi while the aircraft
   climbs (the A320's default flight: 0.007 psi), far below the differential at which the safety
   valves open (the A320's: 8.6 psi against its 8.06 psi normal maximum, FCOM as usually quoted;
   *recalled, not read*); the valves are therefore not modelled after the lag.
5. Door open: the cabin *is* ambient (no lag). The hold: ``"pressurised"`` (the cabin's pressure) or
   ``"unpressurised"`` (ambient): :func:`hold_pressure_pa`. Road legs: :func:`ambient_pressure_pa`.

Figures and their quality (per type in :data:`CABIN_PROFILES`):

- maximum cabin altitude: 14 CFR 25.841(a), 8,000 ft in normal operation; 787: 6,000 ft (Boeing's
  published 787 cabin-altitude figure);
- maximum differential: the 737's three bands 7.45 / 7.80 / 8.35 psid for a selected level up to
  FL280 / FL280-370 / above FL370 (737 FCOM, pressurization system); the other types *derived* so that the cabin is at
  its maximum altitude at the type's certified ceiling (``AircraftProfile.ceiling_ft``, from the TCDS):
  A320 8.08 psi (the figure usually quoted is 8.06), Fokker 100 7.46, 787-8 9.43;
- cabin rates: A320 climb 1,000 ft/min, descent 350 ft/min default, 750 ft/min at most (Airbus A320
  FCOM, pressurization); the others 500 ft/min up and 300 ft/min down, the usual passenger-comfort figures (SAE
  ARP1270 "Aircraft Cabin Pressurization Criteria" recommends them: *recalled, not read*), 750 ft/min
  at most in descent (*assumption*: Airbus's figure);
- pre-pressurisation 0.1 psi at 400 ft/min (A320 FCOM; borrowed by the others, above); the landing
  pressure, the height from which it is held and the Boeing vents are the uncertain parameters of
  :data:`UNCERTAIN` (value, range, source: docs/research/fleet_loads/OTHER_SOURCES.md section 1 lists
  what was read); the A320's release at 500 ft/min (FCOM, paraphrased; 0.1 psi in about 23 s, inside
  its 55 s);
- outflow-valve lag 5 s (*assumption*: no public figure for the controller's closed-loop time constant);
- weather: QNH ~ N(1013.25, 8 hPa) and ISA deviation ~ N(0, 8 K) (*assumptions*: a typical
  mid-latitude day-to-day spread of sea-level pressure and temperature, recalled, not read; no
  climatology was read), truncated to 950-1050 hPa and +-30 K (*assumption*: the ranges nearly all
  airport observations fall in; the records, 870 and 1084 hPa, lie outside).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from flightmode.errors import AircraftError, InputDataError, ScenarioError, did_you_mean, first_nonfinite
from flightmode.labels import AIRBORNE_PHASES, PHASE_CODE, PHASES
from flightmode.sim.flight import atmosphere as isa
from flightmode.uncertain import Uncertain, value_of
from flightmode.units import FPM_MPS, FT_M, HPA_PA, PSI_PA

# ---------------------------------------------------------------------------------------------
# near the ground: the numbers no source gives (docs/research/fleet_loads/OTHER_SOURCES.md, section 1)

LANDING_RESIDUAL = Uncertain(
    "cabin.landing_residual_psi",
    0.1,
    0.03,
    0.2,
    "psi",
    "Airbus Getting to Grips with the Cockpit/Cabin systems, as usually quoted: the cabin reaches field "
    "pressure + 0.1 psi just before landing (not read here); a crew flash-card deck of unnamed type: 190 ft "
    "below the field (0.1 psi); 737 FCOM 2.40.5 and 787 FCOM 2.30.2: 'slightly' pressurised, no number; "
    "assumption: the range from barely measurable to twice the quoted figure",
    "the cabin's overpressure over the arrival field at touchdown: the pressure step after it",
)
LANDING_LEVEL_HEIGHT = Uncertain(
    "cabin.landing_level_height_ft",
    1000.0,
    200.0,
    2500.0,
    "ft",
    "assumption: the descriptions give no height (A320: landing pressure 'just prior to landing'; 737 "
    "FCOM 2.40.5 and 787 FCOM 2.30.2: the cabin descends to slightly below the landing altitude and "
    "lands pressurised); 1,000 ft, the stabilised-approach gate; 200 ft, the last seconds of a final "
    "approach; 2,500 ft, its start",
    "the aircraft's height above the arrival field from which the cabin holds its landing pressure",
)
VENT_737 = Uncertain(
    "cabin.vent_737_s",
    90.0,
    30.0,
    240.0,
    "s",
    "737 FCOM 2.40.5: 'While taxiing in, the controller drives the outflow valve slowly to the full "
    "open position' (no time); assumption: half a minute to four, within a taxi-in",
    "how long a 737's residual overpressure takes to vent, from the start of the taxi-in",
)
VENT_787 = Uncertain(
    "cabin.vent_787_s",
    5.0,
    1.0,
    30.0,
    "s",
    "787 FCOM 2.30.2: 'At touchdown, both outflow valves open' (no rate); the manual switch moves a "
    "valve over its full travel in 30 s (the slowest end); assumption: the automatic drive about as "
    "fast as the valve's 5 s lag",
    "how long a 787's residual overpressure takes to vent from touchdown",
)
UNCERTAIN = (LANDING_RESIDUAL, LANDING_LEVEL_HEIGHT, VENT_737, VENT_787)

# ---------------------------------------------------------------------------------------------
# per-type pressurisation profiles


@dataclass(frozen=True, slots=True)
class CabinProfile:
    """One type's pressurisation system (module docstring for the sources of every figure)."""

    model: str  # JSBSim model (the key of aircraft.registry.PROFILES)
    max_cabin_alt_ft: float  # 14 CFR 25.841(a) 8,000 ft; 787 6,000 ft
    # (selected level up to which, max differential psi); () derives one band from the ceiling
    diff_bands: tuple[tuple[float, float], ...] = ()
    climb_rate_fpm: float = 500.0
    descent_rate_fpm: float = 300.0
    descent_rate_max_fpm: float = 750.0
    prepress_psi: float = 0.1
    prepress_rate_fpm: float = 400.0
    release_rate_fpm: float = 500.0  # the venting rate after landing, unless ``vent`` is given
    ofv_tau_s: float = 5.0
    vent_start: str = "touchdown"  # or "taxi_in": when the residual overpressure starts to vent
    vent: Uncertain | None = None  # the vent's duration (s), when no rate is published

    def max_diff_pa(self, cruise_alt_m: float) -> float:
        """Maximum differential (Pa) the controller holds at the selected cruise level."""
        if self.diff_bands:
            for upto_ft, psi in self.diff_bands:
                if cruise_alt_m <= upto_ft * FT_M + 1e-6:
                    return psi * PSI_PA
            return self.diff_bands[-1][1] * PSI_PA
        from flightmode.sim.flight.aircraft.registry import get_profile

        ceiling_m = get_profile(self.model).ceiling_ft * FT_M
        return float(isa.pressure_pa(self.max_cabin_alt_ft * FT_M) - isa.pressure_pa(ceiling_m))

    def cruise_cabin_alt_m(self, cruise_alt_m: float) -> float:
        """The cabin pressure altitude at the planned level, before the field floor: as low as the
        maximum differential allows, at most the maximum cabin altitude."""
        p = float(isa.pressure_pa(cruise_alt_m)) + self.max_diff_pa(cruise_alt_m)
        return min(self.max_cabin_alt_ft * FT_M, float(isa.pressure_altitude_m(p)))


CABIN_PROFILES: dict[str, CabinProfile] = {
    "737": CabinProfile(
        "737",
        8000.0,
        diff_bands=((28_000.0, 7.45), (37_000.0, 7.80), (1e9, 8.35)),
        vent_start="taxi_in",
        vent=VENT_737,
    ),
    "A320": CabinProfile("A320", 8000.0, climb_rate_fpm=1000.0, descent_rate_fpm=350.0),
    "fokker100": CabinProfile("fokker100", 8000.0),
    "787-8": CabinProfile("787-8", 6000.0, vent=VENT_787),
}


def get_cabin_profile(model: str) -> CabinProfile:
    try:
        return CABIN_PROFILES[model]
    except KeyError:
        raise AircraftError(
            f"no cabin pressure profile for aircraft '{model}'{did_you_mean(model, CABIN_PROFILES)}; "
            f"profiled: {', '.join(sorted(CABIN_PROFILES))}"
        ) from None


# ---------------------------------------------------------------------------------------------
# weather

QNH_MEAN_HPA = 1013.25
QNH_SIGMA_HPA = 8.0  # assumption (module docstring)
QNH_RANGE_HPA = (950.0, 1050.0)
ISA_DEV_SIGMA_K = 8.0  # assumption (module docstring)
ISA_DEV_RANGE_K = (-30.0, 30.0)


@dataclass(frozen=True, slots=True)
class Weather:
    """The pressure field at one airport: its QNH and the ISA temperature deviation above it."""

    qnh_hpa: float = QNH_MEAN_HPA
    isa_dev_k: float = 0.0

    def as_dict(self) -> dict:
        return {"qnh_hpa": self.qnh_hpa, "isa_dev_k": self.isa_dev_k}


def draw_weather(
    rng: np.random.Generator, qnh_sigma_hpa: float = QNH_SIGMA_HPA, isa_dev_sigma_k: float = ISA_DEV_SIGMA_K
) -> Weather:
    """One airport's weather: QNH ~ N(1013.25 hPa, sigma) and ISA deviation ~ N(0, sigma), each
    truncated to its range by redrawing (two normals per attempt, in that order)."""
    if qnh_sigma_hpa < 0 or isa_dev_sigma_k < 0:
        raise ScenarioError(
            f"weather spreads must be >= 0 (QNH sigma {qnh_sigma_hpa} hPa, ISA sigma {isa_dev_sigma_k} K)"
        )
    while True:
        q = QNH_MEAN_HPA + qnh_sigma_hpa * rng.standard_normal()
        d = isa_dev_sigma_k * rng.standard_normal()
        if QNH_RANGE_HPA[0] <= q <= QNH_RANGE_HPA[1] and ISA_DEV_RANGE_K[0] <= d <= ISA_DEV_RANGE_K[1]:
            return Weather(float(q), float(d))


def _g_integral(h_m):
    """G(h) = integral of dh / T_std(h): the temperature correction's kernel (ISA layers)."""
    h = np.asarray(h_m, float)
    tropo = np.log(np.maximum(isa.T0_K + isa.LAPSE_KPM * h, 1.0)) / isa.LAPSE_KPM
    g11 = math.log(isa.T_TROPO_K) / isa.LAPSE_KPM
    return np.where(h < isa.H_TROPO_M, tropo, g11 + (h - isa.H_TROPO_M) / isa.T_TROPO_K)


def ambient_pressure_pa(alt_m, qnh_hpa=QNH_MEAN_HPA, isa_dev_k=0.0, datum_m=0.0) -> np.ndarray:
    """Static pressure (Pa) at geometric altitude ``alt_m`` (above mean sea level).

    ``qnh_hpa``: the altimeter setting that reads the elevation ``datum_m`` (the airport) on the
    ground: the station pressure there is the ISA law started from QNH (its definition), exact
    whatever the temperature. Above the datum the air is ``isa_dev_k`` warmer than ISA at every
    pressure level, so a geometric layer is ``(T_std + dT) / T_std`` times thicker than its
    pressure-altitude layer (hypsometric equation): z - datum = (h_p - h_d) + dT (G(h_p) - G(h_d)),
    solved for h_p by Newton's method (five steps: quadratic convergence, far below a millimetre).
    Every argument broadcasts (a weather blended along a flight is an array).
    """
    z = np.asarray(alt_m, float)
    q = np.asarray(qnh_hpa, float) * HPA_PA
    dt = np.asarray(isa_dev_k, float)
    zd = np.asarray(datum_m, float)
    # station pressure at the datum from QNH under the ISA law: p = QNH (T(zd) / T0)^exp
    p_d = q * (np.maximum(isa.T0_K + isa.LAPSE_KPM * zd, 1.0) / isa.T0_K) ** isa.BAROMETRIC_EXPONENT
    h_d = isa.pressure_altitude_m(p_d)
    target = z - zd
    g_d = _g_integral(h_d)
    h = h_d + target * isa.T0_K / (isa.T0_K + dt)
    for _ in range(5):
        f = (h - h_d) + dt * (_g_integral(h) - g_d) - target
        h = h - f / (1.0 + dt / isa.temperature_k(h))
    return isa.pressure_pa(h)


# ---------------------------------------------------------------------------------------------
# the schedule

HOLD_OPTIONS = ("pressurised", "unpressurised")
DOOR_OPEN_PHASES = ("gate", "parked")  # boarding and deplaning: the cabin door is open
_DESCENT_SIDE = ("descent", "approach", "flare", "rollout", "taxi_in", "shutdown", "parked")


@dataclass(frozen=True, slots=True)
class CabinTruth:
    """Pressure truth per sample (N,), SI. ``schedule_altitude_m`` is the controller's rate-limited
    target before the outflow-valve lag; ``descent_rate_fpm`` the cabin descent rate it used."""

    ambient_pressure_pa: np.ndarray
    cabin_pressure_pa: np.ndarray
    cabin_altitude_m: np.ndarray  # ISA pressure altitude of the cabin pressure
    hold_pressure_pa: np.ndarray
    schedule_altitude_m: np.ndarray
    cruise_cabin_altitude_m: float
    descent_rate_fpm: float
    hold: str
    landing_residual_psi: float = math.nan  # the run's values of the landing parameters (UNCERTAIN)
    landing_level_height_m: float = math.nan
    vent_s: float = math.nan  # the schedule's venting ramp after landing (s; the lag adds ~3 tau)


def _phase_codes(phase, n: int) -> np.ndarray:
    ph = np.asarray(phase)
    if ph.shape != (n,):
        raise InputDataError(f"cabin pressure: phase has shape {ph.shape}, need ({n},) like t_s")
    if ph.dtype.kind in "iu":
        if ph.size and (ph.min() < 0 or ph.max() >= len(PHASES)):
            raise InputDataError(
                f"cabin pressure: phase codes must be in 0..{len(PHASES) - 1} (flightmode.labels.PHASES)"
            )
        return ph.astype(np.intp)
    names, inv = np.unique(ph.astype(str), return_inverse=True)
    for name in names:
        if name not in PHASE_CODE:
            raise InputDataError(f"cabin pressure: unknown phase '{name}'{did_you_mean(name, PHASES)}")
    return np.array([PHASE_CODE[s] for s in names], np.intp)[inv]


def _check_series(t_s, alt_m) -> tuple[np.ndarray, np.ndarray, float]:
    t = np.asarray(t_s, float)
    h = np.asarray(alt_m, float)
    if t.ndim != 1 or h.shape != t.shape or t.size < 2:
        raise InputDataError(
            f"cabin pressure: need t_s and alt_m as 1-D arrays of one length >= 2, "
            f"got {t.shape} and {h.shape}"
        )
    for name, x in (("t_s", t), ("alt_m", h)):
        if (i := first_nonfinite(x)) is not None:
            raise InputDataError(f"cabin pressure: {name} is NaN or inf at sample {i}")
    dt = np.diff(t)
    step = float(np.median(dt))
    bad = np.flatnonzero(np.abs(dt - step) > 1e-6 * step + 1e-9)
    if not step > 0 or bad.size:
        i = int(bad[0]) if bad.size else 0
        raise InputDataError(
            f"cabin pressure: t_s must be uniformly sampled and increasing (step {step:g} s); "
            f"at sample {i + 1} (t = {t[i + 1]:.3f} s) the step is {dt[i]:g} s"
        )
    return t, h, step


def cumulative_rise_m(rate_mps: np.ndarray, dt: float) -> np.ndarray:
    """R[k] = sum of ``rate_mps[i] * dt`` for 1 <= i <= k (R[0] = 0): a rate limit's allowance. The
    rates take a few values (one per phase group), so R is summed per value from integer counts, one
    rounding each: a running float sum drifts by ~1e-9 m over an hour's 10^4 steps, enough to tip the
    first step of a descent at the exact rate it needs over its limit by 1e-6 ft/min."""
    r = np.asarray(rate_mps, float)[1:]
    out = np.zeros(r.size + 1)
    for u in np.unique(r):
        out[1:] += u * dt * np.cumsum(r == u)
    return out


def cabin_pressure(
    t_s,
    alt_m,
    phase,
    cruise_alt_m: float,
    aircraft: str | CabinProfile,
    *,
    weather: Weather = Weather(),
    arrival_weather: Weather | None = None,
    departure_elev_m: float | None = None,
    arrival_elev_m: float | None = None,
    hold: str = "pressurised",
    overrides: Mapping[str, float] | None = None,
) -> CabinTruth:
    """Cabin (and hold) pressure of one flight (module docstring).

    ``t_s`` (N,) uniformly sampled; ``alt_m`` (N,) geometric altitude above MSL of the aircraft;
    ``phase`` (N,) codes into :data:`flightmode.labels.PHASES` or names; ``cruise_alt_m`` the planned
    cruise level as a pressure altitude (FL350 = 35,000 ft); ``aircraft`` a JSBSim model with a
    :data:`CABIN_PROFILES` entry, or a profile. ``weather`` / ``arrival_weather`` (default the same) the
    airports' :class:`Weather`; ``departure_elev_m`` / ``arrival_elev_m`` their elevations (default:
    ``alt_m`` at the first and last sample, the aircraft on the ground there). ``overrides``: the
    run's uncertain model parameters (a scenario's ``[model]`` table, name -> value; read with
    :func:`flightmode.uncertain.value_of`; None: every one nominal).
    """
    prof = aircraft if isinstance(aircraft, CabinProfile) else get_cabin_profile(aircraft)
    t, z, dt = _check_series(t_s, alt_m)
    n = t.shape[0]
    code = _phase_codes(phase, n)
    if hold not in HOLD_OPTIONS:
        raise ScenarioError(
            f"hold '{hold}'{did_you_mean(hold, HOLD_OPTIONS)}: allowed {', '.join(HOLD_OPTIONS)}"
        )
    if not (np.isfinite(cruise_alt_m) and cruise_alt_m > 0):
        raise InputDataError(
            f"cabin pressure: cruise_alt_m {cruise_alt_m!r} must be a positive pressure altitude"
        )
    arr_w = weather if arrival_weather is None else arrival_weather
    e_dep = float(z[0]) if departure_elev_m is None else float(departure_elev_m)
    e_arr = float(z[-1]) if arrival_elev_m is None else float(arrival_elev_m)

    def in_set(names) -> np.ndarray:
        return np.isin(code, [PHASE_CODE[p] for p in names])

    airborne = in_set(AIRBORNE_PHASES)
    air_idx = np.flatnonzero(airborne)
    # weather blend: the departure's up to liftoff, the arrival's from touchdown, linear in between
    if air_idx.size:
        t_off, t_td = t[air_idx[0]], t[min(air_idx[-1] + 1, n - 1)]
        w = np.clip((t - t_off) / max(t_td - t_off, dt), 0.0, 1.0)
    else:
        w = np.zeros(n)
    qnh = weather.qnh_hpa + w * (arr_w.qnh_hpa - weather.qnh_hpa)
    dev = weather.isa_dev_k + w * (arr_w.isa_dev_k - weather.isa_dev_k)
    p_amb = ambient_pressure_pa(z, qnh, dev, e_dep + w * (e_arr - e_dep))
    h_amb = isa.pressure_altitude_m(p_amb)

    # fields (pressure altitudes), pre-pressurised fields, cruise cabin
    pre = prof.prepress_psi * PSI_PA
    resid = value_of(LANDING_RESIDUAL, overrides) * PSI_PA
    n_land = value_of(LANDING_LEVEL_HEIGHT, overrides) * FT_M
    p_dep = float(ambient_pressure_pa(e_dep, weather.qnh_hpa, weather.isa_dev_k, e_dep))
    p_arr = float(ambient_pressure_pa(e_arr, arr_w.qnh_hpa, arr_w.isa_dev_k, e_arr))
    h_dep, h_arr = float(isa.pressure_altitude_m(p_dep)), float(isa.pressure_altitude_m(p_arr))
    a_dep, a_arr = float(isa.pressure_altitude_m(p_dep + pre)), float(isa.pressure_altitude_m(p_arr + resid))
    cruise_cab = max(prof.cruise_cabin_alt_m(cruise_alt_m), min(a_dep, a_arr))
    dp_max = prof.max_diff_pa(cruise_alt_m)

    # the schedule s: ground -> ambient; takeoff roll -> ramp to the pre-pressurised field;
    # airborne -> proportional to the aircraft's progress between field and cruise level
    descent_side = np.maximum.accumulate(in_set(_DESCENT_SIDE))

    def frac(h0: float) -> np.ndarray:  # progress from the field to the cruise level
        return np.clip((h_amb - h0) / (cruise_alt_m - h0), 0.0, 1.0) if cruise_alt_m > h0 else np.ones(n)

    s = h_amb.copy()
    climb_side = airborne & ~descent_side
    s[climb_side] = (a_dep + (cruise_cab - a_dep) * frac(h_dep))[climb_side]
    desc_air = airborne & descent_side
    f_land = frac(h_arr)
    if cruise_alt_m > h_arr:  # the last 2N of the proportional schedule squeezed into N..2N above
        # the field: the cabin at its landing pressure from N above it down to touchdown
        f_land = np.clip(
            np.minimum(f_land, 2.0 * (h_amb - h_arr - n_land) / (cruise_alt_m - h_arr)), 0.0, 1.0
        )
    s[desc_air] = (a_arr + (cruise_cab - a_arr) * f_land)[desc_air]
    roll = code == PHASE_CODE["takeoff_roll"]
    if roll.any():
        t_roll = t[np.flatnonzero(roll)[0]]
        ramp = np.maximum(
            isa.pressure_altitude_m(p_amb + pre), h_amb - prof.prepress_rate_fpm * FPM_MPS * (t - t_roll)
        )
        s[roll] = ramp[roll]

    # after touchdown: the landing pressure held until the vent starts (at touchdown, or the 737's
    # taxi-in), then ambient at the type's venting rate
    up = np.where(airborne, prof.climb_rate_fpm, prof.release_rate_fpm) * FPM_MPS
    vent_s = (h_arr - a_arr) / (prof.release_rate_fpm * FPM_MPS)
    if prof.vent is not None:
        vent_s = value_of(prof.vent, overrides)
    if air_idx.size and air_idx[-1] + 1 < n:
        td = int(air_idx[-1]) + 1
        later = np.flatnonzero(in_set(("taxi_in", "shutdown", "parked"))[td:])
        v0 = td if prof.vent_start == "touchdown" else td + int(later[0]) if later.size else n
        s[td:v0] = a_arr  # the landing pressure: the field's + the residual (not the moving CG's)
        up[td:] = max(h_arr - a_arr, 0.0) / vent_s
    # rate limits per interval (k-1 -> k), by the phase of sample k (the first entry is unused)
    r_up = cumulative_rise_m(up, dt)
    c1 = r_up + np.minimum.accumulate(s - r_up)  # cabin rise limited
    rate_dn = prof.descent_rate_fpm
    if air_idx.size:
        # the steepest average descent the cabin needs from its peak: no earlier start than the peak
        seg = slice(air_idx[0], air_idx[-1] + 1)
        ca = c1[seg]
        k = ca.size - 1 - int(np.argmax(ca[::-1]))
        if k < ca.size - 1:
            # elapsed time as the limiter counts it (steps of dt): the times' own rounding, ~1e-9 s
            # over an hour's descent, would let the first step exceed the rate by that much
            need_mps = float(np.max((ca[k] - ca[k + 1 :]) / (np.arange(1, ca.size - k) * dt)))
            rate_dn = min(max(rate_dn, need_mps / FPM_MPS), prof.descent_rate_max_fpm)
    dn = np.where(airborne, rate_dn, prof.prepress_rate_fpm) * FPM_MPS
    r_dn = cumulative_rise_m(dn, dt)
    c2 = np.minimum.accumulate((c1 + r_dn)[::-1])[::-1] - r_dn  # cabin descent limited (backwards)
    # structural limits: differential at most dp_max (safety valve), never negative (relief valve)
    c2 = np.clip(c2, isa.pressure_altitude_m(p_amb + dp_max), h_amb)

    # outflow-valve dynamics: first-order lag on pressure, started in steady state
    from scipy.signal import lfilter

    p_sched = isa.pressure_pa(c2)
    a = math.exp(-dt / prof.ofv_tau_s)
    p_cab, _ = lfilter([1.0 - a], [1.0, -a], p_sched, zi=[a * p_sched[0]])
    door_open = in_set(DOOR_OPEN_PHASES)
    p_cab = np.where(door_open, p_amb, p_cab)
    return CabinTruth(
        ambient_pressure_pa=p_amb,
        cabin_pressure_pa=p_cab,
        cabin_altitude_m=isa.pressure_altitude_m(p_cab),
        hold_pressure_pa=hold_pressure_pa(p_cab, p_amb, hold),
        schedule_altitude_m=c2,
        cruise_cabin_altitude_m=float(cruise_cab),
        descent_rate_fpm=float(rate_dn),
        hold=hold,
        landing_residual_psi=resid / PSI_PA,
        landing_level_height_m=n_land,
        vent_s=float(vent_s),
    )


def hold_pressure_pa(cabin_pressure_pa, ambient_pressure_pa, hold: str) -> np.ndarray:
    """The cargo hold's pressure: the cabin's when pressurised (one pressure vessel), ambient when not."""
    if hold not in HOLD_OPTIONS:
        raise ScenarioError(
            f"hold '{hold}'{did_you_mean(hold, HOLD_OPTIONS)}: allowed {', '.join(HOLD_OPTIONS)}"
        )
    return np.asarray(cabin_pressure_pa if hold == "pressurised" else ambient_pressure_pa, float).copy()


def cabin_figures(
    t_s,
    alt_m,
    cabin_altitude_m,
    cabin_pressure_pa,
    ambient_pressure_pa,
    phase_code,
    rate_window_s: float = 10.0,
) -> dict:
    """A flight's cabin in the figures a pressurisation schedule is specified by: the cruise cabin
    altitude and pressure (medians over the cruise phase), the largest cabin climb and descent rates
    (ft/min, differences over ``rate_window_s``: the controller's rate limits are per minute, and the
    outflow valve's lag smooths anything shorter), over the whole flight and airborne only (on the
    runway the cabin is pre-pressurised and released at their own rates), the largest differential
    (psi) and the aircraft's highest altitude."""
    t = np.asarray(t_s, float)
    h = np.asarray(cabin_altitude_m, float)
    code = np.asarray(phase_code)
    step = max(1, int(round(rate_window_s / float(np.median(np.diff(t))))))
    rate_fpm = (h[step:] - h[:-step]) / (t[step:] - t[:-step]) / FPM_MPS
    air = np.isin(code, [PHASE_CODE[p] for p in AIRBORNE_PHASES])
    air_rate = rate_fpm[
        air[step:] & air[:-step]
    ]  # both ends airborne (the runway's pre-pressurisation excluded)
    cruise = code == PHASE_CODE["cruise"]
    diff = np.asarray(cabin_pressure_pa, float) - np.asarray(ambient_pressure_pa, float)
    return {
        "max_altitude_ft": float(np.max(alt_m)) / FT_M,
        "cruise_cabin_altitude_ft": float(np.median(h[cruise])) / FT_M if cruise.any() else math.nan,
        "cruise_cabin_pressure_hpa": float(np.median(np.asarray(cabin_pressure_pa)[cruise])) / HPA_PA
        if cruise.any()
        else math.nan,
        "max_cabin_altitude_ft": float(np.max(h)) / FT_M,
        "max_cabin_climb_fpm": float(max(rate_fpm.max(), 0.0)) if rate_fpm.size else math.nan,
        "max_cabin_descent_fpm": float(max(-rate_fpm.min(), 0.0)) if rate_fpm.size else math.nan,
        "max_cabin_climb_airborne_fpm": float(max(air_rate.max(), 0.0)) if air_rate.size else math.nan,
        "max_cabin_descent_airborne_fpm": float(max(-air_rate.min(), 0.0)) if air_rate.size else math.nan,
        "max_differential_psi": float(diff.max()) / PSI_PA,
        "min_differential_psi": float(diff.min()) / PSI_PA,
    }


__all__ = [
    "CABIN_PROFILES",
    "cabin_figures",
    "DOOR_OPEN_PHASES",
    "HOLD_OPTIONS",
    "CabinProfile",
    "CabinTruth",
    "Weather",
    "ambient_pressure_pa",
    "cabin_pressure",
    "draw_weather",
    "get_cabin_profile",
    "hold_pressure_pa",
]
