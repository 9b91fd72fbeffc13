"""Path-estimator figures for the command line (``flightmode path``), printing only: the rows of
:func:`flightmode.runs.path.path_report` as a Rich table, and the paragraph on the whole-flight drift."""

from __future__ import annotations

from rich.console import Console
from rich.table import Table


def _m(x: float) -> str:
    return f"{x:,.2f}" if x < 10 else f"{x:,.0f}"


def print_rows(console: Console, rows: list[dict], title: str) -> None:
    t = Table(title=title)
    for c in ("acceleration", "method", "max error (m)", "RMS (m)", "final (m)"):
        t.add_column(c, justify="right" if "(m)" in c else "left")
    for r in rows:
        t.add_row(r["source"], r["method"], _m(r["max_m"]), _m(r["rms_m"]), _m(r["final_m"]))
    console.print(t)


def print_drift(console: Console, d) -> None:
    """Why the whole-flight path drifts (a :class:`flightmode.runs.path.WholeFlightDrift`): the
    run's own figures, aided first, then the two laws of double integration."""
    where = (
        "figures from run.json, as `flightmode fly` computed them" if d.source == "run.json" else "re-sensed"
    )
    mins = d.span_s / 60
    console.print(
        f"Whole flight, the run's own sensor ({d.preset}; {where}), over the {mins:.0f} min the bag is "
        f"stowed: aided by the two gate positions (tridiagonal), max error {d.aided_max_m:,.0f} m; unaided "
        f"dead reckoning from the gate at rest (recurrence), final error {d.unaided_final_m:,.0f} m.",
        highlight=False,
    )
    console.print(
        "Why it grows: position is acceleration integrated twice, so every error of the sensor grows "
        f"with time. White noise integrates to a random walk, t^1.5 (this sensor's alone: "
        f"{d.random_walk_m:,.0f} m RMS after {mins:.0f} min); a constant offset b to 0.5 b t^2 (this "
        f"unit's zero-g offset, {1e3 * d.offset_g:.0f} mg, alone: {d.offset_drift_m:,.0f} m). Seed 002's "
        "cubic-spline method (Revesz 2014) assumes each sample is the object's true acceleration in a "
        "fixed frame (f''(t_i) = 2 c_i, each axis on its own): it integrates exactly what it is given, "
        "and only its boundary conditions bound the path (the tridiagonal form pins both ends, the "
        "recurrence only the start); its conclusion says inertial navigation 'relies heavily on the "
        "accuracy of accelerometers'. A MEMS unit's offset is tens of mg and unknown in flight, so over "
        "hours nothing but outside information bounds the drift: the gate positions, zero-velocity "
        "updates at the detector's statics (ZUPT), or a short segment beside a stop, where the offset is "
        "measured (the takeoff roll and the rollout in `flightmode fly`).",
        highlight=False,
    )
