"""The convective mixed layer added to the Dryden field (sim.flight.turbulence)."""

from __future__ import annotations

import numpy as np
import pytest

from flightmode.sim.flight.turbulence import convective_sigmas, draw_atmosphere, dryden_parameters


def test_the_convective_sigma_w_profile_has_lenschows_shape():
    """Lenschow, Wyngaard and Pennell (1980) eq. 3: sigma_w / w* = sqrt(1.8) (z/z_i)^(1/3) (1 - 0.8 z/z_i),
    largest (0.68) at z/z_i = 0.31 (d/dx of x^(1/3) (1 - 0.8 x) vanishes at x = 1/3.2), zero at the ground
    and above the mixed layer; sigma_u = 0.6 w* throughout it (Stull 1988)."""
    z_i = 1200.0
    x = np.linspace(0.001, 0.999, 999)
    sw = np.array([convective_sigmas(v * z_i, 2.0, z_i)[1] for v in x]) / 2.0
    assert x[np.argmax(sw)] == pytest.approx(1 / 3.2, abs=2e-3)
    assert sw.max() == pytest.approx(np.sqrt(1.8) * (1 / 3.2) ** (1 / 3) * (1 - 0.8 / 3.2), rel=1e-6)
    assert convective_sigmas(0.0, 2.0, z_i)[1] == 0.0
    assert convective_sigmas(z_i + 1.0, 2.0, z_i) == (0.0, 0.0)
    assert convective_sigmas(300.0, 2.0, z_i)[0] == pytest.approx(1.2)


def test_convective_and_mechanical_variances_add():
    lu, lw, su, sw = dryden_parameters(150.0, 0.6, 4.5)
    lu2, lw2, su2, sw2 = dryden_parameters(150.0, 0.6, 4.5, 1.5, 1000.0)
    cu, cw = convective_sigmas(150.0, 1.5, 1000.0)
    assert (lu2, lw2) == (lu, lw)  # the scale lengths stay MIL-F-8785C's
    assert su2**2 == pytest.approx(su**2 + cu**2, rel=1e-12)
    assert sw2**2 == pytest.approx(sw**2 + cw**2, rel=1e-12)


def test_the_convective_draws_come_last_and_move_no_other_draw():
    """Fixing w* (a scenario's convective_velocity_mps) changes only w*: the surface wind, background EDRs
    and the mixed-layer depth are the same draws."""
    a = draw_atmosphere(np.random.default_rng(7))
    b = draw_atmosphere(np.random.default_rng(7), w_star_mps=0.0)
    assert (a.w20_mps, a.edr_mid, a.edr_upper, a.z_i_m) == (b.w20_mps, b.edr_mid, b.edr_upper, b.z_i_m)
    assert b.w_star_mps == 0.0 and 0.0 <= a.w_star_mps <= 2.0 and 500.0 <= a.z_i_m <= 2000.0


def test_the_low_to_high_ratio_compares_the_roughest_low_air_with_the_background():
    """validate judges "boundary layer rougher than calm cruise" only where the drawn field is
    (low_to_high_sigma_w_ratio >= 1). Its numerator is the low air's roughest sigma_w, MIL-F-8785C's
    0.1 W20 (below 1000 ft) combined in quadrature with the convective peak (found here by brute force
    over heights), an upper estimate between 1000 and 2000 ft where the mechanical part blends towards
    the background; its denominator the background's 9.1 EDR (EDR_TO_SIGMA_W)."""
    from flightmode.sim.flight.turbulence import EDR_TO_SIGMA_W, low_to_high_sigma_w_ratio

    assert EDR_TO_SIGMA_W == pytest.approx(9.1, abs=0.05)
    # no sun: 0.1 x 10 m/s against 9.1 x 0.05 = 0.456 m/s
    want = 1.0 / (EDR_TO_SIGMA_W * 0.05)
    assert low_to_high_sigma_w_ratio(10.0, 0.0, 0.05) == pytest.approx(want, rel=1e-12)
    z_i = 1500.0
    peak = max(convective_sigmas(z, 1.5, z_i)[1] for z in np.linspace(1.0, z_i - 1.0, 20001))
    want = np.hypot(0.3, peak) / (EDR_TO_SIGMA_W * 0.06)
    assert low_to_high_sigma_w_ratio(3.0, 1.5, 0.06) == pytest.approx(want, rel=1e-6)
    # the built-ins' seed-1 day (W20 1.0 m/s, w* 0.34 m/s, EDR 0.059) is calmer low than aloft
    assert low_to_high_sigma_w_ratio(1.02, 0.34, 0.059) < 1.0
