"""The roughness of the surfaces an airliner rolls on: ISO 8608 random profiles along each wheel's
track (felt through the gear: :mod:`flightmode.sim.flight.jsbsim.roughness`).

JSBSim's terrain is one flat elevation, so its gear rolls as on glass. Here each surface the aircraft
rolls on (origin taxiway, origin runway, destination runway, destination taxiway) gets a seeded
random profile along its path, and each gear group (nose, left main, right main) feels the profile
under its wheels as an extra vertical force, so that JSBSim computes the heave, pitch and roll
response with its own mass, inertia and gear.

Profile (ISO 8608:2016, "Mechanical vibration - Road surface profiles - Reporting of measured
data", Table C.2): displacement PSD Gd(n) = Gd(n0) (n / n0)^-2, n0 = 0.1 cycle/m, classes A..H at
geometric-mean Gd(n0) = 16e-6, 64e-6, 256e-6, ... m^3 (x4 per class). Synthesis: complex Gaussian
Fourier coefficients of a periodic profile (2^15 samples 0.1 m apart: 3.3 km, longer than any
takeoff roll or rollout; a long taxi route wraps round seamlessly), so the profile is Gaussian with
that PSD in expectation, over wavelengths 0.5-120 m: 120 m is the longest straightedge of the Boeing
bump method of FAA AC 150/5380-9 (2009), whose straightedges start at two 0.25 m survey increments,
0.5 m, about an airliner tyre's footprint length (it envelops shorter bumps). At 5-90 m/s the band
spans 0.04-180 Hz, past both ends of the rigid-body response. The nose wheel runs on the centreline,
the mains on two tracks a track width B apart; the three are parallel lines of one isotropic random
surface (Dodds and Robson, "The description of road surface roughness", J. Sound Vib. 31(2), 1973):
for Gd ~ n^-2 two tracks d apart have coherence rho(n) = z K1(z), z = 2 pi n d (the isotropic 2-D
spectrum integrated across the track; K1 the modified Bessel function), so long waves lift both mains
together (heave, pitch) and short ones rock the wings (roll). Identical tracks would have no roll;
independent ones would halve the heave of long waves.

Class: runways A, taxiways A (:data:`RUNWAY_CLASS`, :data:`TAXIWAY_CLASS`; :class:`RunwayRoughness`
is the per-surface attribute). Runways are far smoother than roads: NASA's criterion (Morris and Hall,
"Recent studies of runway roughness", NASA conference on aircraft operating problems, 1965) keeps the
cockpit's vertical acceleration within +-0.4 g even on the worst acceptable runway, and a good runway
shakes the CG by a few hundredths of g on the roll. ISO's smoothest class, A, gives about 0.015-0.02 g
RMS at the CG of the 737 and A320 on the takeoff roll and rollout, cockpit peaks below 0.2 g
(tests/sim/test_roughness.py); class B doubles every figure. No public figure read separates taxiways
from runways, so both are A (taxiing is gentler for its speed alone).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flightmode.errors import ScenarioError, did_you_mean
from flightmode.labels import FLIGHT_PHASES

# ISO 8608:2016 Table C.2: geometric mean of each class's Gd(n0), m^3 (n0 = 0.1 cycle/m)
ISO_8608_N0 = 0.1
ISO_8608_GD_N0_M3 = {c: 16e-6 * 4.0**i for i, c in enumerate("ABCDEFGH")}

RUNWAY_CLASS = "A"
TAXIWAY_CLASS = "A"
BAND_M = (0.5, 120.0)  # shortest and longest wavelength synthesized (module docstring)
DX_M = 0.1  # profile sample spacing
PERIOD_SAMPLES = 2**15  # 3,277 m: longer than any takeoff roll or rollout; taxi routes wrap seamlessly


@dataclass(frozen=True, slots=True)
class RunwayRoughness:
    """The roughness of one surface: its ISO 8608 class and the random stream its profile comes from."""

    iso_class: str
    stream: str

    def __post_init__(self) -> None:
        if self.iso_class not in ISO_8608_GD_N0_M3:
            raise ScenarioError(
                f"roughness class '{self.iso_class}'{did_you_mean(self.iso_class, ISO_8608_GD_N0_M3)}: "
                f"ISO 8608 classes are {', '.join(ISO_8608_GD_N0_M3)}"
            )

    @property
    def gd_n0_m3(self) -> float:
        return ISO_8608_GD_N0_M3[self.iso_class]


# the surfaces of a flight, and the phases on each (other phases: no roughness; before taxi-out the
# aircraft stands or is pushed at a walking pace, 0.003 g RMS on these profiles, the accelerometers'
# noise; the profile's datum is where it first rolls)
SURFACES = {
    "origin/taxiway": RunwayRoughness(TAXIWAY_CLASS, "roughness/origin/taxiway"),
    "origin/runway": RunwayRoughness(RUNWAY_CLASS, "roughness/origin/runway"),
    "destination/runway": RunwayRoughness(RUNWAY_CLASS, "roughness/destination/runway"),
    "destination/taxiway": RunwayRoughness(TAXIWAY_CLASS, "roughness/destination/taxiway"),
}
PHASE_SURFACE = {p: None for p in FLIGHT_PHASES} | {
    "taxi_out": "origin/taxiway",
    "takeoff_roll": "origin/runway",
    "initial_climb": "origin/runway",
    "flare": "destination/runway",
    "rollout": "destination/runway",
    "taxi_in": "destination/taxiway",
    "shutdown": "destination/taxiway",
    "parked": "destination/taxiway",
}


# ------------------------------------------------------------------------------------ profiles
def displacement_psd_m3(n_cpm, gd_n0_m3: float) -> np.ndarray:
    """ISO 8608 eq. (4) with w = 2: Gd(n) = Gd(n0) (n / n0)^-2 (m^3; n in cycle/m)."""
    n = np.asarray(n_cpm, dtype=float)
    return gd_n0_m3 * (n / ISO_8608_N0) ** -2.0


def track_coherence(n_cpm, separation_m: float) -> np.ndarray:
    """Coherence of two parallel tracks ``separation_m`` apart on an isotropic surface whose track
    PSD falls as n^-2: rho = z K1(z), z = 2 pi n d (module docstring; 1 at z = 0; K1: the modified
    Bessel function of the second kind, scipy.special.k1)."""
    from scipy.special import k1

    z = 2.0 * math.pi * np.abs(np.asarray(n_cpm, dtype=float)) * separation_m
    rho = np.ones_like(z)
    pos = z > 0.0
    rho[pos] = z[pos] * k1(z[pos])
    return np.clip(rho, 0.0, 1.0)


def synthesize_tracks(
    gd_n0_m3: float,
    rng: np.random.Generator,
    track_m: float,
    *,
    n_samples: int = PERIOD_SAMPLES,
    dx_m: float = DX_M,
    band_m=BAND_M,
) -> np.ndarray:
    """Three parallel profiles (3, n_samples), m: the centreline (nose wheel) and the left and right
    main-gear tracks ``track_m`` apart, periodic with period n_samples * dx_m, zero mean.

    Per frequency, with Z0, Z1, Z2 independent complex Gaussians: centre = Z0, left/right =
    r1 Z0 + sqrt(1 - r1^2) (b Z1 +- c Z2), r1 = rho(B/2), b^2 - c^2 = (rho(B) - r1^2) / (1 - r1^2),
    b^2 + c^2 = 1, so that each track has Gd and the pairs the isotropic coherences. Deterministic:
    the same generator state gives the same tracks.
    """
    period_m = n_samples * dx_m
    k = np.arange(math.ceil(period_m / band_m[1]), math.floor(period_m / band_m[0]) + 1)  # in-band bins
    if k[0] < 1 or k[-1] > n_samples // 2:
        raise ValueError(f"band {band_m} m not inside (2 dx, period) = ({2 * dx_m}, {period_m}) m")
    n = k / period_m  # cycle/m
    # one-sided PSD -> Fourier coefficient scale: variance Gd dn per bin, half in cos and half in sin
    amp = 0.5 * n_samples * np.sqrt(displacement_psd_m3(n, gd_n0_m3) / period_m)
    z = rng.standard_normal((3, 2, n.size))
    z = z[:, 0] + 1j * z[:, 1]  # unit variance in cos and in sin
    r1 = track_coherence(n, 0.5 * track_m)
    r2 = track_coherence(n, track_m)
    one_r1 = np.maximum(1.0 - r1 * r1, 0.0)
    q = np.divide(r2 - r1 * r1, one_r1, out=np.ones_like(n), where=one_r1 > 1e-12)
    q = np.clip(q, -1.0, 1.0)
    side = np.sqrt(one_r1)
    b, c = side * np.sqrt(0.5 * (1.0 + q)), side * np.sqrt(0.5 * (1.0 - q))
    coef = np.zeros((3, n_samples // 2 + 1), dtype=complex)
    coef[0, k] = amp * z[0]
    common = r1 * z[0] + b * z[1]
    coef[1, k] = amp * (common + c * z[2])
    coef[2, k] = amp * (common - c * z[2])
    return np.fft.irfft(coef, n=n_samples, axis=-1)


__all__ = [
    "BAND_M",
    "DX_M",
    "ISO_8608_GD_N0_M3",
    "ISO_8608_N0",
    "PERIOD_SAMPLES",
    "PHASE_SURFACE",
    "RUNWAY_CLASS",
    "SURFACES",
    "TAXIWAY_CLASS",
    "RunwayRoughness",
    "displacement_psd_m3",
    "synthesize_tracks",
    "track_coherence",
]
