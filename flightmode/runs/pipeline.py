"""The pipeline: one run is fly -> sense -> detect -> path -> write, each a plain function over frozen
containers, each callable on its own; :func:`run` chains them. The command line (``flightmode fly``,
``flightmode sense``) is a thin shell over these functions, and so is everything that runs many
flights.

    >>> import flightmode
    >>> r = flightmode.run("pattern", seed=3)          # doctest: +SKIP
    >>> r.detection.false_static_count, r.written      # doctest: +SKIP
    (0, {})

Model parameters: a scenario's ``[model]`` table (:attr:`Scenario.overrides`) is passed to the flight
and sensing functions that read uncertain parameters (:mod:`flightmode.uncertain`), as an argument:
the same scenario, seed and overrides give the same run in any process.

Randomness: one :class:`~flightmode.streams.Streams` per run, from the scenario's seed (or the
``seed`` given), with a named child per stage: ``flight`` (turbulence), ``sensor`` (the unit, the
bag's timeline and motion, vibration, noise, gyro) and ``detector/bench`` (the bench calibration of
the unit's noise). A stage's numbers depend only on its own streams, so re-sensing a flight with
another sensor keeps the flight, and adding a draw to one stage never moves another's.
"""

from __future__ import annotations

import contextlib
import dataclasses
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Literal

from flightmode.errors import FlightmodeError, did_you_mean
from flightmode.scenarios.scenario import Scenario, SensorChoice
from flightmode.streams import Streams

if TYPE_CHECKING:
    import numpy as np

    from flightmode.detector.evaluation import Evaluation
    from flightmode.detector.pressure import PressureParams, RedundantEvaluation
    from flightmode.runs.ground_roll import GroundRollCheck
    from flightmode.sim.flight.track import FlightTrack
    from flightmode.sim.sensor.accelerometer import AccelerometerPreset
    from flightmode.sim.sensor.carrier import CarrierSpec
    from flightmode.sim.sensor.gyroscope import GyroSpec
    from flightmode.sim.sensor.recording import Recording
    from flightmode.viz.rrd import RrdWriter

STAGES = ("fly", "sense", "detect", "path", "write")


@dataclass(frozen=True, slots=True)
class PathResult:
    """The seed 002 path estimates of one recording (nav.evaluation.estimate_paths) and their errors."""

    estimates: dict  # t_s, truth, acc, mask, tridiagonal, recurrence (world frame, m)
    rows: list[dict]  # one per method: max / RMS / final error (m)
    random_walk_m: (
        float  # the t^1.5 law's RMS position error for the sensor's noise (its 0 Hz density) over the span
    )
    offset_drift_m: float  # 0.5 |b| t^2: what the unit's zero-g offset b alone does over the span
    span_s: float
    # the takeoff roll and the rollout rebuilt from the bag's samples (runs.ground_roll), or () when
    # they cannot be (ground_rolls_note says why)
    ground_rolls: tuple[GroundRollCheck, ...] = ()
    ground_rolls_note: str | None = None


@dataclass(frozen=True, slots=True)
class RunResult:
    """What :func:`run` produced: every stage's output (None for a stage not run) and the files written."""

    scenario: Scenario
    seed: int
    track: FlightTrack | None = None
    metrics: dict | None = None
    recording: Recording | None = None
    detection: Evaluation | None = None
    path: PathResult | None = None
    redundant: RedundantEvaluation | None = None  # the redundant rule, when a barometer is fitted
    written: dict[str, Path] = field(default_factory=dict)  # file role -> path ({} when nothing was written)
    wall_s: dict[str, float] = field(default_factory=dict)  # stage -> wall-clock seconds

    @property
    def run_id(self) -> str:
        return f"{self.scenario.name}-s{self.seed}"


# ---------------------------------------------------------------------- resolving inputs
def scenario_of(scenario: Scenario | str | Path) -> Scenario:
    """A Scenario, a built-in name, or the path of a ``.toml`` file."""
    return scenario if isinstance(scenario, Scenario) else Scenario.resolve(scenario)


def streams_of(seed: int) -> Streams:
    """The root random streams of a run."""
    return Streams(seed)


def sensor_preset(sensor: SensorChoice | str | AccelerometerPreset) -> AccelerometerPreset:
    """An accelerometer preset from a scenario's ``[sensor]`` choice, a preset name, or a preset."""
    from flightmode.sim.sensor.accelerometer import AccelerometerPreset, get_preset

    if isinstance(sensor, AccelerometerPreset):
        return sensor
    if isinstance(sensor, str):
        return get_preset(sensor)
    preset = get_preset(sensor.preset)
    if sensor.odr_hz is not None:
        preset = dataclasses.replace(preset, odr_hz=float(sensor.odr_hz))
    return preset


# ---------------------------------------------------------------------- the stages
def fly(
    scenario: Scenario,
    streams: Streams,
    *,
    progress: Callable[[float, str], None] | None = None,
    workdir: Path | None = None,
    stop_after_s: float | None = None,
) -> FlightTrack:
    """Fly the scenario's plan gate to gate in JSBSim (``streams``: the run's flight streams;
    ``stop_after_s``: only the first that many simulated seconds, the exact prefix of the flight), with
    the scenario's ``[model]`` overrides of the uncertain model parameters."""
    from flightmode.sim.flight.simulate import fly as _fly

    return _fly(
        scenario.plan,
        streams,
        workdir=workdir,
        progress=progress,
        stop_after_s=stop_after_s,
        overrides=scenario.overrides,
    )


def baro_preset(sensor: SensorChoice | str | AccelerometerPreset | None):
    """The barometer a ``[sensor]`` choice fits (None: none, or not a SensorChoice)."""
    if not isinstance(sensor, SensorChoice) or sensor.baro is None:
        return None
    from flightmode.sim.sensor.barometer import get_preset, with_odr

    p = get_preset(sensor.baro)
    return p if sensor.baro_odr_hz is None else with_odr(p, sensor.baro_odr_hz)


def sense(
    track: FlightTrack,
    carrier: CarrierSpec,
    sensor: SensorChoice | str | AccelerometerPreset,
    streams: Streams | np.random.Generator | int,
    *,
    gyro: GyroSpec | None = None,
    fitted: SensorChoice | None = None,
    overrides: Mapping[str, float] | None = None,
) -> Recording:
    """What the bag's sensors record of ``track`` (``streams``: the run's sensor streams): the
    accelerometer, and the barometer and gyroscope that the ``[sensor]`` choice fits (``fitted``: take
    them from this choice instead, e.g. the scenario's when ``sensor`` names another accelerometer;
    ``gyro``: this gyroscope instead); ``overrides``: the uncertain model parameters (a scenario's
    ``[model]`` table, :attr:`Scenario.overrides`; None: every one nominal)."""
    from flightmode.sim.sensor.sensing import sense as _sense

    parts = fitted if fitted is not None else sensor if isinstance(sensor, SensorChoice) else None
    if gyro is None and parts is not None and parts.gyro is not None:
        from flightmode.sim.sensor.gyroscope import get_preset

        gyro = get_preset(parts.gyro)
    level = getattr(sensor, "vibration_level", None)
    return _sense(
        track,
        carrier,
        sensor_preset(sensor),
        streams,
        gyro=gyro,
        vibration_level=1.0 if level is None else float(level),
        baro=baro_preset(parts),
        overrides=overrides,
    )


def unit_sigma2(
    preset: str, odr_hz: float, unit: dict | None, window: int, rng: np.random.Generator
) -> np.ndarray:
    """sigma^2 per axis as the tracker's maker calibrates it on the bench (seed 000 section 5.1):
    60 s of the unit (a Recording's ``unit`` dict; None: a perfect one) lying still
    (:func:`~flightmode.sim.sensor.accelerometer.bench_static`), then
    :func:`~flightmode.detector.flight_mode.calibrate_sigma2` with the quantisation floor."""
    from flightmode.detector.flight_mode import calibrate_sigma2
    from flightmode.sim.sensor.accelerometer import UnitDraw, bench_static, get_preset

    p = dataclasses.replace(get_preset(preset), odr_hz=float(odr_hz))
    m = bench_static(p, UnitDraw.from_dict(unit), rng)
    return calibrate_sigma2(m.acc_g, window, p.lsb_g)


SIGMA2_SOURCES = ("preset", "rest")


def _bench_sensor(source: str, info: dict | None) -> dict | None:
    """run.json's sensor summary for ``--sigma2-from preset`` (None for ``rest``); a DetectorError for
    an unknown source, or ``preset`` without the run.json."""
    from flightmode.errors import DetectorError

    if source not in SIGMA2_SOURCES:
        raise DetectorError(
            f"--sigma2-from {source!r}: use one of {', '.join(SIGMA2_SOURCES)}{did_you_mean(source, SIGMA2_SOURCES)}"
        )
    if source == "rest":
        return None
    if info is None:
        raise DetectorError(
            "--sigma2-from preset needs the run.json beside samples.parquet; "
            "use --sigma2-from rest for a bare samples file"
        )
    if not isinstance(info.get("sensor"), dict):
        raise DetectorError(
            "--sigma2-from preset: the run.json beside samples.parquet has no sensor summary (sensor); "
            "fly the run again, or use --sigma2-from rest"
        )
    return info["sensor"]


def stream_rest(source: str, columns: dict, info: dict | None) -> tuple[np.ndarray, np.ndarray | None, str]:
    """A static recording of the unit at the stream's rate for the detectors that calibrate on one
    (seed 001's, :mod:`flightmode.detector.activity.flight`): (acc in g, the gyroscope in deg/s or
    None, where it came from). ``preset``: the same 60 s bench recording as :func:`stream_sigma2`
    (needs run.json); a stream with a gyroscope has it on the bench too: the bench models no
    gyroscope, so its part is what the tracker's gyroscope recorded at rest before the flight (a
    tracker zeroes its gyroscope at rest after power-on), both cut to the shorter; ``rest``: the
    longest run of truly static samples before the flight (with the recording's gyroscope, if it
    has one)."""
    from flightmode.sim.sensor.accelerometer import UnitDraw, bench_static, get_preset

    s = _bench_sensor(source, info)
    gyro = columns.get("gyro_dps")
    if s is not None and info is not None:  # _bench_sensor returns a sensor only from an info
        p = dataclasses.replace(get_preset(s["preset"]), odr_hz=float(s["odr_hz"]))
        m = bench_static(
            p, UnitDraw.from_dict(s.get("unit")), streams_of(int(info["seed"])).rng("detector/bench")
        )
        where = f"bench recording of this {s['preset']} unit (60 s static)"
        if gyro is None:
            return m.acc_g, None, where
        a, b = _rest_before_flight(columns)
        n = min(m.acc_g.shape[0], b - a)
        return m.acc_g[:n], gyro[a : a + n], f"{where}; the gyroscope's {n} samples at rest before the flight"
    a, b = _rest_before_flight(columns)
    return (
        columns["acc_g"][a:b],
        None if gyro is None else gyro[a:b],
        f"{b - a} truly static samples before the flight",
    )


def _rest_before_flight(columns: dict) -> tuple[int, int]:
    """[start, end) of the longest run of truly static samples before the in-flight window."""
    import numpy as np

    from flightmode.detector.evaluation import longest_static_run

    static = np.asarray(columns["sensor_static"], bool).copy()
    window = np.asarray(columns["in_flight_window"], bool)
    if window.any():
        static[int(np.flatnonzero(window)[0]) :] = False  # only what a tracker saw before the flight
    return longest_static_run(static)


def stream_sigma2(source: str, columns: dict, info: dict | None, window: int) -> tuple[np.ndarray, str]:
    """sigma^2 per axis for a samples file and a sentence saying where it came from. ``preset``: the
    bench calibration of the recording's own unit (needs the run.json beside the samples; the same
    stream as the run's own detector); ``rest``: the truly static samples before the flight."""
    from flightmode.detector.recommended import sigma2_from_rest
    from flightmode.errors import DetectorError
    from flightmode.sim.sensor.accelerometer import get_preset

    s = _bench_sensor(source, info)
    if s is not None and info is not None:  # _bench_sensor returns a sensor only from an info
        s2 = unit_sigma2(
            s["preset"],
            float(s["odr_hz"]),
            s.get("unit"),
            window,
            streams_of(int(info["seed"])).rng("detector/bench"),
        )
        return s2, f"bench calibration of this {s['preset']} unit (60 s static, quantisation floor)"
    for name in ("sensor_static", "in_flight_window"):
        if name not in columns:
            raise DetectorError(f"--sigma2-from rest: the samples have no {name} column")
    lsb = get_preset(info["sensor"]["preset"]).lsb_g if info is not None and info.get("sensor") else None
    s2, n = sigma2_from_rest(
        columns["acc_g"], columns["sensor_static"], columns["in_flight_window"], window, lsb
    )
    return s2, f"{n} truly static samples before the flight"


def _labels(recording: Recording) -> dict:
    """The labels a detector is scored against (:mod:`flightmode.detector.evaluation`)."""
    return {
        "in_flight_window": recording.in_flight_window,
        "sensor_static": recording.sensor_static,
        "phase": recording.phase,
    }


def detect(recording: Recording, rng: np.random.Generator) -> Evaluation:
    """Seed 000's recommended detector on the recording, sigma^2 from the bench calibration of its
    unit (``rng``: the run's ``detector/bench`` stream), scored against the truth labels."""
    from flightmode.detector.recommended import evaluate_recommended, recommended_params

    p = recommended_params(recording.odr_hz)
    s2 = unit_sigma2(recording.preset, recording.odr_hz, recording.unit, p.window, rng)
    return evaluate_recommended(recording.t_s, recording.acc_g, _labels(recording), recording.odr_hz, s2)


def pressure_params(scenario: Scenario, baro_odr_hz: float, **changes) -> PressureParams:
    """The pressure detector's parameters for a scenario's barometer: its default thresholds at the
    barometer's rate, the destination's expected ground pressure (the ISA pressure at its elevation)
    known, as a shipment's tracker knows its route; ``changes`` override."""
    from flightmode.detector.pressure import PressureParams
    from flightmode.sim.flight.cabin import ambient_pressure_pa

    e = scenario.plan.destination.elevation_m
    p = PressureParams(fs_hz=float(baro_odr_hz), arrival_ground_pa=float(ambient_pressure_pa(e, datum_m=e)))
    p = dataclasses.replace(p, **changes)
    p.validate()
    return p


def detect_redundant(
    recording: Recording, detection: Evaluation, params: PressureParams
) -> RedundantEvaluation:
    """The redundant rule (:func:`flightmode.detector.pressure.evaluate_redundant`) on a recording with
    a barometer: seed 000's recommended detector (``detection``'s parameters and sigma^2) OR the
    pressure detector (``params``, e.g. :func:`pressure_params`) to suspend, both to resume."""
    from flightmode.detector.pressure import evaluate_redundant

    tb, pb = recording.baro_stream
    return evaluate_redundant(
        recording.t_s, recording.acc_g, tb, pb, _labels(recording), detection.params, detection.sigma2, params
    )


def drift_laws_m(recording: Recording, span_s: float) -> tuple[float, float]:
    """What integrating ``recording``'s unit twice over ``span_s`` costs by the two laws (m): the
    random walk of its noise (RMS, t^1.5; NaN for a noiseless preset) and its zero-g offset b alone,
    0.5 |b| t^2."""
    import math

    import numpy as np

    from flightmode.nav.evaluation import predicted_random_walk_m
    from flightmode.sim.sensor.accelerometer import get_preset, noise_random_walk_sigma_g
    from flightmode.units import G0_MPS2

    # the noise's density at 0 Hz is what integrates into a random walk (white: noise_g at the ODR)
    noise = noise_random_walk_sigma_g(get_preset(recording.preset)) * G0_MPS2
    law = float(predicted_random_walk_m(noise, recording.odr_hz, span_s)) if noise > 0 else math.nan
    offset = float(np.linalg.norm(recording.unit["offset_g"])) * G0_MPS2
    return law, 0.5 * offset * span_s**2


def estimate_path(track: FlightTrack, recording: Recording) -> PathResult:
    """Seed 002's cubic-spline paths of the bag while stowed, from its samples rotated with the truth
    (truth-aided frames), and their errors against the truth, beside the random-walk law's figure;
    and the takeoff roll and the rollout rebuilt from the bag's samples alone
    (:func:`flightmode.runs.ground_roll.ground_rolls`)."""
    from flightmode.errors import NavError
    from flightmode.nav.evaluation import estimate_paths, path_rows
    from flightmode.runs.ground_roll import ground_rolls
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.sensor.carrier import LOCATION_OF

    lever = get_profile(track.aircraft).locations_m[LOCATION_OF[recording.carrier.placement]]
    est = estimate_paths(track, recording, lever)
    span = float(est["t_s"][-1] - est["t_s"][0])
    law, offset_drift = drift_laws_m(recording, span)
    rolls: tuple[GroundRollCheck, ...] = ()
    note = None
    try:
        rolls = ground_rolls(track, recording)
    except NavError as e:  # e.g. no stop beside a roll: the whole-flight rows still stand
        note = str(e)
    return PathResult(est, path_rows(est, recording.preset), law, offset_drift, span, rolls, note)


class RunWriter:
    """Writes one run folder ``out_dir/<run_id>/`` while later stages compute: a hidden staging folder,
    one writer thread running the writes in the order given (pyarrow and Rerun release the GIL while
    they encode), and, once every write has finished, one rename into place. If anything fails (a
    write, or a stage while the writes run), the staging folder is removed and nothing is left
    behind. Use as a context manager."""

    def __init__(self, out_dir: Path, run_id: str):
        self.out_dir, self.run_id = Path(out_dir), run_id
        self.final = self.out_dir / run_id
        self.written: dict[str, Path] = {}
        self._futures: list = []
        self._on_failure: list = []

    def __enter__(self) -> RunWriter:
        from concurrent.futures import ThreadPoolExecutor

        from flightmode.runs import run_io

        self._staging = run_io.staged_run_dir(self.out_dir, self.run_id)
        self.stage = self._staging.__enter__()
        self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="flightmode-writer")
        return self

    def submit(self, role: str, filename: str, fn, *args) -> None:
        """Run ``fn(stage_folder, *args)`` on the writer thread; it writes ``filename``."""
        self._futures.append(self._pool.submit(fn, self.stage, *args))
        self.written[role] = self.final / filename

    def compute(self, fn, *args):
        """Run ``fn(*args)`` on the writer thread, in turn with the writes (hashlib, like pyarrow,
        releases the GIL); returns its Future."""
        f = self._pool.submit(fn, *args)
        self._futures.append(f)
        return f

    def on_failure(self, fn) -> None:
        """Call ``fn()`` if the run fails, before the staging folder is removed (e.g. to close a
        file a write left open for a later task)."""
        self._on_failure.append(fn)

    def wait(self) -> None:
        for f in self._futures:
            f.result()  # re-raises a write's error here

    def __exit__(self, exc_type, exc, tb) -> Literal[False]:  # never swallows an exception
        failure = exc
        if failure is None:
            try:
                self.wait()
            except BaseException as e:  # a failed write: clean up as for any other failure
                failure = e
        self._pool.shutdown(wait=True, cancel_futures=failure is not None)
        if failure is None:
            self._staging.__exit__(None, None, None)  # rename into place
            return False
        for fn in self._on_failure:
            try:
                fn()
            except Exception:  # cleaning up after a failure must not hide the failure
                pass
        self._staging.__exit__(type(failure), failure, failure.__traceback__)  # removes the staging folder
        if exc is None:
            raise failure
        return False


class _Rrd:
    """recording.rrd written in two parts on the writer thread: everything but the 3D paths as soon as
    the detector has run (Rerun encodes it in its own threads while the paths are estimated), then
    the paths, and the rename."""

    def __init__(self, writer: RunWriter):
        self.w: RrdWriter | None = None
        writer.on_failure(self.abort)

    def open(self, stage: Path, result: RunResult) -> None:
        from flightmode.runs.run_view import run_view
        from flightmode.viz.rrd import RrdWriter

        self.w = RrdWriter(stage / "recording.rrd", result.run_id)
        self.w.send(
            run_view(
                result.run_id, result.scenario.plan, result.track, result.recording, result.detection, None
            )
        )

    def close(self, stage: Path, result: RunResult) -> None:
        from flightmode.runs.run_view import path_lines

        if self.w is None:  # never: open ran before on the same writer thread (its failure fails the run)
            raise FlightmodeError("recording.rrd: its paths were to be written before it was opened")
        if result.path is not None and result.recording is not None:  # a path is estimated from a recording
            self.w.send_paths(path_lines(result.path.estimates, result.recording.odr_hz))
        self.w.close()

    def abort(self) -> None:
        if self.w is not None:
            self.w.abort()


def _track_digest(writer: RunWriter, track: FlightTrack):
    """The track's SHA-256 for run.json, computed on the writer thread as soon as the track exists
    (0.6-0.7 s for a 1.5 h flight's 250 MB, beside the later stages instead of after them)."""
    return writer.compute(track.digest)


def _write_run_json(stage: Path, result: RunResult, track_sha256) -> Path:
    from flightmode.runs import run_io

    sha = None if track_sha256 is None else track_sha256.result()
    return run_io.write_run_json(stage, run_io.run_info(result, track_sha256=sha))


def _finish(writer: RunWriter, result: RunResult, rrd: _Rrd | None, track_sha256) -> None:
    """Queue what needs every stage: the rest of recording.rrd, then run.json (a run folder's last
    file; ``track_sha256``: :func:`_track_digest`'s Future, queued before it on the same thread, or
    None to compute it there)."""
    if rrd is not None:
        writer.submit("rrd", "recording.rrd", rrd.close, result)
    writer.submit("run_json", "run.json", _write_run_json, result, track_sha256)


def _rrd_after_detect(writer: RunWriter, result: RunResult, rrd: bool) -> _Rrd | None:
    if not (
        rrd and result.track is not None and result.recording is not None and result.detection is not None
    ):
        return None
    r = _Rrd(writer)
    writer.submit("rrd", "recording.rrd", r.open, result)
    return r


def write(out_dir: Path, result: RunResult, *, rrd: bool = True) -> dict[str, Path]:
    """Write the run folder ``out_dir/<run_id>/`` (truth.parquet, samples.parquet, run.json and, with
    ``rrd``, recording.rrd) atomically (:class:`RunWriter`). Returns {role: path}."""
    from flightmode.runs import run_io

    with RunWriter(out_dir, result.run_id) as w:
        sha = None
        if result.track is not None:
            w.submit("truth", "truth.parquet", run_io.write_truth, result.track)
            sha = _track_digest(w, result.track)
        if result.recording is not None:
            w.submit("samples", "samples.parquet", run_io.write_samples, result.recording)
        _finish(w, result, _rrd_after_detect(w, result, rrd), sha)
    return w.written


# ---------------------------------------------------------------------- the chain
def run(
    scenario: Scenario | str | Path,
    *,
    seed: int | None = None,
    sensor: SensorChoice | str | AccelerometerPreset | None = None,
    out: str | Path | None = None,
    stages: Sequence[str] = STAGES,
    gyro: bool | GyroSpec = False,
    rrd: bool = True,
    progress: Callable[[float, str], None] | None = None,
    on_stage: Callable[[str], None] | None = None,
    track: FlightTrack | None = None,
) -> RunResult:
    """Run the pipeline on a scenario (a :class:`Scenario`, a built-in name or a ``.toml`` path).

    ``seed``: the run's seed (default: the scenario's own); ``sensor``: an accelerometer preset name,
    a :class:`SensorChoice` or an ``AccelerometerPreset`` instead of the scenario's; ``out``: where
    to write the run folder (nothing is written when None); ``stages``: which of fly, sense, detect,
    path, write to run (each needs the ones before it, but ``path`` is optional for ``write``);
    ``gyro``: also record a gyroscope (True: the BMI270 preset, or a ``GyroSpec``; the scenario's
    ``[sensor].gyro`` fits one too); ``rrd``: write recording.rrd too;
    ``progress(t_s, phase)``: called about once per simulated minute while flying; ``on_stage(name)``:
    called as each stage starts; ``track``: the scenario's flight flown before (by :func:`fly` with
    this run's ``flight`` streams), to skip flying it again.
    """
    from flightmode.runs import run_io
    from flightmode.sim.flight.flight_metrics import flight_metrics
    from flightmode.sim.sensor.gyroscope import GyroSpec, get_preset

    sc = scenario_of(scenario)
    if seed is not None:
        sc = sc.replace(seed=seed)
    stages = tuple(stages)
    for s in stages:
        if s not in STAGES:
            raise FlightmodeError(
                f"unknown pipeline stage '{s}'{did_you_mean(s, STAGES)}; stages: {', '.join(STAGES)}"
            )
    needs = {"sense": ("fly",), "detect": ("fly", "sense"), "path": ("fly", "sense"), "write": ("fly",)}
    for s in stages:
        missing = [n for n in needs.get(s, ()) if n not in stages]
        if missing:
            raise FlightmodeError(f"pipeline stage '{s}' needs {', '.join(missing)}: add it to stages")
    root = streams_of(sc.seed)
    wall: dict[str, float] = {}
    tell = on_stage or (lambda name: None)
    with contextlib.ExitStack() as stack:
        # files are written by a background thread as soon as their data exist (a run folder appears
        # whole, or not at all: RunWriter)
        writer = (
            stack.enter_context(RunWriter(Path(out), sc.run_id))
            if "write" in stages and out is not None
            else None
        )
        tell("fly")
        t0 = time.perf_counter()
        if track is None:
            track = fly(sc, root.child("flight"), progress=progress)
        elif track.aircraft != sc.aircraft or track.fs_hz != sc.plan.fdm_hz:
            raise FlightmodeError(
                f"the track given is a {track.aircraft} at {track.fs_hz:g} Hz, not this scenario's "
                f"flight ({sc.aircraft} at {sc.plan.fdm_hz} Hz)"
            )
        metrics = flight_metrics(track, sc.plan)
        wall["fly"] = time.perf_counter() - t0
        if writer is not None:
            writer.submit("truth", "truth.parquet", run_io.write_truth, track)
            track_sha = _track_digest(writer, track)
        rec = det = path = rrd_part = red = None
        if "sense" in stages:
            tell("sense")
            t0 = time.perf_counter()
            g = gyro if isinstance(gyro, GyroSpec) else (get_preset("bmi270") if gyro else None)
            choice = sc.sensor if sensor is None else sensor
            # another accelerometer given by name or preset: the scenario's barometer and gyroscope stay fitted
            rec = sense(
                track,
                sc.carrier,
                choice,
                root.child("sensor"),
                gyro=g,
                fitted=None if isinstance(choice, SensorChoice) else sc.sensor,
                overrides=sc.overrides,
            )
            wall["sense"] = time.perf_counter() - t0
            if writer is not None:
                writer.submit("samples", "samples.parquet", run_io.write_samples, rec)
        if "detect" in stages and rec is not None:  # rec is set: detect needs sense (checked above)
            tell("detect")
            t0 = time.perf_counter()
            det = detect(rec, root.rng("detector/bench"))
            red = (
                detect_redundant(rec, det, pressure_params(sc, rec.baro["odr_hz"]))
                if rec.baro is not None and rec.baro_pa is not None  # a barometer's stream and its fit
                else None
            )
            wall["detect"] = time.perf_counter() - t0
            if writer is not None:
                partial = RunResult(sc, sc.seed, track, metrics, rec, det, None, red, {}, wall)
                rrd_part = _rrd_after_detect(writer, partial, rrd)
        if "path" in stages:
            tell("path")
            t0 = time.perf_counter()
            assert rec is not None  # path needs sense (checked above)
            path = estimate_path(track, rec)
            wall["path"] = time.perf_counter() - t0
        result = RunResult(sc, sc.seed, track, metrics, rec, det, path, red, {}, wall)
        if writer is not None:
            tell("write")
            t0 = time.perf_counter()
            _finish(writer, result, rrd_part, track_sha)
            writer.wait()
            wall["write"] = time.perf_counter() - t0  # what was left to write after the last stage
    if writer is not None:
        result = dataclasses.replace(result, written=writer.written, wall_s=wall)
    return result


__all__ = [
    "run",
    "fly",
    "sense",
    "detect",
    "detect_redundant",
    "pressure_params",
    "baro_preset",
    "estimate_path",
    "drift_laws_m",
    "write",
    "RunWriter",
    "RunResult",
    "PathResult",
    "STAGES",
    "unit_sigma2",
    "stream_sigma2",
    "sensor_preset",
    "scenario_of",
    "streams_of",
]
