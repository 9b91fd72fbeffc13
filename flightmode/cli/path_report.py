"""Path-estimator figures for the command line (``flightmode path``, and the summary line of
``flightmode fly``): nav.evaluation rows as a Rich table."""

from __future__ import annotations

from rich.console import Console
from rich.table import Table

from flightmode.nav.evaluation import evaluate


def lever_arm_m(track, carrier) -> tuple[float, float, float]:
    from flightmode.sim.flight.aircraft_profiles import get_profile
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
    return evaluate(track, recordings, lever_arm_m(track, carrier), checks_of(streams))


def _m(x: float) -> str:
    return f"{x:,.2f}" if x < 10 else f"{x:,.0f}"


def print_rows(console: Console, rows: list[dict], title: str) -> None:
    t = Table(title=title)
    for c in ("acceleration", "method", "max error (m)", "RMS (m)", "final (m)"):
        t.add_column(c, justify="right" if "(m)" in c else "left")
    for r in rows:
        t.add_row(r["source"], r["method"], _m(r["max_m"]), _m(r["rms_m"]), _m(r["final_m"]))
    console.print(t)
