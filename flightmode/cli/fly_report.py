"""What ``flightmode fly`` and ``flightmode sense`` print (printing only): the progress bar, the
flight's summary table, the sensor and detector lines, the ground rolls rebuilt from the bag's samples."""

from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path

from rich import box
from rich.table import Table
from rich.text import Text

from flightmode.cli.common import console


def _estimate_duration_s(plan) -> float:
    """Rough gate-to-gate duration, only for the progress bar's scale."""
    from flightmode.scenarios.spec import route_length_m

    ground = plan.gate_wait_s + 120.0 + plan.taxi_out.length_m / 8.0 + sum(plan.taxi_out.holds_s)
    ground += plan.taxi_out.lineup_hold_s + plan.taxi_in.length_m / 8.0 + sum(plan.taxi_in.holds_s)
    return ground + route_length_m(plan) / 190.0 + 300.0 + plan.post_shutdown_s


@contextmanager
def progress_bar(plan):
    """Yields (on_progress, on_stage, done) for :func:`flightmode.runs.pipeline.run` and its end."""
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    total = _estimate_duration_s(plan)
    with Progress(
        TextColumn("[progress.description]{task.description}"),
        BarColumn(),
        TextColumn("{task.fields[sim]}"),
        TimeElapsedColumn(),
        console=console(),
        transient=False,
    ) as progress:
        task = progress.add_task("flying", total=total, sim="")

        def on_progress(t_s: float, phase: str) -> None:
            progress.update(
                task,
                completed=min(t_s, total * 0.99),
                description=f"{phase:>13}",
                sim=f"{t_s / 60:6.1f} sim-min",
            )

        def on_stage(stage: str) -> None:
            if stage != "fly":
                progress.update(task, completed=total, description=f"{stage:>13}")

        def done(duration_s: float) -> None:
            progress.update(task, completed=total, description="done", sim=f"{duration_s / 60:6.1f} sim-min")

        yield on_progress, on_stage, done


def print_fly(result, out: Path) -> None:
    print_summary(result.scenario.plan, result)
    print_sensor(result.recording)
    print_detector_line(result.detection)
    if result.redundant is not None:
        r = result.redundant
        console().print(
            f"with the barometer ({result.recording.baro['preset']}): accelerometer OR pressure to suspend, "
            f"AND to resume: {r.combined.false_static_count} false-static events in flight (accelerometer "
            f"alone {r.accel.false_static_count}); response after the flight "
            f"{'never came back' if r.combined.response_s is None else f'{r.combined.response_s:.1f} s'}",
            highlight=False,
        )
    rid = Path(out) / result.run_id
    print_ground_rolls(result.path, rid)
    files = ", ".join(p.name for p in result.written.values())
    console().print(Text.assemble("wrote ", (str(rid), "bold"), f" ({files})"), highlight=False)
    if "rrd" in result.written:
        where = result.written["rrd"]
        console().print(
            Text.assemble(
                "recording: ", (str(where), "bold"), "; open it with: ", (f"flightmode view {where}", "bold")
            ),
            highlight=False,
        )


def print_ground_rolls(path, run_dir: Path) -> None:
    """The takeoff roll and the rollout rebuilt from the bag's samples against the truth
    (:func:`flightmode.runs.ground_roll.ground_rolls`); the whole-flight drift is ``flightmode path``'s."""
    if path is None:
        return
    if not path.ground_rolls:
        console().print(f"ground rolls not rebuilt: {path.ground_rolls_note}", highlight=False)
    else:
        t = Table(
            title="ground rolls rebuilt from the bag's samples alone (seed 002 splines): "
            "lengths in m, speeds in m/s",
            box=box.SIMPLE,
        )
        for h in ("", "length", "true", "error", "%", "speed", "true", "error"):
            t.add_column(h, justify="left" if not h else "right", no_wrap=True)
        for c in path.ground_rolls:
            t.add_row(
                c.segment,
                f"{c.est_length_m:,.0f}",
                f"{c.true_length_m:,.0f}",
                f"{c.length_error_m:+,.0f}",
                f"{c.length_error_pct:+.1f}",
                f"{c.est_speed_mps:.1f}",
                f"{c.true_speed_mps:.1f}",
                f"{c.speed_error_mps:+.1f}",
            )
        console().print(t)
        console().print(
            "  offset and tilt from the bag at the stop beside each roll; speed at liftoff (takeoff roll, "
            "integrated from rest at brake release) and at touchdown (rollout, integrated backwards from "
            f"the truth's exit speed {path.ground_rolls[1].known_speed_mps:.1f} m/s)",
            highlight=False,
        )
    console().print(
        Text.assemble(
            "whole-flight dead reckoning drifts by kilometres (a MEMS offset integrated twice): ",
            (f"flightmode path {run_dir}", "bold"),
        ),
        highlight=False,
    )


def print_detector_line(e) -> None:
    resp = "never came back" if e.response_s is None else f"{e.response_s:.1f} s"
    style = "bold red" if e.false_static_count else "bold green"
    console().print(
        Text.assemble(
            "detector (NMV, 1 s, 4 sigma^2, 4 s): ",
            (f"{e.false_static_count} false-static events in flight", style),
            f" ({e.false_static_s:g} s); response after the flight {resp}; accuracy {e.accuracy:.3f}",
        ),
        highlight=False,
    )


def print_sensor(rec) -> None:
    s = rec.summary()
    console().print(
        f"sensed with {s['preset']} at {s['odr_hz']:g} Hz: {s['samples']:,} samples over "
        f"{s['duration_s'] / 60:.1f} min ({rec.carrier.kind}, {rec.carrier.placement}); "
        f"truly static {100 * s['static_fraction']:.0f} % of the time, {s['clipped_samples']} clipped samples",
        highlight=False,
    )


def print_summary(plan, result) -> None:
    from flightmode.units import FT_M, KT_MPS

    track, m, wall_s = result.track, result.metrics, result.wall_s["fly"]
    kt = 1.0 / KT_MPS
    t = Table(
        title=f"{plan.name}: {plan.aircraft}, {plan.origin.icao} {plan.origin.name} -> "
        f"{plan.destination.icao} {plan.destination.name}",
        show_header=False,
    )
    t.add_column("quantity")
    t.add_column("value", justify="right")
    rows = [
        (
            "gate to gate",
            f"{m['gate_to_gate_s'] / 60:.1f} min  ({track.n:,} samples at {track.fs_hz:.0f} Hz)",
        ),
        ("taxi-out (pushback to brake release)", f"{m['taxi_out_s'] / 60:.1f} min"),
        ("liftoff speed", f"{m['liftoff_ias_mps'] * kt:.0f} kt IAS"),
        ("mean takeoff acceleration", f"{m['takeoff_accel_mps2']:.2f} m/s^2"),
        ("initial climb rate (to 1500 ft)", f"{m['initial_climb_vs_mps']:.1f} m/s"),
        ("cruise altitude", f"{m['cruise_alt_m']:.0f} m"),
        ("final approach vertical rate", f"{m['final_approach_vs_mps']:.2f} m/s"),
        ("touchdown sink rate", f"{m['touchdown_sink_mps'] / FT_M * 60:.0f} ft/min"),
        (
            "touchdown speed",
            f"{m['touchdown_ias_mps'] * kt:.0f} kt IAS, {m['touchdown_gs_mps']:.1f} m/s ground",
        ),
        (
            "touchdown point",
            f"{m['touchdown_past_threshold_m']:.0f} m past threshold, "
            f"{m['touchdown_centreline_offset_m']:+.1f} m from centreline",
        ),
        ("rollout deceleration", f"{m['rollout_decel_mps2']:.2f} m/s^2 over {m['rollout_distance_m']:.0f} m"),
        ("taxi-in", f"{m['taxi_in_s'] / 60:.1f} min"),
        (
            "in-flight window (pushback to engines off)",
            f"{track.in_flight_window.sum() / track.fs_hz / 60:.1f} min",
        ),
        ("wall time", f"{wall_s:.1f} s ({track.duration_s / wall_s:.0f}x real time)"),
    ]
    for k, v in rows:
        t.add_row(k, v)
    console().print(t)
