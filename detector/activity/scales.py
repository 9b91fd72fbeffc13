"""Seed 001's thresholds moved onto the scales its tables use (issue 53).

Our detectors keep their merits in g, deg/s and noise variances
(:mod:`~flightmode.detector.activity.common`); where a table of the paper is only consistent with
another scale, :func:`to_paper_scale` converts ours onto it, and :data:`PAPER_SCALES` says why:

- AMVD (eq. 1, Table 1: 0.0188 +- 0.0049; Table 7 on the IMU: 0.0173): a variance in (m/s^2)^2.
  In g^2 it would be a 0.14 g standard deviation, 60 times the sensor noise, far inside walking.
  Ours x g0^2 (g0 = 9.80665 m/s^2; the paper's section 2.1.2: "1 g or 9.8 m/s^2").
- AMD (eq. 2, Table 1: 0.0008 +- 0.0002; Table 7: 0.0011): eq. (2) divides by sigma_a^2, which puts
  a still window at ~1 and makes 0.0008 mark every sample active; unscaled in (m/s^2)^2 it is 1.7
  sigma_a^2 of a 2.23 mg noise (4.8e-4 (m/s^2)^2): the merit without the 1 / sigma_a^2, in
  (m/s^2)^2. Ours x sigma_a^2 g0^2 (sigma_a in g, the bench's).
- FRD (eq. 5, Table 6: Ang 0.172 +- 0.286, Prod 0.168 +- 0.278): an angular rate in rad/s (ours in
  deg/s, x pi / 180); the acceleration input stays in g (Acc 0.0100); the sum of g and an angular rate
  cannot be moved by a factor (not converted).
- Every other threshold is on the scale of the equation as written (ARED, SHOD: noise variances,
  eq. 3-4; LTSD, FSD: dB, eq. 7-8; MBGTD: the signal's unit, eq. 9-10; MBCD: nats, eq. 13-14): no
  unit change brings ours nearer the paper's (see the issue 53 report in docs/seed001_tables_n50.txt).
"""

from __future__ import annotations

import math
from dataclasses import dataclass


# ---------------------------------------------------------------- scales
@dataclass(frozen=True, slots=True)
class PaperScale:
    """How a detector's threshold is moved onto the paper's scale: ``kind`` "same" (factor 1),
    "g2_to_mps2" (x g0^2), "unscaled_mps2" (x sigma_a^2 g0^2), "deg_to_rad" (x pi/180) or "none"
    (not convertible: NaN); ``unit`` the paper-scale unit; ``why`` the evidence."""

    kind: str
    unit: str
    why: str


PAPER_SCALES: dict[tuple[str, str | None], PaperScale] = {
    ("amvd", None): PaperScale(
        "g2_to_mps2", "(m/s^2)^2", "Table 1 0.0188, Table 7 0.0173: a few-mg noise's variance in (m/s^2)^2"
    ),
    ("amd", None): PaperScale(
        "unscaled_mps2",
        "(m/s^2)^2, without 1/sigma_a^2",
        "Table 1 0.0008: 1.7 sigma_a^2 in (m/s^2)^2; scaled as eq. (2) it would mark all samples active",
    ),
    ("frd", "gyr"): PaperScale("deg_to_rad", "rad/s", "Table 6 0.172 +- 0.286: |w| in rad/s"),
    ("frd", "product"): PaperScale(
        "deg_to_rad", "g rad/s", "Table 6 0.168 +- 0.278: |a| |w| with w in rad/s"
    ),
    ("frd", "sum"): PaperScale("none", "g + rad/s", "a sum of g and rad/s is not a factor of g + deg/s"),
}


def paper_scale(detector: str, signal: str | None) -> PaperScale:
    """The scale a case's threshold is reported on beside the paper's (module docstring)."""
    return PAPER_SCALES.get((detector, signal), PaperScale("same", "as ours", "the equation as written"))


def to_paper_scale(
    detector: str, signal: str | None, threshold: float, sigma_acc_g: float | None = None
) -> float:
    """Our threshold on the paper's scale (NaN where there is no such factor)."""
    from flightmode.units import G0_MPS2

    kind = paper_scale(detector, signal).kind
    if kind == "same":
        return float(threshold)
    if kind == "g2_to_mps2":
        return float(threshold) * G0_MPS2**2
    if kind == "unscaled_mps2":
        if sigma_acc_g is None:
            return math.nan
        return float(threshold) * float(sigma_acc_g) ** 2 * G0_MPS2**2
    if kind == "deg_to_rad":
        return math.radians(float(threshold))
    return math.nan


__all__ = ["PAPER_SCALES", "PaperScale", "paper_scale", "to_paper_scale"]
