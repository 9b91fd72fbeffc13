"""Re-sense a flown run with another sensor or carrier into a new run folder beside it: the run's
own truth, its own sensor streams (the same preset and carrier give its samples.parquet again:
labels exactly, counts to one step, truth.parquet storing the forces in float32), and a run.json
rewritten for the new recording (its scenario, sensor summary and truth path; the old recording's
detector and path figures dropped)."""

from __future__ import annotations

import time
from pathlib import Path

from flightmode.errors import ScenarioError, did_you_mean


def carrier_changes(items: list[str] | tuple[str, ...]) -> dict:
    """``KEY=VALUE`` carrier settings (e.g. ``placement=hold``), each value typed as the scenario spec
    declares its key; a ScenarioError naming a bad item and the nearest key."""
    from flightmode.scenarios.spec import SPEC

    keys = SPEC["carrier"]
    out: dict = {}
    for item in items:
        if "=" not in item:
            raise ScenarioError(f"--carrier {item!r}: write KEY=VALUE, e.g. placement=hold")
        k, v = item.split("=", 1)
        if k not in keys:
            raise ScenarioError(
                f"--carrier {k}: unknown carrier key{did_you_mean(k, keys)}; keys: {', '.join(keys)}"
            )
        want = keys[k].type
        if want is str:
            out[k] = v
            continue
        try:
            out[k] = int(v) if want is int else float(v)
        except ValueError:
            raise ScenarioError(
                f"--carrier {k}={v!r}: must be {'an integer' if want is int else 'a number'} ({keys[k].doc})"
            ) from None
    return out


def resense_run(
    run_dir: str | Path,
    *,
    sensor: str | None = None,
    carrier: dict | None = None,
    out: str | Path | None = None,
    gyro: bool = False,
):
    """Sense the flight of ``run_dir`` again (``sensor``: another accelerometer preset; ``carrier``:
    carrier changes, validated as strictly as a scenario file; ``gyro``: add a BMI270 gyroscope) and
    write ``OUT/<run_id>-<preset>[-key-value...]/`` (samples.parquet, run.json; ``out`` defaults to
    the run's parent folder). Returns (the Recording, the new run folder)."""
    from flightmode.runs import pipeline, run_io
    from flightmode.sim.sensor.gyroscope import get_preset as gyro_preset

    track, info = run_io.read_track(Path(run_dir))
    sc = run_io.run_scenario(info, str(run_dir))
    changes = dict(carrier or {})
    if changes:
        sc = sc.replace(carrier=changes)
    if sensor is not None:
        sc = sc.replace(sensor={"preset": sensor, "odr_hz": None})
    t0 = time.perf_counter()
    rec = pipeline.sense(
        track,
        sc.carrier,
        sc.sensor,
        pipeline.streams_of(sc.seed).child("sensor"),
        gyro=gyro_preset("bmi270") if gyro else None,
        overrides=sc.overrides,
    )
    wall = time.perf_counter() - t0
    tag = "-".join([rec.preset] + [f"{k}-{v}" for k, v in sorted(changes.items())])
    rid = f"{info['run_id']}-{tag}"
    folder = Path(out) if out is not None else Path(run_dir).parent
    with run_io.staged_run_dir(folder, rid) as stage:
        run_io.write_samples(stage, rec)
        new = dict(info)
        new["run_id"] = rid
        new["scenario_toml"] = sc.to_toml()
        new["scenario_sha256"] = sc.digest()
        new["truth"] = dict(info["truth"], path=str(Path(run_dir).resolve() / "truth.parquet"))
        new["sensor"] = rec.summary()
        new["wall_time_s"] = {"sense": wall}
        # of the other recording
        for stale in ("detector", "path", "path_laws_m", "ground_rolls", "ground_rolls_note"):
            new.pop(stale, None)
        run_io.write_run_json(stage, new)
    return rec, folder / rid


__all__ = ["carrier_changes", "resense_run"]
