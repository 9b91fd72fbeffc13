"""Assemble a run's results (FlightTrack, Recording, detector Evaluation, nav estimates) into the
plain arrays of :class:`flightmode.viz.rrd.RunView`. Only selection, decimation and frame conventions for
display happen here (NED -> ENU, body -> ENU attitude); every number shown was computed upstream."""

from __future__ import annotations

import numpy as np

from flightmode.intervals import segment_starts
from flightmode.labels import CARRIER_PHASES
from flightmode.sim.flight.aircraft.registry import get_profile
from flightmode.units import G0_MPS2

NED_TO_ENU = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])


def _changes(t: np.ndarray, labels: np.ndarray) -> tuple[np.ndarray, list[str]]:
    i = segment_starts(labels)
    return t[i], [str(x) for x in labels[i]]


def run_view(run_id: str, plan, track, rec, evaluation, paths: dict | None):
    from scipy.spatial.transform import Rotation

    from flightmode.viz.rrd import RunView

    c = evaluation.checks
    state = np.where(c.final_static, 2, np.where(c.temporary_static, 1, 0)).astype(np.int8)
    window = np.where(rec.in_flight_window, "in-flight window (no transmission)", "outside the window")
    info = [(e.t_s, f"{e.name}" + (f": {e.detail}" if e.detail else "")) for e in track.events]
    pt, pl = _changes(rec.t_s, rec.phase)
    # the bag's own phases (the aircraft's are among the track's events already)
    info += [(float(t), f"bag: {p}") for t, p in zip(pt, pl) if p in CARRIER_PHASES]

    def every(hz: float) -> slice:  # the track decimated to about ``hz``
        return slice(None, None, max(1, round(track.fs_hz / hz)))

    # aircraft channels at 10 Hz
    k = every(10.0)
    ta = track.t_s[k]
    ne = track.n1_pct.shape[1]
    aircraft = {
        "altitude_m": (ta, track.alt_m[k], ["altitude MSL"]),
        "airspeed_mps": (
            ta,
            np.column_stack([track.ias_mps[k], track.ground_speed_mps[k]]),
            ["IAS", "ground speed"],
        ),
        "vertical_speed_mps": (ta, track.vertical_speed_mps[k], ["vertical speed"]),
        "n1_pct": (ta, track.n1_pct[k], [f"N1 engine {i + 1}" for i in range(ne)]),
        "load_factor_g": (ta, -track.specific_force_body_mps2[k, 2] / G0_MPS2, ["n_z"]),
    }
    if track.cabin_pressure_pa is not None:  # the pressure truth (sim.flight.cabin), and the bag's barometer
        aircraft["cabin_altitude_m"] = (
            ta,
            np.column_stack([track.alt_m[k], track.cabin_altitude_m[k]]),
            ["aircraft altitude MSL", "cabin pressure altitude"],
        )
        hpa = [track.ambient_pressure_pa[k] / 100.0, track.cabin_pressure_pa[k] / 100.0]
        names = ["ambient", "cabin"]
        if rec.baro_pa is not None:
            hpa.append(np.interp(ta, rec.t_s[rec.baro_new], rec.baro_pa[rec.baro_new]) / 100.0)
            names.append(f"barometer ({rec.baro['preset']})")
        aircraft["pressure_hpa"] = (ta, np.column_stack(hpa), names)
    # 3D pose at 2 Hz: position NED -> ENU, attitude body -> NED -> ENU
    kp = every(2.0)
    pos = track.pos_ned_m[kp] @ NED_TO_ENU.T
    r = Rotation.from_matrix(NED_TO_ENU) * Rotation.from_quat(track.quat_wxyz[kp], scalar_first=True)
    prof = get_profile(track.aircraft)
    box = (prof.length_m, prof.wingspan_m, prof.length_m * 0.2)  # length, span, a rough height
    p3 = path_lines(paths, rec.odr_hz) if paths is not None else {}
    route = np.column_stack([track.lat_deg[every(1.0)], track.lon_deg[every(1.0)]])
    airports = [(a.icao, a.name, a.lat_deg, a.lon_deg) for a in (plan.origin, plan.destination)]
    return RunView(
        run_id=run_id,
        t_s=rec.t_s,
        acc_g=rec.acc_g,
        acc_norm_g=np.linalg.norm(rec.acc_g, axis=1),
        counts=rec.counts,
        check_t_s=c.t_s,
        mv_g2=c.mv,
        threshold_g2=evaluation.params.k_sigma * evaluation.sigma2,
        state_code=state,
        false_static_events=evaluation.false_static_events,
        phase_changes=(pt, pl),
        window_changes=_changes(rec.t_s, window),
        info_events=sorted(info),
        aircraft=aircraft,
        pose_t_s=track.t_s[kp],
        pose_enu_m=pos,
        pose_quat_xyzw=r.as_quat(),
        box_size_m=box,
        paths_enu_m=p3,
        route_lat_lon=route,
        airports=airports,
    )


def path_lines(paths: dict, odr_hz: float) -> dict:
    """The path estimates (nav, world NED) as ENU polylines at one point per second."""
    step = max(1, int(odr_hz))
    return {name: paths[name][::step] @ NED_TO_ENU.T for name in ("truth", "tridiagonal", "recurrence")}
