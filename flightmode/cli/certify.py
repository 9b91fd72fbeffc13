"""``flightmode certify``: the claim a sweep supports, with its evidence (OUT/report.html)."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.table import Table
from rich.text import Text

from flightmode.cli.common import JSON_HELP, WORKERS_HELP, comma_list, console, emit_json
from flightmode.cli.study import (
    GRID_HELP,
    SweepProgress,
    excluded,
    grid_and_detectors,
    out_of,
    point_name,
    print_breakdown,
)


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
            "--pm",
            help="The moving-variance paper's section 5.1.1: the probability of misdetection to set the threshold from.",
        ),
    ] = 1e-3,
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
        typer.Option(
            "--out", help="The report folder (default DATASET/certify; needed for several datasets)."
        ),
    ] = None,
    uncertainty: Annotated[
        bool,
        typer.Option(
            "--uncertainty",
            help="Also fly the dataset's members with each uncertain model parameter at each end of its "
            "range, then at the worst corner (DATASET/uncertainty/), certify each, and say whether the "
            "recommendation holds (one dataset).",
        ),
    ] = False,
    parameter: Annotated[
        str | None,
        typer.Option(
            "--parameter",
            help="With --uncertainty: only these parameters (comma-separated; `flightmode scenarios --model`).",
        ),
    ] = None,
    detector: Annotated[list[str] | None, typer.Option("--detector", help=GRID_HELP["detector"])] = None,
    param: Annotated[list[str] | None, typer.Option("--param", help=GRID_HELP["param"])] = None,
    grid_file: Annotated[Path | None, typer.Option("--grid-file", help=GRID_HELP["grid_file"])] = None,
    grace_s: Annotated[float | None, typer.Option("--grace-s", help=GRID_HELP["grace_s"])] = None,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """Recommend detector parameters that meet a false-static target, with their evidence.

    The Pareto front of (false-static bound, response, availability); the point that meets the target
    with the best response, or how many flight-hours the datasets lack; the paper's section 5.1.1
    threshold from the static data; OUT/report.html with its figures. --uncertainty: the verdict with
    its model uncertainty (a tornado chart in the report). Several detectors (--method's, repeated
    --detector, [[detector]] tables of --grid-file) are certified side by side in one report."""
    from flightmode.studies.certify import Target
    from flightmode.studies.sweep import check_request

    grid, entries = grid_and_detectors(
        method, weight, window_s, k, time_threshold_s, detector, param, grid_file, grace_s
    )
    target = Target(target_fa_per_h, confidence, max_response_s, pm)
    target.validate()
    out = out_of(out, datasets, "certify", "the report")
    sensors = comma_list(sensor, "--sensor")
    check_request(datasets, grid, sigma2_from, sensors, entries)
    study = None
    if uncertainty:
        from flightmode.errors import InputDataError
        from flightmode.studies.uncertainty import choose_parameters
        from flightmode.studies.uncertainty import uncertainty as run_uncertainty

        if len(datasets) != 1:
            raise InputDataError("--uncertainty: give one dataset (its members are flown again per variant)")
        if entries or grid is None:
            raise InputDataError("--uncertainty certifies the built-in grid: drop --detector and --grid-file")
        names = choose_parameters(comma_list(parameter, "--parameter"))
        cert, study = run_uncertainty(
            datasets[0],
            grid,
            target,
            parameters=names,
            sigma2_from=sigma2_from,
            sensors=sensors,
            workers=max(workers, 1),
            out=out,
            log=(lambda m: None) if as_json else (lambda m: console().print(m, highlight=False)),
        )
    else:
        cert = _certify(datasets, grid, target, sigma2_from, workers, sensors, out, as_json, entries)
    _print(cert, study, confidence, out, as_json)


def _certify(datasets, grid, target, sigma2_from, workers, sensors, out, as_json, entries=()):
    from flightmode.studies.certify import certify

    with SweepProgress(quiet=as_json) as progress:
        return certify(
            datasets,
            grid,
            target,
            sigma2_from=sigma2_from,
            workers=workers,
            sensors=sensors,
            out=out,
            on_start=progress.start,
            on_flight=progress.advance,
            log=(lambda m: None) if as_json else (lambda m: console().print(m, highlight=False)),
            detectors=entries,
        )


def _print(cert, study, confidence: float, out, as_json: bool) -> None:
    front = sorted(
        (cert.summary[i] for i in cert.pareto), key=lambda r: (r["rate_upper_per_h"], r["response_p95_s"])
    )
    which = "seed000" if "seed000" in cert.breakdowns else "recommended"
    if as_json:
        emit_json(
            {
                "recommendation": cert.recommendation,
                "pareto": front,
                "paper_point": cert.seed000,
                "breakdown": {"point": which, "rows": cert.breakdowns[which]},
                "threshold": cert.threshold,
                "excluded": cert.meta["excluded"],
                "detectors": [
                    {k: d[k] for k in ("name", "spec", "recommendation", "point_name")}
                    for d in cert.detectors
                ],
                "report": str(Path(out) / "report.html"),
            }
            | ({"uncertainty": study.as_dict()} if study is not None else {})
        )
        return
    excluded(cert.meta["excluded"])
    style_of = {"meets": "green", "too_small": "yellow", "too_slow": "yellow", "unreachable": "red"}
    style = style_of[cert.recommendation["status"]]
    console().print(Text(f"{cert.recommendation['status']}: {cert.recommendation['text']}", style=style))
    if len(cert.detectors) > 1:  # one verdict line per detector
        for d in cert.detectors:
            r = d["recommendation"]
            console().print(
                Text(f"{d['name']}: {r['status']}: {r['text']}", style=style_of.get(r["status"], ""))
            )
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
    for r in front[:10] + ([cert.seed000] if cert.seed000 else []):
        t.add_row(
            point_name(r, r is cert.seed000),
            f"{r['window_s']:g}",
            f"{r['k']:g}",
            f"{r['time_threshold_s']:g}",
            str(r["false_statics"]),
            f"{r['in_window_h']:,.1f}",
            f"{r['rate_upper_per_h']:.3g}",
            f"{r['response_p50_s']:.1f}/{r['response_p95_s']:.1f}/{r['response_max_s']:.1f}",
            f"{r['availability']:.3f}",
        )
    console().print(t)
    if cert.seed000:
        s = cert.seed000
        console().print(
            f"the paper's point {'meets' if s['meets'] else 'does not meet'} the target: "
            f"{s['false_statics']} false statics in {s['in_window_h']:,.1f} h, bound "
            f"{s['rate_upper_per_h']:.3g} /h, response p95 {s['response_p95_s']:.1f} s, "
            f"availability {s['availability']:.3f}",
            highlight=False,
        )
    print_breakdown(
        cert.breakdowns[which],
        f"by condition at {'the paper' if which == 'seed000' else 'the recommended'} point",
    )
    th = cert.threshold
    if th:
        console().print(
            f"section 5.1.1 at P_M {th['pm']:g} ({th['static_checks']:,} static checks, W_s {th['window_s']:g} s): "
            f"k = {th['empirical_k']:.2f} measured{'' if th['empirical_resolved'] else ' (not resolved)'}, "
            f"{th['gaussian_measured_k']:.2f} eq. 13 with the measured spread, "
            f"{th['gaussian_white_k']:.2f} eq. 13 white, {th['chi2_white_k']:.2f} chi-square white",
            highlight=False,
        )
    if study is not None:
        _print_uncertainty(study, confidence)
    console().print(f"report: {Path(out) / 'report.html'}", highlight=False)


def _print_uncertainty(study, confidence: float) -> None:
    """The variants' table and the sentence of a model-uncertainty study."""
    t = Table(
        "variant",
        "flights",
        "in-window h",
        "false statics",
        f"{confidence:.0%} bound /h",
        "response p95 s",
        "its own recommended point",
        "its bound /h",
        "its response p95 s",
        "seed 000's point: bound /h",
        title=f"the recommended point ({study.point}) across the model's uncertainty",
    )
    for v in [study.nominal, *study.variants, *([study.corner] if study.corner else [])]:
        p, r = v.at_point, v.recommendation
        t.add_row(
            v.label,
            str(v.flights_ok),
            f"{v.in_window_h:,.2f}",
            str(p["false_statics"]),
            f"{p['rate_upper_per_h']:.3g}",
            f"{p['response_p95_s']:.1f}",
            r["point"],
            f"{r['rate_upper_per_h']:.3g}",
            f"{r['response_p95_s']:.1f}",
            "-" if v.seed000 is None else f"{v.seed000['rate_upper_per_h']:.3g}",
        )
    console().print(t)
    console().print(
        Text(study.sentence, style="green" if study.holds else "yellow"),
        f"(wall {study.wall_s / 60:.1f} min)",
    )
