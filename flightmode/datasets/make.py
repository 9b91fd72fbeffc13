"""Labelled datasets of a family's flights on Dask: ``flightmode dataset FAMILY --n N --out DIR``.

One Dask task per flight: the worker regenerates member ``i`` from the family's text, flies, senses and
evaluates it (:func:`flightmode.run`), and writes its files itself (the flight's data never leaves
its worker; one flight per worker process at a time bounds its memory). The client keeps the manifest.

Layout (hive-partitioned Parquet, zstd; pyarrow.dataset, polars, DuckDB and Hugging Face ``datasets``
read it as it is)::

    DIR/family.toml                                  the family, as given (its SHA-256 ties DIR to it)
    DIR/flights.parquet                              the manifest: one row per flight (manifest_schema)
    DIR/samples/aircraft=<type>/part-<id>.parquet    the accelerometer stream with every label
    DIR/truth/aircraft=<type>/part-<id>.parquet      the aircraft's state (--truth full | 10hz | none)
    DIR/rrd/aircraft=<type>/part-<id>.rrd            with --rrd: the Rerun recording, for offline replay
    DIR/README.md                                    the dataset card
    DIR/timings.jsonl                                wall time (whole, by stage), peak memory per flight (not data)

Atomic and resumable: every file is written to a temporary name in its final folder and renamed; the
manifest is rewritten whole (temporary name, rename) after each flight. A flight's files depend only
on (family, i, options), so a run killed at any point and resumed with ``--resume`` redoes only the
flights missing from the manifest and ends with exactly the files of an uninterrupted run. A flight
that fails (a typed flightmode error, a worker that died, the ``--flight-timeout-s`` limit) is retried
once, then recorded in the manifest with its error; it never stops the dataset.
Two failures that are not the flight's stop the dataset with one line naming --resume (the manifest
keeps the flights done): the Dask scheduler gone, and a full disk (no space, a file-size limit, a quota).
"""

from __future__ import annotations

import contextlib
import errno
import hashlib
import json
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from flightmode.atomic import TMP_GLOB, read_parquet
from flightmode.atomic import write_parquet as atomic_parquet  # the names the CLI and tests use
from flightmode.atomic import write_text as atomic_text
from flightmode.cluster import open_client
from flightmode.errors import ClusterError, DatasetError, FlightmodeError, FlightTimeoutError, InputDataError

if TYPE_CHECKING:
    from flightmode.scenarios.family import Family

TRUTH_RATES = ("full", "10hz", "none")
ATTEMPTS = 2  # a failed flight is retried once
MANIFEST = "flights.parquet"


@dataclass(frozen=True, slots=True)
class Options:
    truth: str = "10hz"
    flight_timeout_s: float | None = None
    rrd: bool = False  # also a Rerun recording per flight (DIR/rrd/...; not byte-identical across runs)

    def as_dict(self) -> dict[str, Any]:
        return {"truth": self.truth, "flight_timeout_s": self.flight_timeout_s, "rrd": self.rrd}

    def files_dict(self) -> dict[str, Any]:
        """The options that change what is written (a resume must keep them; the time limit may change)."""
        return {"truth": self.truth, "rrd": self.rrd}


# ---------------------------------------------------------------------- files
def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def flight_id(i: int) -> str:
    return f"{i:06d}"


# ---------------------------------------------------------------------- one flight (on a worker)
def fly_member(family_text: str, i: int, out_dir: str, options: dict) -> dict:
    """Fly member ``i`` of the family and write its files under ``out_dir``; the manifest row (plus
    ``wall_s``, ``peak_rss_mb`` and ``stages_s``, the pipeline's wall time per stage). Raises what the
    flight raises (the client records it)."""
    import resource

    import numpy as np
    import pyarrow as pa

    from flightmode.labels import PHASES
    from flightmode.runs import pipeline, run_io
    from flightmode.scenarios.family import Family

    t0 = time.perf_counter()
    fam = Family.from_toml_text(family_text, "family.toml")
    sc = fam.member(i)
    limit = options.get("flight_timeout_s")

    def watchdog(t_s: float, phase: str) -> None:
        if limit is not None and time.perf_counter() - t0 > limit:
            raise FlightTimeoutError(
                f"flight {flight_id(i)} exceeded the {limit:g} s wall-time limit in phase '{phase}' at "
                f"t = {t_s:.0f} s (simulated); raise --flight-timeout-s and --resume"
            )

    r = pipeline.run(sc, stages=("fly", "sense", "detect"), progress=watchdog)
    fid = flight_id(i)
    tr, rec, det, metrics = r.track, r.recording, r.detection, r.metrics
    if tr is None or rec is None or det is None or metrics is None:  # never: run() fills the stages asked
        raise DatasetError(f"flight {fid}: the run returned no track, recording or detection")
    out = Path(out_dir)
    part = f"aircraft={sc.aircraft}/part-{fid}.parquet"
    samples = run_io.recording_table(rec)
    samples = samples.append_column("flight_id", pa.array(np.full(samples.num_rows, fid)))
    files = {"samples": f"samples/{part}"}
    atomic_parquet(samples, out / files["samples"])
    if options["truth"] != "none":
        truth = run_io.track_table(tr)
        if options["truth"] == "10hz":
            step = max(1, int(round(tr.fs_hz / 10.0)))
            truth = truth.take(pa.array(np.arange(0, truth.num_rows, step)))
        truth = truth.append_column("flight_id", pa.array(np.full(truth.num_rows, fid)))
        if options["truth"] == "full":  # what rebuilds the FlightTrack, so that the flight can be re-sensed
            truth = truth.replace_schema_metadata(
                {run_io.TRACK_INFO_KEY: json.dumps(run_io.track_info(tr), default=run_io.json_default)}
            )
        files["truth"] = f"truth/{part}"
        atomic_parquet(truth, out / files["truth"])
    if options.get("rrd"):
        import shutil
        import tempfile

        # the run folder's recording (pipeline.write), moved into place; its scratch folder removed
        with tempfile.TemporaryDirectory(prefix=f".rrd-{fid}.tmp-", dir=out) as scratch:
            written = pipeline.write(Path(scratch), r, rrd=True)
            dest = out / "rrd" / f"aircraft={sc.aircraft}" / f"part-{fid}.rrd"
            dest.parent.mkdir(parents=True, exist_ok=True)
            shutil.move(str(written["rrd"]), dest)
        files["rrd"] = str(dest.relative_to(out))
    dt = 1.0 / tr.fs_hz
    phase_s = np.bincount(tr.phase_code, minlength=len(PHASES)) * dt
    row = {
        "flight_id": fid,
        "index": i,
        "status": "ok",
        "error": None,
        "attempts": 1,
        "name": sc.name,
        "seed": sc.seed,
        "aircraft": sc.aircraft,
        "origin": sc.plan.origin.icao,
        "destination": sc.plan.destination.icao,
        "scenario_sha256": sc.digest(),
        "scenario_toml": sc.to_toml(),
        "gate_to_gate_s": float(tr.duration_s),
        "airborne_s": float(tr.airborne.sum() * dt),
        **{f"phase_{p}_s": float(phase_s[k]) for k, p in enumerate(PHASES)},
        "samples": int(rec.t_s.shape[0]),
        "samples_in_flight_window": int(np.count_nonzero(rec.in_flight_window)),
        "samples_airborne": int(np.count_nonzero(rec.airborne)),
        "samples_static": int(np.count_nonzero(rec.sensor_static)),
        "turbulence": ",".join(t.severity for t in sc.plan.turbulence),
        "landing_quality": sc.plan.landing_quality,
        "placement": sc.carrier.placement,
        "carrier_kind": sc.carrier.kind,
        "sensor_preset": sc.sensor.preset,
        **stowage_columns(rec.stowage),
        "touchdown_sink_mps": float(metrics.get("touchdown_sink_mps", float("nan"))),
        "detector_false_static_count": det.false_static_count,
        "detector_false_static_s": det.false_static_s,
        "detector_response_s": float("nan") if det.response_s is None else float(det.response_s),
        "detector_in_flight_checks": det.in_flight_checks,
        "samples_file": files["samples"],
        "samples_sha256": _sha256(out / files["samples"]),
        "truth_file": files.get("truth"),
        "truth_sha256": _sha256(out / files["truth"]) if "truth" in files else None,
        "rrd_file": files.get("rrd"),
    }
    row["wall_s"] = time.perf_counter() - t0
    row["stages_s"] = {k: float(v) for k, v in r.wall_s.items()}  # fly, sense, detect
    row["peak_rss_mb"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    return row


def stowage_columns(stowage: dict | None) -> dict:
    """The manifest's record of where and how the bag lay in flight (``Recording.stowage["in_flight"]``,
    None where the flight has none): what seed 000's Tables 4 / 5 depend on most."""
    f = (stowage or {}).get("in_flight") or {}
    return {
        "inflight_placement": f.get("placement"),
        "cabin_row": f.get("cabin_row"),
        "packing": f.get("packing"),
        "stowed_yaw_deg": f.get("yaw_deg"),
        "stowed_tilt_deg": f.get("tilt_deg"),
        "sensor_x_from_fuselage_deg": f.get("x_from_fuselage_deg"),
        "stowage_json": None if stowage is None else json.dumps(stowage),
    }


def stowage_of_row(row: dict) -> dict | None:
    """A manifest row's whole stowage record (``Recording.stowage``). A row with only the flat columns
    (written before ``stowage_json`` was kept) gives its one in-flight segment; a row without either
    (a resumed old dataset's first flights), None."""
    text = row.get("stowage_json")
    if text is not None:
        return json.loads(text)
    if row.get("sensor_x_from_fuselage_deg") is None:
        return None
    return {
        "in_flight": {
            "placement": row["inflight_placement"],
            "cabin_row": row["cabin_row"],
            "packing": row["packing"],
            "yaw_deg": row["stowed_yaw_deg"],
            "tilt_deg": row["stowed_tilt_deg"],
            "x_from_fuselage_deg": row["sensor_x_from_fuselage_deg"],
        }
    }


def _failed_row(fam, i: int, error: str, attempts: int) -> dict:
    row = {"flight_id": flight_id(i), "index": i, "status": "failed", "error": error, "attempts": attempts}
    try:
        sc = fam.member(i)
    except Exception:
        return row
    return row | {
        "name": sc.name,
        "seed": sc.seed,
        "aircraft": sc.aircraft,
        "origin": sc.plan.origin.icao,
        "destination": sc.plan.destination.icao,
        "scenario_sha256": sc.digest(),
        "scenario_toml": sc.to_toml(),
    }


def _remove_flight_files(out: Path, i: int) -> None:
    """A failed flight leaves no file: a loader reading the folders would take it for data."""
    for part in ("samples", "truth", "rrd"):
        for p in (out / part).glob(f"aircraft=*/part-{flight_id(i)}.*"):
            p.unlink(missing_ok=True)


def _part_damage(dataset: str | Path, row: dict, part: str) -> str | None:
    """What is wrong with one file of a flown flight: None, or the file and the fault."""
    path = Path(dataset) / row[f"{part}_file"]
    if not path.is_file():
        return f"{path}: missing"
    if row.get(f"{part}_sha256") not in (None, _sha256(path)):
        return f"{path}: not the file this dataset wrote (its SHA-256 is not the one flights.parquet holds)"
    return None


def damage(dataset: str | Path, row: dict) -> str | None:
    """What is wrong with the files of a flight the manifest records as flown (``row``): None if its
    samples and truth files are there with the SHA-256 the manifest holds (and its recording, which
    has no recorded hash, is there), else one line naming the file and the fault."""
    parts = [p for p in ("samples", "truth", "rrd") if row.get(f"{p}_file")]
    return next((why for p in parts if (why := _part_damage(dataset, row, p)) is not None), None)


def flight_file(dataset: str | Path, row: dict, part: str = "samples") -> Path:
    """The ``part`` file ("samples" or "truth") of a dataset flight, checked against the manifest's
    SHA-256 before anyone reads it: an :class:`InputDataError` naming the file if it is missing,
    damaged, cut short or replaced, and how to fly it again."""
    if row.get(f"{part}_file") is None:  # only a truth part may be absent: --truth none
        raise InputDataError(
            f"{dataset}: flight {row['flight_id']} has no {part} file (made with --truth none); make the "
            "dataset with `flightmode dataset ... --truth full`"
        )
    if (why := _part_damage(dataset, row, part)) is not None:
        n = max(read_manifest(Path(dataset))) + 1  # the dataset's family is the copy it keeps
        raise InputDataError(
            f"{why}; fly it again: flightmode dataset {Path(dataset) / 'family.toml'} --n {n} "
            f"--out {dataset} --resume --verify"
        )
    return Path(dataset) / row[f"{part}_file"]


def _error_text(e: BaseException) -> str:
    """What the manifest records of a failure: flightmode's own message (it names the flight's problem
    and depends on nothing but the flight), else only the exception's type (a worker's death names
    the worker's address and time: those go to timings.jsonl, not into the data)."""
    return f"{type(e).__name__}: {e}" if isinstance(e, FlightmodeError) else type(e).__name__


# ---------------------------------------------------------------------- the manifest
TIMING_KEYS = ("wall_s", "peak_rss_mb", "stages_s")


def read_manifest(out: Path) -> dict[int, dict]:
    p = Path(out) / MANIFEST
    if not p.exists():
        return {}
    return {int(r["index"]): r for r in read_parquet(p, "dataset's manifest").to_pylist()}


def is_dataset(path: str | Path) -> bool:
    """A folder made by ``flightmode dataset`` (it has the manifest)."""
    return (Path(path) / MANIFEST).is_file()


def ok_flights(
    dataset: str | Path, purpose: str = "sweep", full_truth_for: str | None = None
) -> tuple[list[dict], list[dict], dict]:
    """A dataset's flights for ``purpose`` (a verb, for the error): the manifest rows of the flights
    that flew and of those that failed (each with its ``dataset``), in manifest order, and its
    dataset.json. An InputDataError if the folder is not a dataset or no flight of it flew, or, when
    ``full_truth_for`` names what needs it (e.g. "validation rebuilds each flight"), if the dataset
    was not made with ``--truth full``."""
    dataset = Path(dataset)
    if not is_dataset(dataset):
        raise InputDataError(f"{dataset}: no flights.parquet: not a dataset made by `flightmode dataset`")
    rows = read_manifest(dataset)
    ok = [rows[i] for i in sorted(rows) if rows[i]["status"] == "ok"]
    failed = [rows[i] | {"dataset": str(dataset)} for i in sorted(rows) if rows[i]["status"] != "ok"]
    if not ok:
        raise InputDataError(f"{dataset}: no flight succeeded ({len(failed)} failed): nothing to {purpose}")
    meta_p = dataset / "dataset.json"
    meta = json.loads(meta_p.read_text()) if meta_p.exists() else {}
    truth = (meta.get("options") or {}).get("truth")
    if full_truth_for is not None and truth != "full":
        raise InputDataError(
            f"{dataset}: {full_truth_for} from its full-rate truth, and this dataset keeps truth "
            f"{truth!r}; make it with `flightmode dataset ... --truth full`"
        )
    return ok, failed, meta


def manifest_schema():
    """The manifest's columns and types, whatever the flights' outcomes (a manifest of failures only
    has every column, null where a failed flight has no value)."""
    import pyarrow as pa

    from flightmode.labels import PHASES

    f64, i64, s = pa.float64(), pa.int64(), pa.string()
    fields = [
        ("flight_id", s),
        ("index", i64),
        ("status", s),
        ("error", s),
        ("attempts", i64),
        ("name", s),
        ("seed", i64),
        ("aircraft", s),
        ("origin", s),
        ("destination", s),
        ("scenario_sha256", s),
        ("scenario_toml", s),
        ("gate_to_gate_s", f64),
        ("airborne_s", f64),
        *((f"phase_{p}_s", f64) for p in PHASES),
        ("samples", i64),
        ("samples_in_flight_window", i64),
        ("samples_airborne", i64),
        ("samples_static", i64),
        ("turbulence", s),
        ("landing_quality", s),
        ("placement", s),
        ("carrier_kind", s),
        ("sensor_preset", s),
        ("inflight_placement", s),
        ("cabin_row", s),
        ("packing", s),
        ("stowed_yaw_deg", f64),
        ("stowed_tilt_deg", f64),
        ("sensor_x_from_fuselage_deg", f64),
        ("stowage_json", s),
        ("touchdown_sink_mps", f64),
        ("detector_false_static_count", i64),
        ("detector_false_static_s", f64),
        ("detector_response_s", f64),
        ("detector_in_flight_checks", i64),
        ("samples_file", s),
        ("samples_sha256", s),
        ("truth_file", s),
        ("truth_sha256", s),
        ("rrd_file", s),
    ]
    return pa.schema(fields)


def _write_manifest(out: Path, rows: dict[int, dict]) -> None:
    import pyarrow as pa

    schema = manifest_schema()
    ordered = [rows[i] for i in sorted(rows)]
    table = pa.Table.from_pylist([{k: r.get(k) for k in schema.names} for r in ordered], schema=schema)
    atomic_parquet(table, Path(out) / MANIFEST)


# ---------------------------------------------------------------------- the folder
def _check_folder(out: Path, fam, options: Options, resume: bool, n: int) -> None:
    """Refuse a folder holding another dataset (or any dataset without --resume); reads only."""
    marker = out / "family.toml"
    meta = out / "dataset.json"
    if out.exists() and not out.is_dir():
        raise DatasetError(f"--out {out} is a file: give a folder")
    if out.exists() and any(out.iterdir()):
        if not marker.exists():
            raise DatasetError(
                f"{out} is not empty and holds no flightmode dataset: choose an empty or new --out"
            )
        have = hashlib.sha256(marker.read_bytes()).hexdigest()
        if have != fam.digest():
            raise DatasetError(
                f"{out} holds a dataset of another family (SHA-256 {have[:12]}, this one "
                f"{fam.digest()[:12]}): choose another --out"
            )
        if not resume:
            raise DatasetError(
                f"{out} already holds a dataset of this family: pass --resume to continue it, "
                "or choose another --out"
            )
        info = json.loads(meta.read_text()) if meta.exists() else {}
        made = {k: v for k, v in info.get("options", {}).items() if k in options.files_dict()}
        if made and made != {k: options.files_dict()[k] for k in made}:
            raise DatasetError(
                f"{out} was made with {made}, not {options.files_dict()}: resume with the same "
                "--truth and --rrd"
            )
        held = read_manifest(out)
        if held and max(held) >= n:
            raise DatasetError(
                f"{out} holds flights up to member {max(held)}: resume with --n {max(held) + 1} or more"
            )


def _sweep_temporaries(out: Path) -> None:
    """Remove the half-written files and scratch folders (flightmode.atomic.TMP_GLOB) of a run that was
    killed or stopped in the middle of a write."""
    import shutil

    for tmp in out.rglob(TMP_GLOB):
        if tmp.is_dir():
            shutil.rmtree(tmp, ignore_errors=True)
        else:
            tmp.unlink(missing_ok=True)


def _claim_folder(out: Path, fam, options: Options) -> None:
    """Make the folder this family's: its family.toml and options; a killed run's half-written files go."""
    out.mkdir(parents=True, exist_ok=True)
    _sweep_temporaries(out)
    marker = out / "family.toml"
    if not marker.exists():
        atomic_text(fam.text, marker)
    atomic_text(
        json.dumps(
            {"family": fam.name, "family_sha256": fam.digest(), "options": options.as_dict()}, indent=2
        ),
        out / "dataset.json",
    )


def check_request(
    family,
    n: int,
    out: str | Path,
    *,
    workers: int = 2,
    resume: bool = False,
    truth: str = "10hz",
    flight_timeout_s: float | None = None,
    rrd: bool = False,
    verify: bool = False,
) -> tuple[Family, Options, Path]:
    """(family, options, out folder) of a valid request; a :class:`DatasetError` (or ScenarioError for the
    family) naming what is wrong otherwise. Writes nothing."""
    from flightmode.scenarios.family import Family

    fam = family if isinstance(family, Family) else Family.resolve(family)
    if isinstance(n, bool) or not isinstance(n, int) or n <= 0:
        raise DatasetError(f"--n {n!r}: the number of flights must be a positive integer")
    if truth not in TRUTH_RATES:
        raise DatasetError(f"--truth {truth!r}: choose one of {', '.join(TRUTH_RATES)}")
    if isinstance(workers, bool) or not isinstance(workers, int) or workers <= 0:
        raise DatasetError(f"--workers {workers!r}: must be a positive integer")
    if flight_timeout_s is not None and not flight_timeout_s > 0:
        raise DatasetError(f"--flight-timeout-s {flight_timeout_s!r}: must be positive")
    if verify and not resume:
        raise DatasetError("--verify checks the flights of a dataset being resumed: add --resume")
    options = Options(truth, flight_timeout_s, bool(rrd))
    out = Path(out)
    _check_folder(out, fam, options, resume, n)
    return fam, options, out


def make_dataset(
    family,
    n: int,
    out: str | Path,
    *,
    workers: int = 2,
    scheduler: str | None = None,
    resume: bool = False,
    truth: str = "10hz",
    flight_timeout_s: float | None = None,
    rrd: bool = False,
    verify: bool = False,
    on_start: Callable[[str | None, int], None] | None = None,
    on_flight: Callable[[dict], None] | None = None,
    on_damaged: Callable[[dict[str, str]], None] | None = None,
) -> dict[int, dict]:
    """Make (or, with ``resume``, complete) the dataset of the family's members 0..n-1 in ``out``;
    returns the manifest rows by index. ``verify`` (with ``resume``): first check every recorded
    flight's files against the manifest (:func:`damage`); a flight whose files are missing or damaged
    is taken out of the manifest, its files removed, and flown again (the same bytes: a flight's files
    depend only on the family, its index and the options). ``on_start(dashboard_url, flights_to_do)``,
    ``on_flight(row)`` and ``on_damaged({flight_id: what is wrong})`` (called once, before any
    flight, when ``verify`` is set) report progress (the CLI's progress bar)."""
    fam, options, out = check_request(
        family,
        n,
        out,
        workers=workers,
        resume=resume,
        truth=truth,
        flight_timeout_s=flight_timeout_s,
        rrd=rrd,
        verify=verify,
    )
    # the cluster before writing: a dead scheduler leaves nothing behind. A failed flight is retried
    # once by _run itself: Dask must not re-run a task whose worker died (allowed_failures 0). The
    # folder's lock is taken once the cluster is up and released after it has closed: a run that ends
    # early (Ctrl-C, an error) closes its LocalCluster, whose nannies stop their workers, perhaps in
    # the middle of a write; that write's temporary is then swept while the folder is still this run's
    with contextlib.ExitStack() as lock:
        locked = False
        try:
            with contextlib.ExitStack() as stack:
                try:
                    client = stack.enter_context(open_client(workers, scheduler, allowed_failures=0))
                except ClusterError as e:
                    raise DatasetError(str(e)) from None
                lock.enter_context(_folder_lock(out))
                locked = True
                try:
                    _claim_folder(out, fam, options)
                    if verify:
                        _drop_damaged(out, on_damaged)
                    return _run(client, fam, n, out, options, on_start, on_flight)
                except OSError as e:  # the manifest, the card or the log on a full disk (written atomically)
                    if _disk_full(e):
                        raise _disk_full_error(out, e, "the manifest or the card") from None
                    raise
        except BaseException:
            # never another run's folder (a held lock raises before this run owns it), and only when the
            # workers were this run's own (a LocalCluster, closed above): the workers of a --scheduler
            # may still be writing, and their leftovers wait for the sweep of the next --resume
            if locked and scheduler is None:
                _sweep_temporaries(out)
            raise


def _drop_damaged(out: Path, on_damaged: Callable[[dict[str, str]], None] | None) -> None:
    """Take the flights whose files are missing or damaged (:func:`damage`) out of the manifest and
    remove their files, so that the run flies them again."""
    rows = read_manifest(out)
    bad = {i: why for i, r in rows.items() if r["status"] == "ok" and (why := damage(out, r)) is not None}
    for i in bad:
        _remove_flight_files(out, i)
        del rows[i]
    if bad:
        _write_manifest(out, rows)
    if on_damaged is not None:
        on_damaged({flight_id(i): why for i, why in sorted(bad.items())})


@contextlib.contextmanager
def _folder_lock(out: Path):
    """One run at a time per dataset folder (a second one would overwrite the first's manifest)."""
    import fcntl

    out.mkdir(parents=True, exist_ok=True)
    with open(out / ".lock", "w") as f:
        try:
            fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise DatasetError(
                f"{out} is being written by another `flightmode dataset` run: wait for it"
            ) from None
        yield


def _run(client, fam, n: int, out: Path, options: Options, on_start, on_flight) -> dict[int, dict]:
    from dask.distributed import as_completed

    held = read_manifest(out)
    rows = {i: r for i, r in held.items() if r["status"] == "ok"}  # failures are tried again
    todo = [i for i in range(n) if i not in rows]
    if on_start is not None:
        on_start(client.dashboard_link, len(todo))
    opts = options.as_dict()
    # task keys unique to this folder and these options: two datasets on one scheduler never share a task
    token = hashlib.sha256(
        f"{fam.digest()}|{out.resolve()}|{json.dumps(opts, sort_keys=True)}".encode()
    ).hexdigest()[:12]
    fut_index: dict[str, int] = {}  # task key -> member index
    attempts: dict[int, int] = {}  # member index -> tries so far
    futures = []

    def submit(i: int):
        f = client.submit(
            fly_member,
            fam.text,
            i,
            str(out.resolve()),
            opts,
            key=f"flight-{token}-{i}-a{attempts[i]}",
            pure=False,
        )
        fut_index[f.key] = i
        return f

    for i in todo:
        attempts[i] = 1
        futures.append(submit(i))
    ac = as_completed(futures, with_results=False)
    timings = out / "timings.jsonl"
    for f in ac:
        i = fut_index[f.key]
        detail = None
        try:
            row = f.result()
        except Exception as e:
            _stop_on_lost_scheduler_or_full_disk(client, e, out, i, len(rows), n)
            detail = f"{type(e).__name__}: {e}"
            if attempts[i] < ATTEMPTS:
                attempts[i] += 1
                ac.add(submit(i))
                continue
            _remove_flight_files(out, i)
            row = _failed_row(fam, i, _error_text(e), attempts[i])
        else:
            row["attempts"] = attempts[i]
        timing = {k: row.pop(k) for k in TIMING_KEYS if k in row}
        rows[i] = row
        _write_manifest(out, rows)
        with open(timings, "a", encoding="utf-8") as t:
            t.write(
                json.dumps(
                    {
                        "flight_id": row["flight_id"],
                        "status": row["status"],
                        "gate_to_gate_s": row.get("gate_to_gate_s"),
                        "error_detail": detail,
                        **timing,
                    }
                )
                + "\n"
            )
        if on_flight is not None:
            on_flight(row | timing)
    from flightmode.datasets.card import write_card

    write_card(out, fam, rows, options)
    return rows


# a write that failed for want of space (ENOSPC), a file-size limit (EFBIG) or a quota (EDQUOT): every
# later flight would fail alike, so the dataset stops with one line instead of recording each as failed
DISK_FULL_ERRNOS = (errno.ENOSPC, errno.EFBIG, errno.EDQUOT)


def _disk_full(e: BaseException) -> bool:
    return isinstance(e, OSError) and e.errno in DISK_FULL_ERRNOS


def _disk_full_error(out: Path, e: OSError, what: str) -> DatasetError:
    import os

    return DatasetError(
        f"{out}: {what} could not be written: {os.strerror(e.errno or 0)} (errno {e.errno}); nothing "
        "half-written is left: free some space and run again with --resume"
    )


def _stop_on_lost_scheduler_or_full_disk(
    client, e: BaseException, out: Path, i: int, done: int, n: int
) -> None:
    """A flight's failure that is not the flight's: the scheduler gone (Dask cancels every future when
    its client loses the scheduler) or the disk full. A DatasetError naming it and --resume; the
    manifest keeps the flights done (the flight's own files, if any, are removed)."""
    from concurrent.futures import CancelledError

    if isinstance(e, CancelledError) or client.status != "running":
        raise DatasetError(
            f"the Dask scheduler went away mid-run ({type(e).__name__}); {done} of {n} flights are in "
            f"{out / MANIFEST}: start the scheduler and its workers again and run with --resume"
        ) from None
    if isinstance(e, OSError) and _disk_full(e):
        _remove_flight_files(out, i)
        raise _disk_full_error(out, e, f"flight {flight_id(i)}") from None


# ---------------------------------------------------------------------- reading
def open_dataset(path: str | Path, part: str = "samples"):
    """The dataset's ``samples`` (or ``truth``) as a ``pyarrow.dataset.Dataset`` (hive partitions:
    the ``aircraft`` column comes from the folder names)."""
    import pyarrow.dataset as ds

    root = Path(path) / part
    if not (Path(path) / MANIFEST).exists() or not root.is_dir():
        raise InputDataError(
            f"{path}: not a flightmode dataset with {part} (make one with `flightmode dataset`)"
        )
    return ds.dataset(root, format="parquet", partitioning="hive")


def windows(path: str | Path, length_s: float, step_s: float | None = None, label: str = "in_flight_window"):
    """Fixed-length windows of every flight's samples for machine learning: an iterator of ``(x, y,
    flight_id)`` with ``x`` (n, 3) accelerations in g and ``y`` the window's ``label`` (True when most
    of its samples carry it). Windows never straddle two flights; ``step_s`` defaults to ``length_s``.
    Checked at once (not at the first ``next``)."""
    step_s = length_s if step_s is None else step_s
    if not (
        isinstance(length_s, (int, float))
        and length_s > 0
        and isinstance(step_s, (int, float))
        and step_s > 0
    ):
        raise InputDataError(f"windows: length_s {length_s!r} and step_s {step_s!r} must be positive seconds")
    rows = read_manifest(Path(path))
    if not rows:
        raise InputDataError(f"{path}: not a flightmode dataset (no flights.parquet)")
    return _windows(Path(path), rows, float(length_s), float(step_s), label)


def _windows(path: Path, rows: dict, length_s: float, step_s: float, label: str):
    import numpy as np
    import pyarrow.parquet as pq

    for i in sorted(rows):
        r = rows[i]
        if r["status"] != "ok":
            continue
        t = pq.read_table(flight_file(path, r), columns=["t_s", "acc_x_g", "acc_y_g", "acc_z_g", label])
        ts = t["t_s"].to_numpy()
        if ts.shape[0] < 2:
            continue
        fs = 1.0 / float(np.median(np.diff(ts)))
        n, s = int(round(length_s * fs)), int(round(step_s * fs))
        if n < 1 or s < 1:
            raise InputDataError(f"windows: {length_s} s or {step_s} s is less than one sample at {fs:g} Hz")
        x = np.stack([t[f"acc_{a}_g"].to_numpy() for a in "xyz"], axis=1)
        y = t[label].to_numpy(zero_copy_only=False).astype(bool)
        for a in range(0, x.shape[0] - n + 1, s):
            yield x[a : a + n], bool(y[a : a + n].mean() > 0.5), r["flight_id"]


__all__ = [
    "make_dataset",
    "fly_member",
    "read_manifest",
    "open_dataset",
    "windows",
    "damage",
    "flight_file",
    "DatasetError",
    "FlightTimeoutError",
    "TRUTH_RATES",
]
