"""``flightmode validate``: a run, or every flight of a dataset, beside its public anchors."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.table import Table
from rich.text import Text

from flightmode.cli.common import JSON_HELP, WORKERS_HELP, CountingBar, console, emit_json, err_console

CHECKS_FILE = "checks.parquet"  # what `flightmode validate DATASET --out DIR` writes into DIR


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
            help="The moving-variance paper's flight whose P_FA table to compare: 1 (Table 4) or 2 (Table 5, calm).",
        ),
    ] = 1,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
    strict: Annotated[
        bool, typer.Option("--strict", help="Exit with status 1 if any check (of any flight) fails.")
    ] = False,
    workers: Annotated[int, typer.Option("--workers", help="A dataset: " + WORKERS_HELP)] = 1,
    out: Annotated[
        Path | None,
        typer.Option("--out", help=f"A dataset: also write every flight's checks to OUT/{CHECKS_FILE}."),
    ] = None,
) -> None:
    """Set a run's figures beside their public anchors (WRAP, ADS-B taxi tracks, ICAO, NASA, the paper).

    For a dataset, each figure's distribution over its flights, per aircraft type."""
    from flightmode.datasets.make import is_dataset

    if is_dataset(run_dir):
        _validate_dataset(run_dir, paper_flight, as_json, strict, workers, out)
        return
    from flightmode.studies.validate import validate_run

    checks = validate_run(run_dir, paper_flight)
    judged = [c for c in checks if c.judged]
    failed = sum(not c.passed for c in judged)
    if as_json:
        emit_json(
            {
                "run_dir": str(run_dir),
                "passed": len(judged) - failed,
                "failed": failed,
                "not_judged": len(checks) - len(judged),
                "checks": [c.as_dict() for c in checks],
            }
        )
    else:
        table = Table(title=f"{run_dir}: the run beside its anchors", title_justify="left")
        for col in ("group", "figure", "anchor", "this run", "", "source / note"):
            table.add_column(col, justify="right" if col in ("anchor", "this run") else "left")
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
        console().print(table)
        shown = len(checks) - len(judged)
        console().print(
            f"{len(judged) - failed} of {len(judged)} checks pass"
            + (f"; {shown} shown without an anchor (-)" if shown else ""),
            highlight=False,
        )
    if strict and failed:
        raise typer.Exit(code=1)


def _validate_dataset(
    dataset: Path, paper_flight: int, as_json: bool, strict: bool, workers: int, out: Path | None
) -> None:
    """`flightmode validate DATASET`: every flight's checks, one table per aircraft type."""
    from flightmode.studies import validate_population as vp

    ok, _ = vp.check_request(dataset, paper_flight)
    with CountingBar("flights", len(ok), stderr=True, transient=True) as bar:
        results, not_flown = vp.validate_dataset(dataset, paper_flight, workers, on_done=bar.advance)
    if out is not None:
        from flightmode.atomic import write_parquet

        write_parquet(vp.checks_table(results), Path(out) / CHECKS_FILE)
    summary = vp.summarise(results)
    errors = [r for r in results if "error" in r]
    failing = sum(s.n_judged - s.passed for s in summary)
    if as_json:
        emit_json(
            {
                "dataset": str(dataset),
                "flights_validated": len(results) - len(errors),
                "not_validated": [{"flight_id": r["flight_id"], "error": r["error"]} for r in errors],
                "failed_to_fly": len(not_flown),
                "failing_checks": failing,
                "figures": [s.as_dict() for s in summary],
            }
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
            console().print(table)
        console().print(
            f"{len(results) - len(errors)} flights validated, {failing} failing checks; "
            f"{len(not_flown)} flights of the dataset failed to fly",
            highlight=False,
        )
        for r in errors:
            err_console().print(Text(f"flight {r['flight_id']} not validated: {r['error']}"), highlight=False)
    if strict and (failing or errors):
        raise typer.Exit(code=1)
