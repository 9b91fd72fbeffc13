"""Safe by default: no network listeners (the stock 737 opens a telnet and a UDP port), nothing
written outside OUT, and nothing half-written when a flight fails."""

from __future__ import annotations

import dataclasses
import json
import subprocess
import sys
import tempfile
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import psutil
import pytest


def _inet_sockets(proc: psutil.Process):
    return [c for c in proc.net_connections(kind="inet")]


def testprivate_model_copy_has_no_io_sections_and_a_tug(tmp_path):
    from flightmode.sim.flight.jsbsim.model_copy import private_model_copy, stock_model_xml

    path = private_model_copy("737", tmp_path)
    root = ET.parse(path / "737" / "737.xml").getroot()
    assert root.findall("input") == [] and root.findall("output") == []
    forces = root.findall("external_reactions/force")
    # the tug, and the runway roughness felt through each gear group (sim.flight.jsbsim.roughness)
    assert [f.get("name") for f in forces] == [
        "pushback",
        "roughness-nose",
        "roughness-left",
        "roughness-right",
    ]
    # the stock file does have them (so the stripping above is doing something)
    stock = ET.parse(stock_model_xml("737")).getroot()
    assert len(stock.findall("input")) == 2


def test_loading_and_stepping_the_737_opens_no_socket(tmp_path):
    from flightmode.sim.flight.jsbsim.adapter import JSBSimAircraft

    me = psutil.Process()
    before = {(c.laddr, c.type) for c in _inet_sockets(me)}
    ac = JSBSimAircraft("737", 1 / 120, 2, workdir=tmp_path)
    ac.init_on_ground(46.25, 6.13, 430.0, 227.0)
    for _ in range(240):
        ac.step()
    after = {(c.laddr, c.type) for c in _inet_sockets(me)}
    assert after == before
    assert list(tmp_path.iterdir()) == []  # the private model copy is gone once loaded


def test_unknown_model_suggests_the_nearest():
    from flightmode.errors import AircraftError
    from flightmode.sim.flight.jsbsim.adapter import JSBSimAircraft

    with pytest.raises(AircraftError, match=r"unknown JSBSim aircraft model 'A3200'.*did you mean \"A320\""):
        JSBSimAircraft("A3200", 1 / 120, 2)


def test_cli_flight_listens_on_nothing_and_writes_only_into_out(tmp_path):
    work = tmp_path / "cwd"
    work.mkdir()
    tmp_before = set(p.name for p in Path(tempfile.gettempdir()).iterdir())
    proc = subprocess.Popen(
        [sys.executable, "-m", "flightmode.cli.main", "fly", "pattern", "--out", "out"],
        cwd=work,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    ps = psutil.Process(proc.pid)
    seen = []
    while proc.poll() is None:
        try:
            seen += [c for c in ps.net_connections(kind="all") if c.status == psutil.CONN_LISTEN or c.laddr]
        except (psutil.NoSuchProcess, psutil.ZombieProcess):
            break
        time.sleep(0.1)
    out, err = proc.communicate()
    assert proc.returncode == 0, err
    assert seen == [], f"sockets opened during the flight: {seen}"
    # the working directory holds only OUT, and OUT only the finished run folder
    assert sorted(p.name for p in work.iterdir()) == ["out"]
    assert sorted(p.name for p in (work / "out").iterdir()) == ["pattern-s1"]
    assert sorted(p.name for p in (work / "out" / "pattern-s1").iterdir()) == [
        "recording.rrd",
        "run.json",
        "samples.parquet",
        "truth.parquet",
    ]
    tmp_after = set(p.name for p in Path(tempfile.gettempdir()).iterdir())
    assert not [n for n in tmp_after - tmp_before if n.startswith("flightmode")]
    info = json.loads((work / "out" / "pattern-s1" / "run.json").read_text())
    assert info["seed"] == 1 and info["scenario"] == "pattern"
    assert {"jsbsim", "numpy", "pyarrow"} <= set(info["versions"])
    assert info["events"][0]["name"] == "gate"
    assert "pattern-s1" in out


def test_failed_flight_leaves_nothing_behind(tmp_path, monkeypatch):
    from typer.testing import CliRunner

    import flightmode.sim.flight.aircraft.registry as ap
    from flightmode.cli.main import app

    monkeypatch.setitem(ap.PROFILES, "737", dataclasses.replace(ap.PROFILES["737"], turn_bank_deg=60.0))
    out = tmp_path / "out"
    r = CliRunner().invoke(app, ["fly", "pattern", "--out", str(out)])
    assert r.exit_code == 2
    assert "flight failed in phase" in " ".join(r.output.split()) and "bank angle" in r.output
    assert not out.exists() or list(out.iterdir()) == []  # no run folder, no staging folder


def test_parquet_truth_round_trip(tmp_path, fly_cached):
    """truth.parquet holds the FlightTrack: same rows, labels as strings, SI values."""
    import numpy as np
    import pyarrow.parquet as pq

    from flightmode.runs import run_io

    sc, tr = fly_cached("pattern")
    path = run_io.write_truth(tmp_path, tr)
    t = pq.read_table(path)
    assert t.num_rows == tr.n
    np.testing.assert_array_equal(t["t_s"].to_numpy(), tr.t_s)
    np.testing.assert_array_equal(t["lat_deg"].to_numpy(), tr.lat_deg)
    # float32 columns keep 7 significant digits
    np.testing.assert_allclose(t["fz_body_mps2"].to_numpy(), tr.specific_force_body_mps2[:, 2], rtol=1e-6)
    phases = t["phase"].to_pylist()
    assert phases[0] == "gate" and phases[-1] == "parked"
    assert t["in_flight_window"].to_numpy().sum() == tr.in_flight_window.sum()
