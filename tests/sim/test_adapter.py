"""The JSBSim adapter's derived channels: height above ground = altitude - terrain elevation; the
angular acceleration = the rates' forward difference. Its private model copies: none left behind."""

import pytest

from flightmode.sim.flight.jsbsim.adapter import JSBSimAircraft
from flightmode.units import FT_M


@pytest.mark.parametrize("model,n_eng", [("A320", 2), ("737", 2)])
def test_derived_height_above_ground_matches_jsbsims_own(model, n_eng):
    """sim.flight derives agl_m as alt_m minus the terrain elevation instead of reading JSBSim's
    ``position/h-agl-ft`` (three times as costly to read). Over JSBSim's flat terrain the two agree
    to 1 cm plus 10 ppm of the height, from the gear on the ground to cruise height, at two
    elevations and latitudes: measured, JSBSim's differs by 4-6 ppm at 47-60 deg and by nothing at
    the equator, i.e. by 1 - cos(geodetic - geocentric latitude): it measures along the geocentric
    radius, the derived height along the ellipsoid normal (the height above a level terrain)."""
    ac = JSBSimAircraft(model, 1 / 120, n_eng)
    for elev_m, lat, lon in ((430.0, 47.46, 8.55), (1.0, 60.3, 24.9)):
        for agl_ft in (20.0, 500.0, 10_000.0, 35_000.0):
            fdm = ac.fdm
            fdm["ic/lat-geod-deg"], fdm["ic/long-gc-deg"] = lat, lon
            fdm["ic/terrain-elevation-ft"] = elev_m / FT_M
            fdm["ic/h-agl-ft"] = agl_ft
            assert fdm.run_ic()
            for _ in range(3):
                ac.step()
            derived = ac.get("position/h-sl-ft") * FT_M - elev_m
            assert derived == pytest.approx(
                ac.get("position/h-agl-ft") * FT_M, abs=0.01 + 1e-5 * agl_ft * FT_M
            )


@pytest.mark.parametrize("model,n_eng", [("A320", 2), ("737", 2)])
def test_angular_acceleration_is_the_rates_forward_difference(model, n_eng):
    """sim.flight derives the angular acceleration as (rates after a step - rates before) / dt instead
    of reading JSBSim's ``accelerations/[pqr]dot-rad_sec2`` every step: JSBSim integrates the body
    rates with rectangular Euler. Checked here on the aircraft in the air with the controls stepped
    (rates and accelerations of 0.1-1 rad/s^2): the two agree to 1e-6 rad/s^2. The rest is the change
    of the Earth's rate (7.3e-5 rad/s) seen in the turning body axes and rounding, measured at 5e-8
    over a whole flight: 1e-6 is far below the 1e-3-1 rad/s^2 the lever-arm term uses."""
    import numpy as np

    ac = JSBSimAircraft(model, 1 / 120, n_eng)
    assert ac.get("simulation/integrator/rate/rotational") == 1  # rectangular Euler
    fdm = ac.fdm
    fdm["ic/lat-geod-deg"], fdm["ic/long-gc-deg"], fdm["ic/h-agl-ft"] = 47.46, 8.55, 10_000.0
    fdm["ic/vc-kts"] = 250.0
    assert fdm.run_ic()
    rates, acc = [], []
    for k in range(600):
        fdm["fcs/aileron-cmd-norm"] = 0.5 if (k // 60) % 2 else -0.5
        fdm["fcs/elevator-cmd-norm"] = 0.3 if (k // 90) % 2 else -0.3
        fdm["fcs/rudder-cmd-norm"] = 0.2 if (k // 45) % 2 else -0.2
        rates.append([ac.get(f"velocities/{a}-rad_sec") for a in "pqr"])
        acc.append([ac.get(f"accelerations/{a}dot-rad_sec2") for a in "pqr"])
        ac.step()
    rates, acc = np.array(rates), np.array(acc)
    derived = np.diff(rates, axis=0) * 120.0
    assert np.abs(acc[1:-1]).max() > 0.1  # the controls did move the aircraft
    np.testing.assert_allclose(derived[1:], acc[1:-1], rtol=0, atol=1e-6)


def test_a_killed_processs_model_copy_is_removed_by_the_next_aircraft(tmp_path):
    """A process SIGKILLed between its private model copy and the copy's removal leaves the copy; the
    next aircraft made in that folder removes it, and nothing of a running process or of a copy
    younger than STALE_COPY_S (another machine's process sharing the folder may still be loading)."""
    import os
    import subprocess
    import sys
    import time

    from flightmode.sim.flight.jsbsim.adapter import COPY_PREFIX, STALE_COPY_S, JSBSimAircraft

    dead = subprocess.run(
        [sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True
    )
    dead_pid = int(dead.stdout)  # a process that has ended (its id is free)
    old = time.time() - STALE_COPY_S - 60.0

    def copy(pid: int, age_s: float | None, letters: str = "abcd1234"):
        d = tmp_path / f"{COPY_PREFIX}{pid}-{letters}"
        (d / "aircraft" / "A320").mkdir(parents=True)
        if age_s is not None:
            os.utime(d, (age_s, age_s))
        return d

    stale = copy(dead_pid, old)
    young = copy(dead_pid, None, "young567")  # the same ended process's, made just now
    alive = copy(os.getpid(), old)  # this process: running
    other = tmp_path / "not-a-copy"
    other.mkdir()
    os.utime(other, (old, old))
    JSBSimAircraft("A320", 1 / 120, 2, workdir=tmp_path)
    assert not stale.exists()
    assert young.exists() and alive.exists() and other.exists()
    # and the aircraft's own copy is gone once loaded
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([young.name, alive.name, other.name])
