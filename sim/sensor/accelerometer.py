"""Accelerometer models: named presets (frozen, vary them with ``dataclasses.replace``), per-unit
draws within the datasheet tolerances, and the measurement chain from specific force to counts.

Sources: the ST LIS302DL datasheet (Rev 4, 2008), and flightmode's named assumptions where it gives
no figure (zero-g offset spread, cross-axis coupling);
seed 000 Table 1 (2.23 mg noise) and section 2 (a 100 Hz stream stored with 16-bit resolution);
seed 003 (e-obs tags) sections 4, 6, 9 and 10.

Chain, per axis, on a specific-force stream in the sensor frame sampled at an internal rate that is
an integer multiple of the output data rate (ODR):

1. per-unit cross-axis coupling and zero-g offset: ``a' = (I + C) a + o`` (C off-diagonal);
2. (the per-unit sensitivity ``lsb (1 + s)`` enters at quantisation, step 6);
3. the part's anti-alias low-pass (``bandwidth_hz``; a 2nd-order Butterworth, ``sosfilt``), or none
   (e-obs: seed 003 section 8 says it has no anti-alias filter, so vibration aliases);
4. sampling at the ODR (every k-th internal sample: whatever the filter let through aliases);
5. output noise, sigma ``noise_g`` per axis: white, its amplitude modulated for the LIS302DL presets
   (the section "Modulated noise" below), independent between axes;
6. quantisation to counts (``round(a / lsb)``, plus the zero-g count for offset-binary ADCs) and
   saturation at the part's range (counts clip at the representable extremes).

``acc_g`` is the counts converted back with the unit's *calibrated* sensitivity (as a logger
would after calibration, seed 003 section 7), so the gain tolerance shows in the raw counts, and
the offsets in both.

The 8-bit LIS302DL: an 18 mg step is eight times the 2.23 mg noise, so a truly static part outputs
an almost constant count and its variance is far below (2.23 mg)^2 (an 18 mg step is eight times the 2.23 mg noise). The
preset ``lis302dl-logged16`` models seed 000's logger: the same part, stored at 16 bits over the
+-2.3 g range (0.07 mg steps), so the noise survives and the static variance is 5.0e-6 g^2.

Modulated noise. Seed 000 describes the logged static noise three ways: its spectrum is white
("approximated as an independent white noise", section 4.1, Fig. 4); the mean 1-3 s moving variance is
flat (Table 3: 0.5, 0.51, 0.51 x 1e-5 g^2 at 1, 2, 3 s, i.e. 1.00, 1.02, 1.02 sigma^2); and the 1 s MV
spreads far more than 100 white samples allow (Table 2 via eq. 13: P_M 6e-3 at 2 sigma^2 and 8e-6 at
2.5 sigma^2 imply sigma_MV 0.35-0.40 sigma^2, where white noise gives 0.14), while consecutive 1 s MVs
are "approximated as independent" (section 5.1.1). A stationary Gaussian noise cannot have all three: a
spread that wide needs correlation, and a correlated noise loses part of its variance to a short
window's mean, so its Table 3 rises with the window (the white + Gauss-Markov model used before issue
53 rose 15 % from 1 to 3 s, and its density below 1 Hz was 1.5 mg/sqrt(Hz), 7.5 times the 200
ug/sqrt(Hz) of the analog sister part LIS302SG's datasheet). White noise whose amplitude wanders has all
three: the LIS302DL presets draw

    n[k] = sigma (1 + d g[k]) / sqrt(1 + d^2) w[k],   w ~ N(0, 1) white,
    g[k] = phi g[k-1] + sqrt(1 - phi^2) e[k],           e ~ N(0, 1),  phi = exp(-1 / (ODR tau)),

per axis, with sigma = ``noise_g`` (the variance stays sigma^2), d = ``noise_am_depth`` and tau =
``noise_am_tau_s``. The autocovariance is sigma^2 delta(m) (w is white and independent of g): the
spectrum is flat (:func:`noise_psd_g2_per_hz`), its density sigma sqrt(2 / ODR) = 315 ug/sqrt(Hz) at
100 Hz, and the mean N-sample MV is (N - 1)/N sigma^2 at every window (Table 3 flat). The wandering
amplitude widens the MV's spread (detector.statistics.nmv_moments_am, exact). The fit
(tests/sim/test_noise_colour.py re-derives it): tau = 0.1 s, the longest tenth of a second at which
consecutive 1 s MVs correlate by less than 0.05 (0.041: section 5.1.1's independence; a longer tau
correlates them more: 0.15 at 0.3 s, 0.44 at 1 s), and d = 0.450, which gives the 100-sample NMV the spread 0.373
sigma^2 (the mean of the spreads Table 2's rows 2 and 2.5 sigma^2 imply: the rows the paper's 35 h
of static data can resolve; rows 3 and 4 are eq. 13 extrapolated into a tail the skewed MV
distribution does not have). Its P_M, exact up to the Monte Carlo over amplitude paths
(detector.statistics.pm_am): 1.3e-2 at 2 sigma^2, 1.3e-3 at 2.5 sigma^2 (the paper 6e-3, 8e-6:
eq. 13's Gaussian tail is thinner than any skewed distribution with that spread). g starts in its
stationary distribution (no power-on transient) and its state is carried from chunk to chunk. The
sample kurtosis is 4.9 (3 for Gaussian noise): a noise that is a little burstier than Gaussian. The
form (a Gaussian carrier, its amplitude a Gauss-Markov process) is flightmode's assumption: the seed
gives the three properties, not a mechanism, and no datasheet describes the part's noise beyond its level.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from flightmode.errors import SensorError, did_you_mean, first_nonfinite


@dataclass(frozen=True, slots=True)
class AccelerometerPreset:
    name: str
    description: str
    odr_hz: float
    allowed_odr_hz: tuple[float, ...]
    range_g: float  # reading saturates at +-range_g
    lsb_g: float | None  # quantisation step of the stored value; None: float output
    bits: int | None  # width of the stored count
    zero_count: int  # count at 0 g (0: two's complement; 2048: e-obs offset binary)
    noise_g: float  # output white noise, 1 sigma per axis
    bandwidth_hz: float | None  # anti-alias low-pass cut-off; None: no filter before sampling
    offset_tol_g: float  # per-unit zero-g offset drawn uniformly in +-tol
    sensitivity_tol: float  # per-unit relative gain error drawn uniformly in +-tol
    cross_axis_tol: float  # per-unit cross-axis coupling drawn uniformly in +-tol
    burst_interval_s: float | None = None  # e-obs: a burst every ACC interval
    burst_samples: int | None = None  # e-obs: samples per axis in a burst
    # modulated noise (module docstring): the depth d of the amplitude's modulation (0: plain white
    # noise) and the modulation's correlation time in seconds
    noise_am_depth: float = 0.0
    noise_am_tau_s: float | None = None

    def validate(self) -> None:
        if self.odr_hz not in self.allowed_odr_hz:
            raise SensorError(
                f"sensor '{self.name}': output data rate {self.odr_hz:g} Hz is not one the part has; "
                f"allowed: {', '.join(f'{f:g}' for f in self.allowed_odr_hz)} Hz"
            )
        if self.noise_g < 0 or self.range_g <= 0:
            raise SensorError(f"sensor '{self.name}': noise must be >= 0 and range > 0")
        if not (math.isfinite(self.noise_am_depth) and self.noise_am_depth >= 0.0):
            raise SensorError(
                f"sensor '{self.name}': noise_am_depth {self.noise_am_depth:g} must be a finite number >= 0"
            )
        if self.noise_am_depth > 0 and not (self.noise_am_tau_s is not None and self.noise_am_tau_s > 0):
            raise SensorError(
                f"sensor '{self.name}': a modulated noise needs noise_am_tau_s > 0 (got {self.noise_am_tau_s})"
            )
        if self.lsb_g is not None and (self.bits is None or self.lsb_g <= 0):
            raise SensorError(f"sensor '{self.name}': a quantised output needs bits and lsb_g > 0")
        if (self.burst_interval_s is None) != (self.burst_samples is None):
            raise SensorError(f"sensor '{self.name}': bursts need both burst_interval_s and burst_samples")
        if self.burst_interval_s is not None and self.burst_interval_s <= 0:
            raise SensorError(f"sensor '{self.name}': burst interval must be > 0 s")
        # a burst longer than the interval is allowed: seed 003 section 10 uses it for (nearly)
        # continuous sampling

    @property
    def noise_am_phi(self) -> float:
        """AR(1) coefficient of the modulation at the ODR, exp(-1 / (ODR tau)); 0 if unmodulated."""
        if self.noise_am_depth == 0 or self.noise_am_tau_s is None:
            return 0.0
        return float(np.exp(-1.0 / (self.odr_hz * self.noise_am_tau_s)))

    @property
    def count_range(self) -> tuple[int, int]:
        """Smallest and largest count the output can hold."""
        if self.bits is None:
            return (-(2**31), 2**31 - 1)
        if self.zero_count == 0:
            return (-(2 ** (self.bits - 1)), 2 ** (self.bits - 1) - 1)
        return (0, 2**self.bits - 1)


# LIS302DL, +-2 g (seed 000 Table 1's range: "+-2 or +-8" g; the datasheet's full scale, whose 8-bit
# count at 18 mg/digit reads to about +-2.3 g, the range_g here; +-8 g reads to +-9.2 g): 8-bit two's
# complement, 18 mg/digit typ. (16.2-19.8),
# ODR 100 or 400 Hz, bandwidth ODR/2, noise 2.23 mg (seed 000 Table 1). Offsets +-40 mg, cross-axis
# +-2 %: flightmode assumptions. Sensitivity tolerance +-10 % is the datasheet's 16.2-19.8 mg/digit.
_LIS302DL = AccelerometerPreset(
    name="lis302dl",
    description="ST LIS302DL, +-2 g, native 8-bit output (18 mg/digit), ODR 100 Hz",
    odr_hz=100.0,
    allowed_odr_hz=(100.0, 400.0),
    range_g=2.3,
    lsb_g=0.018,
    bits=8,
    zero_count=0,
    noise_g=2.23e-3,
    bandwidth_hz=50.0,
    offset_tol_g=0.040,
    sensitivity_tol=0.10,
    cross_axis_tol=0.02,
    # seed 000 Tables 2 and 3 and section 4.1 via the fit in the module docstring
    # (tests/sim/test_noise_colour.py)
    noise_am_depth=0.450,
    noise_am_tau_s=0.1,
)

# e-obs per-axis sampling frequencies (seed 003). The note prints no table of settings; it gives a
# rule and two total rates: the per-axis frequency is the total rate over the enabled axes
# (section 4.2: "if you have three ACC axes enabled, then the sampling frequency for all axes
# together is three times the sampling frequency for one axis"), the total rate is at least 10 Hz
# (section 4.1: "10 is the minimum sampling rate that you can choose"; its 1 million samples a day
# at 10 Hz count all axes together) and section 10 sets "the total sample rate to 100 Hz (33 Hz per
# axis)". So the note's values are 10 and 100 Hz in total, per axis with 1, 2 or 3 axes:
# 10 / 5 / 3.33 Hz and 100 / 50 / 33.33 Hz (the note rounds 100/3 to "33"; a rate is compared as one
# exact number, so 10/3 and 100/3 are written to two decimals, 3.33 and 33.33). Rates the note does
# not name (1, 2, 20, 25 Hz) are not accepted. The Movebank albatross file (2 axes at 5.0 Hz) is the
# 10 Hz minimum. The sim preset always senses 3 axes yet keeps every per-axis value (its default
# 10 Hz per axis is 30 Hz in total, a total the note does not name): this is the per-axis table.
EOBS_TOTAL_RATES_HZ: tuple[float, ...] = (10.0, 100.0)
EOBS_PER_AXIS_RATES_HZ: tuple[float, ...] = (3.33, 5.0, 10.0, 33.33, 50.0, 100.0)

PRESETS: dict[str, AccelerometerPreset] = {
    "lis302dl": _LIS302DL,
    "lis302dl-8g": replace(
        _LIS302DL,
        name="lis302dl-8g",
        description="ST LIS302DL, +-8 g, native 8-bit output (72 mg/digit), ODR 100 Hz",
        range_g=9.2,
        lsb_g=0.072,
        offset_tol_g=0.060,
    ),
    "lis302dl-logged16": replace(
        _LIS302DL,
        name="lis302dl-logged16",
        description="LIS302DL as seed 000 logged it: 100 Hz stored at 16 bits over +-2.3 g (0.07 mg steps)",
        lsb_g=4.6 / 2**16,
        bits=16,
    ),
    # e-obs GPS-acceleration tag (seed 003): 12-bit ADC 0..4095, zero-g about 2048 per axis,
    # a = (n - n0) * 0.0022 g for tags numbered > 2241 (section 6), so the range is about +-4.5 g;
    # no anti-alias filter (section 8); sampling frequency is per axis. The calibration spread of
    # the zero-g count (+-40 counts, i.e. +-88 mg) and the gain (+-5 %) is our assumption, to be
    # replaced by the six-orientation calibration of section 7. Bursts: 3.3 s of 3 axes at 10 Hz
    # every 60 s here; eobs_preset sets them from the ACC settings (sec. 9). Its noise stays white:
    # seed 003 gives no static spectrum (the 1 mg is our assumption).
    "eobs": AccelerometerPreset(
        name="eobs",
        description="e-obs tag accelerometer: 12-bit ADC (0.0022 g/count, zero-g 2048), no anti-alias filter",
        odr_hz=10.0,
        allowed_odr_hz=EOBS_PER_AXIS_RATES_HZ,
        range_g=2048 * 0.0022,
        lsb_g=0.0022,
        bits=12,
        zero_count=2048,
        noise_g=1.0e-3,
        bandwidth_hz=None,
        offset_tol_g=40 * 0.0022,
        sensitivity_tol=0.05,
        cross_axis_tol=0.01,
        burst_interval_s=60.0,
        burst_samples=33,
    ),
    "ideal": AccelerometerPreset(
        name="ideal",
        description="ideal float accelerometer: no noise, offsets, quantisation or filter; 100 Hz",
        odr_hz=100.0,
        allowed_odr_hz=(100.0, 400.0),
        range_g=1.0e6,
        lsb_g=None,
        bits=None,
        zero_count=0,
        noise_g=0.0,
        bandwidth_hz=None,
        offset_tol_g=0.0,
        sensitivity_tol=0.0,
        cross_axis_tol=0.0,
    ),
}


def get_preset(name: str) -> AccelerometerPreset:
    try:
        return PRESETS[name]
    except KeyError:
        raise SensorError(
            f"unknown sensor preset '{name}'{did_you_mean(name, PRESETS)}; presets: {', '.join(PRESETS)}"
        ) from None


def noise_autocovariance_g2(preset: AccelerometerPreset, n_lags: int) -> np.ndarray:
    """Autocovariance of the output noise per axis at lags 0..n_lags-1 output samples, in g^2:
    sigma^2 delta(m), modulated or not (module docstring)."""
    r = np.zeros(n_lags)
    r[0] = preset.noise_g**2
    return r


def noise_psd_g2_per_hz(preset: AccelerometerPreset, f_hz: np.ndarray) -> np.ndarray:
    """One-sided PSD of the output noise per axis (g^2/Hz) at ``f_hz`` in [0, ODR/2]: flat,
    2 noise_g^2 / ODR (module docstring); it integrates to noise_g^2 over [0, ODR/2]."""
    f = np.asarray(f_hz, float)
    return np.full(f.shape, 2.0 / preset.odr_hz * preset.noise_g**2)


def noise_am_cov_a2(depth: float, phi: float, n: int) -> np.ndarray:
    """cov(a_j^2, a_k^2) at lags 0..n-1 of the noise's amplitude a = (1 + depth g) / sqrt(1 + depth^2),
    g a unit stationary AR(1) of coefficient ``phi`` (module docstring): (4 d^2 rho + 2 d^4 rho^2) /
    (1 + d^2)^2, rho = phi^m (g_j, g_k jointly Gaussian: cov(g_j, g_k^2) = 0, cov(g_j^2, g_k^2) = 2 rho^2).
    The one copy of the amplitude's moments: the spread of a static variance below and the NMV's
    statistics (:mod:`flightmode.detector.statistics`) are built on it."""
    rho = phi ** np.arange(n, dtype=float)
    return (4.0 * depth**2 * rho + 2.0 * depth**4 * rho**2) / (1.0 + depth**2) ** 2


def noise_variance_spread_factor(preset: AccelerometerPreset) -> float:
    """F with var(sample variance of n output samples) = F sigma^4 / n for n much longer than the
    modulation's memory: the long-run variance of the squared noise over sigma^4, 3 E[a^4] - 1 +
    2 sum_m cov(a_k^2, a_k+m^2) = 2 + 3 c(0) + 2 sum_m>=1 c(m) (E[a^2] = 1, so E[a^4] = 1 + c(0);
    c = :func:`noise_am_cov_a2`, summed until phi^m < 1e-17). 2 for white Gaussian noise, 15.0 for the
    LIS302DL presets: a static variance is known to sqrt(15 / n), not sqrt(2 / n)."""
    d, phi = preset.noise_am_depth, preset.noise_am_phi
    if d == 0:
        return 2.0
    lags = 2 if phi <= 0.0 else 2 + math.ceil(math.log(1e-17) / math.log(phi))
    c = noise_am_cov_a2(d, phi, lags)
    return float(2.0 + 3.0 * c[0] + 2.0 * c[1:].sum())


def noise_random_walk_sigma_g(preset: AccelerometerPreset) -> float:
    """The white-noise sigma at the ODR with this noise's PSD at 0 Hz, sqrt(sum_m r(m)): what
    integrates into velocity and position random walks. The noise is white (modulated or not), so
    it is noise_g."""
    return float(preset.noise_g)


@dataclass(frozen=True, slots=True)
class UnitDraw:
    """One physical unit's deviations from nominal, drawn once per unit."""

    offset_g: np.ndarray = field(default_factory=lambda: np.zeros(3))
    sensitivity_err: np.ndarray = field(default_factory=lambda: np.zeros(3))
    cross_axis: np.ndarray = field(default_factory=lambda: np.zeros((3, 3)))

    @classmethod
    def from_dict(cls, d: dict | None) -> UnitDraw:
        """The inverse of :meth:`as_dict` (a Recording's ``unit``, or run.json's); None: a perfect unit."""
        if d is None:
            return cls()
        return cls(
            np.asarray(d["offset_g"], float),
            np.asarray(d["sensitivity_err"], float),
            np.asarray(d["cross_axis"], float),
        )

    def as_dict(self) -> dict:
        return {
            "offset_g": self.offset_g.tolist(),
            "sensitivity_err": self.sensitivity_err.tolist(),
            "cross_axis": self.cross_axis.tolist(),
        }


def draw_unit(preset: AccelerometerPreset, rng: np.random.Generator) -> UnitDraw:
    """Draw a unit within the preset's tolerances (uniform: datasheets give bounds, not spreads)."""
    off = rng.uniform(-preset.offset_tol_g, preset.offset_tol_g, 3)
    sens = rng.uniform(-preset.sensitivity_tol, preset.sensitivity_tol, 3)
    cross = rng.uniform(-preset.cross_axis_tol, preset.cross_axis_tol, (3, 3))
    np.fill_diagonal(cross, 0.0)
    return UnitDraw(off, sens, cross)


@dataclass(frozen=True, slots=True)
class Measurement:
    t_s: np.ndarray  # (M,) sample times
    counts: np.ndarray  # (M, 3) int32 raw output
    acc_g: np.ndarray  # (M, 3) counts converted to g with the unit's calibrated sensitivity
    clipped: np.ndarray  # (M, 3) bool: the sample sat at the range limit


class SensorChain:
    """The measurement chain with its state (filter memory, sampling phase), so that a long
    stream can be sensed chunk by chunk with the same result as in one piece."""

    def __init__(self, preset: AccelerometerPreset, unit: UnitDraw, fs_internal_hz: float):
        preset.validate()
        ratio = fs_internal_hz / preset.odr_hz
        k = int(round(ratio))
        if k < 1 or abs(ratio - k) > 1e-9:
            raise SensorError(
                f"internal rate {fs_internal_hz:g} Hz is not an integer multiple of the ODR {preset.odr_hz:g} Hz"
            )
        self.preset, self.unit, self.k, self.fs = preset, unit, k, fs_internal_hz
        self._mix = (np.eye(3) + unit.cross_axis).T
        self._sos = None
        if preset.bandwidth_hz is not None and preset.bandwidth_hz < fs_internal_hz / 2:
            from scipy.signal import butter

            self._sos = butter(2, preset.bandwidth_hz, fs=fs_internal_hz, output="sos")
        self._zi = None
        self._phase = 0  # index within the next chunk of the next internal sample to keep
        self._n_out = 0
        self._am_zi: np.ndarray | None = None  # lfilter state of the noise's modulation, (1, 3): phi g[last]

    def __call__(self, f_sensor_g: np.ndarray, t0_s: float, rng: np.random.Generator) -> Measurement:
        """Sense a chunk (N, 3); ``t0_s`` is the time of the first sample of the whole stream."""
        f = np.asarray(f_sensor_g, dtype=float)
        if f.ndim != 2 or f.shape[1] != 3:
            raise SensorError(f"specific force must be an (N, 3) array, got shape {f.shape}")
        return self.rows(np.ascontiguousarray(f.T), t0_s, rng)

    def rows(self, f_rows_g: np.ndarray, t0_s: float, rng: np.random.Generator) -> Measurement:
        """:meth:`__call__` for a chunk given as rows (3, N): sensor axes x, y, z, time along each
        row (the layout the filters want; no transposed copy)."""
        preset, unit = self.preset, self.unit
        a = np.asarray(f_rows_g, dtype=float)
        if a.ndim != 2 or a.shape[0] != 3:
            raise SensorError(f"specific force rows must be a (3, N) array, got shape {a.shape}")
        if (bad := first_nonfinite(a, axis=1)) is not None:
            raise SensorError(
                f"specific force has NaN or inf (first at sample {bad}): the flight or motion is broken"
            )
        n_in = a.shape[1]
        # the anti-alias filter is linear and per axis, the cross-axis mixing a constant matrix and the
        # offset a constant: they commute, so filter and decimate first and mix at the output rate
        if self._sos is not None:
            from scipy.signal import sosfilt, sosfilt_zi

            if self._zi is None:  # start in the steady state of the first sample (no power-on transient)
                self._zi = sosfilt_zi(self._sos)[:, None, :] * a[:, 0][None, :, None]
            a, self._zi = sosfilt(self._sos, a, axis=-1, zi=self._zi)
        a = a[:, self._phase :: self.k].T @ self._mix + unit.offset_g
        self._phase = (self._phase - n_in) % self.k
        t = t0_s + (self._n_out + np.arange(a.shape[0])) / preset.odr_hz
        self._n_out += a.shape[0]
        if preset.noise_g > 0:
            a = a + self._noise(a.shape[0], rng)
        if preset.lsb_g is None:
            clipped = np.abs(a) >= preset.range_g
            return Measurement(
                t, np.zeros(a.shape, np.int32), np.clip(a, -preset.range_g, preset.range_g), clipped
            )
        # the unit's own sensitivity (lsb * (1 + s), in g per count) maps g to counts; the count
        # saturates at the range and at the width of the word
        sens_g = preset.lsb_g * (1.0 + unit.sensitivity_err)
        lo, hi = preset.count_range
        raw = np.rint(a / sens_g[None, :]) + preset.zero_count
        lim_lo = max(lo, preset.zero_count - int(round(preset.range_g / preset.lsb_g)))
        lim_hi = min(hi, preset.zero_count + int(round(preset.range_g / preset.lsb_g)))
        clipped = (raw <= lim_lo) | (raw >= lim_hi)
        counts = np.clip(raw, lim_lo, lim_hi).astype(np.int32)
        return Measurement(t, counts, (counts - preset.zero_count) * sens_g[None, :], clipped)

    def _noise(self, m: int, rng: np.random.Generator) -> np.ndarray:
        """Output noise for the next ``m`` output samples (m, 3), continuing the stream exactly: the
        draws are taken in sample order (per sample: 3 white, then 3 modulation innovations), so
        any chunking consumes ``rng`` identically, and the AR(1) state is carried in ``_am_zi``."""
        p = self.preset
        if p.noise_am_depth == 0:
            return rng.normal(0.0, p.noise_g, (m, 3))
        from scipy.signal import lfilter

        d, phi = p.noise_am_depth, p.noise_am_phi
        if self._am_zi is None:  # g[-1] from the stationary N(0, 1): no start-up transient
            self._am_zi = phi * rng.standard_normal((1, 3))
        z = rng.standard_normal((m, 6))
        if m == 0:
            return np.zeros((0, 3))
        # g[k] = phi g[k-1] + sqrt(1 - phi^2) e[k]; n = sigma (1 + d g) / sqrt(1 + d^2) w  (module docstring)
        g, self._am_zi = lfilter([1.0], [1.0, -phi], np.sqrt(1.0 - phi**2) * z[:, 3:], axis=0, zi=self._am_zi)
        return (p.noise_g / np.sqrt(1.0 + d * d)) * (1.0 + d * g) * z[:, :3]


def measure(
    f_sensor_g: np.ndarray,
    fs_internal_hz: float,
    t0_s: float,
    preset: AccelerometerPreset,
    unit: UnitDraw,
    rng: np.random.Generator,
) -> Measurement:
    """Run the measurement chain (module docstring) on a whole (N, 3) specific force in g."""
    return SensorChain(preset, unit, fs_internal_hz)(f_sensor_g, t0_s, rng)


def eobs_burst(byte_count: int, n_axes: int, newer_firmware: bool = True) -> tuple[int, int, int]:
    """Samples per axis in one e-obs burst for an ``ACC BYTE COUNT`` setting (seed 003, section 9).

    Memory is used in 64-byte blocks of which 54, then 63 per further block, hold data; each sample
    takes 1.5 bytes; the data bytes top out at 747 (firmware up to rv4_s1) or 1188 (rv5 and later).
    Returns (samples per axis, data bytes, memory bytes used).

    The table is followed here, not section 10's text: section 10 says "the effective maximum of ACC
    BYTECOUNT is 756 for older devices ... and 1197 for newer devices", and its continuous-sampling
    example sets 1197, where section 9's table already reaches the largest burst (1188 bytes, 792
    samples) from a setting of 1135 on rv5 (and 747 bytes from 694 up to rv4_s1). 756 is the end of
    rv5's row 694-756 and 1197 = 1135 + 62 the end a 63-wide row from 1135 would have: neither is where
    the maximum starts. Any setting from 1135 (694) up gives the same burst, so the example's 1197 and
    its 792 samples still agree with the table.
    """
    if byte_count < 0 or n_axes not in (1, 2, 3):
        raise SensorError(f"e-obs burst: byte count must be >= 0 and axes 1-3 (got {byte_count}, {n_axes})")
    if byte_count == 0:
        return 0, 0, 0
    blocks = (byte_count - 1) // 63 + 1
    blocks = min(blocks, 19 if newer_firmware else 12)
    data = 54 + 63 * (blocks - 1)
    samples = int(data / 1.5)
    return samples // n_axes, data, 64 * blocks


def eobs_preset(
    acc_interval_s: float,
    byte_count: int,
    odr_per_axis_hz: float = 10.0,
    n_axes: int = 3,
    newer_firmware: bool = True,
) -> AccelerometerPreset:
    """The ``eobs`` preset with bursts set as on the tag: ACC INTERVAL and ACC BYTE COUNT."""
    per_axis, _, _ = eobs_burst(byte_count, n_axes, newer_firmware)
    p = replace(
        PRESETS["eobs"], odr_hz=odr_per_axis_hz, burst_interval_s=acc_interval_s, burst_samples=per_axis
    )
    p.validate()
    return p


def bench_static(
    preset: AccelerometerPreset, unit: UnitDraw, rng: np.random.Generator, duration_s: float = 60.0
) -> Measurement:
    """The unit lying flat and still on a bench for ``duration_s``: the static behaviour a tracker's
    noise calibration sees (seed 000 section 5.1: sigma^2 from static measurements). The specific
    force is 1 g along the sensor's -z axis (z down in our sensor frame), so two axes read about
    0 g and one about 1 g, through the unit's own offsets, gain, noise and quantisation."""
    if not duration_s > 0:
        raise SensorError(f"bench duration {duration_s} s: must be > 0")
    fs = preset.odr_hz * 4
    n = int(round(duration_s * fs))
    f = np.zeros((n, 3))
    f[:, 2] = -1.0
    return SensorChain(preset, unit, fs)(f, 0.0, rng)
