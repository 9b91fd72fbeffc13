"""The path estimators' error table of one run (``flightmode path``): the run's flight re-sensed
with the run's own streams for each requested preset, then :func:`flightmode.nav.evaluation.evaluate`
with the bag's lever arm and the recommended detector's static periods (ZUPT, tilt-only)."""

from __future__ import annotations

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


def path_table(run_dir: str | Path, sensors: tuple[str, ...] = ("run", "ideal")) -> tuple[list[dict], str]:
    """(rows, run id) of ``flightmode path``: ``sensors`` are accelerometer presets, ``run`` the run's
    own (re-sensing with the run's own streams gives its samples again, to one count, with the
    carrier timeline the truth-aided frames need)."""
    from flightmode.runs import pipeline, run_io

    track, info = run_io.read_track(Path(run_dir))
    sc = run_io.run_scenario(info, str(run_dir))
    run_preset = (info.get("sensor") or {}).get("preset") or sc.sensor.preset
    streams = pipeline.streams_of(int(info["seed"]))
    recs = {}
    for name in sensors:
        preset = run_preset if name == "run" else name
        if preset not in recs:
            recs[preset] = pipeline.sense(track, sc.carrier, preset, streams.child("sensor"))
    return path_rows(track, recs, sc.carrier, streams), info["run_id"]


__all__ = ["checks_of", "lever_arm_m", "path_rows", "path_table"]
