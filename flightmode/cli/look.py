"""``flightmode view``, ``flightmode path`` and ``flightmode cabin``: looking at one run."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer
from rich.table import Table
from rich.text import Text

from flightmode.cli.common import JSON_HELP, comma_list, console, emit_json
from flightmode.errors import FlightmodeError, ScenarioError

CABIN_PNG = "cabin.png"  # what `flightmode cabin --out DIR` writes into DIR


def view_cmd(
    source: Annotated[Path, typer.Argument(help="A run folder (its recording.rrd) or an .rrd file.")],
    web: Annotated[
        bool, typer.Option("--web", help="Serve the web viewer on 127.0.0.1 and print its URL.")
    ] = False,
    port: Annotated[
        int | None, typer.Option("--port", help="Web viewer HTTP port (default: a free one).")
    ] = None,
) -> None:
    """Open a run's recording in the Rerun viewer (native, or the web viewer on 127.0.0.1).

    The recording holds the truth, the samples, the labels and the detector's decisions on one
    timeline."""
    import subprocess

    from flightmode.viz import viewer

    rrd = viewer.resolve_rrd(source)
    if web:
        cmd, url = viewer.web_command(rrd, port or viewer.free_port(), viewer.free_port())
        console().print(Text.assemble("web viewer (127.0.0.1 only): ", (url, "bold")), highlight=False)
        console().print(
            "Ctrl-C stops it. Rerun's viewer sends anonymous usage analytics unless you run "
            "`rerun analytics disable`.",
            highlight=False,
        )
    else:
        cmd = viewer.native_command(rrd)
    proc = subprocess.Popen(cmd)
    try:
        code = proc.wait()
    except KeyboardInterrupt:
        proc.terminate()
        proc.wait(timeout=10)
        return
    if code not in (0, -2, -15, 130):
        raise FlightmodeError(f"the Rerun viewer exited with status {code} ({' '.join(cmd)})")


def path_cmd(
    run_dir: Annotated[Path, typer.Argument(help="A run folder written by `flightmode fly`.")],
    sensor: Annotated[
        str,
        typer.Option(
            "--sensor",
            help="Accelerometer presets to re-sense the flight with, a comma list; run: the run's own.",
        ),
    ] = "run,ideal",
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """Rebuild the bag's path from acceleration (the cubic-spline paper) and print its errors.

    Each row integrates twice over the whole time the bag is stowed: noise drifts as t^1.5 and a
    constant offset b as b t^2 / 2, so unaided dead reckoning from a real unit ends kilometres off;
    the tridiagonal spline, pinned to both gates, and ZUPT at the detector's statics bound it. A
    paragraph after the table explains the drift with the run's own figures."""
    from flightmode.cli.path_report import print_drift, print_rows
    from flightmode.runs.path import path_report

    r = path_report(run_dir, comma_list(sensor, "--sensor") or ("run",))
    if as_json:
        emit_json(r.rows)
        return
    print_rows(console(), r.rows, f"{r.run_id}: path errors against the truth (bag seat position)")
    print_drift(console(), r.drift)


def cabin_cmd(
    run_dir: Annotated[Path, typer.Argument(help="A run folder written by `flightmode fly`.")],
    out: Annotated[
        Path | None,
        typer.Option("--out", help=f"Also draw the cabin beside the aircraft altitude: OUT/{CABIN_PNG}."),
    ] = None,
    as_json: Annotated[bool, typer.Option("--json", help=JSON_HELP)] = False,
) -> None:
    """Print a flight's cabin pressure beside its type's pressurisation schedule.

    Cruise cabin altitude and pressure, cabin climb and descent rates, and the differential; then the
    last 5 minutes before touchdown and the first 2 after it: when the cabin reached its landing
    pressure, the residual overpressure at touchdown, and the pressure step of the vent, beside the
    type's pressure-controller description."""
    from flightmode.runs import run_io
    from flightmode.sim.flight.cabin import (
        LANDING_LEVEL_HEIGHT,
        LANDING_RESIDUAL,
        UNCERTAIN,
        cabin_figures,
        get_cabin_profile,
    )
    from flightmode.sim.flight.cabin_landing import AFTER_S, BEFORE_S, VENT_ANCHORS, landing_figures

    track, info = run_io.read_track(run_dir)
    if track.cabin_pressure_pa is None:
        raise ScenarioError(
            f"{run_dir}: truth.parquet has no cabin pressure (written by an older flightmode); fly the scenario again"
        )
    f = cabin_figures(
        track.t_s,
        track.alt_m,
        track.cabin_altitude_m,
        track.cabin_pressure_pa,
        track.ambient_pressure_pa,
        track.phase_code,
    )
    land = landing_figures(
        track.t_s, track.alt_m, track.cabin_pressure_pa, track.ambient_pressure_pa, track.phase_code
    )
    anchor = VENT_ANCHORS.get(track.aircraft)
    from flightmode.uncertain import value_of

    overrides = run_io.run_scenario(info, str(Path(run_dir) / "run.json")).overrides
    run_values = {p.name: value_of(p, overrides) for p in UNCERTAIN}  # the run's, beside the ranges
    anchors = {
        "run_values": run_values,
        "landing_residual_psi": [LANDING_RESIDUAL.low, LANDING_RESIDUAL.high],
        "landing_level_height_ft": [LANDING_LEVEL_HEIGHT.low, LANDING_LEVEL_HEIGHT.high],
        "vent": anchor.text() if anchor is not None else None,
        "vent_source": anchor.source if anchor is not None else None,
    }
    prof = get_cabin_profile(track.aircraft)
    limits = {
        "max_cabin_alt_ft": prof.max_cabin_alt_ft,
        "climb_rate_fpm": prof.climb_rate_fpm,
        "descent_rate_fpm": prof.descent_rate_fpm,
        "descent_rate_max_fpm": prof.descent_rate_max_fpm,
        "hold": track.conditions.get("hold", "pressurised"),
    }
    png = None
    if out is not None:
        from flightmode.viz.cabin_plot import cabin_png

        Path(out).mkdir(parents=True, exist_ok=True)
        png = Path(out) / CABIN_PNG
        cabin_png(
            track,
            f,
            limits,
            png,
            f"{info['run_id']}: {track.aircraft}, cabin and aircraft altitude",
            landing=land or None,
            window_s=(BEFORE_S, AFTER_S),
        )
    if as_json:
        emit_json({"figures": f, "schedule": limits, "landing": land, "landing_anchors": anchors})
        return
    t = Table(
        "figure",
        "this flight",
        "the type's schedule",
        title=f"{info['run_id']}: cabin pressure ({track.aircraft})",
        title_justify="left",
    )
    t.add_row("highest aircraft altitude", f"{f['max_altitude_ft']:,.0f} ft", "")
    t.add_row(
        "cruise cabin altitude",
        f"{f['cruise_cabin_altitude_ft']:,.0f} ft",
        f"at most {prof.max_cabin_alt_ft:,.0f} ft",
    )
    t.add_row("cruise cabin pressure", f"{f['cruise_cabin_pressure_hpa']:.1f} hPa", "")
    t.add_row(
        "highest cabin altitude",
        f"{f['max_cabin_altitude_ft']:,.0f} ft",
        f"at most {prof.max_cabin_alt_ft:,.0f} ft",
    )
    t.add_row(
        "fastest cabin climb in the air (10 s)",
        f"{f['max_cabin_climb_airborne_fpm']:.0f} ft/min",
        f"{prof.climb_rate_fpm:.0f} ft/min",
    )
    used = track.conditions.get("cabin_descent_rate_fpm", prof.descent_rate_fpm)
    t.add_row(
        "fastest cabin descent in the air (10 s)",
        f"{f['max_cabin_descent_airborne_fpm']:.0f} ft/min",
        f"{prof.descent_rate_fpm:.0f} ft/min, up to {prof.descent_rate_max_fpm:.0f} (this flight: {used:.0f})",
    )
    t.add_row(
        "fastest over the whole flight (10 s)",
        f"{f['max_cabin_descent_fpm']:.0f} down, {f['max_cabin_climb_fpm']:.0f} up ft/min",
        f"{prof.prepress_rate_fpm:.0f} down (pre-pressurising), "
        + (
            f"{prof.release_rate_fpm:.0f} up (release)"
            if prof.vent is None
            else f"the residual vented over {run_values[prof.vent.name]:.0f} s"
        ),
    )
    t.add_row("largest differential", f"{f['max_differential_psi']:.2f} psi", "")
    t.add_row("hold", limits["hold"], "")
    console().print(t)
    if land:
        console().print(_landing_table(info["run_id"], track.aircraft, land, anchors))
    if png is not None:
        console().print(Text.assemble("wrote ", (str(png), "bold")), highlight=False)


def _landing_table(run_id: str, aircraft: str, f: dict, anchors: dict) -> Table:
    """The cabin from 5 minutes before touchdown to 2 after, beside its anchors."""
    t = Table(
        "figure",
        "this flight",
        "anchor",
        title=f"{run_id}: the cabin near touchdown ({aircraft})",
        title_justify="left",
    )
    lo, hi = anchors["landing_residual_psi"]
    hlo, hhi = anchors["landing_level_height_ft"]
    run = anchors["run_values"]
    t.add_row(
        f"cabin {-f['before_t_s'] / 60:.0f} min before touchdown",
        f"{f['cabin_altitude_before_ft']:,.0f} ft ({f['cabin_pressure_before_hpa']:.1f} hPa), aircraft "
        f"{f['aircraft_height_before_ft']:,.0f} ft up",
        "",
    )
    t.add_row(
        "landing pressure reached",
        f"{f['level_before_touchdown_s']:.0f} s before touchdown, aircraft {f['level_height_ft']:,.0f} ft up",
        f"before touchdown, lands pressurised (737, 787 FCOM); declared {hlo:,.0f}-{hhi:,.0f} ft "
        f"(this run: {run['cabin.landing_level_height_ft']:,.0f})",
    )
    t.add_row(
        "residual overpressure at touchdown",
        f"{f['residual_psi']:.3f} psi ({f['residual_hpa']:.2f} hPa)",
        f"declared {lo:g}-{hi:g} psi (this run: {run['cabin.landing_residual_psi']:g})",
    )
    t.add_row(
        "pressure step after touchdown",
        f"{f['step_hpa']:.2f} hPa from {f['vent_start_s']:.0f} s to {f['vent_complete_s']:.0f} s "
        f"({f['vent_duration_s']:.0f} s)",
        anchors["vent"] or "no description read",
    )
    t.add_row(
        "taxi-in, door open",
        f"taxi-in from {f['taxi_in_s']:.0f} s, door open at {f['door_open_s']:.0f} s "
        f"({f['residual_at_door_hpa']:.2f} hPa left)",
        "",
    )
    return t
