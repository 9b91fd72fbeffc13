"""``flightmode activity``: the activity-detector study (nine (in)activity detectors on synthesized
records, grid-searched as the paper did)."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Annotated, Any

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
    window: Annotated[
        str,
        typer.Option(
            "--window",
            help="causal: a sample's merit is its window ending at it (a stream's); centred: the window "
            "centred on it (the paper's eq. 6 envelope is centred).",
        ),
    ] = "causal",
    grid: Annotated[
        str,
        typer.Option(
            "--grid", help="wide: windows 2-256, the paper's optima inside; narrow: the N=500 run's."
        ),
    ] = "wide",
    compare: Annotated[
        bool,
        typer.Option(
            "--compare",
            help="Also print z-scores against the paper, the AUC rank correlation, the AUC floor, where each "
            "case errs (by period kind) and the grid edges.",
        ),
    ] = False,
    sigma_acc_g: Annotated[
        float, typer.Option("--sigma-acc-g", help="Synthesizer accelerometer noise sd (g).")
    ] = 2.23e-3,
    sigma_gyr_dps: Annotated[
        float, typer.Option("--sigma-gyr-dps", help="Synthesizer gyroscope noise sd (deg/s).")
    ] = 0.05,
    activities: Annotated[
        str | None,
        typer.Option("--activities", help="Comma-separated activity mix (default: all seven of the paper)."),
    ] = None,
    mix: Annotated[
        str,
        typer.Option(
            "--mix",
            help="uniform: each activity drawn at random; figure2: the paper's Figure 2 sequence, cycling; "
            "sequence: the --activities in their order, cycling (repeats allowed).",
        ),
    ] = "uniform",
    mbcd_bandwidth: Annotated[
        float | None,
        typer.Option(
            "--mbcd-bandwidth", help="One fixed MBCD kernel width for every input (default: Silverman)."
        ),
    ] = None,
    period_scale: Annotated[
        float,
        typer.Option(
            "--period-scale",
            help="Scale the still, activity and seated/lying lengths and the record's duration by this "
            "factor (1: 2-8 s still, 3-10 s active, 120 s records; a record keeps its number of periods).",
        ),
    ] = 1.0,
    detectors: Annotated[
        str | None,
        typer.Option("--detectors", help="Comma-separated detectors to grid-search (default: all nine)."),
    ] = None,
) -> None:
    """The activity-detector study's Monte Carlo: N synthesized records, every detector grid-searched.

    Every detector and input signal grid-searched for accuracy, ROC/AUC at its best window; Tables
    1-6 and 13 printed beside the paper's."""
    from flightmode.detector.activity import compare as cmp
    from flightmode.detector.activity import montecarlo as mc
    from flightmode.detector.activity.synth import ACTIVITIES, DEFAULT_RANGES, FIGURE2_SEQUENCE

    if n < 1:
        raise ScenarioError(f"--n {n}: the number of runs must be a positive integer")
    if window not in ("causal", "centred"):
        raise ScenarioError(f"--window {window}: use causal or centred")
    if grid not in ("wide", "narrow"):
        raise ScenarioError(f"--grid {grid}: use wide or narrow")
    if mix not in ("uniform", "figure2", "sequence"):
        raise ScenarioError(f"--mix {mix}: use uniform, figure2 or sequence")
    if mix == "figure2" and activities is not None:
        raise ScenarioError(
            "--mix figure2 fixes the activities: drop --activities, or give them with --mix sequence"
        )
    if mix == "sequence" and activities is None:
        raise ScenarioError("--mix sequence takes the activities in order: give them with --activities")
    if not (math.isfinite(period_scale) and period_scale > 0):
        raise ScenarioError(f"--period-scale {period_scale}: give a positive factor (1: the default lengths)")
    acts = ACTIVITIES if activities is None else tuple(a.strip() for a in activities.split(",") if a.strip())
    if mix == "figure2":
        acts = FIGURE2_SEQUENCE
    dets: dict[str, Any] = (
        {}
        if detectors is None
        else {"detectors": tuple(d.strip() for d in detectors.split(",") if d.strip())}
    )
    k = period_scale
    r0 = DEFAULT_RANGES
    ranges = dataclasses.replace(
        r0,
        still_s=(r0.still_s[0] * k, r0.still_s[1] * k),
        activity_s=(r0.activity_s[0] * k, r0.activity_s[1] * k),
        posture_rest_s=(r0.posture_rest_s[0] * k, r0.posture_rest_s[1] * k),
    )
    cfg = mc.MonteCarloConfig(
        duration_s=mc.MonteCarloConfig().duration_s * k,
        ranges=ranges,
        grid=mc.Grid(**dets) if grid == "wide" else mc.Grid.narrow(**dets),
        alignment=window,
        sigma_acc_g=sigma_acc_g,
        sigma_gyr_dps=sigma_gyr_dps,
        activities=acts,
        sequence=mix != "uniform",
        mbcd_bandwidth=mbcd_bandwidth,
    )
    with CountingBar("runs", n, quiet=as_json) as bar:
        res = mc.run_montecarlo(n, seed=seed, config=cfg, workers=workers, on_run=bar.advance)
    written = mc.write_results(res, out) if out is not None else {}
    if as_json:
        emit_json(
            {
                "seed": seed,
                "runs": n,
                "tables": mc.summary(res),
                **(
                    {
                        "z": cmp.z_table(mc.summary(res), n),
                        "auc_rank_rho": cmp.auc_rank_correlation(mc.summary(res))[0],
                        "edges": cmp.grid_edges(res),
                        "auc_floor": cmp.auc_floor_table(res),
                        "errors_by_period": cmp.error_table(res),
                    }
                    if compare
                    else {}
                ),
                "written": {k: str(v) for k, v in written.items()},
            }
        )
        return
    console().print(mc.format_tables(res), highlight=False, soft_wrap=True)
    if compare:
        console().print("\n" + cmp.format_compare(res), highlight=False, soft_wrap=True)
    if out is not None:
        console().print(f"wrote {len(written)} files to {out}", highlight=False)
