"""``flightmode seeds 000``: a source paper's printed tables beside ours (a thin shell over
:mod:`flightmode.studies.seed000`)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from flightmode.cli.common import JSON_HELP, console, emit_json

SEEDS = ("000",)


def seeds_cmd(
    seed: Annotated[
        str, typer.Argument(help="The source paper: 000 (the moving-variance flight-mode detector).")
    ],
    run: Annotated[
        Path | None,
        typer.Option(
            "--run",
            help="Also sense this run folder's flight again at Table 9's rate (66.7 Hz) and its own, "
            "and print P_FA at Table 9's thresholds for both.",
        ),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """Reproduce a source paper's tables on our models and print them beside the paper's."""
    from flightmode.errors import InputDataError

    if seed not in SEEDS:
        from flightmode.errors import did_you_mean

        raise InputDataError(
            f"seed {seed!r}{did_you_mean(seed, SEEDS)}: reproducible here: {', '.join(SEEDS)}"
        )
    from flightmode.studies.seed000 import format_flight, format_tables, reproduce, table9_flight

    r = reproduce()
    if run is not None:
        r["table9_flight"] = table9_flight(run)
    if as_json:
        emit_json(r)
        return
    console().print(format_tables(r), highlight=False, markup=False, soft_wrap=True)
    if run is not None:
        console().print(format_flight(r["table9_flight"], run), highlight=False, markup=False, soft_wrap=True)
