"""The certification report: PNG figures (matplotlib, Agg) and one self-contained ``report.html``
(every figure embedded as a data URI, no script, no network) for :mod:`flightmode.studies.certify`.

Figures (``OUT/figures``):

- ``bound_vs_k.png``: the false-static rate's upper bound against k, one panel per window, a line per
  time threshold (NMV solid, EMV dashed), the target marked;
- ``availability_vs_k.png``: the share of truly static time reported static, same layout;
- ``response_cdf.png``: the distribution of the response at the destination gate, at the
  recommended point, at seed 000's and at the shortest and longest time thresholds;
- ``phase_heatmap.png``: per phase and k, the share of in-window checks under ``k sigma^2`` on all
  axes (eq. 7's temporary statics) at the recommended point's method and window;
- ``pareto.png``: every point's bound against its response p95, coloured by availability, the
  Pareto front ringed, the recommendation and seed 000's point marked;
- ``static_survival.png``: seed 000 section 5.1.1, the measured P(any axis MV >= k sigma^2) on truly
  static checks beside white noise's exact chi-square and eq. 13's Gaussian, P_M and each threshold;
- ``worst_flight.png``: seed 000 Figs. 14 and 15 in form, for the flight closest to trouble: the MV
  per axis against 3/4/5 sigma^2, then the temporary and final statics for k = 3, 4, 5 at T_th 4 s
  (Fig. 14) and for T_th = 2, 3, 4, 5 s at 4 sigma^2 (Fig. 15).

With several detectors (issue 52: the built-in grid's methods and detectors of the interface, the
``detectors`` of the Certification), also:

- ``pareto_detectors.png``: each detector's points (bound against response p95) in a colour of its
  own, its own Pareto front joined, the point it would ship starred;
- ``response_detectors.png``: the response at the destination gate of each detector at that point;

and the HTML gains one verdict line per detector, their chosen points side by side, and each one's
false statics by phase and placement. The bound and availability against k are drawn for the built-in
grid's points only (a detector of the interface has its own parameters, not k).
"""

from __future__ import annotations

import base64
import html
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from flightmode.viz.tornado import TornadoData, fig_tornado, tornado_html

FIGURES = (
    "pareto",
    "pareto_detectors",
    "response_detectors",
    "bound_vs_k",
    "availability_vs_k",
    "response_cdf",
    "phase_heatmap",
    "static_survival",
    "worst_flight",
)


@dataclass(frozen=True, slots=True)
class WorstFlightData:
    """Seed 000 Figs. 14 and 15 in form, for one flight: per detector check (K checks), computed by
    :mod:`flightmode.studies.certify`."""

    t_min: np.ndarray  # (K,) check times, minutes since the tracker started
    mv_over_sigma2: np.ndarray  # (K, 3) moving variance per axis / sigma^2
    ylabel: str  # what mv_over_sigma2 is (method and window)
    in_window: np.ndarray  # (K,) bool: the check lies in the in-flight window (pushback to engines off)
    fig14: list  # [(label, temporary (K,) bool, final (K,) bool)] per amplitude threshold at T_th below
    fig15: list  # the same per time threshold at k below
    time_threshold_s: float  # Fig. 14's T_th (seed 000's recommended)
    k_sigma: float  # Fig. 15's k (seed 000's recommended)


@dataclass(frozen=True, slots=True)
class ReportData:
    """What the report draws beyond the :class:`~flightmode.studies.certify.Certification` itself,
    computed by the study (this module never reads a dataset or a sweep)."""

    names: tuple  # a readable name of each row of cert.summary ("NMV, W_s 1 s, 4 sigma^2, T_th 4 s")
    recommended_name: str  # of cert.recommendation["point"]
    seed000_name: str  # seed 000's recommended point
    seed000_short: str  # the same, short ("NMV 1 s, 4 sigma^2, 4 s")
    seed000_index: int | None  # seed 000's point's row in cert.summary, None if the grid lacks it
    response_curves: list  # [(legend, finite responses s sorted (n,), flights)] for response_cdf
    phases: dict  # {"phase", "k", "checks", "under_all"}: lists at the recommended method and window
    worst_flight: WorstFlightData | None
    # the model-uncertainty study (certify --uncertainty): its tornado chart; None: not run
    tornado: TornadoData | None = None
    # side by side: [(legend, finite responses s sorted, flights)] per detector at its chosen point
    detector_curves: list | tuple = ()


def _plt():
    import matplotlib

    matplotlib.use("Agg")  # files only, never a window
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path: Path) -> None:
    from flightmode.atomic import write_with

    try:
        write_with(path, lambda tmp: fig.savefig(tmp, dpi=110, format="png"), mkdir=False)
    finally:
        _plt().close(fig)


def _methods(summary) -> list[tuple[str, float]]:
    return sorted({(r["method"], r["weight"]) for r in summary})


def fig_vs_k(
    summary, value: str, ylabel: str, path: Path, target: float | None = None, log: bool = False
) -> None:
    plt = _plt()
    windows = sorted({r["window_s"] for r in summary})
    tths = sorted({r["time_threshold_s"] for r in summary})
    cmap = plt.get_cmap("viridis")
    fig, axes = plt.subplots(
        1, len(windows), figsize=(4.2 * len(windows) + 1, 3.8), sharey=True, squeeze=False
    )
    for ax, w in zip(axes[0], windows):
        for mi, (m, wt) in enumerate(_methods(summary)):
            for ti, tth in enumerate(tths):
                rows = sorted(
                    (
                        r
                        for r in summary
                        if (r["method"], r["weight"], r["window_s"], r["time_threshold_s"]) == (m, wt, w, tth)
                    ),
                    key=lambda r: r["k"],
                )
                if rows:
                    ax.plot(
                        [r["k"] for r in rows],
                        [r[value] for r in rows],
                        ls={"nmv": "-", "emv": "--"}.get(m, ":"),
                        color=cmap(ti / max(1, len(tths) - 1)),
                        lw=1.2,
                        label=f"T_th {tth:g} s" if mi == 0 else None,
                    )
        if target is not None:
            ax.axhline(target, color="crimson", lw=1, ls=":", label="target")
        ax.set_title(f"W_s {w:g} s")
        ax.set_xlabel("k (T_sigma = k sigma^2)")
        if log:
            ax.set_yscale("log")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel(ylabel)
    axes[0][-1].legend(
        fontsize=7, loc="best", title="solid NMV, dashed EMV, dotted seed 001's", title_fontsize=7
    )
    fig.tight_layout()
    _save(fig, path)


def fig_pareto_detectors(cert, path: Path) -> None:
    """Each detector's points and its own Pareto front (module docstring)."""
    plt = _plt()
    s = cert.summary
    x_all = np.array([r["response_p95_s"] for r in s], float)
    edge = np.nanmax(np.where(np.isfinite(x_all), x_all, np.nan), initial=1.0) * 1.5
    x_all = np.where(np.isfinite(x_all), x_all, edge)  # never answered: at the right edge
    y_all = np.array([r["rate_upper_per_h"] for r in s], float)
    cmap = plt.get_cmap("tab10")
    fig, ax = plt.subplots(figsize=(8, 5))
    for j, d in enumerate(cert.detectors):
        col = cmap(j % 10)
        idx = np.array(d["points"], int)
        ax.scatter(x_all[idx], y_all[idx], s=10, color=col, alpha=0.45)
        f = sorted(d["pareto"], key=lambda i: (x_all[i], y_all[i]))
        ax.plot(
            x_all[f],
            y_all[f],
            "o",
            color=col,
            ms=6,
            mec="black",
            label=f"{d['name']}: its front ({len(f)} points)",
        )
        rp = d["recommendation"]["point"]
        i_rp = s.index(rp) if rp in s else None
        if i_rp is not None:
            ax.scatter(
                [x_all[i_rp]], [y_all[i_rp]], marker="*", s=240, color=col, edgecolors="black", zorder=5
            )
    ax.axhline(cert.target.rate_per_h, color="crimson", lw=1, ls=":", label="target")
    if cert.target.max_response_s:
        ax.axvline(cert.target.max_response_s, color="grey", lw=1, ls=":", label="max response")
    ax.set_yscale("log")
    ax.set_xscale("symlog", linthresh=10)
    ax.set_xlabel("response p95 at the destination gate, s (never answered: right edge)")
    ax.set_ylabel(f"false statics per flight-hour, {cert.target.confidence:.0%} upper bound")
    ax.set_title("detectors side by side: each one's Pareto front; star: the point it would ship", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower left")  # above the target line: the points are never there yet
    fig.tight_layout()
    _save(fig, path)


def fig_response_cdf(curves, path: Path) -> None:
    """``curves``: [(legend, finite responses s sorted, flights)] (:attr:`ReportData.response_curves`)."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7, 4))
    for label, v, n in curves:
        ax.step(v, np.arange(1, v.size + 1) / n, where="post", label=label)
    ax.set_xscale("symlog", linthresh=10)
    ax.set_xlabel("response at the destination gate, s (truly at rest to the first final static)")
    ax.set_ylabel("share of flights")
    ax.set_ylim(0, 1.02)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    _save(fig, path)


def fig_phase_heatmap(d: dict, cert, path: Path) -> None:
    """``d``: the sweep's phase rows at the recommended method and window (:attr:`ReportData.phases`)."""
    from flightmode.labels import PHASES

    plt = _plt()
    p = cert.recommendation["point"]
    ks = sorted(set(d["k"]))
    names = [ph for ph in PHASES if ph in set(d["phase"])] + sorted(set(d["phase"]) - set(PHASES))
    checks = np.zeros((len(names), len(ks)))
    under = np.zeros((len(names), len(ks)))
    for ph, k, c, u in zip(d["phase"], d["k"], d["checks"], d["under_all"]):
        i, j = names.index(ph), ks.index(k)
        checks[i, j] += c
        under[i, j] += u
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(checks > 0, under / checks, np.nan)
        shown = np.log10(np.where(frac > 0, frac, np.nan))
    fig, ax = plt.subplots(figsize=(max(6.0, 1.0 + 0.55 * len(ks)), 1.2 + 0.36 * len(names)))
    im = ax.imshow(shown, aspect="auto", cmap="magma_r", vmin=-6, vmax=0)
    for i in range(len(names)):
        for j in range(len(ks)):
            if under[i, j] > 0:
                ax.text(
                    j,
                    i,
                    f"{int(under[i, j])}",
                    ha="center",
                    va="center",
                    fontsize=6,
                    color="white" if shown[i, j] > -3 else "black",
                )
    ax.set_xticks(range(len(ks)), [f"{k:g}" for k in ks], fontsize=7)
    ax.set_yticks(range(len(names)), names, fontsize=7)
    ax.set_xlabel("k (T_sigma = k sigma^2)")
    ax.set_title(
        f"in-window checks under k sigma^2 on all axes ({p['method'].upper()}, W_s {p['window_s']:g} s); "
        "numbers: checks",
        fontsize=8,
    )
    fig.colorbar(im, ax=ax, label="log10 share of the phase's checks (blank: none)")
    fig.tight_layout()
    _save(fig, path)


def fig_pareto(cert, path: Path, seed000_index: int | None = None, seed000_short: str = "") -> None:
    plt = _plt()
    s = cert.summary
    x = np.array([r["response_p95_s"] for r in s], float)
    y = np.array([r["rate_upper_per_h"] for r in s], float)
    c = np.array([r["availability"] for r in s], float)
    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    # a point that never answered on enough flights (p95 infinite or missing) is drawn at the right edge
    x = np.where(np.isfinite(x), x, np.nanmax(np.where(np.isfinite(x), x, np.nan), initial=1.0) * 1.5)
    sc = ax.scatter(x, y, c=c, s=12, cmap="viridis")
    f = cert.pareto
    ax.scatter(x[f], y[f], facecolors="none", edgecolors="black", s=60, lw=1, label="Pareto front")
    rp = cert.recommendation["point"]
    i_rp = cert.summary.index(rp) if rp in cert.summary else None
    ax.scatter(
        [x[i_rp] if i_rp is not None else rp["response_p95_s"]],
        [rp["rate_upper_per_h"]],
        marker="*",
        s=260,
        color="crimson",
        label=f"recommended ({cert.recommendation['status']})",
        zorder=5,
    )
    seed = cert.seed000
    if seed:
        i_s = seed000_index
        ax.scatter(
            [x[i_s]],
            [seed["rate_upper_per_h"]],
            marker="D",
            s=70,
            facecolors="none",
            edgecolors="tab:orange",
            lw=2,
            label=f"seed 000 ({seed000_short})",
            zorder=5,
        )
    ax.axhline(cert.target.rate_per_h, color="crimson", lw=1, ls=":", label="target")
    if cert.target.max_response_s:
        ax.axvline(cert.target.max_response_s, color="grey", lw=1, ls=":", label="max response")
    ax.set_yscale("log")
    ax.set_xscale("symlog", linthresh=10)
    ax.set_xlabel("response p95 at the destination gate, s")
    ax.set_ylabel(f"false statics per flight-hour, {cert.target.confidence:.0%} upper bound")
    fig.colorbar(sc, ax=ax, label="availability")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    _save(fig, path)


def fig_static_survival(cert, path: Path) -> None:
    from scipy.stats import chi2, norm

    plt = _plt()
    th = cert.threshold
    k = np.asarray(th["survival_k"], float)[:-1]  # bin edges; the last survival value (0) closes the step
    sv = np.asarray(th["survival_max"][:-1], float)
    n = th["samples_per_window"]
    fig, ax = plt.subplots(figsize=(7, 4.2))
    ok = sv > 0
    ax.step(
        k[ok],
        sv[ok],
        where="post",
        color="black",
        label=f"measured, any axis ({th['static_checks']:,} static checks)",
    )
    kk = np.linspace(0.3, 8, 400)
    white = 1 - (1 - chi2.sf(n * kk, n - 1)) ** 3
    ax.plot(kk, white, color="tab:blue", label=f"white noise, exact chi-square (N = {n})")
    mu, sd = (th["axes"][a]["mean"] for a in "xyz"), (th["axes"][a]["sd"] for a in "xyz")
    g = 1 - np.prod([1 - norm.sf((kk - m) / s) for m, s in zip(mu, sd)], axis=0)
    ax.plot(kk, g, color="tab:green", ls="--", label="eq. 13, measured mean and spread per axis")
    ax.axhline(th["pm"], color="crimson", ls=":", lw=1, label=f"P_M = {th['pm']:g}")
    for key, col in (
        ("empirical_k", "black"),
        ("chi2_white_k", "tab:blue"),
        ("gaussian_measured_k", "tab:green"),
    ):
        ax.axvline(th[key], color=col, lw=0.8, ls=":")
    ax.set_yscale("log")
    ax.set_ylim(max(1e-9, 0.3 / max(1, th["static_checks"])), 1.5)
    ax.set_xlim(0, 8)
    ax.set_xlabel("k: threshold T_sigma = k sigma^2")
    ax.set_ylabel("P(MV >= k sigma^2 on any axis): P_M of one check")
    ax.set_title(
        f"seed 000 section 5.1.1 ({th['method'].upper()}, W_s {th['window_s']:g} s): "
        f"k = {th['empirical_k']:.2f} measured, {th['chi2_white_k']:.2f} white",
        fontsize=9,
    )
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    _save(fig, path)


def fig_worst_flight(cert, data: WorstFlightData, path: Path) -> None:
    """Seed 000 Figs. 14 and 15 in form, for the worst flight (module docstring)."""
    plt = _plt()
    w = cert.worst_flight
    tm, window = data.t_min, data.in_window
    fig, axes = plt.subplots(
        3, 1, figsize=(11, 7.5), sharex=True, gridspec_kw={"height_ratios": [3, 1.4, 1.4]}
    )
    ax = axes[0]
    for j, (a, col) in enumerate(zip("xyz", ("tab:red", "tab:green", "tab:blue"))):
        ax.plot(tm, data.mv_over_sigma2[:, j], lw=0.5, color=col, label=f"MV {a} / sigma^2")
    for k, ls in ((3, ":"), (4, "--"), (5, "-.")):
        ax.axhline(k, color="black", lw=0.8, ls=ls, label=f"{k} sigma^2")
    ax.set_yscale("log")
    ax.set_ylabel(data.ylabel)
    on = np.flatnonzero(window)
    for a_ in axes:
        if on.size:
            a_.axvspan(tm[on[0]], tm[on[-1]], color="grey", alpha=0.12, lw=0)
    ax.legend(fontsize=7, ncol=7, loc="upper right")
    ax.set_title(
        f"flight {w['flight_id']} ({w.get('family') or ''}, {w.get('aircraft')}, {w['sensor_preset']}, {w.get('placement')}, "
        f"turbulence {w.get('turbulence')}); grey: pushback to engines off",
        fontsize=9,
    )

    def lanes(ax, items, title):
        for i, (_label, temp, fin) in enumerate(items):
            ti, fi = np.flatnonzero(temp), np.flatnonzero(fin)
            ax.vlines(tm[ti], i - 0.4, i, color="magenta", lw=0.6)
            ax.vlines(tm[fi], i, i + 0.4, color="black", lw=0.8)
        ax.set_yticks(range(len(items)), [it[0] for it in items], fontsize=7)
        ax.set_ylim(-0.6, len(items) - 0.4)
        ax.set_title(title, fontsize=8)

    lanes(
        axes[1],
        data.fig14,
        f"seed 000 Fig. 14 form: T_th {data.time_threshold_s:g} s; magenta temporary static (eq. 7), "
        "black final static (eq. 8)",
    )
    lanes(axes[2], data.fig15, f"seed 000 Fig. 15 form: {data.k_sigma:g} sigma^2")
    axes[2].set_xlabel("time since the tracker started, min")
    fig.tight_layout()
    _save(fig, path)


# ---------------------------------------------------------------------- HTML
def _table(rows: list[dict], cols: list[tuple[str, str, str]]) -> str:
    """cols: (key, header, format)."""
    head = "".join(f"<th>{html.escape(h)}</th>" for _, h, _ in cols)
    body = []
    for r in rows:
        cells = []
        for key, _, fmt in cols:
            v = r.get(key)
            if isinstance(v, float) and not math.isfinite(v):
                s = "n/a"
            elif v is None:
                s = ""
            else:
                s = format(v, fmt) if fmt else str(v)
            cells.append(f"<td>{html.escape(s)}</td>")
        body.append("<tr>" + "".join(cells) + "</tr>")
    return f"<table><thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>"


POINT_COLS = [
    ("name", "point", ""),
    ("false_statics", "false statics", "d"),
    ("in_window_h", "in-window h", ",.1f"),
    ("rate_upper_per_h", "bound /h", ".3g"),
    ("response_p50_s", "resp. p50 s", ".1f"),
    ("response_p95_s", "resp. p95 s", ".1f"),
    ("response_max_s", "resp. max s", ".1f"),
    ("availability", "availability", ".3f"),
    ("hours_short", "h short", ",.0f"),
]


def _section_511(th: dict) -> list[str]:
    parts = ["<h2>Seed 000 section 5.1.1: the threshold from a probability of misdetection</h2>"]
    parts.append(
        f"<p>{th['static_checks']:,} truly static checks ({th['static_h']:.1f} h) of {th['flights']} flights, "
        f"{th['method'].upper()} W_s {th['window_s']:g} s; P_M = {th['pm']:g} for any axis "
        f"({th['pm_per_axis']:.3g} per axis).</p>"
    )
    rows = [
        {"name": "measured (empirical survival, any axis)", "k": th["empirical_k"]},
        {"name": "eq. 13 with the measured mean and spread", "k": th["gaussian_measured_k"]},
        {
            "name": f"eq. 13 with white-noise moments (N = {th['samples_per_window']})",
            "k": th["gaussian_white_k"],
        },
        {"name": "exact chi-square, white noise", "k": th["chi2_white_k"]},
    ]
    parts.append(_table(rows, [("name", "model", ""), ("k", "threshold, sigma^2", ".2f")]))
    if not th["empirical_resolved"]:
        parts.append(
            f"<p>The measured value is not resolved: P_M = {th['pm']:g} needs at least "
            f"{3 / th['pm']:,.0f} static checks, these flights have {th['static_checks']:,}.</p>"
        )
    pf = th.get("p_fa")
    if pf:
        parts.append(
            f"<p>At the grid's k = {pf['k']:g} (nearest at or below the measured threshold): "
            f"{pf['under_all']:,} of {pf['in_window_checks']:,} in-window checks under it on all axes "
            f"(P_FA^t {pf['p_fa_t_joint']:.2g}); at T_th {pf['time_threshold_s']:g} s, {pf['false_statics']} "
            f"false statics, bound {pf['rate_upper_per_h']:.3g} /h: the target is "
            f"{'met' if pf['meets'] else 'not met'}.</p>"
        )
    loop = th.get("loop_5_1_1")
    if loop:
        parts.append(
            f"<p>Section 5.1.1's last step: P_M raised a decade at a time until eq. 14's P_FA at "
            f"T_th {loop['time_threshold_s']:g} s is at most the target's {loop['pfa_max']:.3g} per check "
            f"(its rate per hour x W_s / 3,600 s): {'met' if loop['met'] else 'not met'} at P_M "
            f"{loop['pm']:.3g}, k {loop['k']:.3g} sigma^2, P_FA {loop['pfa']:.3g}.</p>"
        )
        parts.append(
            _table(
                loop["steps"],
                [("pm", "P_M", ".3g"), ("k", "threshold, sigma^2", ".3g"), ("pfa", "P_FA (eq. 14)", ".3g")],
            )
        )
    return parts


def _img(name: str, png: bytes) -> str:
    return f"<img alt='{html.escape(name)}' src='data:image/png;base64,{base64.b64encode(png).decode()}'>"


def _side_by_side_html(cert, figures: dict[str, bytes]) -> list[str]:
    """One verdict line per detector, their chosen points, the two figures, each one's false statics
    by phase and placement (module docstring)."""
    e = html.escape
    parts = [f"<h2>Detectors side by side ({len(cert.detectors)})</h2>"]
    for d in cert.detectors:
        r = d["recommendation"]
        parts.append(
            f"<div class='verdict {e(r['status'])}'><b>{e(d['name'])}</b> ({e(d['spec'])}): "
            f"<b>{e(r['status'])}</b>: {e(r['text'])}</div>"
        )
    rows = [
        d["recommendation"]["point"]
        | {"name": f"{d['name']}: {d['point_name']}", "front": len(d["pareto"])}
        | {"grid": len(d["points"])}
        for d in cert.detectors
    ]
    parts.append(_table(rows, POINT_COLS + [("grid", "points", "d"), ("front", "on its front", "d")]))
    for name in ("pareto_detectors", "response_detectors"):
        if name in figures:
            parts.append(_img(name, figures[name]))
    for d in cert.detectors:
        parts.append(f"<h3>{e(d['name'])}: false statics by phase and placement at its point</h3>")
        parts.append(
            _table(
                d["breakdown"],
                [
                    ("condition", "condition", ""),
                    ("value", "value", ""),
                    ("flights", "flights", "d"),
                    ("in_window_h", "in-window h", ",.2f"),
                    ("false_statics", "false statics", "d"),
                    ("response_p95_s", "response p95 s", ".1f"),
                ],
            )
        )
    return parts


def render_html(cert, figures: dict[str, bytes], data: ReportData) -> str:
    """The self-contained report: ``figures`` {name: PNG bytes}, point names from ``data``."""
    e = html.escape
    t = cert.target
    meta = cert.meta
    parts = [
        "<!doctype html><html lang='en'><head><meta charset='utf-8'>",
        "<title>flightmode certify</title><style>",
        "body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1150px;color:#222}",
        "table{border-collapse:collapse;font-size:13px;margin:0.6em 0}td,th{border:1px solid #ccc;padding:3px 7px;"
        "text-align:right}th{background:#f0f0f0}td:first-child{text-align:left}",
        ".verdict{padding:0.8em 1em;border-left:6px solid;background:#fafafa}.meets{border-color:#2a2}"
        ".too_small,.too_slow{border-color:#d90}.unreachable{border-color:#c22}img{max-width:100%;border:1px solid #ddd}"
        "pre{background:#f6f6f6;padding:0.6em;overflow-x:auto;font-size:12px}",
        "</style></head><body>",
        "<h1>Flight-mode detector certification</h1>",
        f"<p>Target: at most <b>{t.rate_per_h:g}</b> false statics per in-window flight-hour (pushback to "
        f"engines off) at <b>{t.confidence:.0%}</b> confidence"
        + (f", response p95 within {t.max_response_s:g} s" if t.max_response_s else "")
        + f"; section 5.1.1 at P_M = {t.pm:g}.</p>",
        f"<div class='verdict {e(cert.recommendation['status'])}'><b>{e(cert.recommendation['status'])}</b>: "
        f"{e(cert.recommendation['text'])}</div>",
        f"<p><small>The bound is the chosen point's own, over the flights it was chosen on: picking the best "
        f"of {len(cert.summary)} points makes it optimistic. Confirm the choice on flights it was not chosen "
        "on (a second dataset of the same family, `flightmode certify` with the one point as its grid).</small></p>",
    ]
    if cert.seed000:
        s = cert.seed000
        parts.append(
            f"<p>Seed 000's recommended point ({data.seed000_name}) "
            f"<b>{'meets' if s['meets'] else 'does not meet'}</b> the target: {s['false_statics']} false "
            f"statics in {s['in_window_h']:,.1f} h, bound {s['rate_upper_per_h']:.3g} /h, response p95 "
            f"{s['response_p95_s']:.1f} s, availability {s['availability']:.3f}.</p>"
        )
    if len(cert.detectors) > 1:
        parts += _side_by_side_html(cert, figures)
    if "tornado" in figures and data.tornado is not None:  # the verdict's uncertainty, beside the verdict
        parts += tornado_html(data.tornado, figures["tornado"])
    if "pareto" in figures:  # the verdict's picture, above the fold
        parts.append(
            f"<img alt='pareto' src='data:image/png;base64,{base64.b64encode(figures['pareto']).decode()}'>"
        )
    parts.append("<h2>Data</h2>")
    parts.append(
        _table(
            meta["datasets"],
            [
                ("path", "dataset", ""),
                ("family", "family", ""),
                ("flights", "flights", "d"),
                ("flights_ok", "used", "d"),
                ("manifest_sha256", "manifest SHA-256", ""),
            ],
        )
    )
    ex = meta.get("excluded", [])
    parts.append(
        f"<p>Excluded as failed: <b>{len(ex)}</b> flight(s)"
        + (
            ": "
            + "; ".join(
                e(f"{x['flight_id']} ({Path(x['dataset']).name}): {x['error'][:120]}") for x in ex[:20]
            )
            if ex
            else ""
        )
        + "</p>"
    )
    parts.append(
        f"<p>Grid: {len(cert.summary)} points"
        + "".join(
            f"; {e(d['name'])} ({e(d['spec'])}): {len(d['points'])}"
            for d in cert.detectors
            if len(cert.detectors) > 1
        )
        + f"; sigma^2 from {e(meta['sigma2_from'])}.</p>"
    )
    rec = cert.recommendation["point"]
    front = sorted(
        cert.pareto, key=lambda i: (cert.summary[i]["rate_upper_per_h"], cert.summary[i]["response_p95_s"])
    )
    parts.append("<h2>Recommendation, seed 000 and the Pareto front</h2>")
    shown = [rec | {"name": data.recommended_name}]
    if cert.seed000:
        shown.append(cert.seed000 | {"name": data.seed000_name})
    parts.append(_table(shown, POINT_COLS))
    parts.append(
        f"<p>The Pareto front ({len(front)} of {len(cert.summary)} points; the first 25 by bound):</p>"
    )
    parts.append(_table([cert.summary[i] | {"name": data.names[i]} for i in front[:25]], POINT_COLS))
    th = cert.threshold
    if th:
        parts += _section_511(th)
    for key, title in (("recommended", "recommended point"), ("seed000", "seed 000's point")):
        if key in cert.breakdowns:
            parts.append(f"<h2>By condition, at the {title}</h2>")
            parts.append(
                _table(
                    cert.breakdowns[key],
                    [
                        ("condition", "condition", ""),
                        ("value", "value", ""),
                        ("flights", "flights", "d"),
                        ("in_window_h", "in-window h", ",.1f"),
                        ("false_statics", "false statics", "d"),
                        ("false_static_s", "false static s", ",.0f"),
                        ("response_p95_s", "response p95 s", ".1f"),
                    ],
                )
            )
    parts.append("<h2>Figures</h2>")
    for name, png in figures.items():
        if name in ("pareto", "tornado", "pareto_detectors", "response_detectors"):
            continue
        parts.append(
            f"<h3>{e(name)}</h3><img alt='{e(name)}' src='data:image/png;base64,"
            f"{base64.b64encode(png).decode()}'>"
        )
    parts.append("<h2>Reproduce</h2><pre>" + e("\n".join(meta["commands"])) + "</pre>")
    parts.append("<p>Versions: " + e(", ".join(f"{k} {v}" for k, v in meta["versions"].items())) + "</p>")
    parts.append("</body></html>")
    return "\n".join(parts)


def write_report(cert, data: ReportData, out: Path) -> dict[str, Path]:
    """The figures (``out/figures``) and ``out/report.html`` of ``cert`` with the figure data ``data``
    (:func:`flightmode.studies.certify.report_data`); the paths written."""
    from flightmode.atomic import write_text as atomic_text

    fig_dir = Path(out) / "figures"
    fig_dir.mkdir(parents=True, exist_ok=True)
    paths = {n: fig_dir / f"{n}.png" for n in FIGURES}
    fig_pareto(cert, paths["pareto"], data.seed000_index, data.seed000_short)
    grid_rows = [r for r in cert.summary if not r.get("params")]  # k is the built-in grid's axis
    if grid_rows:
        fig_vs_k(
            grid_rows,
            "rate_upper_per_h",
            f"false statics per h, {cert.target.confidence:.0%} bound",
            paths["bound_vs_k"],
            cert.target.rate_per_h,
            log=True,
        )
        fig_vs_k(
            grid_rows,
            "availability",
            "availability (static time reported static)",
            paths["availability_vs_k"],
        )
    else:
        paths.pop("bound_vs_k")
        paths.pop("availability_vs_k")
    if len(cert.detectors) > 1:
        fig_pareto_detectors(cert, paths["pareto_detectors"])
        fig_response_cdf(list(data.detector_curves), paths["response_detectors"])
    else:
        paths.pop("pareto_detectors")
        paths.pop("response_detectors")
    fig_response_cdf(data.response_curves, paths["response_cdf"])
    fig_phase_heatmap(data.phases, cert, paths["phase_heatmap"])
    if cert.threshold:
        fig_static_survival(cert, paths["static_survival"])
    else:
        paths.pop("static_survival")
    if cert.worst_flight and data.worst_flight is not None:
        fig_worst_flight(cert, data.worst_flight, paths["worst_flight"])
    else:
        paths.pop("worst_flight")
    if data.tornado is not None:
        paths["tornado"] = fig_dir / "tornado.png"
        fig_tornado(data.tornado, paths["tornado"])
    report = Path(out) / "report.html"
    atomic_text(render_html(cert, {n: p.read_bytes() for n, p in paths.items()}, data), report)
    return paths | {"report": report}


__all__ = ["write_report", "render_html", "FIGURES", "ReportData", "WorstFlightData"]
