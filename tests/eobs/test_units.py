"""Seed 003's units (issue 53 item 3): raw counts to m/s^2 exactly as section 6 writes it, with the
note's g = 9.81 beside scipy.constants.g; section 10's 1197 against section 9's table."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.constants

from flightmode.eobs.calibration import EOBS_G_MPS2, Calibration, to_g, to_mps2
from flightmode.sim.sensor.accelerometer import eobs_burst

# section 6's nominal constants for a tag numbered > 2241 (the file does not give its tag number;
# Movebank's individual id 4266-84831108 is not one)
NOMINAL_NEW = Calibration((2048.0,) * 3, (0.0022,) * 3, nominal=True)


def test_the_notes_g_beside_standard_gravity():
    assert EOBS_G_MPS2 == 9.81  # seed 003 section 6's table
    assert scipy.constants.g == 9.80665
    assert (EOBS_G_MPS2 - scipy.constants.g) / scipy.constants.g == pytest.approx(3.4e-4, abs=0.05e-4)


def test_first_albatross_burst_in_mps2_against_a_hand_computation(real_movebank):
    from flightmode.eobs.movebank import read_movebank

    burst = next(r.burst for r in read_movebank(real_movebank).rows if r.burst is not None)
    assert burst.axes == "XY" and burst.raw.shape == (60, 2)  # 120 interleaved counts, X Y X Y ...
    assert burst.raw[0].tolist() == [1856, 1900]  # the file's first two counts
    a = to_mps2(burst, NOMINAL_NEW)
    # by hand, section 6: (1856 - 2048) x 0.0022 x 9.81 = -192 x 0.021582 = -4.143744 m/s^2;
    # (1900 - 2048) x 0.021582 = -3.194136; second sample (1816, 1931): -5.007024, -2.525094
    assert a.acc_mps2[:2].ravel().tolist() == pytest.approx(
        [-4.143744, -3.194136, -5.007024, -2.525094], abs=1e-12
    )
    assert a.g_mps2 == 9.81 and a.nominal
    # the whole burst: exactly section 6's product, and to_g times g
    assert np.array_equal(a.acc_mps2, (burst.raw - 2048.0) * 0.0022 * 9.81)
    b = to_mps2(burst, NOMINAL_NEW, g_mps2=scipy.constants.g)
    assert np.allclose(b.acc_mps2, to_g(burst, NOMINAL_NEW).acc_g * scipy.constants.g, rtol=1e-15, atol=0)


def test_section10s_1197_and_the_tables_1135_give_the_same_burst():
    # section 9's table: from 1135 up (rv5) the burst is 1188 data bytes, 792 samples in all; section 10
    # names 1197 as the effective maximum: the same burst, one row earlier (1134) is shorter
    assert eobs_burst(1197, 3)[:2] == eobs_burst(1135, 3)[:2] == (264, 1188)
    assert eobs_burst(1134, 3)[1] == 1125
    assert (
        eobs_burst(756, 3, newer_firmware=False)[:2]
        == eobs_burst(694, 3, newer_firmware=False)[:2]
        == (166, 747)
    )
