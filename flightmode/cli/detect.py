"""``flightmode detect``: a detection method over one recorded flight, scored against its truth."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.text import Text

from flightmode.cli.common import JSON_HELP, console, emit_json

METHOD_HELP = "The same as --detector (kept for the built-ins' names)."
DETECTOR_HELP = (
    "A registered detector: nmv or emv (the moving-variance paper's detector), nmv+baro or emv+baro "
    "(the redundant rule with the samples' barometer), two-source (any two detectors, OR to suspend, "
    "AND to resume), one of the activity-detector study's: amvd, amd, ared, shod, frd, ltsd, fsd, mbgtd, "
    "mbcd (ared and shod read the gyroscope), a plugin's entry point; or package.module:make, a "
    "detector of your own (docs/detectors.md). Default nmv."
)
# the named options that are parameters of the built-ins (--param sets any parameter)
NAMED_PARAMS = (
    "window_s",
    "k",
    "time_threshold_s",
    "weight",
    "signal",
    "baro_rate_pa_s",
    "baro_margin_hpa",
    "baro_hold_s",
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
    detector: Annotated[str | None, typer.Option("--detector", help=DETECTOR_HELP)] = None,
    method: Annotated[str | None, typer.Option("--method", help=METHOD_HELP)] = None,
    detector_cmd: Annotated[
        str | None,
        typer.Option(
            "--detector-cmd",
            help='A program that decides over a pipe: "PROGRAM ARGS" reads a JSON header line and one '
            "line per sample on stdin, writes one 0/1 line per sample (docs/detector_pipe.md).",
        ),
    ] = None,
    framing: Annotated[
        str, typer.Option("--framing", help="--detector-cmd's samples: csv lines or f64 (binary float64).")
    ] = "csv",
    param: Annotated[
        list[str] | None,
        typer.Option("--param", help="A detector parameter key=value (a TOML value); repeat for more."),
    ] = None,
    channels: Annotated[
        str | None,
        typer.Option(
            "--channels",
            help="The channels the detector reads, comma-separated (acc_x_g, acc_y_g, acc_z_g, gyro_x_dps, "
            "gyro_y_dps, gyro_z_dps, pressure_pa); default the detector's own.",
        ),
    ] = None,
    chunk: Annotated[
        int | None,
        typer.Option("--chunk", help="Push the stream in chunks of N samples (default: all at once)."),
    ] = None,
    window_s: Annotated[
        float | None, typer.Option("--window-s", help="Window W_s and check period, s (default 1).")
    ] = None,
    k: Annotated[
        float | None,
        typer.Option(
            "--k",
            help="Amplitude threshold T_sigma = k sigma^2 (the activity detectors: k times the merit at rest); "
            "default 4.",
        ),
    ] = None,
    signal: Annotated[
        str | None,
        typer.Option("--signal", help="The flexible activity detectors' input: acc, gyr, sum or product."),
    ] = None,
    time_threshold_s: Annotated[
        float | None, typer.Option("--time-threshold-s", help="Time threshold T_th, s (default 4).")
    ] = None,
    weight: Annotated[
        float | None, typer.Option("--weight", help="EMV weighting factor (1, 5, 10 in the paper).")
    ] = None,
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
    compare_float: Annotated[
        bool,
        typer.Option(
            "--compare-float",
            help="nmv-fixed: also count where the integer detector and the floating NMV disagree on the "
            "same 8-bit samples, and how far from the threshold (LSBs).",
        ),
    ] = False,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """Run a flight-mode detector over one recorded flight and score it against the truth.

    The recording is a run folder, a samples.parquet file, or one flight of a dataset (its bench
    calibration regenerated from the manifest's scenario and seed). A flight flown with a gyroscope
    has it on the bench too, so ared and shod run with the defaults. Any detector of the interface
    runs: a registered name, package.module:make, or a program over a pipe (--detector-cmd); one of
    your own is scored from its per-sample decisions. Movebank e-obs files: flightmode eobs detect."""
    from flightmode.datasets.flight import flight_stream
    from flightmode.datasets.make import is_dataset
    from flightmode.detector.interface import parse_params
    from flightmode.errors import DetectorError
    from flightmode.runs.detect import DetectSettings, detect_stream
    from flightmode.runs.run_io import read_samples

    named = dict(
        zip(
            NAMED_PARAMS,
            (window_s, k, time_threshold_s, weight, signal, baro_rate_pa_s, baro_margin_hpa, baro_hold_s),
        )
    )
    params = parse_params(param or [])
    for key, value in named.items():
        if value is None:
            continue
        if key in params:
            raise DetectorError(f"--{key.replace('_', '-')} and --param {key}: given twice; give it once")
        params[key] = value
    given = [
        n for n, v in (("--detector", detector), ("--method", method), ("--detector-cmd", detector_cmd)) if v
    ]
    if len(given) > 1:
        raise DetectorError(f"{' and '.join(given)}: give one detector (--method is --detector's other name)")
    if chunk is not None and chunk < 1:
        raise DetectorError(f"--chunk {chunk}: a chunk holds at least 1 sample")
    if detector_cmd is not None:
        from flightmode.detector.pipe import load_cmd

        spec: object = load_cmd(detector_cmd, framing=framing)
    else:
        spec = detector or method or "nmv"
    settings = DetectSettings(
        params=params,
        sigma2_from=sigma2_from,
        channels=tuple(c.strip() for c in channels.split(",") if c.strip()) if channels else None,
        chunk=chunk,
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
    if compare_float and spec != "nmv-fixed":
        raise DetectorError("--compare-float: only with --detector nmv-fixed (the integer NMV)")
    d = detect_stream(cols, info, source, spec, settings, "--method" if method else "--detector")
    cmp = None
    if compare_float:
        from flightmode.runs.detect import compare_fixed_float

        cmp = compare_fixed_float(cols, info, source, settings)
    if as_json:
        emit_json(
            {
                "source": label,
                "method": d.method,
                "detector": d.source,
                "channels": list(d.channels),
                "params": d.detector_params,
                "fs_hz": d.fs_hz,
                "calibration_source": d.calibration_source,
            }
            | {"rest": d.rest}
            | {"evaluation": d.evaluation.summary()}
            | {"decisions": d.decision_evaluation.summary()}
            | ({"compare_float": _fixed_summary(cmp)} if cmp is not None else {})
        )
        return
    from flightmode.cli import detector_report as dr

    out = console()
    if d.kind == "redundant":
        out.print(Text(f"{label}: accelerometer and barometer", style="bold"), highlight=False)
        dr.print_redundant(out, d.evaluation, d.calibration_source)
        return
    if d.kind == "activity":
        a, ap = d.detector.info, d.detector.params
        out.print(Text(label, style="bold"), highlight=False)
        dr.print_evaluation(
            out,
            d.evaluation,
            d.calibration_source,
            title=f"{a.title} ({a.equations}) with seed 000's decision rule: W_s {ap.window_s:g} s, "
            f"threshold {ap.k:g} x the rest level, T_th {ap.time_threshold_s:g} s",
            calibration=[
                ("rest level of the merit (median)", f"{d.rest['merit_median']:.4g} {a.merit_unit}"),
                ("threshold", f"{d.rest['threshold']:.4g} {a.merit_unit}"),
                ("rest from", d.calibration_source),
            ],
        )
        return
    if d.kind != "moving_variance":  # any other detector: scored from its per-sample decisions
        out.print(Text(label, style="bold"), highlight=False)
        dr.print_decisions(out, d)
        if cmp is not None:
            c = _fixed_summary(cmp)
            out.print(
                f"fixed vs floating NMV on the same 8-bit samples: {c['checks']:,} checks; disagreements: "
                f"{c['axis_disagreements']} axis comparisons, {c['temporary_disagreements']} checks (eq. 7), "
                f"{c['final_disagreements']} (eq. 8), {c['sample_disagreements']:,} samples; farthest "
                f"{c['max_lsb_from_threshold']:.3g} LSB from the threshold "
                f"({'all within one LSB' if c['within_one_lsb'] else 'NOT all within one LSB'})",
                highlight=False,
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


def _fixed_summary(cmp: dict) -> dict:
    """compare_fixed_float's counts (its per-comparison list counted)."""
    return {
        "checks": int(cmp["checks"]),
        "axis_disagreements": len(cmp["axis_disagreements"]),
        "temporary_disagreements": int(cmp["temporary_disagreements"]),
        "final_disagreements": int(cmp["final_disagreements"]),
        "sample_disagreements": int(cmp["sample_disagreements"]),
        "max_lsb_from_threshold": float(cmp["max_lsb_from_threshold"]),
        "within_one_lsb": bool(cmp["within_one_lsb"]),
    }
