"""A type's real-traffic performance figures and its JSBSim model's answer to them: the spreads of
OpenAP WRAP (Sun, Ellerbroek and Hoekstra, "WRAP: An open-source kinematic aircraft performance model",
Transportation Research Part C 98, 2019), the climb schedule and the takeoff thrust curve each flight
draws from (:mod:`flightmode.sim.flight.draws`)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class Spread:
    """A figure's real-traffic distribution as OpenAP WRAP gives it: mean, standard deviation and
    the [minimum, maximum] it reports (draws are clipped to that range)."""

    mean: float
    std: float
    lo: float
    hi: float

    def draw(self, rng) -> float:
        return float(min(self.hi, max(self.lo, rng.normal(self.mean, self.std))))


@dataclass(frozen=True, slots=True)
class ClimbSchedule:
    """The climb of a type in three bands, from OpenAP's WRAP kinematic model (Sun, Ellerbroek and
    Hoekstra, "WRAP: An open-source kinematic aircraft performance model", Transportation Research
    Part C 98, 2019, fitted on ADS-B): vertical rate below the constant-CAS crossover altitude
    (``climb_vs_pre_concas``), in the constant-CAS climb (``climb_vs_concas``) and in the constant-Mach
    climb (``climb_vs_conmach``), the crossover altitudes and the climb CAS. Each flight draws its
    three rates from these spreads."""

    vs_pre_cas: Spread  # m/s, up to cross_cas_m
    vs_cas: Spread  # m/s, cross_cas_m to cross_mach_m
    vs_mach: Spread  # m/s, above cross_mach_m
    cross_cas_m: float
    cross_mach_m: float
    cas_mps: float  # constant-CAS climb speed (above 10,000 ft)
    vs_initial: Spread  # m/s, liftoff to 1,500 ft (WRAP ``initclimb_vs``)


@dataclass(frozen=True, slots=True)
class TakeoffThrust:
    """How hard a type accelerates down the runway, and the throttle that gives it.

    ``accel`` is WRAP's takeoff acceleration (``takeoff_acceleration``: the mean from brake release to
    liftoff on real ADS-B traffic; Sun, Ellerbroek and Hoekstra 2019, as :class:`ClimbSchedule`); each
    flight draws its own from it (:mod:`flightmode.sim.flight.draws`). ``curve`` is the model's answer:
    (takeoff throttle, mean acceleration brake release to liftoff in m/s^2) measured on the JSBSim
    model at ``mass_kg`` and a field air density ``rho_kgm3``. At brake release the pilot turns the
    drawn acceleration into a throttle (:meth:`throttle_for`), as a crew's takeoff performance is
    computed for the actual weight and field: the acceleration is scaled to the curve's conditions by
    ``(mass / mass_kg) ** mass_exp`` (measured on each model with 4-20 t more fuel at 0.90 throttle;
    the A320's fitted on route flights) and by the density ratio (:data:`TAKEOFF_DENSITY_EXP`), then
    interpolated on the curve, clipped to its ends.

    The JSBSim models fly at their stock weights, without passengers: the 737 at 83,000 lb, the
    published operating empty weight of the 737-700 (37,648 kg); the Fokker 100 at 54,217 lb, within
    1 % of its published 24,375 kg; the A320 at 111,000 lb, 7.7 t above the A320ceo's typical 42.6 t
    (the manufacturers' figures as Wikipedia tabulates them); only the 787-8's model carries its
    passengers and cargo (22 t of point masses). With the real airline payload their
    approach speeds, already at the top of the real range, would rise further: measured on 12
    pattern flights each, 10.4 t more on the 737 (126 seats at IATA's 2019 82.6 % passenger load
    factor, 100 kg each) raised its median touchdown speed from 131 to 143 kt (and at the old speeds
    it stalled on approach, 3 of 12), 8.3 t more on the Fokker 100 from 152 to 156 kt. So a light
    aircraft at a deeper reduced thrust stands in for a loaded one at its usual flex thrust: the
    thrust-to-weight ratio, which sets the acceleration the accelerometer records, is the real one."""

    accel: Spread  # m/s^2, WRAP takeoff_acceleration
    curve: tuple[tuple[float, float], ...]  # (throttle, m/s^2), throttle increasing
    mass_kg: float  # the curve's mass at brake release
    rho_kgm3: float  # the curve's field air density
    mass_exp: float  # mean acceleration ~ mass ** -mass_exp near the curve's mass

    def throttle_for(
        self, accel_mps2: float, mass_kg: float | None = None, rho_kgm3: float | None = None
    ) -> float:
        """The throttle that gives a mean acceleration ``accel_mps2`` brake release to liftoff at this
        mass and field density (the curve's when None)."""
        import numpy as np

        a = accel_mps2
        if mass_kg is not None:
            a *= (mass_kg / self.mass_kg) ** self.mass_exp
        if rho_kgm3 is not None:
            a *= (self.rho_kgm3 / rho_kgm3) ** TAKEOFF_DENSITY_EXP
        thr, acc = zip(*self.curve)
        return float(np.interp(a, acc, thr))


# the mean takeoff acceleration scales with the field's air density to this power: measured on the
# pattern flown at 10 and 900 m field elevation (density 1.224 and 1.122 kg/m^3) at 0.90 throttle:
# A320 1.05, 737 0.91, Fokker 100 0.90 (the engines' thrust lapse with density)
TAKEOFF_DENSITY_EXP = 0.95
