"""The cabin pressure of one flight beside its aircraft altitude (matplotlib, Agg): the figure
``flightmode cabin RUN --out DIR`` writes (DIR/cabin.png). Every number drawn was computed upstream
(:mod:`flightmode.sim.flight.cabin`); this module only draws."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flightmode.units import FT_M, HPA_PA


def cabin_png(
    track,
    figures: dict,
    limits: dict,
    path: Path,
    title: str,
    landing: dict | None = None,
    window_s=(300.0, 120.0),
) -> Path:
    """Two panels against time (minutes): aircraft altitude and cabin pressure altitude (ft) with the
    type's maximum cabin altitude; ambient and cabin pressure (hPa). ``limits``: the type's schedule
    figures (``max_cabin_alt_ft``, ``climb_rate_fpm``, ``descent_rate_max_fpm``) for the legend.
    With ``landing`` (:func:`flightmode.sim.flight.cabin_landing.landing_figures`), a third panel: the
    cabin and ambient pressure from ``window_s[0]`` before touchdown to ``window_s[1]`` after it
    (further when the vent ends later), the aircraft's height beside them, the landing pressure's
    level-off, the vent's start and end and the door marked.
    Written to a temporary name and renamed (no half-written file)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    k = slice(None, None, max(1, int(round(track.fs_hz))))  # 1 Hz is plenty for a schedule of minutes
    t_min = track.t_s[k] / 60.0
    if landing:
        fig, axes = plt.subplots(3, 1, figsize=(10, 9.5), constrained_layout=True)
        a1, a2, a3 = axes
        a1.sharex(a2)
    else:
        fig, (a1, a2) = plt.subplots(2, 1, figsize=(10, 6.5), sharex=True, constrained_layout=True)
    a1.plot(t_min, track.alt_m[k] / FT_M, color="0.45", lw=1.2, label="aircraft altitude (MSL)")
    a1.plot(
        t_min, track.cabin_altitude_m[k] / FT_M, color="tab:blue", lw=1.6, label="cabin pressure altitude"
    )
    a1.axhline(
        limits["max_cabin_alt_ft"],
        color="tab:red",
        ls="--",
        lw=1,
        label=f"maximum cabin altitude {limits['max_cabin_alt_ft']:,.0f} ft",
    )
    a1.set_ylabel("ft")
    a1.legend(loc="upper right", fontsize=8)
    a1.set_title(
        f"{title}\ncruise cabin {figures['cruise_cabin_altitude_ft']:,.0f} ft "
        f"({figures['cruise_cabin_pressure_hpa']:.0f} hPa); cabin climb up to "
        f"{figures['max_cabin_climb_airborne_fpm']:.0f} ft/min (limit {limits['climb_rate_fpm']:.0f}), descent up to "
        f"{figures['max_cabin_descent_airborne_fpm']:.0f} ft/min (limit {limits['descent_rate_max_fpm']:.0f}) in the air",
        fontsize=9,
    )
    a2.plot(t_min, track.ambient_pressure_pa[k] / HPA_PA, color="0.45", lw=1.2, label="ambient")
    a2.plot(t_min, track.cabin_pressure_pa[k] / HPA_PA, color="tab:blue", lw=1.6, label="cabin")
    if track.hold_pressure_pa is not None and not np.array_equal(
        track.hold_pressure_pa, track.cabin_pressure_pa
    ):
        a2.plot(t_min, track.hold_pressure_pa[k] / HPA_PA, color="tab:orange", lw=1.2, ls=":", label="hold")
    a2.set_ylabel("hPa")
    a2.set_xlabel("time since the gate (min)")
    a2.legend(loc="lower right", fontsize=8)
    if landing:
        _landing_panel(a3, track, landing, window_s)
    from flightmode.atomic import write_with

    try:
        return write_with(Path(path), lambda tmp: fig.savefig(tmp, dpi=110, format="png"), mkdir=False)
    finally:
        plt.close(fig)


def _landing_panel(ax, track, f: dict, window_s) -> None:
    """Cabin and ambient pressure (hPa) against seconds from touchdown, the aircraft's height (ft) on
    a second axis, the figures marked."""
    t0 = f["touchdown_t_s"]
    after = max(window_s[1], f["vent_complete_s"] + 10.0 if np.isfinite(f["vent_complete_s"]) else 0.0)
    sel = (track.t_s >= t0 - window_s[0]) & (track.t_s <= t0 + after)
    k = np.flatnonzero(sel)[:: max(1, int(round(track.fs_hz / 10.0)))]  # 10 Hz: the vent takes seconds
    ts = track.t_s[k] - t0
    ax.plot(ts, track.ambient_pressure_pa[k] / HPA_PA, color="0.45", lw=1.2, label="ambient")
    ax.plot(ts, track.cabin_pressure_pa[k] / HPA_PA, color="tab:blue", lw=1.6, label="cabin")
    ax.axvline(0.0, color="k", lw=0.8, ls="--")
    ax.axvline(
        -f["level_before_touchdown_s"], color="tab:green", lw=0.8, ls=":", label="landing pressure reached"
    )
    for key, colour, lab in (
        ("vent_start_s", "tab:orange", "vent starts"),
        ("vent_complete_s", "tab:red", "vent complete"),
        ("door_open_s", "tab:purple", "door open"),
    ):
        if np.isfinite(f[key]) and f[key] <= after:
            ax.axvline(f[key], color=colour, lw=0.8, ls=":", label=lab)
    ax.set_xlim(-window_s[0], after)
    cab = track.cabin_pressure_pa[k] / HPA_PA  # the scale of the cabin (the ambient aloft is far off it)
    ax.set_ylim(float(cab.min()) - 2.0, float(cab.max()) + 2.0)
    ax.set_ylabel("hPa")
    ax.set_xlabel("time from touchdown (s)")
    ax.set_title(
        f"the last {window_s[0] / 60:.0f} min before touchdown: landing pressure reached "
        f"{f['level_before_touchdown_s']:.0f} s before it ({f['level_height_ft']:,.0f} ft up); residual "
        f"{f['residual_psi']:.3f} psi; a {f['step_hpa']:.2f} hPa step over {f['vent_duration_s']:.0f} s from "
        f"{f['vent_start_s']:.0f} s",
        fontsize=9,
    )
    ax.legend(loc="lower left", fontsize=8)
    h = ax.twinx()
    h.plot(
        ts, (track.alt_m[k] - track.alt_m[track.t_s.searchsorted(t0)]) / FT_M, color="0.7", lw=0.8, ls="-."
    )
    h.set_ylabel("aircraft height over touchdown (ft)", color="0.5", fontsize=8)
