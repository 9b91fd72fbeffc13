"""Run folders: ``OUT/<scenario>-s<seed>/`` with ``truth.parquet`` and ``run.json``.

The dataset edge (DESIGN.md): arrays become Parquet here and nowhere else. A run folder is built in
a hidden staging folder beside it and renamed into place only when complete, so a failed or
interrupted run leaves nothing half-written (the staging folder is removed on failure).
"""

from __future__ import annotations

import json
import os
import platform
import shutil
import uuid
from contextlib import contextmanager
from dataclasses import asdict
from importlib import metadata
from pathlib import Path

import numpy as np

from sim.labels import PHASES, SEVERITIES
from sim.plan import FlightPlan
from sim.track import FlightTrack


def run_id(plan: FlightPlan) -> str:
    return f"{plan.name}-s{plan.seed}"


@contextmanager
def staged_run_dir(out_dir: Path, rid: str):
    """Yield a fresh staging folder in ``out_dir``; on success rename it to ``out_dir/rid``."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    stage = out_dir / f".{rid}.partial-{uuid.uuid4().hex[:8]}"
    stage.mkdir()
    try:
        yield stage
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    final = out_dir / rid
    if final.exists():
        trash = out_dir / f".{rid}.old-{uuid.uuid4().hex[:8]}"
        os.replace(final, trash)
        os.replace(stage, final)
        shutil.rmtree(trash, ignore_errors=True)
    else:
        os.replace(stage, final)


def _dict_column(codes: np.ndarray, vocabulary: tuple[str, ...]):
    import pyarrow as pa

    return pa.DictionaryArray.from_arrays(pa.array(codes.astype(np.int32)), pa.array(list(vocabulary)))


def track_table(track: FlightTrack):
    """The FlightTrack as a pyarrow Table, one row per FDM step, SI columns with units in names."""
    import pyarrow as pa

    cols: dict[str, object] = {"t_s": track.t_s}
    for name in ("lat_deg", "lon_deg", "alt_m", "agl_m"):
        cols[name] = getattr(track, name)
    for i, ax in enumerate("ned"):
        cols[f"pos_{ax}_m"] = track.pos_ned_m[:, i]
    for i, ax in enumerate("ned"):
        cols[f"vel_{ax}_mps"] = track.vel_ned_mps[:, i]
    for i, ax in enumerate(("phi", "theta", "psi")):
        cols[f"{ax}_rad"] = track.euler_rad[:, i]
    for i, ax in enumerate("wxyz"):
        cols[f"q{ax}"] = track.quat_wxyz[:, i]
    for i, ax in enumerate("pqr"):
        cols[f"{ax}_radps"] = track.rates_radps[:, i]
    for i, ax in enumerate("pqr"):
        cols[f"{ax}dot_radps2"] = track.ang_acc_radps2[:, i]
    for i, ax in enumerate("xyz"):
        cols[f"f{ax}_body_mps2"] = track.specific_force_body_mps2[:, i]
    for e in range(track.n1_pct.shape[1]):
        cols[f"n1_pct_e{e}"] = track.n1_pct[:, e]
        cols[f"n2_pct_e{e}"] = track.n2_pct[:, e]
        cols[f"thrust_n_e{e}"] = track.thrust_n[:, e]
    for name in ("wow", "flap_norm", "gear_norm", "speedbrake_norm", "ias_mps", "tas_mps", "mach",
                 "alpha_rad", "ground_speed_mps", "vertical_speed_mps"):
        cols[name] = getattr(track, name)
    cols["phase"] = _dict_column(track.phase_code, PHASES)
    cols["in_flight_window"] = track.in_flight_window
    cols["airborne"] = track.airborne
    cols["turbulence_severity"] = _dict_column(track.turbulence_code, SEVERITIES)
    out = {}
    for k, v in cols.items():
        if isinstance(v, np.ndarray) and v.dtype == np.float64 and k not in FLOAT64_COLUMNS:
            v = v.astype(np.float32)  # 7 significant digits: far below any sensor resolution
        out[k] = v if isinstance(v, pa.Array) else pa.array(v)
    return pa.table(out)


# time and position keep double precision (float32 would quantise a 5000 km position to 0.5 m)
FLOAT64_COLUMNS = frozenset({"t_s", "lat_deg", "lon_deg", "alt_m", "pos_n_m", "pos_e_m", "pos_d_m"})


def package_versions() -> dict[str, str]:
    out = {"python": platform.python_version()}
    for pkg in ("flightmode", "jsbsim", "numpy", "scipy", "pyarrow"):
        try:
            out[pkg] = metadata.version(pkg)
        except metadata.PackageNotFoundError:
            out[pkg] = "not installed"
    return out


def write_truth(stage: Path, track: FlightTrack) -> Path:
    import pyarrow.parquet as pq

    path = stage / "truth.parquet"
    pq.write_table(track_table(track), path, compression="zstd")
    return path


def write_run_json(stage: Path, info: dict) -> Path:
    path = stage / "run.json"
    path.write_text(json.dumps(info, indent=2, default=_json_default) + "\n", encoding="utf-8")
    return path


def _json_default(o):
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, tuple):
        return list(o)
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def run_info(plan: FlightPlan, description: str, source: str, track: FlightTrack, metrics: dict) -> dict:
    return {
        "run_id": run_id(plan),
        "scenario": plan.name,
        "description": description,
        "scenario_file": source,
        "seed": plan.seed,
        "aircraft": plan.aircraft,
        "versions": package_versions(),
        "plan": asdict(plan),
        "events": [{"t_s": e.t_s, "name": e.name, "detail": e.detail} for e in track.events],
        "summary": metrics,
        "truth": {"rows": track.n, "fs_hz": track.fs_hz, "sha256": track.digest()},
    }
