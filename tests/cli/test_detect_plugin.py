"""`flightmode detect --detector package.module:make`: a user's own detector (here seed 000's NMV as a
tracker maker would write it in a page of NumPy) scored from its per-sample decisions on the pattern
run, equal to the built-in's; and a detector that misbehaves is one line, exit status 2, nothing
written."""

from __future__ import annotations

import json
import sys
import textwrap

import pytest
from typer.testing import CliRunner

from flightmode.cli.main import app

MOD = '''
"""Seed 000's NMV written from the paper (eq. 1, 7, 8): every second the variance of each axis over
that second, static when all three are below k sigma^2, transmission after T_th / W_s statics in a row."""
import numpy as np

from flightmode.detector.flight_mode import calibrate_sigma2


class NMV:
    def __init__(self, n, thresholds, need):
        self.n, self.thr, self.need = n, thresholds, need
        self.buf = np.zeros((0, 3))
        self.run = 0
        self.state = False

    def push(self, t_s, x):
        buf = np.vstack([self.buf, np.asarray(x)])
        k = buf.shape[0] // self.n  # checks closed in this chunk
        out = np.empty(len(t_s), bool)
        done = 0  # samples of the chunk decided so far
        for j in range(k):
            static = bool(np.all(buf[j * self.n : (j + 1) * self.n].var(axis=0) < self.thr))
            self.run = self.run + 1 if static else 0
            end = (j + 1) * self.n - self.buf.shape[0]  # the check's closing sample in the chunk, + 1
            out[done : end - 1] = self.state
            self.state = self.run >= self.need
            out[end - 1] = self.state
            done = end
        out[done:] = self.state
        self.buf = buf[k * self.n :]
        return out


def make(fs_hz, channels, *, k=4.0, window_s=1.0, time_threshold_s=4.0, rest=None):
    n = int(round(window_s * fs_hz))
    sigma2 = calibrate_sigma2(np.ascontiguousarray(rest), n)
    return NMV(n, k * sigma2, int(np.ceil(time_threshold_s / window_s)))


def raises(fs_hz, channels, **params):
    raise ValueError("no calibration table for this unit")


class Short:
    def push(self, t_s, x):
        return np.ones(len(t_s) - 1, bool)


def short(fs_hz, channels):
    return Short()


class Text:
    def push(self, t_s, x):
        return ["rest"] * len(t_s)


def text(fs_hz, channels):
    return Text()


NOT_A_FACTORY = 3
'''


@pytest.fixture()
def tests_pkg(tmp_path, monkeypatch):
    """A user's package ``tests_pkg`` with its module ``mod`` on the path."""
    pkg = tmp_path / "site" / "tests_pkg"
    pkg.mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "mod.py").write_text(textwrap.dedent(MOD))
    monkeypatch.syspath_prepend(str(tmp_path / "site"))
    for m in ("tests_pkg", "tests_pkg.mod"):
        sys.modules.pop(m, None)
    yield "tests_pkg.mod"
    for m in ("tests_pkg", "tests_pkg.mod"):
        sys.modules.pop(m, None)


def _json(args):
    r = CliRunner().invoke(app, [*args, "--json"])
    assert r.exit_code == 0, r.output
    return json.loads(r.output)


def test_a_users_detector_is_scored_from_its_decisions(pattern_run, tests_pkg):
    """The user's NMV (a check every 100 samples from the stream's start, as the built-in's) on the
    bench recording of the unit gives the built-in's decisions at every sample, so the same per-sample
    figures; and pushed in chunks of 4,000 samples, the same again."""
    run, _ = pattern_run
    mine = _json(["detect", str(run), "--detector", f"{tests_pkg}:make", "--param", "k=4"])
    builtin = _json(["detect", str(run), "--detector", "nmv"])
    assert mine["detector"] == f"{tests_pkg}:make" and mine["params"] == {"k": 4}
    assert mine["channels"] == ["acc_x_g", "acc_y_g", "acc_z_g"]
    assert "bench recording" in mine["calibration_source"]
    # np.var against running sums: equal decisions unless a variance falls within rounding (1e-16
    # relative) of its threshold, which none of the flight's 4,451 checks does
    assert mine["decisions"] == builtin["decisions"]
    assert mine["evaluation"] == mine["decisions"]  # a plugin's evaluation is its per-sample one
    chunked = _json(
        ["detect", str(run), "--detector", f"{tests_pkg}:make", "--param", "k=4", "--chunk", "4000"]
    )
    assert chunked["decisions"] == mine["decisions"]
    # the table a user reads
    r = CliRunner().invoke(
        app, ["detect", str(run), "--detector", f"{tests_pkg}:make"], env={"COLUMNS": "200"}
    )
    assert r.exit_code == 0, r.output
    d = mine["decisions"]
    text = " ".join(r.output.split())
    assert (
        "scored per sample" in text
        and f"{d['false_static_count']} ({d['false_static_s']:g} s in all)" in text
    )


def test_a_detector_that_misbehaves_is_one_line_and_exit_2(pattern_run, tests_pkg, tmp_path, monkeypatch):
    import pyarrow.parquet as pq

    run, _ = pattern_run
    before = sorted(p.name for p in run.iterdir())
    cwd = tmp_path / "cwd"
    cwd.mkdir()
    samples = tmp_path / "first" / "samples.parquet"  # the flight's first 200 s: every case fails as soon
    samples.parent.mkdir()  # on it, and reading 20,000 rows is quick
    pq.write_table(pq.read_table(run / "samples.parquet").slice(0, 20_000), samples)
    monkeypatch.chdir(cwd)
    cases = [
        (["--detector", f"{tests_pkg}:raises"], "raised ValueError: no calibration table for this unit"),
        (
            ["--detector", f"{tests_pkg}:short"],
            "returned shape (19999,) for the 20000 samples starting at sample 0",
        ),
        (["--detector", f"{tests_pkg}:short", "--chunk", "1000"], "starting at sample 0"),
        (["--detector", f"{tests_pkg}:text"], "decisions are True/False"),
        (["--detector", f"{tests_pkg}:NOT_A_FACTORY"], "is not callable"),
        (["--detector", f"{tests_pkg}:missing"], "has no 'missing'"),
        (["--detector", "tests_pkg_nowhere.mod:make"], "does not import"),
        (["--detector", "nmvv"], 'did you mean "nmv"'),
        (["--detector", f"{tests_pkg}:make", "--param", "kk=3"], "no parameter 'kk'"),
        (["--detector", f"{tests_pkg}:make", "--channels", "acc_x_g,acc_q_g"], "unknown channel 'acc_q_g'"),
        (["--detector", "nmv", "--method", "emv"], "give one detector"),
        (["--detector-cmd", "false"], "exited with status 1 at sample 0"),  # a program that exits early
        (["--detector", "nmv", "--k", "3", "--param", "k=5"], "given twice"),
    ]
    for args, words in cases:
        r = CliRunner().invoke(app, ["detect", str(samples), *args], env={"COLUMNS": "300"})
        assert r.exit_code == 2, (args, r.output)
        assert words in r.output and len(r.output.strip().splitlines()) == 1, (args, r.output)
    assert sorted(p.name for p in run.iterdir()) == before and not any(cwd.iterdir())
    assert [p.name for p in samples.parent.iterdir()] == ["samples.parquet"]


def test_nmv_fixed_against_the_floating_nmv_on_the_pattern_run(pattern_run):
    """seed 000's NMV in integer arithmetic (nmv-fixed) beside the floating NMV on the same 8-bit
    samples: the register's rounding is half an LSB of k sigma^2, so every comparison that differs lies
    within one LSB of the threshold (docs/detector_pipe.md)."""
    import json

    from typer.testing import CliRunner

    from flightmode.cli.main import app

    run, _ = pattern_run
    r = CliRunner().invoke(app, ["detect", str(run), "--detector", "nmv-fixed", "--compare-float", "--json"])
    assert r.exit_code == 0, r.output
    c = json.loads(r.output)["compare_float"]
    assert c["checks"] > 4000  # one a second over the 74-minute circuit
    assert c["within_one_lsb"] and c["max_lsb_from_threshold"] <= 1.0
    assert c["final_disagreements"] <= c["temporary_disagreements"] <= c["axis_disagreements"]
    r = CliRunner().invoke(app, ["detect", str(run), "--detector", "nmv", "--compare-float"])
    assert r.exit_code == 2 and "only with --detector nmv-fixed" in r.output
