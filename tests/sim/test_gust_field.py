"""The Dryden gust field's arithmetic (sim.flight.turbulence.GustField)."""

from __future__ import annotations

import math

import numpy as np
from scipy.signal import lfilter

from flightmode.sim.flight.turbulence import Atmosphere, GustField, _first_order_filter, dryden_parameters
from flightmode.units import FT_M


def test_the_first_order_filter_is_lfilters_output_bit_for_bit():
    # the gusts of every flight go through it: a SciPy whose core stopped matching lfilter would move
    # every flight without a word, so equality is exact, not within a tolerance
    rng = np.random.default_rng(11)
    filt = _first_order_filter()
    for _ in range(200):
        b0, a1, z0 = rng.uniform(0.0, 2.0), rng.uniform(0.9, 1.0), rng.normal()
        x = rng.standard_normal(int(rng.integers(1, 300)))
        assert np.array_equal(filt(b0, a1, x, z0), lfilter([b0], [1.0, -a1], x, zi=[z0])[0])


def test_block_fps_is_the_block_in_feet_per_second_bit_for_bit():
    atm = Atmosphere(w20_mps=6.0, edr_mid=0.03, edr_upper=0.05, w_star_mps=1.5, z_i_m=1200.0)
    a, b = GustField(120.0, np.random.default_rng(5)), GustField(120.0, np.random.default_rng(5))
    rng = np.random.default_rng(6)
    for _ in range(50):
        h_m, tas_mps = rng.uniform(0.0, 12_000.0), rng.uniform(0.0, 260.0)
        heading_rad = rng.uniform(-4.0, 4.0)
        args = (h_m, tas_mps, heading_rad, rng.uniform(0.0, 3.0), atm)
        assert (a.block(*args).T / FT_M).tolist() == list(b.block_fps(*args))


def test_the_gusts_have_the_dryden_intensity_and_the_vertical_gust_its_time_scale():
    # MIL-F-8785C above 2000 ft: L = 1750 ft, sigma_u = sigma_v = sigma_w. The AR(1) forms' stationary
    # variance is b^2 / (1 - a^2) = sigma^2 / (1 - T / (2 tau)) for u (sigma^2 / (1 - T / tau) for v, w):
    # within 0.1 % of sigma^2 at T / tau = 1/320 here
    sigma, tas, heading = 1.5, 200.0, 0.7
    field = GustField(120.0, np.random.default_rng(2))
    atm = Atmosphere(w20_mps=5.0, edr_mid=0.05, edr_upper=0.05)
    g = np.concatenate([field.block(3000.0, tas, heading, sigma, atm) for _ in range(3000)])  # 3000 s
    c, s = math.cos(heading), math.sin(heading)
    u, v = c * g[:, 0] + s * g[:, 1], -s * g[:, 0] + c * g[:, 1]  # back to along and across the heading
    lu, lw, su, sw = dryden_parameters(3000.0, sigma, 5.0)
    tau_s = lw / tas  # 2.67 s: 3000 s hold about 560 independent spans of 2 tau, so a variance estimate
    # scatters by sqrt(2 / 560) = 6 % (1 sigma); 20 % is over 3 sigma
    for comp, want in ((u, su), (v, su), (g[:, 2], sw)):
        assert abs(np.var(comp) / want**2 - 1.0) < 0.2
    # the vertical gust's autocorrelation at one time constant: exp(-2) for the w form (a = 1 - 2 T / tau)
    w = g[:, 2] - g[:, 2].mean()
    lag = round(tau_s * 120.0)
    rho = float(np.dot(w[:-lag], w[lag:]) / np.dot(w, w))
    # Bartlett's formula for an AR(1) sample autocorrelation: var ~ 2 / (N (1 - a^2)),
    # 2 / (360,000 x 0.0125): a scatter of 0.021, and 0.08 is about 4 of it
    assert abs(rho - math.exp(-2.0)) < 0.08
