"""The path from the floor to the sensor: where the bag rests (the support) and what surrounds the
sensor inside it (the packing), each a spring-damper stage per axis whose natural frequencies and
damping are drawn per flight from the ranges below (:func:`draw_mounts`), and the cabin row whose
floor it rests on.

Each stage is a base-excited single-degree-of-freedom system per axis (x fore-aft, y lateral, z
vertical, aircraft axes): H(s) = (2 zeta wn s + wn^2) / (s^2 + 2 zeta wn s + wn^2), unity at 0 Hz (the
bag feels the floor's steady specific force), resonant near fn, falling as 2 zeta fn / f far above
it. The two stages are taken in series and uncoupled (the sensor is light against the bag, the bag
against the seat or floor). A stage isolates the 10-30 Hz airframe vibration (seed 000, Fig. 6)
only when its fn is well below it: this is how a handbag on a soft seat lets the horizontal axes, and
even the vertical one, go quiet in flight, as seed 000's flights 1 and 2 did (Tables 4-5).

Natural frequencies. For a bag resting under gravity on a linear spring, fn = (1 / 2 pi) sqrt(g /
delta), delta its static deflection (any vibration handbook, e.g. Harris and Piersol, "Shock and
Vibration Handbook", 5th ed., 2002, ch. 2). Horizontal stiffness of foam-like supports: for open-cell
foams the shear modulus is about 3/8 of Young's (Gibson and Ashby, "Cellular Solids", 2nd ed., 1997,
ch. 5), so a block resting on foam has fn_h about sqrt(3/8) = 0.6 fn_v. Every range below is a
flightmode assumption unless a source is named; the seat's and the packing's were set so that seed
000's two flights (Tables 4 and 5) are reproduced to within a decade per cell by the built-in
scenarios gva-lhr-a320 and hel-zrh-f100-calm (tests/sim/test_vibration_variability.py):

- ``under_seat``: a bag on the cabin floor's carpet. Vertical 30-60 Hz (a static deflection of
  0.07-0.28 mm of carpet pile under a few kilograms); horizontal 15-30 Hz (friction-held, the pile in
  shear: about 0.5 fn_v); damping ratio 0.1-0.2. Nearly rigid in the 10-30 Hz band.
- ``seat``: a bag on a passenger seat's foam cushion, the soft surface of seed 000's flight 2.
  Vertical 3.0-4.5 Hz (a deflection of 1.2-2.8 cm into the cushion); horizontal 5-7 Hz, stiffer than
  the foam alone would be (0.6 fn_v) because the seat's back and armrests and the cover's friction
  hold the bag; damping ratio 0.1-0.2 (polyurethane foam loss factors of 0.2-0.4, assumption).
- ``lap``: on a seated passenger's thighs. Vertical 4-6 Hz: the seated human body's principal
  vertical resonance (ISO 5982:2001, apparent mass; Griffin, "Handbook of Human Vibration", 1990,
  ch. 8); horizontal 1.5-3 Hz and damping 0.3-0.5 (assumptions). The passenger's own movement
  (breathing, fidgeting) is not modelled: a bag on a lap is quieter here than it would be.
- ``overhead_bin``: on the bin's moulded floor: vertical 20-40 Hz, horizontal 15-30 Hz, damping
  0.05-0.15 (assumptions).
- ``hold``: on the hold floor or a container's (unit load device): vertical 25-50 Hz, horizontal
  20-40 Hz, damping 0.05-0.15 (assumptions).

Packings (the sensor inside the bag):

- ``soft`` (a handbag, the sensor among soft contents): vertical 12-25 Hz (0.4-1.7 mm of sinking into
  the contents), horizontal 8-16 Hz (about 0.65 fn_v, the foam ratio above), damping 0.3-0.5
  (textiles are heavily damped: assumption);
- ``rigid`` (a hard-shell case, the tracker clipped inside): vertical 40-80 Hz, horizontal 30-60 Hz,
  damping 0.05-0.1 (assumptions);
- ``boxed`` (a parcel: the tracker cushioned in a corrugated box, in a container): vertical 20-40
  Hz, horizontal 15-30 Hz, damping 0.1-0.3 (assumptions: a cushion designed to resonate above a
  road vehicle's 1-15 Hz band resonates inside the airframe's 10-30 Hz one, and amplifies it).

The seat's and the lap's ranges decide the certification verdict (most false statics are bags on
them at the ground holds) and rest on assumptions: each is scaled by a declared uncertain factor
(:data:`UNCERTAIN`: ``mount.seat.fn_v_scale``, ``fn_h_scale``, ``zeta_scale`` and the lap's; 1 is the
range above), which a scenario's ``[model]`` table overrides (:func:`support_stage`).

The cabin row (``front``, ``mid``, ``rear``) sets the floor's vibration level
(:data:`flightmode.sim.sensor.vibration.LOCATION_LEVEL`); it is drawn uniformly unless the carrier
fixes it; a bag in the hold is in the hold.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from flightmode.uncertain import Uncertain, value_of

if TYPE_CHECKING:
    from flightmode.sim.sensor.carrier import CarrierSpec


@dataclass(frozen=True, slots=True)
class Stage:
    """The distribution of one spring-damper stage between the floor and the sensor (base excitation,
    per axis; x and y horizontal, z vertical in the aircraft's axes): its horizontal natural
    frequencies (uniform in ``fn_h_hz``, drawn for x and y apart), its vertical one (uniform in
    ``fn_v_hz``) and its damping ratio per axis (uniform in ``zeta``)."""

    fn_h_hz: tuple[float, float]
    fn_v_hz: tuple[float, float]
    zeta: tuple[float, float]


@dataclass(frozen=True, slots=True)
class Support:
    """Where the bag rests on board: its spring-damper stage, the Rayleigh scale (deg) of the tilt
    from level of a handbag set down on it, and what it is."""

    stage: Stage
    tilt_deg: float
    doc: str


PLACEMENTS = {  # the supports (module docstring)
    "under_seat": Support(
        Stage((15.0, 30.0), (30.0, 60.0), (0.1, 0.2)),
        3.0,
        "on the cabin floor's carpet, under the seat in front",
    ),
    "seat": Support(
        Stage((5.0, 7.0), (3.0, 4.5), (0.1, 0.2)), 5.0, "on a passenger seat's foam cushion (a soft surface)"
    ),
    "overhead_bin": Support(
        Stage((15.0, 30.0), (20.0, 40.0), (0.05, 0.15)), 3.0, "on the overhead bin's moulded floor"
    ),
    "lap": Support(Stage((1.5, 3.0), (4.0, 6.0), (0.3, 0.5)), 8.0, "on a seated passenger's lap"),
    "hold": Support(
        Stage((20.0, 40.0), (25.0, 50.0), (0.05, 0.15)), 3.0, "on the hold floor, or a container's"
    ),
}
PACKINGS = {  # the bag around the sensor (module docstring)
    "soft": Stage((8.0, 16.0), (12.0, 25.0), (0.3, 0.5)),
    "rigid": Stage((30.0, 60.0), (40.0, 80.0), (0.05, 0.1)),
    "boxed": Stage((15.0, 30.0), (20.0, 40.0), (0.1, 0.3)),
}
CABIN_ROWS = ("front", "mid", "rear")

# ---------------------------------------------------------------------- uncertain parameters
# The soft supports' ranges above are assumptions, and they decide the verdict: most false statics of
# a population are bags on a seat cushion or a lap at the pushback and taxi holds. Each range is
# scaled by a factor (1: the range above) declared here, so that a study can move it
# (flightmode.uncertain; `flightmode certify --uncertainty`). A factor multiplies both ends of the
# range, so the flight's draw moves with it (the same uniform number, a scaled range).
SEAT_FN_V_SCALE = Uncertain(
    "mount.seat.fn_v_scale",
    1.0,
    0.67,
    3.8,
    "1",
    "assumption: fn = sqrt(g / delta) / 2 pi (Harris and Piersol, ch. 2); the 3.0-4.5 Hz above is a "
    "deep 1.2-2.8 cm sinking; a light bag (1-3 kg) on a firm airline cushion sinks 1-5 mm, "
    "7-16 Hz (x 3.8: 11-17 Hz); x 0.67: 2.8-6 cm into a soft one",
    "a bag on a seat cushion: the vertical resonance (3.0-4.5 Hz times this)",
)
SEAT_FN_H_SCALE = Uncertain(
    "mount.seat.fn_h_scale",
    1.0,
    0.6,
    2.5,
    "1",
    "assumption: foam shear gives fn_h about 0.6 fn_v (Gibson and Ashby, ch. 5), so a 3.8 x firmer "
    "cushion could hold the bag at up to 2.5 x the 5-7 Hz above; x 0.6: the foam alone, no friction",
    "a bag on a seat cushion: the horizontal resonances (5-7 Hz times this)",
)
SEAT_ZETA_SCALE = Uncertain(
    "mount.seat.zeta_scale",
    1.0,
    0.5,
    2.0,
    "1",
    "assumption: polyurethane foam loss factors 0.2-0.4 (zeta 0.1-0.2 above), halved or doubled",
    "a bag on a seat cushion: the damping of its resonances (0.1-0.2 times this)",
)
LAP_FN_V_SCALE = Uncertain(
    "mount.lap.fn_v_scale",
    1.0,
    0.75,
    2.0,
    "1",
    "assumption: the 4-6 Hz above is the seated body's resonance (ISO 5982:2001; Griffin 1990, ch. 8) "
    "for a body-sized mass; a light bag on the thighs' soft tissue alone sits higher, up to 8-12 Hz",
    "a bag on a lap: the vertical resonance (4-6 Hz times this)",
)
LAP_FN_H_SCALE = Uncertain(
    "mount.lap.fn_h_scale",
    1.0,
    0.5,
    2.0,
    "1",
    "assumption: no source for the 1.5-3 Hz above; halved or doubled",
    "a bag on a lap: the horizontal resonances (1.5-3 Hz times this)",
)
LAP_ZETA_SCALE = Uncertain(
    "mount.lap.zeta_scale",
    1.0,
    0.5,
    2.0,
    "1",
    "assumption: the 0.3-0.5 above (soft tissue is heavily damped), halved or doubled (at most 1)",
    "a bag on a lap: the damping of its resonances (0.3-0.5 times this)",
)
UNCERTAIN = (
    SEAT_FN_V_SCALE,
    SEAT_FN_H_SCALE,
    SEAT_ZETA_SCALE,
    LAP_FN_V_SCALE,
    LAP_FN_H_SCALE,
    LAP_ZETA_SCALE,
)
SCALED_SUPPORTS = {  # placement -> its (fn_h, fn_v, zeta) scale factors
    "seat": (SEAT_FN_H_SCALE, SEAT_FN_V_SCALE, SEAT_ZETA_SCALE),
    "lap": (LAP_FN_H_SCALE, LAP_FN_V_SCALE, LAP_ZETA_SCALE),
}


def support_stage(placement: str, overrides: Mapping[str, float] | None = None) -> Stage:
    """The support's stage at ``placement`` with the run's ``overrides`` of its scale factors
    (:data:`SCALED_SUPPORTS`; nominal: :data:`PLACEMENTS`' ranges, bit for bit). A damping ratio
    is capped at 1 (critical)."""
    st = PLACEMENTS[placement].stage
    if placement not in SCALED_SUPPORTS:
        return st
    kh, kv, kz = (value_of(p, overrides) for p in SCALED_SUPPORTS[placement])
    return Stage(
        (st.fn_h_hz[0] * kh, st.fn_h_hz[1] * kh),
        (st.fn_v_hz[0] * kv, st.fn_v_hz[1] * kv),
        (min(1.0, st.zeta[0] * kz), min(1.0, st.zeta[1] * kz)),
    )


@dataclass(frozen=True, slots=True)
class MountDraw:
    """One flight's draw of the path from the floor to the sensor at one placement: the support and
    the packing stages' natural frequencies and damping ratios (rows support, packing; columns the
    aircraft's axes x, y, z), the cabin row (``hold`` in the hold) and the packing."""

    fn_hz: np.ndarray  # (2, 3)
    zeta: np.ndarray  # (2, 3)
    cabin_row: str
    packing: str

    def as_dict(self) -> dict:
        return {
            "fn_hz": self.fn_hz.tolist(),
            "zeta": self.zeta.tolist(),
            "cabin_row": self.cabin_row,
            "packing": self.packing,
        }


def draw_stage(stage: Stage, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """(fn x, y, z in Hz, zeta x, y, z) of one stage. Draws: fn_h x, fn_h y, fn_v, then three dampings."""
    fh = rng.uniform(*stage.fn_h_hz, 2)
    fv = rng.uniform(*stage.fn_v_hz)
    zeta = rng.uniform(*stage.zeta, 3)
    return np.array([fh[0], fh[1], fv]), zeta


def draw_mount(
    spec: CarrierSpec, rng: np.random.Generator, overrides: Mapping[str, float] | None = None
) -> MountDraw:
    """The mount at the carrier's ``placement``. Draws, in this order: the support's stage
    (:func:`support_stage`, with the run's ``overrides``), the packing's (:func:`draw_stage` each),
    the cabin row (uniform over :data:`CABIN_ROWS`; replaced by the carrier's ``cabin_row`` when it
    fixes one, by ``hold`` in the hold)."""
    f1, z1 = draw_stage(support_stage(spec.placement, overrides), rng)
    f2, z2 = draw_stage(PACKINGS[spec.packing_name], rng)
    row = CABIN_ROWS[int(rng.integers(0, len(CABIN_ROWS)))]
    if spec.placement == "hold":
        row = "hold"
    elif spec.cabin_row is not None:
        row = spec.cabin_row
    return MountDraw(np.vstack([f1, f2]), np.vstack([z1, z2]), row, spec.packing_name)


def draw_mounts(
    spec: CarrierSpec, rng: np.random.Generator, overrides: Mapping[str, float] | None = None
) -> dict[str, MountDraw]:
    """The mount of every placement the bag rests on in the flight: :func:`draw_mount` at its
    ``placement``, then, for a ``cruise_placement``, that support's stage (drawn last, so that adding
    it moves no other draw) with the same packing and cabin row (the same bag, at the same seat).
    ``overrides``: the run's uncertain parameters (:data:`UNCERTAIN`)."""
    m = draw_mount(spec, rng, overrides)
    out = {spec.placement: m}
    cp = spec.cruise_placement
    if cp is not None and cp != spec.placement:
        f1, z1 = draw_stage(support_stage(cp, overrides), rng)
        out[cp] = MountDraw(np.vstack([f1, m.fn_hz[1]]), np.vstack([z1, m.zeta[1]]), m.cabin_row, m.packing)
    return out


def stage_gain(fn_hz, zeta, f_hz) -> np.ndarray:
    """|H(j 2 pi f)| of one stage (the module docstring's H): the continuous-time transmissibility."""
    r = np.asarray(f_hz, float) / np.asarray(fn_hz, float)
    two_zr = 2.0 * np.asarray(zeta, float) * r
    return np.sqrt((1.0 + two_zr**2) / ((1.0 - r * r) ** 2 + two_zr**2))


def mount_sos(mount: MountDraw, fs_hz: float) -> list[np.ndarray]:
    """Per-axis transmissibility of the mount's two stages in series as SOS at ``fs_hz`` (bilinear
    transform), one (2, 6) array per axis x, y, z."""
    from scipy.signal import bilinear, tf2sos

    out = []
    for ax in range(3):
        secs = []
        for st in range(2):
            wn = 2 * np.pi * float(mount.fn_hz[st, ax])
            zeta = float(mount.zeta[st, ax])
            b, a = bilinear([2 * zeta * wn, wn * wn], [1.0, 2 * zeta * wn, wn * wn], fs=fs_hz)
            secs.append(tf2sos(b, a))
        out.append(np.vstack(secs))
    return out


__all__ = [
    "CABIN_ROWS",
    "PACKINGS",
    "PLACEMENTS",
    "SCALED_SUPPORTS",
    "UNCERTAIN",
    "MountDraw",
    "Stage",
    "Support",
    "draw_mount",
    "draw_mounts",
    "draw_stage",
    "mount_sos",
    "stage_gain",
    "support_stage",
]
