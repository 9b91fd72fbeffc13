"""Firmware over a pipe (flightmode.detector.pipe): examples/nmv_fixed.c compiled and run through the
protocol on the pattern flight (decisions equal to nmv-fixed's and to the built-in floating NMV's
but for the counted near-threshold checks), both framings; the framings' bytes; and the failures
(a program that exits early, writes garbage, too few or too many answers, is not there), each one
line naming the sample, no process left behind."""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from flightmode.detector import fixed_point as fp
from flightmode.detector import interface, pipe
from flightmode.errors import DetectorError
from flightmode.scenarios.scenario import builtin_names

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "nmv_fixed.c"
FS = 100.0


def compile_example(out_dir: Path) -> Path:
    """examples/nmv_fixed.c built with the C compiler (cc or gcc); a skip without one, a failure when
    FLIGHTMODE_REQUIRE_CC=1 (.ci/run installs gcc and sets it)."""
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None:
        if os.environ.get("FLIGHTMODE_REQUIRE_CC") == "1":
            pytest.fail("FLIGHTMODE_REQUIRE_CC=1 but there is no C compiler (cc or gcc) on PATH")
        pytest.skip("no C compiler: install gcc (apt-get install gcc) to run the C firmware example")
    exe = out_dir / "nmv_fixed"
    r = subprocess.run(
        [cc, "-std=c99", "-O2", "-Wall", "-Wextra", "-pedantic", "-o", str(exe), str(EXAMPLE), "-lm"],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    assert r.stderr == "", r.stderr  # it compiles without a warning under -Wall -Wextra -pedantic
    return exe


@pytest.fixture(scope="module")
def firmware(tmp_path_factory) -> Path:
    return compile_example(tmp_path_factory.mktemp("cc"))


@pytest.fixture(scope="module")
def flight(pattern_run):
    """(t, x in the accelerometer channels, sigma^2 in counts^2 from the unit's bench recording)."""
    from flightmode.runs.pipeline import stream_rest
    from flightmode.runs.run_io import read_samples

    cols, info = read_samples(pattern_run[0])
    rest, _, _ = stream_rest("preset", cols, info)
    t, x = interface.stream_matrix(cols, interface.ACC_CHANNELS)
    return t, x, fp.sigma2_counts_of_rest(rest, 100).tolist()


@pytest.mark.parametrize("framing", pipe.FRAMINGS)
def test_the_c_firmware_on_the_pattern_flight(firmware, flight, framing, record_property):
    # the C program and nmv-fixed are the same integer algorithm: equal decisions on every one of the
    # flight's samples, whether the stream goes as one chunk or in 1,000-sample chunks (no tolerance;
    # csv in chunks only: its text costs 2-3 s a pass, f64 20 times less)
    t, x, s2 = flight
    params = {"sigma2_counts": s2}
    ref = interface.decisions("nmv-fixed", fp.make(FS, list(interface.ACC_CHANNELS), **params), t, x)
    loaded = pipe.load_cmd(shlex.quote(str(firmware)), framing)
    for chunk in (None, 1000) if framing == "f64" else (1000,):
        det = interface.build(loaded, FS, loaded.channels, params)
        t0 = time.perf_counter()
        got = interface.decisions(loaded.name, det, t, x, chunk=chunk)
        rate = t.shape[0] / (time.perf_counter() - t0)
        np.testing.assert_array_equal(got, ref)
        assert det.proc.returncode == 0  # closed: it exited cleanly at the end of its input
        record_property(f"samples_per_s_{framing}_chunk_{chunk}", round(rate))
    # and the built-in floating NMV on the same 8-bit samples, sigma^2 in g^2: the samples that differ
    # are the ones compare_fixed_float counts (the register's rounding, within one LSB)
    x8 = fp.to_counts(x) * fp.LSB_G
    r = fp.compare_fixed_float(t, x, FS, sigma2_counts=s2)
    assert r["within_one_lsb"]
    nmv = interface.build(
        interface.load("nmv"),
        FS,
        list(interface.ACC_CHANNELS),
        {"sigma2": (np.array(s2) * fp.LSB_G**2).tolist()},
    )
    floating = interface.decisions("nmv", nmv, t, x8)
    assert int(np.sum(got != floating)) == r["sample_disagreements"]
    record_property("fixed_vs_float_sample_disagreements", r["sample_disagreements"])


def test_the_framings_carry_the_exact_floats():
    # repr is the shortest text that reads back to the same float64; f64 is the bytes themselves
    rng = np.random.default_rng(4)
    t = np.cumsum(rng.uniform(0.005, 0.015, 50))
    x = rng.normal(0, 1, (50, 2)) * 10.0 ** rng.integers(-12, 6, (50, 2))
    rows = np.column_stack([t, x])
    text = pipe.encode(t, x, "csv").decode()
    back = np.array([[float(v) for v in line.split(",")] for line in text.splitlines()])
    np.testing.assert_array_equal(back, rows)
    np.testing.assert_array_equal(np.frombuffer(pipe.encode(t, x, "f64"), "<f8").reshape(50, 3), rows)
    h = pipe.header(FS, ["acc_z_g", "pressure_pa"], "f64", {"k": np.float64(4.0), "axes": np.arange(2)})
    assert h.endswith(b"\n") and h.count(b"\n") == 1
    import json

    assert json.loads(h) == {
        "fs_hz": 100.0,
        "channels": ["acc_z_g", "pressure_pa"],
        "units": {"t_s": "s", "acc_z_g": "g", "pressure_pa": "Pa"},
        "framing": "f64",
        "params": {"k": 4.0, "axes": [0, 1]},
    }


def py(code: str) -> str:
    """A command running ``code`` in this Python, unbuffered."""
    return f"{shlex.quote(sys.executable)} -u -c {shlex.quote(code)}"


# each program reads the header line, then answers per its rule; sample i's line is read before
# its answer is written
ANSWER = "import sys\nsys.stdin.readline()\n"
PROGRAMS = {
    "exits early": (
        ANSWER + "for i in range(5):\n    sys.stdin.readline(); print(1)\nsys.exit(3)",
        ["exited with status 3 at sample 5", "5 answers for the 20 samples"],
    ),
    "garbage": (
        ANSWER
        + "for i, l in enumerate(sys.stdin):\n    print('maybe so, said the firmware' if i == 7 else 0)",
        ["answer for sample 7 is 'maybe so, said the firmware'"],
    ),
    "too few, then exits": (
        ANSWER + "for i in range(12):\n    sys.stdin.readline(); print(0)",
        ["exited with status 0 at sample 12", "too few answers"],
    ),
    "too many": (
        ANSWER + "for l in sys.stdin:\n    print(0); print(1)",
        ["more answers than samples"],
    ),
}


@pytest.mark.parametrize("what", PROGRAMS)
def test_a_failing_program_is_one_line_naming_the_sample(what, capfd):
    code, expected = PROGRAMS[what]
    loaded = pipe.load_cmd(py(code), "csv", timeout_s=20)
    det = interface.build(loaded, FS, loaded.channels, {})
    t = np.arange(20) / FS
    with pytest.raises(DetectorError) as e:
        interface.decisions(loaded.name, det, t, np.zeros((20, 3)), chunk=10 if what == "too many" else None)
    msg = str(e.value)
    assert "\n" not in msg
    for part in expected:
        assert part in msg, msg
    assert det.proc.returncode is not None  # reaped: no zombie, nothing left running


def test_silence_is_too_few_answers():
    # a program that answers 3 of a chunk's samples and then waits: after timeout_s of silence
    code = ANSWER + "for i in range(3):\n    sys.stdin.readline(); print(1)\nimport time; time.sleep(60)"
    loaded = pipe.load_cmd(py(code), timeout_s=1.0)
    det = interface.build(loaded, FS, loaded.channels, {})
    with pytest.raises(
        DetectorError, match=r"gave 3 answers for the 10 samples 0-9 .* no answer for sample 3"
    ):
        interface.decisions(loaded.name, det, np.arange(10) / FS, np.zeros((10, 3)))
    assert det.proc.returncode is not None  # killed and reaped


def test_f64_answers_are_bytes_0_or_1():
    code = (
        "import sys\nsys.stdin.buffer.readline()\nfor i in range(4):\n"
        "    sys.stdin.buffer.read(32); sys.stdout.buffer.write(b'\\x01' if i < 3 else b'1'); sys.stdout.flush()"
    )
    loaded = pipe.load_cmd(py(code), "f64", timeout_s=20)
    det = interface.build(loaded, FS, loaded.channels, {})
    with pytest.raises(DetectorError, match=r"answer for sample 3 is byte 0x31"):
        interface.decisions(loaded.name, det, np.arange(4) / FS, np.zeros((4, 3)))


def test_a_missing_program():
    loaded = pipe.load_cmd("/nonexistent/firmware --fast")
    with pytest.raises(DetectorError, match=r"program '/nonexistent/firmware' not found \(before sample 0\)"):
        interface.build(loaded, FS, loaded.channels, {})
    with pytest.raises(DetectorError, match="framing"):
        pipe.load_cmd("x", framing="json")


def test_the_firmware_refuses_a_nan_at_its_sample(firmware, capfd):
    # the C program answers the samples before, says why on stderr (passed through) and exits 2
    loaded = pipe.load_cmd(shlex.quote(str(firmware)))
    det = interface.build(loaded, FS, loaded.channels, {})
    x = np.zeros((50, 3))
    x[20, 1] = np.nan
    with pytest.raises(DetectorError, match=r"exited with status 2 at sample 20 \(20 answers for the 50"):
        interface.decisions(loaded.name, det, np.arange(50) / FS, x)
    assert "NaN or inf in the sample (at sample 20)" in capfd.readouterr().err


ROUTES = [n for n in builtin_names() if n != "pattern"]


@pytest.mark.slow
@pytest.mark.parametrize("name", ROUTES)
def test_the_c_firmware_on_the_built_in_routes(firmware, run_cached, name, record_property):
    # every built-in route gate to gate: the C program (f64) equals nmv-fixed on every sample, and the
    # integer detector differs from the floating one only within one LSB of the threshold (counted)
    import dataclasses

    from flightmode.runs.pipeline import streams_of
    from flightmode.sim.sensor.accelerometer import UnitDraw, bench_static, get_preset

    r = run_cached(name)
    rec = r.recording
    preset = dataclasses.replace(get_preset(rec.preset), odr_hz=float(rec.odr_hz))
    bench = bench_static(preset, UnitDraw.from_dict(rec.unit), streams_of(r.seed).rng("detector/bench"))
    s2 = fp.sigma2_counts_of_rest(bench.acc_g, int(round(rec.odr_hz)))
    params = {"sigma2_counts": s2.tolist()}
    ref = fp.make(rec.odr_hz, list(interface.ACC_CHANNELS), **params).push(rec.t_s, rec.acc_g)
    loaded = pipe.load_cmd(shlex.quote(str(firmware)), "f64")
    got = interface.decisions(
        loaded.name, interface.build(loaded, rec.odr_hz, loaded.channels, params), rec.t_s, rec.acc_g
    )
    np.testing.assert_array_equal(got, ref)
    c = fp.compare_fixed_float(rec.t_s, rec.acc_g, rec.odr_hz, sigma2_counts=s2)
    assert c["within_one_lsb"] and c["final_explained"], c["axis_disagreements"]
    for key in ("checks", "temporary_disagreements", "final_disagreements", "sample_disagreements"):
        record_property(key, c[key])
    record_property("axis_disagreements", len(c["axis_disagreements"]))


def test_sigma2_in_g2_as_the_builtin_nmv_takes_it(firmware):
    # the same parameter grid serves nmv and nmv-fixed: sigma2 in g^2 is sigma2_counts times lsb_g^2,
    # in the C program as in Python (thresholds chosen so the decisions vary: both outcomes occur)
    rng = np.random.default_rng(6)
    n = 3000
    t = np.arange(n) / FS
    x = np.array([0.0, 0.0, 1.0]) + rng.normal(0.0, 0.01, (n, 3))
    x[1000:1500] += rng.normal(0.0, 0.03, (500, 3))
    params = {"sigma2": [1.0e-4, 1.2e-4, 0.9e-4], "time_threshold_s": 2.0}
    ch = list(interface.ACC_CHANNELS)
    ref = fp.make(FS, ch, **params).push(t, x)
    counts = np.array(params["sigma2"]) / (fp.LSB_G * fp.LSB_G)
    assert np.array_equal(fp.make(FS, ch, sigma2_counts=counts, time_threshold_s=2.0).push(t, x), ref)
    assert ref.any() and not ref.all()
    loaded = pipe.load_cmd(shlex.quote(str(firmware)), "csv")
    got = interface.decisions(loaded.name, interface.build(loaded, FS, ch, params), t, x, chunk=700)
    np.testing.assert_array_equal(got, ref)
