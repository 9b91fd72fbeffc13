"""Runway roughness (flightmode.sim.flight.runway_roughness, flightmode.sim.flight.jsbsim.roughness and
roughness_model): the ISO 8608 profile, the isotropic track
coherence, determinism, JSBSim's external-force conventions, and what a flight feels.

Welch spread: with Hann windows overlapping by half, each bin of a Welch estimate from K segments is
a chi-square variable of nu = 2K / (1 + 2 c^2) degrees of freedom, c = 0.167 the overlap correlation
(Welch, IEEE Trans. Audio Electroacoust. 15(2), 1967), so its relative standard deviation is
sqrt(2 / nu); a Hann window makes neighbouring bins dependent, so an octave of m bins averages about
m / 2 independent ones. The tests allow 5 of those standard deviations per octave (over 60 seeds the
octave means spread by 1.1 of them, at most 4.3).
"""

from __future__ import annotations

import math
from itertools import pairwise

import numpy as np
import pytest
from scipy.signal import csd, welch

from flightmode.errors import AircraftError, ScenarioError
from flightmode.sim.flight import runway_roughness as P
from flightmode.sim.flight.jsbsim import roughness as R
from flightmode.sim.flight.jsbsim import roughness_model as M
from flightmode.studies.validate import ground_roughness_g
from flightmode.units import FT_M, LBF_N

N_LONG = 2**18  # 26 km of profile: 127 Welch segments of 410 m
NPERSEG = 4096
OCTAVES = 0.02 * 2.0 ** np.arange(7)  # 0.02-1.28 cycle/m: inside the 1/120-2 cycle/m band, clear of its edges


def _welch_sigma(n_bins: int, n_samples: int = N_LONG, nperseg: int = NPERSEG) -> float:
    k = 2 * n_samples // nperseg - 1
    nu = 2 * k / (1 + 2 * 0.167**2)
    return math.sqrt(2 / nu) / math.sqrt(n_bins / 2)


def test_classes_follow_iso_8608_table_c2():
    assert P.ISO_8608_GD_N0_M3["A"] == pytest.approx(16e-6, rel=1e-12)
    assert P.ISO_8608_GD_N0_M3["B"] == pytest.approx(64e-6, rel=1e-12)
    assert P.ISO_8608_GD_N0_M3["H"] == pytest.approx(262144e-6, rel=1e-12)
    # Gd(n0) at n0 = 0.1 cycle/m, falling as n^-2 (w = 2)
    assert P.displacement_psd_m3(0.1, 16e-6) == pytest.approx(16e-6)
    assert P.displacement_psd_m3(0.2, 16e-6) == pytest.approx(4e-6)
    assert P.RunwayRoughness("A", "roughness/x").gd_n0_m3 == 16e-6
    with pytest.raises(ScenarioError, match="ISO 8608 classes are A, B"):
        P.RunwayRoughness("Z", "roughness/x")


def test_track_coherence_is_z_k1_z():
    from scipy.special import k1

    n = np.logspace(-4, 1, 400)
    for d in (0.5, 3.7, 7.3):
        z = 2 * math.pi * n * d
        assert np.allclose(P.track_coherence(n, d), z * k1(z), atol=1e-7, rtol=0)
    assert P.track_coherence(np.array([0.0, 0.3]), 0.0).tolist() == [1.0, 1.0]


@pytest.mark.parametrize("iso_class", ["A", "C"])
def test_profile_psd_matches_the_class(iso_class):
    gd = P.ISO_8608_GD_N0_M3[iso_class]
    tracks = P.synthesize_tracks(gd, np.random.default_rng(11), 7.3, n_samples=N_LONG)
    f, p = welch(tracks, fs=1 / P.DX_M, nperseg=NPERSEG, axis=-1)
    for lo, hi in pairwise(OCTAVES):
        sel = (f >= lo) & (f < hi)
        ratio = (p[:, sel] / P.displacement_psd_m3(f[sel], gd)).mean(axis=1)  # nose, left, right
        tol = 5 * _welch_sigma(int(sel.sum()))
        assert np.all(np.abs(ratio - 1) < tol), (lo, hi, ratio, tol)
    # nothing outside the band: below 1/120 and above 2 cycle/m the estimate is leakage only
    assert p[:, (f > 3.0)].max() < 1e-3 * P.displacement_psd_m3(2.0, gd)
    # zero mean, and the variance of the band: Gd(n0) n0^2 (1/n_lo - 1/n_hi)
    assert np.abs(tracks.mean(axis=1)).max() < 1e-12
    var = gd * P.ISO_8608_N0**2 * (P.BAND_M[1] - P.BAND_M[0])
    assert np.allclose(tracks.var(axis=1), var, rtol=0.25)


def test_tracks_are_lines_of_one_isotropic_surface():
    track = 2.0  # narrow, so that the coherence spans several octaves
    tracks = P.synthesize_tracks(16e-6, np.random.default_rng(5), track, n_samples=N_LONG)
    k = 2 * N_LONG // NPERSEG - 1
    for a, b, d in ((1, 2, track), (0, 1, track / 2), (0, 2, track / 2)):
        f, pab = csd(tracks[a], tracks[b], fs=1 / P.DX_M, nperseg=NPERSEG)
        _, paa = welch(tracks[a], fs=1 / P.DX_M, nperseg=NPERSEG)
        _, pbb = welch(tracks[b], fs=1 / P.DX_M, nperseg=NPERSEG)
        for lo, hi in pairwise(OCTAVES):
            sel = (f >= lo) & (f < hi)
            rho_hat = (pab.real[sel] / np.sqrt(paa[sel] * pbb[sel])).mean()
            rho = P.track_coherence(f[sel], d).mean()
            # coherency estimate: standard deviation about (1 - rho^2) / sqrt(K) per bin
            tol = 4 * (1 - rho**2) / math.sqrt(k * sel.sum() / 2) + 1e-3
            assert abs(rho_hat - rho) < tol, (a, b, lo, rho_hat, rho, tol)


def test_same_generator_same_profile():
    a = P.synthesize_tracks(16e-6, np.random.default_rng(3), 7.3)
    b = P.synthesize_tracks(16e-6, np.random.default_rng(3), 7.3)
    c = P.synthesize_tracks(16e-6, np.random.default_rng(4), 7.3)
    assert np.array_equal(a, b)
    assert not np.allclose(a, c)
    assert a.shape == (3, P.PERIOD_SAMPLES)


def _parked(model: str = "737"):
    from flightmode.sim.flight.jsbsim.adapter import JSBSimAircraft

    ac = JSBSimAircraft(model, 1 / 120, 2)
    ac.init_on_ground(46.0, 6.0, 400.0, 0.0)
    for _ in range(960):
        ac.step()
    return ac


@pytest.mark.parametrize("model", ["A320", "737", "fokker100", "787-8"])
def test_gear_groups_of_the_stock_models(model):
    import xml.etree.ElementTree as ET

    from flightmode.sim.flight.jsbsim.model_copy import stock_model_xml

    root = ET.parse(stock_model_xml(model)).getroot()
    g = M.gear_groups(root)
    assert g["nose"]["x"] < g["left"]["x"] - 10.0  # structural x runs aft: the nose wheel is metres ahead
    assert g["left"]["y"] < 0 < g["right"]["y"]
    assert g["left"]["spring"] == g["right"]["spring"] > 0
    names = [c.get("name") for c in root.find("ground_reactions").findall("contact")]
    for grp in g.values():
        for u in grp["units"]:  # the A320's BOGEY bumpers (tail, engines, wingtips) are not gear
            assert not any(s in names[u].upper() for s in ("TAIL", "ENG", "WING", "NOSE_T"))


def test_gear_groups_need_a_gear():
    import xml.etree.ElementTree as ET

    with pytest.raises(AircraftError, match="no BOGEY"):
        M.gear_groups(ET.fromstring("<fdm_config><ground_reactions/></fdm_config>"))


def test_a_constant_force_moves_the_gear_reaction_by_that_much():
    """JSBSim's conventions: a LOCAL-frame force of direction (0, 0, -1) and magnitude F (lbf) pushes
    up (body z is down, so forces/fbz-external-lbs = -F), at its location (metres, structural frame),
    and the gear carries F less: on a parked aircraft the gear reaction changes by exactly F and the
    left main's strut extends by F / k."""
    ac = _parked()
    dt = 1 / 120
    gear0 = ac.get("forces/fbz-gear-lbs")
    comp0 = ac.get("gear/unit[1]/compression-ft")
    assert ac.get("forces/fbz-external-lbs") == 0.0
    force_lbf = 5000.0
    ac.set("roughness/knot-sec", 1e6)  # u stays ~0 for the test
    ac.set("roughness/t0-sec", ac.get("simulation/sim-time-sec") + dt)
    for j in range(M.RING):
        ac.set(f"roughness/left/f{j}-lbf", force_lbf)
    ac.set("roughness/active", 1.0)
    for _ in range(1200):
        ac.step()
    assert ac.get("roughness/left/force-lbf") == pytest.approx(force_lbf, rel=1e-6)
    assert ac.get("forces/fbz-external-lbs") == pytest.approx(-force_lbf, rel=2e-3)  # cos(pitch)
    assert ac.get("forces/fbz-gear-lbs") - gear0 == pytest.approx(force_lbf, rel=2e-3)
    k_ft = ac.get("roughness/left/spring") / LBF_N * FT_M  # lbf per ft
    assert comp0 - ac.get("gear/unit[1]/compression-ft") == pytest.approx(force_lbf / k_ft, rel=0.05)
    ac.set("roughness/active", 0.0)
    ac.step()
    assert ac.get("forces/fbz-external-lbs") == 0.0


def test_knots_are_interpolated_at_every_step_round_the_ring():
    """The knot at u = 0 acts at the first step after the tick (JSBSim advances its clock before it
    computes external forces, so t0 = now + dt), then linearly to the next knots, and from the
    ring's last slot round to its first."""
    ac = _parked()
    dt = 1 / 120
    for j in range(M.RING):
        ac.set(f"roughness/nose/f{j}-lbf", 100.0 * j)
    ac.set("roughness/knot-sec", 2 * dt)
    ac.set("roughness/t0-sec", ac.get("simulation/sim-time-sec") + dt)
    ac.set("roughness/active", 1.0)
    seen = []
    for _ in range(2 * M.RING + 4):
        ac.step()
        seen.append(ac.get("roughness/nose/force-lbf"))
    ramp = [50.0 * i for i in range(2 * M.RING - 2)]  # 0 .. 100 (RING - 1) in half-knot steps
    last = 100.0 * (M.RING - 1)
    assert seen == pytest.approx(ramp + [last, last / 2, 0.0, 50.0, 100.0, 150.0], abs=1e-6)


def test_no_force_off_the_ground():
    from flightmode.sim.flight.jsbsim.adapter import JSBSimAircraft

    ac = JSBSimAircraft("737", 1 / 120, 2)
    fdm = ac.fdm
    fdm["ic/h-agl-ft"] = 3000.0
    fdm["ic/u-fps"] = 400.0
    fdm.run_ic()
    ac.set("roughness/knot-sec", 1e6)
    ac.set("roughness/t0-sec", ac.get("simulation/sim-time-sec"))
    for g in R.GROUPS:
        ac.set(f"roughness/{g}/f0-lbf", 5000.0)
    ac.set("roughness/active", 1.0)
    ac.step()
    assert ac.get("forces/fbz-external-lbs") == 0.0
    assert [ac.get(f"roughness/{g}/force-lbf") for g in R.GROUPS] == [0.0, 0.0, 0.0]


def test_stream_profiles_are_deterministic_and_lazy():
    from flightmode.streams import Streams

    a, b = R.GearRoughness(_parked(), Streams(7), 120.0), R.GearRoughness(_parked(), Streams(7), 120.0)
    assert not a._profiles  # made when first rolled on
    pa, pb = a.profile("origin/runway"), b.profile("origin/runway")
    assert pa.h[1] == pb.h[1] and pa.c[2] == pb.c[2]
    assert a.profile("destination/runway").h[1] != pa.h[1]  # one stream per surface
    assert 0.02 < a.tau_s[1] < 0.2  # the main tyre's lag: a few Hz


def test_a_stopped_aircraft_rocking_on_its_struts_comes_to_rest_on_its_own_gear():
    """Rolling at 1 m/s the wheels feel the profile. Stopped, an aircraft still rocks on its struts at
    a few mm/s: that must not creep the wheels along the profile, and the force left by the last
    bumps decays with the datum's lag (R.DATUM_TAU_S), so that the struts carry the aircraft at the
    stand. (A fixed datum once left thousands of lbf on one strut there, and JSBSim's contact rocked at
    2.6 Hz, 0.025 g, with the engines off.) After 30 s, 15 lags, e^-15 = 3e-7 of a force of thousands
    of lbf is left: under 0.01 lbf."""
    from flightmode.streams import Streams

    ac = _parked()
    rough = R.GearRoughness(ac, Streams(7), 120.0)
    x = np.zeros(len(ac.index))
    x[ac.index["wow"]] = 1.0

    def ticks(v_mps, n):  # 40 Hz ticks (every 3 steps at 120 Hz): the ring's knots after each
        out = []
        for k in range(n):
            x[ac.index["v_north_mps"]] = v_mps if v_mps >= 1.0 else v_mps * (-1.0) ** k  # rolling, or rocking
            rough.tick(x, "parked", 3)
            out.append([ac.get(f"roughness/{g}/f{j}-lbf") for g in R.GROUPS for j in range(M.RING)])
        return np.array(out)

    rolling = ticks(1.0, 160)  # 4 m of taxiway: 40 profile samples under each wheel
    assert np.ptp(rolling[:, M.RING :], axis=0).min() > 1.0  # lbf: the mains feel it
    rocking = ticks(0.005, 1200)  # 30 s at +-5 mm/s
    assert np.abs(rocking[-1]).max() < 0.01
    # no bump felt while rocking: once the tyre's lag has settled (1 s, > 5 of its tau < 0.2 s), each
    # group's force only decays towards 0, never a step away from it
    last = rocking[40 :: M.RING, M.RING - 1 :: M.RING]  # one slot per group, rewritten every RING ticks
    assert np.all(np.diff(np.abs(last), axis=0) <= 1e-9)


# --------------------------------------------------------------------------- on a flown flight
# the vertical increments and ground windows are validate's (ground_roughness_g): the takeoff roll to
# the rotation, the rollout from 8 s after touchdown, taxiing above walking pace
def test_the_runway_roll_is_the_roughest_ground_phase(fly_cached):
    """RMS vertical load factor at the CG: the takeoff roll and the rollout (40-80 m/s) shake more
    than taxiing (5-10 m/s) on the same class of surface, and stay at a few hundredths of g, as on a
    good runway (module docstring of flightmode.sim.flight.jsbsim.roughness)."""
    _, tr = fly_cached("pattern")
    rms = {name: float(np.sqrt(np.mean(dn**2))) for name, dn in ground_roughness_g(tr).items()}
    assert rms["takeoff_roll"] > 1.5 * rms["taxi"] and rms["rollout"] > 1.5 * rms["taxi"], rms
    for name in ("takeoff_roll", "rollout"):
        assert 0.005 < rms[name] < 0.06, rms
    assert rms["taxi"] > 0.002, rms  # taxiways are not glass either


def test_cockpit_stays_within_the_nasa_criterion(fly_cached):
    """NASA (Morris and Hall, 1965): a runway is acceptable while the cockpit's vertical acceleration
    stays within +-0.4 g. The pilot's seat is taken 40 % of the fuselage ahead of the CG."""
    from flightmode.sim.flight.aircraft.registry import get_profile

    _, tr = fly_cached("pattern")
    cockpit = (0.4 * get_profile(tr.aircraft).length_m, 0.0, 0.0)
    dn_ck, dn_cg = ground_roughness_g(tr, cockpit), ground_roughness_g(tr)
    for name in dn_cg:
        assert np.abs(dn_ck[name]).max() < 0.4, name
        assert np.abs(dn_cg[name]).max() < 0.4, name
