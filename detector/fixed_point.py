"""Seed 000's NMV detector as a microcontroller runs it (``--detector nmv-fixed``): 8-bit samples,
integer running sums, the threshold an integer register. The same algorithm, bit for bit, as the C
firmware example ``examples/nmv_fixed.c`` (run through :mod:`flightmode.detector.pipe`).

Integer form, per axis (all integers; the only floating-point step is the emulation of the sensor's
ADC, which the part does in hardware, and the configuration of the threshold register):

1. the count: ``c = clip(rint(a / lsb_g), -128, 127)`` (the LIS302DL at +-2 g: 8-bit two's complement,
   18 mg/digit typ., ST's LIS302DL datasheet, Rev 4, 2008; the LSB and the count range are those of
   :mod:`flightmode.sim.sensor.accelerometer`'s ``lis302dl`` preset, rounding to nearest, ties to
   even, and saturation as it quantises);
2. running sums over the last ``N = round(W_s fs)`` counts (seed 000, eq. 2-3: add the new sample and
   its square, subtract the oldest's): ``S1 = sum c``, ``S2 = sum c^2``; exact in integers, so they
   never drift (the floating NMV has to re-anchor, :mod:`~flightmode.detector.moving_variance`);
3. the variance without a division: ``D = N S2 - S1^2 = N^2 MV`` (eq. 1 times ``N^2``, in counts^2);
4. the threshold register ``T = rint(k sigma^2 2^f)``: ``k sigma^2`` (eq. 12, sigma^2 in counts^2) in
   unsigned fixed point with ``f = frac_bits`` fractional bits (one LSB = ``2^-f`` counts^2); a check
   is temporarily static (eq. 7) when ``D 2^f < T N^2`` on every axis;
5. every ``N`` samples a check; final static (eq. 8) when the last ``ceil(T_th / W_s)`` checks since
   the last reset were all temporarily static. Each sample's decision is the latest check's final
   static (False before the first check); a time gap (more than 1.5 sample periods) resets the sums
   and the count of checks, as the floating detector does (:mod:`~flightmode.detector.flight_mode`).

The floating detector compares ``MV < k sigma^2`` exactly; the register rounds ``k sigma^2`` to
``2^-f`` counts^2, so the two can disagree only on a check whose MV lies between the two thresholds:
within half an LSB of the threshold (:func:`compare_fixed_float` counts them and checks the bound).

sigma^2 (counts^2 per axis): ``sigma2_counts`` if given, else ``sigma2`` in g^2 (the built-in ``nmv``'s
parameter) over ``lsb_g^2``, else calibrated on the unit's rest recording
(``rest``, quantised to counts, :func:`~flightmode.detector.flight_mode.calibrate_sigma2` with the
quantisation floor 1/12 counts^2), else that floor itself: the calibration a truly still 8-bit part
gives (its count is constant: an 18 mg step is eight times the part's 2.23 mg noise, seed 000 Table 1).

This module imports NumPy (and the floating detector, for the comparison) inside its functions.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from flightmode.detector.interface import ACC_CHANNELS
from flightmode.detector.recommended_point import POINT
from flightmode.errors import DetectorError

_PART = "lis302dl"  # the sensor preset whose 8-bit counts the firmware reads (LSB_G, COUNT_MIN, COUNT_MAX)
# the threshold register's fractional bits: one LSB = 1/256 counts^2, 1/85 of the default threshold
# (k = 4 times the quantisation floor 1/12 counts^2)
FRAC_BITS = 8
# the quantisation noise of a count, in counts^2 (a uniform rounding error of one LSB: 1/12)
QUANTISATION_FLOOR = 1.0 / 12.0
# a gap: consecutive samples more than 1.5 periods apart (as flight_mode's detector)
GAP_PERIODS = 1.5


def _part() -> dict:
    """The LIS302DL preset's LSB (g) and count range (:mod:`flightmode.sim.sensor.accelerometer`, the
    one copy of those datasheet figures: 18 mg/digit, 8-bit two's complement, -128 to +127)."""
    from flightmode.sim.sensor.accelerometer import get_preset

    p = get_preset(_PART)
    lo, hi = p.count_range
    return {"LSB_G": p.lsb_g, "COUNT_MIN": lo, "COUNT_MAX": hi}


def __getattr__(name: str):  # LSB_G, COUNT_MIN, COUNT_MAX: read from the preset when first asked for
    if name in ("LSB_G", "COUNT_MIN", "COUNT_MAX"):
        return _part()[name]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _lsb(lsb_g: float | None) -> float:
    return _part()["LSB_G"] if lsb_g is None else float(lsb_g)


def to_counts(acc_g: Any, lsb_g: float | None = None):
    """The 8-bit counts (int64 array) of accelerations in g: rint(a / lsb_g) clipped to the part's
    count range [-128, 127] (``lsb_g`` None: the part's 18 mg)."""
    import numpy as np

    part = _part()
    lsb = part["LSB_G"] if lsb_g is None else float(lsb_g)
    a = np.asarray(acc_g, float)
    return np.clip(np.rint(a / lsb), part["COUNT_MIN"], part["COUNT_MAX"]).astype(np.int64)


def threshold_register(k: float, sigma2_counts: Any, frac_bits: int = FRAC_BITS):
    """The per-axis threshold register ``rint(k sigma^2 2^f)`` (int64): k sigma^2 in counts^2 with
    ``frac_bits`` fractional bits (module docstring, step 4). The C example computes it the same way
    ((k * sigma2) * 2^f in double, then llrint), so both registers hold the same integers."""
    import numpy as np

    s2 = np.asarray(sigma2_counts, float)
    return np.rint(float(k) * s2 * float(2**frac_bits)).astype(np.int64)


class FixedNMV:
    """The streaming integer detector (module docstring). ``push(t_s, acc_g)`` returns one decision
    per sample; :meth:`checks` the checks of a chunk (index, D per axis, temporary and final static)."""

    def __init__(
        self,
        fs_hz: float,
        window_s: float = POINT.window_s,
        k: float = POINT.k_sigma,
        time_threshold_s: float = POINT.time_threshold_s,
        sigma2_counts: Any = QUANTISATION_FLOOR,
        lsb_g: float | None = None,
        frac_bits: int = FRAC_BITS,
    ):
        import numpy as np

        if not fs_hz > 0:
            raise DetectorError(f"nmv-fixed: sampling rate {fs_hz}: must be > 0 Hz")
        self.fs_hz = float(fs_hz)
        self.window = int(round(window_s * fs_hz))
        if self.window < 2:
            raise DetectorError(
                f"nmv-fixed: window {window_s} s at {fs_hz:g} Hz is {self.window} sample(s): a variance needs >= 2"
            )
        if self.window > 65536:
            raise DetectorError(
                f"nmv-fixed: window of {self.window} samples: at most 65,536 (the sums are 64-bit)"
            )
        if not k > 0 or not time_threshold_s > 0:
            raise DetectorError(f"nmv-fixed: k = {k} and time_threshold_s = {time_threshold_s} must be > 0")
        lsb_g = _lsb(lsb_g)
        if not lsb_g > 0:
            raise DetectorError(f"nmv-fixed: lsb_g = {lsb_g}: the count's step must be > 0 g")
        if int(frac_bits) != frac_bits or not 0 <= frac_bits <= 16:
            raise DetectorError(f"nmv-fixed: frac_bits = {frac_bits}: an integer in 0-16")
        s2 = np.broadcast_to(np.asarray(sigma2_counts, float), (3,)).copy()
        if not np.all(np.isfinite(s2)) or not np.all(s2 > 0):
            raise DetectorError(
                f"nmv-fixed: sigma2_counts {s2.tolist()}: three positive per-axis variances in counts^2"
            )
        self.k, self.window_s, self.time_threshold_s = float(k), float(window_s), float(time_threshold_s)
        self.sigma2_counts = s2
        self.lsb_g, self.frac_bits = float(lsb_g), int(frac_bits)
        self.register = threshold_register(k, s2, self.frac_bits)
        # eq. 8: checks in a row (as DetectorParams.checks_needed)
        self.need = max(1, math.ceil(time_threshold_s / window_s - 1e-9))
        self._n = 0  # samples seen
        self._t_last: float | None = None
        self._reset()

    def _reset(self) -> None:
        import numpy as np

        self._tail = np.zeros((0, 3), np.int64)  # the last N - 1 counts since the reset
        self._since = 0  # samples since the reset
        self._run = 0  # temporary statics in a row (eq. 8's state)
        self._decision = False  # the latest check's final static

    def push(self, t_s: Any, acc_g: Any):
        """One decision (bool) per sample of the chunk."""
        return self._push(t_s, acc_g)[0]

    def checks(self, t_s: Any, acc_g: Any) -> dict:
        """Push the chunk and return its checks: ``index`` (global sample), ``d`` (K, 3) = N^2 MV in
        counts^2, ``temporary``, ``final`` (K,) and the per-sample ``decisions``."""
        dec, chk = self._push(t_s, acc_g)
        return {**chk, "decisions": dec}

    def _push(self, t_s: Any, acc_g: Any):
        import numpy as np

        t = np.asarray(t_s, float)
        a = np.asarray(acc_g, float)
        if a.ndim != 2 or a.shape[1] != 3 or t.shape != (a.shape[0],):
            raise DetectorError(f"nmv-fixed: need t_s (n,) and acc_g (n, 3); got {t.shape} and {a.shape}")
        bad = ~np.isfinite(a).all(axis=1) | ~np.isfinite(t)
        if bad.any():
            raise DetectorError(
                f"nmv-fixed: NaN or inf in the stream at sample {self._n + int(np.argmax(bad))}"
            )
        period = 1.0 / self.fs_hz
        if t.shape[0] > 1:
            dt = np.diff(t)
            if np.any(dt <= 0):
                i = int(np.flatnonzero(dt <= 0)[0])
                raise DetectorError(
                    f"nmv-fixed: time is not increasing at sample {self._n + i + 1} (t = {t[i + 1]:.4f} s)"
                )
            med = float(np.median(dt))
            if abs(med - period) > 0.01 * period:
                raise DetectorError(
                    f"nmv-fixed: the stream is sampled at {1 / med:.2f} Hz but the detector expects "
                    f"{self.fs_hz:g} Hz: set fs_hz to the stream's rate"
                )
        c = to_counts(a, self.lsb_g)
        gaps = []
        if self._t_last is not None and t.shape[0] and t[0] - self._t_last > GAP_PERIODS * period:
            gaps.append(0)
        if t.shape[0] > 1:
            gaps += [int(g) for g in np.flatnonzero(np.diff(t) > GAP_PERIODS * period) + 1]
        decs, parts, start = [], [], 0
        for g in [*gaps, t.shape[0]]:
            if g > start:
                d, chk = self._segment(c[start:g], self._n + start)
                decs.append(d)
                parts.append(chk)
            if g < t.shape[0]:
                self._reset()
            start = g
        if t.shape[0]:
            self._t_last = float(t[-1])
        self._n += t.shape[0]
        dec = np.concatenate(decs) if decs else np.zeros(0, bool)
        keys = ("index", "d", "temporary", "final")
        empty = {
            "index": np.zeros(0, np.int64),
            "d": np.zeros((0, 3), np.int64),
            "temporary": np.zeros(0, bool),
            "final": np.zeros(0, bool),
        }
        chk = {k: np.concatenate([p[k] for p in parts]) if parts else empty[k] for k in keys}
        return dec, chk

    def _segment(self, c, base: int):
        """A run of samples with no gap: the sums, the checks and the decisions (module docstring)."""
        import numpy as np

        n_win, m = self.window, c.shape[0]
        h = np.vstack([self._tail, c])  # the last N - 1 counts before, then the segment
        k0 = self._tail.shape[0]
        zero = np.zeros((1, 3), np.int64)
        c1 = np.vstack([zero, np.cumsum(h, axis=0)])  # exact: integers
        c2 = np.vstack([zero, np.cumsum(h * h, axis=0)])
        seen = self._since + np.arange(1, m + 1)  # samples since the reset, this one included
        at = np.flatnonzero((seen % n_win == 0) & (seen >= n_win))  # the checks, every N samples
        end = k0 + at + 1  # prefix index just past the check's sample in h
        s1 = c1[end] - c1[end - n_win]  # eq. 2: the window's sum
        s2 = c2[end] - c2[end - n_win]  # eq. 3: the window's sum of squares
        d = n_win * s2 - s1 * s1  # N^2 MV, counts^2
        temp = np.all((d << self.frac_bits) < self.register * (n_win * n_win), axis=1)  # eq. 7
        # eq. 8: the run of temporary statics ending at each check, continued from the carried run
        j = np.arange(at.shape[0])
        last_dyn = np.maximum.accumulate(np.where(~temp, j, -1)) if j.size else j
        run = np.where(last_dyn < 0, self._run + j + 1, j - last_dyn)
        final = temp & (run >= self.need)
        if j.size:
            self._run = int(run[-1]) if temp[-1] else 0
        # each sample holds the latest check's decision
        mark = np.full(m, -1)
        mark[at] = j
        last = np.maximum.accumulate(mark)
        dec = (
            np.where(last >= 0, final[np.maximum(last, 0)], self._decision)
            if j.size
            else (np.full(m, self._decision))
        )
        if j.size:
            self._decision = bool(final[-1])
        self._tail = h[-(n_win - 1) :] if h.shape[0] >= n_win - 1 else h
        self._since += m
        return dec.astype(bool), {"index": base + at, "d": d, "temporary": temp, "final": final}


def _acc_columns(channels: Sequence[str]) -> list[int]:
    missing = [c for c in ACC_CHANNELS if c not in channels]
    if missing:
        raise DetectorError(
            f"nmv-fixed: the stream has no {', '.join(missing)} (it reads the three accelerometer axes)"
        )
    return [list(channels).index(c) for c in ACC_CHANNELS]


class _Detector:
    """The interface's detector (:mod:`flightmode.detector.interface`): the accelerometer columns of
    ``x`` fed to a :class:`FixedNMV`."""

    def __init__(self, engine: FixedNMV, cols: list[int]):
        self.engine, self.cols = engine, cols

    def push(self, t_s: Any, x: Any):
        import numpy as np

        return self.engine.push(t_s, np.asarray(x, float)[:, self.cols])


def sigma2_counts_of_rest(rest: Any, window: int, lsb_g: float | None = None):
    """sigma^2 per axis in counts^2 from the unit's rest recording in g (m, 3): the recording
    quantised to counts and calibrated as seed 000 section 5.1 step (1) asks
    (:func:`~flightmode.detector.flight_mode.calibrate_sigma2`, floor 1/12 counts^2)."""
    from flightmode.detector.flight_mode import calibrate_sigma2

    return calibrate_sigma2(to_counts(rest, lsb_g).astype(float), window, lsb_g=1.0)


def make(
    fs_hz: float,
    channels: Sequence[str],
    window_s: float = POINT.window_s,
    k: float = POINT.k_sigma,
    time_threshold_s: float = POINT.time_threshold_s,
    rest: Any = None,
    sigma2_counts: Any = None,
    lsb_g: float | None = None,
    frac_bits: int = FRAC_BITS,
    sigma2: Any = None,
):
    """The ``nmv-fixed`` factory (module docstring): seed 000's NMV in integers. sigma^2 per axis (one
    number or three): ``sigma2_counts`` in counts^2, else ``sigma2`` in g^2 as the built-in ``nmv``
    takes it (divided by ``lsb_g * lsb_g``: the same parameter grid serves both), else calibrated on
    the rest recording ``rest`` (in the stream's channels), else the quantisation floor."""
    import numpy as np

    lsb_g = _lsb(lsb_g)
    cols = _acc_columns(channels)
    if sigma2_counts is None and sigma2 is not None:
        sigma2_counts = np.asarray(sigma2, float) / (lsb_g * lsb_g)  # examples/nmv_fixed.c: the same
    if sigma2_counts is None:
        if rest is not None:
            window = int(round(window_s * fs_hz))
            r = np.asarray(rest, float)
            if r.ndim != 2 or r.shape[1] != len(channels):
                raise DetectorError(
                    f"nmv-fixed: the rest recording has shape {r.shape}, expected (m, {len(channels)})"
                )
            sigma2_counts = sigma2_counts_of_rest(r[:, cols], window, lsb_g)
        else:
            sigma2_counts = QUANTISATION_FLOOR
    engine = FixedNMV(fs_hz, window_s, k, time_threshold_s, sigma2_counts, lsb_g, frac_bits)
    return _Detector(engine, cols)


make.channels = ACC_CHANNELS  # type: ignore[attr-defined]


def compare_fixed_float(
    t_s: Any,
    acc_g: Any,
    fs_hz: float,
    window_s: float = POINT.window_s,
    k: float = POINT.k_sigma,
    time_threshold_s: float = POINT.time_threshold_s,
    sigma2_counts: Any = QUANTISATION_FLOOR,
    lsb_g: float | None = None,
    frac_bits: int = FRAC_BITS,
) -> dict:
    """The integer detector against the floating one (:func:`flightmode.detector.flight_mode.detect`,
    NMV) on the same 8-bit samples (the counts times ``lsb_g``, in g) and the same threshold
    (``k sigma^2``, sigma^2 = ``sigma2_counts lsb_g^2`` in g^2). Returns a dict:

    - ``checks``: checks run (the same samples in both: asserted);
    - ``temporary_disagreements`` / ``final_disagreements``: checks whose eq. 7 / eq. 8 outcome differs;
      ``sample_disagreements``: samples whose decision differs;
    - ``axis_disagreements``: (check, axis) comparisons that differ, each with ``lsb_from_threshold``,
      ``|MV - k sigma^2|`` in LSBs of the register (``2^-f`` counts^2, MV the floating one);
    - ``max_lsb_from_threshold`` and ``within_one_lsb`` (every disagreement within one LSB of the
      threshold: the module docstring's bound, half an LSB from the register's rounding);
    - ``final_explained``: every final-static disagreement has a temporary disagreement among the
      ``ceil(T_th / W_s)`` checks ending at it (eq. 8 carries no other difference);
    - the parameters, the registers and the thresholds.
    """
    lsb_g = _lsb(lsb_g)
    import numpy as np

    from flightmode.detector.flight_mode import DetectorParams, detect

    t = np.asarray(t_s, float)
    counts = to_counts(acc_g, lsb_g)
    fixed = FixedNMV(fs_hz, window_s, k, time_threshold_s, sigma2_counts, lsb_g, frac_bits)
    fx = fixed.checks(t, counts * lsb_g)
    s2_counts = fixed.sigma2_counts
    p = DetectorParams(
        fs_hz=float(fs_hz), window_s=window_s, k_sigma=k, time_threshold_s=time_threshold_s, method="nmv"
    )
    fl = detect(t, counts * lsb_g, p, s2_counts * lsb_g**2)
    if not np.array_equal(fl.index, fx["index"]):
        raise DetectorError(
            f"nmv-fixed: its checks ({fx['index'].shape[0]}) are not at the floating detector's "
            f"({fl.index.shape[0]}) samples"
        )
    n_win = fixed.window
    float_below = fl.mv < p.k_sigma * s2_counts * lsb_g**2  # eq. 7 per axis, floating
    fixed_below = (fx["d"] << fixed.frac_bits) < fixed.register * (n_win * n_win)
    diff = float_below != fixed_below
    mv_counts2 = fl.mv / lsb_g**2
    lsb = 2.0**-fixed.frac_bits
    dist = np.abs(mv_counts2 - k * s2_counts[None, :]) / lsb
    ci, ai = np.nonzero(diff)
    axis_dis = [
        {
            "check": int(c),
            "sample": int(fl.index[c]),
            "t_s": float(fl.t_s[c]),
            "axis": "xyz"[a],
            "mv_counts2": float(mv_counts2[c, a]),
            "threshold_counts2": float(k * s2_counts[a]),
            "register_counts2": float(fixed.register[a] * lsb),
            "lsb_from_threshold": float(dist[c, a]),
        }
        for c, a in zip(ci, ai, strict=True)
    ]
    temp_dis = fl.temporary_static != fx["temporary"]
    fin_dis = fl.final_static != fx["final"]
    # eq. 8 only looks back over the last `need` checks: a final disagreement needs a temporary one there
    tdi = np.flatnonzero(temp_dis)
    explained = all(np.any((tdi <= c) & (tdi > c - fixed.need)) for c in np.flatnonzero(fin_dis).tolist())
    # the floating detector's per-sample decisions as the integer one makes them: each sample holds
    # the latest check's final static, False from a gap (a reset) until the next check
    event = np.full(t.shape[0], -1)  # -1: nothing new; 0: a reset; 1 + j: check j
    if t.shape[0] > 1:
        event[np.flatnonzero(np.diff(t) > GAP_PERIODS / float(fs_hz)) + 1] = 0
    event[fl.index] = 1 + np.arange(fl.index.shape[0])
    pos = np.maximum.accumulate(np.where(event >= 0, np.arange(t.shape[0]), -1)) if t.size else event
    latest = np.where(pos >= 0, event[np.maximum(pos, 0)], 0)
    final_or_false = np.concatenate([[False], fl.final_static])
    float_dec = final_or_false[latest]
    max_lsb = float(dist[ci, ai].max()) if ci.size else 0.0
    return {
        "samples": int(t.shape[0]),
        "checks": int(fl.index.shape[0]),
        "temporary_disagreements": int(temp_dis.sum()),
        "final_disagreements": int(fin_dis.sum()),
        "sample_disagreements": int(np.sum(float_dec != fx["decisions"])),
        "axis_disagreements": axis_dis,
        "max_lsb_from_threshold": max_lsb,
        "within_one_lsb": bool(max_lsb <= 1.0),
        "final_explained": bool(explained),
        "final_static_checks_fixed": int(fx["final"].sum()),
        "final_static_checks_float": int(fl.final_static.sum()),
        "window": n_win,
        "checks_needed": fixed.need,
        "k": float(k),
        "frac_bits": fixed.frac_bits,
        "lsb_g": fixed.lsb_g,
        "sigma2_counts": s2_counts.tolist(),
        "register": fixed.register.tolist(),
    }


__all__ = [
    "FRAC_BITS",
    "QUANTISATION_FLOOR",
    "FixedNMV",
    "compare_fixed_float",
    "make",
    "sigma2_counts_of_rest",
    "threshold_register",
    "to_counts",
]
