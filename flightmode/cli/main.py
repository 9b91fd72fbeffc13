"""The ``flightmode`` command line (Typer + Rich): a thin shell over the library
(:mod:`flightmode.runs.pipeline` and the rooms); anything it does, ``import flightmode`` can do.

    flightmode scenarios [--spec | --phases]      the built-in scenarios, the file format, the pilot's phases
    flightmode fly [SCENARIO] [--seed N] [--out DIR] [--sensor P] [--gyro] [--no-rrd]
    flightmode sense RUN_DIR [--sensor P] [--carrier K=V ...] [--out DIR] [--gyro]
    flightmode detect RUN_DIR_OR_SAMPLES [--method] [--window-s] [--k] [--time-threshold-s] [--weight]
                      [--sigma2-from] [--tables]
    flightmode path RUN_DIR [--sensors run,ideal,...]
    flightmode view RUN_DIR_OR_RRD [--web]
    flightmode validate RUN_DIR_OR_DATASET [--paper-flight 1|2] [--json] [--strict] [--workers N]
                      [--checks-out FILE]

Errors that flightmode raises on purpose (bad scenario, unknown aircraft, failed flight, a file that
is not a run) print one line on stderr and exit with status 2, with no traceback. Only Typer and
Rich are imported to start; each command imports what it needs.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.table import Table
from rich.text import Text

from flightmode.errors import DetectorError, FlightmodeError, ScenarioError

DEFAULT_SCENARIO = "gva-lhr-a320"  # the same as flightmode.scenarios.scenario.DEFAULT_SCENARIO (tested)

# Help is Click's plain text (rich_markup_mode=None): Typer's Rich help imports rich.markdown and
# markdown_it (0.15-0.2 s of a 0.5 s `flightmode --help` budget); the commands' own output uses Rich.
HELP_MARKUP = None
app = typer.Typer(
    add_completion=False,
    no_args_is_help=False,
    rich_markup_mode=HELP_MARKUP,
    help="Physics-simulated accelerometer data for a package in an airliner, and its flight-mode detector.",
)
console = Console()
err_console = Console(stderr=True)


@app.callback()
def _start() -> None:
    """Physics-simulated accelerometer data for a package in an airliner, and its flight-mode detector."""
    # fresh consoles for each invocation: they read the terminal's width (COLUMNS) when made
    global console, err_console
    console = Console()
    err_console = Console(stderr=True)


def _die(e: Exception) -> None:
    # user text (scenario paths, [section].key names) must not be read as Rich markup
    err_console.print(Text.assemble(("error:", "bold red"), " ", str(e)), highlight=False, soft_wrap=True)
    raise typer.Exit(code=2)


@app.command("scenarios")
def scenarios_cmd(
    spec: Annotated[
        bool, typer.Option("--spec", help="Print every section and key a scenario file may hold.")
    ] = False,
    phases: Annotated[
        bool, typer.Option("--phases", help="Print the pilot's phase transition table.")
    ] = False,
) -> None:
    """List the built-in scenarios with a one-line description each."""
    if spec:
        from flightmode.scenarios.spec import spec_text

        console.print(spec_text(), highlight=False, markup=False)
        return
    if phases:
        from flightmode.sim.flight.phases import TRANSITIONS

        table = Table(title="the pilot's phase transitions (sim.flight.phases.TRANSITIONS)")
        for c in ("from phase", "condition", "to phase"):
            table.add_column(c)
        for tr in TRANSITIONS:
            table.add_row(
                tr.source,
                Text.assemble((tr.condition, "bold"), ": ", tr.doc),
                tr.target or "(end of the flight)",
            )
        console.print(table)
        return
    from flightmode.scenarios.scenario import Scenario, builtin_names

    table = Table(title="built-in scenarios", show_lines=False)
    table.add_column("name", style="bold")
    table.add_column("aircraft")
    table.add_column("description")
    for name in builtin_names():
        try:
            sc = Scenario.builtin(name)
        except FlightmodeError as e:  # a broken built-in must not hide the others
            table.add_row(name, "?", Text(str(e), style="red"))
            continue
        marker = " (default)" if name == DEFAULT_SCENARIO else ""
        table.add_row(name + marker, sc.aircraft, Text(sc.description))
    console.print(table)


def _estimate_duration_s(plan) -> float:
    """Rough gate-to-gate duration, only for the progress bar's scale."""
    from flightmode.scenarios.spec import route_length_m

    ground = plan.gate_wait_s + 120.0 + plan.taxi_out.length_m / 8.0 + sum(plan.taxi_out.holds_s)
    ground += plan.taxi_out.lineup_hold_s + plan.taxi_in.length_m / 8.0 + sum(plan.taxi_in.holds_s)
    return ground + route_length_m(plan) / 190.0 + 300.0 + plan.post_shutdown_s


@app.command("fly")
def fly_cmd(
    scenario: Annotated[
        str | None,
        typer.Argument(help=f"Built-in scenario name or path to a .toml file (default {DEFAULT_SCENARIO})."),
    ] = None,
    seed: Annotated[int | None, typer.Option("--seed", help="Override the scenario's seed.")] = None,
    out: Annotated[
        Path, typer.Option("--out", help="Output folder; the run goes to OUT/<scenario>-s<seed>/.")
    ] = Path("runs"),
    sensor: Annotated[
        str | None, typer.Option("--sensor", help="Accelerometer preset (default: the scenario's).")
    ] = None,
    gyro: Annotated[
        bool, typer.Option("--gyro", help="Also record a gyroscope channel (a Bosch BMI270).")
    ] = False,
    baro: Annotated[
        str | None,
        typer.Option(
            "--baro",
            help="Fit a barometer (bmp581, bmp581-osrN, lps22hh, ideal): samples gain baro_pa, and the redundant rule runs.",
        ),
    ] = None,
    rrd: Annotated[
        bool, typer.Option("--rrd/--no-rrd", help="Write recording.rrd (Rerun) beside the Parquet files.")
    ] = True,
    origin: Annotated[
        str | None,
        typer.Option(
            "--from", help="Fly from this airport (ICAO) instead of a scenario; needs --to and --aircraft."
        ),
    ] = None,
    destination: Annotated[
        str | None, typer.Option("--to", help="Destination airport (ICAO), with --from.")
    ] = None,
    aircraft: Annotated[
        str | None,
        typer.Option("--aircraft", help="Aircraft type for --from/--to: 737, A320, fokker100, 787-8."),
    ] = None,
) -> None:
    """Fly a scenario gate to gate in JSBSim, sense it, run the detector and the path estimators;
    write truth.parquet, samples.parquet, run.json and recording.rrd. With --from, --to and
    --aircraft, fly between any two airports with paved runways (OurAirports data)."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario

    try:
        pair = (origin, destination, aircraft)
        if any(v is not None for v in pair):
            if None in pair:
                raise ScenarioError(
                    "--from, --to and --aircraft go together: give all three "
                    "(e.g. --from LFPG --to LEMD --aircraft A320)"
                )
            if scenario is not None:
                raise ScenarioError(f"give a scenario ({scenario}) or --from/--to/--aircraft, not both")
            from flightmode.scenarios.routes import scenario_between

            sc = scenario_between(origin, destination, aircraft, seed=1 if seed is None else seed)
        else:
            sc = Scenario.resolve(DEFAULT_SCENARIO if scenario is None else scenario)
            if seed is not None:
                sc = sc.replace(seed=seed)
        if baro is not None:
            sc = sc.replace(sensor={"baro": baro})
        console.print(Text.assemble((sc.name, "bold"), f" seed {sc.seed}: {sc.description}"), highlight=False)
        total = _estimate_duration_s(sc.plan)
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

            def on_stage(stage: str) -> None:
                if stage != "fly":
                    progress.update(task, completed=total, description=f"{stage:>13}")

            result = pipeline.run(
                sc, sensor=sensor, out=out, gyro=gyro, rrd=rrd, progress=on_progress, on_stage=on_stage
            )
            progress.update(
                task, completed=total, description="done", sim=f"{result.track.duration_s / 60:6.1f} sim-min"
            )
        _print_summary(sc.plan, result.track, result.metrics, result.wall_s["fly"])
        _print_sensor(result.recording)
        _print_detector_line(result.detection)
        if result.redundant is not None:
            r = result.redundant
            console.print(
                f"with the barometer ({result.recording.baro['preset']}): accelerometer OR pressure to suspend, "
                f"AND to resume: {r.combined.false_static_count} false-static events in flight (accelerometer "
                f"alone {r.accel.false_static_count}); response after the flight "
                f"{'never came back' if r.combined.response_s is None else f'{r.combined.response_s:.1f} s'}",
                highlight=False,
            )
        _print_path_lines(result.path)
        rid = Path(out) / result.run_id
        files = ", ".join(p.name for p in result.written.values())
        console.print(Text.assemble("wrote ", (str(rid), "bold"), f" ({files})"), highlight=False)
        if "rrd" in result.written:
            where = result.written["rrd"]
            console.print(
                Text.assemble(
                    "recording: ",
                    (str(where), "bold"),
                    "; open it with: ",
                    (f"flightmode view {where}", "bold"),
                ),
                highlight=False,
            )
    except FlightmodeError as e:
        _die(e)


def _print_path_lines(path) -> None:
    """The path errors, aided first, and the unaided error beside what the random-walk law predicts."""
    by = {r["method"].split(" ")[0]: r for r in path.rows}
    tri, rec = by["tridiagonal"], by["recurrence"]
    console.print(
        f"path from acceleration (seed 002 cubic splines, frames from the truth), over the {path.span_s / 60:.0f} min "
        f"the bag is stowed: aided by the two gate positions (tridiagonal), max error {tri['max_m']:,.0f} m",
        highlight=False,
    )
    console.print(
        f"  unaided dead reckoning from the gate at rest (recurrence): final error {rec['final_m']:,.0f} m. Integrating "
        f"twice drifts: noise as t^1.5 (this sensor's alone: {path.random_walk_m:,.0f} m RMS after "
        f"{path.span_s / 60:.0f} min), a constant offset b as b t^2 / 2 (this unit's zero-g offset alone: "
        f"{path.offset_drift_m:,.0f} m). flightmode path RUN_DIR prints the table.",
        highlight=False,
    )


def _print_detector_line(e) -> None:
    resp = "never came back" if e.response_s is None else f"{e.response_s:.1f} s"
    style = "bold red" if e.false_static_count else "bold green"
    console.print(
        Text.assemble(
            "detector (NMV, 1 s, 4 sigma^2, 4 s): ",
            (f"{e.false_static_count} false-static events in flight", style),
            f" ({e.false_static_s:g} s); response after the flight {resp}; accuracy {e.accuracy:.3f}",
        ),
        highlight=False,
    )


@app.command("detect")
def detect_cmd(
    source: Annotated[Path, typer.Argument(help="A run folder, or a samples.parquet file.")],
    method: Annotated[
        str,
        typer.Option(
            "--method",
            help="nmv or emv (seed 000's moving variance), nmv+baro or emv+baro (the redundant rule with the samples' barometer), or one of seed 001's detectors: amvd, amd, ared, shod, frd, ltsd, fsd, mbgtd, mbcd.",
        ),
    ] = "nmv",
    window_s: Annotated[float, typer.Option("--window-s", help="Window W_s and check period, s.")] = 1.0,
    k: Annotated[
        float,
        typer.Option(
            "--k",
            help="Amplitude threshold T_sigma = k sigma^2 (seed 001's detectors: k times the merit at rest).",
        ),
    ] = 4.0,
    signal: Annotated[
        str, typer.Option("--signal", help="Seed 001's flexible input: acc, gyr, sum or product.")
    ] = "acc",
    time_threshold_s: Annotated[
        float, typer.Option("--time-threshold-s", help="Time threshold T_th, s.")
    ] = 4.0,
    weight: Annotated[
        float, typer.Option("--weight", help="EMV weighting factor (1, 5, 10 in the seed).")
    ] = 1.0,
    sigma2_from: Annotated[
        str,
        typer.Option(
            "--sigma2-from",
            help="preset (bench calibration of the unit) or rest (the recording's static samples before the flight).",
        ),
    ] = "preset",
    tables: Annotated[
        bool,
        typer.Option(
            "--tables", help="Also print the seed's Table 2, 3, 4/5 forms and the Fig. 18 response."
        ),
    ] = False,
    bursts: Annotated[
        int,
        typer.Option(
            "--bursts", help="Movebank e-obs file: final static after this many quiet bursts in a row."
        ),
    ] = 2,
    tag_number: Annotated[
        int | None,
        typer.Option(
            "--tag-number",
            help="Movebank e-obs file: the tag's number (sets the nominal slope; a Movebank id is not one).",
        ),
    ] = None,
    calibration: Annotated[
        Path | None,
        typer.Option(
            "--calibration", help="Movebank e-obs file: a calibration TOML from `flightmode eobs calibrate`."
        ),
    ] = None,
    baro_rate_pa_s: Annotated[
        float | None,
        typer.Option(
            "--baro-rate-pa-s", help="+baro: the pressure rate bound, Pa/s (default: the detector's, 1)."
        ),
    ] = None,
    baro_margin_hpa: Annotated[
        float | None,
        typer.Option(
            "--baro-margin-hpa",
            help="+baro: the level margin below the ground reference, hPa (0: no level bound; default 25).",
        ),
    ] = None,
    baro_hold_s: Annotated[
        float | None,
        typer.Option("--baro-hold-s", help="+baro: the pressure source's hold time, s (default 120)."),
    ] = None,
) -> None:
    """Run the flight-mode detector over a recording (a run folder or samples.parquet) and print how
    it did against the truth; or, on a Movebank e-obs CSV, the duty-cycled detector per burst."""
    import numpy as np

    from flightmode.detector.evaluation import evaluate
    from flightmode.detector.flight_mode import DetectorParams
    from flightmode.detector.recommended import labels_of
    from flightmode.cli import detector_report as dr
    from flightmode.runs import run_io
    from flightmode.runs.pipeline import stream_sigma2

    try:
        if Path(source).suffix.lower() == ".csv":
            _detect_movebank(source, k, bursts, tag_number, calibration)
            return
        cols, info = run_io.read_samples(source)
        t, a = cols["t_s"], cols["acc_g"]
        if info and info.get("sensor"):
            fs = float(info["sensor"]["odr_hz"])
        else:
            fs = 1.0 / float(np.median(np.diff(t[: min(len(t), 10_000)])))
        labels = labels_of(cols)
        base, _, extra = method.lower().partition("+")
        if extra:
            if base not in ("nmv", "emv") or extra != "baro":
                raise DetectorError(f"--method {method!r}: the redundant rule is nmv+baro or emv+baro")
            pp = _pressure_params(cols, info, source, baro_rate_pa_s, baro_margin_hpa, baro_hold_s)
            p = DetectorParams(
                fs_hz=fs,
                window_s=window_s,
                k_sigma=k,
                time_threshold_s=time_threshold_s,
                method=base,
                weight=weight,
            )
            p.validate()
            s2, s2_source = stream_sigma2(sigma2_from, cols, info, p.window)
            from flightmode.detector.pressure import evaluate_redundant

            new = cols["baro_new"]
            red = evaluate_redundant(t, a, t[new], cols["baro_pa"][new], labels, p, s2, pp)
            console.print(Text(f"{source}: accelerometer and barometer", style="bold"), highlight=False)
            dr.print_redundant(console, red, s2_source)
            return
        if method.lower() not in ("nmv", "emv"):
            _detect_activity(
                source,
                cols,
                info,
                labels,
                fs,
                method.lower(),
                window_s,
                k,
                time_threshold_s,
                signal,
                sigma2_from,
            )
            return
        p = DetectorParams(
            fs_hz=fs,
            window_s=window_s,
            k_sigma=k,
            time_threshold_s=time_threshold_s,
            method=method,
            weight=weight,
        )
        p.validate()
        s2, s2_source = stream_sigma2(sigma2_from, cols, info, p.window)
        title = f"{source}" + (
            f": {info['sensor']['preset']} at {fs:g} Hz" if info and info.get("sensor") else ""
        )
        console.print(Text(title, style="bold"), highlight=False)
        e = evaluate(t, a, labels, p, s2)
        dr.print_evaluation(console, e, s2_source)
        if tables:
            dr.print_tables(console, t, a, labels, p, s2)
    except FlightmodeError as e:
        _die(e)


def _pressure_params(
    cols: dict,
    info: dict | None,
    source,
    rate_pa_s: float | None,
    margin_hpa: float | None,
    hold_s: float | None,
):
    """The pressure detector's parameters for a samples file's barometer (its rate from run.json, or
    from the spacing of its readings)."""
    import numpy as np

    from flightmode.detector.pressure import PressureParams

    if "baro_pa" not in cols or "baro_new" not in cols:
        raise DetectorError(
            f"{source}: the samples have no barometer (baro_pa): fly with [sensor].baro = "
            '"bmp581" (or `flightmode fly --baro bmp581`)'
        )
    baro = ((info or {}).get("sensor") or {}).get("baro")
    if baro:
        fs = float(baro["odr_hz"])
    else:
        tb = cols["t_s"][cols["baro_new"]]
        fs = round(1.0 / float(np.median(np.diff(tb))), 3) if tb.shape[0] > 2 else math.nan
    changes: dict = {}
    if margin_hpa is not None:
        if margin_hpa < 0:
            raise DetectorError(f"--baro-margin-hpa {margin_hpa:g}: must be >= 0 (0: no level bound)")
        changes["level_margin_pa"] = margin_hpa * 100.0 if margin_hpa > 0 else None
    if rate_pa_s is not None:
        changes["rate_threshold_pa_s"] = rate_pa_s
    if hold_s is not None:
        changes["hold_s"] = hold_s
    if info is not None and "scenario_toml" in info:  # the destination known (the run's scenario)
        from flightmode.runs.pipeline import pressure_params
        from flightmode.runs.run_io import run_scenario

        return pressure_params(run_scenario(info, str(source)), fs, **changes)
    pp = PressureParams(fs_hz=fs, **changes)
    pp.validate()
    return pp


def _detect_movebank(
    source: Path, k: float, m: int, tag_number: int | None, calibration: Path | None
) -> None:
    """`flightmode detect FILE.csv`: seed 003's bursts through the duty-cycled detector (eobs.duty_cycle)."""
    import warnings

    from flightmode.eobs.calibration import NominalCalibrationWarning, read_calibration
    from flightmode.eobs.duty_cycle import detect_movebank

    cal = read_calibration(calibration) if calibration is not None else None
    if cal is None and tag_number is None:
        raise ScenarioError(
            f"{source}: give --tag-number (a Movebank id is not a tag number; it sets the nominal "
            "slope) or --calibration FILE.toml"
        )
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", category=NominalCalibrationWarning)  # said once, below
        det = detect_movebank(source, k=k, m=m, calibration=cal, tag_number=tag_number)
    if det.nominal:
        console.print(
            f"warning: counts converted with the nominal constants of tag {tag_number} (seed 003 section 6); "
            "calibrate the tag (flightmode eobs calibrate) for its own offsets and slopes",
            highlight=False,
        )
    t = Table(
        "individual",
        "axes",
        "bursts",
        "quiet",
        "final static",
        "sigma^2 per axis g^2",
        title=f"{source}: burst variance < {k:g} sigma^2 on every axis; final static after {m} quiet bursts "
        f"(sigma^2: {det.sigma2_source})",
    )
    for ind in det.individuals.values():
        c = ind.checks
        t.add_row(
            ind.individual,
            ind.axes,
            str(c.t.shape[0]),
            str(int(c.quiet.sum())),
            str(int(c.final_static.sum())),
            ", ".join(f"{v:.2e}" for v in ind.sigma2_g2),
        )
    console.print(t)


def _detect_activity(
    source, cols, info, labels, fs, name, window_s, k, time_threshold_s, signal, rest_from
) -> None:
    """`flightmode detect --method <seed 001 detector>` (flightmode.detector.activity.flight)."""
    from flightmode.detector.activity import registry
    from flightmode.detector.activity.flight import ActivityParams, evaluate_activity, rest_figures
    from flightmode.errors import DetectorError, did_you_mean
    from flightmode.runs.pipeline import stream_rest

    if name not in registry.NAMES:
        raise DetectorError(
            f"--method {name!r}: use 'nmv' or 'emv' (seed 000) or one of seed 001's detectors: "
            f"{', '.join(registry.NAMES)}{did_you_mean(name, ('nmv', 'emv') + registry.NAMES)}"
        )
    p = ActivityParams(
        name, fs_hz=fs, window_s=window_s, k=k, time_threshold_s=time_threshold_s, signal=signal
    )
    p.validate()
    bench, bench_gyr, bench_source = stream_rest(rest_from, cols, info)
    if (
        bench_gyr is None
        and cols.get("gyro_dps") is not None
        and (registry.get(name).needs_gyro or signal != "acc")
    ):
        raise DetectorError(
            f"{name}: the bench recording has no gyroscope; calibrate on the rest before the "
            "flight instead: --sigma2-from rest"
        )
    rest = rest_figures(p, bench, bench_gyr)
    e = evaluate_activity(cols["t_s"], cols["acc_g"], cols.get("gyro_dps"), labels, p, rest)
    from flightmode.cli import detector_report as dr

    d = registry.get(name)
    console.print(Text(f"{source}", style="bold"), highlight=False)
    dr.print_evaluation(
        console,
        e,
        bench_source,
        title=f"{d.title} ({d.equations}) with seed 000's decision rule: W_s {window_s:g} s, "
        f"threshold {k:g} x the rest level, T_th {time_threshold_s:g} s",
        calibration=[
            ("rest level of the merit (median)", f"{rest['merit_median']:.4g} {d.merit_unit}"),
            ("threshold", f"{rest['threshold']:.4g} {d.merit_unit}"),
            ("rest from", bench_source),
        ],
    )


activity_app = typer.Typer(
    help="Seed 001's (in)activity detectors: the synthesizer and Monte Carlo study.",
    no_args_is_help=True,
    rich_markup_mode=HELP_MARKUP,
)
app.add_typer(activity_app, name="activity")


@activity_app.command("synth")
def activity_synth_cmd(
    n: Annotated[int, typer.Option("--n", help="Synthesized runs (the paper: 500).")] = 500,
    seed: Annotated[
        int, typer.Option("--seed", help="The study's seed (run i: SeedSequence(seed, spawn_key=(i,))).")
    ] = 0,
    workers: Annotated[
        int, typer.Option("--workers", help="Dask worker processes (1: in this process).")
    ] = 2,
    out: Annotated[
        Path | None, typer.Option("--out", help="Write the tables, runs, ROC curves and figures here.")
    ] = None,
) -> None:
    """Seed 001 section 3: N synthesized activity records, every detector and input signal grid-searched
    for accuracy, ROC/AUC at its best window; Tables 1-6 and 13 printed beside the paper's."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from flightmode.detector.activity import montecarlo as mc

    try:
        if n < 1:
            raise ScenarioError(f"--n {n}: the number of runs must be a positive integer")
        with Progress(
            TextColumn("runs"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(), console=console
        ) as bar:
            task = bar.add_task("runs", total=n)
            if workers <= 1:
                res = mc.run_montecarlo(n, seed=seed, on_run=lambda i: bar.update(task, advance=1))
            else:
                import logging

                from dask.distributed import Client, LocalCluster

                with (
                    LocalCluster(
                        n_workers=workers,
                        threads_per_worker=1,
                        processes=True,
                        host="127.0.0.1",
                        dashboard_address="127.0.0.1:0",
                        silence_logs=logging.CRITICAL,
                    ) as cluster,
                    Client(cluster) as client,
                ):
                    res = mc.run_montecarlo(
                        n, seed=seed, client=client, on_run=lambda i: bar.update(task, advance=1)
                    )
        console.print(mc.format_tables(res), highlight=False, soft_wrap=True)
        if out is not None:
            written = mc.write_results(res, out)
            console.print(f"wrote {len(written)} files to {out}", highlight=False)
    except FlightmodeError as e:
        _die(e)


eobs_app = typer.Typer(
    help="The e-obs tag toolkit (seed 003): calibration, the battery trade-off on flights.",
    no_args_is_help=True,
    rich_markup_mode=HELP_MARKUP,
)
app.add_typer(eobs_app, name="eobs")


@eobs_app.command("tradeoff")
def eobs_tradeoff_cmd(
    datasets: Annotated[
        list[Path], typer.Argument(help="Dataset folders made by `flightmode dataset ... --truth full`.")
    ],
    interval_s: Annotated[
        str, typer.Option("--interval-s", help="ACC intervals, s (the tag's burst period).")
    ] = "10,30,60,120",
    byte_count: Annotated[
        int,
        typer.Option("--byte-count", help="Bytes per burst (seed 003 section 9: sets the samples per axis)."),
    ] = 216,
    m: Annotated[str, typer.Option("--m", help="Quiet bursts in a row before final static.")] = "1,2,3",
    k: Annotated[
        float,
        typer.Option("--k", help="A burst is quiet when its variance is under k sigma^2 on every axis."),
    ] = 4.0,
    odr_hz: Annotated[float, typer.Option("--odr-hz", help="Samples per second per axis in a burst.")] = 10.0,
    confidence: Annotated[float, typer.Option("--confidence", help="Confidence of the upper bound.")] = 0.95,
    workers: Annotated[
        int, typer.Option("--workers", help="Dask worker processes (1: in this process).")
    ] = 1,
    out: Annotated[
        Path | None, typer.Option("--out", help="Write the per-flight rows here (Parquet).")
    ] = None,
) -> None:
    """The battery trade-off of a duty-cycled e-obs tag on flights: samples per hour against false
    statics per flight-hour and the response at the gate, per ACC interval and m."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from flightmode.eobs.population import summarise, tradeoff_population

    try:
        intervals = _axis(interval_s, "--interval-s")
        ms = tuple(int(x) for x in _axis(m, "--m"))
        with Progress(
            TextColumn("flights"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(), console=console
        ) as bar:
            task = bar.add_task("flights", total=None)
            rows = tradeoff_population(
                [str(d) for d in datasets],
                intervals,
                byte_count,
                ms,
                k,
                odr_hz,
                workers,
                on_start=lambda n: bar.update(task, total=n),
                on_flight=lambda n: bar.advance(task),
            )
        t = Table(
            "ACC interval s",
            "samples/axis/burst",
            "m",
            "samples/h/axis",
            "flights",
            "in-window h",
            "false statics",
            "/h",
            f"{confidence:.0%} bound /h",
            "response p50/p95/max s",
            title=f"e-obs duty cycle on flights: k {k:g}, {odr_hz:g} Hz per axis, {byte_count} bytes per burst",
            title_justify="left",
        )
        for r in summarise(rows, confidence):
            t.add_row(
                f"{r['interval_s']:g}",
                str(r["burst_samples"]),
                str(r["m"]),
                f"{r['samples_per_hour_per_axis']:,.0f}",
                str(r["flights"]),
                f"{r['in_window_h']:.1f}",
                str(r["false_statics"]),
                f"{r['rate_per_h']:.3g}",
                f"{r['rate_upper_per_h']:.3g}",
                f"{r['response_p50_s']:.0f}/{r['response_p95_s']:.0f}/{r['response_max_s']:.0f}",
            )
        console.print(t)
        if out is not None:
            import pyarrow as pa

            from flightmode.datasets.make import atomic_parquet

            atomic_parquet(pa.Table.from_pylist(rows), out)
            console.print(Text.assemble("wrote ", (str(out), "bold")), highlight=False)
    except FlightmodeError as e:
        _die(e)


@eobs_app.command("calibrate")
def eobs_calibrate_cmd(
    plus_x: Annotated[Path, typer.Option("--plus-x", help="Movebank CSV of the tag still with X at +1 g.")],
    minus_x: Annotated[Path, typer.Option("--minus-x", help="... X at -1 g.")],
    plus_y: Annotated[Path, typer.Option("--plus-y", help="... Y at +1 g.")],
    minus_y: Annotated[Path, typer.Option("--minus-y", help="... Y at -1 g.")],
    plus_z: Annotated[Path, typer.Option("--plus-z", help="... Z at +1 g.")],
    minus_z: Annotated[Path, typer.Option("--minus-z", help="... Z at -1 g.")],
    out: Annotated[Path, typer.Option("--out", help="The calibration TOML to write.")],
    tag_number: Annotated[
        int | None, typer.Option("--tag-number", help="The tag's number (recorded; old tags <= 2241).")
    ] = None,
) -> None:
    """Seed 003 section 7's six-orientation calibration: zero-g count and slope per axis from six static
    recordings, each a Movebank e-obs file whose bursts all hold the tag in one orientation (XYZ bursts)."""
    import numpy as np

    from flightmode.eobs.calibration import calibrate, write_calibration
    from flightmode.eobs.movebank import read_movebank

    try:
        recs = {}
        for key, path in (
            ("+x", plus_x),
            ("-x", minus_x),
            ("+y", plus_y),
            ("-y", minus_y),
            ("+z", plus_z),
            ("-z", minus_z),
        ):
            bursts = [r.burst for r in read_movebank(path).rows if r.burst is not None]
            if not bursts or any(b.axes != "XYZ" for b in bursts):
                raise ScenarioError(f"{path}: the {key} recording needs bursts of all three axes (XYZ)")
            recs[key] = np.concatenate([b.raw for b in bursts])
        cal = calibrate(recs, tag_number)
        write_calibration(cal, out)
        t = Table("axis", "zero-g count", "slope g/count", title=f"seed 003 section 7: {out}")
        for j, a in enumerate("XYZ"):
            t.add_row(a, f"{cal.zero_count[j]:.2f}", f"{cal.slope_g_per_count[j]:.6f}")
        console.print(t)
    except FlightmodeError as e:
        _die(e)


@app.command("path")
def path_cmd(
    run_dir: Annotated[Path, typer.Argument(help="A run folder written by `flightmode fly`.")],
    sensors: Annotated[
        str,
        typer.Option("--sensors", help="Comma-separated presets to compare; 'run' is the run's own sensor."),
    ] = "run,ideal",
    as_json: Annotated[
        bool, typer.Option("--json", help="Print the rows as JSON instead of a table.")
    ] = False,
) -> None:
    """Rebuild the bag's path from acceleration (seed 002 cubic splines) and print its errors."""
    from flightmode.runs import pipeline, run_io
    from flightmode.cli.path_report import path_rows, print_rows

    try:
        track, info = run_io.read_track(run_dir)
        sc = run_io.run_scenario(info, str(run_dir))
        run_preset = (info.get("sensor") or {}).get("preset") or sc.sensor.preset
        streams = pipeline.streams_of(int(info["seed"]))
        recs = {}
        for name in [s.strip() for s in sensors.split(",") if s.strip()]:
            preset = run_preset if name == "run" else name
            if preset in recs:
                continue
            # re-sensing with the run's own streams: the run's own preset gives its samples again (to
            # one count: truth.parquet stores the forces in float32), with the carrier timeline
            # (orientations) that the truth-aided frames need
            recs[preset] = pipeline.sense(track, sc.carrier, preset, streams.child("sensor"))
        rows = path_rows(track, recs, sc.carrier, streams)
        if as_json:
            import json

            typer.echo(json.dumps(rows, indent=1))
        else:
            print_rows(console, rows, f"{info['run_id']}: path errors against the truth (bag seat position)")
    except FlightmodeError as e:
        _die(e)


@app.command("cabin")
def cabin_cmd(
    run_dir: Annotated[Path, typer.Argument(help="A run folder written by `flightmode fly`.")],
    png: Annotated[
        Path | None,
        typer.Option("--png", help="Also draw the cabin beside the aircraft altitude to this PNG."),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help="Print the figures as JSON.")] = False,
) -> None:
    """The flight's cabin pressure: cruise cabin altitude and pressure, cabin climb and descent rates
    and differential, beside the type's pressurisation schedule."""
    from flightmode.runs import run_io
    from flightmode.sim.flight.cabin import cabin_figures, get_cabin_profile

    try:
        track, info = run_io.read_track(run_dir)
        if track.cabin_pressure_pa is None:
            raise ScenarioError(
                f"{run_dir}: truth.parquet has no cabin pressure (written by an older flightmode); "
                "fly the scenario again"
            )
        f = cabin_figures(
            track.t_s,
            track.alt_m,
            track.cabin_altitude_m,
            track.cabin_pressure_pa,
            track.ambient_pressure_pa,
            track.phase_code,
        )
        prof = get_cabin_profile(track.aircraft)
        limits = {
            "max_cabin_alt_ft": prof.max_cabin_alt_ft,
            "climb_rate_fpm": prof.climb_rate_fpm,
            "descent_rate_fpm": prof.descent_rate_fpm,
            "descent_rate_max_fpm": prof.descent_rate_max_fpm,
            "hold": track.conditions.get("hold", "pressurised"),
        }
        if png is not None:
            from flightmode.viz.cabin_plot import cabin_png

            cabin_png(
                track, f, limits, png, f"{info['run_id']}: {track.aircraft}, cabin and aircraft altitude"
            )
        if as_json:
            import json

            typer.echo(json.dumps({"figures": f, "schedule": limits}, indent=1))
            return
        t = Table(
            "figure",
            "this flight",
            "the type's schedule",
            title=f"{info['run_id']}: cabin pressure ({track.aircraft})",
            title_justify="left",
        )
        t.add_row("highest aircraft altitude", f"{f['max_altitude_ft']:,.0f} ft", "")
        t.add_row(
            "cruise cabin altitude",
            f"{f['cruise_cabin_altitude_ft']:,.0f} ft",
            f"at most {prof.max_cabin_alt_ft:,.0f} ft",
        )
        t.add_row("cruise cabin pressure", f"{f['cruise_cabin_pressure_hpa']:.1f} hPa", "")
        t.add_row(
            "highest cabin altitude",
            f"{f['max_cabin_altitude_ft']:,.0f} ft",
            f"at most {prof.max_cabin_alt_ft:,.0f} ft",
        )
        t.add_row(
            "fastest cabin climb in the air (10 s)",
            f"{f['max_cabin_climb_airborne_fpm']:.0f} ft/min",
            f"{prof.climb_rate_fpm:.0f} ft/min",
        )
        used = track.conditions.get("cabin_descent_rate_fpm", prof.descent_rate_fpm)
        t.add_row(
            "fastest cabin descent in the air (10 s)",
            f"{f['max_cabin_descent_airborne_fpm']:.0f} ft/min",
            f"{prof.descent_rate_fpm:.0f} ft/min, up to {prof.descent_rate_max_fpm:.0f} (this flight: {used:.0f})",
        )
        t.add_row(
            "fastest over the whole flight (10 s)",
            f"{f['max_cabin_descent_fpm']:.0f} down, {f['max_cabin_climb_fpm']:.0f} up ft/min",
            f"{prof.prepress_rate_fpm:.0f} down (pre-pressurising), {prof.release_rate_fpm:.0f} up (release)",
        )
        t.add_row("largest differential", f"{f['max_differential_psi']:.2f} psi", "")
        t.add_row("hold", limits["hold"], "")
        console.print(t)
        if png is not None:
            console.print(Text.assemble("wrote ", (str(png), "bold")), highlight=False)
    except FlightmodeError as e:
        _die(e)


@app.command("family")
def family_cmd(
    family: Annotated[str, typer.Argument(help="A built-in family name or the path of a family .toml file.")],
    show: Annotated[int, typer.Option("--show", help="Print the first SHOW members.")] = 5,
    start: Annotated[int, typer.Option("--start", help="First member to show.")] = 0,
) -> None:
    """Validate a scenario family and print its first members (each a plain scenario)."""
    from flightmode.scenarios.family import Family, builtin_families
    from flightmode.units import FT_M

    try:
        fam = Family.resolve(family)
        if show < 0 or start < 0:
            raise ScenarioError("--show and --start must be >= 0")
        console.print(
            Text.assemble(
                (fam.name, "bold"), f" (seed {fam.seed}, SHA-256 {fam.digest()[:12]}): {fam.description}"
            ),
            highlight=False,
        )
        for i in range(start, start + show):
            m = fam.member(i)
            p, c = m.plan, m.carrier
            turb = ", ".join(
                f"{t.severity} {t.duration_s / 60:.0f} min at {t.start_s / 60:.0f} min" for t in p.turbulence
            )
            where = c.placement if c.kind == "handbag" else f"hold, {c.truck_s / 60:.0f} min by road"
            handled = (
                f", handled x{c.handled_in_cruise}" if c.kind == "handbag" and c.handled_in_cruise else ""
            )
            console.print(
                f"{i:>5}  {m.aircraft:<9} {p.origin.icao} {p.origin.name:<4} -> {p.destination.icao} "
                f"{p.destination.name:<4} FL{p.cruise_alt_m / FT_M / 100:03.0f}  turbulence: {turb or 'none'}; "
                f"landing {p.landing_quality}; {c.kind}, {where}{handled}; {m.sensor.preset}"
                + (f", vibration x{m.sensor.vibration_level:g}" if m.sensor.vibration_level else "")
                + f"; seed {m.seed}",
                highlight=False,
                soft_wrap=True,
            )
        console.print(f"built-in families: {', '.join(builtin_families())}", highlight=False)
    except FlightmodeError as e:
        _die(e)


@app.command("dataset")
def dataset_cmd(
    family: Annotated[str, typer.Argument(help="A built-in family name or the path of a family .toml file.")],
    n: Annotated[int, typer.Option("--n", help="Number of flights (members 0..N-1).")],
    out: Annotated[Path, typer.Option("--out", help="The dataset folder.")],
    workers: Annotated[
        int, typer.Option("--workers", help="Local worker processes (a LocalCluster on 127.0.0.1).")
    ] = 2,
    scheduler: Annotated[
        str | None,
        typer.Option("--scheduler", help="Use a running Dask scheduler instead, e.g. tcp://127.0.0.1:8786."),
    ] = None,
    resume: Annotated[
        bool, typer.Option("--resume", help="Continue a dataset of the same family in OUT.")
    ] = False,
    truth: Annotated[
        str, typer.Option("--truth", help="Aircraft state files: full (every FDM step), 10hz or none.")
    ] = "10hz",
    flight_timeout_s: Annotated[
        float | None,
        typer.Option("--flight-timeout-s", help="Fail a flight that runs longer than this (wall s)."),
    ] = None,
    rrd: Annotated[
        bool, typer.Option("--rrd", help="Also write each flight's Rerun recording (DIR/rrd/).")
    ] = False,
) -> None:
    """Generate a labelled dataset of a family's first N flights on Dask (see flightmode.datasets.make)."""
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    from flightmode.datasets.make import check_request, make_dataset

    try:
        # checked before the progress bar (an error prints alone); make_dataset takes the resolved family
        fam, _, _ = check_request(
            family,
            n,
            out,
            workers=workers,
            resume=resume,
            truth=truth,
            flight_timeout_s=flight_timeout_s,
            rrd=rrd,
        )
        with Progress(
            TextColumn("[progress.description]{task.description}"),
            BarColumn(),
            MofNCompleteColumn(),
            TextColumn("{task.fields[hours]:.1f} flight-h, {task.fields[failed]} failed"),
            TimeElapsedColumn(),
            TimeRemainingColumn(),
            console=console,
        ) as progress:
            task = progress.add_task("flights", total=None, hours=0.0, failed=0)
            state = {"hours": 0.0, "failed": 0}

            def on_start(dashboard: str | None, todo: int) -> None:
                progress.update(task, total=todo)
                if dashboard:
                    progress.console.print(f"Dask dashboard: {dashboard}", highlight=False)

            def on_flight(row: dict) -> None:
                state["hours"] += (row.get("gate_to_gate_s") or 0.0) / 3600.0
                state["failed"] += row["status"] != "ok"
                progress.update(task, advance=1, hours=state["hours"], failed=state["failed"])
                if row["status"] != "ok":
                    progress.console.print(
                        f"flight {row['flight_id']} failed: {row['error']}", highlight=False
                    )

            rows = make_dataset(
                fam,
                n,
                out,
                workers=workers,
                scheduler=scheduler,
                resume=resume,
                truth=truth,
                flight_timeout_s=flight_timeout_s,
                rrd=rrd,
                on_start=on_start,
                on_flight=on_flight,
            )
        ok = sum(r["status"] == "ok" for r in rows.values() if r["index"] < n)
        console.print(
            Text.assemble(
                "wrote ",
                (str(out), "bold"),
                f": {ok} flights ok, {n - ok} failed; manifest flights.parquet, card README.md",
            ),
            highlight=False,
        )
    except FlightmodeError as e:
        _die(e)


def _axis(text: str, name: str) -> tuple[float, ...]:
    """``2,3,4`` or ``start:stop:step`` (stop included) as floats; a ScenarioError naming the option."""
    import numpy as np

    try:
        if ":" in text:
            a, b, c = (float(x) for x in text.split(":"))
            if not c > 0 or b < a:
                raise ValueError
            return tuple(round(float(v), 10) for v in np.arange(a, b + c / 2, c))
        return tuple(float(x) for x in text.split(",") if x.strip())
    except ValueError:
        raise ScenarioError(f"{name} {text!r}: give values as 2,3,4 or a range start:stop:step") from None


def _grid(method: str, weight: str, window_s: str, k: str, time_threshold_s: str):
    from flightmode.detector.grid import Grid

    methods = [m.strip() for m in method.split(",") if m.strip()]
    weights = _axis(weight, "--weight")
    pairs = tuple((m, w) for m in methods for w in (weights if m in ("emv", "emv+baro") else (1.0,)))
    return Grid(
        pairs, _axis(window_s, "--window-s"), _axis(k, "--k"), _axis(time_threshold_s, "--time-threshold-s")
    )


def _sensors(text: str | None) -> tuple[str, ...] | None:
    return None if text is None else tuple(x.strip() for x in text.split(",") if x.strip())


class _SweepProgress:
    """A progress bar shown only once the sweep starts (certify may reuse a sweep and sweep nothing)."""

    def __enter__(self):
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

        self.bar = Progress(
            TextColumn("sweeping"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(), console=console
        )
        self.task = self.bar.add_task("sweep", total=None)
        self.started = False
        return self

    def start(self, flights: int) -> None:
        self.bar.update(self.task, total=flights)
        self.bar.start()
        self.started = True

    def advance(self, flight_id: str) -> None:
        self.bar.update(self.task, advance=1)

    def __exit__(self, *exc):
        if self.started:
            self.bar.stop()


def _excluded(failed: list[dict]) -> None:
    if failed:
        console.print(
            f"excluded: {len(failed)} failed flight(s) ("
            + ", ".join(f"{Path(r['dataset']).name}/{r['flight_id']}" for r in failed[:10])
            + (", ..." if len(failed) > 10 else "")
            + ")",
            highlight=False,
        )


# the default grid of sweep and certify: NMV and EMV (weight 5), three windows, 13 k, 8 time thresholds
# (624 points); each moving variance is computed once, so the grid costs little more than one point
GRID_HELP = {
    "method": "nmv, emv (seed 000), nmv+baro, emv+baro (the redundant rule with the samples' barometer) and seed 001's detectors amvd, amd, ared, shod, frd, ltsd, fsd, mbgtd, mbcd (ared and shod read the gyroscope; the flexible ones take :acc, :gyr, :sum or :product, e.g. fsd:sum) "
    "(threshold k x the merit at rest; the memory detectors cost O(N^2), O(N^3) per sample: short windows).",
    "weight": "EMV weighting factors, e.g. 1,5,10.",
    "window_s": "Windows W_s, s (list or start:stop:step).",
    "k": "Amplitude thresholds T_sigma = k sigma^2.",
    "time_threshold_s": "Time thresholds T_th, s.",
}


@app.command("sweep")
def sweep_cmd(
    datasets: Annotated[list[Path], typer.Argument(help="Dataset folders made by `flightmode dataset`.")],
    method: Annotated[str, typer.Option("--method", help=GRID_HELP["method"])] = "nmv,emv",
    weight: Annotated[str, typer.Option("--weight", help=GRID_HELP["weight"])] = "5",
    window_s: Annotated[str, typer.Option("--window-s", help=GRID_HELP["window_s"])] = "0.5,1,2",
    k: Annotated[str, typer.Option("--k", help=GRID_HELP["k"])] = "2:8:0.5",
    time_threshold_s: Annotated[
        str, typer.Option("--time-threshold-s", help=GRID_HELP["time_threshold_s"])
    ] = "1:8:1",
    sigma2_from: Annotated[
        str, typer.Option("--sigma2-from", help="preset (each unit's bench calibration) or rest.")
    ] = "preset",
    sensor: Annotated[
        str | None,
        typer.Option(
            "--sensor",
            help="Re-sense every flight with these presets (e.g. lis302dl,lis302dl-8g; a dataset made with --truth full).",
        ),
    ] = None,
    workers: Annotated[
        int, typer.Option("--workers", help="Dask worker processes (1: in this process).")
    ] = 1,
    out: Annotated[
        Path | None,
        typer.Option("--out", help="The sweep folder (default DATASET/sweep; needed for several datasets)."),
    ] = None,
    confidence: Annotated[float, typer.Option("--confidence", help="Confidence of the upper bounds.")] = 0.95,
    target_fa_per_h: Annotated[
        float, typer.Option("--target-fa-per-h", help="Target false statics per flight-hour.")
    ] = 1e-4,
    top: Annotated[int, typer.Option("--top", help="Grid points to print.")] = 10,
) -> None:
    """Evaluate a grid of detector parameters over every flight of one or more datasets (each moving
    variance computed once); print the best points with exact upper bounds on the false-static rate."""
    from flightmode.studies.sweep import breakdown, check_request, summarise, sweep

    try:
        grid = _grid(method, weight, window_s, k, time_threshold_s)
        if not target_fa_per_h > 0:
            raise ScenarioError(f"--target-fa-per-h {target_fa_per_h!r}: must be > 0")
        if out is None:
            if len(datasets) > 1:
                raise ScenarioError("several datasets: give --out, the folder for their common sweep")
            out = Path(datasets[0]) / "sweep"
        sensors = _sensors(sensor)
        check_request(datasets, grid, sigma2_from, sensors)
        with _SweepProgress() as progress:
            result = sweep(
                datasets,
                grid,
                sigma2_from=sigma2_from,
                workers=workers,
                sensors=sensors,
                out=out,
                on_start=progress.start,
                on_flight=progress.advance,
            )
        _excluded(result.failed)
        table = result.points
        rows = summarise(table, confidence, target_fa_per_h, by_sensor=bool(sensors))

        def order(r):  # NaN last (a point nothing could measure), then a fixed order on ties
            def fin(v, sign=1.0):
                return sign * v if v == v else math.inf

            return (
                fin(r["rate_upper_per_h"]),
                fin(r["response_p95_s"]),
                fin(r["availability"], -1.0),
                r["method"],
                r["weight"],
                r["window_s"],
                r["k"],
                r["time_threshold_s"],
            )

        rows.sort(key=order)
        t = Table(
            "method",
            "W_s",
            "k",
            "T_th s",
            "false statics",
            "in-window h",
            f"{confidence:.0%} bound /h",
            "response p50/p95/max s",
            "availability",
            "h needed",
        )
        shown = rows[:top]
        rec = [
            r
            for r in rows
            if (r["method"], r["window_s"], r["k"], r["time_threshold_s"]) == ("nmv", 1.0, 4.0, 4.0)
        ]
        for r in shown + [r for r in rec if r not in shown]:
            name = r["method"] + (f" w{r['weight']:g}" if r["method"] == "emv" else "")
            t.add_row(
                name + (" (seed 000)" if r in rec else ""),
                f"{r['window_s']:g}",
                f"{r['k']:g}",
                f"{r['time_threshold_s']:g}",
                str(r["false_statics"]),
                f"{r['in_window_h']:.1f}",
                f"{r['rate_upper_per_h']:.3g}",
                f"{r['response_p50_s']:.1f}/{r['response_p95_s']:.1f}/{r['response_max_s']:.1f}",
                f"{r['availability']:.3f}",
                f"{r['hours_needed']:,.0f}",
            )
        console.print(t)
        # where the best point's false statics and slow responses come from
        best_point = rows[0]
        b = Table(
            "condition",
            "value",
            "flights",
            "in-window h",
            "false statics",
            "response p95 s",
            title=f"by condition at {best_point['method']} W_s {best_point['window_s']:g} k {best_point['k']:g} "
            f"T_th {best_point['time_threshold_s']:g}",
        )
        for r in breakdown(table, best_point, result.phases):
            b.add_row(
                r["condition"],
                r["value"],
                str(r["flights"]),
                f"{r['in_window_h']:.1f}",
                str(r["false_statics"]),
                "" if r["response_p95_s"] != r["response_p95_s"] else f"{r['response_p95_s']:.1f}",
            )
        console.print(b)
        if len({m for m, _ in grid.methods}) > 1:  # the detectors side by side, each at its best point
            from flightmode.studies.sweep import compare_methods

            c = Table(
                "method",
                "W_s",
                "k",
                "T_th s",
                "false statics /h",
                f"{confidence:.0%} bound /h",
                "response p95 s",
                "availability",
                "accuracy",
                "AUC",
                title="each method at its best point (AUC: k swept there)",
            )
            for r in compare_methods(table, confidence):
                c.add_row(
                    r["method"] + (f" w{r['weight']:g}" if r["method"].startswith("emv") else ""),
                    f"{r['window_s']:g}",
                    f"{r['k']:g}",
                    f"{r['time_threshold_s']:g}",
                    f"{r['rate_per_h']:.3g}",
                    f"{r['rate_upper_per_h']:.3g}",
                    f"{r['response_p95_s']:.1f}",
                    f"{r['availability']:.3f}",
                    f"{r['accuracy']:.3f}",
                    "" if r["auc"] != r["auc"] else f"{r['auc']:.3f}",
                )
            console.print(c)
        flights = len(set(zip(table["dataset"].to_pylist(), table["flight_id"].to_pylist())))
        console.print(
            f"{table.num_rows:,} rows ({len(grid)} grid points x {flights} flights"
            + (f" x {len(sensors)} sensors" if sensors else "")
            + f") written to {out}",
            highlight=False,
        )
    except FlightmodeError as e:
        _die(e)


@app.command("certify")
def certify_cmd(
    datasets: Annotated[list[Path], typer.Argument(help="Dataset folders made by `flightmode dataset`.")],
    target_fa_per_h: Annotated[
        float, typer.Option("--target-fa-per-h", help="Target: false statics per in-window flight-hour.")
    ] = 1e-4,
    confidence: Annotated[float, typer.Option("--confidence", help="Confidence of the claim.")] = 0.95,
    max_response_s: Annotated[
        float | None, typer.Option("--max-response-s", help="Response p95 limit at the gate, s.")
    ] = None,
    pm: Annotated[
        float,
        typer.Option(
            "--pm", help="Seed 000 section 5.1.1: the probability of misdetection to set the threshold from."
        ),
    ] = 1e-3,
    method: Annotated[str, typer.Option("--method", help=GRID_HELP["method"])] = "nmv,emv",
    weight: Annotated[str, typer.Option("--weight", help=GRID_HELP["weight"])] = "5",
    window_s: Annotated[str, typer.Option("--window-s", help=GRID_HELP["window_s"])] = "0.5,1,2",
    k: Annotated[str, typer.Option("--k", help=GRID_HELP["k"])] = "2:8:0.5",
    time_threshold_s: Annotated[
        str, typer.Option("--time-threshold-s", help=GRID_HELP["time_threshold_s"])
    ] = "1:8:1",
    sigma2_from: Annotated[
        str, typer.Option("--sigma2-from", help="preset (each unit's bench calibration) or rest.")
    ] = "preset",
    sensor: Annotated[
        str | None,
        typer.Option(
            "--sensor",
            help="Re-sense every flight with these presets (e.g. lis302dl,lis302dl-8g; a dataset made with --truth full).",
        ),
    ] = None,
    workers: Annotated[
        int, typer.Option("--workers", help="Dask worker processes for the sweep (1: in this process).")
    ] = 1,
    out: Annotated[
        Path | None,
        typer.Option(
            "--out", help="The report folder (default DATASET/certify; needed for several datasets)."
        ),
    ] = None,
) -> None:
    """Find the Pareto front of (false-static bound, response, availability), recommend the parameters
    that meet the target with the best response (or say how many flight-hours the dataset lacks), set
    seed 000 section 5.1.1's threshold from the static data, and write report.html with its figures."""
    from flightmode.studies.certify import Target, certify
    from flightmode.studies.sweep import check_request

    try:
        grid = _grid(method, weight, window_s, k, time_threshold_s)
        target = Target(target_fa_per_h, confidence, max_response_s, pm)
        target.validate()
        if out is None:
            if len(datasets) > 1:
                raise ScenarioError("several datasets: give --out, the folder for the report")
            out = Path(datasets[0]) / "certify"
        sensors = _sensors(sensor)
        check_request(datasets, grid, sigma2_from, sensors)
        with _SweepProgress() as progress:
            cert = certify(
                datasets,
                grid,
                target,
                sigma2_from=sigma2_from,
                workers=workers,
                sensors=sensors,
                out=out,
                on_start=progress.start,
                on_flight=progress.advance,
                log=lambda m: console.print(m, highlight=False),
            )
        ex = cert.meta["excluded"]
        if ex:
            console.print(
                f"excluded: {len(ex)} failed flight(s) ("
                + ", ".join(f"{Path(r['dataset']).name}/{r['flight_id']}" for r in ex[:10])
                + ")",
                highlight=False,
            )
        style = {"meets": "green", "too_small": "yellow", "too_slow": "yellow", "unreachable": "red"}[
            cert.recommendation["status"]
        ]
        console.print(Text(f"{cert.recommendation['status']}: {cert.recommendation['text']}", style=style))
        t = Table(
            "method",
            "W_s",
            "k",
            "T_th s",
            "false statics",
            "in-window h",
            f"{confidence:.0%} bound /h",
            "response p50/p95/max s",
            "availability",
            title=f"Pareto front: {len(cert.pareto)} of {len(cert.summary)} points (first 10 by bound)",
        )
        front = sorted(
            (cert.summary[i] for i in cert.pareto), key=lambda r: (r["rate_upper_per_h"], r["response_p95_s"])
        )
        for r in front[:10] + ([cert.seed000] if cert.seed000 else []):
            name = r["method"] + (f" w{r['weight']:g}" if r["method"] == "emv" else "")
            t.add_row(
                name + (" (seed 000)" if r is cert.seed000 else ""),
                f"{r['window_s']:g}",
                f"{r['k']:g}",
                f"{r['time_threshold_s']:g}",
                str(r["false_statics"]),
                f"{r['in_window_h']:,.1f}",
                f"{r['rate_upper_per_h']:.3g}",
                f"{r['response_p50_s']:.1f}/{r['response_p95_s']:.1f}/{r['response_max_s']:.1f}",
                f"{r['availability']:.3f}",
            )
        console.print(t)
        if cert.seed000:
            s = cert.seed000
            console.print(
                f"seed 000's point {'meets' if s['meets'] else 'does not meet'} the target: "
                f"{s['false_statics']} false statics in {s['in_window_h']:,.1f} h, bound "
                f"{s['rate_upper_per_h']:.3g} /h, response p95 {s['response_p95_s']:.1f} s, "
                f"availability {s['availability']:.3f}",
                highlight=False,
            )
        which = "seed000" if "seed000" in cert.breakdowns else "recommended"
        b = Table(
            "condition",
            "value",
            "flights",
            "in-window h",
            "false statics",
            "response p95 s",
            title=f"by condition at {'seed 000' if which == 'seed000' else 'the recommended'} point",
        )
        for r in cert.breakdowns[which]:
            b.add_row(
                r["condition"],
                r["value"],
                str(r["flights"]),
                f"{r['in_window_h']:,.1f}",
                str(r["false_statics"]),
                "" if r["response_p95_s"] != r["response_p95_s"] else f"{r['response_p95_s']:.1f}",
            )
        console.print(b)
        th = cert.threshold
        if th:
            console.print(
                f"section 5.1.1 at P_M {th['pm']:g} ({th['static_checks']:,} static checks, W_s {th['window_s']:g} s): "
                f"k = {th['empirical_k']:.2f} measured{'' if th['empirical_resolved'] else ' (not resolved)'}, "
                f"{th['gaussian_measured_k']:.2f} eq. 13 with the measured spread, "
                f"{th['gaussian_white_k']:.2f} eq. 13 white, {th['chi2_white_k']:.2f} chi-square white",
                highlight=False,
            )
        console.print(f"report: {Path(out) / 'report.html'}", highlight=False)
    except FlightmodeError as e:
        _die(e)


@app.command("validate")
def validate_cmd(
    run_dir: Annotated[
        Path,
        typer.Argument(
            help="A run folder written by `flightmode fly`, or a dataset folder "
            "(`flightmode dataset ... --truth full`): every flight, summarised per type."
        ),
    ],
    paper_flight: Annotated[
        int,
        typer.Option(
            "--paper-flight",
            help="Seed 000 flight whose P_FA table to compare: 1 (Table 4) or 2 (Table 5, calm).",
        ),
    ] = 1,
    as_json: Annotated[
        bool,
        typer.Option("--json", help="Print the checks (a dataset: the summary) as JSON instead of a table."),
    ] = False,
    strict: Annotated[
        bool, typer.Option("--strict", help="Exit with status 1 if any check (of any flight) fails.")
    ] = False,
    workers: Annotated[
        int,
        typer.Option("--workers", help="A dataset: local worker processes (a LocalCluster on 127.0.0.1)."),
    ] = 1,
    checks_out: Annotated[
        Path | None,
        typer.Option(
            "--checks-out", help="A dataset: also write every flight's checks to this Parquet file."
        ),
    ] = None,
) -> None:
    """Set a run's figures beside their public anchors (WRAP, ADS-B taxi tracks, ICAO, NASA, seed 000);
    for a dataset, each figure's distribution over its flights, per aircraft type."""
    from flightmode.datasets.make import is_dataset

    if is_dataset(run_dir):
        _validate_dataset(run_dir, paper_flight, as_json, strict, workers, checks_out)
        return
    from flightmode.studies.validate import validate_run

    try:
        checks = validate_run(run_dir, paper_flight)
    except FlightmodeError as e:
        _die(e)
    judged = [c for c in checks if c.judged]
    failed = sum(not c.passed for c in judged)
    if as_json:
        import json

        typer.echo(
            json.dumps(
                {
                    "run_dir": str(run_dir),
                    "passed": len(judged) - failed,
                    "failed": failed,
                    "not_judged": len(checks) - len(judged),
                    "checks": [_finite(c.as_dict()) for c in checks],
                },
                indent=1,
                allow_nan=False,
            )
        )
    else:
        table = Table(title=f"{run_dir}: the run beside its anchors", title_justify="left")
        for col, kw in (
            ("group", {}),
            ("figure", {}),
            ("anchor", {"justify": "right"}),
            ("this run", {"justify": "right"}),
            ("", {}),
            ("source / note", {}),
        ):
            table.add_column(col, **kw)
        for c in checks:
            mark = (
                Text("-", style="dim")
                if not c.judged
                else Text("pass", style="green")
                if c.passed
                else Text("FAIL", style="bold red")
            )
            note = c.source + (f"; {c.note}" if c.note else "")
            table.add_row(c.group, f"{c.figure} ({c.unit})", c.anchor_text(), f"{c.value:.4g}", mark, note)
        console.print(table)
        shown = len(checks) - len(judged)
        console.print(
            f"{len(judged) - failed} of {len(judged)} checks pass"
            + (f"; {shown} shown without an anchor (-)" if shown else ""),
            highlight=False,
        )
    if strict and failed:
        raise typer.Exit(code=1)


def _validate_dataset(
    dataset: Path, paper_flight: int, as_json: bool, strict: bool, workers: int, checks_out: Path | None
) -> None:
    """`flightmode validate DATASET`: every flight's checks, one table per aircraft type."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

    from flightmode.studies import validate_population as vp

    try:
        ok, _ = vp.check_request(dataset, paper_flight)
        with Progress(
            TextColumn("flights"),
            BarColumn(),
            MofNCompleteColumn(),
            TimeElapsedColumn(),
            console=err_console,
            transient=True,
        ) as bar:
            task = bar.add_task("flights", total=len(ok))
            results, not_flown = vp.validate_dataset(
                dataset, paper_flight, workers, on_done=lambda _: bar.update(task, advance=1)
            )
        if checks_out is not None:
            from flightmode.datasets.make import atomic_parquet

            atomic_parquet(vp.checks_table(results), Path(checks_out))
    except FlightmodeError as e:
        _die(e)
    summary = vp.summarise(results)
    errors = [r for r in results if "error" in r]
    failing = sum(s.n_judged - s.passed for s in summary)
    if as_json:
        import json

        typer.echo(
            json.dumps(
                {
                    "dataset": str(dataset),
                    "flights_validated": len(results) - len(errors),
                    "not_validated": [{"flight_id": r["flight_id"], "error": r["error"]} for r in errors],
                    "failed_to_fly": len(not_flown),
                    "failing_checks": failing,
                    "figures": [_finite(s.as_dict()) for s in summary],
                },
                indent=1,
                allow_nan=False,
            )
        )
    else:
        for aircraft in dict.fromkeys(s.aircraft for s in summary):
            rows = [s for s in summary if s.aircraft == aircraft]
            n = max(s.flights for s in rows)
            table = Table(
                title=f"{dataset}: {aircraft}, {n} flights beside the anchors", title_justify="left"
            )
            for col in ("group", "figure", "anchor", "p5", "median", "p95", "pass", "95 % CI", "source"):
                table.add_column(
                    col, justify="right" if col in ("anchor", "p5", "median", "p95", "pass") else "left"
                )
            for s in rows:
                style = (
                    "dim"
                    if s.n_judged == 0
                    else "green"
                    if s.passed == s.n_judged
                    else "bold red"
                    if s.passed == 0
                    else "yellow"
                )
                # a figure some flights show without judging it (a bag lying unlike the paper's): "3/5 of 7"
                shown = f" of {s.flights}" if s.n_judged != s.flights else ""
                table.add_row(
                    s.group,
                    f"{s.figure} ({s.unit})",
                    s.anchor,
                    f"{s.p5:.4g}",
                    f"{s.median:.4g}",
                    f"{s.p95:.4g}",
                    Text(f"{s.passed}/{s.n_judged}{shown}", style=style),
                    f"{s.pass_ci[0]:.2f}-{s.pass_ci[1]:.2f}",
                    s.source,
                )
            console.print(table)
        console.print(
            f"{len(results) - len(errors)} flights validated, {failing} failing checks; "
            f"{len(not_flown)} flights of the dataset failed to fly",
            highlight=False,
        )
        for r in errors:
            err_console.print(Text(f"flight {r['flight_id']} not validated: {r['error']}"), highlight=False)
    if strict and (failing or errors):
        raise typer.Exit(code=1)


def _finite(d: dict) -> dict:
    """JSON has no infinities: a value of -inf (a fraction of zero on a log scale) becomes null."""
    import math

    return {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in d.items()}


@app.command("view")
def view_cmd(
    source: Annotated[Path, typer.Argument(help="A run folder (its recording.rrd) or an .rrd file.")],
    web: Annotated[
        bool, typer.Option("--web", help="Serve the web viewer on 127.0.0.1 and print its URL.")
    ] = False,
    port: Annotated[
        int | None, typer.Option("--port", help="Web viewer HTTP port (default: a free one).")
    ] = None,
) -> None:
    """Open a recording in a new Rerun viewer (native), or serve the web viewer on 127.0.0.1."""
    import subprocess

    from flightmode.viz import viewer

    try:
        rrd = viewer.resolve_rrd(source)
        if web:
            cmd, url = viewer.web_command(rrd, port or viewer.free_port(), viewer.free_port())
            console.print(Text.assemble("web viewer (127.0.0.1 only): ", (url, "bold")), highlight=False)
            console.print(
                "Ctrl-C stops it. Rerun's viewer sends anonymous usage analytics unless you run "
                "`rerun analytics disable`.",
                highlight=False,
            )
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
    sensor: Annotated[str | None, typer.Option("--sensor", help="Accelerometer preset.")] = None,
    carrier: Annotated[
        list[str] | None,
        typer.Option("--carrier", help="KEY=VALUE carrier setting, e.g. placement=hold (repeatable)."),
    ] = None,
    out: Annotated[
        Path | None, typer.Option("--out", help="Output folder (default: beside RUN_DIR).")
    ] = None,
    gyro: Annotated[
        bool, typer.Option("--gyro", help="Also record a gyroscope channel (a Bosch BMI270).")
    ] = False,
) -> None:
    """Re-sense an existing flight with another sensor or carrier into a new run folder."""
    from flightmode.runs import pipeline, run_io
    from flightmode.sim.sensor.gyroscope import get_preset as gyro_preset

    try:
        track, info = run_io.read_track(run_dir)
        sc = run_io.run_scenario(info, str(run_dir))
        changes = dict(_key_value(item) for item in carrier or [])
        if changes:
            sc = sc.replace(carrier=changes)  # validated as strictly as a scenario file
        if sensor is not None:
            sc = sc.replace(sensor={"preset": sensor, "odr_hz": None})
        t0 = time.perf_counter()
        # the run's own sensor streams: the same preset and carrier give its samples.parquet again
        # (labels exactly, counts to one step: truth.parquet stores the forces in float32)
        rec = pipeline.sense(
            track,
            sc.carrier,
            sc.sensor,
            pipeline.streams_of(sc.seed).child("sensor"),
            gyro=gyro_preset("bmi270") if gyro else None,
        )
        wall = time.perf_counter() - t0
        tag = "-".join([rec.preset] + [f"{k}-{v}" for k, v in sorted(changes.items())])
        rid = f"{info['run_id']}-{tag}"
        with run_io.staged_run_dir(out or Path(run_dir).parent, rid) as stage:
            run_io.write_samples(stage, rec)
            new = dict(info)
            new["run_id"] = rid
            new["scenario_toml"] = sc.to_toml()
            new["scenario_sha256"] = sc.digest()
            new["truth"] = dict(info["truth"], path=str(Path(run_dir).resolve() / "truth.parquet"))
            new["sensor"] = rec.summary()
            new["wall_time_s"] = {"sense": wall}
            for stale in ("detector", "path", "path_laws_m"):  # of the other recording
                new.pop(stale, None)
            run_io.write_run_json(stage, new)
        _print_sensor(rec)
        console.print(
            Text.assemble(
                "wrote ", (str((out or Path(run_dir).parent) / rid), "bold"), " (samples.parquet, run.json)"
            )
        )
    except FlightmodeError as e:
        _die(e)


def _key_value(item: str) -> tuple[str, object]:
    """``KEY=VALUE`` of a --carrier option, the value typed as the scenario spec declares it."""
    from flightmode.errors import ScenarioError, did_you_mean
    from flightmode.scenarios.spec import SPEC

    if "=" not in item:
        raise ScenarioError(f"--carrier {item!r}: write KEY=VALUE, e.g. placement=hold")
    k, v = item.split("=", 1)
    keys = SPEC["carrier"]
    if k not in keys:
        raise ScenarioError(
            f"--carrier {k}: unknown carrier key{did_you_mean(k, keys)}; keys: {', '.join(keys)}"
        )
    want = keys[k].type
    if want is str:
        return k, v
    try:
        return k, (int(v) if want is int else float(v))
    except ValueError:
        raise ScenarioError(
            f"--carrier {k}={v!r}: must be {'an integer' if want is int else 'a number'} ({keys[k].doc})"
        ) from None


def _print_summary(plan, track, m: dict, wall_s: float) -> None:
    from flightmode.units import KT_MPS

    kt = 1.0 / KT_MPS
    t = Table(
        title=f"{plan.name}: {plan.aircraft}, {plan.origin.icao} {plan.origin.name} -> "
        f"{plan.destination.icao} {plan.destination.name}",
        show_header=False,
    )
    t.add_column("quantity")
    t.add_column("value", justify="right")
    rows = [
        (
            "gate to gate",
            f"{m['gate_to_gate_s'] / 60:.1f} min  ({track.n:,} samples at {track.fs_hz:.0f} Hz)",
        ),
        ("taxi-out (pushback to brake release)", f"{m['taxi_out_s'] / 60:.1f} min"),
        ("liftoff speed", f"{m['liftoff_ias_mps'] * kt:.0f} kt IAS"),
        ("mean takeoff acceleration", f"{m['takeoff_accel_mps2']:.2f} m/s^2"),
        ("initial climb rate (to 1500 ft)", f"{m['initial_climb_vs_mps']:.1f} m/s"),
        ("cruise altitude", f"{m['cruise_alt_m']:.0f} m"),
        ("final approach vertical rate", f"{m['final_approach_vs_mps']:.2f} m/s"),
        ("touchdown sink rate", f"{m['touchdown_sink_mps'] / 0.3048 * 60:.0f} ft/min"),
        (
            "touchdown speed",
            f"{m['touchdown_ias_mps'] * kt:.0f} kt IAS, {m['touchdown_gs_mps']:.1f} m/s ground",
        ),
        (
            "touchdown point",
            f"{m['touchdown_past_threshold_m']:.0f} m past threshold, "
            f"{m['touchdown_centreline_offset_m']:+.1f} m from centreline",
        ),
        ("rollout deceleration", f"{m['rollout_decel_mps2']:.2f} m/s^2 over {m['rollout_distance_m']:.0f} m"),
        ("taxi-in", f"{m['taxi_in_s'] / 60:.1f} min"),
        (
            "in-flight window (pushback to engines off)",
            f"{track.in_flight_window.sum() / track.fs_hz / 60:.1f} min",
        ),
        ("wall time", f"{wall_s:.1f} s ({track.duration_s / wall_s:.0f}x real time)"),
    ]
    for k, v in rows:
        t.add_row(k, v)
    console.print(t)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(app())
