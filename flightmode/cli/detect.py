"""``flightmode detect``: a detection method over one recorded flight, scored against its truth."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.text import Text

from flightmode.cli.common import JSON_HELP, console, emit_json

METHOD_HELP = (
    "nmv or emv (the moving-variance paper's detector), nmv+baro or emv+baro (the redundant rule with "
    "the samples' barometer), or one of the activity-detector study's: amvd, amd, ared, shod, frd, ltsd, "
    "fsd, mbgtd, mbcd (ared and shod read the gyroscope)."
)


def detect_cmd(
    source: Annotated[
        Path,
        typer.Argument(help="A run folder, a samples.parquet file, or a dataset folder (with --flight)."),
    ],
    flight: Annotated[
        str | None,
        typer.Option("--flight", help="A dataset's flight: its id (000003) or index (3); default the first."),
    ] = None,
    method: Annotated[str, typer.Option("--method", help=METHOD_HELP)] = "nmv",
    window_s: Annotated[float, typer.Option("--window-s", help="Window W_s and check period, s.")] = 1.0,
    k: Annotated[
        float,
        typer.Option(
            "--k",
            help="Amplitude threshold T_sigma = k sigma^2 (the activity detectors: k times the merit at rest).",
        ),
    ] = 4.0,
    signal: Annotated[
        str,
        typer.Option("--signal", help="The flexible activity detectors' input: acc, gyr, sum or product."),
    ] = "acc",
    time_threshold_s: Annotated[
        float, typer.Option("--time-threshold-s", help="Time threshold T_th, s.")
    ] = 4.0,
    weight: Annotated[
        float, typer.Option("--weight", help="EMV weighting factor (1, 5, 10 in the paper).")
    ] = 1.0,
    sigma2_from: Annotated[
        str,
        typer.Option(
            "--sigma2-from",
            help="preset (the bench calibration of the recording's own unit; a dataset flight's is "
            "regenerated from its scenario and seed) or rest (the recording's static samples before the flight).",
        ),
    ] = "preset",
    tables: Annotated[
        bool,
        typer.Option(
            "--tables",
            help="Also print the paper's Table 2, 3, 4/5 forms and the Fig. 18 response (nmv, emv).",
        ),
    ] = False,
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
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """Run a flight-mode detector over one recorded flight and score it against the truth.

    The recording is a run folder, a samples.parquet file, or one flight of a dataset (its bench
    calibration regenerated from the manifest's scenario and seed). A flight flown with a gyroscope
    has it on the bench too, so ared and shod run with the defaults. Movebank e-obs files: flightmode
    eobs detect."""
    from flightmode.datasets.flight import flight_stream
    from flightmode.datasets.make import is_dataset
    from flightmode.runs.detect import DetectSettings, detect_stream
    from flightmode.runs.run_io import read_samples

    settings = DetectSettings(
        window_s=window_s,
        k=k,
        time_threshold_s=time_threshold_s,
        weight=weight,
        signal=signal,
        sigma2_from=sigma2_from,
        baro_rate_pa_s=baro_rate_pa_s,
        baro_margin_hpa=baro_margin_hpa,
        baro_hold_s=baro_hold_s,
    )
    info: dict | None
    if is_dataset(source):
        cols, info = flight_stream(source, 0 if flight is None else flight)
        label = f"{source} flight {info['run_id']}"
    else:
        if flight is not None:
            raise typer.BadParameter(f"{source} is not a dataset folder", param_hint="--flight")
        cols, info = read_samples(source)
        label = str(source)
    d = detect_stream(cols, info, source, method, settings)
    if as_json:
        emit_json(
            {
                "source": label,
                "method": d.method,
                "fs_hz": d.fs_hz,
                "calibration_source": d.calibration_source,
            }
            | {"rest": d.rest}
            | {"evaluation": d.evaluation.summary()}
        )
        return
    from flightmode.cli import detector_report as dr

    out = console()
    if d.kind == "redundant":
        out.print(Text(f"{label}: accelerometer and barometer", style="bold"), highlight=False)
        dr.print_redundant(out, d.evaluation, d.calibration_source)
        return
    if d.kind == "activity":
        from flightmode.detector.activity import registry

        a = registry.get(d.method)
        out.print(Text(label, style="bold"), highlight=False)
        dr.print_evaluation(
            out,
            d.evaluation,
            d.calibration_source,
            title=f"{a.title} ({a.equations}) with seed 000's decision rule: W_s {window_s:g} s, "
            f"threshold {k:g} x the rest level, T_th {time_threshold_s:g} s",
            calibration=[
                ("rest level of the merit (median)", f"{d.rest['merit_median']:.4g} {a.merit_unit}"),
                ("threshold", f"{d.rest['threshold']:.4g} {a.merit_unit}"),
                ("rest from", d.calibration_source),
            ],
        )
        return
    sensor = (info or {}).get("sensor")
    out.print(
        Text(label + (f": {sensor['preset']} at {d.fs_hz:g} Hz" if sensor else ""), style="bold"),
        highlight=False,
    )
    dr.print_evaluation(out, d.evaluation, d.calibration_source)
    if tables:
        from flightmode.detector.recommended import labels_of

        dr.print_tables(out, cols["t_s"], cols["acc_g"], labels_of(cols), d.params, d.evaluation.sigma2)
