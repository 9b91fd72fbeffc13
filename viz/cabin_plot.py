"""The cabin pressure of one flight beside its aircraft altitude (matplotlib, Agg): the figure
``flightmode cabin RUN --out DIR`` writes (DIR/cabin.png). Every number drawn was computed upstream
(:mod:`flightmode.sim.flight.cabin`); this module only draws."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flightmode.units import FT_M, HPA_PA


def cabin_png(track, figures: dict, limits: dict, path: Path, title: str) -> Path:
    """Two panels against time (minutes): aircraft altitude and cabin pressure altitude (ft) with the
    type's maximum cabin altitude; ambient and cabin pressure (hPa). ``limits``: the type's schedule
    figures (``max_cabin_alt_ft``, ``climb_rate_fpm``, ``descent_rate_max_fpm``) for the legend.
    Written to a temporary name and renamed (no half-written file)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    k = slice(None, None, max(1, int(round(track.fs_hz))))  # 1 Hz is plenty for a schedule of minutes
    t_min = track.t_s[k] / 60.0
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
    from flightmode.atomic import write_with

    try:
        return write_with(Path(path), lambda tmp: fig.savefig(tmp, dpi=110, format="png"), mkdir=False)
    finally:
        plt.close(fig)
