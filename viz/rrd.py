"""A run as a Rerun recording (.rrd): what the bag's accelerometer saw, what the detector decided, what
the aircraft did and where the path estimators went, on one clock.

Everything is sent in bulk with ``send_columns`` (one call per entity; measured with rerun-sdk
0.41: a per-sample ``rr.log`` loop is 100x slower). viz computes nothing: it receives the arrays of the sensor, the
detector, the truth and nav (:class:`RunView`), and only lays them out.

Timelines: ``sim_time`` (exact integer nanoseconds of FlightTrack time; negative before the track
starts, while the bag is in the terminal) and ``sample`` (the accelerometer sample index).

Entities:

    /sensor/acc_g          Scalars (N, 3) x y z in g, named and coloured; /sensor/acc_norm_g |a|
    /sensor/raw_counts     Scalars (N, 3) raw output counts
    /detector/mv_g2        Scalars (K, 3) MV at each check; /detector/threshold_g2 T_sigma per axis
    /detector/state        StateChange: dynamic / temporary static / final static
    /truth/phase           StateChange: the bag's and the aircraft's phase
    /truth/in_flight_window StateChange: in flight window / outside
    /events                TextLog: INFO phase transitions and flight events, WARN false statics
    /aircraft/*            altitude, airspeed, vertical speed, N1 per engine, load factor
    /world/aircraft        Transform3D over time + a Boxes3D sized to the type (ENU, m)
    /world/path/*          LineStrips3D: truth, tridiagonal, recurrence (ENU, m)
    /map/route, /map/airports/<ICAO>   GeoLineStrings and GeoPoints
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

AXIS_COLOURS = [[230, 80, 60], [70, 170, 70], [60, 110, 230]]
STATE_NAMES = ("dynamic", "temporary static", "final static")
STATE_COLOURS = [[200, 60, 50], [240, 180, 40], [40, 170, 80]]


@dataclass
class RunView:
    """What one run shows. Times in seconds of FlightTrack time."""

    run_id: str
    # accelerometer, one row per sample
    t_s: np.ndarray
    acc_g: np.ndarray
    acc_norm_g: np.ndarray
    counts: np.ndarray
    # detector, one row per check
    check_t_s: np.ndarray
    mv_g2: np.ndarray
    threshold_g2: np.ndarray  # (3,)
    state_code: np.ndarray  # (K,) index into STATE_NAMES
    false_static_events: list[dict]
    # truth labels as transitions: (times, labels)
    phase_changes: tuple[np.ndarray, list[str]]
    window_changes: tuple[np.ndarray, list[str]]
    info_events: list[tuple[float, str]]  # (t, text)
    # aircraft channels (decimated by the caller): name -> (t_s, (M,) or (M, k) values, series names)
    aircraft: dict
    # 3D scene, local ENU at the origin airport
    pose_t_s: np.ndarray
    pose_enu_m: np.ndarray  # (P, 3)
    pose_quat_xyzw: np.ndarray  # (P, 4) body -> ENU
    box_size_m: tuple[float, float, float]
    paths_enu_m: dict = field(default_factory=dict)  # name -> (Q, 3)
    # map
    route_lat_lon: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    airports: list = field(default_factory=list)  # (icao, name, lat, lon)


def _ns(t_s) -> np.ndarray:
    """Exact integer nanoseconds (``TimeColumn(duration=float seconds)`` truncates to the nanosecond below), as timedelta64[ns]."""
    return np.rint(np.asarray(t_s, float) * 1e9).astype(np.int64).astype("timedelta64[ns]")


def _layout():
    import rerun.blueprint as rrb

    # every time-series and state view shows the whole run on its x-axis, whatever the time cursor
    whole = [
        rrb.VisibleTimeRange(t, start=rrb.TimeRangeBoundary.infinite(), end=rrb.TimeRangeBoundary.infinite())
        for t in ("sim_time", "sample")
    ]
    axis = rrb.TimeAxis(
        view_range=rrb.TimeRange(start=rrb.TimeRangeBoundary.infinite(), end=rrb.TimeRangeBoundary.infinite())
    )
    series = rrb.Vertical(
        rrb.TimeSeriesView(origin="/sensor/acc_g", name="accelerometer (g)", time_ranges=whole, axis_x=axis),
        rrb.TimeSeriesView(
            origin="/detector", name="moving variance and T_sigma (g^2)", time_ranges=whole, axis_x=axis
        ),
        rrb.StateTimelineView(
            origin="/",
            contents=["/detector/state", "/truth/phase", "/truth/in_flight_window"],
            name="detector state, phase, in-flight window",
            time_ranges=whole,
            time_view=axis,
        ),
        rrb.Tabs(
            rrb.TimeSeriesView(
                origin="/aircraft/altitude_m", name="altitude (m)", time_ranges=whole, axis_x=axis
            ),
            rrb.TimeSeriesView(
                origin="/aircraft/airspeed_mps", name="airspeed (m/s)", time_ranges=whole, axis_x=axis
            ),
            rrb.TimeSeriesView(
                origin="/aircraft/vertical_speed_mps",
                name="vertical speed (m/s)",
                time_ranges=whole,
                axis_x=axis,
            ),
            rrb.TimeSeriesView(origin="/aircraft/n1_pct", name="N1 (%)", time_ranges=whole, axis_x=axis),
            rrb.TimeSeriesView(
                origin="/aircraft/load_factor_g", name="load factor (g)", time_ranges=whole, axis_x=axis
            ),
            rrb.TimeSeriesView(
                origin="/aircraft/cabin_altitude_m",
                name="cabin and aircraft altitude (m)",
                time_ranges=whole,
                axis_x=axis,
            ),
            rrb.TimeSeriesView(
                origin="/aircraft/pressure_hpa", name="pressure (hPa)", time_ranges=whole, axis_x=axis
            ),
            rrb.TimeSeriesView(
                origin="/sensor/raw_counts", name="raw counts", time_ranges=whole, axis_x=axis
            ),
            rrb.TimeSeriesView(origin="/sensor/acc_norm_g", name="|a| (g)", time_ranges=whole, axis_x=axis),
            name="aircraft and raw data",
        ),
        row_shares=[3, 2, 2, 2],
    )
    side = rrb.Vertical(
        rrb.Spatial3DView(origin="/world", name="3D: aircraft and paths (ENU, m)"),
        rrb.MapView(origin="/map", name="route"),
        rrb.TextLogView(origin="/events", name="events"),
        row_shares=[3, 2, 2],
    )
    return rrb.Horizontal(series, side, column_shares=[3, 2])


def blueprint():
    """The embedded default blueprint: :func:`_layout`, opened paused on ``sim_time`` (so the views
    show the whole flight rather than following its last minute)."""
    import rerun.blueprint as rrb

    return rrb.Blueprint(
        _layout(),
        rrb.TimePanel(timeline="sim_time", play_state="paused", state="collapsed"),
        rrb.BlueprintPanel(state="collapsed"),
        rrb.SelectionPanel(state="collapsed"),
    )


def view_names() -> list[str]:
    """The names of every view in :func:`blueprint`'s layout (walked, not listed twice)."""

    def walk(part):
        if hasattr(part, "contents") and not hasattr(part, "origin"):
            return [n for c in part.contents for n in walk(c)]
        return [str(part.name)]

    return walk(_layout())


class RrdWriter:
    """An .rrd being written: opened at a temporary name beside ``path`` with the embedded blueprint,
    filled with :meth:`send` (a RunView; Rerun encodes and writes in its own threads meanwhile) and
    :meth:`send_paths` (3D paths computed later), renamed into place by :meth:`close`; :meth:`abort`
    removes it."""

    def __init__(self, path: Path, run_id: str):
        import rerun as rr

        from flightmode.atomic import tmp_name

        self._rr = rr
        self.path = Path(path)
        self._tmp = tmp_name(self.path)
        self._rec = rr.RecordingStream("flightmode", recording_id=run_id)
        try:
            self._rec.save(self._tmp, default_blueprint=blueprint())
        except BaseException:
            self.abort()
            raise

    def send(self, view: RunView) -> None:
        _send(self._rr, self._rec, view)

    def send_paths(self, paths_enu_m: dict) -> None:
        _send_paths(self._rr, self._rec, paths_enu_m)

    def close(self) -> Path:
        try:
            self._rec.flush()
            self._rec.disconnect()
            os.replace(self._tmp, self.path)
        except BaseException:
            self.abort()
            raise
        return self.path

    def abort(self) -> None:
        try:
            self._rec.disconnect()
        finally:
            self._tmp.unlink(missing_ok=True)


def write_rrd(view: RunView, path: Path) -> Path:
    """Write ``view`` to ``path`` (temporary name, then rename) with the embedded blueprint."""
    w = RrdWriter(path, view.run_id)
    try:
        w.send(view)
    except BaseException:
        w.abort()
        raise
    return w.close()


def _send(rr, rec, v: RunView) -> None:
    n = v.t_s.shape[0]
    idx = [rr.TimeColumn("sim_time", duration=_ns(v.t_s)), rr.TimeColumn("sample", sequence=np.arange(n))]
    kw = {"recording": rec}
    # sensor
    rr.log(
        "/sensor/acc_g",
        rr.SeriesLines(names=["x", "y", "z"], colors=AXIS_COLOURS, widths=1.0),
        static=True,
        **kw,
    )
    rr.send_columns("/sensor/acc_g", indexes=idx, columns=rr.Scalars.columns(scalars=v.acc_g), **kw)
    rr.log("/sensor/acc_norm_g", rr.SeriesLines(names=["|a|"], colors=[[90, 90, 90]]), static=True, **kw)
    rr.send_columns("/sensor/acc_norm_g", indexes=idx, columns=rr.Scalars.columns(scalars=v.acc_norm_g), **kw)
    rr.log(
        "/sensor/raw_counts",
        rr.SeriesLines(names=["raw x", "raw y", "raw z"], colors=AXIS_COLOURS),
        static=True,
        **kw,
    )
    rr.send_columns(
        "/sensor/raw_counts",
        indexes=idx,
        columns=rr.Scalars.columns(scalars=v.counts.astype(np.float64)),
        **kw,
    )
    # detector
    cidx = [rr.TimeColumn("sim_time", duration=_ns(v.check_t_s))]
    rr.log(
        "/detector/mv_g2",
        rr.SeriesLines(names=["MV x", "MV y", "MV z"], colors=AXIS_COLOURS),
        static=True,
        **kw,
    )
    rr.send_columns("/detector/mv_g2", indexes=cidx, columns=rr.Scalars.columns(scalars=v.mv_g2), **kw)
    rr.log(
        "/detector/threshold_g2",
        rr.SeriesLines(
            names=["T_sigma x", "T_sigma y", "T_sigma z"],
            colors=[[c // 2 + 100 for c in col] for col in AXIS_COLOURS],
            widths=2.0,
        ),
        static=True,
        **kw,
    )
    k = v.check_t_s.shape[0]
    rr.send_columns(
        "/detector/threshold_g2",
        indexes=cidx,
        columns=rr.Scalars.columns(scalars=np.broadcast_to(v.threshold_g2, (k, 3)).copy()),
        **kw,
    )
    rr.log(
        "/detector/state",
        rr.StateConfiguration(values=list(STATE_NAMES), colors=STATE_COLOURS),
        static=True,
        **kw,
    )
    change = np.flatnonzero(np.r_[True, np.diff(v.state_code) != 0]) if k else np.zeros(0, int)
    rr.send_columns(
        "/detector/state",
        indexes=[rr.TimeColumn("sim_time", duration=_ns(v.check_t_s[change]))],
        columns=rr.StateChange.columns(state=[STATE_NAMES[i] for i in v.state_code[change]]),
        **kw,
    )
    # truth labels
    for ent, (t, labels) in (
        ("/truth/phase", v.phase_changes),
        ("/truth/in_flight_window", v.window_changes),
    ):
        rr.send_columns(
            ent,
            indexes=[rr.TimeColumn("sim_time", duration=_ns(t))],
            columns=rr.StateChange.columns(state=list(labels)),
            **kw,
        )
    # event log: INFO phase transitions and flight events, WARN false statics
    ev = [(t, "INFO", txt) for t, txt in v.info_events]
    ev += [
        (
            e["t_s"],
            "WARN",
            (
                f"false static: transmission allowed at t = {e['t_s']:.0f} s for "
                f"{e['duration_s']:g} s in phase {e['phase']}"
            ),
        )
        for e in v.false_static_events
    ]
    ev.sort(key=lambda e: e[0])
    if ev:
        rr.send_columns(
            "/events",
            indexes=[rr.TimeColumn("sim_time", duration=_ns([e[0] for e in ev]))],
            columns=rr.TextLog.columns(text=[e[2] for e in ev], level=[e[1] for e in ev]),
            **kw,
        )
    # aircraft channels
    for name, (t, vals, names) in v.aircraft.items():
        vals = np.asarray(vals, float)
        rr.log(f"/aircraft/{name}", rr.SeriesLines(names=list(names)), static=True, **kw)
        rr.send_columns(
            f"/aircraft/{name}",
            indexes=[rr.TimeColumn("sim_time", duration=_ns(t))],
            columns=rr.Scalars.columns(scalars=vals),
            **kw,
        )
    # 3D scene
    rr.log("/world", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True, **kw)
    sx, sy, sz = v.box_size_m
    rr.log(
        "/world/aircraft",
        rr.Boxes3D(sizes=[[sx, sy, sz]], colors=[[220, 220, 240]], fill_mode="solid"),
        static=True,
        **kw,
    )
    rr.send_columns(
        "/world/aircraft",
        indexes=[rr.TimeColumn("sim_time", duration=_ns(v.pose_t_s))],
        columns=rr.Transform3D.columns(translation=v.pose_enu_m, quaternion=v.pose_quat_xyzw),
        **kw,
    )
    _send_paths(rr, rec, v.paths_enu_m)
    # map
    if v.route_lat_lon.shape[0]:
        rr.log(
            "/map/route",
            rr.GeoLineStrings(
                lat_lon=[v.route_lat_lon], radii=rr.components.Radius.ui_points(2.0), colors=[[40, 120, 255]]
            ),
            static=True,
            **kw,
        )
    # airports: one class per airport, its label from an annotation context (GeoPoints have no
    # label field in Rerun 0.41); the entity path carries the ICAO code as well
    rr.log(
        "/map/airports",
        rr.AnnotationContext(
            [
                rr.ClassDescription(info=(i + 1, f"{icao} {name}", (255, 80, 40)))
                for i, (icao, name, _, _) in enumerate(v.airports)
            ]
        ),
        static=True,
        **kw,
    )
    for i, (icao, _name, lat, lon) in enumerate(v.airports):
        rr.log(
            f"/map/airports/{icao}",
            rr.GeoPoints(lat_lon=[[lat, lon]], radii=rr.components.Radius.ui_points(8.0), class_ids=[i + 1]),
            static=True,
            **kw,
        )


PATH_COLOURS = {"truth": [240, 240, 240], "tridiagonal": [80, 200, 255], "recurrence": [255, 120, 60]}


def _send_paths(rr, rec, paths_enu_m: dict) -> None:
    for name, pts in paths_enu_m.items():
        rr.log(
            f"/world/path/{name}",
            rr.LineStrips3D(
                [pts], radii=[40.0], colors=[PATH_COLOURS.get(name, [200, 200, 0])], labels=[name]
            ),
            static=True,
            recording=rec,
        )
