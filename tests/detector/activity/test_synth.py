"""Seed 001's activity synthesizer (section 3.1.1): the marker is the periods it drew, the same seed
gives the same arrays, the gravity axis and the sensor ranges are what was asked. Noise-free
recordings (sigma 0) make most checks exact."""

from __future__ import annotations

import numpy as np
import pytest

from flightmode.detector.activity.synth import (
    ACTIVITIES,
    GRAVITY_AXES,
    PERIOD_KINDS,
    body_to_sensor,
    still_recording,
    synthesize,
)
from flightmode.errors import SensorError

FS = 50.0
QUIET = {"sigma_acc_g": 0.0, "sigma_gyr_dps": 0.0}


def _rec(seed: int, duration_s: float = 120.0, **kw):
    return synthesize(np.random.default_rng(seed), duration_s, fs_hz=FS, **kw)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_marker_is_the_periods_drawn(seed):
    s = _rec(seed, **QUIET)
    n = s.t_s.shape[0]
    assert n == 6000 and np.array_equal(s.t_s, np.arange(n) / FS)
    # the periods tile the recording, in order, starting still
    assert s.periods[0].kind == "still" and s.periods[0].start == 0 and s.periods[-1].stop == n
    assert all(a.stop == b.start and a.stop > a.start for a, b in zip(s.periods, s.periods[1:]))
    still = np.array([0.0, 0.0, 1.0])  # standing still, the default gravity axis "z" up
    for p in s.periods:
        assert p.kind in PERIOD_KINDS
        seg = slice(p.start, p.stop)
        assert np.all(s.marker[seg] == int(p.active))
        acc, gyr = s.acc_g[seg], s.gyr_dps[seg]
        if not p.active:
            # inactivity: exactly 1 g ("the magnitude of the acceleration is set to be 1g at every
            # static instant", section 3.1.1) and no rotation; 1e-12: rounding of sin^2 + cos^2
            assert np.all(np.abs(np.linalg.norm(acc, axis=1) - 1.0) < 1e-12)
            assert np.all(gyr == 0.0)
            if p.kind == "still":
                assert np.array_equal(acc, np.tile(still, (p.stop - p.start, 1)))
        else:
            # activity: the sensor moves at some sample (by far more than these bounds: the smallest
            # draws are 0.1 g of constant acceleration and a 20 deg/s constant rate)
            moved = (
                np.abs(acc - acc[0]).max() > 0.05
                or np.abs(acc - still).max() > 0.05
                or np.abs(gyr).max() > 1.0
            )
            assert moved, p
    # sit/lie: down (active), the rest (inactive), up (active)
    kinds = [p.kind for p in s.periods]
    for i, k in enumerate(kinds):
        if k in ("sit_down", "lie_down") and i + 2 < len(kinds):
            assert kinds[i + 1] == ("seated" if k == "sit_down" else "lying") and kinds[i + 2] == "stand_up"


def test_every_activity_appears_over_a_few_recordings():
    seen = {p.kind for seed in range(4) for p in _rec(seed).periods}
    assert seen == set(PERIOD_KINDS)  # the seven activities of ACTIVITIES as their periods, and still


def test_same_seed_same_arrays_and_different_seed_different():
    a, b, c = _rec(11), _rec(11), _rec(12)
    for name in ("t_s", "acc_g", "gyr_dps", "marker"):
        assert np.array_equal(getattr(a, name), getattr(b, name))  # bit-identical
    assert a.periods == b.periods
    assert not np.array_equal(a.acc_g, c.acc_g) and a.periods != c.periods
    # the noise has its own streams: a different noise level draws the same schedule
    q = _rec(11, **QUIET)
    assert q.periods == a.periods and np.array_equal(q.marker, a.marker)


@pytest.mark.parametrize("axis", GRAVITY_AXES)
def test_gravity_axis(axis):
    m = body_to_sensor(axis)
    assert np.allclose(m @ m.T, np.eye(3), atol=0) and np.linalg.det(m) == pytest.approx(1.0, abs=1e-15)
    s = _rec(3, 30.0, gravity_axis=axis, **QUIET)
    p = s.periods[0]
    expect = np.zeros(3)
    expect["xyz".index(axis[-1])] = -1.0 if axis.startswith("-") else 1.0
    assert np.array_equal(
        s.acc_g[p.start : p.stop], np.tile(expect, (p.stop - p.start, 1))
    )  # +1 g on the up axis
    # the same recording on another axis is the same body motion rotated: exactly (sigma 0; the
    # rotation is a signed permutation, so no rounding)
    z = _rec(3, 30.0, gravity_axis="z", **QUIET)
    r = m @ body_to_sensor("z").T
    assert s.periods == z.periods
    assert np.array_equal(s.acc_g, z.acc_g @ r.T) and np.array_equal(s.gyr_dps, z.gyr_dps @ r.T)


def test_ranges_clip_the_outputs():
    s = _rec(5, 60.0, activities=("running", "jumping"), acc_range_g=1.5, gyr_range_dps=30.0)
    assert np.abs(s.acc_g).max() == 1.5 and np.abs(s.gyr_dps).max() == 30.0  # saturated at the rails
    wide = _rec(5, 60.0, activities=("running", "jumping"), acc_range_g=16.0, gyr_range_dps=2000.0)
    assert np.abs(wide.acc_g).max() > 1.5 and np.abs(wide.gyr_dps).max() > 30.0  # so the clip did something
    # the default +-3 g (the seed's ADXL335) saturates in jumps (contact pushes of 2-6 g)
    d = _rec(5, 60.0, activities=("jumping",))
    assert np.abs(d.acc_g).max() == 3.0


def test_noise_level_and_the_bench():
    b = still_recording(np.random.default_rng(0), 200.0, fs_hz=FS)
    assert np.all(b.marker == 0)
    # 10,000 samples per axis: the sample std is within 3 % of sigma (its relative standard error is
    # 1/sqrt(2 n) = 0.7 %, so 3 % is over 4 standard errors)
    assert np.std(b.acc_g, axis=0) == pytest.approx(np.full(3, 2.23e-3), rel=0.03)
    assert np.std(b.gyr_dps, axis=0) == pytest.approx(np.full(3, 0.05), rel=0.03)


@pytest.mark.parametrize(
    ("kw", "match"),
    [
        ({"gravity_axis": "zz"}, 'did you mean "z"'),
        ({"acc_range_g": 1.0}, "must exceed the 1 g"),
        ({"fs_hz": 0.0}, "fs_hz"),
        ({"sigma_acc_g": -1.0}, "sigma_acc_g"),
        ({"activities": ("walkng",)}, 'did you mean "walking"'),
    ],
)
def test_bad_settings_raise_one_typed_error(kw, match):
    with pytest.raises(SensorError, match=match):
        synthesize(np.random.default_rng(0), 10.0, **kw)


def test_the_activity_list_is_the_seeds():
    assert ACTIVITIES == (
        "walking",
        "sit_stand",
        "lie_stand",
        "running",
        "jumping",
        "constant_rate",
        "constant_acc",
    )


def test_the_figure2_sequence_is_followed_in_order_and_cycles():
    """sequence=True takes the activities in their order (seed 001, Figure 2's ten), cycling; each
    activity is still-separated and sit/lie are their three periods."""
    from flightmode.detector.activity.synth import FIGURE2_SEQUENCE

    first = {"sit_down": "sit_stand", "lie_down": "lie_stand"}
    s = _rec(3, duration_s=600.0, activities=FIGURE2_SEQUENCE, sequence=True, **QUIET)
    kinds = [p.kind for p in s.periods]
    acts = [first.get(k, k) for k in kinds if k not in ("still", "seated", "lying", "stand_up")]
    assert len(acts) > len(FIGURE2_SEQUENCE)  # 600 s holds more than one cycle
    assert acts == [FIGURE2_SEQUENCE[i % len(FIGURE2_SEQUENCE)] for i in range(len(acts))]
