"""The verdict with its uncertainty: ``flightmode certify DATASET --uncertainty``.

The certification's bound rests on a model whose uncertain parameters (:mod:`flightmode.uncertain`;
the registry :func:`flightmode.scenarios.model.registry`) are set to nominal values. This study
moves them, one at a time, to each end of their declared range, and then all at once to the worst
plausible corner, and certifies every variant exactly as the nominal:

- a variant's population is the nominal dataset's family with a ``[model]`` table
  (:meth:`~flightmode.scenarios.family.Family.with_model`): the same members, drawn from the same
  streams with the same seeds (common random numbers: a variant's flights differ from the nominal's
  only where the parameter acts), made by :func:`flightmode.datasets.make.make_dataset` into
  ``DATASET/uncertainty/<name>=<value>/`` (resumable like any dataset: a killed study picks up where
  it stopped);
- each variant is certified with :func:`flightmode.studies.certify.certify` (the same grid, target
  and sigma^2 source; its sweep computed on its own flights) into ``OUT/uncertainty/<label>/``;
- per variant: the bound on false statics per in-window flight-hour of the **nominal's recommended
  point** (what the tornado chart draws, and what decides whether the recommendation holds), the
  variant's own recommendation (its point, bound and response at the gate), and seed 000's
  recommended point's bound (the paper's verdict with its uncertainty band: the tornado's second
  panel);
- the worst plausible corner: every parameter at the end that gave the higher bound (a parameter
  whose ends both leave the bound at or under the nominal's stays nominal);
- one sentence: "the recommendation holds across the model's uncertainty", or "it flips when NAME
  is at VALUE (bound X > target Y)" (the variant with the highest bound above the target).

Every flight and every sweep runs on one Dask cluster (:func:`flightmode.cluster.open_client`: a
LocalCluster of ``workers`` processes, or the ``scheduler`` given). The nominal certification is
written as usual to ``OUT`` (``certify.json`` gains ``uncertainty``, ``report.html`` the tornado:
:mod:`flightmode.viz.tornado`).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from flightmode.errors import InputDataError, ScenarioError, did_you_mean

if TYPE_CHECKING:
    from flightmode.detector.grid import Grid
    from flightmode.studies.certify import Certification, Target
    from flightmode.viz.tornado import TornadoData

NOMINAL = "nominal"
CORNER = "worst corner"


@dataclass(frozen=True)
class Variant:
    """One population of the study and its certification's figures."""

    label: str  # "nominal", "<name>=<value>" or "worst corner"
    overrides: dict[str, float]  # the [model] table its flights were flown with (beyond the family's own)
    dataset: str
    flights_ok: int
    in_window_h: float
    at_point: dict  # the nominal recommended point here: false_statics, rate_upper_per_h, response_*_s, ...
    recommendation: dict  # this variant's own: status, point (name), rate_upper_per_h, response_p95_s, text
    seed000: dict | None = None  # seed 000's recommended point here (as at_point), None if the grid lacks it


@dataclass(frozen=True)
class UncertaintyResult:
    """What :func:`uncertainty` found (module docstring)."""

    target_per_h: float
    confidence: float
    point: str  # the nominal recommended point's name
    nominal: Variant
    variants: list[Variant]  # one per parameter end (an end at the nominal value is the nominal itself)
    corner: Variant | None  # None when no parameter raised the bound
    parameters: list[dict]  # per parameter: name, unit, value, low, high, bound_low, bound_high
    holds: bool
    sentence: str
    wall_s: float = math.nan
    meta: dict = field(default_factory=dict)

    def as_dict(self) -> dict:
        return asdict(self)


def variant_label(name: str, value: float) -> str:
    """The folder and table name of one parameter end: ``<name>=<value>``."""
    return f"{name}={value:g}"


def corner_label(overrides: dict[str, float]) -> str:
    """The corner's folder name: its overrides' short digest (another corner, another folder)."""
    h = hashlib.sha256(json.dumps(sorted(overrides.items())).encode()).hexdigest()[:10]
    return f"worst-corner-{h}"


def choose_parameters(names: Sequence[str] | None) -> list[str]:
    """The registry's parameters to vary (all when ``names`` is None), in the registry's order; an
    unknown name is a :class:`ScenarioError` naming the nearest."""
    from flightmode.scenarios.model import registry

    reg = registry()
    if not names:
        return list(reg)
    for n in names:
        if n not in reg:
            raise ScenarioError(
                f"--parameter {n}: unknown model parameter{did_you_mean(n, reg)}; `flightmode scenarios --model` lists them"
            )
    return [n for n in reg if n in set(names)]


def at_point(cert: Certification, point: dict) -> dict:
    """The summary row of ``cert`` at grid ``point`` (a dict of the grid keys), with ``meets``; an
    :class:`InputDataError` if the grid lacks it."""
    from flightmode.studies.certify import grid_point

    for r in cert.summary:
        if grid_point(r) == point:
            return r | {"meets": bool(r["rate_upper_per_h"] <= cert.target.rate_per_h)}
    raise InputDataError(f"the variant's sweep has no row at {point}: certify it with the nominal's grid")


def sentence_of(
    target_per_h: float, nominal: Variant, variants: Sequence[Variant], registry_units: dict[str, str]
) -> tuple[bool, str]:
    """(holds, the one sentence) of the study (module docstring)."""
    bound0 = nominal.at_point["rate_upper_per_h"]
    if bound0 > target_per_h:
        worst = max(variants, key=lambda v: v.at_point["rate_upper_per_h"], default=nominal)
        return False, (
            f"no verdict to hold: at the nominal model the recommended point's bound "
            f"{bound0:.3g} /h is above the target {target_per_h:g} /h (too few flight-hours); across the "
            f"model's uncertainty it reaches {worst.at_point['rate_upper_per_h']:.3g} /h ({worst.label})"
        )
    over = [v for v in variants if v.at_point["rate_upper_per_h"] > target_per_h]
    if not over:
        return True, "the recommendation holds across the model's uncertainty"
    single = [v for v in over if len(v.overrides) == 1] or over
    v = max(single, key=lambda v: v.at_point["rate_upper_per_h"])
    if len(v.overrides) == 1:
        ((name, value),) = v.overrides.items()
        unit = registry_units.get(name, "")
        where = f"{name} is at {value:g}" + ("" if unit in ("", "1") else f" {unit}")  # "1": a factor
    else:
        where = (
            "every parameter is at its worst end together ("
            + ", ".join(f"{k} = {x:g}" for k, x in sorted(v.overrides.items()))
            + ")"
        )
    return False, (
        f"it flips when {where} (bound {v.at_point['rate_upper_per_h']:.3g} /h > target {target_per_h:g} /h)"
    )


def uncertainty(
    dataset: str | Path,
    grid: Grid,
    target: Target,
    *,
    parameters: Sequence[str] | None = None,
    sigma2_from: str = "preset",
    sensors: Sequence[str] | None = None,
    workers: int = 2,
    scheduler: str | None = None,
    out: str | Path,
    log: Callable[[str], None] = lambda s: None,
    on_flight: Callable[[dict], None] | None = None,
    corner: bool = True,
) -> tuple[Certification, UncertaintyResult]:
    """Certify ``dataset`` and every variant of its model (module docstring); returns the nominal
    certification (with the study in its ``certify.json`` and ``report.html``) and the study."""
    import time

    from flightmode.cluster import open_client
    from flightmode.datasets.make import read_manifest
    from flightmode.errors import ClusterError, DatasetError
    from flightmode.scenarios.family import Family
    from flightmode.scenarios.model import registry
    from flightmode.studies.certify import certify, grid_point, point_name

    t0 = time.perf_counter()
    ds = Path(dataset)
    fam_file, info_file = ds / "family.toml", ds / "dataset.json"
    if not fam_file.exists() or not info_file.exists():
        raise InputDataError(
            f"{ds}: not a dataset folder (no family.toml / dataset.json): make it with `flightmode dataset`"
        )
    fam = Family.from_toml_text(fam_file.read_text(encoding="utf-8"), str(fam_file))
    truth = json.loads(info_file.read_text())["options"]["truth"]
    rows = read_manifest(ds)
    if not rows:
        raise InputDataError(f"{ds}: the dataset holds no flight")
    n = max(rows) + 1
    names = choose_parameters(parameters)
    reg = registry()
    base = dict(fam.model)  # the family's own [model] table: the study's nominal
    out = Path(out)

    try:
        with open_client(workers, scheduler, allowed_failures=0) as client:
            address = client.scheduler.address if scheduler is None else scheduler

            def run_certify(paths: list[Path], where: Path) -> Certification:
                return certify(
                    paths,
                    grid,
                    target,
                    sigma2_from=sigma2_from,
                    sensors=sensors,
                    workers=workers,
                    scheduler=address,
                    out=where,
                    figures=False,
                )

            log(f"nominal: certifying {ds}")
            nominal_cert = run_certify([ds], out)
            point = grid_point(nominal_cert.recommendation["point"])

            def variant(label: str, overrides: dict[str, float], folder: str) -> Variant:
                from flightmode.datasets.make import make_dataset

                vdir = ds / "uncertainty" / folder
                log(f"{label}: flying {n} members into {vdir}")
                make_dataset(
                    fam.with_model(base | overrides),
                    n,
                    vdir,
                    scheduler=address,
                    resume=True,
                    truth=truth,
                    on_flight=on_flight,
                )
                cert = run_certify([vdir], out / "uncertainty" / folder)
                return _variant(label, overrides, vdir, cert, point)

            nominal = _variant(NOMINAL, {}, ds, nominal_cert, point)
            variants: list[Variant] = []
            params: list[dict] = []
            for name in names:
                p = reg[name]
                ends = {}
                for end in (p.low, p.high):
                    if end == base.get(name, p.value):
                        ends[end] = nominal
                        continue
                    v = variant(variant_label(name, end), {name: end}, variant_label(name, end))
                    variants.append(v)
                    ends[end] = v
                params.append(
                    {
                        "name": name,
                        "unit": p.unit,
                        "value": base.get(name, p.value),
                        "low": p.low,
                        "high": p.high,
                        "bound_low": ends[p.low].at_point["rate_upper_per_h"],
                        "bound_high": ends[p.high].at_point["rate_upper_per_h"],
                        "seed000_bound_low": _seed000_bound(ends[p.low]),
                        "seed000_bound_high": _seed000_bound(ends[p.high]),
                        "shapes": p.shapes,
                    }
                )
            worst = worst_corner(params, nominal.at_point["rate_upper_per_h"])
            corner_v = None
            if corner and worst:
                same = next((v for v in variants if v.overrides == worst), None)
                corner_v = (
                    variant(CORNER, worst, corner_label(worst))
                    if same is None
                    else dataclasses.replace(same, label=f"{CORNER} (= {same.label})")
                )
    except ClusterError as e:
        raise DatasetError(str(e)) from None
    units = {k: p.unit for k, p in reg.items()}
    holds, sentence = sentence_of(
        target.rate_per_h, nominal, variants + ([corner_v] if corner_v is not None else []), units
    )
    result = UncertaintyResult(
        target.rate_per_h,
        target.confidence,
        point_name(nominal_cert.recommendation["point"]),
        nominal,
        variants,
        corner_v,
        params,
        holds,
        sentence,
        time.perf_counter() - t0,
        {"dataset": str(ds), "members": n, "family": fam.name, "parameters": names},
    )
    log(sentence)
    # the nominal again, from its sweep (reused): certify.json and report.html with the study in them
    final = certify(
        [ds],
        grid,
        target,
        sigma2_from=sigma2_from,
        sensors=sensors,
        workers=1,
        out=out,
        tornado=tornado_data(result),
        uncertainty=result.as_dict(),
    )
    return final, result


def worst_corner(params: Sequence[dict], nominal_bound: float) -> dict[str, float]:
    """Each parameter at the end whose bound was higher, where that is above the nominal's bound (the
    others stay nominal: moving them would not make the corner worse)."""
    out = {}
    for p in params:
        lo, hi = p["bound_low"], p["bound_high"]
        end, b = (p["high"], hi) if hi >= lo else (p["low"], lo)
        if b > nominal_bound and end != p["value"]:
            out[p["name"]] = end
    return out


def _variant(
    label: str, overrides: dict[str, float], path: Path, cert: Certification, point: dict
) -> Variant:
    from flightmode.studies.certify import point_name

    rec = cert.recommendation
    r = rec["point"]
    datasets = cert.meta.get("datasets", [])
    return Variant(
        label,
        dict(overrides),
        str(path),
        int(sum(d.get("flights_ok", 0) for d in datasets)),
        float(r["in_window_h"]),
        _plain(at_point(cert, point)),
        {
            "status": rec["status"],
            "point": point_name(r),
            "false_statics": int(r["false_statics"]),
            "rate_upper_per_h": float(r["rate_upper_per_h"]),
            "response_p50_s": float(r["response_p50_s"]),
            "response_p95_s": float(r["response_p95_s"]),
            "availability": float(r["availability"]),
            "text": rec["text"],
        },
        None if cert.seed000 is None else _plain(cert.seed000),
    )


def _seed000_bound(v: Variant) -> float | None:
    return None if v.seed000 is None else float(v.seed000["rate_upper_per_h"])


def _plain(row: dict) -> dict:
    keep = (
        "false_statics",
        "in_window_h",
        "rate_per_h",
        "rate_upper_per_h",
        "response_p50_s",
        "response_p95_s",
        "response_max_s",
        "availability",
        "meets",
    )
    return {k: (v.item() if hasattr(v, "item") else v) for k, v in row.items() if k in keep}


def tornado_data(result: UncertaintyResult) -> TornadoData:
    """The tornado chart's plain data (:class:`flightmode.viz.tornado.TornadoData`) of a study."""
    from flightmode.viz.tornado import TornadoData

    return TornadoData(
        point=result.point,
        nominal_bound=float(result.nominal.at_point["rate_upper_per_h"]),
        target=float(result.target_per_h),
        confidence=float(result.confidence),
        bars=tuple(
            (p["name"], p["low"], p["high"], p["unit"], float(p["bound_low"]), float(p["bound_high"]))
            for p in result.parameters
        ),
        corner_bound=None if result.corner is None else float(result.corner.at_point["rate_upper_per_h"]),
        seed000=None
        if result.nominal.seed000 is None
        else (
            float(result.nominal.seed000["rate_upper_per_h"]),
            tuple((p["seed000_bound_low"], p["seed000_bound_high"]) for p in result.parameters),
            None if result.corner is None else _seed000_bound(result.corner),
        ),
        sentence=result.sentence,
        rows=tuple(
            _table_row(v)
            for v in [result.nominal, *result.variants, *([result.corner] if result.corner else [])]
        ),
    )


def _table_row(v: Variant) -> dict[str, Any]:
    return {
        "variant": v.label,
        "flights": v.flights_ok,
        "in_window_h": v.in_window_h,
        "false_statics": v.at_point["false_statics"],
        "bound_per_h": v.at_point["rate_upper_per_h"],
        "response_p95_s": v.at_point["response_p95_s"],
        "recommended": v.recommendation["point"],
        "recommended_bound_per_h": v.recommendation["rate_upper_per_h"],
        "recommended_response_p95_s": v.recommendation["response_p95_s"],
        "seed000_false_statics": None if v.seed000 is None else v.seed000["false_statics"],
        "seed000_bound_per_h": _seed000_bound(v),
    }


__all__ = [
    "CORNER",
    "NOMINAL",
    "UncertaintyResult",
    "Variant",
    "at_point",
    "choose_parameters",
    "corner_label",
    "sentence_of",
    "tornado_data",
    "uncertainty",
    "variant_label",
    "worst_corner",
]
