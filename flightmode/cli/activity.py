"""``flightmode activity``: the activity-detector study (nine (in)activity detectors on synthesized
records, grid-searched as the paper did)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from flightmode.cli.common import JSON_HELP, WORKERS_HELP, CountingBar, console, emit_json, sub_app
from flightmode.errors import ScenarioError

activity_app = sub_app("The activity-detector study: nine (in)activity detectors on synthesized records.")


@activity_app.command("synth", epilog="Example: flightmode activity synth --n 50 --out study/")
def activity_synth_cmd(
    n: Annotated[int, typer.Option("--n", help="Synthesized runs (the paper: 500).")] = 500,
    seed: Annotated[
        int, typer.Option("--seed", help="The study's seed (run i: SeedSequence(seed, spawn_key=(i,))).")
    ] = 0,
    workers: Annotated[int, typer.Option("--workers", help=WORKERS_HELP)] = 1,
    out: Annotated[
        Path | None,
        typer.Option("--out", help="Write the tables, runs, ROC curves and figures into this folder."),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """The activity-detector study's Monte Carlo: N synthesized records, every detector grid-searched.

    Every detector and input signal grid-searched for accuracy, ROC/AUC at its best window; Tables
    1-6 and 13 printed beside the paper's."""
    from flightmode.detector.activity import montecarlo as mc

    if n < 1:
        raise ScenarioError(f"--n {n}: the number of runs must be a positive integer")
    with CountingBar("runs", n, quiet=as_json) as bar:
        res = mc.run_montecarlo(n, seed=seed, workers=workers, on_run=bar.advance)
    written = mc.write_results(res, out) if out is not None else {}
    if as_json:
        emit_json(
            {
                "seed": seed,
                "runs": n,
                "tables": mc.summary(res),
                "written": {k: str(v) for k, v in written.items()},
            }
        )
        return
    console().print(mc.format_tables(res), highlight=False, soft_wrap=True)
    if out is not None:
        console().print(f"wrote {len(written)} files to {out}", highlight=False)
