"""Run folders: ``OUT/<scenario>-s<seed>/`` with ``truth.parquet``, ``samples.parquet``,
``run.json`` and ``recording.rrd`` (written by :func:`flightmode.runs.pipeline.write`).

The dataset edge: arrays become Parquet here and nowhere else. A run folder is built in a hidden
staging folder beside it and renamed into place only when complete, so a failed or interrupted run
leaves nothing half-written (the staging folder is removed on failure).
"""

from __future__ import annotations

import json
import platform
from contextlib import contextmanager
from dataclasses import asdict
from importlib import metadata
from pathlib import Path

import numpy as np

from flightmode.atomic import read_parquet, staged_folder
from flightmode.labels import PHASES, SEVERITIES
from flightmode.sim.flight.track import FlightTrack


@contextmanager
def staged_run_dir(out_dir: Path, rid: str):
    """Yield a fresh staging folder in ``out_dir``; on success rename it to ``out_dir/rid``
    (:func:`flightmode.atomic.staged_folder`)."""
    with staged_folder(Path(out_dir) / rid) as stage:
        yield stage


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
    for name in (
        "wow",
        "flap_norm",
        "gear_norm",
        "speedbrake_norm",
        "ias_mps",
        "tas_mps",
        "mach",
        "alpha_rad",
        "ground_speed_mps",
        "vertical_speed_mps",
    ):
        cols[name] = getattr(track, name)
    cols["phase"] = _dict_column(track.phase_code, PHASES)
    cols["in_flight_window"] = track.in_flight_window
    cols["airborne"] = track.airborne
    cols["turbulence_severity"] = _dict_column(track.turbulence_code, SEVERITIES)
    for name in PRESSURE_COLUMNS:
        if getattr(track, name) is not None:
            cols[name] = getattr(track, name)
    out = {}
    for k, v in cols.items():
        if isinstance(v, np.ndarray) and v.dtype == np.float64 and k not in FLOAT64_COLUMNS:
            v = v.astype(np.float32)  # 7 significant digits: far below any sensor resolution
        out[k] = v if isinstance(v, pa.Array) else pa.array(v)
    return pa.table(out)


# time and position keep double precision (float32 would quantise a 5000 km position to 0.5 m), and so do
# the pressures (float32 near 100 kPa steps by 0.008 Pa: below any barometer's noise, but an ideal
# barometer read from the file would then differ from one read from the flight) and the ground speed
# (the floor vibration places the taxiway joints by integrating it: rounded to float32, a joint's
# impulse moved by one sample on re-sensing the pattern flight, 48 counts for a second after it)
FLOAT64_COLUMNS = frozenset(
    {
        "t_s",
        "lat_deg",
        "lon_deg",
        "alt_m",
        "pos_n_m",
        "pos_e_m",
        "pos_d_m",
        "ambient_pressure_pa",
        "cabin_pressure_pa",
        "hold_pressure_pa",
        "ground_speed_mps",
    }
)
PRESSURE_COLUMNS = ("ambient_pressure_pa", "cabin_pressure_pa", "cabin_altitude_m", "hold_pressure_pa")


def recording_table(rec):
    """A Recording as a pyarrow Table: one row per sample, raw counts, g and the labels."""
    import pyarrow as pa

    from flightmode.sim.sensor.carrier import BAG_STATES

    cols = {"t_s": pa.array(rec.t_s)}
    for i, ax in enumerate("xyz"):
        cols[f"raw_{ax}"] = pa.array(rec.counts[:, i].astype(np.int32))
    for i, ax in enumerate("xyz"):
        cols[f"acc_{ax}_g"] = pa.array(rec.acc_g[:, i])
    if rec.gyro_dps is not None:
        for i, ax in enumerate("xyz"):
            cols[f"gyro_{ax}_dps"] = pa.array(rec.gyro_dps[:, i])
    cols["clipped"] = pa.array(rec.clipped.any(axis=1))
    cols["phase"] = _dict_column(rec.phase_code, PHASES)
    cols["in_flight_window"] = pa.array(rec.in_flight_window)
    cols["airborne"] = pa.array(rec.airborne)
    cols["turbulence_severity"] = _dict_column(rec.turbulence_code, SEVERITIES)
    cols["sensor_static"] = pa.array(rec.sensor_static)
    cols["bag_state"] = _dict_column(rec.bag_state_code, BAG_STATES)
    if rec.baro_pa is not None:  # the barometer, read at the accelerometer's rows, and the truth it measured
        cols["baro_pa"] = pa.array(rec.baro_pa)
        cols["baro_new"] = pa.array(rec.baro_new)
        cols["pressure_pa"] = pa.array(rec.pressure_pa)
    return pa.table(cols)


def write_samples(stage: Path, rec) -> Path:
    import pyarrow.parquet as pq

    path = stage / "samples.parquet"
    pq.write_table(recording_table(rec), path, compression="zstd", write_page_checksum=True)
    return path


def read_samples(path: Path) -> tuple[dict, dict | None]:
    """Read a ``samples.parquet`` (or the run folder holding one) back: ``(columns, run_info)``.

    ``columns`` holds ``t_s`` (M,), ``acc_g`` (M, 3), ``counts`` (M, 3) and the labels as arrays
    (``phase`` as strings); ``run_info`` is the run.json beside it, or None if there is none."""
    from flightmode.errors import InputDataError

    path = Path(path)
    file = path / "samples.parquet" if path.is_dir() else path
    if not file.is_file():
        raise InputDataError(f"{path}: no samples.parquet (make a run folder with `flightmode fly`)")
    t = read_parquet(file, "run's samples")  # a flipped byte fails its page CRC
    need = {"t_s", "acc_x_g", "acc_y_g", "acc_z_g"}
    if not need <= set(t.column_names):
        raise InputDataError(f"{file}: not a flightmode samples file (columns {sorted(need)} missing)")
    col = lambda n: t[n].to_numpy(zero_copy_only=False)  # noqa: E731
    out = {
        "t_s": np.asarray(col("t_s"), float),
        "acc_g": np.stack([np.asarray(col(f"acc_{a}_g"), float) for a in "xyz"], axis=1),
    }
    if "gyro_x_dps" in t.column_names:
        out["gyro_dps"] = np.stack([np.asarray(col(f"gyro_{a}_dps"), float) for a in "xyz"], axis=1)
    if "raw_x" in t.column_names:
        out["counts"] = np.stack([np.asarray(col(f"raw_{a}"), np.int32) for a in "xyz"], axis=1)
    for name in ("baro_pa", "pressure_pa"):
        if name in t.column_names:
            out[name] = np.asarray(col(name), float)
    for name in ("in_flight_window", "airborne", "sensor_static", "clipped", "baro_new"):
        if name in t.column_names:
            out[name] = np.asarray(col(name), bool)
    for name in ("phase", "bag_state", "turbulence_severity"):
        if name in t.column_names:
            out[name] = _strings(t[name])
    info_path = file.parent / "run.json"
    info = _read_json(info_path) if info_path.is_file() else None
    return out, info


def _read_json(path: Path) -> dict:
    from flightmode.errors import InputDataError

    try:
        info = json.loads(path.read_text(encoding="utf-8"))
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise InputDataError(f"{path}: not a readable run.json ({e})") from None
    if not isinstance(info, dict):
        raise InputDataError(f"{path}: not a flightmode run.json (not an object)")
    return info


def run_scenario(info: dict, source: str):
    """The Scenario of a run folder's run.json (its ``scenario_toml``)."""
    from flightmode.errors import InputDataError
    from flightmode.scenarios.scenario import Scenario

    if "scenario_toml" not in info:
        raise InputDataError(
            f"{source}: run.json has no scenario_toml: written by an older flightmode; fly it again"
        )
    return Scenario.from_toml_text(info["scenario_toml"], f"{source} (scenario_toml)")


def read_track(run_dir: Path) -> tuple[FlightTrack, dict]:
    """Rebuild the FlightTrack of a run folder from truth.parquet and run.json."""
    from flightmode.errors import InputDataError

    run_dir = Path(run_dir)
    if not (run_dir / "truth.parquet").is_file() or not (run_dir / "run.json").is_file():
        raise InputDataError(
            f"{run_dir}: not a flight run folder (needs truth.parquet and run.json; "
            "make one with `flightmode fly`)"
        )
    info = _read_json(run_dir / "run.json")
    t = read_parquet(run_dir / "truth.parquet", "run's truth")
    need = {
        "t_s",
        "lat_deg",
        "pos_n_m",
        "phi_rad",
        "fz_body_mps2",
        "n1_pct_e0",
        "phase",
        "turbulence_severity",
    }
    if not need <= set(t.column_names):
        raise InputDataError(
            f"{run_dir / 'truth.parquet'}: not a flightmode truth file (columns {sorted(need - set(t.column_names))} "
            "missing)"
        )
    try:
        return track_from_table(t, info), info
    except (KeyError, TypeError, ValueError) as e:  # a run.json key, or a truth column, that is not there
        raise InputDataError(
            f"{run_dir}: run.json and truth.parquet do not make a flight ({type(e).__name__}: {e}); "
            "fly the scenario again"
        ) from None


TRACK_INFO_KEY = (
    b"flightmode.track"  # Parquet metadata of a dataset's full-rate truth: what read_track needs of run.json
)


def track_info(track: FlightTrack) -> dict:
    """The part of run.json a FlightTrack needs besides its columns (:func:`track_from_table`)."""
    return {
        "aircraft": track.aircraft,
        "plan": {
            "origin": {
                "lat_deg": track.origin_lat_deg,
                "lon_deg": track.origin_lon_deg,
                "elevation_m": track.origin_alt_m,
            }
        },
        "events": [{"t_s": e.t_s, "name": e.name, "detail": e.detail} for e in track.events],
        "conditions": track.conditions,
        "truth": {"fs_hz": track.fs_hz},
    }


def track_from_table(t, info: dict) -> FlightTrack:
    """A FlightTrack from a truth table (:func:`track_table`, every FDM step) and run.json's
    aircraft, plan origin, events, conditions and truth rate."""
    from flightmode.sim.flight.track import Event, euler_to_quat_wxyz

    c = {name: t[name].to_numpy(zero_copy_only=False) for name in t.column_names}
    ne = sum(1 for k in c if k.startswith("n1_pct_e"))
    f64 = lambda *names: np.stack([np.asarray(c[n], dtype=float) for n in names], axis=1)  # noqa: E731
    phase = t["phase"].combine_chunks()
    turb = t["turbulence_severity"].combine_chunks()
    euler = f64("phi_rad", "theta_rad", "psi_rad")
    return FlightTrack(
        aircraft=info["aircraft"],
        fs_hz=float(info["truth"]["fs_hz"]),
        origin_lat_deg=info["plan"]["origin"]["lat_deg"],
        origin_lon_deg=info["plan"]["origin"]["lon_deg"],
        origin_alt_m=info["plan"]["origin"]["elevation_m"],
        t_s=c["t_s"],
        lat_deg=c["lat_deg"],
        lon_deg=c["lon_deg"],
        alt_m=c["alt_m"],
        agl_m=np.asarray(c["agl_m"], float),
        pos_ned_m=f64("pos_n_m", "pos_e_m", "pos_d_m"),
        vel_ned_mps=f64("vel_n_mps", "vel_e_mps", "vel_d_mps"),
        euler_rad=euler,
        quat_wxyz=euler_to_quat_wxyz(euler),
        rates_radps=f64("p_radps", "q_radps", "r_radps"),
        ang_acc_radps2=f64("pdot_radps2", "qdot_radps2", "rdot_radps2"),
        specific_force_body_mps2=f64("fx_body_mps2", "fy_body_mps2", "fz_body_mps2"),
        n1_pct=f64(*[f"n1_pct_e{e}" for e in range(ne)]),
        n2_pct=f64(*[f"n2_pct_e{e}" for e in range(ne)]),
        thrust_n=f64(*[f"thrust_n_e{e}" for e in range(ne)]),
        wow=np.asarray(c["wow"], bool),
        flap_norm=np.asarray(c["flap_norm"], float),
        gear_norm=np.asarray(c["gear_norm"], float),
        speedbrake_norm=np.asarray(c["speedbrake_norm"], float),
        ias_mps=np.asarray(c["ias_mps"], float),
        tas_mps=np.asarray(c["tas_mps"], float),
        mach=np.asarray(c["mach"], float),
        alpha_rad=np.asarray(c["alpha_rad"], float),
        ground_speed_mps=np.asarray(c["ground_speed_mps"], float),
        vertical_speed_mps=np.asarray(c["vertical_speed_mps"], float),
        phase_code=_codes(phase, PHASES),
        in_flight_window=np.asarray(c["in_flight_window"], bool),
        airborne=np.asarray(c["airborne"], bool),
        turbulence_code=_codes(turb, SEVERITIES),
        events=tuple(Event(e["t_s"], e["name"], e["detail"]) for e in info["events"]),
        conditions=info.get("conditions", {}),
        **{k: np.asarray(c[k], float) if k in c else None for k in PRESSURE_COLUMNS},
    )


def _strings(col) -> np.ndarray:
    """A (dictionary-encoded) string column as a NumPy object array: the dictionary's strings taken
    by the indices (one Python string per distinct value, not per row)."""
    import pyarrow as pa

    col = col.combine_chunks() if isinstance(col, pa.ChunkedArray) else col
    if not pa.types.is_dictionary(col.type):
        return np.asarray(col.to_pylist(), dtype=object)
    return np.asarray(col.dictionary.to_pylist(), dtype=object)[col.indices.to_numpy(zero_copy_only=False)]


def _codes(col, vocabulary) -> np.ndarray:
    """Dictionary column -> codes into ``vocabulary`` (by name, whatever the file's dictionary order)."""
    lut = np.array([vocabulary.index(v) for v in col.dictionary.to_pylist()], dtype=np.uint8)
    return lut[col.indices.to_numpy(zero_copy_only=False)]


def package_versions() -> dict[str, str]:
    out = {"python": platform.python_version()}
    for pkg in ("flightmode", "jsbsim", "numpy", "scipy", "pyarrow"):
        try:
            out[pkg] = metadata.version(pkg)
        except metadata.PackageNotFoundError:
            out[pkg] = "not installed"
    return out


def write_truth(stage: Path, track: FlightTrack) -> Path:
    """truth.parquet: zstd; dictionary encoding only for the label columns (a float column almost
    never repeats, so trying a dictionary first only costs time) and BYTE_STREAM_SPLIT for the
    floats (their bytes compress better split by significance): 4x faster and half the size of
    the defaults, the same table when read back. Every page carries its CRC-32 (Parquet's page
    checksum, verified by :func:`read_track`): zstd stores incompressible float bytes raw, and a flipped
    byte there would otherwise read back as a wrong number without any error."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    table = track_table(track)
    floats = [f.name for f in table.schema if pa.types.is_floating(f.type)]
    labels = [f.name for f in table.schema if pa.types.is_dictionary(f.type)]
    path = stage / "truth.parquet"
    pq.write_table(
        table,
        path,
        compression="zstd",
        use_dictionary=labels,
        use_byte_stream_split=floats,
        write_page_checksum=True,
    )
    return path


def write_run_json(stage: Path, info: dict) -> Path:
    path = stage / "run.json"
    path.write_text(json.dumps(info, indent=2, default=json_default) + "\n", encoding="utf-8")
    return path


def json_default(o):
    """``json.dumps``'s ``default`` for run.json and the truth's metadata: NumPy scalars as Python
    numbers, tuples as lists; a TypeError for anything else."""
    if isinstance(o, (np.floating, np.integer)):
        return o.item()
    if isinstance(o, tuple):
        return list(o)
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def run_info(result, *, track_sha256: str | None = None) -> dict:
    """run.json of a :class:`~flightmode.runs.pipeline.RunResult`: the scenario (as TOML text,
    reads back with ``Scenario.from_toml_text``), seed, versions, plan, events, the flight's figures,
    the track's SHA-256 (computed here unless given), and each later stage's summary."""
    sc, track = result.scenario, result.track
    info = {
        "run_id": result.run_id,
        "scenario": sc.name,
        "description": sc.description,
        "scenario_file": sc.source,
        "scenario_sha256": sc.digest(),
        "scenario_toml": sc.to_toml(),
        "seed": result.seed,
        "aircraft": sc.aircraft,
        "versions": package_versions(),
        "plan": asdict(sc.plan),
        "events": [{"t_s": e.t_s, "name": e.name, "detail": e.detail} for e in track.events],
        "conditions": track.conditions,
        "summary": result.metrics,
        "truth": {"rows": track.n, "fs_hz": track.fs_hz, "sha256": track_sha256 or track.digest()},
        "wall_time_s": dict(result.wall_s),
    }
    if result.recording is not None:
        info["sensor"] = result.recording.summary()
    if result.detection is not None:
        info["detector"] = result.detection.summary() | {"sigma2_from": "bench calibration of the unit"}
    if result.redundant is not None:
        info["redundant"] = result.redundant.summary()
    if result.path is not None:
        info["path"] = result.path.rows
        info["path_laws_m"] = {
            "random_walk": result.path.random_walk_m,
            "offset": result.path.offset_drift_m,
            "span_s": result.path.span_s,
        }
        info["ground_rolls"] = [c.as_dict() for c in result.path.ground_rolls]
        if result.path.ground_rolls_note is not None:
            info["ground_rolls_note"] = result.path.ground_rolls_note
    return info
