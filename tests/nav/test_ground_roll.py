"""nav.ground_roll on synthetic rolls with a known answer: a tilted bag at an unknown yaw, with a
zero-g offset, on a roll of known acceleration; forwards from rest and backwards from a known speed."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from flightmode.errors import NavError
from flightmode.nav.ground_roll import along_track_acceleration, estimate_roll
from flightmode.units import G0_MPS2

FS_HZ = 100.0
OFFSET_G = np.array([0.031, -0.042, 0.018])  # within the LIS302DL's +-40 mg per axis, and beyond on y
# the bag's frame: tilted 20 deg and 10 deg, at a yaw of 37 deg to the direction of travel
SENSOR_FROM_WORLD = Rotation.from_euler("xyz", [20.0, -10.0, 37.0], degrees=True).inv()


def _bag(acc_along_mps2: np.ndarray, heading_deg: float = 0.0) -> np.ndarray:
    """(n, 3) readings in g of the tilted bag with its offset, for an along-track acceleration on a
    level runway at ``heading_deg`` (world: x, y horizontal, z up; at rest the bag reads +1 g up)."""
    h = np.radians(heading_deg)
    world = np.zeros((acc_along_mps2.shape[0], 3))
    world[:, 0] = acc_along_mps2 * np.cos(h) / G0_MPS2
    world[:, 1] = acc_along_mps2 * np.sin(h) / G0_MPS2
    world[:, 2] = 1.0  # f = a - g: gravity reads +1 g on the up axis
    return SENSOR_FROM_WORLD.apply(world) + OFFSET_G


def test_constant_acceleration_from_rest_is_exact_once_the_offset_is_removed():
    a0, dur = 1.9, 40.0  # an airliner's takeoff roll: 1.5-2.5 m/s^2 for 30-45 s
    t = np.arange(int(dur * FS_HZ) + 1) / FS_HZ
    rest = _bag(np.zeros(500), heading_deg=65.0)
    est = estimate_roll(
        t, _bag(np.full(t.shape, a0), 65.0), rest, accelerating=True, known_speed_mps=0.0, known_at="start"
    )
    # the stop's mean is gravity plus the offset, both removed exactly: the along-track acceleration
    # is a0 to rounding (1e-12 of it), and seed 002's recurrence is exact for the quadratic path of a
    # constant acceleration (2 c_i = a0, d_i = 0): speed a0 t and distance a0 t^2 / 2 to 1e-9 relative
    assert np.max(np.abs(est.along_acc_mps2 - a0)) < 1e-12 * a0
    assert np.max(np.abs(est.speed_mps - a0 * t)) < 1e-9 * a0 * dur
    assert np.max(np.abs(est.distance_m - 0.5 * a0 * t**2)) < 1e-9 * 0.5 * a0 * dur**2
    assert abs(est.length_m / (0.5 * a0 * dur**2) - 1) < 1e-9
    assert abs(est.end_speed_mps / (a0 * dur) - 1) < 1e-9 and est.peak_speed_mps == est.end_speed_mps
    # the travel axis is the runway's direction seen from the bag: the world heading rotated into it
    h = np.radians(65.0)
    expect = SENSOR_FROM_WORLD.apply([np.cos(h), np.sin(h), 0.0])
    assert np.allclose(est.travel_axis, expect, atol=1e-12)
    assert np.allclose(est.rest_specific_force_g, SENSOR_FROM_WORLD.apply([0, 0, 1.0]) + OFFSET_G, atol=1e-12)


def test_without_the_offset_removed_the_error_is_half_b_t_squared():
    """What the rest-based offset buys: a stop that read gravity alone leaves the offset b in the
    roll's samples, integrated twice with the acceleration."""
    a0, dur = 1.9, 40.0
    t = np.arange(int(dur * FS_HZ) + 1) / FS_HZ
    roll = _bag(np.full(t.shape, a0))
    rest_no_offset = np.tile(SENSOR_FROM_WORLD.apply([0, 0, 1.0]), (500, 1))
    est = estimate_roll(t, roll, rest_no_offset, accelerating=True, known_speed_mps=0.0, known_at="start")
    # the mean reading beyond the stop's is a0 plus b: its magnitude is taken as along-track, so the
    # length is 0.5 |a0 + b| t^2, off the truth by 0.5 (|a0 + b| - a0) t^2 (hundreds of m for 50 mg)
    along = np.linalg.norm(SENSOR_FROM_WORLD.apply([a0 / G0_MPS2, 0, 0]) + OFFSET_G) * G0_MPS2
    assert abs(est.length_m / (0.5 * along * dur**2) - 1) < 1e-9
    assert abs(est.length_m - 0.5 * a0 * dur**2) > 100.0


def test_a_rollout_integrated_backwards_from_its_exit_speed():
    """A landing rollout: touchdown at 68 m/s, deceleration growing linearly from 1.0 to 2.0 m/s^2
    over 40 s (reversers, then brakes), exit at the speed left; integrated backwards from the exit
    speed, the touchdown speed and the length come back exactly (the recurrence is exact for the
    cubic path of a linearly varying acceleration)."""
    v_td, dur = 68.0, 40.0
    t = 500.0 + np.arange(int(dur * FS_HZ) + 1) / FS_HZ
    s = t - t[0]
    dec = 1.0 + s / dur  # m/s^2, slowing down
    v = v_td - s - 0.5 * s**2 / dur
    x = v_td * s - 0.5 * s**2 - s**3 / (6.0 * dur)
    est = estimate_roll(
        t,
        _bag(-dec, 210.0),
        _bag(np.zeros(300), 123.0),
        accelerating=False,
        known_speed_mps=float(v[-1]),
        known_at="end",
    )
    assert np.max(np.abs(est.along_acc_mps2 + dec)) < 1e-12 * 2.0
    assert np.max(np.abs(est.speed_mps - v)) < 1e-9 * v_td
    assert np.max(np.abs(est.distance_m - x)) < 1e-9 * x[-1]
    assert abs(est.start_speed_mps / v_td - 1) < 1e-9 and abs(est.peak_speed_mps / v_td - 1) < 1e-9


def test_bad_input_is_named():
    t = np.arange(100) / FS_HZ
    roll = _bag(np.full(100, 1.0))
    with pytest.raises(NavError, match="rest samples must be an"):
        along_track_acceleration(roll, np.zeros((0, 3)), True)
    with pytest.raises(NavError, match="reads about 1 g"):
        along_track_acceleration(roll, np.zeros((10, 3)), True)
    with pytest.raises(NavError, match="NaN"):
        along_track_acceleration(np.where(t[:, None] > 0.5, np.nan, roll), roll[:5], True)
    with pytest.raises(NavError, match="no direction of travel"):
        along_track_acceleration(roll[:5], roll[:5], True)
    with pytest.raises(NavError, match="known_at must be"):
        estimate_roll(
            t,
            roll,
            _bag(np.zeros(5)),
            accelerating=True,
            known_speed_mps=0.0,
            known_at="middle",
        )
