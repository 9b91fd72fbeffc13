"""Pressure in real flights (issue 17 wired): every flight's truth carries its ambient, cabin and hold
pressure; a barometer beside the accelerometer reads the bag's pressure into the samples; the
redundant rule runs in the pipeline, in `detect --method nmv+baro` and on a sweep's grid. The
schedule itself is tested on synthetic profiles in test_cabin.py; here, on JSBSim's flights."""

from __future__ import annotations

import math

import numpy as np
import pytest

from flightmode.errors import ScenarioError
from flightmode.labels import AIRBORNE_PHASES, PHASE_CODE
from flightmode.runs import pipeline
from flightmode.scenarios.scenario import DEFAULT_SCENARIO, Scenario
from flightmode.sim.flight.cabin import cabin_figures, get_cabin_profile
from flightmode.units import HPA_PA

# ISA troposphere (ICAO Doc 7488): T0 288.15 K, lapse 6.5 K/km, exponent g0 M / (R L) = 5.25588
T0_K, LAPSE_KPM, EXPONENT = 288.15, 0.0065, 5.25588


def _station_pa(qnh_hpa: float, elevation_m: float) -> float:
    """The pressure at an airfield from its QNH, by QNH's definition (the ISA law from sea level)."""
    return qnh_hpa * HPA_PA * (1.0 - LAPSE_KPM * elevation_m / T0_K) ** EXPONENT


@pytest.mark.slow  # gva-lhr-a320 gate to gate: the schedule's cruise and its climb and descent
def test_the_default_flight_has_the_pressure_truth_of_its_schedule(fly_cached):
    sc, tr = fly_cached(DEFAULT_SCENARIO)
    prof = get_cabin_profile(sc.aircraft)
    # at the gate the door is open: the cabin is ambient, the airfield's pressure from the drawn QNH
    w = tr.conditions["departure_weather"]
    assert tr.cabin_pressure_pa[0] == tr.ambient_pressure_pa[0]
    # the track's first sample is the aircraft settled on its gear at the stand: its altitude is the
    # field's within a few metres (the CG height), 0.1 hPa per metre near sea level
    assert tr.ambient_pressure_pa[0] == pytest.approx(_station_pa(w["qnh_hpa"], tr.alt_m[0]), abs=0.5)
    f = cabin_figures(
        tr.t_s, tr.alt_m, tr.cabin_altitude_m, tr.cabin_pressure_pa, tr.ambient_pressure_pa, tr.phase_code
    )
    # 14 CFR 25.841(a): at most 8,000 ft of cabin altitude in normal operation
    assert f["max_cabin_altitude_ft"] <= prof.max_cabin_alt_ft + 1.0
    # the A320 cruises at FL360 here: its maximum differential keeps the cabin above 6,000 ft
    assert f["cruise_cabin_altitude_ft"] > 6000.0
    # rates over 10 s in the air within the controller's limits; the outflow valve's lag can exceed a
    # rate limit in altitude by the density ratio across the lag, r tau / H_rho ~ 0.2 % (cabin module)
    assert f["max_cabin_climb_airborne_fpm"] <= prof.climb_rate_fpm * 1.005
    assert f["max_cabin_descent_airborne_fpm"] <= tr.conditions["cabin_descent_rate_fpm"] * 1.005
    # the maximum differential: the schedule holds it, the outflow valve's lag overshoots it by at most
    # its rate times tau (the ambient falls at most ~40 Pa/s in a climb: 200 Pa over 5 s, 0.03 psi);
    # never below ambient by more than the lag's undershoot in the descent (the same bound)
    assert f["max_differential_psi"] <= prof.max_diff_pa(sc.plan.cruise_alt_m) / 6894.757 + 0.03
    assert f["min_differential_psi"] > -0.03
    # the hold of every profiled type is the cabin's pressure vessel
    assert np.array_equal(tr.hold_pressure_pa, tr.cabin_pressure_pa)


def test_weather_is_drawn_per_airport_from_its_own_streams(fly_cached):
    sc, tr = fly_cached("pattern")
    # a pattern lands where it took off: one airport, one weather
    assert tr.conditions["departure_weather"] == tr.conditions["arrival_weather"]
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.flight.draws import draw_flight

    prof = get_profile(sc.aircraft)
    a = draw_flight(sc.plan, prof, pipeline.streams_of(1).child("flight"))
    b = draw_flight(sc.plan, prof, pipeline.streams_of(2).child("flight"))
    assert a.departure_weather != b.departure_weather
    # fixing a QNH in the scenario replaces that draw and leaves every other draw as it was
    fixed = sc.replace(atmosphere={"departure_qnh_hpa": 990.0, "arrival_qnh_hpa": 990.0})
    c = draw_flight(fixed.plan, prof, pipeline.streams_of(1).child("flight"))
    assert (
        c.departure_weather.qnh_hpa == 990.0
        and c.departure_weather.isa_dev_k == a.departure_weather.isa_dev_k
    )
    assert (c.climb_vs_mps, c.touchdown_sink_mps, c.atmosphere) == (
        a.climb_vs_mps,
        a.touchdown_sink_mps,
        a.atmosphere,
    )


@pytest.fixture(scope="module")
def baro_run(fly_cached):
    """The pattern flight sensed with a BMP581 beside the accelerometer, through the whole pipeline."""
    sc, tr = fly_cached("pattern")
    sc = sc.replace(sensor={"baro": "bmp581"})
    return sc, tr, pipeline.run(sc, track=tr, stages=("fly", "sense", "detect"))


def test_the_barometer_reads_the_bag_pressure_at_its_rate(baro_run):
    sc, tr, r = baro_run
    rec = r.recording
    tb, pb = rec.baro_stream
    # 25 Hz read at a 100 Hz accelerometer's rows: a new reading every 4th row, exactly
    assert np.allclose(np.diff(tb), 0.04, atol=1e-9)
    assert rec.baro_new.sum() == tb.shape[0] and np.array_equal(rec.baro_pa[rec.baro_new], pb)
    # the bag's pressure: ambient off board (the terminal), the cabin's when stowed under a seat
    off = rec.bag_state == "carried"
    stowed = rec.bag_state == "stowed"
    assert off.any() and stowed.any()
    t_in = (rec.t_s >= tr.t_s[0]) & (rec.t_s <= tr.t_s[-1])
    cab = np.interp(rec.t_s, tr.t_s, tr.cabin_pressure_pa)
    assert np.allclose(rec.pressure_pa[stowed & t_in], cab[stowed & t_in], rtol=0, atol=1e-6)
    assert np.allclose(
        rec.pressure_pa[off & (rec.t_s < tr.t_s[0])], tr.ambient_pressure_pa[0], rtol=0, atol=1e-9
    )
    # reading minus truth: the unit's offset plus noise of the datasheet's RMS (0.21 Pa at x16) and a
    # 1/64 Pa quantisation (1/64 / sqrt(12) = 0.0045 Pa RMS); n ~ 1e5 readings pin the mean to 0.002 Pa
    err = pb - rec.pressure_pa[rec.baro_new]
    assert err.mean() == pytest.approx(rec.baro["unit"]["offset_pa"], abs=0.01)
    assert err.std() == pytest.approx(math.hypot(0.21, (1 / 64) / math.sqrt(12)), rel=0.02)


def test_the_redundant_rule_in_the_pipeline(baro_run):
    sc, tr, r = baro_run
    red = r.redundant
    acc, comb = red.accel, red.combined
    # the rule's suspension is the accelerometer's OR the pressure's: it can only remove false statics
    # and delay the response (AND to resume)
    assert np.array_equal(acc.checks.t_s, comb.checks.t_s)
    assert not (comb.checks.final_static & ~acc.checks.final_static).any()
    assert comb.false_static_s <= acc.false_static_s
    assert comb.response_s is not None and comb.response_s >= acc.response_s
    # the accelerometer alone is seed 000's recommended detector, as the pipeline's own detection
    assert acc.false_static_count == r.detection.false_static_count
    # the pressure source suspends in the air: every airborne check is suspended by it, or by the
    # accelerometer
    air = np.isin(
        np.asarray(r.recording.phase_code)[acc.checks.index], [PHASE_CODE[p] for p in AIRBORNE_PHASES]
    )
    assert air.any() and not comb.checks.final_static[air].any()


def test_the_sweep_gate_is_the_redundant_rule(baro_run):
    """evaluate_grid with the pressure source as gate gives the redundant rule's evaluation exactly."""
    from flightmode.detector.grid import Grid, evaluate_grid
    from flightmode.detector.pressure import detect_pressure, static_at

    sc, tr, r = baro_run
    rec, red = r.recording, r.redundant
    labels = {
        "in_flight_window": rec.in_flight_window,
        "sensor_static": rec.sensor_static,
        "phase": rec.phase,
    }
    tb, pb = rec.baro_stream
    pc = detect_pressure(tb, pb, red.pressure_params)
    p = r.detection.params
    grid = Grid(((p.method, p.weight),), (p.window_s,), (p.k_sigma,), (p.time_threshold_s,))
    ((_, e),) = evaluate_grid(
        rec.t_s,
        rec.acc_g,
        labels,
        grid,
        rec.odr_hz,
        lambda n: r.detection.sigma2,
        gate=lambda t: static_at(pc, t),
    )
    assert np.array_equal(e.checks.final_static, red.combined.checks.final_static)
    assert (
        e.false_static_events == red.combined.false_static_events and e.response_s == red.combined.response_s
    )


def test_the_cabin_lands_pressurised_and_steps_down_while_taxiing_in(fly_cached):
    # issue 50's "At landing": the cabin level at its landing pressure before touchdown, then one step
    # down to the field's pressure (the pattern is a 737: held through the rollout, vented while
    # taxiing in, 737 FCOM 2.40.5)
    from flightmode.sim.flight.cabin import LANDING_RESIDUAL, VENT_737
    from flightmode.sim.flight.cabin_landing import LEVEL_AHEAD_MIN_S, TOL_PA, landing_figures

    sc, tr = fly_cached("pattern")
    assert sc.aircraft == "737"
    f = landing_figures(tr.t_s, tr.alt_m, tr.cabin_pressure_pa, tr.ambient_pressure_pa, tr.phase_code)
    td = int(np.searchsorted(tr.t_s, f["touchdown_t_s"]))
    flare = tr.phase_code == PHASE_CODE["flare"]
    assert flare.any() and f["level_before_touchdown_s"] >= LEVEL_AHEAD_MIN_S
    # through the final approach and the flare the cabin does not move (a step detector's baseline)
    assert np.ptp(tr.cabin_pressure_pa[flare]) <= TOL_PA
    # the residual over the ambient at the aircraft: the declared 0.1 psi (6.9 hPa) less the air
    # between the runway and the aircraft's reference point (the 737's CG 1.1 m up: 13 Pa; 30 Pa
    # allows the struts' travel at touchdown)
    assert f["residual_psi"] * 6894.757 == pytest.approx(LANDING_RESIDUAL.value * 6894.757, abs=30.0)
    # held through the rollout, vented while taxiing in over the declared time, done before the door
    roll = slice(td, td + int(np.searchsorted(tr.t_s[td:], f["touchdown_t_s"] + f["taxi_in_s"])))
    assert np.ptp(tr.cabin_pressure_pa[roll]) <= TOL_PA
    assert f["taxi_in_s"] <= f["vent_start_s"] < f["vent_complete_s"] < f["door_open_s"]
    assert f["vent_duration_s"] == pytest.approx(VENT_737.value, abs=20.0)  # the ramp, less TOL, plus the lag
    # one step of the residual: what the cabin at touchdown drops to once vented is the field's pressure
    assert f["step_hpa"] * HPA_PA == pytest.approx(f["residual_hpa"] * HPA_PA, abs=30.0)


def test_the_model_table_reaches_the_cabin(fly_cached):
    # a scenario's [model] overrides reach the cabin of the flight flown (issue 50 item 4's parameters)
    from flightmode.sim.flight.cabin_landing import TOL_PA, landing_figures

    sc, tr = fly_cached("pattern", model={"cabin.vent_737_s": 30.0, "cabin.landing_residual_psi": 0.05})
    f = landing_figures(tr.t_s, tr.alt_m, tr.cabin_pressure_pa, tr.ambient_pressure_pa, tr.phase_code)
    # 0.05 psi (3.4 hPa) less the air to the aircraft's CG (13 Pa; 30 Pa: the first test's allowance)
    assert f["residual_psi"] * 6894.757 == pytest.approx(0.05 * 6894.757, abs=30.0)
    # a 30 s ramp: the cabin is within TOL of ambient TOL / residual of it early and starts TOL below
    # its touchdown value up to tau = 5 s late (the lag); the lag settles the end within 9 s
    resid_pa = f["residual_hpa"] * HPA_PA
    assert 30.0 * (1.0 - 2.0 * TOL_PA / resid_pa) - 5.0 <= f["vent_duration_s"] <= 30.0 + 9.0
    assert f["vent_complete_s"] < f["door_open_s"]


def test_an_unpressurised_hold_is_valid_and_changes_the_schedule(fly_cached):
    sc, tr = fly_cached(
        "pattern", cabin={"hold": "unpressurised"}, carrier={"kind": "parcel", "placement": "hold"}
    )
    air = tr.airborne
    assert np.array_equal(tr.hold_pressure_pa, tr.ambient_pressure_pa)
    # in the air the cabin is pressurised above ambient (up to 1.4 psi on this low pattern), the hold is not
    assert (tr.cabin_pressure_pa[air] - tr.hold_pressure_pa[air]).max() > 50 * HPA_PA
    sc = sc.replace(sensor={"baro": "ideal"})
    rec = pipeline.sense(tr, sc.carrier, sc.sensor, pipeline.streams_of(sc.seed).child("sensor"))
    in_hold = rec.bag_state == "in_hold"
    amb = np.interp(rec.t_s, tr.t_s, tr.ambient_pressure_pa)
    assert np.allclose(rec.pressure_pa[in_hold], amb[in_hold], rtol=0, atol=1e-6)


def test_scenario_keys_and_bad_input():
    sc = Scenario.builtin("pattern")
    s2 = sc.replace(
        sensor={"baro": "lps22hh", "baro_odr_hz": 10.0},
        cabin={"hold": "unpressurised"},
        atmosphere={"isa_dev_k": 5.0},
    )
    assert Scenario.from_toml_text(s2.to_toml()) == s2
    bad = [
        ({"sensor": {"baro": "bmp58"}}, "bmp581"),  # misspelt: the nearest preset named
        ({"sensor": {"baro_odr_hz": 25.0}}, "needs [sensor].baro"),
        ({"sensor": {"baro": "lps22hh", "baro_odr_hz": 30.0}}, "has only"),
        ({"cabin": {"hold": "heated"}}, "pressurised"),
        ({"atmosphere": {"departure_qnh_hpa": 800.0}}, ">= 950"),
    ]
    for change, words in bad:
        with pytest.raises(ScenarioError) as e:
            sc.replace(**change)
        assert words in str(e.value) and "\n" not in str(e.value)


def test_detect_cli_nmv_plus_baro_reads_the_run_folder(baro_run, tmp_path):
    from typer.testing import CliRunner

    from flightmode.cli.main import app

    sc, tr, _ = baro_run
    r = pipeline.run(sc, track=tr, out=tmp_path, stages=("fly", "sense", "detect", "write"), rrd=False)
    run_dir = r.written["run_json"].parent
    cli = CliRunner()
    out = cli.invoke(app, ["detect", str(run_dir), "--method", "nmv+baro"], env={"COLUMNS": "200"})
    assert out.exit_code == 0, out.output
    red = r.redundant
    # the file's figures are the run's: the first suspensions and the gate response, to the 0.1 s printed
    fs = red.sources.first_suspend_s
    assert f"accelerometer {fs['accelerometer']:.1f} s, pressure {fs['pressure']:.1f} s" in out.output
    assert f"transmission after {red.sources.resume_s['combined']:.1f} s" in out.output
    # the file gives the run's figures: samples.parquet's barometer is the recording's
    from flightmode.runs.run_io import read_samples

    cols, _ = read_samples(run_dir)
    assert np.array_equal(cols["baro_pa"], r.recording.baro_pa) and np.array_equal(
        cols["baro_new"], r.recording.baro_new
    )
    # typed one-line errors, exit status 2
    for args, words in ((["--baro-rate-pa-s", "-1"], "must be > 0"), (["--baro-margin-hpa", "-3"], ">= 0")):
        bad = cli.invoke(app, ["detect", str(run_dir), "--method", "nmv+baro", *args])
        assert bad.exit_code == 2 and words in bad.output and "Traceback" not in bad.output
    bad = cli.invoke(app, ["detect", str(run_dir), "--method", "nmv+gps"])
    assert bad.exit_code == 2 and "nmv+baro" in bad.output


def test_a_track_missing_part_of_its_pressure_truth_is_a_typed_error(fly_cached):
    """The barometer reads the bag's pressure from all three truths (ambient, cabin, hold): a track
    with the cabin's but not the ambient's is refused with a SensorError naming what is missing (it
    was a TypeError from NumPy)."""
    import dataclasses

    from flightmode.errors import SensorError

    sc, tr = fly_cached("pattern")
    sc = sc.replace(sensor={"baro": "bmp581"})
    with pytest.raises(SensorError, match="no pressure truth"):
        pipeline.run(sc, track=dataclasses.replace(tr, ambient_pressure_pa=None), stages=("fly", "sense"))
