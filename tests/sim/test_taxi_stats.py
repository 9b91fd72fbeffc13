"""Taxi statistics (flightmode.sim.flight.taxi_stats): known answers on synthetic taxi tracks, the
real ADS-B figures recomputed against ADSB_TAXI_ANCHORS, and the cut of a simulated flight."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from flightmode.errors import InputDataError
from flightmode.labels import PHASE_CODE
from flightmode.sim.flight import taxi_stats as ts
from flightmode.sim.flight.geodesy import WGS84_A_M, WGS84_E2
from flightmode.units import G0_MPS2, KT_MPS
from tests.shared_data import shared_data_or_skip

LAT0, LON0 = 47.45, 8.56


def _to_geodetic(north_m, east_m):
    """Local north/east (m) to lat/lon with the WGS-84 radii of curvature at the origin: over the
    2-3 km of these paths the mapping's scale error is about 3e-4, i.e. mm/s at taxi speeds."""
    s2 = math.sin(math.radians(LAT0)) ** 2
    m = WGS84_A_M * (1 - WGS84_E2) / (1 - WGS84_E2 * s2) ** 1.5
    n = WGS84_A_M / math.sqrt(1 - WGS84_E2 * s2)
    lat = LAT0 + np.degrees(np.asarray(north_m) / m)
    lon = LON0 + np.degrees(np.asarray(east_m) / (n * math.cos(math.radians(LAT0))))
    return lat, lon


def _path(legs, v_mps, fs_hz=120.0, psi0_deg=20.0):
    """A constant-speed path of legs ("straight", length_m) / ("turn", radius_m, angle_deg, +1 right
    or -1 left), sampled at fs_hz: t, lat, lon, heading (deg), turn rate (deg/s) per sample."""
    seq, rates = [], []
    for leg in legs:
        if leg[0] == "straight":
            seq.append(leg[1] / v_mps)
            rates.append(0.0)
        else:
            _, r, ang, sign = leg
            seq.append(math.radians(ang) * r / v_mps)
            rates.append(sign * math.degrees(v_mps / r))
    t = np.arange(0.0, sum(seq), 1.0 / fs_hz)
    edges = np.concatenate([[0.0], np.cumsum(seq)])
    k = np.clip(np.searchsorted(edges, t, side="right") - 1, 0, len(seq) - 1)
    rate = np.asarray(rates)[k]
    # heading: piecewise linear in time, integrated exactly per leg
    psi_at_edges = psi0_deg + np.concatenate([[0.0], np.cumsum(np.asarray(rates) * np.asarray(seq))])
    psi = psi_at_edges[k] + rate * (t - edges[k])
    # position: exact integral of v (cos psi, sin psi) per leg (arcs and straights)
    pos = np.zeros((len(seq) + 1, 2))
    for i, (dur, rt) in enumerate(zip(seq, rates)):
        pos[i + 1] = pos[i] + _leg_disp(psi_at_edges[i], rt, dur, v_mps)
    disp = np.array([_leg_disp(psi_at_edges[kk], rates[kk], tt, v_mps) for kk, tt in zip(k, t - edges[k])])
    ne = pos[k] + disp
    lat, lon = _to_geodetic(ne[:, 0], ne[:, 1])
    return t, lat, lon, psi, rate


def _leg_disp(psi0_deg, rate_dps, dt_s, v):
    p0 = math.radians(psi0_deg)
    if rate_dps == 0.0:
        return np.array([v * dt_s * math.cos(p0), v * dt_s * math.sin(p0)])
    w = math.radians(rate_dps)
    p1 = p0 + w * dt_s
    return np.array([v / w * (math.sin(p1) - math.sin(p0)), -v / w * (math.cos(p1) - math.cos(p0))])


# ---------------------------------------------------------------------------------------------------
# (a) known answers


def test_straight_taxi_at_constant_speed_irregular_adsb_like_sampling():
    rng = np.random.default_rng(7)
    t_all, lat, lon, psi, _ = _path([("straight", 2400.0)], 8.0)
    # irregular 0.5-7 s reports, like ADS-B (the last sample kept)
    reports = np.searchsorted(t_all, np.cumsum(rng.uniform(0.5, 7.0, 80)))
    idx = np.unique(np.concatenate([reports, [t_all.size - 1]]))
    idx = idx[idx < t_all.size]
    t, la, lo, hd = t_all[idx], lat[idx], lon[idx], psi[idx]
    gs = np.full(t.size, 8.0)
    rep = ts.taxi_statistics(t, la, lo, ground_speed_mps=gs, track_deg=hd)
    # reported inputs: a constant stays constant through interpolation and the filter (float rounding)
    for k in ("speed_p50_mps", "speed_p90_mps", "speed_p99_mps", "speed_max_mps"):
        assert rep[k] == pytest.approx(8.0, abs=1e-9), k
    for k in (
        "yaw_rate_p50_dps",
        "yaw_rate_p90_dps",
        "yaw_rate_p99_dps",
        "yaw_rate_max_dps",
        "brake_max_g",
        "accel_max_g",
        "n_turns",
        "turns_per_min",
    ):
        assert rep[k] == pytest.approx(0.0, abs=1e-9), k
    assert rep["duration_s"] == pytest.approx(t[-1] - t[0])
    assert rep["distance_m"] == pytest.approx(8.0 * math.floor(t[-1] - t[0]), rel=1e-9)
    # derived from positions alone: the same answers to the test mapping's mm/s and the filter's
    # edge fits (a straight line is a polynomial: the Savitzky-Golay slope is exact)
    der = ts.taxi_statistics(t, la, lo)
    for k in ("speed_p50_mps", "speed_p90_mps", "speed_p99_mps"):
        assert der[k] == pytest.approx(8.0, abs=0.01), k
    assert der["yaw_rate_max_dps"] < 0.01
    assert der["n_turns"] == 0.0 and der["brake_max_g"] < 1e-3


V, R = 5.0, 40.0  # three 90 deg turns at 5 m/s on a 40 m radius: v/R = 7.16 deg/s, 12.6 s per turn
THREE_TURNS = [
    ("straight", 200.0),
    ("turn", R, 90.0, +1),
    ("straight", 200.0),
    ("turn", R, 90.0, -1),
    ("straight", 200.0),
    ("turn", R, 90.0, +1),
    ("straight", 200.0),
]


def test_three_right_angle_turns_at_known_radius_and_speed():
    t, lat, lon, psi, _ = _path(THREE_TURNS, V)
    st = ts.taxi_statistics(t, lat, lon, ground_speed_mps=np.full(t.size, V), track_deg=psi)
    assert st["n_turns"] == 3.0
    assert st["turns_per_min"] == pytest.approx(3.0 / ((t[-1] - t[0]) / 60.0))
    # the heading is a ramp through each turn; a 9 s quadratic fit whose window lies inside the
    # 12.6 s arc returns the ramp's slope exactly, so the peak yaw rate is v/R to float rounding
    # (and the top 1 % of moving samples sit on that plateau)
    v_over_r = math.degrees(V / R)
    assert st["yaw_rate_max_dps"] == pytest.approx(v_over_r, rel=1e-9)
    assert st["yaw_rate_p99_dps"] == pytest.approx(v_over_r, rel=1e-9)
    assert st["yaw_rate_p50_dps"] == pytest.approx(0.0, abs=1e-9)  # most of the path is straight
    assert st["speed_p50_mps"] == pytest.approx(V) and st["speed_in_turns_p50_mps"] == pytest.approx(V)
    # the length of the path, to the 1 s grid's last partial second
    length = 800.0 + 3 * math.pi / 2 * R
    assert st["distance_m"] == pytest.approx(length, abs=V * 1.0)


def test_turn_rate_derived_from_positions_matches_v_over_r():
    # derived from positions the heading passes two 9 s fits (velocity, then heading rate): the rate
    # is exact where both windows lie inside the arc, so the arc must last > 18 s: R = 60 m (18.8 s)
    r = 60.0
    legs = [
        ("straight", 150.0),
        ("turn", r, 90.0, -1),
        ("straight", 150.0),
        ("turn", r, 90.0, +1),
        ("straight", 150.0),
        ("turn", r, 90.0, -1),
        ("straight", 150.0),
    ]
    t, lat, lon, _, _ = _path(legs, V)
    st = ts.taxi_statistics(t, lat, lon)
    assert st["n_turns"] == 3.0
    # 1e-3 relative: the test's flat-earth mapping (3e-4) and meridian convergence over the path
    assert st["yaw_rate_max_dps"] == pytest.approx(math.degrees(V / r), rel=1e-3)
    # the speed of an arc fitted by a quadratic over +-4 s is low by (w h)^2 ~ 1.4 % at w = v/R
    assert st["speed_max_mps"] == pytest.approx(V, rel=1e-3)
    assert st["speed_in_turns_p50_mps"] == pytest.approx(V, rel=0.02)


def test_small_heading_changes_are_not_turns_and_large_ones_are():
    for angle, expect in ((25.0, 0.0), (40.0, 1.0)):
        legs = [("straight", 200.0), ("turn", 100.0, angle, +1), ("straight", 200.0)]
        t, lat, lon, psi, _ = _path(legs, V)
        assert ts.taxi_statistics(t, lat, lon, np.full(t.size, V), psi)["n_turns"] == expect, angle


def test_braking_is_the_slope_of_the_smoothed_speed():
    # 8 m/s, then braking at 0.05 g to rest (16.3 s: longer than the 9 s window, so the slope is exact)
    dec = 0.05 * G0_MPS2
    t = np.arange(0.0, 80.0, 0.5)
    gs = np.clip(8.0 - dec * np.clip(t - 30.0, 0.0, None), 0.0, None)
    north = np.concatenate([[0.0], np.cumsum(0.5 * (gs[1:] + gs[:-1]) * 0.5)])
    lat, lon = _to_geodetic(north, np.zeros_like(north))
    st = ts.taxi_statistics(t, lat, lon, ground_speed_mps=gs, track_deg=np.zeros_like(t))
    assert st["brake_max_g"] == pytest.approx(0.05, rel=1e-9)
    assert st["accel_max_g"] < 0.01  # only the filter's rounding of the corners
    assert st["moving_s"] == pytest.approx(30.0 + (8.0 - 1.0) / dec, abs=2.0)


def test_bad_input_raises_typed_errors():
    t = np.arange(30.0)
    lat, lon = _to_geodetic(np.arange(30.0) * 5, np.zeros(30))
    with pytest.raises(InputDataError, match="increase"):
        ts.taxi_statistics(t[::-1], lat, lon)
    with pytest.raises(InputDataError, match="at least"):
        ts.taxi_statistics(t[:5], lat[:5], lon[:5])
    with pytest.raises(InputDataError, match="one length"):
        ts.taxi_statistics(t, lat, lon[:-1])


# ---------------------------------------------------------------------------------------------------
# (b) the real tracks against the anchors


def _adsb_files():
    # the real tracks (data nobody here wrote, not copied into the repository)
    adsb = shared_data_or_skip("adsb")
    return {p.stem: p for p in sorted(adsb.glob("*.csv"))}


def test_adsb_taxi_figures_match_the_anchors():
    files = _adsb_files()
    assert set(files) == set(ts.ADSB_TAXI_ANCHORS)
    for stem, anchors in ts.ADSB_TAXI_ANCHORS.items():
        got = ts.adsb_taxi_statistics(files[stem])
        assert list(got) == list(anchors), stem  # the same segments, found in the same order
        for seg, figs in anchors.items():
            assert set(got[seg]) == set(figs), (stem, seg)
            for k, v in figs.items():
                # anchors are written with 12 significant digits: equal to that rounding
                assert got[seg][k] == pytest.approx(v, rel=1e-9, abs=1e-9), (stem, seg, k)


def test_adsb_segments_begin_and_end_where_the_rules_say():
    files = _adsb_files()
    for stem, path in files.items():
        tr = ts.read_adsb_csv(path)
        kt = tr.ground_speed_mps / KT_MPS
        for seg in ts.adsb_taxi_segments(tr.t_s, tr.on_ground, tr.ground_speed_mps):
            s = seg.slice
            assert tr.on_ground[s].all(), (stem, seg)
            if seg.kind == "taxi_out":  # ends below 12 kt, just before the roll
                assert kt[seg.i1] <= ts.ROLL_START_KT and (kt[seg.i1 + 1 :] > ts.ROLL_KT).any()
            else:  # starts at or below the exit speed, the sample before was faster (or airborne)
                before = seg.i0 - 1
                assert kt[seg.i0] <= ts.EXIT_KT and (kt[before] > ts.EXIT_KT or not tr.on_ground[before])
            assert seg.t1_s - seg.t0_s > 60.0


# ---------------------------------------------------------------------------------------------------
# simulated flights: the same function on the phase-cut segments


def _fake_track():
    t, lat, lon, psi, _ = _path(THREE_TURNS, V, fs_hz=20.0)
    n = t.size
    phase = np.full(n, PHASE_CODE["taxi_out"], dtype=np.uint8)
    phase[:100] = PHASE_CODE["pushback"]
    phase[-100:] = PHASE_CODE["takeoff_roll"]
    euler = np.zeros((n, 3))
    euler[:, 2] = np.radians(psi)
    return SimpleNamespace(
        t_s=t, lat_deg=lat, lon_deg=lon, ground_speed_mps=np.full(n, V), euler_rad=euler, phase_code=phase
    )


def test_flight_segments_follow_the_phase_labels():
    tr = _fake_track()
    segs = ts.flight_taxi_segments(tr)
    assert segs == {"taxi_out": slice(100, tr.t_s.size - 100)}
    st = ts.flight_taxi_statistics(tr)["taxi_out"]
    s = segs["taxi_out"]
    assert st == ts.taxi_statistics(
        tr.t_s[s], tr.lat_deg[s], tr.lon_deg[s], tr.ground_speed_mps[s], np.degrees(tr.euler_rad[s, 2])
    )
    tr.phase_code[:] = PHASE_CODE["cruise"]
    with pytest.raises(InputDataError, match="no taxi_out or taxi_in"):
        ts.flight_taxi_segments(tr)


def test_pattern_flight_taxi_figures(fly_cached):
    _, tr = fly_cached("pattern")
    stats = ts.flight_taxi_statistics(tr)
    assert set(stats) == {"taxi_out", "taxi_in"}
    for name, st in stats.items():
        idx = np.flatnonzero(tr.phase == name)
        assert st["duration_s"] == pytest.approx(tr.t_s[idx[-1]] - tr.t_s[idx[0]])
        assert st["n_turns"] >= 1.0, name  # the generated routes turn onto and off the runway
        assert all(math.isfinite(v) for v in st.values()), name
