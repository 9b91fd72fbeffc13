"""Certify detector parameters on datasets: ``flightmode certify DATASET... --target-fa-per-h 1e-4``.

From a sweep (:mod:`flightmode.studies.sweep`; run here, or reused from ``OUT/sweep`` when it
covers the same datasets, grid and sigma^2 source):

- every grid point's false-static rate per in-window flight-hour with its exact upper bound
  (Garwood; the rule of three at zero events: :mod:`flightmode.detector.confidence`), the response at
  the destination gate (p50/p95/max) and the availability (the share of truly static time reported
  static);
- the **Pareto front** of (rate bound: lower is better, response p95: lower, availability: higher);
- the **recommendation**: among the points whose bound meets the target (and whose response p95 is
  within ``max_response_s``, if given), the best response, then availability. If none meets it, the
  dataset is too small to show it (or the point's observed rate already exceeds the target): the
  provisional point (fewest false statics, then best response) and the in-window flight-hours still
  needed, as flights of each family;
- seed 000's recommended point (NMV, W_s 1 s, 4 sigma^2, T_th 4 s) measured the same way;
- seed 000 section 5.1.1: the amplitude threshold from a target probability of misdetection P_M,
  computed from the truly static checks of the flights (the empirical survival of MV / sigma^2, over
  all three axes at once: a check is misdetected when any axis reaches the threshold) beside the
  paper's Gaussian formula (eq. 13) with the measured mean and spread, and with white-noise moments
  and the exact chi-square of white noise;
- the breakdown by condition at the recommended and at seed 000's point.

Written to ``OUT``: ``certify.json`` (all of the above), ``report.html`` (self-contained: figures
embedded) and ``figures/*.png`` (:mod:`flightmode.viz.certify_report`).
"""

from __future__ import annotations

import dataclasses
import json
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from flightmode.detector.recommended_point import POINT as RECOMMENDED
from flightmode.errors import InputDataError

if TYPE_CHECKING:
    from flightmode.detector.grid import Grid
    from flightmode.viz.tornado import TornadoData

SEED000_POINT = RECOMMENDED.grid_point()  # seed 000, Table 9, as a grid point of the sweep (params "")


@dataclass(frozen=True)
class Target:
    """What is to be shown: false statics per in-window flight-hour at most ``rate_per_h`` at
    ``confidence``; optionally a response p95 within ``max_response_s``; section 5.1.1's P_M."""

    rate_per_h: float = 1e-4
    confidence: float = 0.95
    max_response_s: float | None = None
    pm: float = 1e-3

    def validate(self) -> None:
        if not (self.rate_per_h > 0 and math.isfinite(self.rate_per_h)):
            raise InputDataError(f"--target-fa-per-h {self.rate_per_h!r}: must be a rate > 0 (e.g. 1e-4)")
        if not 0.0 < self.confidence < 1.0:
            raise InputDataError(
                f"--confidence {self.confidence!r}: must be strictly between 0 and 1 (e.g. 0.95)"
            )
        if self.max_response_s is not None and not self.max_response_s > 0:
            raise InputDataError(f"--max-response-s {self.max_response_s!r}: must be > 0 s")
        if not 0.0 < self.pm < 1.0:
            raise InputDataError(
                f"--pm {self.pm!r}: a probability of misdetection strictly between 0 and 1 (e.g. 1e-3)"
            )


@dataclass(frozen=True)
class Certification:
    target: Target
    summary: list[dict]  # one row per grid point (sweep.summarise)
    pareto: list[int]  # indices into summary
    recommendation: dict
    seed000: dict | None  # seed 000's point's summary row, if the grid holds it
    threshold: dict  # section 5.1.1
    breakdowns: dict  # {"recommended": [...], "seed000": [...]}
    worst_flight: dict | None
    meta: dict = field(default_factory=dict)
    # side by side (:func:`side_by_side`): per detector (the sweep's method column), its points'
    # indices into summary, its own Pareto front, verdict and breakdown at its chosen point
    detectors: list[dict] = field(default_factory=list)


def grid_point(row: dict) -> dict:
    """The grid point of a summary row (and its sensor preset, when the sweep re-sensed)."""
    from flightmode.studies.sweep import POINT_ID

    return {k: row[k] for k in POINT_ID + (("sensor_preset",) if "sensor_preset" in row else ())}


def point_name(row: dict) -> str:
    if row.get("params"):  # a detector of the interface: its label and parameters
        sensor = f" on {row['sensor_preset']}" if row.get("sensor_preset") else ""
        return (
            f"{row['method']} {row['params']}{sensor}"
            if row["params"] != "{}"
            else f"{row['method']}{sensor}"
        )
    m = row["method"].upper() + (f" w{row['weight']:g}" if row["method"] == "emv" else "")
    k = f"{row['k']:g} sigma^2" if row["method"] in ("nmv", "emv") else f"{row['k']:g} x rest"
    sensor = f" on {row['sensor_preset']}" if row.get("sensor_preset") else ""
    return f"{m}, W_s {row['window_s']:g} s, {k}, T_th {row['time_threshold_s']:g} s{sensor}"


# ---------------------------------------------------------------------- the Pareto front
def pareto_front(rows: Sequence[dict]) -> list[int]:
    """Indices of the rows no other row dominates on (rate bound: min, response p95: min,
    availability: max). A missing response counts as the worst (never resumed), a missing
    availability as the worst."""
    if not rows:
        return []
    cost = np.array([[r["rate_upper_per_h"], r["response_p95_s"], -r["availability"]] for r in rows], float)
    cost = np.where(np.isfinite(cost), cost, np.inf)
    le = np.all(cost[:, None, :] <= cost[None, :, :], axis=2)  # le[j, i]: j at least as good as i everywhere
    lt = np.any(cost[:, None, :] < cost[None, :, :], axis=2)  # ... and better somewhere
    dominated = np.any(le & lt, axis=0)
    return np.flatnonzero(~dominated).tolist()


# ---------------------------------------------------------------------- the recommendation
def _hours_per_flight(points, point: dict) -> dict[str, float]:
    """Mean in-window flight-hours of one flight, per family, at a point's rows."""
    from flightmode.studies.sweep import at_point

    by: dict[str, list[float]] = {}
    for r in at_point(points, point):
        by.setdefault(r.get("family") or "dataset", []).append(r["in_window_h"])
    return {f: float(np.mean(v)) for f, v in sorted(by.items())}


def _fixed_order(r: dict) -> tuple:
    """A total order on points for ties: whatever order the grid was given in, the same choice."""
    return (
        r["method"],
        r["weight"],
        r["window_s"],
        r["k"],
        r["time_threshold_s"],
        r.get("params", ""),
        str(r.get("sensor_preset", "")),
    )


def hours_at_rate(target_rate_per_h: float, confidence: float, rate_per_h: float) -> float:
    """In-window hours after which the exact bound reaches the target if events keep coming at the
    observed ``rate_per_h`` (< the target): the smallest T with chi2.ppf(c, 2 (rT + 1)) / 2T <= target."""
    from scipy.optimize import brentq
    from scipy.stats import chi2

    if rate_per_h >= target_rate_per_h:
        return math.inf  # the bound tends to the rate: never below a target it exceeds

    def excess(t_h: float) -> float:
        return chi2.ppf(confidence, 2.0 * (rate_per_h * t_h + 1.0)) / (2.0 * t_h) - target_rate_per_h

    lo = chi2.ppf(confidence, 2.0) / (2.0 * target_rate_per_h)  # no event at all: the least it can need
    hi = lo
    while excess(hi) > 0:
        hi *= 2.0
    return float(brentq(excess, lo * 0.999, hi)) if hi > lo else float(lo)


def recommend(
    summary: Sequence[dict], target: Target, hours_per_flight: Callable[[dict], dict[str, float]]
) -> dict:
    """The point to ship, or why the dataset cannot show one (module docstring). Statuses: ``meets``;
    ``too_slow`` (points meet the rate but none answers within ``max_response_s``); ``unreachable``
    (even the best point's lower bound on its rate is above the target); ``too_small`` (more
    flight-hours would show it)."""
    from scipy.stats import chi2

    from flightmode.detector.confidence import hours_needed

    def fast(r):
        return target.max_response_s is None or r["response_p95_s"] <= target.max_response_s  # NaN: not fast

    def by_response(r):
        resp = r["response_p95_s"] if r["response_p95_s"] == r["response_p95_s"] else math.inf
        avail = r["availability"] if r["availability"] == r["availability"] else -math.inf
        return (resp, -avail, r["rate_upper_per_h"], *_fixed_order(r))

    rate_ok = [r for r in summary if r["rate_upper_per_h"] <= target.rate_per_h]
    meets = [r for r in rate_ok if fast(r)]
    if meets:
        best = min(meets, key=by_response)
        return {
            "status": "meets",
            "point": best,
            "candidates": len(meets),
            "text": f"{point_name(best)} meets the target: at most {best['rate_upper_per_h']:.3g} false statics "
            f"per flight-hour ({target.confidence:.0%} bound, {best['false_statics']} in "
            f"{best['in_window_h']:,.0f} h), response p95 {best['response_p95_s']:.1f} s, "
            f"availability {best['availability']:.3f}",
        }
    if rate_ok:  # the rate is shown, the response limit is what fails
        best = min(rate_ok, key=by_response)
        return {
            "status": "too_slow",
            "point": best,
            "candidates": 0,
            "text": f"{len(rate_ok)} points meet {target.rate_per_h:g} false statics per flight-hour, but none "
            f"answers within {target.max_response_s:g} s at the gate (p95); the fastest of them, "
            f"{point_name(best)}, answers in {best['response_p95_s']:.1f} s: raise --max-response-s or "
            + (
                "widen its grid (faster to resume)" if best.get("params") else "widen the grid (shorter T_th)"
            ),
        }
    pool = [r for r in summary if fast(r)] or list(summary)
    fewest = min(r["false_statics"] for r in pool)
    best = min((r for r in pool if r["false_statics"] == fewest), key=by_response)
    out = {"status": "too_small", "point": best, "candidates": 0}
    limit = (
        ""
        if fast(best)
        else (
            f"; and no point answers within {target.max_response_s:g} s (p95), so the "
            "response limit fails too"
        )
    )
    x, t_h = best["false_statics"], best["in_window_h"]
    lower = chi2.ppf(1.0 - target.confidence, 2 * x) / (2.0 * t_h) if x > 0 else 0.0  # Garwood's lower bound
    if lower > target.rate_per_h:
        out["status"] = "unreachable"
        out["rate_lower_per_h"] = float(lower)
        out["text"] = (
            f"no grid point can meet {target.rate_per_h:g} per flight-hour on such flights: the one with "
            f"the fewest false statics, {point_name(best)}, has {x} in {t_h:,.0f} h, and even the "
            f"{target.confidence:.0%} lower bound on its rate, {lower:.3g} /h, is above the target; widen "
            + ("its grid (slower to call rest)" if best.get("params") else "the grid (lower k, longer T_th)")
            + limit
        )
        return out
    need = hours_needed(target.rate_per_h, target.confidence, x)
    short = max(0.0, need - t_h)
    per = hours_per_flight(grid_point(best))
    flights_short = {f: int(math.ceil(short / h)) for f, h in per.items() if h > 0}
    out |= {"hours_needed": need, "hours_short": short, "flights_short": flights_short}
    at_rate = ""
    if x > 0:  # if the events keep coming at the observed rate, the claim needs more
        at_rate_h = hours_at_rate(target.rate_per_h, target.confidence, best["rate_per_h"])
        out["hours_needed_at_rate"] = at_rate_h
        at_rate = (
            f"; never, if they keep coming at {best['rate_per_h']:.2g} /h"
            if math.isinf(at_rate_h)
            else f"; {at_rate_h:,.0f} h in all if they keep coming at {best['rate_per_h']:.2g} /h"
        )
    more = " or ".join(
        f"{n:,} more flights of {f} ({per[f]:.2f} in-window h each)" for f, n in flights_short.items()
    )
    out["text"] = (
        f"the dataset is too small to show {target.rate_per_h:g} false statics per flight-hour at "
        f"{target.confidence:.0%}: the best point, {point_name(best)}, has {x} false statics in "
        f"{t_h:,.0f} in-window h (bound {best['rate_upper_per_h']:.3g} /h); the claim needs {need:,.0f} h "
        f"{'with no more events' if x else 'with none'}, {short:,.0f} h more: {more}{at_rate}{limit}"
    )
    return out


# ---------------------------------------------------------------------- seed 000 section 5.1.1
def threshold_from_static(
    static,
    pm: float,
    method: str = "nmv",
    weight: float = 1.0,
    window_s: float = 1.0,
    confidence: float = 0.95,
) -> dict:
    """Seed 000 section 5.1.1's threshold for a probability of misdetection ``pm``, in units of
    sigma^2, from the truly static checks of the swept flights (module docstring), beside eq. 13 and
    the exact chi-square for white noise over the window's N samples (the streams of the most common
    rate: N depends on it)."""
    import pyarrow.compute as pc
    from scipy.stats import chi2, norm

    from flightmode.detector.confidence import proportion_upper_bound
    from flightmode.detector.statistics import nmv_moments
    from flightmode.studies.sweep import AXES, STATIC_EDGES

    sel = static.filter(
        pc.and_(
            pc.and_(pc.equal(static["method"], method), pc.equal(static["weight"], weight)),
            pc.equal(static["window_s"], window_s),
        )
    )
    if sel.num_rows == 0:
        raise InputDataError(
            f"the sweep has no {method} W_s {window_s:g} s: section 5.1.1 needs that window in the grid"
        )
    rates = sel["fs_hz"].to_pylist()
    fs = max(set(rates), key=lambda f: (rates.count(f), f))
    sel = sel.filter(pc.equal(sel["fs_hz"], fs))
    n_window = int(round(window_s * fs))
    d = sel.to_pydict()
    n = int(sum(d["static_checks"]))
    if n == 0:
        raise InputDataError(
            "no check of the swept flights has a truly static window: section 5.1.1 needs static data"
        )
    out: dict = {
        "method": method,
        "weight": weight,
        "window_s": window_s,
        "pm": pm,
        "static_checks": n,
        "static_h": n * window_s / 3600.0,
        "flights": sel.num_rows,
    }
    pm_axis = 1.0 - (1.0 - pm) ** (1.0 / 3.0)  # three independent axes, any of which misdetects
    out["pm_per_axis"] = pm_axis
    edges = STATIC_EDGES
    hists = {a: np.sum(np.array(d[f"hist_{a}"], np.int64), axis=0) for a in (*AXES, "max")}
    surv = {a: np.concatenate([np.cumsum(h[::-1])[::-1], [0]]) / n for a, h in hists.items()}  # P(MV >= edge)
    out["survival_k"] = edges.tolist()
    out["survival_max"] = surv["max"].tolist()
    ok = np.flatnonzero(surv["max"] <= pm)
    overflow = ok[0] >= edges.size - 2  # the tail beyond the last bin (1e3 sigma^2): not measured
    k_emp = math.inf if overflow else float(edges[ok[0]])
    count = int(round(surv["max"][ok[0]] * n))
    out["empirical_k"] = k_emp
    out["fs_hz"] = fs
    # fewer than 3 expected exceedances, or the tail beyond the histogram: the threshold is not measured
    out["empirical_resolved"] = bool(n * pm >= 3.0 and not overflow)
    out["empirical_pm_at_k"] = count / n
    out["empirical_pm_upper"] = proportion_upper_bound(count, n, confidence)
    per_axis = {}
    for a in AXES:
        s = float(np.sum(d[f"sum_{a}"]))
        ss = float(np.sum(d[f"sumsq_{a}"]))
        mu = s / n
        sd = math.sqrt(max(ss / n - mu * mu, 0.0))
        i_a = np.flatnonzero(surv[a] <= pm_axis)[0]
        k_a = math.inf if i_a >= edges.size - 2 else float(edges[i_a])
        per_axis[a] = {
            "mean": mu,
            "sd": sd,
            "empirical_k": k_a,
            "gaussian_k": mu + sd * float(norm.isf(pm_axis)),
        }  # eq. 13 inverted, measured mu, sigma_MV
    out["axes"] = per_axis
    out["gaussian_measured_k"] = max(v["gaussian_k"] for v in per_axis.values())
    mu, sd = nmv_moments(n_window)
    out["samples_per_window"] = n_window
    out["gaussian_white_k"] = mu + sd * float(norm.isf(pm_axis))  # seed 000 eq. 13 with white-noise moments
    out["chi2_white_k"] = float(chi2.isf(pm_axis, n_window - 1)) / n_window  # N MV / sigma^2 ~ chi2(N - 1)
    return out


def _flight_key(r: dict) -> tuple:
    """A flight of the sweep: (dataset, flight id, sensor preset)."""
    return r["dataset"], r["flight_id"], r["sensor_preset"]


def worst_flight(points, phases, point: dict) -> dict | None:
    """The flight closest to trouble at ``point``: the most false-static seconds; on a tie (none),
    the most in-window checks under ``k sigma^2`` on all axes (eq. 7's temporary statics)."""
    from flightmode.studies.sweep import at_point, where

    rows = at_point(points, point)
    if not rows:
        return None
    under: dict[tuple, int] = {}
    for r in (
        where(phases, {k: point.get(k, "") for k in ("method", "weight", "window_s", "k", "params")})
        .select(["dataset", "flight_id", "sensor_preset", "under_all"])
        .to_pylist()
    ):
        flight = _flight_key(r)
        under[flight] = under.get(flight, 0) + r["under_all"]

    best = max(rows, key=lambda r: (r["false_static_s"], under.get(_flight_key(r), 0)))
    return {
        "dataset": best["dataset"],
        "flight_id": best["flight_id"],
        "sensor_preset": best["sensor_preset"],
        "false_static_s": best["false_static_s"],
        "false_statics": best["false_static_count"],
        "under_all": under.get(_flight_key(best), 0),
        "aircraft": best.get("aircraft"),
        "placement": best.get("placement"),
        "turbulence": best.get("turbulence"),
        "family": best.get("family"),
    }


# ---------------------------------------------------------------------- the whole job
def _sweep_matches(
    meta: dict, datasets: list[Path], grid, sigma2_from: str, sensors, detectors: Sequence = ()
) -> bool:
    from flightmode.studies.sweep import manifest_digest

    have = [(d["path"], d["manifest_sha256"]) for d in meta.get("datasets", [])]
    want = [(str(p), manifest_digest(p)) for p in datasets]
    g = meta.get("grid")
    if meta.get("detectors") != json.loads(json.dumps([e.as_dict() for e in detectors])):
        return False  # a plugin's code may change under the same name: its points must at least match
    if g is None or grid is None:
        return have == want and g is None and grid is None and meta.get("sigma2_from") == sigma2_from
    return (
        have == want
        and meta.get("sigma2_from") == sigma2_from
        and meta.get("sensors") == (list(sensors) if sensors else None)
        and g.get("methods") == [list(m) for m in grid.methods]
        and g.get("windows_s") == list(grid.windows_s)
        and g.get("ks") == list(grid.ks)
        and g.get("time_thresholds_s") == list(grid.time_thresholds_s)
    )


def command_of(
    datasets_meta: list[dict], grid, target: Target, sigma2_from: str, out: Path, sensors=None, detectors=()
) -> list[str]:
    """The commands that make the datasets again and certify them (for the report)."""
    lines = []
    for d in datasets_meta:
        opts = d.get("options") or {}
        extra = "".join(
            [
                f" --truth {opts['truth']}" if opts.get("truth") not in (None, "10hz") else "",
                " --rrd" if opts.get("rrd") else "",
            ]
        )
        lines.append(f"flightmode dataset {d['family']} --n {d['flights']} --out {d['path']}{extra}")

    def axis(v):
        return ",".join(f"{x:g}" for x in v)

    cmd = (
        f"flightmode certify {' '.join(d['path'] for d in datasets_meta)} --target-fa-per-h {target.rate_per_h:g} "
        f"--confidence {target.confidence:g} --pm {target.pm:g}"
        + (f" --max-response-s {target.max_response_s:g}" if target.max_response_s else "")
    )
    if grid is not None:
        methods = list(dict.fromkeys(m for m, _ in grid.methods))  # the grid's own order
        weights = list(dict.fromkeys(w for m, w in grid.methods if m == "emv"))
        cmd += (
            f" --method {','.join(methods)}"
            + (f" --weight {axis(weights)}" if weights else "")
            + f" --window-s {axis(grid.windows_s)} --k {axis(grid.ks)} --time-threshold-s {axis(grid.time_thresholds_s)}"
        )
    if detectors:  # the detectors' specs and points are in certify.json (meta.detectors)
        cmd += " --grid-file DETECTORS.toml"
    cmd += (
        f" --sigma2-from {sigma2_from}"
        + (f" --sensor {','.join(sensors)}" if sensors else "")
        + f" --out {out}"
    )
    return lines + [cmd]


def certify(
    datasets: Sequence[str | Path],
    grid: Grid | None,
    target: Target,
    *,
    sigma2_from: str = "preset",
    workers: int = 1,
    sensors: Sequence[str] | None = None,
    out: str | Path,
    on_start: Callable[[int], None] | None = None,
    on_flight: Callable[[str], None] | None = None,
    figures: bool = True,
    log: Callable[[str], None] = lambda s: None,
    scheduler: str | None = None,
    tornado: TornadoData | None = None,
    uncertainty: dict | None = None,
    detectors: Sequence = (),
) -> Certification:
    """Sweep (or reuse ``OUT/sweep``), then certify (module docstring); writes ``OUT``. ``grid``: the
    built-in grid (None: none); ``detectors``: detectors of the interface
    (:class:`flightmode.studies.detectors.Entry`), certified side by side with the grid's methods. ``workers``
    and ``scheduler``: the sweep's Dask cluster (:func:`flightmode.studies.sweep.sweep`). ``tornado``
    and ``uncertainty``: the model-uncertainty study of these flights
    (:func:`flightmode.studies.uncertainty.uncertainty`), drawn in the report and kept in
    ``certify.json`` (its ``uncertainty``)."""
    from flightmode.atomic import write_text as atomic_text
    from flightmode.studies.sweep import breakdown, read_sweep, summarise, sweep

    target.validate()
    paths = [Path(d) for d in datasets]
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InputDataError(f"--out {out} is a file: give a folder for the report")
    sweep_dir = out / "sweep"
    result = None
    if (sweep_dir / "sweep.json").exists():
        try:
            cached = read_sweep(sweep_dir)
        except InputDataError:  # an older layout: swept again below
            cached = None
        if cached is not None and _sweep_matches(cached.meta, paths, grid, sigma2_from, sensors, detectors):
            log(f"reusing the sweep in {sweep_dir} (same datasets, grid and sigma^2 source)")
            result = cached
    if result is None:
        result = sweep(
            paths,
            grid,
            sigma2_from=sigma2_from,
            workers=workers,
            sensors=sensors,
            out=sweep_dir,
            on_start=on_start,
            on_flight=on_flight,
            scheduler=scheduler,
            detectors=detectors,
        )
    summary = summarise(
        result.points, target.confidence, target.rate_per_h, by_sensor=bool(result.meta.get("sensors"))
    )
    summary.sort(key=_fixed_order)
    front = pareto_front(summary)
    rec = recommend(summary, target, lambda p: _hours_per_flight(result.points, p))
    seed000 = next(
        (r for r in summary if {k: r[k] for k in SEED000_POINT} == SEED000_POINT and not r["params"]), None
    )
    if seed000 is not None:
        seed000 = seed000 | {
            "meets": bool(
                seed000["rate_upper_per_h"] <= target.rate_per_h
                and (target.max_response_s is None or seed000["response_p95_s"] <= target.max_response_s)
            )
        }
    rp = grid_point(rec["point"])
    # section 5.1.1 is about the moving variance: seed 000's NMV at 1 s if the grid has it, else the
    # first moving-variance method and window of the grid; none at all: no section 5.1.1
    # (the moving variances the sweep kept static statistics of: seed 000's own methods first)
    static: Any = result.static
    swept = static.select(["method", "weight", "window_s"]).to_pylist() if static.num_rows else []
    mv_methods = sorted(
        dict.fromkeys((r["method"], r["weight"]) for r in swept), key=lambda m: m[0] not in ("nmv", "emv")
    )
    th: dict = {}
    if mv_methods:
        seed_method = (RECOMMENDED.method, RECOMMENDED.weight)
        method_5_1_1 = seed_method if seed_method in mv_methods else mv_methods[0]
        windows = sorted({r["window_s"] for r in swept if (r["method"], r["weight"]) == method_5_1_1})
        window_5_1_1 = RECOMMENDED.window_s if RECOMMENDED.window_s in windows else windows[0]
        method, weight = method_5_1_1  # a grid's (method, weight) pair
        th = threshold_from_static(result.static, target.pm, method, weight, window_5_1_1, target.confidence)
        th["p_fa"] = _pfa_near(result.phases, summary, method_5_1_1, window_5_1_1, th["empirical_k"], target)
        th["loop_5_1_1"] = loop_5_1_1(th, result.phases, method_5_1_1, window_5_1_1, target)
    breakdowns = {"recommended": breakdown(result.points, rp, result.phases)}
    seed_point = (
        SEED000_POINT
        | {"params": ""}
        | ({"sensor_preset": seed000["sensor_preset"]} if seed000 and "sensor_preset" in seed000 else {})
    )
    if seed000 is not None:
        breakdowns["seed000"] = breakdown(result.points, seed_point, result.phases)
    worst = worst_flight(result.points, result.phases, seed_point if seed000 is not None else rp)
    meta = result.meta | {
        "excluded": [
            {"dataset": r["dataset"], "flight_id": r["flight_id"], "error": (r.get("error") or "")[:300]}
            for r in result.failed
        ],
        "commands": command_of(result.meta["datasets"], grid, target, sigma2_from, out, sensors, detectors),
    }
    if uncertainty is not None:
        meta["uncertainty"] = uncertainty
    cert = Certification(
        target,
        summary,
        front,
        rec,
        seed000,
        th,
        breakdowns,
        worst,
        meta,
        side_by_side(summary, target, result),
    )
    out.mkdir(parents=True, exist_ok=True)
    atomic_text(json.dumps(as_dict(cert), indent=2, default=_jsonable), out / "certify.json")
    if figures:
        from flightmode.viz.certify_report import write_report

        write_report(cert, dataclasses.replace(report_data(cert, result), tornado=tornado), out)
    return cert


# ---------------------------------------------------------------------- detectors side by side
def side_by_side(summary: Sequence[dict], target: Target, result) -> list[dict]:
    """Per detector (the sweep's ``method`` column: a built-in grid's method, or a detector entry's
    label), in the summary's order: its points (indices into ``summary``), its own Pareto front, its
    verdict (:func:`recommend` over its points alone) and the breakdown by phase and placement at
    the point it would ship."""
    from flightmode.studies.sweep import breakdown

    specs = {e["name"]: e for e in result.meta.get("detectors") or []}
    out = []
    for name in dict.fromkeys(r["method"] for r in summary):
        idx = [i for i, r in enumerate(summary) if r["method"] == name]
        rows = [summary[i] for i in idx]
        rec = recommend(rows, target, lambda p: _hours_per_flight(result.points, p))
        rows_at = breakdown(result.points, grid_point(rec["point"]), result.phases)
        e = specs.get(name)
        out.append(
            {
                "name": name,
                "spec": e["spec"] if e else f"--method {name}",
                "points": idx,
                "pareto": [idx[j] for j in pareto_front(rows)],
                "recommendation": rec,
                "point_name": point_name(rec["point"]),
                "breakdown": [b for b in rows_at if b["condition"] in ("phase", "placement")],
            }
        )
    return out


# ---------------------------------------------------------------------- the report's figure data
def report_data(cert: Certification, result):
    """What :func:`flightmode.viz.certify_report.write_report` draws beyond ``cert``, computed from
    the sweep ``result`` (:class:`~flightmode.viz.certify_report.ReportData`)."""
    from flightmode.studies.sweep import POINT_ID, at_point, where
    from flightmode.viz.certify_report import ReportData

    rec = grid_point(cert.recommendation["point"])
    tths = sorted(
        {
            r["time_threshold_s"]
            for r in cert.summary
            if (r["method"], r["params"]) == (rec["method"], rec["params"])
        }
    )
    shown = [
        ("recommended", rec),
        ("seed 000", SEED000_POINT),
        (f"T_th {tths[0]:g} s", rec | {"time_threshold_s": tths[0]}),
        (f"T_th {tths[-1]:g} s", rec | {"time_threshold_s": tths[-1]}),
    ]
    curves, done = [], set()
    for label, p in shown:
        key = tuple(p.get(k, "") for k in POINT_ID)  # seed 000's point: params "" (a grid point)
        rows = at_point(result.points, p)
        if key in done or not rows:
            continue
        done.add(key)
        v = np.sort(np.array([r["response_s"] for r in rows], float))
        n = v.size
        v = v[np.isfinite(v)]
        if v.size:
            curves.append((f"{label}: {point_name(p)}", v, n))
    p = cert.recommendation["point"]
    phases = (
        where(result.phases, {k: p[k] for k in ("method", "weight", "window_s", "params")})
        .select(["phase", "k", "checks", "under_all"])
        .to_pydict()
    )
    seed = cert.seed000
    per_detector = []  # the response at the gate of each detector at the point it would ship
    for d in cert.detectors if len(cert.detectors) > 1 else []:
        rows = at_point(result.points, grid_point(d["recommendation"]["point"]))
        v = np.sort(np.array([r["response_s"] for r in rows], float))
        per_detector.append(
            (f"{d['name']}: {point_name(d['recommendation']['point'])}", v[np.isfinite(v)], v.size)
        )
    return ReportData(
        names=tuple(point_name(row) for row in cert.summary),
        recommended_name=point_name(cert.recommendation["point"]),
        seed000_name=point_name(SEED000_POINT),
        seed000_short=(  # "NMV 1 s, 4 sigma^2, 4 s"
            f"{RECOMMENDED.method.upper()} {RECOMMENDED.window_s:g} s, {RECOMMENDED.k_sigma:g} sigma^2, "
            f"{RECOMMENDED.time_threshold_s:g} s"
        ),
        seed000_index=(
            next(i for i, row in enumerate(cert.summary) if grid_point(row) == grid_point(seed))
            if seed
            else None
        ),
        response_curves=curves,
        phases=phases,
        worst_flight=_worst_flight_data(cert.worst_flight, result.meta["sigma2_from"])
        if cert.worst_flight
        else None,
        detector_curves=per_detector,
    )


def _worst_flight_data(w: dict, sigma2_from: str):
    """Seed 000 Figs. 14 and 15 in form for the flight ``w`` (:func:`worst_flight`): the recommended
    detector rerun on its stream, then k = 3, 4, 5 sigma^2 at the recommended T_th (Fig. 14) and
    T_th = 2, 3, 4, 5 s at the recommended k (Fig. 15)."""
    import dataclasses

    from flightmode.datasets.make import read_manifest
    from flightmode.detector.flight_mode import detect, final_static
    from flightmode.detector.recommended import recommended_params
    from flightmode.studies.sweep import flight_streams, sigma2_of_flight
    from flightmode.viz.certify_report import WorstFlightData

    ds = Path(w["dataset"])
    row = next(r for r in read_manifest(ds).values() if r["flight_id"] == w["flight_id"])
    resense = [w["sensor_preset"]] if w["sensor_preset"] != row["sensor_preset"] else None  # swept re-sensed
    _, cols, text = next(flight_streams(str(ds), row, resense))
    row = row | {"scenario_toml": text}
    t, acc = cols["t_s"], cols["acc_g"]
    fs = round(1.0 / float(np.median(np.diff(t))), 6)
    p = recommended_params(fs)
    sigma2 = np.asarray(sigma2_of_flight(sigma2_from, row, cols)(p.window), float)
    c = detect(t, acc, p, sigma2)
    fig14 = []
    for k in (3.0, 4.0, 5.0):  # seed 000, Fig. 14
        temp = np.all(c.mv < k * sigma2[None, :], axis=1)
        fin = final_static(temp, c.after_reset, dataclasses.replace(p, k_sigma=k).checks_needed)
        fig14.append((f"{k:g} sigma^2", temp, fin))
    temp_k = np.all(c.mv < p.k_sigma * sigma2[None, :], axis=1)
    fig15 = [
        (
            f"T_th {tth:g} s",
            temp_k,
            final_static(temp_k, c.after_reset, dataclasses.replace(p, time_threshold_s=tth).checks_needed),
        )
        for tth in (2.0, 3.0, 4.0, 5.0)  # seed 000, Fig. 15
    ]
    return WorstFlightData(
        t_min=(c.t_s - t[0]) / 60.0,
        mv_over_sigma2=c.mv / sigma2[None, :],
        ylabel=f"{p.method.upper()} (W_s {p.window_s:g} s) / sigma^2",
        in_window=np.asarray(cols["in_flight_window"], bool)[c.index],
        fig14=fig14,
        fig15=fig15,
        time_threshold_s=p.time_threshold_s,
        k_sigma=p.k_sigma,
    )


def _pfa_near(phases, summary, method: tuple, window_s: float, k: float, target: Target) -> dict | None:
    """Seed 000 section 5.1.1's last step: the P_FA at the grid's k nearest below the threshold found,
    as the in-window fraction of checks under it on all axes (P_FA^t, joint) and the false-static rate
    bound at T_th 4 s (seed 000's) or the nearest."""
    from flightmode.studies.sweep import where

    ks = sorted({r["k"] for r in summary if (r["method"], r["weight"], r["window_s"]) == (*method, window_s)})
    if not math.isfinite(k):
        return None
    below = [x for x in ks if x <= k]
    if not below:
        return None
    kg = below[-1]
    d = (
        where(phases, {"method": method[0], "weight": method[1], "window_s": window_s, "k": kg})
        .select(["checks", "under_all"])
        .to_pydict()
    )
    checks, under = int(sum(d["checks"])), int(sum(d["under_all"]))
    rows = [
        r for r in summary if (r["method"], r["weight"], r["window_s"], r["k"]) == (*method, window_s, kg)
    ]
    tths = sorted(r["time_threshold_s"] for r in rows)
    tth = min(tths, key=lambda t: abs(t - RECOMMENDED.time_threshold_s))
    r = next(x for x in rows if x["time_threshold_s"] == tth)
    return {
        "k": kg,
        "in_window_checks": checks,
        "under_all": under,
        "p_fa_t_joint": under / checks if checks else math.nan,
        "time_threshold_s": tth,
        "false_statics": r["false_statics"],
        "rate_upper_per_h": r["rate_upper_per_h"],
        "meets": bool(r["rate_upper_per_h"] <= target.rate_per_h),
    }


def loop_5_1_1(th: dict, phases, method: tuple, window_s: float, target: Target) -> dict | None:
    """Seed 000 section 5.1.1's last step on the swept flights
    (:func:`flightmode.detector.statistics.threshold_for_pfa`): from the target's P_M, the threshold
    k(P_M) from the truly static checks' survival (any axis), the P_FA of eq. 14 it gives,
    P_FA = (P_FA^t)^(T_th / W_s), P_FA^t the in-window fraction of checks under k on all three axes at
    the grid's k nearest at or above it (the conservative side: a higher k passes more checks), T_th
    seed 000's 4 s; if P_FA is above the target's, P_M is raised a decade and k found again. The
    target's P_FA is its false-static rate per check: ``rate_per_h`` x W_s / 3,600 s (eq. 14's P_FA is
    per check). None when the sweep has no grid k at or above the first threshold."""
    from flightmode.detector.statistics import threshold_for_pfa
    from flightmode.studies.sweep import where

    edges = np.asarray(th["survival_k"], float)
    surv = np.asarray(th["survival_max"], float)
    sel = where(phases, {"method": method[0], "weight": method[1], "window_s": window_s})
    d = sel.select(["k", "checks", "under_all"]).to_pydict()
    grid_k = sorted(set(d["k"]))
    n_checks = RECOMMENDED.time_threshold_s / window_s  # eq. 14's exponent T_th / W_s

    def k_of_pm(pm: float) -> float:
        ok = np.flatnonzero(surv <= pm)
        return float(edges[min(ok[0], edges.size - 1)])

    def pfa_of_k(k: float) -> float:
        above = [x for x in grid_k if x >= k]
        if not above:
            return math.inf  # the grid stops below the threshold: P_FA not measured
        kg = above[0]
        checks = sum(c for kk, c in zip(d["k"], d["checks"]) if kk == kg)
        under = sum(u for kk, u in zip(d["k"], d["under_all"]) if kk == kg)
        return (under / checks) ** n_checks if checks else math.inf

    if not grid_k:
        return None
    pfa_max = target.rate_per_h * window_s / 3600.0
    out = threshold_for_pfa(k_of_pm, pfa_of_k, target.pm, pfa_max)
    return out | {"pfa_max": pfa_max, "time_threshold_s": RECOMMENDED.time_threshold_s, "grid_k": grid_k}


def as_dict(cert: Certification) -> dict:
    d = dataclasses.asdict(cert)
    d["threshold"] = {k: v for k, v in d["threshold"].items() if k not in ("survival_k", "survival_max")}
    if "uncertainty" in d["meta"]:  # the model-uncertainty study, beside the verdict it qualifies
        d["uncertainty"] = d["meta"].pop("uncertainty")
    return d


def _jsonable(v):
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (np.floating,)):
        return float(v)
    if isinstance(v, np.ndarray):
        return v.tolist()
    return str(v)


__all__ = [
    "certify",
    "Certification",
    "Target",
    "pareto_front",
    "recommend",
    "threshold_from_static",
    "worst_flight",
    "SEED000_POINT",
    "point_name",
    "grid_point",
    "report_data",
    "command_of",
    "side_by_side",
]
