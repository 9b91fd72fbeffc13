"""``flightmode sweep`` and ``flightmode certify``: a detector grid over datasets, and its claim."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, Any

import typer
from rich.table import Table

from flightmode.cli.common import JSON_HELP, WORKERS_HELP, comma_list, console, emit_json
from flightmode.errors import ScenarioError

# the default grid of sweep and certify: NMV and EMV (weight 5), three windows, 13 k, 8 time thresholds
# (624 points); each moving variance is computed once, so the grid costs little more than one point
GRID_HELP = {
    "method": "Methods, a comma list: nmv, emv (the moving-variance paper), nmv+baro, emv+baro (the redundant "
    "rule with the samples' barometer) and the activity-detector study's amvd, amd, ared, shod, frd, ltsd, fsd, "
    "mbgtd, mbcd (ared and shod read the gyroscope; the flexible ones take :acc, :gyr, :sum or :product, e.g. "
    "fsd:sum) (threshold k x the merit at rest; the memory detectors mbgtd and mbcd keep the study's own "
    "window of samples, O(N^2) per sample, whatever W_s).",
    "weight": "EMV weighting factors, e.g. 1,5,10 (paired with each EMV method).",
    "window_s": "Windows W_s, s (list or start:stop:step).",
    "k": "Amplitude thresholds T_sigma = k sigma^2.",
    "time_threshold_s": "Time thresholds T_th, s.",
    "sensor": "Re-sense every flight with these presets, one or a comma list (e.g. lis302dl,lis302dl-8g; "
    "a dataset made with --truth full).",
    "sigma2_from": "preset (each unit's bench calibration) or rest.",
    "detector": "A detector of the interface, repeatable: a registered name (nmv, two-source, eobs-duty, "
    "a plugin's entry point) or package.module:make; each runs per sample on every flight, side by side "
    "with the others (--method is then off unless given).",
    "param": "key=value for every --detector (repeatable; values read as TOML).",
    "grid_file": "A TOML file of [[detector]] tables (name, spec, channels, grace_s, [detector.params], "
    "[detector.grid]: the Cartesian product of its lists); docs/studies.md.",
    "grace_s": "A detector's rest decision carried into the in-flight window from before pushback counts as "
    "a false static when it lasts this long (default 1 s, seed 000's W_s: the built-ins' resolution).",
}
DEFAULT_METHODS = "nmv,emv"


def grid_and_detectors(method, weight, window_s, k, time_threshold_s, detector, param, grid_file, grace_s):
    """The built-in grid (None when detectors are given and --method is not) and the detector entries
    of --detector/--param and --grid-file (:mod:`flightmode.studies.detectors`)."""
    from flightmode.detector.grid import grid_from_text
    from flightmode.studies import detectors as dets

    if param and not detector:
        raise ScenarioError("--param: give the --detector it is for (or use --grid-file)")
    entries = dets.from_cli(detector or [], param or [], grace_s)
    if grid_file is not None:
        entries += dets.from_toml(grid_file, grace_s)
    if method is None and entries:
        return None, entries
    grid = grid_from_text(method or DEFAULT_METHODS, weight, window_s, k, time_threshold_s)
    return grid, entries


class SweepProgress:
    """A progress bar shown only once the sweep starts (certify may reuse a sweep and sweep nothing)."""

    def __init__(self, quiet: bool = False):
        self.quiet = quiet

    def __enter__(self):
        from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeElapsedColumn

        self.bar = Progress(
            TextColumn("sweeping"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(), console=console()
        )
        self.task = self.bar.add_task("sweep", total=None)
        self.started = False
        return self

    def start(self, flights: int) -> None:
        self.bar.update(self.task, total=flights)
        if not self.quiet:
            self.bar.start()
            self.started = True

    def advance(self, flight_id: str) -> None:
        self.bar.update(self.task, advance=1)

    def __exit__(self, *exc):
        if self.started:
            self.bar.stop()


def excluded(failed: list[dict]) -> None:
    if failed:
        console().print(
            f"excluded: {len(failed)} failed flight(s) ("
            + ", ".join(f"{Path(r['dataset']).name}/{r['flight_id']}" for r in failed[:10])
            + (", ..." if len(failed) > 10 else "")
            + ")",
            highlight=False,
        )


def point_name(r: dict, recommended: bool) -> str:
    if r.get("params"):  # a detector of the interface: its label and parameters
        return r["method"] + ("" if r["params"] == "{}" else f" {r['params']}")
    name = r["method"] + (f" w{r['weight']:g}" if r["method"].startswith("emv") else "")
    return name + (" (the paper's point)" if recommended else "")


def _is_paper_point(r: dict) -> bool:
    from flightmode.detector.recommended import RECOMMENDED as R

    return (r["method"], r["window_s"], r["k"], r["time_threshold_s"]) == (
        R.method,
        R.window_s,
        R.k_sigma,
        R.time_threshold_s,
    )


def out_of(out: Path | None, datasets: list[Path], name: str, what: str) -> Path:
    if out is not None:
        return out
    if len(datasets) > 1:
        raise ScenarioError(f"several datasets: give --out, the folder for {what}")
    return Path(datasets[0]) / name


def sweep_cmd(
    datasets: Annotated[list[Path], typer.Argument(help="Dataset folders made by `flightmode dataset`.")],
    method: Annotated[str | None, typer.Option("--method", help=GRID_HELP["method"])] = None,
    weight: Annotated[str, typer.Option("--weight", help=GRID_HELP["weight"])] = "5",
    window_s: Annotated[str, typer.Option("--window-s", help=GRID_HELP["window_s"])] = "0.5,1,2",
    k: Annotated[str, typer.Option("--k", help=GRID_HELP["k"])] = "2:8:0.5",
    time_threshold_s: Annotated[
        str, typer.Option("--time-threshold-s", help=GRID_HELP["time_threshold_s"])
    ] = "1:8:1",
    sigma2_from: Annotated[str, typer.Option("--sigma2-from", help=GRID_HELP["sigma2_from"])] = "preset",
    sensor: Annotated[str | None, typer.Option("--sensor", help=GRID_HELP["sensor"])] = None,
    workers: Annotated[int, typer.Option("--workers", help=WORKERS_HELP)] = 1,
    out: Annotated[
        Path | None,
        typer.Option("--out", help="The sweep folder (default DATASET/sweep; needed for several datasets)."),
    ] = None,
    confidence: Annotated[float, typer.Option("--confidence", help="Confidence of the upper bounds.")] = 0.95,
    target_fa_per_h: Annotated[
        float, typer.Option("--target-fa-per-h", help="Target false statics per flight-hour.")
    ] = 1e-4,
    top: Annotated[int, typer.Option("--top", help="Grid points to print.")] = 10,
    detector: Annotated[list[str] | None, typer.Option("--detector", help=GRID_HELP["detector"])] = None,
    param: Annotated[list[str] | None, typer.Option("--param", help=GRID_HELP["param"])] = None,
    grid_file: Annotated[Path | None, typer.Option("--grid-file", help=GRID_HELP["grid_file"])] = None,
    grace_s: Annotated[float | None, typer.Option("--grace-s", help=GRID_HELP["grace_s"])] = None,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """Evaluate a grid of detector parameters over every flight of one or more datasets.

    Each moving variance is computed once; prints the best points with exact upper bounds on the
    false-static rate and where they come from, and writes the per-flight rows to OUT. --detector and
    --grid-file add detectors of the interface (run per sample; docs/studies.md)."""
    from flightmode.studies.sweep import (
        breakdown,
        check_request,
        compare_methods,
        rank_points,
        summarise,
        sweep,
    )

    grid, entries = grid_and_detectors(
        method, weight, window_s, k, time_threshold_s, detector, param, grid_file, grace_s
    )
    if not target_fa_per_h > 0:
        raise ScenarioError(f"--target-fa-per-h {target_fa_per_h!r}: must be > 0")
    out = out_of(out, datasets, "sweep", "their common sweep")
    sensors = comma_list(sensor, "--sensor")
    check_request(datasets, grid, sigma2_from, sensors, entries)
    with SweepProgress(quiet=as_json) as progress:
        result = sweep(
            datasets,
            grid,
            sigma2_from=sigma2_from,
            workers=workers,
            sensors=sensors,
            out=out,
            on_start=progress.start,
            on_flight=progress.advance,
            detectors=entries,
        )
    table: Any = result.points
    rows = rank_points(summarise(table, confidence, target_fa_per_h, by_sensor=bool(sensors)))
    shown = rows[:top]
    paper = [r for r in rows if _is_paper_point(r)]
    shown += [r for r in paper if r not in shown]
    best = rows[0]
    by_condition = breakdown(table, best, result.phases)
    methods = compare_methods(table, confidence) if len(set(table["method"].to_pylist())) > 1 else []
    flights = len(set(zip(table["dataset"].to_pylist(), table["flight_id"].to_pylist(), strict=True)))
    if as_json:
        emit_json(
            {
                "out": str(out),
                "excluded": result.failed,
                "points": shown,
                "breakdown": by_condition,
                "methods": methods,
                "rows": table.num_rows,
                "grid_points": len(rows),
                "flights": flights,
            }
        )
        return
    excluded(result.failed)
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
    for r in shown:
        t.add_row(
            point_name(r, r in paper),
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
    console().print(t)
    print_breakdown(
        by_condition,
        f"by condition at {best['method']} W_s {best['window_s']:g} k {best['k']:g} T_th {best['time_threshold_s']:g}",
    )
    if methods:  # the detectors side by side, each at its best point
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
        for r in methods:
            c.add_row(
                point_name(r, False),
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
        console().print(c)
    console().print(
        f"{table.num_rows:,} rows ({len(rows)} grid points x {flights} flights"
        + (f" x {len(sensors)} sensors" if sensors else "")
        + f") written to {out}",
        highlight=False,
    )


def print_breakdown(rows: list[dict], title: str) -> None:
    b = Table("condition", "value", "flights", "in-window h", "false statics", "response p95 s", title=title)
    for r in rows:
        b.add_row(
            r["condition"],
            r["value"],
            str(r["flights"]),
            f"{r['in_window_h']:,.1f}",
            str(r["false_statics"]),
            "" if r["response_p95_s"] != r["response_p95_s"] else f"{r['response_p95_s']:.1f}",
        )
    console().print(b)
