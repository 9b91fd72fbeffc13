"""Sensing a flight: labels, orientation, clipping, determinism, bad input (fast, on `pattern`), and
the in-flight spectra and aliasing of the default flight (slow)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from scipy.signal import get_window, welch
from scipy.stats import chi2

from flightmode.sim.sensor.accelerometer import SensorError, UnitDraw, get_preset
from flightmode.sim.sensor.carrier import CarrierSpec
from flightmode.sim.sensor.sensing import sense


@pytest.fixture(scope="module")
def pattern_rec(fly_cached):
    sc, tr = fly_cached("pattern")
    rec = sense(tr, CarrierSpec(), get_preset("lis302dl-logged16"), np.random.default_rng(1), unit=UnitDraw())
    return tr, rec


def test_in_flight_window_spans_pushback_to_engines_off_to_one_sample(pattern_rec):
    tr, rec = pattern_rec
    win = rec.t_s[rec.in_flight_window]
    dt = 1.0 / rec.odr_hz
    assert abs(win[0] - tr.event_time("pushback")) <= dt
    assert abs(win[-1] + dt - tr.event_time("engines_off")) <= dt
    assert np.all(np.diff(win) == pytest.approx(dt))


def test_sensor_static_only_while_resting_or_stowed_with_engines_stopped(pattern_rec):
    tr, rec = pattern_rec
    st = rec.sensor_static
    states = set(rec.bag_state[st])
    assert states <= {"resting", "stowed"}
    assert not np.any(st & rec.in_flight_window)  # nothing moves the bag... the aircraft does
    t_es, t_off = tr.event_time("engine_start"), tr.event_time("engines_off")
    stowed_static = st & (rec.bag_state == "stowed")
    assert np.all((rec.t_s[stowed_static] < t_es) | (rec.t_s[stowed_static] >= t_off))
    # truly static samples show only sensor noise: per segment, variance = (2.23 mg)^2 (seed 000
    # Table 1) to 5 standard errors of a sample variance of n samples of the modulated noise,
    # 5 sqrt(F / n) (noise_variance_spread_factor: F = 15 for the LIS302DL presets; 19 % at the
    # smallest segment checked, 10,000 samples, 6 % at 100,000); the 0.07 mg steps add lsb^2 / 12 =
    # 0.008 % of it (a put-down's ringing left after SETTLE_S = 2 s would show: 0.5 mg RMS adds 5 %)
    from flightmode.sim.sensor.accelerometer import noise_variance_spread_factor

    spread = noise_variance_spread_factor(get_preset("lis302dl-logged16"))  # pattern_rec's preset
    for seg in rec.segments:
        sel = st & (rec.t_s >= seg.t0_s) & (rec.t_s < seg.t1_s)
        n = int(sel.sum())
        if n > 10_000:
            np.testing.assert_allclose(rec.acc_g[sel].var(axis=0), 2.23e-3**2, rtol=5 * np.sqrt(spread / n))
    # walking and the flight itself are never static
    assert not st[rec.bag_state == "carried"].any()
    assert not st[rec.airborne].any()
    # every rest off board is static from SETTLE_S = 2 s after the put-down (sim.sensor.sensing) to
    # its end: on this continuous 100 Hz stream the static fraction of a rest of duration D is
    # (D - 2 s) / D to one sample (0.998 for the 900 s arrival rest)
    for seg in rec.segments:
        if seg.state == "resting":
            sel = (rec.t_s >= seg.t0_s) & (rec.t_s < seg.t1_s)
            d = seg.t1_s - seg.t0_s
            assert st[sel].mean() == pytest.approx((d - 2.0) / d, abs=1.0 / sel.sum()), seg.phase


def test_resting_orientation_norm_and_direction(pattern_rec):
    _, rec = pattern_rec
    means = []
    for seg in rec.segments:
        if seg.state not in ("resting", "stowed"):
            continue
        sel = rec.sensor_static & (rec.t_s >= seg.t0_s) & (rec.t_s < seg.t1_s)
        if sel.sum() < 1000:
            continue
        m = rec.acc_g[sel].mean(axis=0)
        # a perfect unit at rest reads exactly 1 g in norm, whatever its tilt: off board the
        # specific force is -g, on board JSBSim's load factor is F / W = 1 at rest (local gravity
        # cancels in F / W). Tolerance: 5 standard errors of a mean of n samples of 2.23 mg noise
        # (<= 0.35 mg at n >= 1000) plus one 0.07 mg step (quantisation is dithered by the noise)
        tol = 5 * 2.23e-3 / np.sqrt(sel.sum()) + get_preset("lis302dl-logged16").lsb_g
        assert np.linalg.norm(m) == pytest.approx(1.0, abs=tol)
        if not seg.on_board:
            # specific force of a resting body is "up": in sensor axes, minus the frame's down axis
            np.testing.assert_allclose(m, -seg.orientation[2, :], atol=tol)
        means.append((m, seg.on_board))

    def angle_deg(a, b):
        return np.degrees(np.arccos(np.clip(a @ b / np.linalg.norm(a) / np.linalg.norm(b), -1, 1)))

    # off board the orientation is drawn uniformly at every put-down, so it changes (two uniform
    # directions lie within 5 deg with probability (1 - cos 5 deg) / 2 = 0.2 %); on board a handbag
    # rests level (sim.sensor.carrier, "Orientation"): gravity within its Rayleigh tilt (scale 3 deg
    # under a seat) of the sensor's z axis; 15 deg is five scales (probability exp(-12.5) = 4e-6)
    for (a, a_on), (b, b_on) in zip(means, means[1:]):
        if not (a_on and b_on):
            assert angle_deg(a, b) > 5.0
    on_board = [m for m, on in means if on]
    assert on_board
    for m in on_board:
        assert angle_deg(m, np.array([0.0, 0.0, 1.0])) < 15.0


def test_drawn_offsets_move_the_resting_norm_by_at_most_their_size(fly_cached):
    _, tr = fly_cached("pattern")
    rec = sense(tr, CarrierSpec(), get_preset("lis302dl-logged16"), np.random.default_rng(3))
    off = np.asarray(rec.unit["offset_g"])
    cross = np.asarray(rec.unit["cross_axis"])
    seg = next(s for s in rec.segments if s.phase == "arrival_rest")
    sel = rec.sensor_static & (rec.t_s >= seg.t0_s)
    m = rec.acc_g[sel].mean(axis=0)
    # exactly what this unit must read: (I + C) times the 1 g "up" in sensor axes, plus its offset
    # (acc_g uses the unit's own sensitivity, so the gain error cancels). Tolerance: 5 standard
    # errors of the mean of ~88,000 samples of 2.23 mg noise (38 ug) plus one 0.07 mg step.
    tol = 5 * 2.23e-3 / np.sqrt(sel.sum()) + get_preset("lis302dl-logged16").lsb_g
    np.testing.assert_allclose(m, (np.eye(3) + cross) @ -seg.orientation[2, :] + off, atol=tol)
    # triangle inequality: |(I + C) g + o| differs from |g| = 1 g by at most ||C||_2 + |o| (this
    # unit's spectral norm; cross-axis <= 2 % per term). Over the preset's tolerances (offsets
    # +-40 mg per axis) only about half of all units rest within 2 % of 1 g; the worst are 7 % off.
    assert abs(np.linalg.norm(m) - 1.0) <= np.linalg.norm(off) + np.linalg.norm(cross, 2) + tol


def test_dropped_bag_saturates_at_the_range_and_never_beyond(fly_cached):
    _, tr = fly_cached("pattern")
    p = get_preset("lis302dl")
    rec = sense(tr, dataclasses.replace(CarrierSpec(), putdown_peak_g=6.0), p, np.random.default_rng(2))
    assert rec.clipped.any()
    assert rec.counts.max() <= 127 and rec.counts.min() >= -128
    # LIS302DL: 8-bit two's complement at 18 mg/digit, read back with this unit's own sensitivity
    # 18 mg (1 + s): the output spans exactly [-128, 127] x 18 mg (1 + s) per axis (round-off 1e-12)
    step = 0.018 * (1.0 + np.asarray(rec.unit["sensitivity_err"]))
    assert np.all(rec.acc_g >= -128 * step - 1e-12) and np.all(rec.acc_g <= 127 * step + 1e-12)
    low = rec.counts == -128
    assert low.any()
    np.testing.assert_allclose(rec.acc_g[low], np.broadcast_to(-128 * step, rec.acc_g.shape)[low], rtol=1e-12)
    # the clipped samples are the put-down shocks (first 0.2 s of a segment after a carry)
    starts = np.array([s.t0_s for s in rec.segments])
    t_clip = rec.t_s[rec.clipped.any(axis=1)]
    assert np.all(np.min(np.abs(t_clip[:, None] - starts[None, :]), axis=1) < 0.25)


def test_pick_up_lifts_the_bag_and_leaves_no_net_velocity(fly_cached):
    """Every carry that starts from a rest begins with the lift (sim.carrier.pickup_pulse_mps2): on a
    perfect sensor with the gait switched off, |a| - 1 g is the lift alone."""
    from flightmode.sim.sensor.accelerometer import UnitDraw
    from flightmode.sim.sensor.carrier import pickup_pulse_mps2

    _, tr = fly_cached("pattern")
    spec = dataclasses.replace(CarrierSpec(), gait_vertical_g=0.0, gait_lateral_g=0.0, gait_fore_aft_g=0.0)
    rec = sense(tr, spec, get_preset("ideal"), np.random.default_rng(0), unit=UnitDraw())
    from flightmode.sim.sensor.sensing import FS_INTERNAL_HZ

    peak_g = float(pickup_pulse_mps2(1 / FS_INTERNAL_HZ, spec).max()) / 9.80665
    assert peak_g == pytest.approx(
        5.77 * spec.pickup_height_m / spec.pickup_s**2 / 9.80665, rel=0.01
    )  # min-jerk peak
    a = np.linalg.norm(rec.acc_g, axis=1) - 1.0
    lifts = 0
    for k, seg in enumerate(rec.segments):
        if k == 0 or seg.on_board or seg.state != "carried" or rec.segments[k - 1].state != "resting":
            continue
        sel = (rec.t_s >= seg.t0_s) & (rec.t_s < seg.t0_s + spec.pickup_s + 0.2)
        x = a[sel]
        # 100 Hz samples of a smooth 0.8 s pulse: the sampled extremes lie within 1 % of the peak
        assert x.max() == pytest.approx(peak_g, rel=0.01) and x.min() == pytest.approx(-peak_g, rel=0.01)
        assert x[0] >= 0 and x.argmax() < x.argmin()  # up first (no jolt: starts from ~0), then slowing
        # net velocity change: the impulses cancel (sum * dt, to well under 1 mm/s)
        assert abs(x.sum() * 9.80665 / rec.odr_hz) < 1e-3
        lifts += 1
    assert lifts >= 2  # the walk to the gate and the boarding walk (deplaning starts from the seat)


def test_same_seed_same_recording_other_seed_other_noise_and_unit(fly_cached):
    _, tr = fly_cached("pattern")
    p = get_preset("lis302dl-logged16")
    a = sense(tr, CarrierSpec(), p, np.random.default_rng(10))
    b = sense(tr, CarrierSpec(), p, np.random.default_rng(10))
    c = sense(tr, CarrierSpec(), p, np.random.default_rng(11))
    assert a.digest() == b.digest()
    assert a.digest() != c.digest()
    assert a.unit["offset_g"] != c.unit["offset_g"]


def test_bad_tracks_are_named(fly_cached):
    _, tr = fly_cached("pattern")
    t = tr.t_s.copy()
    t[100] = t[99]
    with pytest.raises(SensorError, match="not strictly increasing at sample 99"):
        sense(dataclasses.replace(tr, t_s=t), CarrierSpec(), get_preset("ideal"), np.random.default_rng(0))
    f = tr.specific_force_body_mps2.copy()
    f[5, 2] = np.nan
    with pytest.raises(SensorError, match="specific_force_body_mps2 has NaN"):
        sense(
            dataclasses.replace(tr, specific_force_body_mps2=f),
            CarrierSpec(),
            get_preset("ideal"),
            np.random.default_rng(0),
        )
    from flightmode.sim.sensor.carrier import CarrierError

    with pytest.raises(CarrierError, match="placement 'under_sea'.*did you mean \"under_seat\""):
        sense(tr, CarrierSpec(placement="under_sea"), get_preset("ideal"), np.random.default_rng(0))


ENGINE_PHASES = ("taxi_out", "takeoff_roll", "climb", "cruise", "descent", "rollout", "taxi_in")


@pytest.fixture(scope="module")
def default_rec(fly_cached):
    sc, tr = fly_cached("gva-lhr-a320")
    return tr, sense(tr, CarrierSpec(), get_preset("lis302dl-logged16"), np.random.default_rng(sc.seed))


def _psd(x, fs):
    return welch(x - x.mean(), fs=fs, nperseg=512)


@pytest.mark.slow
def test_in_flight_spectra_peak_between_10_and_30_hz(default_rec):
    """Seed 000 Fig. 6: peaks between 10 and 30 Hz in every flight stage, far above the static floor.

    The largest value of the spectrum above 2 Hz (resolution 0.2 Hz) is taken, outside turbulence
    segments. That air is not still: its background turbulence (EDR < 0.1, Sharman & Pearson 2017)
    moves the airframe as a rigid body below 2 Hz (the short-period and gust response), where the
    largest peak of a climb may sit; the whole spectrum's largest bin is therefore asserted to be
    either there or in the vibration band, never between. In the default scenario's light-turbulence segment (end of cruise, start of descent) the
    largest peak is the turbulence itself, below 1 Hz: asserted separately, with the vibration peak
    still standing 10 dB above the floor."""
    tr, rec = default_rec
    a = np.linalg.norm(rec.acc_g, axis=1)
    f, floor_psd = _psd(a[rec.sensor_static][:100_000], rec.odr_hz)
    floor = float(np.median(floor_psd[1:]))
    # the static floor is the sensor's noise of (2.23 mg)^2 (seed 000 Table 1; the norm's noise is
    # that of the axis along gravity), white (its amplitude modulated: the spectrum stays flat): the
    # median of the model's one-sided PSD over the same bins. The median of 256 bins, each chi2 with
    # ~740 dof (5.2 % spread), is good to 1.25 x 5.2 % / sqrt(128) ~ 0.6 % (adjacent Hann bins
    # correlated: half as many independent), biased by -2/(3 nu) = -0.1 %: 3 % is more than 3 errors
    import dataclasses

    from flightmode.sim.sensor.accelerometer import get_preset, noise_psd_g2_per_hz

    pr = dataclasses.replace(get_preset(rec.preset), odr_hz=rec.odr_hz)
    assert floor == pytest.approx(float(np.median(noise_psd_g2_per_hz(pr, f[1:]))), rel=0.03)
    db = lambda p: round(float(10 * np.log10(p / floor)), 1)  # noqa: E731
    report = {}
    calm = rec.turbulence_severity == "none"
    for ph in ENGINE_PHASES:
        sel = (rec.phase == ph) & (rec.bag_state == "stowed") & calm
        f, p = _psd(a[sel], rec.odr_hz)
        k_all = 1 + int(np.argmax(p[1:]))
        assert f[k_all] < 2.0 or 10.0 <= f[k_all] <= 30.0, (ph, f[k_all])
        above = np.flatnonzero(f >= 2.0)
        k = above[int(np.argmax(p[above]))]
        report[ph] = (round(float(f[k]), 1), db(p[k]))
        assert 10.0 <= f[k] <= 30.0, (ph, f[k])
        assert p[k] >= 10 * floor, (ph, db(p[k]))
    # light turbulence: the gusts' own low-frequency peak dominates; the vibration peak remains
    turb = (rec.bag_state == "stowed") & (rec.turbulence_severity == "light")
    f, p = _psd(a[turb], rec.odr_hz)
    k = 1 + int(np.argmax(p[1:]))
    band = (f >= 10) & (f <= 30)
    assert f[k] < 2.0
    assert p[band].max() >= 10 * floor
    report["light turbulence"] = (round(float(f[k]), 1), db(p[k]), "10-30 Hz:", db(p[band].max()))
    # engines off and the bag resting: no such peak (every 10-30 Hz bin within 3 dB of the floor)
    rest = rec.phase == "arrival_rest"
    f, p = _psd(a[rest], rec.odr_hz)
    band = (f >= 10) & (f <= 30)
    model = noise_psd_g2_per_hz(pr, f[band])
    assert p[band].max() < 2.0 * model.max()  # 3 dB over the noise at its highest in the band
    # and noise alone may not even reach that: a Welch bin of noise is S(f) chi2_nu / nu with
    # nu = 2 K / (1 + 2 c^2) (Welch 1967; K segments of 512, 50 % overlap, Hann: c = overlap
    # correlation = 1/6), nu ~ 660 for the 900 s rest; the largest ratio to the model over M ~ 100
    # bins exceeds chi2.isf(1e-6 / M, nu) / nu (~1.34: union bound, probability < 1e-6) essentially
    # never. So the bound is a noise-only fact and any residual vibration line above ~1.34 times
    # the noise fails it.
    k_seg = (int(rest.sum()) - 512) // 256 + 1
    w = get_window("hann", 512)
    c2 = float(np.sum(w[:256] * w[256:]) ** 2 / np.sum(w**2) ** 2)  # 1/36
    nu = 2 * k_seg / (1 + 2 * c2)
    bound = float(chi2.isf(1e-6 / band.sum(), nu) / nu)
    assert bound < 2.0
    assert np.max(p[band] / model) < bound, (np.max(p[band] / model), bound)
    report["arrival_rest 10-30 Hz max"] = db(p[band].max())
    print(f"\nlargest spectral peak (Hz, dB over the static floor): {report}")


CFM56_5B_N1_RPM = 5000.0  # N1 at 100 %: EASA type-certificate data sheet E.067 (CFM56-5B)
LINE_BAND_HZ = 1.5  # half-width of the band a line's power is summed over (the alias test's comment)


def _folded_hz(f_hz: float, fs_hz: float) -> float:
    """Sampling theorem: a tone at f sampled at fs appears at |f - k fs| for the integer k that
    brings it into [0, fs/2]."""
    return abs(f_hz - fs_hz * round(f_hz / fs_hz))


@pytest.mark.slow
def test_100_hz_odr_aliases_the_fan_line_400_hz_records_it(fly_cached):
    """Seed 000 section 4.2 says 60-70 Hz sampling keeps all vibration; the fan (N1) line at cruise
    is above 50 Hz: at 100 Hz ODR it folds, at 400 Hz it is kept. The expected frequencies come
    from the flight's N1 and the engine's published 100 % speed, folded by the sampling theorem."""
    sc, tr = fly_cached("gva-lhr-a320")
    # the steadiest 5 minutes of cruise (the autothrottle moves N1, which smears the line)
    idx = np.flatnonzero(tr.phase == "cruise")
    w = int(300 * tr.fs_hz)
    starts = idx[: len(idx) - w : w]
    i0 = min(starts, key=lambda i: tr.n1_pct[i : i + w, 0].std())
    t0, t1 = tr.t_s[i0], tr.t_s[i0 + w]
    n1 = tr.n1_pct[i0 : i0 + w]
    assert np.all(np.abs(n1 - n1[:, :1]) < 1e-9)  # the FDM runs both engines at one N1
    f_n1 = float(n1[:, 0].mean()) / 100.0 * CFM56_5B_N1_RPM / 60.0  # shaft rotation rate, Hz
    # a parcel in the hold (stiff mount) and a noiseless part; the line is isolated exactly as the
    # difference between two recordings with the same random streams, with and without engine lines
    from flightmode.sim.sensor.vibration import VibrationModel

    spec = CarrierSpec(kind="parcel", placement="hold")
    # both floor models given explicitly (no per-flight draw of the floor), the same in all but the
    # fan's fundamental; the mount is drawn from the same streams in both. The N1 harmonic and the
    # N2 line stay in both and cancel: at 100 Hz ODR they fold too (N1 x 2 to 2 f - 100, N2 near
    # 230 Hz to about 30 Hz), and the difference is the fan's line alone wherever they fold
    with_lines = VibrationModel()
    no_lines = VibrationModel(n1_line_g=0.0)
    res = {}
    for odr in (100.0, 400.0):
        p = dataclasses.replace(
            get_preset("lis302dl-logged16"), odr_hz=odr, bandwidth_hz=odr / 2, noise_g=0.0
        )
        p = dataclasses.replace(p, lsb_g=None, bits=None)  # no quantisation either: a linear chain
        a = sense(tr, spec, p, np.random.default_rng(5), unit=UnitDraw(), vibration=with_lines)
        b = sense(tr, spec, p, np.random.default_rng(5), unit=UnitDraw(), vibration=no_lines)
        sel = (a.t_s >= t0) & (a.t_s < t1)
        d = a.acc_g[sel, 2] - b.acc_g[sel, 2]
        fr, pxx = welch(d, fs=odr, nperseg=int(4 * odr))
        k = int(np.argmax(pxx[fr > 5.0])) + int(np.argmax(fr > 5.0))
        band = np.abs(fr - _folded_hz(f_n1, odr)) <= LINE_BAND_HZ
        res[odr] = (float(fr[k]), float(np.sqrt(2 * pxx[band].sum() * (fr[1] - fr[0]))), fr[1] - fr[0])
    print(
        f"\ncruise N1 line at {f_n1:.2f} Hz: 100 Hz ODR records a tone at {res[100.0][0]:.2f} Hz "
        f"({1000 * res[100.0][1]:.3f} mg), 400 Hz ODR at {res[400.0][0]:.2f} Hz ({1000 * res[400.0][1]:.3f} mg)"
    )
    assert 50.0 < f_n1 < 200.0  # above the 100 Hz part's Nyquist, below the 400 Hz part's
    # Frequency tolerance: half a Welch bin (0.125 Hz: the peak bin of a tone) + the spread of the
    # two engines' lines (each shaft runs within +-0.3 % of the FDM's N1, the model's stated
    # detune: 0.2 Hz at 67 Hz) + the N1 wander over the 5 minutes (std 0.06 % N1 = 0.05 Hz here):
    # 0.38 Hz, against 1.4 Hz for a 2 % error in the 100 % speed.
    for odr, (f_peak, _, df) in res.items():
        tol = df / 2 + 0.003 * f_n1 + float(n1[:, 0].std()) / 100.0 * CFM56_5B_N1_RPM / 60.0
        assert f_peak == pytest.approx(_folded_hz(f_n1, odr), abs=tol), (odr, f_peak, tol)
    assert _folded_hz(f_n1, 100.0) == pytest.approx(100.0 - f_n1)  # folded about 50 Hz
    assert _folded_hz(f_n1, 400.0) == f_n1  # kept where it is
    # Amplitude: the chain is linear and the two recordings share every random stream, so the
    # ratio of the two tones is the ratio of the anti-alias filters' gains at the line (2nd-order
    # Butterworth at ODR / 2 = the datasheet bandwidth, run at the internal rate): 0.46-0.49.
    # The line's power is summed over +-LINE_BAND_HZ about its expected (folded) frequency: the
    # band holds the two engines' lines (+-0.2 Hz), the N1 wander and a Hann window's leakage
    # (+-2 bins, 0.5 Hz) whatever the flight's N1 does; a +-2-bin sum about each spectrum's own
    # peak did not (the peaks of a smeared line need not mirror: 0.476 against 0.456 on a flight
    # whose N1 wandered). What remains is the two engines' lines sitting +-0.2 Hz apart on the
    # 50 Hz filter's slope (|H| falls 2.3 %/Hz at 67 Hz): +-0.5 %. 2 % is four times that (a
    # 1st-order filter would give 0.62, a 45 Hz cut-off 0.41).
    from scipy.signal import butter, sosfreqz

    from flightmode.sim.sensor.sensing import FS_INTERNAL_HZ as FS

    h100 = abs(sosfreqz(butter(2, 50.0, fs=FS, output="sos"), worN=[f_n1], fs=FS)[1][0])
    h400 = abs(sosfreqz(butter(2, 200.0, fs=FS, output="sos"), worN=[f_n1], fs=FS)[1][0])
    assert res[100.0][1] / res[400.0][1] == pytest.approx(h100 / h400, rel=0.02)


def test_eobs_bursts_and_a_parcel_in_the_hold(fly_cached):
    _, tr = fly_cached("pattern")
    p = get_preset("eobs")
    rec = sense(tr, CarrierSpec(kind="parcel", placement="hold"), p, np.random.default_rng(4))
    # bursts of 33 samples at 10 Hz, one every 60 s: 33 samples then a 56.7 s gap
    gaps = np.diff(rec.t_s)
    assert np.isclose(gaps, 0.1).sum() > 0 and gaps.max() == pytest.approx(60.0 - 3.2, abs=1e-6)
    assert np.all((rec.counts >= 0) & (rec.counts <= 4095))
    assert {"truck", "loading", "unloading", "arrival_rest"} <= set(rec.phase)
    assert "in_hold" in set(rec.bag_state) and "stowed" not in set(rec.bag_state)
    # the van is not static, the arrival rest is from SETTLE_S = 2 s after its start (the settling
    # time of sim.sensor.sensing) to its end: the static samples are exactly those 2 s or more into
    # the segment, and with a burst every 60 s a 900 s segment holds exactly 15 bursts of 33
    assert not rec.sensor_static[rec.phase == "truck"].any()
    seg = next(s for s in rec.segments if s.phase == "arrival_rest")
    rest = rec.phase == "arrival_rest"
    assert seg.t1_s - seg.t0_s == pytest.approx(900.0)
    assert rest.sum() == 900 // 60 * 33
    np.testing.assert_array_equal(rec.sensor_static[rest], rec.t_s[rest] - seg.t0_s >= 2.0)


@pytest.mark.slow
def test_the_recording_records_how_the_bag_lay_in_flight(fly_cached):
    from flightmode.sim.sensor.carrier import orientation_angles
    from flightmode.studies.validate import comparable_x_from_fuselage_deg, placement_text

    _, tr = fly_cached("gva-lhr-a320")
    spec = CarrierSpec(placement="under_seat", cruise_placement="seat", cabin_row="rear", handled_in_cruise=2)
    rec = sense(tr, spec, get_preset("lis302dl-logged16"), np.random.default_rng(5))
    st = rec.stowage
    assert set(st["mounts"]) == {"under_seat", "seat"} and st["floor"]["location_level"] > 0
    # every stowed segment of the in-flight window (pushback to engines off) with its own orientation
    # (each handling sets the bag down anew) and its share of the window; the shares add up to the
    # time the bag lay stowed there (the rest: the handlings, in hand)
    ev = {e.name: e.t_s for e in tr.events}
    t0, t1 = ev["pushback"], ev["engines_off"]
    stowed = [
        s for s in rec.segments if s.on_board and s.state == "stowed" and min(s.t1_s, t1) > max(s.t0_s, t0)
    ]
    parts = st["in_flight_segments"]
    assert len(parts) == len(stowed) >= 4  # under the seat, on the seat (moved twice), under the seat again
    for p, s in zip(parts, stowed):
        angles = {k: p[k] for k in ("yaw_deg", "tilt_deg", "x_from_fuselage_deg")}
        assert angles == orientation_angles(s.orientation)
        assert p["placement"] == s.placement
        assert p["share"] == pytest.approx((min(s.t1_s, t1) - max(s.t0_s, t0)) / (t1 - t0), rel=1e-12)
    handled = sum(
        min(s.t1_s, t1) - max(s.t0_s, t0)
        for s in rec.segments
        if s.on_board and s.state == "handled" and min(s.t1_s, t1) > max(s.t0_s, t0)
    )
    assert sum(p["share"] for p in parts) == pytest.approx(1.0 - handled / (t1 - t0), abs=1e-9)
    # the in-flight record is the segment covering most, with its mount's row and packing
    best = max(parts, key=lambda p: p["share"])
    f = st["in_flight"]
    assert {k: f[k] for k in best if k != "share"} == {k: v for k, v in best.items() if k != "share"}
    assert (f["cabin_row"], f["packing"]) == ("rear", "soft")
    assert rec.summary()["stowage"] == st
    # validate judges seed 000's tables by the share of that time with x within 26.6 deg of the fuselage
    # (validate.comparable_x_from_fuselage_deg)
    limit = comparable_x_from_fuselage_deg()
    stowed = sum(p["share"] for p in parts)
    near = sum(p["share"] for p in parts if p["x_from_fuselage_deg"] <= limit) / stowed
    assert placement_text(st)[1] == (near >= 0.9)
    # with every segment at yaw 0 they are comparable whatever their shares; at yaw 90, never
    for yaw, comparable in ((0.0, True), (90.0, False)):
        fixed = sense(
            tr,
            dataclasses.replace(spec, stowed_yaw_deg=yaw),
            get_preset("lis302dl-logged16"),
            np.random.default_rng(5),
        )
        assert placement_text(fixed.stowage)[1] is comparable
    # a parcel in the hold: no cabin row
    rec = sense(
        tr,
        CarrierSpec(kind="parcel", placement="hold"),
        get_preset("lis302dl-logged16"),
        np.random.default_rng(5),
    )
    assert rec.stowage["in_flight"]["placement"] == "hold" and rec.stowage["in_flight"]["cabin_row"] == "hold"


def test_cli_sense_writes_a_new_run_folder(tmp_path, pattern_run):
    import pyarrow.parquet as pq
    from typer.testing import CliRunner

    from flightmode.cli.main import app

    run, _ = pattern_run
    r = CliRunner().invoke(
        app,
        [
            "sense",
            str(run),
            "--sensor",
            "lis302dl",
            "--carrier",
            "placement=overhead_bin",
            "--out",
            str(tmp_path),
        ],
    )
    assert r.exit_code == 0, r.output
    new = tmp_path / "pattern-s1-lis302dl-placement-overhead_bin"
    t = pq.read_table(new / "samples.parquet")
    assert {"raw_x", "acc_z_g", "phase", "sensor_static", "bag_state", "in_flight_window"} <= set(
        t.column_names
    )
    # the native part's 8-bit two's complement counts (datasheet: -128..127)
    assert -128 <= t["raw_z"].to_numpy().min() and t["raw_z"].to_numpy().max() <= 127
    r = CliRunner().invoke(app, ["sense", str(run), "--carrier", "placment=hold", "--out", str(tmp_path)])
    assert r.exit_code == 2 and 'did you mean "placement"' in r.output
    # re-sensing with the run's own sensor and carrier gives its samples.parquet again: labels and
    # times exactly; the counts to one step (0.07 mg), because `sense` reads the truth back from
    # truth.parquet, which stores forces and rates in float32 (relative rounding 6e-8 of a 1 g
    # signal is 0.06 ug, so a count moves only when the value sits within that of a rounding
    # boundary: a fraction of a percent of the samples, here measured 0.1 %)
    r = CliRunner().invoke(app, ["sense", str(run), "--out", str(tmp_path)])
    assert r.exit_code == 0, r.output
    again = pq.read_table(tmp_path / "pattern-s1-lis302dl-logged16" / "samples.parquet")
    orig = pq.read_table(run / "samples.parquet")
    for c in ("t_s", "phase", "in_flight_window", "sensor_static", "bag_state", "turbulence_severity"):
        assert again[c].equals(orig[c]), c
    for ax in "xyz":
        d = np.abs(again[f"raw_{ax}"].to_numpy() - orig[f"raw_{ax}"].to_numpy())
        assert d.max() <= 1 and (d > 0).mean() < 0.01


def test_optional_gyroscope_sees_the_aircraft_turn_in_sensor_axes(fly_cached):
    from flightmode.sim.sensor.gyroscope import GyroSpec

    _, tr = fly_cached("pattern")
    spec = GyroSpec(noise_dps=0.0, bias_tol_dps=0.0)
    rec = sense(
        tr, CarrierSpec(handled_in_cruise=0), get_preset("ideal"), np.random.default_rng(6), gyro=spec
    )
    assert rec.gyro_dps is not None and rec.gyro_dps.shape == rec.acc_g.shape
    # stowed: the gyro reads the body rates rotated into the bag's axes (|w| is frame-invariant)
    st = rec.bag_state == "stowed"
    w = np.stack([np.interp(rec.t_s[st], tr.t_s, tr.rates_radps[:, j]) for j in range(3)], axis=1)
    body = np.degrees(np.linalg.norm(w, axis=1))
    np.testing.assert_allclose(np.linalg.norm(rec.gyro_dps[st], axis=1), body, atol=1e-9)
    assert body.max() > 2.0  # the circuit's turns (about 3 deg/s) are really there
    # resting in the terminal: nothing but (here zero) noise and bias
    assert np.abs(rec.gyro_dps[rec.phase == "terminal_rest"]).max() < 1e-9
    # and the default recording has no gyro channel
    assert sense(tr, CarrierSpec(), get_preset("ideal"), np.random.default_rng(6)).gyro_dps is None
