"""``flightmode family`` and ``flightmode dataset``: many flights, described and made."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer
from rich.text import Text

from flightmode.cli.common import JSON_HELP, console, emit_json
from flightmode.errors import ScenarioError


def family_cmd(
    family: Annotated[str, typer.Argument(help="A built-in family name or the path of a family .toml file.")],
    show: Annotated[int, typer.Option("--show", help="Print the first SHOW members.")] = 5,
    start: Annotated[int, typer.Option("--start", help="First member to show.")] = 0,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """Validate a scenario family and print its first members (each a plain scenario).

    A family draws aircraft, routes, turbulence, landings, bags and sensors; member i is regenerated
    alone from the family's seed."""
    from flightmode.scenarios.family import Family, builtin_families
    from flightmode.units import FT_M

    fam = Family.resolve(family)
    if show < 0 or start < 0:
        raise ScenarioError("--show and --start must be >= 0")
    members = [(i, fam.member(i)) for i in range(start, start + show)]
    if as_json:
        emit_json(
            {
                "family": fam.name,
                "seed": fam.seed,
                "sha256": fam.digest(),
                "description": fam.description,
                "members": [
                    {"index": i, "name": m.name, "seed": m.seed, "toml": m.to_toml()} for i, m in members
                ],
            }
        )
        return
    out = console()
    out.print(
        Text.assemble(
            (fam.name, "bold"), f" (seed {fam.seed}, SHA-256 {fam.digest()[:12]}): {fam.description}"
        ),
        highlight=False,
    )
    for i, m in members:
        p, c = m.plan, m.carrier
        turb = ", ".join(
            f"{t.severity} {t.duration_s / 60:.0f} min at {t.start_s / 60:.0f} min" for t in p.turbulence
        )
        where = c.placement if c.kind == "handbag" else f"hold, {c.truck_s / 60:.0f} min by road"
        handled = f", handled x{c.handled_in_cruise}" if c.kind == "handbag" and c.handled_in_cruise else ""
        out.print(
            f"{i:>5}  {m.aircraft:<9} {p.origin.icao} {p.origin.name:<4} -> {p.destination.icao} "
            f"{p.destination.name:<4} FL{p.cruise_alt_m / FT_M / 100:03.0f}  turbulence: {turb or 'none'}; "
            f"landing {p.landing_quality}; {c.kind}, {where}{handled}; {m.sensor.preset}"
            + (f", vibration x{m.sensor.vibration_level:g}" if m.sensor.vibration_level else "")
            + f"; seed {m.seed}",
            highlight=False,
            soft_wrap=True,
        )
    out.print(f"built-in families: {', '.join(builtin_families())}", highlight=False)


def dataset_cmd(
    family: Annotated[str, typer.Argument(help="A built-in family name or the path of a family .toml file.")],
    n: Annotated[int, typer.Option("--n", help="Number of flights (members 0..N-1).")],
    out: Annotated[Path, typer.Option("--out", help="The dataset folder.")],
    workers: Annotated[
        int,
        typer.Option(
            "--workers",
            help="Dask worker processes on 127.0.0.1 (a dataset is whole flights: always a cluster, default 2).",
        ),
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
        bool, typer.Option("--rrd", help="Also write each flight's Rerun recording (OUT/rrd/).")
    ] = False,
    verify: Annotated[
        bool,
        typer.Option(
            "--verify",
            help="With --resume: first check every recorded flight's files against the manifest's "
            "SHA-256, and fly again those missing or damaged.",
        ),
    ] = False,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """Make a labelled dataset of a family's first N flights on Dask.

    OUT holds hive-partitioned Parquet (samples/, truth/), the manifest flights.parquet and the card
    README.md; a killed run resumes with --resume, and --resume --verify also flies again any flight
    whose files were damaged or lost since."""
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    from flightmode.datasets.make import check_request, make_dataset

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
        verify=verify,
    )
    damaged: dict[str, str] = {}
    with Progress(
        TextColumn("[progress.description]{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TextColumn("{task.fields[hours]:.1f} flight-h, {task.fields[failed]} failed"),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
        console=console(),
        disable=as_json,
    ) as progress:
        task = progress.add_task("flights", total=None, hours=0.0, failed=0)
        state = {"hours": 0.0, "failed": 0}

        def on_start(dashboard: str | None, todo: int) -> None:
            progress.update(task, total=todo)
            if dashboard and not as_json:
                progress.console.print(f"Dask dashboard: {dashboard}", highlight=False)

        def on_flight(row: dict) -> None:
            state["hours"] += (row.get("gate_to_gate_s") or 0.0) / 3600.0
            state["failed"] += row["status"] != "ok"
            progress.update(task, advance=1, hours=state["hours"], failed=state["failed"])
            if row["status"] != "ok" and not as_json:
                progress.console.print(f"flight {row['flight_id']} failed: {row['error']}", highlight=False)

        def on_damaged(found: dict[str, str]) -> None:
            damaged.update(found)
            if as_json:
                return
            if not found:
                progress.console.print(
                    "verified: every recorded flight's files match the manifest", highlight=False
                )
            for fid, why in found.items():
                progress.console.print(f"flight {fid} flown again: {why}", highlight=False)

        if verify and not as_json:  # reading every file takes about 1 s per GB
            progress.console.print(
                "checking the recorded flights' files against the manifest", highlight=False
            )
        try:
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
                verify=verify,
                on_start=on_start,
                on_flight=on_flight,
                on_damaged=on_damaged,
            )
        except KeyboardInterrupt:  # Ctrl-C: every flight recorded so far is whole (atomic writes)
            progress.stop()
            print(
                f"interrupted: {out} holds the flights finished so far; run the same command with "
                "--resume to finish it",
                file=sys.stderr,
            )
            raise typer.Exit(130) from None
    ok = sum(r["status"] == "ok" for r in rows.values() if r["index"] < n)
    if as_json:
        emit_json(
            {"dataset": str(out), "flights_ok": ok, "flights_failed": n - ok}
            | ({"flown_again": damaged} if verify else {})
        )
        return
    console().print(
        Text.assemble(
            "wrote ",
            (str(out), "bold"),
            f": {ok} flights ok, {n - ok} failed; manifest flights.parquet, card README.md",
        ),
        highlight=False,
    )
