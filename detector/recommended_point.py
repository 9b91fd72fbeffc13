"""Seed 000's recommended detector point as plain numbers: the one copy of the fact.

Seed 000, Table 9 and section 7: the normal moving variance (NMV), a window and check period W_s of
1 s, an amplitude threshold T_sigma = 4 sigma^2 per axis and a time threshold T_th of 4 s. The
detector's parameter defaults (:class:`flightmode.detector.flight_mode.DetectorParams`) and
:data:`flightmode.detector.recommended.RECOMMENDED` are built from :data:`POINT`; text shown to users
is built from :attr:`RecommendedPoint.text`. This module imports nothing, so that the detector's
own parameters can refer to it without a cycle.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class RecommendedPoint:
    method: str  # "nmv": the normal moving variance (seed 000, eq. 6)
    weight: float  # the EMV weighting factor (1.0: unused by the NMV)
    window_s: float  # W_s, s: the moving variance's window and the check period
    k_sigma: float  # T_sigma = k_sigma * sigma^2 per axis (seed 000, eq. 7, 12)
    time_threshold_s: float  # T_th, s: static for this long before final static (eq. 8)

    @property
    def text(self) -> str:
        """``NMV, W_s 1 s, 4 sigma^2, T_th 4 s``."""
        return (
            f"{self.method.upper()}, W_s {self.window_s:g} s, {self.k_sigma:g} sigma^2, "
            f"T_th {self.time_threshold_s:g} s"
        )

    @property
    def short_text(self) -> str:
        """``NMV, 1 s, 4 sigma^2, 4 s``."""
        return f"{self.method.upper()}, {self.window_s:g} s, {self.k_sigma:g} sigma^2, {self.time_threshold_s:g} s"

    def grid_point(self) -> dict:
        """The point as a sweep grid point: {method, weight, window_s, k, time_threshold_s}."""
        return {
            "method": self.method,
            "weight": self.weight,
            "window_s": self.window_s,
            "k": self.k_sigma,
            "time_threshold_s": self.time_threshold_s,
        }


# seed 000, Table 9 and section 7
POINT = RecommendedPoint(method="nmv", weight=1.0, window_s=1.0, k_sigma=4.0, time_threshold_s=4.0)

__all__ = ["POINT", "RecommendedPoint"]
