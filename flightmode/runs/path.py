"""The path estimators' error table of one run (``flightmode path``): the run's flight re-sensed
with the run's own streams for each requested preset, then :func:`flightmode.nav.evaluation.evaluate`
with the bag's lever arm and the recommended detector's static periods (ZUPT, tilt-only)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path


def lever_arm_m(track, carrier) -> tuple[float, float, float]:
    """The bag's position in the body frame (m): its placement's location on the aircraft type."""
    from flightmode.sim.flight.aircraft.registry import get_profile
    from flightmode.sim.sensor.carrier import LOCATION_OF

    return get_profile(track.aircraft).locations_m[LOCATION_OF[carrier.placement]]


def checks_of(streams):
    """The seed's recommended detector on a recording (for ZUPT and tilt-only static periods), sigma^2
    from the bench calibration of its unit on the run's own ``detector/bench`` stream (so the run's
    own sensor gets exactly the detector ``flightmode fly`` ran)."""
    from flightmode.detector.flight_mode import detect
    from flightmode.detector.recommended import recommended_params
    from flightmode.runs.pipeline import unit_sigma2

    def run(rec):
        p = recommended_params(rec.odr_hz)
        s2 = unit_sigma2(rec.preset, rec.odr_hz, rec.unit, p.window, streams.rng("detector/bench"))
        return detect(rec.t_s, rec.acc_g, p, s2), p.window

    return run


def path_rows(track, recordings: dict, carrier, streams) -> list[dict]:
    """nav.evaluation rows for ``recordings`` ({label: Recording}) of one run (``streams``: the run's)."""
    from flightmode.nav.evaluation import evaluate

    return evaluate(track, recordings, lever_arm_m(track, carrier), checks_of(streams))


@dataclass(frozen=True, slots=True)
class WholeFlightDrift:
    """The whole-flight path of the run's own sensor over the span the bag is stowed, and the two laws
    that explain its drift (``flightmode path``'s paragraph)."""

    preset: str
    span_s: float
    aided_max_m: float  # tridiagonal, pinned to both gate positions: max error
    unaided_final_m: float  # recurrence from the gate at rest: final error
    random_walk_m: float  # the noise's random walk (RMS) over the span, t^1.5
    offset_drift_m: float  # 0.5 |b| t^2 for the unit's zero-g offset b
    offset_g: float  # |b|, g
    source: str  # "run.json" (what `flightmode fly` computed) or "re-sensed"


@dataclass(frozen=True, slots=True)
class PathReport:
    """What ``flightmode path`` prints: the rows of every requested sensor and the drift paragraph's figures."""

    run_id: str
    rows: list[dict]
    drift: WholeFlightDrift


def _drift(info: dict, preset: str, track, rec, rows: list[dict]) -> WholeFlightDrift:
    """From run.json's own figures when it holds them (what `flightmode fly` computed, from the truth
    at full precision), else from the re-sensed rows of the run's preset and the laws for its
    recording over the same span."""
    import math

    unit = rec.unit if rec is not None else info["sensor"]["unit"]
    offset_g = math.sqrt(sum(x * x for x in unit["offset_g"]))
    if "path" in info and "path_laws_m" in info:
        by = {r["method"].split(" ")[0]: r for r in info["path"]}
        laws = info["path_laws_m"]
        rw, od, span_s, source = laws["random_walk"], laws["offset"], laws["span_s"], "run.json"
    else:
        from flightmode.nav.evaluation import span
        from flightmode.runs.pipeline import drift_laws_m

        by = {r["method"].split(" ")[0]: r for r in rows if r["source"] == f"{preset}, truth-aided"}
        t0, t1 = span(rec, track)
        t = rec.t_s[(rec.t_s >= t0) & (rec.t_s <= t1)]
        span_s = float(t[-1] - t[0])
        rw, od = drift_laws_m(rec, span_s)
        source = "re-sensed"
    return WholeFlightDrift(
        preset=preset,
        span_s=float(span_s),
        aided_max_m=float(by["tridiagonal"]["max_m"]),
        unaided_final_m=float(by["recurrence"]["final_m"]),
        random_walk_m=float(rw),
        offset_drift_m=float(od),
        offset_g=offset_g,
        source=source,
    )


def path_report(run_dir: str | Path, sensors: tuple[str, ...] = ("run", "ideal")) -> PathReport:
    """``flightmode path``: the rows of :func:`path_rows` for ``sensors`` (accelerometer presets, ``run``
    the run's own: re-sensing with the run's own streams gives its samples again, to one count, with
    the carrier timeline the truth-aided frames need) and the whole-flight drift of the run's own
    sensor (:class:`WholeFlightDrift`; the run's own is sensed for it when ``sensors`` lacks it)."""
    from flightmode.runs import pipeline, run_io

    track, info = run_io.read_track(Path(run_dir))
    sc = run_io.run_scenario(info, str(run_dir))
    run_preset = (info.get("sensor") or {}).get("preset") or sc.sensor.preset
    streams = pipeline.streams_of(int(info["seed"]))
    recs = {}
    for name in sensors:
        preset = run_preset if name == "run" else name
        if preset not in recs:
            recs[preset] = pipeline.sense(
                track, sc.carrier, preset, streams.child("sensor"), overrides=sc.overrides
            )
    rows = path_rows(track, recs, sc.carrier, streams)
    own = recs.get(run_preset)
    own_rows = rows
    if own is None and not ("path" in info and "path_laws_m" in info and "sensor" in info):
        # the drift paragraph is about the run's own sensor: sensed for it when run.json lacks it
        own = pipeline.sense(track, sc.carrier, run_preset, streams.child("sensor"), overrides=sc.overrides)
        own_rows = path_rows(track, {run_preset: own}, sc.carrier, streams)
    return PathReport(info["run_id"], rows, _drift(info, run_preset, track, own, own_rows))


def path_table(run_dir: str | Path, sensors: tuple[str, ...] = ("run", "ideal")) -> tuple[list[dict], str]:
    """(rows, run id) of :func:`path_report`."""
    r = path_report(run_dir, sensors)
    return r.rows, r.run_id


__all__ = [
    "PathReport",
    "WholeFlightDrift",
    "checks_of",
    "lever_arm_m",
    "path_report",
    "path_rows",
    "path_table",
]
