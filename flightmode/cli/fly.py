"""``flightmode fly`` and ``flightmode sense``: one flight gate to gate, and a flight sensed again."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer
from rich.table import Table
from rich.text import Text

from flightmode.cli.common import JSON_HELP, comma_list, console, emit_json
from flightmode.errors import ScenarioError

DEFAULT_SCENARIO = "gva-lhr-a320"  # the same as flightmode.scenarios.scenario.DEFAULT_SCENARIO (tested)


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
        str | None, typer.Option("--sensor", help="One accelerometer preset (default: the scenario's).")
    ] = None,
    gyro: Annotated[
        bool, typer.Option("--gyro", help="Also record a gyroscope channel (a Bosch BMI270).")
    ] = False,
    baro: Annotated[
        str | None,
        typer.Option(
            "--baro",
            help="Fit a barometer (bmp581, bmp581-osrN, lps22hh, ideal): samples gain baro_pa, "
            "and the redundant rule runs.",
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
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """Fly a scenario gate to gate in JSBSim, sense it and run the detector.

    Writes truth.parquet, samples.parquet, run.json and recording.rrd into OUT/<scenario>-s<seed>/.
    With --from, --to and --aircraft, fly between any two airports with paved runways (OurAirports
    data)."""
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario

    pair = (origin, destination, aircraft)
    if any(v is not None for v in pair):
        if origin is None or destination is None or aircraft is None:
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
    if as_json:
        result = pipeline.run(sc, sensor=sensor, out=out, gyro=gyro, rrd=rrd)
        emit_json(_fly_json(result, out))
        return
    from flightmode.cli.fly_report import print_fly, progress_bar

    console().print(Text.assemble((sc.name, "bold"), f" seed {sc.seed}: {sc.description}"), highlight=False)
    with progress_bar(sc.plan) as (on_progress, on_stage, done):
        result = pipeline.run(
            sc, sensor=sensor, out=out, gyro=gyro, rrd=rrd, progress=on_progress, on_stage=on_stage
        )
        done(result.track.duration_s if result.track is not None else 0.0)
    print_fly(result, out)


def _fly_json(result, out: Path) -> dict:
    e = result.detection
    return {
        "run_dir": str(Path(out) / result.run_id),
        "summary": result.metrics,
        "sensor": result.recording.summary(),
        "detector": {
            "false_static_count": e.false_static_count,
            "false_static_s": e.false_static_s,
            "response_s": e.response_s,
            "accuracy": e.accuracy,
        },
        "ground_rolls": [] if result.path is None else [c.as_dict() for c in result.path.ground_rolls],
        "wall_s": result.wall_s,
        "written": {k: str(v) for k, v in result.written.items()},
    }


def sense_cmd(
    run_dir: Annotated[Path, typer.Argument(help="A run folder written by `flightmode fly`.")],
    sensor: Annotated[
        str | None,
        typer.Option("--sensor", help="Accelerometer preset, or a comma list (one new run folder each)."),
    ] = None,
    carrier: Annotated[
        list[str] | None,
        typer.Option("--carrier", help="KEY=VALUE carrier setting, e.g. placement=hold (repeatable)."),
    ] = None,
    out: Annotated[
        Path | None, typer.Option("--out", help="Output folder (default: the folder holding RUN_DIR).")
    ] = None,
    gyro: Annotated[
        bool, typer.Option("--gyro", help="Also record a gyroscope channel (a Bosch BMI270).")
    ] = False,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """Sense a flown run again with another sensor or carrier, into a new run folder.

    The run's own truth and sensor streams: the same preset and carrier give its samples again. The
    new folder is OUT/<run_id>-<preset>[-key-value...]/ (samples.parquet, run.json)."""
    from flightmode.runs.resense import carrier_changes, resense_run

    changes = carrier_changes(carrier or [])
    done = []
    for preset in comma_list(sensor, "--sensor") or (None,):
        rec, folder = resense_run(run_dir, sensor=preset, carrier=changes, out=out, gyro=gyro)
        done.append((rec, folder))
    if as_json:
        emit_json([{"run_dir": str(f), "sensor": r.summary()} for r, f in done])
        return
    from flightmode.cli.fly_report import print_sensor

    for rec, folder in done:
        print_sensor(rec)
        console().print(Text.assemble("wrote ", (str(folder), "bold"), " (samples.parquet, run.json)"))


def scenarios_cmd(
    spec: Annotated[
        bool, typer.Option("--spec", help="Print every section and key a scenario file may hold.")
    ] = False,
    phases: Annotated[
        bool, typer.Option("--phases", help="Print the pilot's phase transition table.")
    ] = False,
    model: Annotated[
        bool,
        typer.Option(
            "--model",
            help="Print the uncertain model parameters a [model] table may override (value, range, "
            "unit, source, what each shapes).",
        ),
    ] = False,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """List the built-in scenarios, each with a one-line description.

    --spec prints the scenario file format, --phases the pilot's phase transition table, --model the
    uncertain model parameters (what `flightmode certify --uncertainty` varies)."""
    from flightmode.errors import FlightmodeError

    if model:
        from flightmode.cli.model import print_registry

        print_registry(as_json)
        return

    if spec:
        from flightmode.scenarios.spec import spec_text

        console().print(spec_text(), highlight=False, markup=False)
        return
    if phases:
        from flightmode.sim.flight.pilot.phases import TRANSITIONS

        if as_json:
            emit_json(
                [
                    {"from": t.source, "condition": t.condition, "doc": t.doc, "to": t.target}
                    for t in TRANSITIONS
                ]
            )
            return
        table = Table(title="the pilot's phase transitions (sim.flight.pilot.phases.TRANSITIONS)")
        for c in ("from phase", "condition", "to phase"):
            table.add_column(c)
        for tr in TRANSITIONS:
            table.add_row(
                tr.source,
                Text.assemble((tr.condition, "bold"), ": ", tr.doc),
                tr.target or "(end of the flight)",
            )
        console().print(table)
        return
    from flightmode.scenarios.scenario import Scenario, builtin_names

    rows: list[dict[str, Any]] = []
    for name in builtin_names():
        try:
            sc = Scenario.builtin(name)
            rows.append({"name": name, "aircraft": sc.aircraft, "description": sc.description, "error": None})
        except FlightmodeError as e:  # a broken built-in must not hide the others
            rows.append({"name": name, "aircraft": None, "description": None, "error": str(e)})
    if as_json:
        emit_json({"default": DEFAULT_SCENARIO, "scenarios": rows})
        return
    table = Table(title="built-in scenarios", show_lines=False)
    table.add_column("name", style="bold")
    table.add_column("aircraft")
    table.add_column("description")
    for r in rows:
        if r["error"]:
            table.add_row(r["name"], "?", Text(r["error"], style="red"))
            continue
        marker = " (default)" if r["name"] == DEFAULT_SCENARIO else ""
        table.add_row(r["name"] + marker, r["aircraft"], Text(r["description"]))
    console().print(table)
