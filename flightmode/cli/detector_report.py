"""Detector figures for the command line, formatted only: an evaluation (per-recording scores) as Rich
tables, and with ``tables`` seed 000's Table 2, 3, 4/5 forms and the turn-on response of Fig. 18
(computed by :mod:`flightmode.detector.evaluation` and :mod:`flightmode.detector.statistics`), and any
detector's per-sample scores (:func:`print_decisions`). Used by ``flightmode detect``."""

from __future__ import annotations

import math

import numpy as np
from rich.console import Console
from rich.table import Table

from flightmode.detector import evaluation as ev
from flightmode.detector.flight_mode import DetectorParams
from flightmode.detector.statistics import table2
from flightmode.errors import DetectorError


def _e(x) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    return "0" if x == 0 else f"{x:.1e}"


def print_evaluation(
    console: Console,
    e: ev.Evaluation,
    source: str,
    max_events: int = 15,
    title: str | None = None,
    calibration: list[tuple[str, str]] | None = None,
) -> None:
    """The evaluation as a table, then its false-static events. ``title`` and ``calibration`` (the
    rows saying what the threshold is and where it came from) default to the moving variance's."""
    p = e.params
    if title is None:
        title = (
            f"flight-mode detector: {p.method.upper()}"
            + (f" weight {p.weight:g}" if p.method == "emv" else "")
            + f", W_s {p.window_s:g} s, T_sigma {p.k_sigma:g} sigma^2, T_th {p.time_threshold_s:g} s"
        )
    if calibration is None:
        calibration = [
            ("sigma^2 per axis", ", ".join(f"{v:.2e}" for v in e.sigma2) + " g^2"),
            ("sigma^2 from", source),
        ]
    t = Table(title=title, show_header=False)
    t.add_column("quantity")
    t.add_column("value", justify="right")
    for row in calibration:
        t.add_row(*row)
    t.add_row("checks (in the in-flight window)", f"{e.checks.t_s.shape[0]:,} ({e.in_flight_checks:,})")
    t.add_row("false-static events in flight", f"{e.false_static_count} ({e.false_static_s:g} s in all)")
    t.add_row("response after the flight", "never" if e.response_s is None else f"{e.response_s:.1f} s")
    t.add_row("static time missed outside the window", f"{e.missed_static_s:g} s")
    t.add_row("accuracy / correlation vs sensor_static", f"{e.accuracy:.4f} / {e.correlation:.4f}")
    console.print(t)
    if e.false_static_events:
        ft = Table(title="false-static events (transmission allowed while the aircraft moves)")
        for c in ("t (s)", "duration (s)", "phase"):
            ft.add_column(c)
        for ev_ in e.false_static_events[:max_events]:
            ft.add_row(f"{ev_['t_s']:.0f}", f"{ev_['duration_s']:g}", ev_["phase"])
        if e.false_static_count > max_events:
            ft.add_row("...", f"{e.false_static_count - max_events} more", "")
        console.print(ft)


def print_tables(console: Console, t_s, acc_g, labels: dict, p: DetectorParams, sigma2) -> dict:
    """Print (and return) the Table 2, 3, 4/5 forms and the Fig. 18 turn-on response."""
    out = {}
    rows = table2(window_s=p.window_s, fs_hz=p.fs_hz)
    out["table2"] = rows
    t = Table(
        title=f"Table 2 form: P_M of one check on white noise, N = {p.window} (seed 000 eq. 13; the paper's "
        "beside eq. 13 with measured moments and the exact P_M of the LIS302DL's noise: flightmode seeds 000)"
    )
    for c in (
        "T_sigma",
        "P_M Gaussian (eq. 13)",
        "P_M exact chi-square",
        "TimeError Gaussian",
        "TimeError exact",
    ):
        t.add_column(c, justify="right")
    for r in rows:
        t.add_row(
            r["T_sigma"],
            _e(r["P_M_gaussian"]),
            _e(r["P_M_exact"]),
            f"{r['time_error_gaussian_s']:.1e} s",
            f"{r['time_error_exact_s']:.1e} s",
        )
    console.print(t)

    static = labels["sensor_static"]
    rows = ev.mv_vs_window(t_s, acc_g, static, p, sigma2)
    out["table3"] = rows
    t = Table(
        title="Table 3 form: NMV average on truly static data (seed 000 Table 3 reads 0.6, 0.5, 0.51, 0.51)"
    )
    for c in ("W_s", "checks", "MV x, y, z (1e-5 g^2)", "mean (1e-5 g^2)", "mean / sigma^2"):
        t.add_column(c, justify="right")
    s2m = float(np.mean(sigma2))
    for r in rows:
        t.add_row(
            f"{r['window_s']:g} s",
            str(r["checks"]),
            ", ".join(f"{v / 1e-5:.3f}" for v in r["mv_g2"]),
            f"{r['mv_mean_g2'] / 1e-5:.3f}",
            f"{r['mv_mean_g2'] / s2m:.2f}",
        )
    console.print(t)

    rows = ev.pfa_table(t_s, acc_g, labels, p, sigma2)
    out["table4"] = rows
    t = Table(title="Tables 4-5 form: P_FA over the in-flight window (eq. 14), and the observed rate")
    t.add_column("")
    for r in rows:
        t.add_column(f"{r['T_sigma']:g}s2/{r['T_th_s']:g}s", justify="right")
    for key, name in (
        ("P_FA_x", "P_FA^x"),
        ("P_FA_y", "P_FA^y"),
        ("P_FA_z", "P_FA^z"),
        ("P_FA_t", "P_FA^t (product)"),
        ("P_FA_t_joint", "P_FA^t (joint, observed)"),
        ("P_FA", "P_FA = (P_FA^t)^(T_th/W_s)"),
        ("observed_final_static_rate", "final statics / checks (observed)"),
    ):
        t.add_row(name, *[_e(r[key]) for r in rows])
    console.print(t)

    try:
        a, b = ev.longest_static_run(static)
        rows = ev.turn_on_response(t_s[a:b], acc_g[a:b], p, sigma2)
    except DetectorError:
        rows = []
    out["turn_on"] = rows
    t = Table(
        title=f"Turn-on response on static data (section 7.1, Fig. 18; EMV starts at {p.emv_initial_k:g} sigma^2)"
    )
    for c in ("method", "MV below T_sigma", "first temporary static", "final static"):
        t.add_column(c, justify="right")
    fmt = lambda v: "never" if v is None else f"{v:.2f} s"  # noqa: E731
    for r in rows:
        name = "NMV" if r["method"] == "nmv" else f"EMV w={r['weight']:g}"
        t.add_row(
            name, fmt(r["mv_below_threshold_s"]), fmt(r["first_temporary_static_s"]), fmt(r["response_s"])
        )
    console.print(t)
    return out


def print_decisions(console: Console, d) -> None:
    """A detector scored from its per-sample decisions (:class:`flightmode.runs.detect.Detection`
    with its :class:`~flightmode.detector.decisions.DecisionEvaluation`), then its false-static events."""
    e = d.decision_evaluation
    params = ", ".join(f"{k}={v!r}" for k, v in d.detector_params.items()) or "its defaults"
    t = Table(
        title=f"detector {d.method}"
        + (f" ({d.source}{': ' + d.title if d.title else ''})" if d.source != d.method else "")
        + f", {params}; "
        f"channels {', '.join(d.channels)}; scored per sample",
        show_header=False,
    )
    t.add_column("quantity")
    t.add_column("value", justify="right")
    if d.calibration_source:
        t.add_row("rest recording", d.calibration_source)
    t.add_row("samples (in the in-flight window)", f"{e.samples:,} ({e.in_flight_samples:,})")
    t.add_row("false-static events in flight", f"{e.false_static_count} ({e.false_static_s:g} s in all)")
    t.add_row("suspension after pushback", _s(e.suspend_s))
    t.add_row("response after the flight", "never" if e.response_s is None else f"{e.response_s:.1f} s")
    t.add_row("static time missed outside the window", f"{e.missed_static_s:g} s")
    t.add_row("accuracy / correlation vs sensor_static", f"{e.accuracy:.4f} / {e.correlation:.4f}")
    console.print(t)
    if e.false_static_events:
        ft = Table(title="false-static events (transmission allowed while the aircraft moves)")
        for c in ("t (s)", "duration (s)", "phase"):
            ft.add_column(c)
        for ev_ in e.false_static_events[:15]:
            ft.add_row(f"{ev_['t_s']:.0f}", f"{ev_['duration_s']:g}", ev_["phase"])
        if e.false_static_count > 15:
            ft.add_row("...", f"{e.false_static_count - 15} more", "")
        console.print(ft)


def _s(x) -> str:
    return "never" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.1f} s"


def print_redundant(console: Console, r, sigma2_source: str) -> None:
    """The redundant rule beside the accelerometer alone (:class:`flightmode.detector.pressure.RedundantEvaluation`)."""
    a, c, s, pp = r.accel, r.combined, r.sources, r.pressure_params
    p = a.params
    t = Table(
        "",
        "accelerometer alone",
        "accelerometer OR pressure (suspend), AND (resume)",
        title=f"{p.method.upper()} W_s {p.window_s:g} s, {p.k_sigma:g} sigma^2, T_th {p.time_threshold_s:g} s "
        f"(sigma^2: {sigma2_source}); pressure at {pp.fs_hz:g} Hz: |rate| <= {pp.rate_threshold_pa_s:g} Pa/s over "
        f"{pp.window_s:g} s, level within "
        + ("no margin" if pp.level_margin_pa is None else f"{pp.level_margin_pa / 100:g} hPa")
        + " of the ground reference"
        + (
            ""
            if pp.arrival_ground_pa is None
            else f" or of the destination's ({pp.arrival_ground_pa / 100:.0f} hPa)"
        )
        + f", for {pp.hold_s:g} s",
        title_justify="left",
    )
    t.add_row("false statics in the in-flight window", str(a.false_static_count), str(c.false_static_count))
    t.add_row("false static time", f"{a.false_static_s:g} s", f"{c.false_static_s:g} s")
    t.add_row("missed static outside the window", f"{a.missed_static_s:g} s", f"{c.missed_static_s:g} s")
    t.add_row("response at the gate", _s(a.response_s), _s(c.response_s))
    console.print(t)
    fs = s.first_suspend_s
    console.print(
        f"after pushback, first to suspend: {s.first_source} (accelerometer {_s(fs['accelerometer'])}, "
        f"pressure {_s(fs['pressure'])} after t = 0)",
        highlight=False,
    )
    h, hp = s.held_by, s.held_by_pressure
    console.print(
        f"cruise, {s.cruise_checks} checks: suspension held by the accelerometer only {h['accelerometer_only']}, "
        f"the pressure only {h['pressure_only']} (rate {hp['rate']}, level {hp['level']}, hold {hp['hold']}), "
        f"both {h['both']}, neither {h['neither']}",
        highlight=False,
    )
    if s.resume_s["combined"] is not None:
        rs = s.resume_s
        console.print(
            f"at the gate, from the bag at rest: accelerometer static after {_s(rs['accelerometer'])}, "
            f"pressure after {_s(rs['pressure'])}, transmission after {_s(rs['combined'])}",
            highlight=False,
        )
