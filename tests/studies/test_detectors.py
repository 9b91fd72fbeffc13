"""Detectors of the interface in sweep and certify (issue 52): a plugin from a module path and from an
entry point (a dist-info on sys.path) swept and certified side by side with the built-in grid on a
one-flight dataset (the pattern circuit's recording, the fast tier's session flight), the grid file,
the e-obs duty-cycled rule's chunks, and the one-line refusals."""

from __future__ import annotations

import json
import textwrap
from pathlib import Path

import numpy as np
import pytest

from flightmode.errors import DetectorError, InputDataError

PLUGIN = '''
"""At rest when the acceleration's magnitude is within thr_g of 1 g (per sample, no state)."""
import numpy as np


class Near1g:
    def __init__(self, thr_g):
        self.thr_g = thr_g

    def push(self, t_s, x):
        return np.abs(np.sqrt((np.asarray(x) ** 2).sum(axis=1)) - 1.0) < self.thr_g


def make(fs_hz, channels, thr_g=0.05):
    return Near1g(thr_g)


class Raises:
    def push(self, t_s, x):
        raise ValueError("sensor fault")


def make_raises(fs_hz, channels):
    return Raises()


class Short:
    def push(self, t_s, x):
        return np.ones(len(t_s) - 1, bool)


def make_short(fs_hz, channels):
    return Short()


def fast_nmv(fs_hz, channels, window_s=1.0, k=4.0, time_threshold_s=4.0, rest=None):
    from flightmode.detector.builtin import nmv

    return nmv(fs_hz, channels, window_s=window_s, k=k, time_threshold_s=time_threshold_s, rest=rest)


fast_nmv.grid_method = "nmv"  # the sweep may use its grid's fast path
'''


@pytest.fixture(scope="module")
def tiny_dataset(tmp_path_factory, run_cached) -> Path:
    """A dataset of one flight: the pattern circuit's run (the session's cached flight) written in the
    layout `flightmode dataset` writes (samples partition, manifest, dataset.json)."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from flightmode.datasets.make import MANIFEST, manifest_schema
    from flightmode.runs import run_io

    r = run_cached("pattern")
    sc, rec = r.scenario, r.recording
    out = tmp_path_factory.mktemp("tiny") / "ds"
    part = f"samples/aircraft={sc.aircraft}/part-f0000.parquet"
    table = run_io.recording_table(rec)
    table = table.append_column("flight_id", pa.array(["f0000"] * table.num_rows))
    (out / part).parent.mkdir(parents=True)
    pq.write_table(table, out / part)
    import hashlib

    row = {
        "flight_id": "f0000",
        "index": 0,
        "status": "ok",
        "attempts": 1,
        "name": sc.name,
        "seed": sc.seed,
        "aircraft": sc.aircraft,
        "scenario_toml": sc.to_toml(),
        "placement": sc.carrier.placement,
        "carrier_kind": sc.carrier.kind,
        "sensor_preset": sc.sensor.preset,
        "turbulence": ",".join(t.severity for t in sc.plan.turbulence),
        "landing_quality": sc.plan.landing_quality,
        "samples_file": part,
        "samples_sha256": hashlib.sha256((out / part).read_bytes()).hexdigest(),
    }
    pq.write_table(pa.Table.from_pylist([row], schema=manifest_schema()), out / MANIFEST)
    (out / "dataset.json").write_text(json.dumps({"family": "pattern-once", "options": {"truth": "none"}}))
    return out


@pytest.fixture
def plugin(tmp_path, monkeypatch) -> str:
    """The module ``fm52_plugin`` on sys.path, and an installed distribution (a dist-info beside it)
    whose entry point ``near1g`` of the group flightmode.detectors names its factory."""
    site = tmp_path / "site"
    site.mkdir()
    (site / "fm52_plugin.py").write_text(PLUGIN)
    di = site / "fm52plug-0.1.dist-info"
    di.mkdir()
    (di / "METADATA").write_text("Metadata-Version: 2.1\nName: fm52plug\nVersion: 0.1\n")
    (di / "entry_points.txt").write_text("[flightmode.detectors]\nnear1g = fm52_plugin:make\n")
    monkeypatch.syspath_prepend(str(site))
    return "fm52_plugin"


def _cli(args):
    from typer.testing import CliRunner

    from flightmode.cli.main import app

    return CliRunner().invoke(app, [str(a) for a in args])


def test_a_plugin_from_a_module_path_is_swept_and_its_rows_are_the_per_sample_scores(
    tiny_dataset, plugin, tmp_path
):
    from flightmode.detector.decisions import score
    from flightmode.runs.run_io import read_samples
    from flightmode.studies.detectors import GRACE_S
    from flightmode.studies.sweep import read_sweep

    out = tmp_path / "sweep"
    r = _cli(
        [
            "sweep",
            tiny_dataset,
            "--detector",
            f"{plugin}:make",
            "--param",
            "thr_g=0.02",
            "--out",
            out,
            "--json",
        ]
    )
    assert r.exit_code == 0, r.output
    rows = read_sweep(out).points.to_pylist()
    assert len(rows) == 1 and rows[0]["method"] == f"{plugin}:make" and rows[0]["params"] == '{"thr_g":0.02}'
    # the row is the scorer's figures of the rule applied to the flight's own samples
    cols, _ = read_samples(next((tiny_dataset / "samples").rglob("*.parquet")))
    dec = np.abs(np.linalg.norm(cols["acc_g"], axis=1) - 1.0) < 0.02
    labels = {k: cols[k] for k in ("in_flight_window", "sensor_static", "phase")}
    d = score(cols["t_s"], dec, labels, grace_s=GRACE_S)
    got = rows[0]
    assert (got["false_static_count"], got["false_static_s"], got["missed_static_s"]) == (
        d.false_static_count,
        d.false_static_s,
        d.missed_static_s,
    )
    assert got["availability"] == d.availability and got["accuracy"] == d.accuracy


def test_plugins_from_an_entry_point_and_a_module_certified_side_by_side_with_nmv(
    tiny_dataset, plugin, tmp_path
):
    grid_file = tmp_path / "grid.toml"
    grid_file.write_text(
        textwrap.dedent(
            f"""
            [[detector]]
            name = "near1g-ep"
            spec = "near1g"            # the entry point of the dist-info
            [detector.grid]
            thr_g = [0.01, 0.03, 0.1]

            [[detector]]
            name = "near1g-mod"
            spec = "{plugin}:make"
            [detector.params]
            thr_g = 0.03
            """
        )
    )
    from flightmode.detector.grid import grid_from_text
    from flightmode.studies.certify import Target, as_dict, certify, report_data
    from flightmode.studies.detectors import from_toml
    from flightmode.studies.sweep import read_sweep
    from flightmode.viz.certify_report import fig_pareto_detectors, render_html

    out = tmp_path / "cert"
    grid = grid_from_text("nmv", "5", "1", "3,4", "4")
    # the figures of a whole report take longer than the sweep: drawn here, only the side by side's
    cert = certify([tiny_dataset], grid, Target(), out=out, detectors=from_toml(grid_file), figures=False)
    doc = json.loads((out / "certify.json").read_text())
    assert doc["detectors"] == json.loads(json.dumps(as_dict(cert)["detectors"], default=str))
    by = {d["name"]: d for d in cert.detectors}
    assert sorted(by) == ["near1g-ep", "near1g-mod", "nmv"]
    assert [len(by[n]["points"]) for n in ("near1g-ep", "near1g-mod", "nmv")] == [3, 1, 2]
    rows = {(s["method"], s["params"]): s for s in cert.summary}
    # the same rule at the same threshold, loaded two ways: the same figures
    a, b = rows[("near1g-ep", '{"thr_g":0.03}')], rows[("near1g-mod", '{"thr_g":0.03}')]
    assert {k: a[k] for k in a if k != "method"} == {k: b[k] for k in b if k != "method"}
    # a wider band calls every sample at rest that a narrower one does: false-static time and
    # availability never fall as thr_g grows
    ep = [rows[("near1g-ep", json.dumps({"thr_g": t}, separators=(",", ":")))] for t in (0.01, 0.03, 0.1)]
    assert all(x["false_static_s"] <= y["false_static_s"] for x, y in zip(ep, ep[1:], strict=False))
    assert all(x["availability"] <= y["availability"] for x, y in zip(ep, ep[1:], strict=False))
    # each detector's verdict is recommend() over its own points: its point is one of them
    for d in cert.detectors:
        assert cert.summary.index(d["recommendation"]["point"]) in d["points"]
        assert set(d["pareto"]) <= set(d["points"])
    fig_pareto_detectors(cert, out / "pareto_detectors.png")
    assert (out / "pareto_detectors.png").stat().st_size > 0
    page = render_html(
        cert,
        {"pareto_detectors": (out / "pareto_detectors.png").read_bytes()},
        report_data(cert, read_sweep(out / "sweep")),
    )
    assert "Detectors side by side (3)" in page and page.count("class='verdict") == 4  # overall + one each


@pytest.mark.parametrize(
    ("factory", "message"),
    [
        ("make_raises", r"raised ValueError on the samples from 0 \(sensor fault\)"),
        ("make_short", r"returned shape \(\d+,\) for the \d+ samples starting at sample 0"),
    ],
)
def test_a_failing_detector_is_one_line_exit_2_and_writes_nothing(
    tiny_dataset, plugin, tmp_path, factory, message
):
    import re

    for cmd in ("sweep", "certify"):
        out = tmp_path / f"{cmd}-{factory}"
        r = _cli([cmd, tiny_dataset, "--detector", f"{plugin}:{factory}", "--out", out])
        assert r.exit_code == 2, r.output
        # the error: one line (after the progress bar's), naming the detector, the sample, the flight
        errors = [line for line in r.output.splitlines() if line.startswith("error:")]
        assert len(errors) == 1 and r.output.strip().endswith(errors[0]), r.output
        assert re.search(message, errors[0]) and "flight f0000" in errors[0], errors[0]
        assert not out.exists()


def test_the_grid_file_is_the_cartesian_product_and_its_mistakes_are_named(tmp_path):
    from flightmode.studies.detectors import from_toml

    p = tmp_path / "g.toml"
    p.write_text(
        '[[detector]]\nspec = "nmv"\n[detector.params]\nweight = 1.0\n[detector.grid]\nk = [3, 4, 5]\nwindow_s = [0.5, 1]\n'
    )
    (e,) = from_toml(p)
    assert e.name == "nmv" and len(e.points) == 6
    assert {(q["k"], q["window_s"], q["weight"]) for q in e.points} == {
        (k, w, 1.0) for k in (3, 4, 5) for w in (0.5, 1)
    }
    for text, message in (
        ('[[detector]]\nspec = "nmv"\nthreshold = 3\n', "unknown key 'threshold'"),
        ('[[detector]]\nname = "x"\n', "spec missing"),
        ('[[detector]]\nspec = "nmv"\n[detector.grid]\nk = []\n', "grid.k must be a non-empty list"),
        ('[[detector]]\nspec = "nmv"\n[detector.grid]\nk = [3, 3]\n', "gives a value twice"),
        ("[detectors]\n", "no \\[\\[detector\\]\\] table"),
    ):
        p.write_text(text)
        with pytest.raises(InputDataError, match=message):
            from_toml(p)


def test_the_eobs_duty_rule_decides_once_per_burst_and_its_chunks_agree():
    from flightmode.eobs.detector import make

    fs, sig = 100.0, 2e-3
    rng = np.random.default_rng(5)
    n = int(120 * fs)
    t = np.arange(n) / fs
    x = rng.normal(0.0, sig, (n, 3)) + np.array([0.0, 0.0, 1.0])
    moving = (t >= 40) & (t < 70)
    x[moving] += rng.normal(0.0, 30 * sig, (int(moving.sum()), 3))  # 900 sigma^2: never quiet
    rest = rng.normal(0.0, sig, (6000, 3))
    det = make(fs, ["acc_x_g", "acc_y_g", "acc_z_g"], interval_s=10.0, burst_samples=20, m=2, rest=rest)
    whole = det.decide(t, x)
    det2 = make(fs, ["acc_x_g", "acc_y_g", "acc_z_g"], interval_s=10.0, burst_samples=20, m=2, rest=rest)
    sizes = rng.integers(1, 3000, 200)
    cuts = np.cumsum(sizes)[np.cumsum(sizes) < n]
    parts = [det2.push(a, b) for a, b in zip(np.split(t, cuts), np.split(x, cuts))]
    assert np.array_equal(np.concatenate(parts), whole)  # exactly, whatever the chunks
    # bursts of 20 samples at 10 Hz (every 10th sample: 1.9 s) every 10 s: burst j decides at
    # j x 10 + 1.9 s; final static from the second quiet burst (m = 2): 11.9 s
    assert not whole[: int(11.9 * fs)].any() and whole[int(11.9 * fs)]
    # the decision changes only at a burst's last sample
    changes = np.flatnonzero(np.diff(whole.astype(int))) + 1
    assert np.all(np.isclose((t[changes] - 1.9) % 10.0, 0.0, atol=1e-6))
    # motion 40-70 s: the bursts at 40 ... 60 s are loud (off from 41.9 s), then two quiet bursts
    # (70, 80 s) are needed: at rest again from 81.9 s
    assert not whole[int(41.9 * fs) : int(81.9 * fs)].any() and whole[int(81.9 * fs)]
    with pytest.raises(DetectorError, match="interval"):
        make(fs, ["acc_x_g"], interval_s=1.0, burst_samples=20, sigma2=[1e-6])
    with pytest.raises(DetectorError, match="sigma2"):
        make(fs, ["acc_x_g"])


def test_a_factory_with_a_grid_method_is_swept_by_the_grid_fast_path(tiny_dataset, plugin, tmp_path):
    """The attribute grid_method, not the name, sends a detector to the built-in grid's fast path: its
    rows are the grid's own (--method nmv), under its label."""
    from flightmode.detector.grid import grid_from_text
    from flightmode.studies.detectors import Entry, fast_grid
    from flightmode.studies.sweep import sweep

    entry = Entry("mine", f"{plugin}:fast_nmv", None, ({"k": 3.0}, {"k": 4.0}))
    assert fast_grid(entry) == grid_from_text("nmv", "1", "1", "3,4", "4")
    assert fast_grid(Entry("x", f"{plugin}:make")) is None  # no grid_method: per sample
    # a registered built-in with a grid: by its factory's kind; with a parameter off the grid: per sample
    assert fast_grid(Entry("n", "nmv", None, ({"k": 3.0},))) == grid_from_text("nmv", "1", "1", "3", "4")
    assert fast_grid(Entry("n", "nmv", None, ({"sigma2": [1e-6] * 3},))) is None
    assert fast_grid(Entry("t", "two-source")) is None
    a = sweep(tiny_dataset, None, detectors=[entry]).points.to_pylist()
    b = sweep(tiny_dataset, grid_from_text("nmv", "1", "1", "3,4", "4")).points.to_pylist()
    assert [r["method"] for r in a] == ["mine", "mine"]
    assert [r | {"method": "nmv"} for r in a] == b
