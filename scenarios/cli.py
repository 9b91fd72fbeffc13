"""The ``flightmode`` command line (Typer + Rich).

    flightmode scenarios [--spec]                 list the built-in scenarios (or the file spec)
    flightmode fly [SCENARIO] [--seed N] [--out DIR]   fly one gate to gate; default gva-lhr-a320
    flightmode sense RUN_DIR [--sensor P] [--carrier K=V]   re-sense a flight
    flightmode detect RUN_DIR_OR_SAMPLES [--method] [--window-s] [--k] [--time-threshold-s]
                      [--weight] [--tables]       the flight-mode detector's figures

Errors that flightmode raises on purpose (bad scenario, unknown aircraft, failed flight) print one
line on stderr and exit with status 2, with no traceback.
"""

from __future__ import annotations

import dataclasses
import sys
import time
from pathlib import Path
from typing import Annotated, Optional

import typer
from rich.console import Console
from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table
from rich.text import Text

from flightmode.scenarios.registry import DEFAULT_SCENARIO, builtin_names, builtin_path, resolve
from flightmode.scenarios.spec import load_scenario, route_length_m, spec_text
from flightmode.errors import FlightmodeError

app = typer.Typer(
    add_completion=False,
    no_args_is_help=False,
    help="Physics-simulated accelerometer data for a package in an airliner, and its flight-mode detector.",
)
console = Console()
err_console = Console(stderr=True)


def _die(e: Exception) -> None:
    from rich.text import Text

    # user text (scenario paths, [section].key names) must not be read as Rich markup
    err_console.print(Text.assemble(("error:", "bold red"), " ", str(e)), highlight=False, soft_wrap=True)
    raise typer.Exit(code=2)


@app.command("scenarios")
def scenarios_cmd(
    spec: Annotated[bool, typer.Option("--spec", help="Print every section and key a scenario file may hold.")] = False,
) -> None:
    """List the built-in scenarios with a one-line description each."""
    if spec:
        console.print(spec_text(), highlight=False, markup=False)
        return
    table = Table(title="built-in scenarios", show_lines=False)
    table.add_column("name", style="bold")
    table.add_column("aircraft")
    table.add_column("description")
    for name in builtin_names():
        try:
            plan, desc = load_scenario(builtin_path(name))
        except FlightmodeError as e:  # a broken built-in must not hide the others
            table.add_row(name, "?", Text(str(e), style="red"))
            continue
        marker = " (default)" if name == DEFAULT_SCENARIO else ""
        table.add_row(name + marker, plan.aircraft, Text(desc))
    console.print(table)


def _estimate_duration_s(plan) -> float:
    """Rough gate-to-gate duration, only for the progress bar's scale."""
    ground = plan.gate_wait_s + 120.0 + plan.taxi_out.length_m / 8.0 + sum(plan.taxi_out.holds_s)
    ground += plan.taxi_out.lineup_hold_s + plan.taxi_in.length_m / 8.0 + sum(plan.taxi_in.holds_s)
    return ground + route_length_m(plan) / 190.0 + 300.0 + plan.post_shutdown_s


@app.command("fly")
def fly_cmd(
    scenario: Annotated[str, typer.Argument(help="Built-in scenario name or path to a .toml file.")] = DEFAULT_SCENARIO,
    seed: Annotated[Optional[int], typer.Option("--seed", help="Override the scenario's seed.")] = None,
    out: Annotated[Path, typer.Option("--out", help="Output folder; the run goes to OUT/<scenario>-s<seed>/.")] = Path(
        "runs"
    ),
    sensor: Annotated[Optional[str], typer.Option("--sensor", help="Accelerometer preset (default: the scenario's).")] = None,
    gyro: Annotated[bool, typer.Option("--gyro", help="Also record a gyroscope channel.")] = False,
    rrd: Annotated[bool, typer.Option("--rrd/--no-rrd", help="Write recording.rrd (Rerun) beside the Parquet files.")] = True,
) -> None:
    """Fly a scenario gate to gate in JSBSim, sense it, run the detector and the path estimators;
    write truth.parquet, samples.parquet, run.json and recording.rrd."""
    from flightmode.nav.evaluation import path_rows
    from flightmode.scenarios import run_io
    from flightmode.sim.flight.simulate import fly
    from flightmode.sim.flight.flight_metrics import flight_metrics

    try:
        plan, desc, path = resolve(scenario)
        if seed is not None:
            if not 0 <= seed <= 2**31 - 3:
                raise FlightmodeError(f"--seed {seed}: must be between 0 and {2**31 - 3}")
            plan = dataclasses.replace(plan, seed=seed)
        rid = run_io.run_id(plan)
        console.print(Text.assemble((plan.name, "bold"), f" seed {plan.seed}: {desc}"), highlight=False)
        total = _estimate_duration_s(plan)
        t0 = time.perf_counter()
        with run_io.staged_run_dir(out, rid) as stage:
            with Progress(
                TextColumn("[progress.description]{task.description}"),
                BarColumn(),
                TextColumn("{task.fields[sim]}"),
                TimeElapsedColumn(),
                console=console,
                transient=False,
            ) as progress:
                task = progress.add_task("flying", total=total, sim="")

                def on_progress(t_s: float, phase: str) -> None:
                    progress.update(
                        task,
                        completed=min(t_s, total * 0.99),
                        description=f"{phase:>13}",
                        sim=f"{t_s / 60:6.1f} sim-min",
                    )

                track = fly(plan, workdir=stage, progress=on_progress)
                progress.update(task, completed=total, description="parked", sim=f"{track.duration_s / 60:6.1f} sim-min")
            wall = time.perf_counter() - t0
            metrics = flight_metrics(track, plan)
            run_io.write_truth(stage, track)
            rec, sense_wall = _sense(track, plan.extra, plan.seed, sensor, gyro=gyro)
            run_io.write_samples(stage, rec)
            info = run_io.run_info(plan, desc, str(path), track, metrics)
            info["wall_time_s"] = wall
            info["sensor"] = rec.summary() | {"wall_time_s": sense_wall}
            from flightmode.scenarios.detector_report import evaluate_recommended

            evaluation = evaluate_recommended(rec, plan.seed)
            info["detector"] = evaluation.summary() | {"sigma2_from": "bench calibration of the unit"}
            paths = _estimate_paths(track, rec)
            path = path_rows(paths, rec.preset)
            info["path"] = path
            if rrd:
                from flightmode.scenarios.run_view import run_view
                from flightmode.viz.rrd import write_rrd

                t_rrd = time.perf_counter()
                write_rrd(run_view(rid, plan, track, rec, evaluation, paths), stage / "recording.rrd")
                info["rrd_wall_time_s"] = time.perf_counter() - t_rrd
            run_io.write_run_json(stage, info)
        _print_summary(plan, track, metrics, wall)
        _print_sensor(rec)
        _print_detector_line(evaluation)
        _print_path_line(path)
        files = "truth.parquet, samples.parquet, run.json" + (", recording.rrd" if rrd else "")
        console.print(Text.assemble("wrote ", (str(Path(out) / rid), "bold"), f" ({files})"), highlight=False)
        if rrd:
            where = Path(out) / rid / "recording.rrd"
            console.print(Text.assemble("recording: ", (str(where), "bold"), "; open it with: ",
                                        (f"flightmode view {where}", "bold")), highlight=False)
    except FlightmodeError as e:
        _die(e)


def _sense(track, extra: dict, seed: int, sensor: str | None, carrier_changes: dict | None = None,
           gyro: bool = False):
    """Sense a track with the scenario's carrier and sensor (``sensor`` overrides the preset)."""
    import numpy as np

    from flightmode.sim.sensor.accelerometer import get_preset
    from flightmode.sim.sensor.carrier import CarrierSpec
    from flightmode.sim.sensor.sensing import GyroSpec, sense

    sens = dict(extra.get("sensor") or {"preset": "lis302dl-logged16", "odr_hz": None})
    preset = get_preset(sensor or sens["preset"])
    if sens.get("odr_hz") and not sensor:
        preset = dataclasses.replace(preset, odr_hz=float(sens["odr_hz"]))
    carrier = CarrierSpec(**{**(extra.get("carrier") or {}), **(carrier_changes or {})})
    t0 = time.perf_counter()
    # a stream of its own, derived from the scenario seed: re-sensing with another preset or
    # carrier keeps the flight and changes only what it must
    rec = sense(track, carrier, preset, np.random.default_rng([seed, 0x5E45E]), gyro=GyroSpec() if gyro else None)
    return rec, time.perf_counter() - t0


def _estimate_paths(track, rec) -> dict:
    """The seed 002 estimators on this recording, truth-aided (nav.evaluation)."""
    from flightmode.nav.evaluation import estimate_paths
    from flightmode.scenarios.path_report import lever_arm_m

    return estimate_paths(track, rec, lever_arm_m(track, rec.carrier))


def _print_path_line(rows: list[dict]) -> None:
    by = {r["method"].split(" ")[0]: r for r in rows}
    tri, rec = by["tridiagonal"], by["recurrence"]
    console.print(
        f"path from acceleration (truth-aided frames): tridiagonal with the gate positions max error "
        f"{tri['max_m']:,.0f} m; recurrence from the gate final {rec['final_m']:,.0f} m, max {rec['max_m']:,.0f} m "
        "(flightmode path RUN_DIR for the table)",
        highlight=False,
    )


def _print_detector_line(e) -> None:
    resp = "never came back" if e.response_s is None else f"{e.response_s:.1f} s"
    style = "bold red" if e.false_static_count else "bold green"
    console.print(Text.assemble(
        "detector (NMV, 1 s, 4 sigma^2, 4 s): ",
        (f"{e.false_static_count} false-static events in flight", style),
        f" ({e.false_static_s:g} s); response after the flight {resp}; accuracy {e.accuracy:.3f}",
    ), highlight=False)


@app.command("detect")
def detect_cmd(
    source: Annotated[Path, typer.Argument(help="A run folder, or a samples.parquet file.")],
    method: Annotated[str, typer.Option("--method", help="Moving variance: nmv or emv.")] = "nmv",
    window_s: Annotated[float, typer.Option("--window-s", help="Window W_s and check period, s.")] = 1.0,
    k: Annotated[float, typer.Option("--k", help="Amplitude threshold T_sigma = k sigma^2.")] = 4.0,
    time_threshold_s: Annotated[float, typer.Option("--time-threshold-s", help="Time threshold T_th, s.")] = 4.0,
    weight: Annotated[float, typer.Option("--weight", help="EMV weighting factor (1, 5, 10 in the seed).")] = 1.0,
    sigma2_from: Annotated[str, typer.Option("--sigma2-from", help="preset (bench calibration of the unit) or rest (the recording's static samples before the flight).")] = "preset",
    tables: Annotated[bool, typer.Option("--tables", help="Also print the seed's Table 2, 3, 4/5 forms and the Fig. 18 response.")] = False,
) -> None:
    """Run the flight-mode detector over a recording and print how it did against the truth."""
    import numpy as np

    from flightmode.detector.evaluation import evaluate
    from flightmode.detector.flight_mode import DetectorParams
    from flightmode.scenarios import detector_report as dr
    from flightmode.scenarios import run_io

    try:
        cols, info = run_io.read_samples(source)
        t, a = cols["t_s"], cols["acc_g"]
        if info and info.get("sensor"):
            fs = float(info["sensor"]["odr_hz"])
        else:
            fs = 1.0 / float(np.median(np.diff(t[: min(len(t), 10_000)])))
        p = DetectorParams(fs_hz=fs, window_s=window_s, k_sigma=k, time_threshold_s=time_threshold_s,
                           method=method, weight=weight)
        p.validate()
        labels = dr.labels_of(cols)
        seed = int(info["seed"]) if info else 0
        s2, s2_source = dr.calibrate(cols, info, p, sigma2_from, seed)
        title = f"{source}" + (f": {info['sensor']['preset']} at {fs:g} Hz" if info and info.get("sensor") else "")
        console.print(Text(title, style="bold"), highlight=False)
        e = evaluate(t, a, labels, p, s2)
        dr.print_evaluation(console, e, s2_source)
        if tables:
            dr.print_tables(console, t, a, labels, p, s2)
    except FlightmodeError as e:
        _die(e)


@app.command("path")
def path_cmd(
    run_dir: Annotated[Path, typer.Argument(help="A run folder written by `flightmode fly`.")],
    sensors: Annotated[str, typer.Option("--sensors", help="Comma-separated presets to compare; 'run' is the run's own sensor.")] = "run,ideal",
) -> None:
    """Rebuild the bag's path from acceleration (seed 002 cubic splines) and print its errors."""
    from flightmode.scenarios import run_io
    from flightmode.scenarios.path_report import path_rows, print_rows
    from flightmode.sim.sensor.carrier import CarrierSpec

    try:
        track, info = run_io.read_track(run_dir)
        extra = info["plan"].get("extra") or {}
        seed = int(info["seed"])
        run_preset = (info.get("sensor") or {}).get("preset")
        recs = {}
        for name in [s.strip() for s in sensors.split(",") if s.strip()]:
            preset = run_preset if name == "run" else name
            if preset in recs:
                continue
            # re-sensing is deterministic: the run's own preset gives its samples.parquet again,
            # with the carrier timeline (orientations) that the truth-aided frames need
            recs[preset], _ = _sense(track, extra, seed, preset)
        carrier = CarrierSpec(**(extra.get("carrier") or {}))
        rows = path_rows(track, recs, carrier, seed)
        print_rows(console, rows, f"{info['run_id']}: path errors against the truth (bag seat position)")
    except FlightmodeError as e:
        _die(e)


@app.command("view")
def view_cmd(
    source: Annotated[Path, typer.Argument(help="A run folder (its recording.rrd) or an .rrd file.")],
    web: Annotated[bool, typer.Option("--web", help="Serve the web viewer on 127.0.0.1 and print its URL.")] = False,
    port: Annotated[Optional[int], typer.Option("--port", help="Web viewer HTTP port (default: a free one).")] = None,
) -> None:
    """Open a recording in a new Rerun viewer (native), or serve the web viewer on 127.0.0.1."""
    import subprocess

    from flightmode.viz import viewer

    try:
        rrd = viewer.resolve_rrd(source)
        if web:
            cmd, url = viewer.web_command(rrd, port or viewer.free_port(), viewer.free_port())
            console.print(Text.assemble("web viewer (127.0.0.1 only): ", (url, "bold")), highlight=False)
            console.print("Ctrl-C stops it. Rerun's viewer sends anonymous usage analytics unless you run "
                          "`rerun analytics disable`.", highlight=False)
        else:
            cmd = viewer.native_command(rrd)
        proc = subprocess.Popen(cmd)
        try:
            code = proc.wait()
        except KeyboardInterrupt:
            proc.terminate()
            proc.wait(timeout=10)
            return
        if code not in (0, -2, -15, 130):
            raise FlightmodeError(f"the Rerun viewer exited with status {code} ({' '.join(cmd)})")
    except FlightmodeError as e:
        _die(e)


def _print_sensor(rec) -> None:
    s = rec.summary()
    console.print(
        f"sensed with {s['preset']} at {s['odr_hz']:g} Hz: {s['samples']:,} samples over "
        f"{s['duration_s'] / 60:.1f} min ({rec.carrier.kind}, {rec.carrier.placement}); "
        f"truly static {100 * s['static_fraction']:.0f} % of the time, {s['clipped_samples']} clipped samples",
        highlight=False,
    )


@app.command("sense")
def sense_cmd(
    run_dir: Annotated[Path, typer.Argument(help="A run folder written by `flightmode fly`.")],
    sensor: Annotated[Optional[str], typer.Option("--sensor", help="Accelerometer preset.")] = None,
    carrier: Annotated[Optional[list[str]], typer.Option("--carrier", help="KEY=VALUE carrier setting, e.g. placement=hold (repeatable).")] = None,
    out: Annotated[Optional[Path], typer.Option("--out", help="Output folder (default: beside RUN_DIR).")] = None,
    gyro: Annotated[bool, typer.Option("--gyro", help="Also record a gyroscope channel.")] = False,
) -> None:
    """Re-sense an existing flight with another sensor or carrier into a new run folder."""
    from flightmode.scenarios import run_io
    from flightmode.scenarios.spec import SPEC, Key, _check_value

    try:
        track, info = run_io.read_track(run_dir)
        changes = {}
        for item in carrier or []:
            if "=" not in item:
                raise FlightmodeError(f"--carrier {item!r}: write KEY=VALUE, e.g. placement=hold")
            k, v = item.split("=", 1)
            keys = SPEC["carrier"]
            if k not in keys:
                from flightmode.errors import did_you_mean

                raise FlightmodeError(f"--carrier {k}: unknown carrier key{did_you_mean(k, keys)}; keys: {', '.join(keys)}")
            key: Key = keys[k]
            val = v if key.type is str else (int(v) if key.type is int else float(v))
            changes[k] = _check_value("--carrier", k, key, val)
        extra = info["plan"].get("extra") or {}
        rec, wall = _sense(track, extra, int(info["seed"]), sensor, changes, gyro=gyro)
        tag = "-".join([rec.preset] + [f"{k}-{v}" for k, v in sorted(changes.items())])
        rid = f"{info['run_id']}-{tag}"
        with run_io.staged_run_dir(out or Path(run_dir).parent, rid) as stage:
            run_io.write_samples(stage, rec)
            new = dict(info)
            new["run_id"] = rid
            new["truth"] = dict(info["truth"], path=str(Path(run_dir).resolve() / "truth.parquet"))
            new["sensor"] = rec.summary() | {"wall_time_s": wall}
            run_io.write_run_json(stage, new)
        _print_sensor(rec)
        console.print(Text.assemble("wrote ", (str((out or Path(run_dir).parent) / rid), "bold"), " (samples.parquet, run.json)"))
    except (FlightmodeError, ValueError) as e:
        _die(e)


def _print_summary(plan, track, m: dict, wall_s: float) -> None:
    kt = 1.0 / 0.514444
    t = Table(title=f"{plan.name}: {plan.aircraft}, {plan.origin.icao} {plan.origin.name} -> "
              f"{plan.destination.icao} {plan.destination.name}", show_header=False)
    t.add_column("quantity")
    t.add_column("value", justify="right")
    rows = [
        ("gate to gate", f"{m['gate_to_gate_s'] / 60:.1f} min  ({track.n:,} samples at {track.fs_hz:.0f} Hz)"),
        ("taxi-out (pushback to brake release)", f"{m['taxi_out_s'] / 60:.1f} min"),
        ("liftoff speed", f"{m['liftoff_ias_mps'] * kt:.0f} kt IAS"),
        ("mean takeoff acceleration", f"{m['takeoff_accel_mps2']:.2f} m/s^2"),
        ("initial climb rate (to 1500 ft)", f"{m['initial_climb_vs_mps']:.1f} m/s"),
        ("cruise altitude", f"{m['cruise_alt_m']:.0f} m"),
        ("final approach vertical rate", f"{m['final_approach_vs_mps']:.2f} m/s"),
        ("touchdown sink rate", f"{m['touchdown_sink_mps'] / 0.3048 * 60:.0f} ft/min"),
        ("touchdown speed", f"{m['touchdown_ias_mps'] * kt:.0f} kt IAS, {m['touchdown_gs_mps']:.1f} m/s ground"),
        ("touchdown point", f"{m['touchdown_past_threshold_m']:.0f} m past threshold, "
                            f"{m['touchdown_centreline_offset_m']:+.1f} m from centreline"),
        ("rollout deceleration", f"{m['rollout_decel_mps2']:.2f} m/s^2 over {m['rollout_distance_m']:.0f} m"),
        ("taxi-in", f"{m['taxi_in_s'] / 60:.1f} min"),
        ("in-flight window (pushback to engines off)", f"{track.in_flight_window.sum() / track.fs_hz / 60:.1f} min"),
        ("wall time", f"{wall_s:.1f} s ({track.duration_s / wall_s:.0f}x real time)"),
    ]
    for k, v in rows:
        t.add_row(k, v)
    console.print(t)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(app())
