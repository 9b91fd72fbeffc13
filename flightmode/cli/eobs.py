"""``flightmode eobs``: the e-obs tag note's toolkit (calibration, Movebank detection, the battery
trade-off on flights)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, TypedDict

import typer
from rich.table import Table
from rich.text import Text

from flightmode.cli.common import JSON_HELP, WORKERS_HELP, CountingBar, console, emit_json, sub_app
from flightmode.errors import ScenarioError

eobs_app = sub_app(
    "The e-obs tag note's toolkit: calibration, Movebank detection, the battery trade-off on flights."
)

CALIBRATION_FILE = "calibration.toml"  # what `flightmode eobs calibrate --out DIR` writes into DIR
TRADEOFF_FILE = "tradeoff.parquet"  # what `flightmode eobs tradeoff --out DIR` writes into DIR
BURSTS_HELP = "Final static after this many quiet bursts in a row."


class _DetectRow(TypedDict):
    """One individual's line of `flightmode eobs detect` (its JSON and its table)."""

    individual: str
    axes: str
    bursts: int
    quiet: int
    final_static: int
    sigma2_g2: list[float]


@eobs_app.command("detect", epilog="Example: flightmode eobs detect tag.csv --tag-number 2242")
def eobs_detect_cmd(
    source: Annotated[Path, typer.Argument(help="A Movebank e-obs CSV file.")],
    k: Annotated[
        float,
        typer.Option("--k", help="A burst is quiet when its variance is under k sigma^2 on every axis."),
    ] = 4.0,
    bursts: Annotated[int, typer.Option("--bursts", help=BURSTS_HELP)] = 2,
    tag_number: Annotated[
        int | None,
        typer.Option(
            "--tag-number", help="The tag's number (sets the nominal slope; a Movebank id is not one)."
        ),
    ] = None,
    calibration: Annotated[
        Path | None,
        typer.Option("--calibration", help="A calibration TOML written by `flightmode eobs calibrate`."),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """Run the duty-cycled detector over a Movebank e-obs file's bursts, per individual."""
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
        det = detect_movebank(source, k=k, m=bursts, calibration=cal, tag_number=tag_number)
    rows: list[_DetectRow] = [
        {
            "individual": ind.individual,
            "axes": ind.axes,
            "bursts": int(ind.checks.t.shape[0]),
            "quiet": int(ind.checks.quiet.sum()),
            "final_static": int(ind.checks.final_static.sum()),
            "sigma2_g2": [float(v) for v in ind.sigma2_g2],
        }
        for ind in det.individuals.values()
    ]
    if as_json:
        emit_json(
            {
                "source": str(source),
                "nominal": det.nominal,
                "sigma2_source": det.sigma2_source,
                "individuals": rows,
            }
        )
        return
    if det.nominal:
        console().print(
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
        title=f"{source}: burst variance < {k:g} sigma^2 on every axis; final static after {bursts} quiet bursts "
        f"(sigma^2: {det.sigma2_source})",
    )
    for r in rows:
        t.add_row(
            r["individual"],
            r["axes"],
            str(r["bursts"]),
            str(r["quiet"]),
            str(r["final_static"]),
            ", ".join(f"{v:.2e}" for v in r["sigma2_g2"]),
        )
    console().print(t)


@eobs_app.command(
    "tradeoff", epilog="Example: flightmode eobs tradeoff flights/ --interval-s 30,60 --bursts 1,2"
)
def eobs_tradeoff_cmd(
    datasets: Annotated[
        list[Path], typer.Argument(help="Dataset folders made by `flightmode dataset ... --truth full`.")
    ],
    interval_s: Annotated[
        str, typer.Option("--interval-s", help="ACC intervals, s (the tag's burst period), a comma list.")
    ] = "10,30,60,120",
    byte_count: Annotated[
        int,
        typer.Option(
            "--byte-count", help="Bytes per burst (the note's section 9: sets the samples per axis)."
        ),
    ] = 216,
    bursts: Annotated[str, typer.Option("--bursts", help=BURSTS_HELP + " A comma list.")] = "1,2,3",
    k: Annotated[
        float,
        typer.Option("--k", help="A burst is quiet when its variance is under k sigma^2 on every axis."),
    ] = 4.0,
    odr_hz: Annotated[float, typer.Option("--odr-hz", help="Samples per second per axis in a burst.")] = 10.0,
    confidence: Annotated[float, typer.Option("--confidence", help="Confidence of the upper bound.")] = 0.95,
    workers: Annotated[int, typer.Option("--workers", help=WORKERS_HELP)] = 1,
    out: Annotated[
        Path | None, typer.Option("--out", help=f"Also write the per-flight rows to OUT/{TRADEOFF_FILE}.")
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """The battery trade-off of a duty-cycled e-obs tag on simulated flights.

    Samples per hour against false statics per flight-hour and the response at the gate, per ACC
    interval and number of quiet bursts."""

    from flightmode.detector.grid import parse_axis
    from flightmode.eobs.population import summarise, tradeoff_population

    intervals = parse_axis(interval_s, "--interval-s")
    ms = tuple(int(x) for x in parse_axis(bursts, "--bursts"))
    with CountingBar("flights", quiet=as_json) as bar:
        rows = tradeoff_population(
            [str(d) for d in datasets],
            intervals,
            byte_count,
            ms,
            k,
            odr_hz,
            workers,
            on_start=bar.total,
            on_flight=bar.advance,
        )
    if out is not None:
        import pyarrow as pa

        from flightmode.atomic import write_parquet

        write_parquet(pa.Table.from_pylist(rows), Path(out) / TRADEOFF_FILE)
    summary = summarise(rows, confidence)
    if as_json:
        emit_json(summary)
        return
    t = Table(
        "ACC interval s",
        "samples/axis/burst",
        "quiet bursts",
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
    for r in summary:
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
    console().print(t)
    if out is not None:
        console().print(Text.assemble("wrote ", (str(Path(out) / TRADEOFF_FILE), "bold")), highlight=False)


@eobs_app.command(
    "calibrate",
    epilog="Example: flightmode eobs calibrate --plus-x px.csv ... --minus-z mz.csv --out tag2242/",
)
def eobs_calibrate_cmd(
    plus_x: Annotated[Path, typer.Option("--plus-x", help="Movebank CSV of the tag still with X at +1 g.")],
    minus_x: Annotated[Path, typer.Option("--minus-x", help="... X at -1 g.")],
    plus_y: Annotated[Path, typer.Option("--plus-y", help="... Y at +1 g.")],
    minus_y: Annotated[Path, typer.Option("--minus-y", help="... Y at -1 g.")],
    plus_z: Annotated[Path, typer.Option("--plus-z", help="... Z at +1 g.")],
    minus_z: Annotated[Path, typer.Option("--minus-z", help="... Z at -1 g.")],
    out: Annotated[Path, typer.Option("--out", help=f"The folder to write {CALIBRATION_FILE} into.")],
    tag_number: Annotated[
        int | None, typer.Option("--tag-number", help="The tag's number (recorded; old tags <= 2241).")
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """The e-obs note's six-orientation calibration: zero-g count and slope per axis.

    From six static recordings, each a Movebank e-obs file whose bursts all hold the tag in one
    orientation (XYZ bursts); writes OUT/calibration.toml for `flightmode eobs detect --calibration`."""
    from flightmode.eobs.calibration import calibrate_movebank, write_calibration

    files = {"+x": plus_x, "-x": minus_x, "+y": plus_y, "-y": minus_y, "+z": plus_z, "-z": minus_z}
    cal = calibrate_movebank(files, tag_number)
    Path(out).mkdir(parents=True, exist_ok=True)
    path = write_calibration(cal, Path(out) / CALIBRATION_FILE)
    if as_json:
        emit_json(
            {
                "calibration": str(path),
                "zero_count": list(cal.zero_count),
                "slope_g_per_count": list(cal.slope_g_per_count),
            }
        )
        return
    t = Table("axis", "zero-g count", "slope g/count", title=f"seed 003 section 7: {path}")
    for j, a in enumerate("XYZ"):
        t.add_row(a, f"{cal.zero_count[j]:.2f}", f"{cal.slope_g_per_count[j]:.6f}")
    console().print(t)
