"""The uncertain model parameters (flightmode.scenarios.model): the registry, the [model] table of
scenario and family files, and each parameter acting where its physics says, in the direction it says,
with common random numbers (a parameter moves only what it shapes)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from flightmode.errors import ScenarioError
from flightmode.scenarios.family import Family
from flightmode.scenarios.model import MODULES, check_model, registry, registry_markdown
from flightmode.scenarios.scenario import Scenario
from flightmode.streams import Streams

ROOT = Path(__file__).resolve().parents[2]


# ---------------------------------------------------------------------- the registry
def test_every_parameter_declares_a_source_a_range_a_unit_and_what_it_shapes():
    reg = registry()
    assert len(reg) >= 8  # the seat's and lap's three factors, the idle share, the calm-air scale
    for name, p in reg.items():
        assert p.name == name
        assert p.low < p.high, name  # a range, not a point
        assert p.low <= p.value <= p.high, name
        assert p.unit and p.shapes, name
        # a source names a public document, or says why the range is an assumption
        assert len(p.source) > 20, name


def test_the_parameters_that_decide_the_verdict_are_declared():
    reg = registry()
    for name in (
        "mount.seat.fn_v_scale",
        "mount.seat.fn_h_scale",
        "mount.seat.zeta_scale",
        "mount.lap.fn_v_scale",
        "vibration.engine_idle_share",
        "turbulence.background_scale",
    ):
        assert name in reg
    # the seat cushion's range reaches the 7-17 Hz issue 50 mentions: 3.0-4.5 Hz times the factor
    p = reg["mount.seat.fn_v_scale"]
    assert 3.0 * p.high >= 7.0 and 4.5 * p.high >= 17.0 - 0.2  # 4.5 x 3.8 = 17.1 Hz
    # calm air: today 2-3 times rougher than an A320's recorded cruise, so down to a third
    q = reg["turbulence.background_scale"]
    assert q.low == pytest.approx(0.33) and q.value == q.high == 1.0


def test_a_name_declared_twice_is_an_error(monkeypatch):
    import flightmode.scenarios.model as model

    monkeypatch.setattr(model, "MODULES", (*MODULES, MODULES[0]))
    with pytest.raises(ScenarioError, match="declared twice"):
        model.registry()


def test_docs_modelling_holds_the_current_registry_table():
    # regenerate with: python -c "from flightmode.scenarios.model import registry_markdown as r; print(r())"
    text = (ROOT / "docs" / "modelling.md").read_text(encoding="utf-8")
    assert registry_markdown() in text, "docs/modelling.md's uncertain-parameter table is stale"


# ---------------------------------------------------------------------- the [model] table
def test_a_scenario_reads_writes_and_replaces_its_model_table():
    s = Scenario.builtin("pattern")
    assert s.model == () and s.overrides == {} and "[model]" not in s.to_toml()
    text = s.to_toml() + '\n[model]\n"mount.seat.fn_v_scale" = 3\n"turbulence.background_scale" = 0.5\n'
    s2 = Scenario.from_toml_text(text)
    # sorted pairs, numbers as floats
    assert s2.model == (("mount.seat.fn_v_scale", 3.0), ("turbulence.background_scale", 0.5))
    assert Scenario.from_toml_text(s2.to_toml()) == s2
    assert s2.replace(model={}) == s and s2.replace(model={}).to_toml() == s.to_toml()
    assert s.replace(model={"mount.lap.fn_v_scale": 2.0}).overrides == {"mount.lap.fn_v_scale": 2.0}
    assert s2 != s and s2.digest() != s.digest()  # another model, another scenario


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ({"mount.seat.fn_v_scal": 2.0}, 'unknown model parameter \\(did you mean "mount.seat.fn_v_scale"'),
        ({"mount.seat.fn_v_scale": 9.0}, "outside its declared range 0.67-3.8"),
        ({"mount.seat.fn_v_scale": 0.1}, "outside its declared range"),
        ({"mount.seat.fn_v_scale": "stiff"}, "must be a finite number"),
        ({"mount.seat.fn_v_scale": True}, "must be a finite number"),
        ({"mount.seat.fn_v_scale": float("nan")}, "must be a finite number"),
    ],
)
def test_a_bad_model_table_names_the_file_the_key_and_what_is_allowed(table, message):
    with pytest.raises(ScenarioError, match=message):
        Scenario.builtin("pattern").replace(model=table)
    with pytest.raises(ScenarioError, match="my.toml"):
        check_model(table, "my.toml")


def test_a_model_table_must_be_a_table():
    with pytest.raises(ScenarioError, match="must be a table"):
        check_model(3.0, "x.toml")


def test_a_family_gives_every_member_its_model_table_and_moves_no_draw():
    fam = Family.builtin("regional-hops")
    var = fam.with_model({"mount.seat.fn_v_scale": 3.8})
    assert var.model == (("mount.seat.fn_v_scale", 3.8),) and var.digest() != fam.digest()
    for i in range(6):
        a, b = fam.member(i), var.member(i)
        assert b.overrides == {"mount.seat.fn_v_scale": 3.8}
        assert b.replace(model={}) == a  # the same member, flown with another model
    assert var.with_model({}).model == () and var.with_model({}).member(2) == fam.member(2)
    with pytest.raises(ScenarioError, match="did you mean"):
        Family.from_toml_text(fam.text + '\n[model]\n"vibration.engine_idle_shar" = 0.3\n')


# ---------------------------------------------------------------------- the physics, direction and CRN
def _band_gain(stage, f_hz) -> float:
    """Mean transmissibility over ``f_hz`` of a stage at its range's centre (mount.stage_gain)."""
    from flightmode.sim.sensor.mount import stage_gain

    fv = 0.5 * (stage.fn_v_hz[0] + stage.fn_v_hz[1])
    z = 0.5 * (stage.zeta[0] + stage.zeta[1])
    return float(np.mean(stage_gain(fv, z, f_hz)))


@pytest.mark.parametrize("placement", ["seat", "lap"])
def test_a_stiffer_support_passes_more_of_the_10_to_30_hz_airframe_band(placement):
    from flightmode.sim.sensor.mount import SCALED_SUPPORTS, support_stage

    p = SCALED_SUPPORTS[placement][1]  # its fn_v factor
    f = np.linspace(10.0, 30.0, 201)  # seed 000, Fig. 6: the airframe's peaks
    g = [_band_gain(support_stage(placement, {p.name: k}), f) for k in (p.low, p.value, p.high)]
    # above resonance the transmissibility grows with fn (about 2 zeta fn / f): strictly increasing
    assert g[0] < g[1] < g[2]
    if placement == "seat":  # the firm end resonates inside the band: it amplifies it (gain > 1)
        assert g[2] > 1.0 > g[1]


def test_more_damping_on_a_cushion_passes_more_far_above_its_resonance():
    from flightmode.sim.sensor.mount import SEAT_ZETA_SCALE, support_stage

    f = np.linspace(20.0, 30.0, 101)  # > 4 fn: the gain falls as 2 zeta fn / f, so more zeta passes more
    g = [_band_gain(support_stage("seat", {SEAT_ZETA_SCALE.name: k}), f) for k in (0.5, 1.0, 2.0)]
    assert g[0] < g[1] < g[2]


@pytest.mark.parametrize("placement", ["seat", "lap", "under_seat"])
def test_a_mount_factor_scales_the_same_draw_and_moves_nothing_else(placement):
    from flightmode.sim.sensor.carrier import CarrierSpec
    from flightmode.sim.sensor.mount import SEAT_FN_V_SCALE, draw_mounts

    spec = CarrierSpec(placement=placement)
    nominal = draw_mounts(spec, np.random.default_rng(4))[placement]
    firm = draw_mounts(spec, np.random.default_rng(4), {SEAT_FN_V_SCALE.name: 3.0})[placement]
    fn0, fn1 = nominal.fn_hz.copy(), firm.fn_hz.copy()
    if placement == "seat":
        # common random numbers: the same uniform, a range three times higher; 1e-12 relative is
        # floating-point rounding of low + (high - low) u against 3 (low + (high - low) u)
        assert fn1[0, 2] == pytest.approx(3.0 * fn0[0, 2], rel=1e-12)
        fn1[0, 2] = fn0[0, 2]
    np.testing.assert_array_equal(fn1, fn0)  # the other axes, the packing: bit-identical
    np.testing.assert_array_equal(firm.zeta, nominal.zeta)
    assert firm.cabin_row == nominal.cabin_row


def test_the_calm_air_scale_multiplies_the_drawn_background_and_nothing_else():
    from flightmode.sim.flight.turbulence import BACKGROUND_SCALE, draw_atmosphere

    a = draw_atmosphere(np.random.default_rng(7))
    b = draw_atmosphere(np.random.default_rng(7), overrides={BACKGROUND_SCALE.name: 0.33})
    assert b.edr_mid == pytest.approx(0.33 * a.edr_mid, rel=1e-15)  # one multiplication's rounding
    assert b.edr_upper == pytest.approx(0.33 * a.edr_upper, rel=1e-15)
    assert (b.w20_mps, b.w_star_mps, b.z_i_m, b.patch_edr) == (a.w20_mps, a.w_star_mps, a.z_i_m, a.patch_edr)
    assert draw_atmosphere(np.random.default_rng(7), overrides={BACKGROUND_SCALE.name: 1.0}) == a
    # a scenario's fixed background EDR is used as given
    fixed = draw_atmosphere(
        np.random.default_rng(7), background_edr=0.02, overrides={BACKGROUND_SCALE.name: 0.5}
    )
    assert fixed.edr_mid == fixed.edr_upper == 0.02


def test_the_idle_share_sets_the_floor_at_idle_and_moves_no_draw():
    from flightmode.sim.sensor.vibration import ENGINE_IDLE_SHARE, draw_floor

    a = draw_floor("A320", "mid", np.random.default_rng(3))
    lo = draw_floor("A320", "mid", np.random.default_rng(3), overrides={ENGINE_IDLE_SHARE.name: 0.25})
    hi = draw_floor("A320", "mid", np.random.default_rng(3), overrides={ENGINE_IDLE_SHARE.name: 0.8})
    assert a.as_dict() == lo.as_dict() == hi.as_dict()  # the flight's factors: the same draws
    assert (lo.model.engine_idle_share, a.model.engine_idle_share, hi.model.engine_idle_share) == (
        0.25,
        0.5,
        0.8,
    )
    assert dataclasses.replace(hi.model, engine_idle_share=0.5) == a.model  # nothing else moved


def test_sensor_side_parameters_leave_the_flight_draws_untouched():
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.draws import draw_flight

    sc = Scenario.builtin("pattern")
    prof = get_profile(sc.aircraft)
    nominal = draw_flight(sc.plan, prof, Streams(1).child("flight"))
    for name in ("mount.seat.fn_v_scale", "mount.lap.zeta_scale", "vibration.engine_idle_share"):
        p = registry()[name]
        assert draw_flight(sc.plan, prof, Streams(1).child("flight"), {name: p.high}) == nominal
    moved = draw_flight(sc.plan, prof, Streams(1).child("flight"), {"turbulence.background_scale": 0.5})
    assert moved.atmosphere != nominal.atmosphere and moved.climb_vs_mps == nominal.climb_vs_mps


# ---------------------------------------------------------------------- whole runs (slow: JSBSim)
def _synthetic_profile() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(t_s, alt_m, phase names) of a plain gate-to-gate flight at 1 Hz: 10 min on the ground, a climb
    to 10 km, 15 min of cruise, a descent, the landing and 6 min of taxi in."""
    legs = [  # (phase, duration s, altitude at its end m)
        ("gate", 300, 0.0),
        ("taxi_out", 300, 0.0),
        ("takeoff_roll", 40, 0.0),
        ("climb", 1500, 10_000.0),
        ("cruise", 900, 10_000.0),
        ("descent", 1500, 600.0),
        ("approach", 200, 15.0),
        ("flare", 10, 0.0),
        ("rollout", 40, 0.0),
        ("taxi_in", 360, 0.0),
        ("shutdown", 120, 0.0),
    ]
    alt, phase, h = [], [], 0.0
    for name, dur, end in legs:
        alt.append(np.linspace(h, end, dur, endpoint=False) if end != h else np.full(dur, h))
        phase += [name] * dur
        h = end
    a = np.concatenate(alt)
    return np.arange(a.size, dtype=float), a, np.array(phase)


SYNTHETIC_PROFILE = _synthetic_profile()


@pytest.mark.slow
def test_every_parameter_is_read_and_a_nominal_table_changes_nothing():
    """Every declared parameter, at each end of its range, changes the run it belongs to: the pattern
    flight's draws or pressure truth, what a bag on a seat or a lap records of it, or (a flight-side
    parameter read while flying) the first 10 minutes of the flight itself; and a [model] table of
    every nominal value gives the same bytes as none (the nominal is today's run)."""
    from flightmode.digest import digest
    from flightmode.runs import pipeline
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.cabin import cabin_pressure
    from flightmode.sim.flight.draws import draw_flight
    from flightmode.sim.flight.simulate import pressure_truth

    sc = Scenario.builtin("pattern")
    # the bag boards straight away: the terminal's walks and rests are nothing any parameter shapes
    sc = sc.replace(
        carrier={"terminal_walk_s": 0.0, "terminal_rest_s": 0.0, "gate_walk_s": 0.0, "gate_rest_s": 0.0}
    )
    root = Streams(sc.seed)
    track = pipeline.fly(sc, root.child("flight"))
    prof = get_profile(sc.aircraft)

    def track_digest(tr) -> str:
        return digest(
            tuple(
                getattr(tr, f.name)
                for f in dataclasses.fields(tr)
                if isinstance(getattr(tr, f.name), np.ndarray)
            )
        )

    def prefix(overrides: dict) -> str:  # gate, engine start, the push and the taxi out
        return track_digest(
            pipeline.fly(sc.replace(model=overrides), root.child("flight"), stop_after_s=600.0)
        )

    def parts(overrides: dict):
        """(part, digest) of everything a parameter may change, the cheapest first (a generator: the
        parameters' loop stops at the first part that moved)."""
        draws = draw_flight(sc.plan, prof, root.child("flight"), overrides)
        yield "draws", repr(draws)
        cab = pressure_truth(track, sc.plan, draws, overrides)
        yield "cabin", digest((cab.cabin_pressure_pa, cab.hold_pressure_pa))
        # the cabin of every type's controller on a gate-to-gate profile with a cruise at FL330 (the
        # pattern's circuit barely pressurises; a type-specific parameter acts only on its type)
        for ac in ("A320", "737", "787-8"):
            c = cabin_pressure(*SYNTHETIC_PROFILE, 10_000.0, ac, overrides=overrides)
            yield f"cabin {ac}", digest((c.cabin_pressure_pa, c.hold_pressure_pa))
        for placement in ("seat", "lap"):
            rec = pipeline.sense(
                track,
                dataclasses.replace(sc.carrier, placement=placement),
                sc.sensor,
                root.child("sensor"),
                overrides=overrides,
            )
            yield placement, digest((rec.acc_g, rec.t_s))
        yield "prefix", prefix(overrides)  # 10 minutes flown: 1.5 s, against 0.6 s for each sensing

    base = dict(parts({}))
    reg = registry()
    every_nominal = {n: p.value for n, p in reg.items()}
    assert dict(parts(every_nominal)) == base
    for name, p in reg.items():
        for end in (p.low, p.high):
            if end == p.value:
                continue
            moved = any(d != base[part] for part, d in parts({name: end}))
            assert moved, f"{name} = {end} changed nothing: is it read?"
