"""The e-obs toolkit through the CLI: `flightmode eobs calibrate` on six simulated Movebank files
recovers the drawn constants, and `flightmode eobs detect FILE.csv` runs the duty-cycled detector on the
real albatross file."""

from __future__ import annotations

import numpy as np
from typer.testing import CliRunner

from flightmode.cli.main import app


def test_eobs_calibrate_recovers_a_simulated_tag_from_six_movebank_files(tmp_path):
    from flightmode.eobs.calibration import read_calibration
    from flightmode.eobs.movebank import bursts_to_file, write_movebank
    from flightmode.eobs.simulate import draw_unit, simulate_burst
    from flightmode.sim.sensor.accelerometer import PRESETS

    rng = np.random.default_rng(2242)
    unit = draw_unit(2242, rng)
    noise_g = PRESETS["eobs"].noise_g
    args = []
    for key in ("+x", "-x", "+y", "-y", "+z", "-z"):
        g = np.zeros((60, 3))
        g[:, "xyz".index(key[1])] = 1.0 if key[0] == "+" else -1.0
        bursts = [
            simulate_burst(
                unit,
                g,
                "XYZ",
                10.0,
                np.datetime64("2026-01-01T00:00:00", "ns") + np.timedelta64(60 * i, "s"),
                rng,
                noise_g,
            )
            for i in range(4)
        ]
        path = tmp_path / f"{key}.csv"
        write_movebank(bursts_to_file(bursts), path)
        args += [f"--{'plus' if key[0] == '+' else 'minus'}-{key[1]}", str(path)]
    r = CliRunner().invoke(
        app, ["eobs", "calibrate", *args, "--tag-number", "2242", "--out", str(tmp_path / "cal")]
    )
    assert r.exit_code == 0, r.output
    cal = read_calibration(tmp_path / "cal" / "calibration.toml")  # --out is a folder
    # 240 samples per orientation at 1 mg noise (0.45 count) and 1-count rounding: the mean of a
    # recording has sigma_m = sqrt(0.45^2 + 1/12) / sqrt(240) = 0.038 count, the zero sigma_m / sqrt(2)
    # = 0.027 count: 0.15 count is over 5 sigma; the slope's relative sigma is sigma_m * c / sqrt(2)
    # = 6e-5, 5e-4 is 8 sigma
    assert np.allclose(cal.zero_count, unit.zero_count, atol=0.15)
    assert np.allclose(np.array(cal.slope_g_per_count) / np.array(unit.slope_g_per_count), 1.0, atol=5e-4)
    # a file with the wrong axes (two-axis XY bursts, as the albatross tags recorded): one line
    xy = tmp_path / "xy.csv"
    t0 = np.datetime64("2026-01-01T00:00:00", "ns")
    write_movebank(bursts_to_file([simulate_burst(unit, g, "XY", 10.0, t0, rng, noise_g)]), xy)
    bad = CliRunner().invoke(
        app, ["eobs", "calibrate", *args[:-1], str(xy), "--out", str(tmp_path / "x.toml")]
    )
    assert bad.exit_code == 2 and "needs bursts of all three axes (XYZ)" in bad.output
    assert not (tmp_path / "x.toml").exists()


def test_detect_runs_the_duty_cycled_detector_on_the_real_albatross_file(real_movebank):
    r = CliRunner().invoke(
        app,
        ["eobs", "detect", str(real_movebank), "--tag-number", "2242", "--k", "4", "--bursts", "1"],
        env={"COLUMNS": "160"},
    )
    assert r.exit_code == 0, r.output
    assert "nominal constants of tag 2242" in r.output
    rows = {
        line.split()[1]: line.split()
        for line in r.output.splitlines()
        if line.startswith("│") and "XY" in line
    }
    assert len(rows) == 9  # nine individuals, five bursts each
    assert all(v[5] == "5" for v in rows.values())
    # the birds seen flying by their GPS fixes (9-11 m/s) never hold still for a 12 s burst
    for bird in ("2131-2131", "1163-1163", "unbanded-159"):
        assert rows[bird][7] == "0"
    r = CliRunner().invoke(app, ["eobs", "detect", str(real_movebank)])
    assert r.exit_code == 2 and "give --tag-number" in r.output
