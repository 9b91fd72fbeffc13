"""Six-orientation calibration (seed 003 section 7), tag generations (sections 2, 6), counts to g."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from flightmode.eobs.burst import AccBurst
from flightmode.eobs.calibration import (
    Calibration,
    NominalCalibrationWarning,
    calibrate,
    calibration_to_toml,
    nominal_calibration,
    read_calibration,
    recordings_from_orientations,
    to_g,
    write_calibration,
)
from flightmode.eobs.simulate import draw_unit, orientation_recordings, unit_spread
from flightmode.eobs.tag import is_old_tag, nominal_slope_g_per_count
from flightmode.errors import InputDataError, SensorError
from flightmode.sim.sensor.accelerometer import PRESETS


def test_the_notes_worked_example():
    """Section 7: n_X,-1g = 1345 and n_X,+1g = 2255 give n_X,zerog = (1345 + 2255) / 2 = 1800 and
    c_X = 2 / (2255 - 1345) = 0.0022 (the note rounds 2/910 = 0.0021978 to two figures)."""
    rec = {k: np.full((50, 3), 2048) for k in ("+x", "-x", "+y", "-y", "+z", "-z")}
    rec["-x"] = np.tile([1345, 2048, 2048], (50, 1))
    rec["+x"] = np.tile([2255, 2048, 2048], (50, 1))
    rec["-y"], rec["+y"] = np.tile([2048, 1593, 2048], (50, 1)), np.tile([2048, 2503, 2048], (50, 1))
    rec["-z"], rec["+z"] = np.tile([2048, 2048, 1593], (50, 1)), np.tile([2048, 2048, 2503], (50, 1))
    cal = calibrate(rec)
    assert cal.zero_count[0] == 1800.0
    assert cal.slope_g_per_count[0] == 2 / 910 and cal.slope_g_per_count[0] == pytest.approx(0.0022, abs=5e-5)


def test_chapter_three_ideal_readings():
    """Section 3's images for the new tags: (x, y, z) = (2048, 2048, 1593) for a_z = -1 g, (2048, 2048,
    2503) for +1 g, (1593, 2048, 2048), (2503, 2048, 2048), (2048, 2503, 2048), (2048, 1593, 2048):
    a noise-free nominal unit in orientations A-F."""
    unit = nominal_calibration(2242)
    rec = orientation_recordings(unit, np.random.default_rng(0), 1, noise_g=0.0)
    got = {k: tuple(v[0]) for k, v in rec.items()}
    assert got == {
        "A": (2048, 2048, 1593),
        "B": (2048, 2048, 2503),
        "C": (1593, 2048, 2048),
        "D": (2503, 2048, 2048),
        "E": (2048, 2503, 2048),
        "F": (2048, 1593, 2048),
    }


def test_tag_generations_by_number():
    # section 6: 0.001 / 0.0027 "only for Tags up to number 2241"; 0.0022 "with number greater than 2241"
    assert is_old_tag(2241) and not is_old_tag(2242)
    assert nominal_slope_g_per_count(2241, "high") == 0.001 and nominal_slope_g_per_count(1, "low") == 0.0027
    assert nominal_slope_g_per_count(2242) == 0.0022
    with pytest.raises(SensorError, match=r"tag 2241 \(<= 2241\) has a sensitivity setting"):
        nominal_slope_g_per_count(2241)
    with pytest.raises(SensorError, match=r"did you mean \"low\""):
        nominal_slope_g_per_count(2000, "lo")
    with pytest.raises(SensorError, match="fixed sensitivity"):
        nominal_slope_g_per_count(2242, "low")


@pytest.mark.parametrize("tag, sensitivity", [(2242, None), (4000, None), (1500, "low"), (12, "high")])
def test_calibration_recovers_drawn_constants_within_the_noise(tag, sensitivity):
    """Six static recordings of n = 200 samples (20 s at 10 Hz) of a unit drawn around the nominal
    constants. Per recording the mean count has sigma_m = sqrt(s^2 + 1/12) / sqrt(n), s = noise / c in
    counts and 1/12 the rounding's variance (Sheppard; the rounding acts as uniform noise because s >=
    0.35 count here: 1 mg at 0.0027 x 1.05 g/count); then sigma(zero) = sigma_m / sqrt(2) and
    sigma(c)/c = sqrt(2) sigma_m c / 2. The rounding also biases a mean by at most b = (1/pi)
    exp(-2 pi^2 s^2) (the first term of the rounding error's Fourier series): 0.028 count at s = 0.35,
    1e-9 at s = 1; so the zero by at most b and c by at most b c relatively (2 b over the span 2 / c).
    Tolerance: 5 sigma plus that bias, per axis; the draws of these seeds lie within 2.6 sigma."""
    rng = np.random.default_rng(tag)
    noise_g = PRESETS["eobs"].noise_g  # 1 mg: flightmode's assumption; the note gives no noise figure
    n = 200
    for _ in range(5):
        unit = draw_unit(tag, rng, sensitivity)
        dz, dc = unit_spread()
        c0 = nominal_slope_g_per_count(tag, sensitivity)
        assert np.all(np.abs(np.array(unit.zero_count) - 2048) <= dz)
        assert np.all(np.abs(np.array(unit.slope_g_per_count) / c0 - 1) <= dc)
        cal = calibrate(recordings_from_orientations(orientation_recordings(unit, rng, n, noise_g), tag), tag)
        for j in range(3):
            c = unit.slope_g_per_count[j]
            s = noise_g / c
            bias = np.exp(-2 * np.pi**2 * s**2) / np.pi
            sigma_m = np.sqrt(s**2 + 1 / 12) / np.sqrt(n)
            assert abs(cal.zero_count[j] - unit.zero_count[j]) <= 5 * sigma_m / np.sqrt(2) + bias
            assert abs(cal.slope_g_per_count[j] / c - 1) <= 5 * np.sqrt(2) * sigma_m * c / 2 + bias * c


def test_old_tags_y_axis_is_reversed():
    """Sections 2 and 7: tags up to 2241 have the Y axis the other way: in orientation E (new tags'
    Y +1 g) an old tag's Y reads -1 g. Mapping A-F with the tag number undoes it; mapping an old
    tag's recordings as a new tag's is caught."""
    rng = np.random.default_rng(9)
    unit = draw_unit(1000, rng, "low")
    rec = orientation_recordings(unit, rng, 50, 1e-3)
    assert rec["E"][:, 1].mean() < unit.zero_count[1] < rec["F"][:, 1].mean()
    with pytest.raises(SensorError, match=r"calibration Y: the \+1 g mean .*tags up to 2241 have Y reversed"):
        calibrate(recordings_from_orientations(rec, 3000))
    cal = calibrate(recordings_from_orientations(rec, 1000), 1000)
    b = AccBurst("1000", np.datetime64("2014-05-11"), "XYZ", 10.0, rec["E"], 0)
    own = to_g(b, cal).acc_g.mean(axis=0)
    rh = to_g(b, cal, frame="right-handed").acc_g.mean(axis=0)
    # Y: -1 g to float rounding (E is one of the two recordings its constants come from); X, Z: the
    # mean of E's 50 samples (sigma 0.066 count, as in the test above) against a zero-g count of 100
    # other samples: 0.08 count = 0.22 mg at 0.0027 g/count at 1 sigma; atol 1 mg is 4.5 sigma
    np.testing.assert_allclose(own, [0, -1, 0], atol=1e-3)
    assert own[1] == pytest.approx(-1.0, abs=1e-12)
    np.testing.assert_allclose(rh, [0, 1, 0], atol=1e-3)


def test_to_g_with_nominal_constants_warns_and_flags():
    b = AccBurst("2242", np.datetime64("2014-05-11"), "XZ", 10.0, np.array([[2048, 1593], [2503, 2048]]), 0)
    with pytest.warns(
        NominalCalibrationWarning, match="tag 2242: converting counts with the nominal constants"
    ):
        g = to_g(b)
    assert g.nominal and g.axes == "XZ"
    np.testing.assert_allclose(g.acc_g, [[0, -455 * 0.0022], [455 * 0.0022, 0]], rtol=1e-12)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        g = to_g(b, nominal_calibration(2242))  # a calibration passed in: no warning, whatever it holds
    assert not g.nominal
    # an id that is no tag number (a Movebank individual) needs the number
    b2 = AccBurst("4266-84831108", np.datetime64("2008-07-27"), "XY", 5.0, np.array([[1856, 1900]]), 0)
    with pytest.raises(SensorError, match="not an e-obs tag number"):
        to_g(b2)
    with pytest.warns(NominalCalibrationWarning):
        assert to_g(b2, tag_number=2242).acc_g.shape == (1, 2)


def test_calibration_toml_round_trip_and_bad_files(tmp_path):
    cal = Calibration((1800.0, 2061.25, 2031.0), (2 / 910, 0.00215, 0.0023), 2242)
    p = write_calibration(cal, tmp_path / "tag2242.toml")
    assert read_calibration(p) == cal  # floats are written by repr: exact
    assert "[X]\nzero_count = 1800.0" in p.read_text()
    cases = {
        "nominal = false\n": r"\[X\]: missing table",
        calibration_to_toml(cal).replace(
            "zero_count = 1800.0", "zero_count = 5000.0"
        ): r"X.zero_count = 5000.0: must be a number in 0-4095",
        calibration_to_toml(cal).replace(
            "slope_g_per_count = 0.00215", "slope_g_per_count = -0.00215"
        ): r"Y.slope_g_per_count = -0.00215: must be a number > 0",
        calibration_to_toml(cal).replace(
            "nominal", "nominl"
        ): r"unknown key 'nominl' \(did you mean \"nominal\"\?\)",
        "tag_number = [": r"not TOML",
    }
    for text, message in cases.items():
        p.write_text(text)
        with pytest.raises(InputDataError, match=message) as e:
            read_calibration(p)
        assert str(e.value).startswith(str(p)) and "\n" not in str(e.value)
