"""Determinism over every built-in scenario (as Gymnasium checks every registered environment): the
same scenario and seed give bit-identical tracks and samples, in this process and in another; another
seed gives another sensor unit, other noise and another turbulence stream, and nothing else changes."""

from __future__ import annotations

import dataclasses
import subprocess
import sys

import numpy as np
import pytest

from flightmode.digest import digest
from flightmode.runs import pipeline
from flightmode.scenarios.scenario import builtin_names

ARRAYS = (
    "t_s",
    "lat_deg",
    "lon_deg",
    "alt_m",
    "vel_ned_mps",
    "euler_rad",
    "rates_radps",
    "specific_force_body_mps2",
    "phase_code",
    "turbulence_code",
)  # recorded at every FDM step
SLOW = ("n1_pct", "n2_pct", "ias_mps")  # read at the pilot's ticks, interpolated between them
HELD = 30  # after a stopped flight's last tick (ticks are <= 30 steps apart) the slow ones are held


def _prefix_digest(track, n: int) -> str:
    return digest(
        tuple(getattr(track, a)[:n] for a in ARRAYS) + tuple(getattr(track, a)[: n - HELD] for a in SLOW)
    )


@pytest.mark.slow
@pytest.mark.parametrize("name", builtin_names())
def test_same_seed_bit_identical_track_in_another_process_and_samples_here(name, fly_cached, run_cached):
    sc, full = fly_cached(name)
    # another interpreter flies the scenario from the gate to two minutes after liftoff (the ground
    # phases, the takeoff and the climb-out: every controller up to there): the exact prefix
    stop = full.event_time("liftoff") + 120.0
    code = (
        "import sys, flightmode; from flightmode.runs import pipeline; from flightmode.digest import digest;"
        f"sc = flightmode.Scenario.builtin({name!r});"
        f"tr = pipeline.fly(sc, pipeline.streams_of(sc.seed).child('flight'), stop_after_s={stop!r});"
        f"print(tr.n); print(digest(tuple(getattr(tr, a) for a in {ARRAYS!r})"
        f" + tuple(getattr(tr, a)[: tr.n - {HELD}] for a in {SLOW!r})))"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    n, d = r.stdout.split()[-2:]
    assert 0 < int(n) < full.n and d == _prefix_digest(full, int(n))
    # the samples: sensing the flight again with the run's sensor streams gives the run's recording
    rec = run_cached(name).recording
    again = pipeline.sense(full, sc.carrier, sc.sensor, pipeline.streams_of(sc.seed).child("sensor"))
    assert again.digest() == rec.digest()


@pytest.mark.slow
@pytest.mark.parametrize("name", builtin_names())
def test_another_seed_changes_the_unit_the_noise_and_the_turbulence_stream_only(name, fly_cached, run_cached):
    sc, track = fly_cached(name)
    rec = run_cached(name).recording
    other = pipeline.streams_of(sc.seed + 1)
    b = pipeline.sense(track, sc.carrier, sc.sensor, other.child("sensor"))
    assert b.n == rec.n and np.array_equal(b.t_s, rec.t_s)
    assert b.unit["offset_g"] != rec.unit["offset_g"]  # another unit (offsets drawn within +-40 mg)
    # other noise: in the first rest in the terminal (truly static in both; the bag's orientation and
    # the unit's offsets differ, both constant there, so the mean difference is removed), the
    # difference of two independent 2.23 mg noise streams has a spread of sqrt(2) x 2.23 mg; over the
    # ~60,000 samples of a 10 min rest the estimate is good to 0.3 %, so 5 % is far outside chance
    seg = next(s for s in rec.segments if s.state == "resting")
    sel = rec.sensor_static & b.sensor_static & (rec.t_s >= seg.t0_s) & (rec.t_s < seg.t1_s)
    assert sel.sum() > 10_000
    d = (b.acc_g - rec.acc_g)[sel]
    d -= d.mean(axis=0)
    np.testing.assert_allclose(d.std(axis=0), np.sqrt(2) * 2.23e-3, rtol=0.05)
    # the labels follow the flight and the carrier's timeline, not the sensor's noise
    assert np.array_equal(b.in_flight_window, rec.in_flight_window)
    # the flight's turbulence stream differs (JSBSim's gust seed); that the gusts then differ is
    # tests/sim/test_pattern_flight.py's check
    s1 = pipeline.streams_of(sc.seed).child("flight").integer_seed("turbulence")
    s2 = other.child("flight").integer_seed("turbulence")
    assert s1 != s2
    assert dataclasses.replace(sc, seed=sc.seed + 1).plan == sc.plan  # the seed is not part of the plan


def test_the_digest_hashes_each_arrays_bytes_in_c_order_whatever_its_layout():
    """The digest reads each array's own buffer (no copy), and still hashes SHA-256 over the dtype, the
    shape and the values' bytes in C order, as run.json's truth digest always has: a C-ordered array and
    the same values in Fortran order hash alike, a strided view as its values copied in C order, a
    transposed bool array too; other values change it."""
    import hashlib

    a = np.arange(24.0).reshape(4, 6)
    want = hashlib.sha256(b"float64(4, 6)" + a.tobytes()).hexdigest()
    assert digest(a) == want
    assert digest(np.asfortranarray(a)) == want
    assert digest(np.arange(48.0).reshape(8, 6)[::2]) != want  # rows 0, 2, 4, 6 of 0..47: other values
    view = np.arange(48.0).reshape(4, 12)[:, ::2]
    assert digest(view) == hashlib.sha256(b"float64(4, 6)" + np.ascontiguousarray(view).tobytes()).hexdigest()
    flags = np.array([[True, False], [False, True]])
    assert digest(flags.T) == hashlib.sha256(b"bool(2, 2)" + flags.T.copy().tobytes()).hexdigest()
