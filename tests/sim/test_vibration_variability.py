"""What varies from flight to flight between the airframe and the sensor (sim.sensor.vibration's floor
draws, sim.sensor.mount's supports and packings, sim.sensor.carrier's stowage and orientation): the
draws follow the distributions their modules document, the documented orderings hold (cabin rows,
engine position, supports, packings, axes), and the two built-in flights that stand for seed 000's
flights 1 and 2 reproduce the paper's Tables 4 and 5 to within a decade per cell (slow).

Statistical tolerances: every distribution is checked by a Kolmogorov-Smirnov or chi-square test on
a few thousand draws of a fixed seed, failing below p = 1e-3: a correct implementation fails such a
test on one seed in a thousand, a wrong range or law (a shifted bound, a normal for a lognormal) by
orders of magnitude less than that p.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from flightmode.errors import CarrierError
from flightmode.sim.sensor import mount as mnt
from flightmode.sim.sensor import vibration as vib
from flightmode.sim.sensor.carrier import CarrierSpec, build_timeline, orientation_angles, stowed_rot

N = 4000
P_MIN = 1e-3  # module docstring


def _rng(seed: int = 7) -> np.random.Generator:
    return np.random.default_rng(seed)


# ---------------------------------------------------------------------- the floor (sim.sensor.vibration)
def test_floor_draws_follow_their_distributions():
    rng = _rng()
    draws = [vib.draw_floor("A320", "mid", rng) for _ in range(N)]
    ln_flight = np.log([d.flight_level for d in draws])
    # flight-to-flight factor: lognormal of ln-spread FLIGHT_LN_SIGMA, median 1
    assert stats.kstest(ln_flight, "norm", args=(0.0, vib.FLIGHT_LN_SIGMA)).pvalue > P_MIN
    # mode frequencies: one uniform scale within +-MODE_JITTER
    scale = np.array([d.mode_scale for d in draws])
    lo = 1.0 - vib.MODE_JITTER
    assert stats.kstest(scale, "uniform", args=(lo, 2 * vib.MODE_JITTER)).pvalue > P_MIN
    # the model is the base's with every amplitude scaled by type x location x flight (exactly) and
    # every mode frequency by the drawn scale
    base = vib.VibrationModel()
    d = draws[0]
    k = d.type_level * d.location_level * d.flight_level
    for name in (
        "n1_line_g",
        "n1_h2_g",
        "n2_line_g",
        "mode_engine_g",
        "mode_airflow_g",
        "roughness_g_per_mps",
        "joint_impulse_g",
    ):
        assert getattr(d.model, name) == pytest.approx(getattr(base, name) * k, rel=1e-12)
    np.testing.assert_allclose(d.model.mode_hz, np.array(base.mode_hz) * d.mode_scale, rtol=1e-6)
    # the axis weights and the modes' sharpness are not drawn
    assert d.model.axis_share == base.axis_share and d.model.mode_q == base.mode_q


def test_floor_levels_by_type_and_location_are_the_documented_ones():
    for aircraft, position in vib.ENGINE_POSITION.items():
        for location, level in vib.LOCATION_LEVEL[position].items():
            d = vib.draw_floor(aircraft, location, _rng(1))
            assert d.type_level == vib.TYPE_LEVEL[aircraft] and d.location_level == level
    # the same draws whatever the type or the row: changing either scales, it never reshuffles
    a = vib.draw_floor("A320", "front", _rng(3))
    b = vib.draw_floor("fokker100", "rear", _rng(3))
    assert (a.flight_level, a.mode_scale) == (b.flight_level, b.mode_scale)
    with pytest.raises(Exception, match="no vibration data for aircraft 'A321'.*A320"):
        vib.draw_floor("A321", "mid", _rng())


def test_orderings_of_rows_engine_position_and_axes():
    # Li et al. (2022), in-flight ISO 2631 comfort by seat position: the middle rows quietest, the
    # front next, the rear worst (taken for wing-mounted engines); with engines on the rear fuselage
    # the level grows towards them (assumption); the hold above the cabin's middle (no trim, seats or
    # carpet between the bag and the skin)
    wing, rear = vib.LOCATION_LEVEL["wing"], vib.LOCATION_LEVEL["rear"]
    assert wing["mid"] < wing["front"] < wing["rear"]
    assert rear["front"] < rear["mid"] < rear["rear"]
    for lv in (wing, rear):
        assert lv["hold"] > lv["mid"]
    # engines on the rear fuselage make the rear rows worse than wing-mounted ones do
    assert vib.LOCATION_LEVEL["rear"]["rear"] > vib.LOCATION_LEVEL["wing"]["rear"]
    # fore-aft lowest (the fuselage is stiffest along its axis), vertical highest
    x, y, z = vib.VibrationModel().axis_share
    assert x < y < z


def test_engine_excitation_grows_with_spool_speed_and_is_felt_at_idle():
    model = vib.VibrationModel()
    n1 = np.array([[0.0, 10.0, 30.0, 80.0, 100.0]])
    n2 = np.array([[0.0, 40.0, 60.0, 90.0, 100.0]])
    level = vib._running_level(n1, n2, model)[0]
    assert level[0] == 0.0  # stopped
    assert np.all(np.diff(level) > 0)
    # idle (30 % N1) keeps the idle share plus the square law's part; full power is 1
    assert level[2] == pytest.approx(model.engine_idle_share + (1 - model.engine_idle_share) * 0.09)
    assert level[4] == pytest.approx(1.0)


def test_engines_are_felt_until_the_labels_turn_them_off_and_not_after():
    """The run-down after fuel cut-off (JSBSim: N1 and N2 fall together, N1 / N2 = 0.5 for the
    CFM56 at idle): the excitation falls with them and is exactly zero once N2 is under the mark at
    which the in-flight window ends and a stowed bag is labelled at rest (labels.ENGINES_OFF_N2_PCT);
    the N1 fade alone left a sixth of the idle level there (N1 2.5 %: 2.5 / 15)."""
    from flightmode.labels import ENGINES_OFF_N2_PCT

    model = vib.VibrationModel()
    n2 = np.array([[60.0, 30.0, 15.0, 10.0, ENGINES_OFF_N2_PCT, 2.0, 0.0]])
    level = vib._running_level(0.5 * n2, n2, model)[0]
    assert np.all(np.diff(level[:5]) < 0) and np.all(level[:4] > 0.0)
    assert np.all(level[4:] == 0.0)
    # above 15 % N2 only the N1 fade acts: at N1 7.5 % it halves the running level
    assert level[2] == pytest.approx(
        (model.engine_idle_share + (1 - model.engine_idle_share) * 0.075**2) * 0.5
    )


def test_floor_rms_matches_the_documented_cruise_level():
    """The module docstring's figure: about 20 mg RMS vertical on a mid-cabin floor in cruise (an
    A320 at 80 % N1 and q = 9.6 kPa), lines and modes together, and the axis weights (6 and 12 mg).
    Over 60 s at 800 Hz the modal part (4 modes of Q 8, about 4 x 2 Hz x 60 s = 500 independent
    samples) is estimated to 3 % RMS, and the two engines' lines beat (0.3 % apart) by +-0.5 mg: 10 %
    covers both."""
    fs, n = 800.0, 48_000
    model = vib.VibrationModel()
    st = vib.initial_state(2, model, fs, _rng(2))
    y, _ = vib.vibration_g(
        np.full((2, n), 80.0),
        np.full((2, n), 90.0),
        np.full(n, 9600.0),
        np.zeros(n),
        np.zeros(n, bool),
        fs,
        "A320",
        model,
        st,
        _rng(3),
    )
    rms = np.sqrt(np.mean(y**2, axis=1))
    np.testing.assert_allclose(rms, 20e-3 * np.array(model.axis_share), rtol=0.1)


@pytest.mark.parametrize("scale", [1.0 - vib.MODE_JITTER, 1.0, 1.0 + vib.MODE_JITTER])
def test_the_mode_cascade_is_the_sum_of_the_unit_rms_resonators(scale):
    """The airframe modes run as one cascade (vibration._mode_bank) whose response must be the sum of
    the modes' resonators, each iirpeak(f0, Q) scaled to unit output RMS, at the extremes of the
    drawn mode frequencies. Both are the same rational function, so they differ only by rounding
    (measured 3e-13 of the peak; with the poles and zeros scipy's tf2zpk finds from the sum's
    polynomials, 2e-5): a lost mode or a mispaired section is off by order one; 1e-9 of the peak."""
    from scipy.signal import freqz, iirpeak, sosfreqz

    fs, q = 800.0, vib.VibrationModel().mode_q
    modes = tuple(f * scale for f in vib.VibrationModel().mode_hz)
    f = np.linspace(0.0, fs / 2, 4001)
    _, h_cascade = sosfreqz(vib._mode_bank(modes, q, fs), worN=f, fs=fs)
    h_sum = np.zeros_like(h_cascade)
    for f0 in modes:
        b, a = iirpeak(f0, q, fs=fs)
        # unit output RMS for unit white input: the impulse response's energy, by Parseval the mean
        # of |H|^2 over the band
        _, h = freqz(b, a, worN=2**16, fs=fs)
        h_sum += freqz(b, a, worN=f, fs=fs)[1] / np.sqrt(np.mean(np.abs(h) ** 2))
    assert np.abs(h_cascade - h_sum).max() < 1e-9 * np.abs(h_sum).max()


def test_a_vibration_level_scales_the_floor_exactly():
    """A scenario's [sensor].vibration_level multiplies every amplitude (vibration.scaled): the floor's
    vibration is linear in them, so with the same draws twice the level gives exactly twice the output
    (a factor of 2 is exact in binary floating point), rolling on a runway included."""
    fs, n = 800.0, 8_000
    model = vib.VibrationModel()
    gs = np.linspace(0.0, 60.0, n)
    args = (
        np.full((2, n), 80.0),
        np.full((2, n), 90.0),
        np.full(n, 9600.0),
        gs,
        np.ones(n, bool),
        fs,
        "A320",
    )
    st = vib.initial_state(2, model, fs, _rng(2))
    y1, _ = vib.vibration_g(*args, model, st, _rng(3))
    y2, _ = vib.vibration_g(*args, vib.scaled(model, 2.0), st, _rng(3))
    assert np.array_equal(y2, 2.0 * y1) and np.abs(y1).max() > 0


# ---------------------------------------------------------------------- the mounts (sim.sensor.mount)
def _many_mounts(spec: CarrierSpec, seed: int = 11) -> list[dict]:
    rng = _rng(seed)
    return [mnt.draw_mounts(spec, rng) for _ in range(N)]


@pytest.mark.parametrize("placement", sorted(mnt.PLACEMENTS))
def test_support_draws_are_uniform_in_their_documented_ranges(placement):
    kind = "parcel" if placement == "hold" else "handbag"
    mounts = [m[placement] for m in _many_mounts(CarrierSpec(kind=kind, placement=placement))]
    fn = np.array([m.fn_hz for m in mounts])  # (N, 2 stages, 3 axes)
    zeta = np.array([m.zeta for m in mounts])
    support, packing = mnt.PLACEMENTS[placement].stage, mnt.PACKINGS[CarrierSpec(kind=kind).packing_name]
    for st, stage in ((0, support), (1, packing)):
        for ax, rng_hz in ((0, stage.fn_h_hz), (1, stage.fn_h_hz), (2, stage.fn_v_hz)):
            lo, hi = rng_hz
            assert stats.kstest(fn[:, st, ax], "uniform", args=(lo, hi - lo)).pvalue > P_MIN, (st, ax)
            lo, hi = stage.zeta
            assert stats.kstest(zeta[:, st, ax], "uniform", args=(lo, hi - lo)).pvalue > P_MIN, (st, ax)
    # x and y are drawn apart (correlation of two independent uniforms: 0 +- 1/sqrt(N) = 0.016)
    assert abs(np.corrcoef(fn[:, 0, 0], fn[:, 0, 1])[0, 1]) < 5 / math.sqrt(N)


def test_cabin_row_is_uniform_unless_fixed_and_the_hold_is_the_hold():
    rows = [m["under_seat"].cabin_row for m in _many_mounts(CarrierSpec())]
    counts = np.array([rows.count(r) for r in mnt.CABIN_ROWS])
    assert counts.sum() == N
    assert stats.chisquare(counts).pvalue > P_MIN
    fixed = _many_mounts(CarrierSpec(cabin_row="rear"))[:50]
    assert {m["under_seat"].cabin_row for m in fixed} == {"rear"}
    hold = _many_mounts(CarrierSpec(kind="parcel", placement="hold"))[:50]
    assert {m["hold"].cabin_row for m in hold} == {"hold"}
    assert {m["hold"].packing for m in hold} == {"boxed"}


def test_a_cruise_placement_shares_the_bag_and_seat_and_moves_no_other_draw():
    spec = CarrierSpec(placement="under_seat", cruise_placement="seat")
    with_move = mnt.draw_mounts(spec, _rng(5))
    without = mnt.draw_mounts(CarrierSpec(placement="under_seat"), _rng(5))
    a, b = with_move["under_seat"], without["under_seat"]
    np.testing.assert_array_equal(a.fn_hz, b.fn_hz)
    np.testing.assert_array_equal(a.zeta, b.zeta)
    assert a.cabin_row == b.cabin_row
    seat = with_move["seat"]
    np.testing.assert_array_equal(seat.fn_hz[1], a.fn_hz[1])  # the same packing: the same bag
    assert seat.cabin_row == a.cabin_row and seat.packing == a.packing


VIB_BAND = np.linspace(10.0, 30.0, 81)  # seed 000's vibration band (Fig. 6)
LINE_BAND = np.linspace(60.0, 85.0, 51)  # the fan lines in cruise (CFM56: 5000 rpm at 70-100 % N1)


def _mean_band_gain(stage: mnt.Stage, axis: int, band=VIB_BAND, seed: int = 13) -> float:
    """Mean |H|^2 over ``band``, averaged over 2000 draws of the stage."""
    rng = _rng(seed)
    g = []
    for _ in range(2000):
        fn, zeta = mnt.draw_stage(stage, rng)
        g.append(float(np.mean(mnt.stage_gain(fn[axis], zeta[axis], band) ** 2)))
    return float(np.mean(g))


def test_isolation_orderings_of_supports_and_packings():
    P, K = mnt.PLACEMENTS, mnt.PACKINGS
    # a soft seat isolates the 10-30 Hz band on every axis far more than the carpet under a seat,
    # which is no isolator there at all (mean power gain above 1: its resonances, 15-60 Hz, sit in
    # or just above the band)
    for ax in (0, 1, 2):
        assert _mean_band_gain(P["seat"].stage, ax) < 0.25 * _mean_band_gain(P["under_seat"].stage, ax)
        assert _mean_band_gain(P["under_seat"].stage, ax) > 1.0
    # packings, softest first: soft < boxed < rigid in natural frequency; above the vibration band
    # (the fan lines, which alias into it at 100 Hz ODR) the soft contents isolate most and the hard
    # shell, resonating there, least; inside the band a cushion resonating in it amplifies most
    for ax, band in ((0, "fn_h_hz"), (1, "fn_h_hz"), (2, "fn_v_hz")):
        fns = [getattr(K[p], band) for p in ("soft", "boxed", "rigid")]
        assert fns[0][1] <= fns[2][0] and fns[0][0] < fns[1][0] < fns[2][0]
        soft, boxed, rigid = (_mean_band_gain(K[p], ax, LINE_BAND) for p in ("soft", "boxed", "rigid"))
        assert soft < boxed < rigid and soft < 0.1
        assert _mean_band_gain(K["boxed"], ax) > _mean_band_gain(K["rigid"], ax)
    # foam in shear: the soft packing is softer horizontally than vertically (Gibson and Ashby: G/E
    # about 3/8 for open-cell foams)
    assert K["soft"].fn_h_hz[1] < K["soft"].fn_v_hz[1] and K["soft"].fn_h_hz[0] < K["soft"].fn_v_hz[0]
    # the static-deflection bounds the docstring gives: fn = sqrt(g / delta) / 2 pi
    g = 9.80665
    assert 1 / (2 * math.pi) * math.sqrt(g / 0.028) == pytest.approx(P["seat"].stage.fn_v_hz[0], rel=0.05)
    assert 1 / (2 * math.pi) * math.sqrt(g / 0.012) == pytest.approx(P["seat"].stage.fn_v_hz[1], rel=0.05)
    # the seated human's vertical resonance, 4-6 Hz (ISO 5982), is the lap's
    assert P["lap"].stage.fn_v_hz == (4.0, 6.0)


def test_digital_mount_matches_the_continuous_transmissibility():
    """The bilinear SOS against |H(j w)| of the two stages in series, at 5-40 Hz. The bilinear
    transform maps f to (fs / pi) tan(pi f / fs): at 800 Hz and 40 Hz a 0.8 % frequency shift, which
    moves the gain by less than 3 % on the steepest slope of these stages (at most 40 dB/decade: a
    1.7 % gain change per 0.4 % in frequency... taken twice)."""
    from scipy.signal import sosfreqz

    fs = 800.0
    m = mnt.MountDraw(
        np.array([[6.0, 5.5, 4.0], [10.0, 11.0, 18.0]]),
        np.array([[0.1, 0.15, 0.2], [0.3, 0.4, 0.5]]),
        "mid",
        "soft",
    )
    f = np.linspace(5.0, 40.0, 36)
    for ax, sos in enumerate(mnt.mount_sos(m, fs)):
        digital = np.abs(sosfreqz(sos, worN=f, fs=fs)[1])
        analog = mnt.stage_gain(m.fn_hz[0, ax], m.zeta[0, ax], f) * mnt.stage_gain(
            m.fn_hz[1, ax], m.zeta[1, ax], f
        )
        np.testing.assert_allclose(digital, analog, rtol=0.03)
        assert abs(np.sum(sos[:, :3], axis=1) / np.sum(sos[:, 3:], axis=1)).prod() == pytest.approx(
            1.0
        )  # 0 Hz


# ---------------------------------------------------------------------- stowage and orientation (carrier)
def _tilt_and_yaw(r: np.ndarray) -> tuple[float, float]:
    """Tilt of the sensor's z axis from body up (deg), and the yaw of its x axis (deg, 0 = forward)."""
    a = orientation_angles(r)
    return a["tilt_deg"], a["yaw_deg"]


@pytest.mark.parametrize(
    "yaw, x_fus", [(0.0, 0.0), (30.0, 30.0), (90.0, 90.0), (150.0, 30.0), (270.0, 90.0), (330.0, 30.0)]
)
def test_orientation_angles_of_a_level_sensor(yaw, x_fus):
    # a level sensor yawed by ``yaw``: its x axis makes |yaw| folded into 0-90 deg with the fuselage
    # axis (fore or aft alike: the same vibration), its z axis is vertical (tilt 0); 1e-9 deg: rounding
    spec = CarrierSpec(stowed_yaw_deg=yaw)
    r = stowed_rot(spec, _rng(3))
    a = orientation_angles(r)
    tilt = a["tilt_deg"]  # the Rayleigh tilt drawn (scale 3 deg under a seat)
    # the tilt turns the x axis's heading and its angle to the fuselage by at most the tilt (small tilt)
    assert min(abs(a["yaw_deg"] - yaw), 360.0 - abs(a["yaw_deg"] - yaw)) <= tilt + 1e-9
    assert abs(a["x_from_fuselage_deg"] - x_fus) <= tilt + 1e-9
    level = orientation_angles(
        np.array(
            [
                [math.cos(math.radians(yaw)), -math.sin(math.radians(yaw)), 0.0],
                [math.sin(math.radians(yaw)), math.cos(math.radians(yaw)), 0.0],
                [0.0, 0.0, 1.0],
            ]
        )
        @ np.diag([1.0, -1.0, -1.0])
    )
    assert level["tilt_deg"] == pytest.approx(0.0, abs=1e-9)
    assert level["x_from_fuselage_deg"] == pytest.approx(x_fus, abs=1e-6)
    assert level["yaw_deg"] % 360.0 == pytest.approx(yaw, abs=1e-6)


@pytest.mark.parametrize("placement", ["under_seat", "seat", "lap"])
def test_a_handbag_rests_level_with_a_rayleigh_tilt(placement):
    rng = _rng(17)
    spec = CarrierSpec(placement=placement)
    ty = np.array([_tilt_and_yaw(stowed_rot(spec, rng)) for _ in range(N)])
    scale = mnt.PLACEMENTS[placement].tilt_deg
    assert stats.kstest(ty[:, 0], "rayleigh", args=(0.0, scale)).pvalue > P_MIN
    # yaw drawn uniformly when the carrier does not fix it (the tilt moves the x axis's projection by
    # at most 1 - cos(tilt) of a turn's worth: invisible at this sample size)
    assert stats.kstest(ty[:, 1], "uniform", args=(0.0, 360.0)).pvalue > P_MIN
    # fixed yaw 0: x along the fuselage to within the tilt (a tilt t about any horizontal axis turns
    # the x axis's heading by at most t for small t)
    fixed = CarrierSpec(placement=placement, stowed_yaw_deg=0.0)
    rng = _rng(19)
    for _ in range(200):
        tilt, yaw = _tilt_and_yaw(stowed_rot(fixed, rng))
        assert min(yaw, 360.0 - yaw) <= tilt + 1e-9 or tilt > 60.0


def test_a_parcel_lies_any_way_up():
    rng = _rng(23)
    spec = CarrierSpec(kind="parcel", placement="hold")
    up = np.array([-stowed_rot(spec, rng)[2, 2] for _ in range(N)])  # cos of the tilt of sensor z
    # uniform on the sphere: cos(tilt) uniform in [-1, 1] (Archimedes' hat-box theorem)
    assert stats.kstest(up, "uniform", args=(-1.0, 2.0)).pvalue > P_MIN


def test_bags_are_stowed_for_taxi_takeoff_and_landing_and_moved_for_the_cruise():
    events = {"engine_start": 1000.0, "engines_off": 9000.0}
    cruise = (3000.0, 7000.0)
    spec = CarrierSpec(placement="under_seat", cruise_placement="seat", handled_in_cruise=2)
    for seed in range(20):
        segs = build_timeline(spec, events, cruise, _rng(seed))
        on = [s for s in segs if s.on_board]
        stowed = [s for s in on if s.state == "stowed"]
        # at its placement from the stow until after the cruise starts, back there before it ends
        assert stowed[0].placement == "under_seat" and stowed[0].t1_s > cruise[0]
        assert stowed[-1].placement == "under_seat" and stowed[-1].t0_s <= cruise[1]
        on_seat = [s for s in stowed if s.placement == "seat"]
        assert on_seat and all(cruise[0] < s.t0_s and s.t1_s <= cruise[1] for s in on_seat)
        # moved 1-10 min into the cruise (CRUISE_MOVE_DELAY_S), and every move is a handling
        assert 60.0 <= on_seat[0].t0_s - spec.handling_s - cruise[0] <= 600.0
        for a, b in zip(on, on[1:]):
            assert a.t1_s == pytest.approx(b.t0_s)
            if a.state == "stowed" and b.state == "stowed":
                pytest.fail("two stowed segments in a row: a move without a handling")
        # stowed under the seat, on the seat, under the seat: one move there and one back, and the
        # in-cruise handlings (two drawn; one is dropped if it overlaps another) in between, on the seat
        places = [s.placement for s in stowed]
        assert [p for i, p in enumerate(places) if i == 0 or p != places[i - 1]] == [
            "under_seat",
            "seat",
            "under_seat",
        ]
        in_seat = [s for s in on if s.state == "handled" and on_seat[0].t0_s <= s.t0_s < on_seat[-1].t1_s]
        assert 1 <= len(in_seat) <= 2
    # without a cruise placement the bag stays put
    segs = build_timeline(CarrierSpec(), events, cruise, _rng(1))
    assert {s.placement for s in segs if s.state == "stowed"} == {"under_seat"}


def test_cruise_placement_is_validated():
    with pytest.raises(CarrierError, match="cruise_placement 'seats'.*did you mean \"seat\""):
        CarrierSpec(cruise_placement="seats").validate()
    with pytest.raises(CarrierError, match="only a handbag"):
        CarrierSpec(kind="parcel", placement="hold", cruise_placement="hold").validate()
    with pytest.raises(CarrierError, match="stays at the passenger's seat.*allowed under_seat, seat, lap"):
        CarrierSpec(cruise_placement="overhead_bin").validate()
    with pytest.raises(CarrierError, match="packing 'sof'.*did you mean \"soft\""):
        CarrierSpec(packing="sof").validate()
    with pytest.raises(CarrierError, match="cabin_row 'middle'"):
        CarrierSpec(cabin_row="middle").validate()


def test_new_carrier_keys_round_trip_through_toml():
    from flightmode.scenarios.scenario import Scenario

    sc = Scenario.builtin("hel-zrh-f100-calm")
    assert (sc.carrier.placement, sc.carrier.cruise_placement, sc.carrier.stowed_yaw_deg) == (
        "under_seat",
        "seat",
        0.0,
    )
    assert sc.plan.background_edr == 0.01 and sc.plan.turbulence == ()
    assert Scenario.from_toml_text(sc.to_toml()) == sc
    other = sc.replace(carrier={"packing": "rigid", "cabin_row": "rear", "cruise_placement": None})
    assert (other.carrier.packing, other.carrier.cabin_row, other.carrier.cruise_placement) == (
        "rigid",
        "rear",
        None,
    )
    assert Scenario.from_toml_text(other.to_toml()) == other


# ---------------------------------------------------------------------- seed 000, Tables 4 and 5 (slow)
# Seed 000, Tables 4 and 5 (NMV, W_s = 1 s): per-axis fractions of in-flight checks whose moving
# variance is below T_sigma = k sigma^2, and their product P_FA^t, for k = 3, 4, 5 (the same for
# T_th = 3 and 4 s). Table 4's P_FA^t at 3 sigma^2 reads 2e-10, but the product of its row is 3e-11
# (and its P_FA column, 6e-33 = (P_FA^t)^3, implies 1.8e-11): the per-axis cells are used, and
# P_FA^t is compared as their product.
TABLES = {
    "gva-lhr-a320": {
        3: (5e-2, 7e-4, 9e-7),
        4: (8e-2, 2e-3, 2e-6),
        5: (1e-1, 4e-3, 2e-4),
    },  # Table 4, flight 1
    "hel-zrh-f100-calm": {
        3: (3e-1, 1e-2, 7e-3),
        4: (6e-1, 1e-1, 7e-2),
        5: (7e-1, 4e-1, 2e-1),
    },  # Table 5, flight 2
}
RESOLVED = 10.0  # expected checks at the paper's fraction above which a cell is compared both ways


def _within_a_decade(ours: float, paper: float, n: int) -> bool:
    """The acceptance criterion (issue 13, item 8): within one order of magnitude of the paper. A
    fraction the paper gives below what n checks resolve is compared one way: ours may not exceed
    ten times max(paper, 1 / n). Below RESOLVED expected checks a count is Poisson-noisy (a spread of
    1 / sqrt(10) = 32 % at 10, and a zero count has probability exp(-lambda), 37 % at lambda = 1), so
    only cells with paper x n >= 10 are also held from below."""
    if paper * n >= RESOLVED:
        return paper / 10.0 <= ours <= paper * 10.0
    return ours <= 10.0 * max(paper, 1.0 / n)


@pytest.mark.slow
@pytest.mark.parametrize("name", sorted(TABLES))
def test_table_4_and_5_cells_within_a_decade(name, run_cached):
    from flightmode.detector.evaluation import pfa_table
    from flightmode.detector.recommended import recommended_params
    from flightmode.studies.validate import dynamic_part

    r = run_cached(name)
    rec, det = r.recording, r.detection  # sigma^2: the bench calibration of the run's own unit
    # the checks the paper counted: the in-flight window without the engines' run-down (validate.dynamic_part)
    labels = dynamic_part(
        {"in_flight_window": rec.in_flight_window, "sensor_static": rec.sensor_static, "phase": rec.phase}
    )
    rows = [
        row
        for row in pfa_table(rec.t_s, rec.acc_g, labels, recommended_params(rec.odr_hz), det.sigma2)
        if row["T_th_s"] == 4.0
    ]
    report, bad = [], []
    for row in rows:
        k = int(row["T_sigma"])
        n = row["checks"]
        ours = (row["P_FA_x"], row["P_FA_y"], row["P_FA_z"])
        paper = TABLES[name][k]
        report.append(
            f"{k} sigma^2: ours {[f'{v:.1e}' for v in ours]} P_t {row['P_FA_t']:.1e} | paper "
            f"{[f'{v:.0e}' for v in paper]} P_t {math.prod(paper):.0e} (n = {n})"
        )
        for axis, o, p in zip("xyz", ours, paper):
            if not _within_a_decade(o, p, n):
                bad.append(f"{axis} at {k} sigma^2: {o:.2e} against {p:.0e}")
        # P_FA^t, the product: compared both ways when all three cells are resolved; otherwise held
        # under ten times the product of the cells at our resolution
        if all(p * n >= RESOLVED for p in paper):
            ok = math.prod(paper) / 10.0 <= row["P_FA_t"] <= math.prod(paper) * 10.0
        else:
            ok = row["P_FA_t"] <= 10.0 * math.prod(max(p, 1.0 / n) for p in paper)
        if not ok:
            bad.append(f"P_t at {k} sigma^2: {row['P_FA_t']:.2e} against {math.prod(paper):.0e}")
    print(f"\n{name}:\n  " + "\n  ".join(report))
    assert not bad, bad
    # in both tables the fore-aft axis (x) is the quietest: it goes below the threshold most often
    for row in rows:
        assert row["P_FA_x"] >= max(row["P_FA_y"], row["P_FA_z"])


@pytest.mark.slow
def test_the_calm_flight_has_false_temporary_statics_in_cruise_and_flight_1_none_airborne(run_cached):
    """Seed 000 section 6: in flight 2 "the algorithm starts to detect false temporary static
    condition during flight time for a MV threshold of 4 sigma^2", in flight 1 it "always outputs a
    dynamic condition up to an MV threshold of 4 sigma^2". Here: with the handbag on the seat in
    cruise, the calm flight has checks with all three axes below 4 sigma^2 while airborne; flight 1
    has none airborne (the engines' last seconds of spool-down, still inside the in-flight window,
    may give one on the ground)."""
    calm = run_cached("hel-zrh-f100-calm")
    c, rec = calm.detection.checks, calm.recording
    airborne = rec.airborne[c.index] & rec.in_flight_window[c.index]
    assert int((c.temporary_static & airborne).sum()) > 0
    f1 = run_cached("gva-lhr-a320")
    c, rec = f1.detection.checks, f1.recording
    assert int((c.temporary_static & rec.airborne[c.index]).sum()) == 0
