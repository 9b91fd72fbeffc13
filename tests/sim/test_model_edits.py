"""flightmode's edits to the stock JSBSim models (sim.flight.jsbsim.model_edits), other than the gear's."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import numpy as np
import pytest

from flightmode.errors import AircraftError
from flightmode.sim.flight.jsbsim.model_copy import stock_model_xml
from flightmode.sim.flight.jsbsim.model_edits import spread_spoiler_lift_loss


def _model(name: str) -> ET.Element:
    return ET.parse(stock_model_xml(name)).getroot()


def _spoiler_lift_table(root: ET.Element) -> np.ndarray:
    for table in root.iterfind(".//aerodynamics//table"):
        if (table.findtext("independentVar") or "").strip() == "fcs/spoiler-pos-norm":
            return np.array(
                [
                    [float(v) for v in line.split()]
                    for line in table.findtext("tableData").split("\n")
                    if line.strip()
                ]
            )
    raise AssertionError("no spoiler lift table")


def test_the_737_spoilers_lose_their_lift_over_their_whole_travel():
    """The stock 737 loses 40 % of its lift at 10 % of the spoilers' travel; after the edit the same
    40 % is lost at full travel and, linearly, 4 % at 10 % (JSBSim interpolates tables linearly)."""
    stock, root = _spoiler_lift_table(_model("737")), _model("737")
    spread_spoiler_lift_loss(root)
    edited = _spoiler_lift_table(root)
    assert np.interp(0.1, *stock.T) == pytest.approx(0.6, abs=1e-12)
    assert edited[-1].tolist() == pytest.approx([1.0, 0.6], abs=1e-12)
    assert np.interp(0.1, *edited.T) == pytest.approx(0.96, abs=1e-12)
    assert np.interp(0.5, *edited.T) == pytest.approx(0.8, abs=1e-12)


def test_a_model_without_a_spoiler_lift_table_is_refused_by_name():
    # the stock A320 has no lift term for its spoilers: the edit must not pass silently
    with pytest.raises(AircraftError, match="spoiler lift table"):
        spread_spoiler_lift_loss(_model("A320"))


def test_the_737s_load_factor_does_not_drop_when_its_spoilers_open(fly_cached):
    """After the mains touch, the struts take the weight the spoilers take from the wing. Their rebound
    leaves the centre of gravity's load factor at most about 0.15 g under 1 g (30 seeded 737 pattern
    landings with the edit: lowest 0.82 g, median 0.87 g, 0.5 s before to 3 s after the touchdown). The
    stock table's lift loss within 0.06 s let it fall far lower (same 30: median 0.81 g, lowest 0.61 g;
    this flight 0.75 g)."""
    from flightmode.units import G0_MPS2

    sc, tr = fly_cached("pattern")
    assert sc.aircraft == "737"
    t_td = tr.event_time("touchdown")
    near = (tr.t_s >= t_td - 0.5) & (tr.t_s <= t_td + 3.0)
    nz = -tr.specific_force_body_mps2[near, 2] / G0_MPS2
    assert nz.min() > 0.8


def test_the_a320_gets_ground_spoilers_that_take_the_737s_share_of_its_wing_lift():
    """The edit adds a spoiler channel and a lift factor to the stock A320 (which has neither), and
    JSBSim flies it. In the air at 150 kt, 0.3 s after the command the panels are half out (0.6 s over
    their travel, the 737's), and the wing's lift force is the stock table's lift, bilinear in alpha and
    flap angle as JSBSim interpolates it, times 1 - 0.4 x 0.5: computed here from the stock XML's table,
    independently of the edit."""
    from scipy.interpolate import RegularGridInterpolator

    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.jsbsim.adapter import JSBSimAircraft
    from flightmode.sim.flight.jsbsim.model_edits import add_ground_spoilers, edits_for

    root = _model("A320")
    add_ground_spoilers(root)
    lift_axis = root.find(".//aerodynamics/axis[@name='LIFT']")
    assert "aero/function/kCLsp" in [
        p.text for p in lift_axis.find("function[@name='aero/coefficient/CLalpha']/product")
    ]
    # the tail's lift is not the wing's
    assert "aero/function/kCLsp" not in [
        p.text for p in lift_axis.find("function[@name='aero/coefficient/CLDe']/product")
    ]

    rows = _model("A320").find(
        ".//aerodynamics/axis[@name='LIFT']/function[@name='aero/coefficient/CLalpha']//tableData"
    )
    header, *body = [[float(v) for v in line.split()] for line in rows.text.strip().splitlines()]
    flaps_deg, body = np.array(header), np.array(body)  # the first row: the flap angles (columns)
    alpha_rad, cl = body[:, 0], body[:, 1:]
    cl_table = RegularGridInterpolator((alpha_rad, flaps_deg), cl)

    prof = get_profile("A320")
    assert add_ground_spoilers in edits_for(prof)
    ac = JSBSimAircraft("A320", 1.0 / 120.0, prof.n_engines, edits=edits_for(prof))
    for prop, value in (("ic/h-sl-ft", 5000.0), ("ic/vc-kts", 150.0), ("ic/gamma-deg", 0.0)):
        ac.fdm[prop] = value
    ac.fdm.run_ic()

    def wing_lift_share() -> float:  # the lift force over the stock table's (qbar S CL)
        expected = (
            ac.get("aero/qbar-psf")
            * ac.get("metrics/Sw-sqft")
            * cl_table([[ac.get("aero/alpha-rad"), ac.get("fcs/flap-pos-deg")]])[0]
        )
        return ac.get("aero/coefficient/CLalpha") / expected

    ac.step()
    assert wing_lift_share() == pytest.approx(1.0, abs=1e-9)
    ac.set("fcs/spoiler-cmd-norm", 1.0)
    for _ in range(36):  # 0.3 s
        ac.step()
    assert ac.get("fcs/spoiler-pos-norm") == pytest.approx(0.5, abs=1e-9)
    assert wing_lift_share() == pytest.approx(0.8, abs=1e-9)


def test_a_model_that_has_spoilers_is_not_given_a_second_set():
    from flightmode.sim.flight.jsbsim.model_edits import add_ground_spoilers

    with pytest.raises(AircraftError, match="already has spoilers"):
        add_ground_spoilers(_model("737"))
    twice = _model("A320")
    add_ground_spoilers(twice)
    with pytest.raises(AircraftError, match="already has spoilers"):
        add_ground_spoilers(twice)


def test_the_a320s_nose_is_flown_down_not_let_fall(fly_cached):
    """After the mains touch, the A320 lowers its nose no faster than 4.7 deg/s. On 30 seeded A320 pattern
    landings the fastest nose-down pitch rate was 4.9-6.4 deg/s before the ground spoilers and the
    kept elevator (its wing held the weight and its elevator stepped back at touchdown), and 2.7-4.5
    deg/s after; 4.7 lies between the two populations. The pitch rate is averaged over 0.25 s (the
    gear's bounce on the runway's roughness is faster)."""
    sc, tr = fly_cached("pattern", aircraft="A320")
    t_td = tr.event_time("touchdown")
    w = int(0.25 * tr.fs_hz)
    q_dps = np.degrees(np.convolve(tr.rates_radps[:, 1], np.ones(w) / w, mode="same"))
    after = (tr.t_s >= t_td) & (tr.t_s <= t_td + 8.0)
    assert q_dps[after].min() > -4.7
    # and the nose is down (below 1.5 deg, the rollout's nose-wheel test) 4.3-4.9 s after the mains on
    # those 30 landings (4.0-4.3 s before): 3-6 s
    theta_deg = np.degrees(tr.euler_rad[:, 1])
    t_nose = tr.t_s[after][np.argmax(theta_deg[after] < 1.5)] - t_td
    assert 3.0 <= t_nose <= 6.0


def test_the_a320_rotates_smoothly(fly_cached):
    """The rotation's elevator bias is ramped in over pilot.takeoff.ROTATE_RAMP_S. Applied at once it
    pitched the A320 up at 13.6-17.3 deg/s^2 on 3 seeded pattern takeoffs (instantaneous; this flight
    13.0 averaged over 0.1 s), 0.36-0.42 g at the cockpit (40 % of the length ahead of the CG);
    ramped, 5.7-6.7 deg/s^2 and 0.22-0.29 g (this flight 5.6 and 0.21). A smooth rotation toward
    2-3 deg/s of pitch rate (Airbus A320 FCTM) builds it in about a second: 10 deg/s^2 lies between
    the two populations, and the cockpit stays inside NASA's 0.4 g (Morris and Hall 1965). Averaged
    over 0.1 s: the gear's bounce on the runway is faster."""
    from flightmode.sim.flight.aircraft.registry import get_profile

    sc, tr = fly_cached("pattern", aircraft="A320")
    t_r, t_lo = tr.event_time("rotate"), tr.event_time("liftoff")
    sel = (tr.t_s >= t_r - 1.0) & (tr.t_s <= t_lo + 2.0)
    w = int(0.1 * tr.fs_hz)
    qdot_dps2 = np.degrees(np.convolve(tr.ang_acc_radps2[:, 1], np.ones(w) / w, mode="same"))
    assert qdot_dps2[sel].max() < 10.0
    cockpit = (0.4 * get_profile("A320").length_m, 0.0, 0.0)
    nz = -tr.specific_force_at(cockpit)[sel, 2] / 9.80665
    assert np.abs(nz - np.median(nz)).max() < 0.4


def test_the_a320s_nose_tyre_gets_the_other_models_side_force_peak():
    """JSBSim takes a tyre's side-force peak from its contact's static_friction. The edit sets the
    A320's nose tyre to 0.8, the stock 737's and Fokker 100's, and leaves the other contacts as they
    were (0.5: the mains' grip is not what turns the aircraft)."""
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.jsbsim.gear import nose_gear
    from flightmode.sim.flight.jsbsim.model_edits import edits_for

    root = _model("A320")
    before = {
        c.get("name"): c.findtext("static_friction").strip()
        for c in root.iterfind("ground_reactions/contact")
    }
    for edit in edits_for(get_profile("A320")):
        edit(root)
    nose = nose_gear(root)
    assert float(nose.findtext("static_friction")) == 0.8
    for c in root.iterfind("ground_reactions/contact"):
        if c is not nose:
            assert c.findtext("static_friction").strip() == before[c.get("name")]
    for model in ("737", "fokker100"):
        assert float(nose_gear(_model(model)).findtext("static_friction")) == 0.8


def test_the_a320s_nose_wheel_turns_it_briskly(fly_cached):
    """With the stock 0.5 side-force peak the A320's nose wheel built the yaw rate at 1.82-2.08
    deg/s^2 at most on 6 seeded pattern taxis (0.5 s means), so its turns had to be flown at 5-7 deg/s;
    with 0.8, 2.22-3.93 deg/s^2 (this flight 3.93; 1.82 before). 2.15 lies between the two."""
    sc, tr = fly_cached("pattern", aircraft="A320")
    taxi = np.isin(tr.phase, ["taxi_out", "taxi_in"])
    w = int(0.5 * tr.fs_hz)
    r_acc_dps2 = np.degrees(np.convolve(tr.ang_acc_radps2[:, 2], np.ones(w) / w, mode="same"))
    assert np.abs(r_acc_dps2[taxi]).max() > 2.15


@pytest.mark.parametrize("model", ["737", "A320", "787-8", "fokker100"])
def test_the_first_ground_contact_is_the_nose_gear(model):
    """The rollout reads the nose wheels' weight-on-wheels as JSBSim's gear/unit[0] (pilot.rollout.NOSE_WOW):
    JSBSim numbers the contacts in the order of the model file, so the first must be the nose gear (the
    model's one steerable contact, gear.nose_gear) in every profiled model."""
    from flightmode.sim.flight.jsbsim.gear import nose_gear

    root = _model(model)
    assert root.find("ground_reactions/contact") is nose_gear(root)


# a 787-8 landing without the 7-hour flight before it: the pattern's (seed 65, the gusty approach of
# test_flare_law, whose flight it shares in the full tier); the nose's derotation and the cockpit's
# runway loads are the landing's and the ground's, not the route's
PATTERN_787 = {"seed": 65, "aircraft": "787-8", "takeoff.thrust_norm": None}


def test_the_787s_nose_is_flown_onto_the_runway(fly_cached):
    """The rollout flies the nose down until its wheels carry weight. Before, it pushed the nose down
    (elevator 0.2) once the pitch fell below 0.5 deg, but the 787-8's nose wheels meet the runway at
    -0.4 deg: on lhr-jfk-787 the nose then fell at 3.8 deg/s and hit with a 1.68 g increment at the
    cockpit (40 % of the length ahead of the CG; 1.3-1.9 g from the mains' touch on, on six seeded 787
    pattern landings), then 0.55 g (0.67 g since the softer nose strut; 0.84 g on this pattern
    landing, the gustiest of them). 1.0 g lies between the two.
    From 1 s after the mains touch (their own impact is the touchdown checks') to 8 s (validate's
    rollout roughness window starts there); the increment is validate's (quasi-static part below
    0.2 Hz removed)."""
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.studies.validate import vertical_increment_g

    sc, tr = fly_cached("pattern", **PATTERN_787)
    t_td = tr.event_time("touchdown")
    dn = vertical_increment_g(tr, (0.4 * get_profile("787-8").length_m, 0.0, 0.0))
    sel = (tr.t_s >= t_td + 1.0) & (tr.t_s <= t_td + 8.0)
    assert np.abs(dn[sel]).max() < 1.0


def test_the_787s_nose_strut_is_softened_at_its_stock_stance():
    """gear.set_nose_strut: the spring gives the profile's static deflection under the nose's share of
    the reference landing weight, and the contact point moves down by the deflection added, so at
    that weight the nose stands where the stock strut held it (the stock 160,000 lbf/ft sits 5 cm
    down under it)."""
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.jsbsim.gear import MAIN_SHARE, nose_gear
    from flightmode.sim.flight.jsbsim.model_edits import edits_for
    from flightmode.units import FT_M, G0_MPS2, LBF_N

    prof = get_profile("787-8")
    stock = _model("787-8")
    root = _model("787-8")
    for edit in edits_for(prof):
        edit(root)
    load_lbf = prof.ref_landing_mass_kg * (1.0 - MAIN_SHARE) * G0_MPS2 / LBF_N
    k_stock, k = (float(nose_gear(r).findtext("spring_coeff")) for r in (stock, root))
    z_stock, z = (float(nose_gear(r).findtext("location/z")) for r in (stock, root))  # inches
    assert k_stock == 160_000.0
    # the file holds k to 0.001 lbf/ft (of about 35,000) and z to 1e-5 in
    assert load_lbf / k * FT_M == pytest.approx(prof.nose_static_deflection_m, rel=1e-7)
    # at rest the contact point sits its static compression below the ground (JSBSim's structural z
    # points up), so the airframe's height there is -(z + compression): the same before and after
    assert z + load_lbf / k * 12.0 == pytest.approx(z_stock + load_lbf / k_stock * 12.0, abs=1e-4)
    assert z < z_stock - 7.0  # 0.25 m - 5 cm lower: about 7.8 in
    for model in ("737", "A320", "fokker100"):  # the others keep their stock nose spring
        r = _model(model)
        before = nose_gear(r).findtext("spring_coeff")
        for edit in edits_for(get_profile(model)):
            edit(r)
        assert nose_gear(r).findtext("spring_coeff") == before


def test_the_787s_cockpit_stays_within_nasas_runway_bound(fly_cached):
    """NASA's criterion for an acceptable runway (Morris and Hall 1965): the cockpit within +-0.4 g. On
    ISO 8608 class A runways and taxiways, the stock nose strut gave lhr-jfk-787 a cockpit peak of
    0.46 g (0.40-0.52 g, p5-p95, over 20 route flights); the softer strut gives it 0.20 g (0.17-0.29 g
    on 4 seeded pattern flights; 0.25 g on this one). Validate's own check (the takeoff roll, the
    rollout, taxiing: the same runways and taxiways on the pattern as on a route)."""
    from flightmode.studies.validate import ground_checks

    _, tr = fly_cached("pattern", **PATTERN_787)
    check = next(c for c in ground_checks(tr) if c.figure.startswith("cockpit peak"))
    assert check.passed, check
    assert check.value < 0.3


@pytest.mark.parametrize("model", ["fokker100", "787-8"])
def test_wing_tip_contacts_sit_at_the_wing_tips(model):
    """The stock Fokker 100's wing STRUCTURE contacts are 1,105.4 in either side, its whole span (92.13 ft
    = 1,105.6 in) rather than half of it; the edit moves them to the tip, 552.78 in (exact arithmetic:
    0.01 in, the value's printed precision). The 787-8's sit at 1,173.5 in against its 1,152 in half span
    (2 % outside, its model's rounded 192 ft span): left as they are."""
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.jsbsim.model_edits import edits_for

    root = _model(model)
    before = {
        c.get("name"): float(c.findtext("location/y"))
        for c in root.iterfind("ground_reactions/contact[@type='STRUCTURE']")
    }
    assert before, f"{model}: no STRUCTURE contacts to check"
    half_in = float(root.findtext("metrics/wingspan")) * 6.0
    for edit in edits_for(get_profile(model)):
        edit(root)
    after = {
        c.get("name"): float(c.findtext("location/y"))
        for c in root.iterfind("ground_reactions/contact[@type='STRUCTURE']")
    }
    for name, y in before.items():
        if abs(y) > 1.05 * half_in:
            assert after[name] == pytest.approx(np.copysign(half_in, y), abs=0.01)
        else:
            assert after[name] == y
    if model == "fokker100":
        assert after["LEFT_WING"] == pytest.approx(-552.78, abs=0.01) and after[
            "RIGHT_WING"
        ] == pytest.approx(552.78, abs=0.01)
