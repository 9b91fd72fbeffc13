"""A pressure-rate detector, and the redundant suspension rule over it and seed 000's accelerometer
detector (EASA's FAQ on cargo trackers with transmitting devices: at least two independent sources;
suspend when ANY says flying, resume only when ALL say on the ground).

**Pressure detector.** Every ``check_s`` (every ``M = check_s fs`` samples, at fixed global positions,
as seed 000's checks every W_s) two statistics of the last ``window_s`` (``N`` samples):

- the rate: the least-squares slope of pressure against time, ``r = sum_i w_i p_i`` with
  ``w_i = fs (i - (N - 1) / 2) / S``, ``S = N (N^2 - 1) / 12`` (a linear FIR filter, optimal for a line in
  white noise);
- the level: the window's mean ``m``.

A check is *quiet* when ``|r| <= T_rate`` (rate bound) and ``m >= p_ref - margin`` (level bound: the
pressure not below the reference ground pressure by more than the margin, i.e. the cabin not well
above the departure field, which holds the suspension in calm cruise when the rate is zero). The
pressure source says *static* (on the ground, at rest) when the last ``ceil(hold_s / check_s)``
checks were all quiet: seed 000 eq. 8's run-length rule (as :func:`flightmode.detector.flight_mode.final_static`,
unrolled into a loop over the checks because the reference below depends on the state) with the hold
time as T_th. The reference ``p_ref`` is the first window's mean (the stream starts on
the ground) and then follows the window mean at every static check, so slow weather and road
elevation changes at rest are tracked; while suspended it is frozen at the departure ground pressure.

*The arrival field*: an arrival field more than the margin above the departure's (e.g. 1,330 ft
higher: London to Geneva) would leave the level bound out after landing for ever. The pressure alone
cannot tell that ground from a level-off in the descent, so the detector takes the destination's
expected ground pressure when it is known (``arrival_ground_pa``: a shipment's tracker is told its
route; flightmode uses the ISA pressure at the destination's elevation, the day's QNH being within
the margin): the level bound also holds within the margin of it. The cost: a holding pattern whose
cabin is within the margin of the arrival field's pressure (a low hold near the destination) is
quiet to the pressure source after the hold time, and the accelerometer alone guards it. Without a
known destination :func:`evaluate_sources` shows such a flight ``held`` by ``pressure_level``.

**Thresholds from the noise (seed 000 section 5.1.1 style).** With white noise sigma_p per sample,
the slope has sigma_r = sigma_p sqrt(12 / (N (N^2 - 1))) fs (:func:`rate_sigma_pa_s`) and the mean
sigma_m = sigma_p / sqrt(N). Per check (H1: at rest on the ground; H0: cabin moving / in cruise):

- P_M (rate) = P(|r| > T | rate 0) = erfc(T / (sqrt 2 sigma_r));
- P_FA (rate) = P(|r| <= T | rate rho) = Phi((T - rho) / sigma_r) - Phi((-T - rho) / sigma_r);
- P_M (level) = P(m - p_ref < -margin | at ref) = Q(margin / (sqrt 2 sigma_m)) (both means noisy);
- P_FA (level) = P(m - p_ref >= -margin | depth d) = Q((d - margin) / (sqrt 2 sigma_m)).

The defaults, BMP581 at x16 (0.21 Pa) and 25 Hz, 30 s windows: sigma_r = 8.9e-4 Pa/s. The schedule's
rate limits (300-1,000 ft/min) are not the slowest cabin rates a flight shows: the proportional
schedule moves the cabin from the field to its cruise altitude over the whole climb, so a low cruise
moves it slowly (an A320 from Liege at FL240: about 1,200 ft of cabin in 15 min, 80 ft/min, 4.8 Pa/s;
the first design, 5 Pa/s over 4 s, missed it, declared the climb quiet and let the ground reference
creep up with the cabin). ``T_rate = 1 Pa/s`` (17 ft/min at sea level, 21 ft/min at 8,000 ft) is a
third of a 60 ft/min cabin at 8,000 ft (2.9 Pa/s, :func:`cabin_rate_pa_s`, the design's slowest rate):
T / sigma_r = 1,130 (P_M per check ~ 0; below 1e-6 for any sensor up to sigma_p = 48 Pa), and
(rho - T) / sigma_r = 2,100 at 60 ft/min (P_FA ~ 0). It is far above the weather's pressure changes at
rest (a deep low deepens by 1-2 hPa/h: 0.06 Pa/s, *recalled, not read*). What exceeds it on the
ground (a lift at 1-2 m/s, a hilly road, gusts on an open apron) costs only missed transmissions
(P_M), never a false static; the 30 s window makes a second's door slam or gust a small slope. A
300 ft/min cabin is flagged 4.6 s after it starts (:func:`ramp_response_s`). A cabin that does not
move at all (a hop whose cruise cabin stays at the field's pressure) gives the pressure source
nothing to see: there only the accelerometer can suspend. The level margin of 25 hPa (about 700 ft of
cabin altitude near sea level) is above a day's typical weather change while suspended
(*assumption*: a few hPa; 25 hPa is a deep storm) and holds a calm cruise whenever the cruise cabin is
more than about 700 ft above the departure field: at FL350 the cabin is at 3,600 ft (787-8), 6,550
(A320), 7,190 (737) and 8,000 ft (Fokker 100) (:mod:`flightmode.sim.flight.cabin`). From a higher
field, or on a short low flight, only the rate bound and the accelerometer remain. The hold of 120 s
is shorter than any taxi-in, so it costs no response time at the gate in the normal case (the
accelerometer's own T_th dominates), and it rides through level-offs shorter than 2 min below the
margin (*assumption*).

**Redundant rule.** Per accelerometer check (every W_s), transmission is allowed when the
accelerometer is final static (eq. 8) AND the pressure source is static as of that time (its last
check at or before it; before its first check it is not static). Equivalently: OR to suspend, AND to
resume; each source's own hold decides its resume. Each source's state is kept per check.
Streaming: :class:`RedundantRule` takes each detector's checks as they come and emits a combined
check once the pressure checks have reached its time (:meth:`RedundantRule.finish` emits the rest with
the last pressure state), so any chunking gives the batch result exactly (:func:`detect_redundant`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import TYPE_CHECKING

import numpy as np

from flightmode.detector.flight_mode import Checks, DetectorParams, FlightModeDetector
from flightmode.errors import DetectorError, first_nonfinite
from flightmode.units import FPM_MPS, FT_M, G0_MPS2

if TYPE_CHECKING:  # imported where it is used, at run time
    from flightmode.detector.evaluation import Evaluation

# ---------------------------------------------------------------------------------------------
# parameters and statistics


@dataclass(frozen=True, slots=True)
class PressureParams:
    """Pressure detector parameters (module docstring for the justification of the defaults)."""

    fs_hz: float = 25.0
    window_s: float = 30.0
    check_s: float = 1.0
    rate_threshold_pa_s: float = 1.0
    level_margin_pa: float | None = 2500.0  # None: no level bound (rate only)
    hold_s: float = 120.0
    max_gap_periods: float = 1.5  # consecutive samples further apart than this many periods: a gap
    # the destination's expected ground pressure (a shipment's tracker knows its route): the level bound
    # also holds within the margin of it, so an arrival field higher than the departure's by more than the
    # margin does not hold the suspension for ever; None: the departure reference only
    arrival_ground_pa: float | None = None

    @property
    def window(self) -> int:
        return round(self.window_s * self.fs_hz)

    @property
    def check(self) -> int:
        return round(self.check_s * self.fs_hz)

    @property
    def checks_needed(self) -> int:
        return max(1, math.ceil(self.hold_s / self.check_s - 1e-9))

    def validate(self) -> None:
        if not (self.fs_hz > 0 and math.isfinite(self.fs_hz)):
            raise DetectorError(f"pressure detector: sampling rate {self.fs_hz} Hz must be > 0")
        if self.window < 3:
            raise DetectorError(
                f"pressure detector: window {self.window_s} s at {self.fs_hz:g} Hz is "
                f"{self.window} sample(s); a rate needs >= 3"
            )
        if self.check < 1 or abs(self.check_s * self.fs_hz - self.check) > 1e-6:
            raise DetectorError(
                f"pressure detector: check period {self.check_s} s must be a whole number "
                f"(>= 1) of samples at {self.fs_hz:g} Hz"
            )
        if not self.rate_threshold_pa_s > 0:
            raise DetectorError(
                f"pressure detector: rate threshold {self.rate_threshold_pa_s} Pa/s must be > 0"
            )
        if self.level_margin_pa is not None and not self.level_margin_pa > 0:
            raise DetectorError(
                f"pressure detector: level margin {self.level_margin_pa} Pa must be > 0 "
                "(or None for no level bound)"
            )
        if not self.hold_s > 0:
            raise DetectorError(f"pressure detector: hold time {self.hold_s} s must be > 0")
        if not self.max_gap_periods > 1:
            raise DetectorError(f"pressure detector: max_gap_periods {self.max_gap_periods} must be > 1")
        if self.arrival_ground_pa is not None and not (
            math.isfinite(self.arrival_ground_pa) and self.arrival_ground_pa > 0
        ):
            raise DetectorError(
                f"pressure detector: arrival_ground_pa {self.arrival_ground_pa} must be a pressure > 0 Pa"
            )


def slope_weights(n: int, fs_hz: float) -> np.ndarray:
    """Least-squares slope weights over n samples at fs: r = sum w_i p_i (Pa/s)."""
    i = np.arange(n, dtype=float)
    return fs_hz * (i - (n - 1) / 2.0) / (n * (n * n - 1) / 12.0)


def rate_sigma_pa_s(noise_pa: float, fs_hz: float, window_s: float) -> float:
    """Standard deviation of the least-squares rate over a window of white noise sigma_p."""
    n = round(window_s * fs_hz)
    return float(noise_pa * math.sqrt(12.0 / (n * (n * n - 1.0))) * fs_hz)


def mean_sigma_pa(noise_pa: float, fs_hz: float, window_s: float) -> float:
    return float(noise_pa / math.sqrt(round(window_s * fs_hz)))


def cabin_rate_pa_s(rate_fpm: float, cabin_alt_m: float) -> float:
    """A cabin altitude rate (ft/min) as a pressure rate (Pa/s) at a cabin pressure altitude:
    dp/dt = rho(h) g dh/dt (hydrostatic, ISA density)."""
    from flightmode.sim.flight.atmosphere import density_kgpm3

    return float(rate_fpm * FPM_MPS * density_kgpm3(cabin_alt_m) * G0_MPS2)


def _phi(x: float) -> float:
    return 0.5 * math.erfc(-x / math.sqrt(2.0))


def pm_rate(threshold_pa_s: float, sigma_r: float) -> float:
    """P(|r| > T) at rest: a quiet check flagged by the rate bound."""
    return float(math.erfc(threshold_pa_s / (math.sqrt(2.0) * sigma_r))) if sigma_r > 0 else 0.0


def pfa_rate(threshold_pa_s: float, rate_pa_s: float, sigma_r: float) -> float:
    """P(|r| <= T) while the pressure changes at ``rate_pa_s``: the rate bound misses a moving cabin."""
    if sigma_r == 0:
        return float(abs(rate_pa_s) <= threshold_pa_s)
    return _phi((threshold_pa_s - rate_pa_s) / sigma_r) - _phi((-threshold_pa_s - rate_pa_s) / sigma_r)


def pm_level(margin_pa: float, sigma_m: float) -> float:
    """P(m - p_ref < -margin) at the reference (the two window means both noisy)."""
    return 1.0 - _phi(margin_pa / (math.sqrt(2.0) * sigma_m)) if sigma_m > 0 else 0.0


def pfa_level(margin_pa: float, depth_pa: float, sigma_m: float) -> float:
    """P(m - p_ref >= -margin) with the pressure ``depth_pa`` below the reference (cruise cabin)."""
    if sigma_m == 0:
        return float(depth_pa <= margin_pa)
    return 1.0 - _phi((depth_pa - margin_pa) / (math.sqrt(2.0) * sigma_m))


def ramp_response_s(rate_pa_s: float, threshold_pa_s: float, window_s: float) -> float:
    """Time after a pressure ramp of ``rate_pa_s`` starts until the least-squares rate over the window
    exceeds the threshold (noise-free). The slope of a ramp that started d seconds ago is
    rate (3 u^2 - 2 u^3), u = d / W (integrate the LS weights against the ramp); inf if |rate| <= T."""
    q = threshold_pa_s / abs(rate_pa_s) if rate_pa_s else math.inf
    if q >= 1.0:
        return math.inf
    lo, hi = 0.0, 1.0
    for _ in range(80):  # bisection on the monotone smoothstep
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if 3 * mid**2 - 2 * mid**3 < q else (lo, mid)
    return hi * window_s


def lagged_ramp_response_s(rate_pa_s: float, threshold_pa_s: float, window_s: float, tau_s: float) -> float:
    """An upper bound on the response to a ramp seen through a first-order lag of time constant tau
    (the cabin's outflow valve): the lag's output rate is rate (1 - exp(-s / tau)), at least q rate
    after d_q = -tau ln(1 - q); the least-squares slope is an average of the derivative with a
    non-negative kernel (6 u (W - u) / W^3), so from d_q on it is at least the smoothstep response of
    a ramp of q rate. The bound is min over q in (T / rate, 1) of d_q + :func:`ramp_response_s`."""
    r = abs(rate_pa_s)
    if tau_s <= 0:
        return ramp_response_s(r, threshold_pa_s, window_s)
    if r <= threshold_pa_s:
        return math.inf
    q = np.linspace(threshold_pa_s / r, 1.0, 2002)[1:-1]
    return float(
        min(-tau_s * math.log(1.0 - qi) + ramp_response_s(qi * r, threshold_pa_s, window_s) for qi in q)
    )


def design(
    noise_pa: float,
    params: PressureParams = PressureParams(),
    slowest_cabin_rate_fpm: float = 60.0,
    cabin_alt_ft: float = 8000.0,
    cruise_depth_pa: float | None = None,
) -> dict:
    """The thresholds' statistics for a sensor noise (module docstring): sigma_r, sigma_m, T / sigma_r,
    per-check P_M and P_FA of both bounds, and the ramp response at the slowest cabin rate."""
    params.validate()
    s_r = rate_sigma_pa_s(noise_pa, params.fs_hz, params.window_s)
    s_m = mean_sigma_pa(noise_pa, params.fs_hz, params.window_s)
    rho = cabin_rate_pa_s(slowest_cabin_rate_fpm, cabin_alt_ft * FT_M)
    out = {
        "sigma_rate_pa_s": s_r,
        "sigma_mean_pa": s_m,
        "threshold_over_sigma": params.rate_threshold_pa_s / s_r if s_r > 0 else math.inf,
        "slowest_cabin_rate_pa_s": rho,
        "pm_rate": pm_rate(params.rate_threshold_pa_s, s_r),
        "pfa_rate": pfa_rate(params.rate_threshold_pa_s, rho, s_r),
        "ramp_response_s": ramp_response_s(rho, params.rate_threshold_pa_s, params.window_s),
    }
    if params.level_margin_pa is not None:
        out["pm_level"] = pm_level(params.level_margin_pa, s_m)
        if cruise_depth_pa is not None:
            out["pfa_level"] = pfa_level(params.level_margin_pa, cruise_depth_pa, s_m)
    return out


# ---------------------------------------------------------------------------------------------
# the pressure detector


@dataclass(frozen=True, slots=True)
class PressureChecks:
    """One row per pressure check (every check_s)."""

    index: np.ndarray  # (K,) global sample index of the window end
    t_s: np.ndarray  # (K,)
    rate_pa_s: np.ndarray  # (K,) least-squares slope over the window
    mean_pa: np.ndarray  # (K,) window mean
    reference_pa: np.ndarray  # (K,) the ground reference the level bound used
    rate_ok: np.ndarray  # (K,) bool
    level_ok: np.ndarray  # (K,) bool
    quiet: np.ndarray  # (K,) bool: both bounds hold
    static: np.ndarray  # (K,) bool: quiet for the hold time (the pressure source says at rest)


def _cat_pressure(parts: list[PressureChecks]) -> PressureChecks:
    names = [f.name for f in fields(PressureChecks)]
    if not parts:
        z = np.zeros(0)
        return PressureChecks(z.astype(np.int64), z, z, z, z, *(z.astype(bool) for _ in range(4)))
    return PressureChecks(*(np.concatenate([getattr(p, n) for p in parts]) for n in names))


class PressureDetector:
    """Streaming pressure detector: ``push(t_s, baro_pa)`` returns the checks completed by the chunk.
    A gap, NaN, a wrong rate or non-increasing time raises :class:`DetectorError` (a pressure stream
    is judged whole: clean it, or start a new detector after the gap)."""

    def __init__(self, params: PressureParams = PressureParams()):
        params.validate()
        self.p = params
        self._w = slope_weights(params.window, params.fs_hz)
        self._tail = np.zeros(0)  # the last N - 1 samples, relative to _p0
        self._p0: float | None = None
        self._n = 0
        self._t_last: float | None = None
        self._run = 0
        self._ref: float | None = None

    def push(self, t_s, baro_pa) -> PressureChecks:
        p = self.p
        t = np.asarray(t_s, float)
        x = np.asarray(baro_pa, float)
        if t.ndim != 1 or x.shape != t.shape:
            raise DetectorError(
                f"pressure detector: need t_s (n,) and baro_pa (n,); got {t.shape} and {x.shape}"
            )
        m = t.shape[0]
        if m == 0:
            return _cat_pressure([])
        for name, v in (("t_s", t), ("baro_pa", x)):
            if (i := first_nonfinite(v)) is not None:
                raise DetectorError(
                    f"pressure detector: {name} is NaN or inf at sample {self._n + i} "
                    f"(t = {t[i]:.3f} s): clean the stream"
                )
        period = 1.0 / p.fs_hz
        tt = t if self._t_last is None else np.concatenate([[self._t_last], t])
        if tt.shape[0] > 1:
            dt = np.diff(tt)
            off = 0 if self._t_last is None else 1
            if np.any(dt <= 0):
                i = int(np.flatnonzero(dt <= 0)[0])
                raise DetectorError(
                    f"pressure detector: time is not increasing at sample {self._n + i + 1 - off} "
                    f"(t = {tt[i + 1]:.3f} s)"
                )
            med = float(np.median(dt))
            if (dt.size >= 3 and abs(med - period) > 0.01 * period) or np.any(
                dt < period / p.max_gap_periods
            ):
                raise DetectorError(
                    f"pressure detector: the stream is sampled at {1 / med:.3f} Hz but the detector "
                    f"expects {p.fs_hz:g} Hz: set fs_hz to the stream's rate"
                )
            gap = np.flatnonzero(dt > p.max_gap_periods * period)
            if gap.size:
                i = int(gap[0])
                raise DetectorError(
                    f"pressure detector: gap of {dt[i]:.3f} s before t = {tt[i + 1]:.3f} s (sample "
                    f"{self._n + i + 1 - off}); a {p.fs_hz:g} Hz stream allows "
                    f"{p.max_gap_periods * period:.3f} s: split the stream there"
                )
        if self._p0 is None:
            self._p0 = float(x[0])
        n_w, n_c = p.window, p.check
        buf = np.concatenate([self._tail, x - self._p0])
        first = self._n - self._tail.shape[0]  # global index of buf[0]
        g = self._n + np.arange(m)
        at = ((g + 1) % n_c == 0) & (g + 1 >= n_w)
        idx = g[at]
        if idx.size:
            starts = idx - n_w + 1 - first
            win = np.lib.stride_tricks.sliding_window_view(buf, n_w)[starts]
            rate = (win * self._w).sum(axis=1)
            mean = self._p0 + win.sum(axis=1) / n_w
        else:
            rate = mean = np.zeros(0)
        k_n = idx.size
        ref = np.empty(k_n)
        rate_ok = np.abs(rate) <= p.rate_threshold_pa_s
        level_ok = np.ones(k_n, bool)
        quiet = np.empty(k_n, bool)
        static = np.empty(k_n, bool)
        need = p.checks_needed
        # seed 000 eq. 8 (the run length of quiet checks against the hold), written as the loop it unrolls
        # to: the level bound's reference follows the static state, so each check needs the previous one
        for k in range(k_n):
            if self._ref is None:
                self._ref = float(mean[k])
            ref[k] = self._ref
            if p.level_margin_pa is not None:
                level_ok[k] = mean[k] >= self._ref - p.level_margin_pa or (
                    p.arrival_ground_pa is not None
                    and abs(mean[k] - p.arrival_ground_pa) <= p.level_margin_pa
                )
            quiet[k] = rate_ok[k] and level_ok[k]
            self._run = self._run + 1 if quiet[k] else 0
            static[k] = self._run >= need
            if static[k]:
                self._ref = float(mean[k])
        keep = min(n_w - 1, buf.shape[0])
        self._tail = buf[buf.shape[0] - keep :].copy()
        t_chk = t[idx - self._n]
        self._n += m
        self._t_last = float(t[-1])
        return PressureChecks(idx.astype(np.int64), t_chk, rate, mean, ref, rate_ok, level_ok, quiet, static)


def detect_pressure(t_s, baro_pa, params: PressureParams = PressureParams()) -> PressureChecks:
    """Batch front end: every pressure check of a whole stream."""
    return PressureDetector(params).push(t_s, baro_pa)


def static_at(checks: PressureChecks, t_s) -> np.ndarray:
    """The pressure source's state as of each time (its last check at or before it; not static before
    its first check): what the redundant rule ANDs with the accelerometer's final static."""
    t = np.asarray(t_s, float)
    j = np.searchsorted(checks.t_s, t, side="right") - 1
    return (
        np.where(j >= 0, checks.static[np.maximum(j, 0)], False)
        if checks.t_s.size
        else np.zeros(t.shape, bool)
    )


# ---------------------------------------------------------------------------------------------
# the redundant rule


@dataclass(frozen=True, slots=True)
class RedundantChecks:
    """One row per accelerometer check; each source's state and the combined decision."""

    t_s: np.ndarray  # (K,) accelerometer check times
    accel_static: np.ndarray  # (K,) bool: seed 000 final static
    pressure_static: np.ndarray  # (K,) bool: pressure source static as of t_s
    pressure_rate_ok: np.ndarray  # (K,) bool: its rate bound as of t_s
    pressure_level_ok: np.ndarray  # (K,) bool: its level bound as of t_s
    allowed: np.ndarray  # (K,) bool: transmission allowed = all sources static

    @property
    def suspended(self) -> np.ndarray:
        return ~self.allowed


def _cat_redundant(parts: list[RedundantChecks]) -> RedundantChecks:
    names = [f.name for f in fields(RedundantChecks)]
    if not parts:
        z = np.zeros(0)
        return RedundantChecks(z, *(z.astype(bool) for _ in range(5)))
    return RedundantChecks(*(np.concatenate([getattr(p, n) for p in parts]) for n in names))


class RedundantRule:
    """Combine the accelerometer's checks and the pressure detector's checks as they arrive (module
    docstring). ``push(accel=..., pressure=...)`` returns the combined checks it can decide now."""

    def __init__(self):
        self._acc_t = np.zeros(0)
        self._acc_s = np.zeros(0, bool)
        self._p_t = np.zeros(0)
        self._p_state = np.zeros((0, 3), bool)  # static, rate_ok, level_ok
        self._done = False

    def push(self, accel: Checks | None = None, pressure: PressureChecks | None = None) -> RedundantChecks:
        if self._done:
            raise DetectorError("redundant rule: finish() was called; start a new rule for a new stream")
        if accel is not None and accel.t_s.size:
            if self._acc_t.size and accel.t_s[0] <= self._acc_t[-1]:
                raise DetectorError("redundant rule: accelerometer checks must arrive in time order")
            self._acc_t = np.concatenate([self._acc_t, accel.t_s])
            self._acc_s = np.concatenate([self._acc_s, accel.final_static])
        if pressure is not None and pressure.t_s.size:
            if self._p_t.size and pressure.t_s[0] <= self._p_t[-1]:
                raise DetectorError("redundant rule: pressure checks must arrive in time order")
            self._p_t = np.concatenate([self._p_t, pressure.t_s])
            st = np.stack([pressure.static, pressure.rate_ok, pressure.level_ok], axis=1)
            self._p_state = np.concatenate([self._p_state, st])
        if not self._p_t.size:
            return _cat_redundant([])
        return self._emit(int(np.searchsorted(self._acc_t, self._p_t[-1], side="right")))

    def finish(self) -> RedundantChecks:
        """Emit every pending accelerometer check with the pressure source's last state."""
        out = self._emit(self._acc_t.shape[0])
        self._done = True
        return out

    def _emit(self, n: int) -> RedundantChecks:
        t, acc = self._acc_t[:n], self._acc_s[:n]
        j = np.searchsorted(self._p_t, t, side="right") - 1  # the last pressure check at or before t
        if self._p_t.size:
            st = np.where((j >= 0)[:, None], self._p_state[np.maximum(j, 0)], False)
        else:  # no pressure check at all: the pressure source never said static
            st = np.zeros((n, 3), bool)
        out = RedundantChecks(t, acc, st[:, 0], st[:, 1], st[:, 2], acc & st[:, 0])
        self._acc_t, self._acc_s = self._acc_t[n:], self._acc_s[n:]
        if n and self._p_t.size:  # keep the pressure checks still needed: the last at or before t, and later
            k = max(int(j[-1]), 0)
            self._p_t, self._p_state = self._p_t[k:], self._p_state[k:]
        return out


class RedundantDetector:
    """Both detectors and the rule, streaming: ``push(t_acc_s, acc_g, t_baro_s, baro_pa)`` (either
    stream may be empty in a push); ``finish()`` at the end of the streams."""

    def __init__(
        self, accel_params: DetectorParams, sigma2, pressure_params: PressureParams = PressureParams()
    ):
        self.accel = FlightModeDetector(accel_params, sigma2)
        self.pressure = PressureDetector(pressure_params)
        self.rule = RedundantRule()

    def push(self, t_acc_s=None, acc_g=None, t_baro_s=None, baro_pa=None) -> RedundantChecks:
        a = self.accel.push(t_acc_s, acc_g) if t_acc_s is not None else None
        p = self.pressure.push(t_baro_s, baro_pa) if t_baro_s is not None else None
        return self.rule.push(a, p)

    def finish(self) -> RedundantChecks:
        return self.rule.finish()


def detect_redundant(
    t_acc_s,
    acc_g,
    t_baro_s,
    baro_pa,
    accel_params: DetectorParams,
    sigma2,
    pressure_params: PressureParams = PressureParams(),
) -> RedundantChecks:
    """Batch front end: the combined checks of whole accelerometer and pressure streams."""
    d = RedundantDetector(accel_params, sigma2, pressure_params)
    return _cat_redundant([d.push(t_acc_s, acc_g, t_baro_s, baro_pa), d.finish()])


# ---------------------------------------------------------------------------------------------
# evaluation by source

SOURCES = ("accelerometer", "pressure", "combined")


@dataclass(frozen=True, slots=True)
class SourceEvaluation:
    first_suspend_s: dict  # per source: the first check at/after pushback where it says suspend (nan: never)
    first_source: str  # "accelerometer", "pressure", "both" (same check) or "none"
    cruise_checks: int
    held_by: dict  # counts over the cruise checks: accelerometer_only, pressure_only, both, neither
    held_by_pressure: (
        dict  # the pressure suspensions in cruise by bound: rate, level, hold (both ok, in hold)
    )
    resume_s: dict  # per source: first static check at/after t_end minus t_end (nan: never; None: no t_end)


def evaluate_sources(
    checks: RedundantChecks, t_pushback_s: float, cruise_windows, t_end_s: float | None = None
) -> SourceEvaluation:
    """Which source suspended first after pushback; which held the suspension in (calm) cruise, over
    the checks inside ``cruise_windows`` ((t0, t1) pairs, seconds); and, with ``t_end_s`` (engines off,
    or the bag set down at arrival), each source's response: the time to its first static check."""
    t = checks.t_s
    susp = {
        "accelerometer": ~checks.accel_static,
        "pressure": ~checks.pressure_static,
        "combined": ~checks.allowed,
    }
    after = t >= t_pushback_s
    first = {}
    for s, m in susp.items():
        k = np.flatnonzero(after & m)
        first[s] = float(t[k[0]]) if k.size else math.nan
    fa, fp = first["accelerometer"], first["pressure"]
    if math.isnan(fa) and math.isnan(fp):
        first_source = "none"
    elif fa == fp:
        first_source = "both"
    elif math.isnan(fp) or (not math.isnan(fa) and fa < fp):
        first_source = "accelerometer"
    else:
        first_source = "pressure"
    win = np.zeros(t.shape, bool)
    for t0, t1 in cruise_windows:
        win |= (t >= t0) & (t <= t1)
    a, p = susp["accelerometer"][win], susp["pressure"][win]
    held = {
        "accelerometer_only": int((a & ~p).sum()),
        "pressure_only": int((~a & p).sum()),
        "both": int((a & p).sum()),
        "neither": int((~a & ~p).sum()),
    }
    rate_bad = ~checks.pressure_rate_ok[win]
    level_bad = ~checks.pressure_level_ok[win]
    by_p = {
        "rate": int((p & rate_bad).sum()),
        "level": int((p & ~rate_bad & level_bad).sum()),
        "hold": int((p & ~rate_bad & ~level_bad).sum()),
    }
    resume: dict[str, float | None] = {}
    for s, m in susp.items():
        if t_end_s is None:
            resume[s] = None
            continue
        k = np.flatnonzero((t >= t_end_s) & ~m)
        resume[s] = float(t[k[0]] - t_end_s) if k.size else math.nan
    return SourceEvaluation(first, first_source, int(win.sum()), held, by_p, resume)


@dataclass(frozen=True, slots=True)
class RedundantEvaluation:
    """The accelerometer alone and the redundant rule over one labelled recording, scored alike
    (:func:`flightmode.detector.evaluation.score`: false statics in the in-flight window, missed
    static, response at the gate), with each source's states and who suspended / held / resumed."""

    accel: Evaluation  # seed 000's detector alone
    combined: Evaluation  # the same checks scored with final static = the rule's "allowed"
    pressure: PressureChecks
    checks: RedundantChecks
    sources: SourceEvaluation
    pressure_params: PressureParams

    def summary(self) -> dict:
        a, c, s = self.accel, self.combined, self.sources
        return {
            "pressure_params": {
                f.name: getattr(self.pressure_params, f.name) for f in fields(PressureParams)
            },
            "accel_false_static_count": a.false_static_count,
            "accel_false_static_s": a.false_static_s,
            "combined_false_static_count": c.false_static_count,
            "combined_false_static_s": c.false_static_s,
            "combined_false_static_events": c.false_static_events,
            "accel_response_s": a.response_s,
            "combined_response_s": c.response_s,
            "accel_missed_static_s": a.missed_static_s,
            "combined_missed_static_s": c.missed_static_s,
            "first_suspend_s": s.first_suspend_s,
            "first_source": s.first_source,
            "cruise_checks": s.cruise_checks,
            "held_by": s.held_by,
            "held_by_pressure": s.held_by_pressure,
            "resume_s": s.resume_s,
        }


def evaluate_redundant(
    t_s,
    acc_g,
    t_baro_s,
    baro_pa,
    labels: dict,
    accel_params: DetectorParams,
    sigma2,
    pressure_params: PressureParams | None = None,
    t_pushback_s: float | None = None,
    acc_checks: Checks | None = None,
) -> RedundantEvaluation:
    """Seed 000's detector, the pressure detector and the redundant rule over one labelled recording
    (``labels``: ``in_flight_window``, ``sensor_static``, ``phase`` per accelerometer sample; the
    pressure stream at its own rate, ``pressure_params.fs_hz`` defaulting to it). The rule's checks are
    the accelerometer's, so the accelerometer alone and the rule are scored on the same checks.
    ``t_pushback_s`` (default: the window's first sample) starts "which suspended first"; the calm
    cruise windows are the runs of ``phase == "cruise"``; the gate response counts from the first
    truly static sample after the window. ``acc_checks``: the accelerometer detector's checks of this
    stream when already run (a streaming detector's), else run here."""
    import dataclasses

    from flightmode.detector.evaluation import check_labels, score
    from flightmode.detector.flight_mode import detect
    from flightmode.intervals import true_runs

    check_labels(t_s, labels)
    tb = np.asarray(t_baro_s, float)
    if pressure_params is None:
        if tb.shape[0] < 3:
            raise DetectorError("redundant rule: the pressure stream has fewer than 3 samples")
        pressure_params = PressureParams(fs_hz=round(1.0 / float(np.median(np.diff(tb))), 6))
    if acc_checks is None:
        acc_checks = detect(t_s, acc_g, accel_params, sigma2)
    pc = detect_pressure(tb, baro_pa, pressure_params)
    rule = RedundantRule()
    rc = _cat_redundant([rule.push(acc_checks, pc), rule.finish()])
    accel = score(acc_checks, t_s, labels, accel_params, sigma2)
    combined = score(
        dataclasses.replace(acc_checks, final_static=rc.allowed), t_s, labels, accel_params, sigma2
    )
    window = np.asarray(labels["in_flight_window"], bool)
    t = np.asarray(t_s, float)
    win_idx = np.flatnonzero(window)
    t_push = (
        t_pushback_s if t_pushback_s is not None else (float(t[win_idx[0]]) if win_idx.size else float(t[0]))
    )
    cruise = np.asarray(labels["phase"], dtype=object) == "cruise"
    cruise_windows = [(float(t[a]), float(t[b - 1])) for a, b in true_runs(cruise)]
    t_end = None
    if win_idx.size:
        after = np.flatnonzero(np.asarray(labels["sensor_static"], bool)[win_idx[-1] :])
        t_end = float(t[win_idx[-1] + after[0]]) if after.size else None
    sources = evaluate_sources(rc, t_push, cruise_windows, t_end)
    return RedundantEvaluation(accel, combined, pc, rc, sources, pressure_params)


__all__ = [
    "PressureChecks",
    "RedundantEvaluation",
    "evaluate_redundant",
    "PressureDetector",
    "PressureParams",
    "RedundantChecks",
    "RedundantDetector",
    "RedundantRule",
    "SourceEvaluation",
    "cabin_rate_pa_s",
    "design",
    "detect_pressure",
    "detect_redundant",
    "evaluate_sources",
    "static_at",
    "lagged_ramp_response_s",
    "mean_sigma_pa",
    "pfa_level",
    "pfa_rate",
    "pm_level",
    "pm_rate",
    "ramp_response_s",
    "rate_sigma_pa_s",
    "slope_weights",
]
