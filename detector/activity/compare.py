"""Seed 001's Monte Carlo tables against ours (issue 53): z-scores, the grid edges, the AUC ranking's
rank correlation, and the thresholds moved onto the scales the paper's tables use.

z-scores. For a statistic with our mean m over N runs (sample standard deviation s) and the paper's
m_p +- s_p over its N_p = 500 runs (seed 001, section 3.1.2, Tables 1-6: "average value" +- the
spread of the runs), the standard error of the difference of the two means is

    SE = sqrt(s^2 / N + s_p^2 / N_p),      z = (m - m_p) / SE,

and ``z500`` is the z the same difference would have if ours were also N_p runs (SE with s / sqrt(N_p)):
what an N = 500 rerun would show if the mean stayed where the small run put it. Table 13 prints the
AUC without a spread: its s_p is taken equal to ours (stated in the table).

Rank correlation: Spearman's rho of the two AUC rankings over the cases both have (the Pearson
correlation of the ranks, ties given their average rank; Spearman 1904, Am. J. Psychol. 15:72).

Thresholds on the paper's scales: :mod:`~flightmode.detector.activity.scales`.

The AUC's floor (:func:`auc_floor`). A ROC curve rises monotonically from (0, 0) to (1, 1), so one
that passes through an operating point (FPR f, TPR t) stays at or above t for every FPR >= f: its
area is at least t (1 - f). The accuracy there is a = pi t + (1 - pi)(1 - f), pi the active share of
the samples. On that line t (1 - f) is a downward parabola, least at an end (t = 1 or f = 0):

    AUC >= floor(a, pi) = max(0, min((a - pi) / (1 - pi), (a - (1 - pi)) / pi)),

which is 2a - 1 at pi = 1/2 and lower on either side. Seed 001's AUC is taken "at the optimal
parameters" (section 3.1.2) and its accuracy is the best over thresholds there, so the two columns
of one case must satisfy it. For a fixed pi the floor is one straight line in a (clipped at 0, a
convex function), so the mean AUC over runs is at least the floor of the mean accuracy. The paper
does not print pi; a paper AUC below the floor is impossible for every pi in
[pi_lo, 1 - pi_lo], pi_lo = (1 - a) / (1 - AUC) (:func:`auc_floor_interval`).
"""

from __future__ import annotations

import math

import numpy as np

from flightmode.detector.activity.scales import PAPER_SCALES, PaperScale, paper_scale, to_paper_scale

PAPER_N = 500  # seed 001, section 3.1.2: "a Monte Carlo simulation of N = 500 runs"


# ---------------------------------------------------------------- z-scores
def z_score(mean: float, sd: float, n: int, paper_mean: float, paper_sd: float, paper_n: int = PAPER_N):
    """(SE, z, z at N = paper_n) of our mean against the paper's (module docstring)."""
    se = math.sqrt(sd * sd / n + paper_sd * paper_sd / paper_n)
    se500 = math.sqrt(sd * sd / paper_n + paper_sd * paper_sd / paper_n)
    d = mean - paper_mean
    z = d / se if se > 0 else math.copysign(math.inf, d) if d else 0.0
    z500 = d / se500 if se500 > 0 else math.copysign(math.inf, d) if d else 0.0
    return se, z, z500


def z_table(
    rows, n_runs: int, stats=("accuracy", "correlation", "auc"), paper_n: int = PAPER_N
) -> list[dict]:
    """One dict per (case, statistic) of :func:`montecarlo.summary` rows that the paper has: ours,
    the paper's, the difference, SE, z and z500. Table 13's AUC has no spread: the paper's sd is
    taken as ours (``paper_sd_assumed`` True)."""
    out = []
    for r in rows:
        for stat in stats:
            m, s = r[f"{stat}_mean"], r[f"{stat}_std"]
            if stat == "auc":
                pm, ps, assumed = r["paper_auc"], s, True
            else:
                pm, ps, assumed = r[f"paper_{stat}_mean"], r[f"paper_{stat}_std"], False
            if not (np.isfinite(m) and np.isfinite(pm)):
                continue
            s = s if np.isfinite(s) else 0.0
            se, z, z500 = z_score(m, s, n_runs, pm, ps, paper_n)
            out.append(
                {
                    "label": r["label"],
                    "detector": r["detector"],
                    "signal": r["signal"],
                    "stat": stat,
                    "ours": m,
                    "ours_sd": s,
                    "paper": pm,
                    "paper_sd": ps,
                    "paper_sd_assumed": assumed,
                    "diff": m - pm,
                    "se": se,
                    "z": z,
                    "z500": z500,
                }
            )
    return out


# ---------------------------------------------------------------- ranks
def ranks(values) -> np.ndarray:
    """Ranks 1..n of ``values`` (1 = smallest), ties given their average rank."""
    v = np.asarray(values, float)
    order = np.argsort(v, kind="mergesort")
    r = np.empty(v.size)
    sv = v[order]
    i = 0
    while i < v.size:
        j = i
        while j + 1 < v.size and sv[j + 1] == sv[i]:
            j += 1
        r[order[i : j + 1]] = 0.5 * (i + j) + 1.0
        i = j + 1
    return r


def spearman(x, y) -> float:
    """Spearman's rank correlation of two equal-length sequences (Pearson's r of their ranks, ties
    averaged); NaN for fewer than 2 pairs or a constant sequence."""
    a, b = np.asarray(x, float), np.asarray(y, float)
    if a.shape != b.shape or a.ndim != 1:
        raise ValueError(f"spearman: x {a.shape} and y {b.shape} must be 1-D of one length")
    if a.size < 2:
        return math.nan
    ra, rb = ranks(a), ranks(b)
    ra -= ra.mean()
    rb -= rb.mean()
    den = math.sqrt(float(np.sum(ra * ra) * np.sum(rb * rb)))
    return float(np.sum(ra * rb) / den) if den > 0 else math.nan


def auc_rank_correlation(rows) -> tuple[float, int]:
    """(Spearman's rho, number of cases) of our mean AUCs against Table 13's over the cases both have
    (a higher AUC is a better rank in both)."""
    pairs = [
        (r["auc_mean"], r["paper_auc"])
        for r in rows
        if np.isfinite(r["auc_mean"]) and np.isfinite(r["paper_auc"])
    ]
    if not pairs:
        return math.nan, 0
    ours, paper = zip(*pairs)
    return spearman(ours, paper), len(pairs)


# ---------------------------------------------------------------- the AUC's floor
def auc_floor(accuracy, activity_fraction):
    """The least area of any ROC curve through an operating point of accuracy ``accuracy`` on a
    record whose active share of samples is ``activity_fraction`` (module docstring); arrays
    broadcast."""
    a = np.asarray(accuracy, float)
    pi = np.asarray(activity_fraction, float)
    if np.any((pi <= 0) | (pi >= 1)):
        raise ValueError(f"auc_floor: activity_fraction must be in (0, 1), got {activity_fraction!r}")
    f = np.maximum(0.0, np.minimum((a - pi) / (1.0 - pi), (a - (1.0 - pi)) / pi))
    return float(f) if f.ndim == 0 else f


def auc_floor_interval(accuracy: float, auc_value: float) -> tuple[float, float] | None:
    """The active shares pi for which an AUC of ``auc_value`` is below the floor of an operating
    point of accuracy ``accuracy`` (:func:`auc_floor`): (pi_lo, 1 - pi_lo), or None when no pi makes
    it impossible (the floor peaks at pi = 1/2 at 2a - 1)."""
    if auc_value >= 2.0 * accuracy - 1.0:
        return None
    lo = (1.0 - accuracy) / (1.0 - auc_value)
    return lo, 1.0 - lo


def auc_floor_table(result) -> list[dict]:
    """Per case: the paper's accuracy and AUC, the floor its accuracy puts under its AUC at our runs'
    mean active share, the shares for which its AUC is impossible; our mean AUC and the mean of our
    runs' floors (each run at its own share: every run's AUC is at or above its floor)."""
    from flightmode.detector.activity.montecarlo import label, paper_row

    pi = float(np.mean([r["activity_fraction"] for r in result.rows]))
    out = []
    for name, signal in result.config.grid.cases():
        mine = [r for r in result.rows if r["detector"] == name and r["signal"] == signal]
        p = paper_row(name, signal)
        ours_floor = auc_floor([r["accuracy"] for r in mine], [r["activity_fraction"] for r in mine])
        row = {
            "label": label(name, signal),
            "pi": pi,
            "ours_auc": float(np.mean([r["auc"] for r in mine])),
            "ours_floor": float(np.mean(ours_floor)),
            "ours_below": int(np.sum(np.array([r["auc"] for r in mine]) < ours_floor - 1e-12)),
            "paper_accuracy": p.accuracy[0] if p else math.nan,
            "paper_auc": p.auc if p else math.nan,
        }
        if p:
            row["paper_floor"] = auc_floor(p.accuracy[0], pi)
            row["paper_impossible_for"] = auc_floor_interval(p.accuracy[0], p.auc)
        else:
            row["paper_floor"], row["paper_impossible_for"] = math.nan, None
        out.append(row)
    return out


# ---------------------------------------------------------------- grid edges
def grid_edges(result) -> list[dict]:
    """Per case of a :class:`montecarlo.MonteCarloResult`: the grid's window (and shift) range, our
    mean best window (shift), the fraction of runs whose best window (shift) is the grid's lowest or
    highest value, and the paper's mean (is it inside the grid?)."""
    from flightmode.detector.activity.montecarlo import label, paper_row

    grid = result.config.grid
    out = []
    for name, signal in grid.cases():
        e = grid.edges(name)
        mine = [r for r in result.rows if r["detector"] == name and r["signal"] == signal]
        p = paper_row(name, signal)
        row = {"label": label(name, signal), "detector": name, "signal": signal}
        for par in ("window", "shift"):
            lo_hi = e[par]
            vals = np.array([r[par] for r in mine], float)
            pm = getattr(p, par)[0] if p is not None and getattr(p, par) is not None else math.nan
            if lo_hi is None:
                row[par] = None
                continue
            lo, hi = lo_hi
            row[par] = {
                "grid": (lo, hi),
                "mean": float(np.mean(vals)),
                "at_low": float(np.mean(vals == lo)),
                "at_high": float(np.mean(vals == hi)),
                "paper": pm,
                "paper_inside": bool(lo <= pm <= hi) if np.isfinite(pm) else None,
            }
        out.append(row)
    return out


# the columns of error_table: groups of synth.PERIOD_KINDS (a posture's transitions together, its rest
# together), and the jump's flight beside the whole jump
ERROR_GROUPS: tuple[tuple[str, tuple[str, ...]], ...] = (
    ("still", ("still",)),
    ("walking", ("walking",)),
    ("running", ("running",)),
    ("jumping", ("jumping",)),
    ("of it in flight", ("jumping_flight",)),
    ("transitions", ("sit_down", "lie_down", "stand_up")),
    ("seated/lying", ("seated", "lying")),
    ("constant rate", ("constant_rate",)),
    ("constant acc.", ("constant_acc",)),
)


def error_table(result) -> list[dict]:
    """Per case: its errors by period (:func:`montecarlo.errors_by_kind`, mean over runs, share of all
    samples) in the groups of :data:`ERROR_GROUPS`, and 1 - accuracy (their total without the flight
    column, which is part of the jumps')."""
    from flightmode.detector.activity.montecarlo import label

    out = []
    for name, signal in result.config.grid.cases():
        mine = [r for r in result.rows if r["detector"] == name and r["signal"] == signal]
        row = {"label": label(name, signal), "detector": name, "signal": signal}
        for col, kinds in ERROR_GROUPS:
            row[col] = float(np.mean([sum(r[f"err_{k}"] for k in kinds) for r in mine]))
        row["error"] = float(np.mean([1.0 - r["accuracy"] for r in mine]))
        out.append(row)
    return out


# ---------------------------------------------------------------- the text
def _f(v, fmt):
    return f"{v:{fmt}}" if v is not None and np.isfinite(v) else "-"


def format_compare(result) -> str:
    """The comparison as text: z-scores of accuracy, correlation and AUC (Tables 1-6, 13), the AUC
    rank correlation, the thresholds on the paper's scales, the AUC floor, where each case errs and
    the grid edges."""
    from flightmode.detector.activity.montecarlo import summary

    rows = summary(result)
    n = result.n_runs
    out = [
        f"Paper vs ours (N = {n} runs, {result.config.alignment} windows; the paper N = {PAPER_N}): "
        "z = (ours - paper) / sqrt(sd^2/N + sd_p^2/500); z500 = the same difference at N = 500.",
        "Table 13's AUC has no spread: its sd is taken as ours (*).",
        f"{'case':<11} {'stat':<5} {'ours':>15} {'paper':>15} {'diff':>7} {'SE':>7} {'z':>7} {'z500':>7}",
    ]
    zt = z_table(rows, n)
    for stat in ("accuracy", "correlation", "auc"):
        for z in (z for z in zt if z["stat"] == stat):
            star = "*" if z["paper_sd_assumed"] else ""
            out.append(
                f"{z['label']:<11} {stat[:5]:<5} {z['ours']:>7.4f} +- {z['ours_sd']:.3f} "
                f"{z['paper']:>7.4f} +- {z['paper_sd']:.3f}{star} {z['diff']:>+7.4f} {z['se']:>7.4f} "
                f"{z['z']:>+7.1f} {z['z500']:>+7.1f}"
            )
        within = [z for z in zt if z["stat"] == stat]
        k3 = sum(abs(z["z"]) <= 3 for z in within)
        k3_500 = sum(abs(z["z500"]) <= 3 for z in within)
        out.append(f"  {stat}: |z| <= 3 in {k3} of {len(within)} cases; |z500| <= 3 in {k3_500}")
    rho, k = auc_rank_correlation(rows)
    out += ["", f"AUC ranking (Table 13): Spearman's rho = {_f(rho, '.3f')} over {k} cases", ""]
    out += [
        "Thresholds on the paper's scales (median over runs; the mean is pulled by flat optima)",
        f"{'case':<11} {'ours':>11} {'paper scale':>11} {'paper':>19}  unit (why)",
    ]
    for r in rows:
        sc = paper_scale(r["detector"], r["signal"])
        out.append(
            f"{r['label']:<11} {_f(r['threshold_median'], '.4g'):>11} {_f(r.get('threshold_paper_median'), '.4g'):>11} "
            f"{_f(r['paper_threshold_mean'], '.4g'):>9} +- {_f(r['paper_threshold_std'], '.3g'):<7}  "
            f"{sc.unit} ({sc.why})"
        )
    fl = auc_floor_table(result)
    out += [
        "",
        "AUC floor (any ROC through an operating point of accuracy a, active share pi, has AUC >= "
        f"min((a - pi)/(1 - pi), (a - 1 + pi)/pi); pi = {fl[0]['pi']:.3f}, our runs' mean):",
        f"{'case':<11} {'paper acc':>9} {'paper AUC':>9} {'its floor':>9}  {'impossible for pi in':<20} "
        f"{'our AUC':>8} {'our floor':>9} {'runs below':>10}",
    ]
    for r in fl:
        iv = r["paper_impossible_for"]
        iv_s = f"[{iv[0]:.3f}, {iv[1]:.3f}]" if iv else "-"
        out.append(
            f"{r['label']:<11} {_f(r['paper_accuracy'], '9.4f')} {_f(r['paper_auc'], '9.4f')} "
            f"{_f(r['paper_floor'], '9.4f')}  {iv_s:<20} {r['ours_auc']:>8.4f} {r['ours_floor']:>9.4f} "
            f"{r['ours_below']:>10d}"
        )
    bad = [r["label"] for r in fl if r["paper_impossible_for"] and r["paper_floor"] > r["paper_auc"]]
    out.append(
        f"  the paper's AUC is below the floor of its own accuracy at pi = {fl[0]['pi']:.3f} in {len(bad)} "
        f"cases{': ' + ', '.join(bad) if bad else ''}"
    )
    if bad:
        rho_ok, k_ok = auc_rank_correlation([r for r in rows if r["label"] not in bad])
        out.append(f"  AUC ranking without them: Spearman's rho = {_f(rho_ok, '.3f')} over {k_ok} cases")
    out += [
        "",
        "Where each case errs: share of all samples (%) it marks wrongly, by period (mean over runs; 'of it in "
        "flight': the jumps' samples under 0.5 g)",
        f"{'case':<11} {'error':>6} " + " ".join(f"{c:>{max(len(c), 6)}}" for c, _ in ERROR_GROUPS),
    ]
    for r in error_table(result):
        out.append(
            f"{r['label']:<11} {100 * r['error']:>6.2f} "
            + " ".join(f"{100 * r[c]:>{max(len(c), 6)}.2f}" for c, _ in ERROR_GROUPS)
        )
    out += [
        "",
        "Grid edges: the grid's range, our mean best value, the fraction of runs at the low / high edge, the paper's",
        f"{'case':<11} {'window grid':>11} {'mean':>6} {'@lo':>5} {'@hi':>5} {'paper':>6}   "
        f"{'shift grid':>10} {'mean':>5} {'@lo':>5} {'@hi':>5} {'paper':>6}",
    ]
    for e in grid_edges(result):
        parts = [f"{e['label']:<11}"]
        for par, wid in (("window", 11), ("shift", 10)):
            v = e[par]
            if v is None:
                parts.append(
                    f"{'-':>{wid}} {'':>6} {'':>5} {'':>5} {'':>6}" if par == "window" else f"{'-':>{wid}}"
                )
                continue
            g = f"{v['grid'][0]}-{v['grid'][1]}"
            parts.append(
                f"{g:>{wid}} {v['mean']:>6.1f} {v['at_low']:>5.2f} {v['at_high']:>5.2f} {_f(v['paper'], '6.1f'):>6}"
            )
        out.append("  ".join(parts))
    return "\n".join(out)


__all__ = [
    "PAPER_N",
    "PAPER_SCALES",
    "PaperScale",
    "auc_floor",
    "auc_floor_interval",
    "auc_floor_table",
    "auc_rank_correlation",
    "format_compare",
    "grid_edges",
    "paper_scale",
    "ranks",
    "spearman",
    "to_paper_scale",
    "z_score",
    "z_table",
]
