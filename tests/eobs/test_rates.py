"""The e-obs per-axis sampling frequencies are the note's values (seed 003 sections 4.1, 4.2, 10).

The note prints no table of rate settings. What it says, quoted:
  4.1: "you want to get 10 acceleration samples per second or more (10 is the minimum sampling rate
       that you can choose)" and "at a sample rate of 10 Hz ... you would get about 1 Million samples
       per day" (864,000: all axes together);
  4.2: "if you have three ACC axes enabled, then the sampling frequency for all axes together is
       three times the sampling frequency for one axis";
  10:  "Set the total sample rate to 100 Hz (33 Hz per axis)".
So the note's total rates are 10 and 100 Hz, and per axis, for 1, 2 or 3 enabled axes:
       total 10 Hz  -> 10, 5, 3.33 Hz;     total 100 Hz -> 100, 50, 33.33 Hz.
"""

from __future__ import annotations

import pytest

from flightmode.errors import SensorError
from flightmode.sim.sensor.accelerometer import (
    EOBS_PER_AXIS_RATES_HZ,
    EOBS_TOTAL_RATES_HZ,
    PRESETS,
    eobs_preset,
)

NOTE_TABLE_PER_AXIS_HZ = {10.0: (10.0, 5.0, 3.33), 100.0: (100.0, 50.0, 33.33)}  # total -> 1, 2, 3 axes


def test_the_rate_table_is_the_notes():
    assert EOBS_TOTAL_RATES_HZ == (10.0, 100.0)
    assert set(EOBS_PER_AXIS_RATES_HZ) == {f for row in NOTE_TABLE_PER_AXIS_HZ.values() for f in row}
    assert len(EOBS_PER_AXIS_RATES_HZ) == 6 and list(EOBS_PER_AXIS_RATES_HZ) == sorted(EOBS_PER_AXIS_RATES_HZ)
    # every per-axis value is a total over 1-3 axes, written to two decimals (33 Hz in the note)
    for total, row in NOTE_TABLE_PER_AXIS_HZ.items():
        assert [round(total / n, 2) for n in (1, 2, 3)] == list(row)
    assert PRESETS["eobs"].allowed_odr_hz == EOBS_PER_AXIS_RATES_HZ


def test_three_point_three_three_hz_is_accepted_and_one_or_two_hz_refused():
    p = eobs_preset(acc_interval_s=60.0, byte_count=442, odr_per_axis_hz=3.33, n_axes=3)
    assert p.odr_hz == 3.33 and p.burst_samples == 110  # 330 samples (section 9) over 3 axes
    for f in (1.0, 2.0, 20.0, 25.0):
        with pytest.raises(
            SensorError, match=rf"{f:g} Hz is not one the part has; allowed: 3.33, 5, 10, 33.33, 50, 100"
        ):
            eobs_preset(acc_interval_s=60.0, byte_count=442, odr_per_axis_hz=f)
