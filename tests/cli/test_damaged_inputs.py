"""Damaged inputs (issue 54, item 5): each of `view`, `validate`, `path`, `cabin`, `detect` and `sense` on a
copy of the pattern run with one of its files damaged ends in one line on standard error that names the
file and what is wrong, exit status 2, no traceback, and nothing written beside the run.

A command is given only the damages of the files it reads (`cabin` never opens samples.parquet, so a
truncated one is no error for it): :data:`READS`. A flipped byte inside a Parquet page is caught by the
page's CRC-32 (run_io writes and verifies Parquet's page checksums); a Rerun recording carries no
checksum, so for the .rrd only its framing (header, footer) is checked: a cut-short or overwritten file.
"""

from __future__ import annotations

import json
import shutil
import subprocess

import pytest
from typer.testing import CliRunner

from flightmode.cli.main import app


def _truncate(p):
    b = p.read_bytes()
    p.write_bytes(b[: len(b) // 2])  # a copy or a write that stopped half way


def _flip(p):
    b = bytearray(p.read_bytes())
    i = len(b) // 3
    b[i : i + 4096] = bytes(x ^ 0x5A for x in b[i : i + 4096])  # 4 KiB of bit flips inside the data pages
    p.write_bytes(bytes(b))


def _no_scenario(p):
    info = json.loads(p.read_text())
    del info["scenario_toml"]
    p.write_text(json.dumps(info))


# damage -> (the file it damages, how, what the message must say besides the file's name)
DAMAGES = {
    "samples-truncated": ("samples.parquet", _truncate, "not a readable Parquet file"),
    "samples-flipped": ("samples.parquet", _flip, "not a readable Parquet file"),
    "samples-not-samples": (
        "samples.parquet",
        lambda p: shutil.copy(p.parent / "truth.parquet", p),
        "not a flightmode samples file",
    ),
    "truth-truncated": ("truth.parquet", _truncate, "not a readable Parquet file"),
    "truth-flipped": ("truth.parquet", _flip, "not a readable Parquet file"),
    "truth-not-truth": (
        "truth.parquet",
        lambda p: shutil.copy(p.parent / "samples.parquet", p),
        "not a flightmode truth file",
    ),
    "run.json-missing": ("run.json", lambda p: p.unlink(), ""),
    "run.json-corrupt": (
        "run.json",
        lambda p: p.write_text('{"run_id": "pattern-s1", "scen'),
        "not a readable",
    ),
    "run.json-latin-1": ("run.json", lambda p: p.write_bytes(b'{"run_id": "caf\xe9"}'), "not a readable"),
    "run.json-a-list": ("run.json", lambda p: p.write_text("[1, 2]"), "not an object"),
    "run.json-no-scenario": ("run.json", _no_scenario, "scenario_toml"),
    "rrd-truncated": ("recording.rrd", _truncate, "damaged Rerun recording"),
    "rrd-overwritten": ("recording.rrd", lambda p: p.write_bytes(b"\0" * 4096), "not a Rerun recording"),
    "not-a-run": (None, None, ""),
}

# what each command reads of a run folder (its damages are those of these files)
READS = {
    "view": ("recording.rrd",),
    "validate": ("samples.parquet", "truth.parquet", "run.json", "scenario"),
    "path": ("truth.parquet", "run.json", "scenario"),
    "cabin": ("truth.parquet", "run.json", "scenario"),
    "detect": ("samples.parquet", "run.json"),  # its sigma^2 from run.json's sensor, not the scenario
    "sense": ("truth.parquet", "run.json", "scenario"),
}
ARGS = {"sense": ["--sensor", "ideal"], "cabin": ["--out", "{root}/figures"]}


def _cases():
    for cmd, reads in READS.items():
        for name, (file, _, _) in DAMAGES.items():
            if name == "run.json-no-scenario" and "scenario" not in reads:
                continue
            if file is None or file in reads:
                yield pytest.param(cmd, name, id=f"{cmd}-{name}")


def _listing(root):
    return sorted((str(p.relative_to(root)), p.stat().st_size) for p in root.rglob("*"))


@pytest.mark.parametrize(("cmd", "damage"), list(_cases()))
def test_damaged_run_is_one_line_exit_2_and_nothing_written(pattern_run, tmp_path, monkeypatch, cmd, damage):
    src, _ = pattern_run
    run = tmp_path / src.name
    run.mkdir()
    file, spoil, says = DAMAGES[damage]
    if file is None:  # a folder that is not a run: a note, and nothing flightmode wrote
        (run / "notes.txt").write_text("not a run\n")
    else:
        for f in src.iterdir():  # copies (never links: the damage must not reach the session's run)
            if f.name in ("truth.parquet", "samples.parquet", "run.json") or f.name == file:
                shutil.copy(f, run / f.name)
        spoil(run / file)

    def no_viewer(*a, **k):  # `view` must refuse before it starts Rerun's viewer
        raise AssertionError(f"the viewer was started on a damaged recording: {a}")

    monkeypatch.setattr(subprocess, "Popen", no_viewer)
    before = _listing(tmp_path)
    args = [a.format(root=tmp_path) for a in ARGS.get(cmd, [])]
    r = CliRunner().invoke(app, [cmd, str(run), *args], env={"COLUMNS": "80"})
    assert r.exception is None or isinstance(r.exception, SystemExit), repr(r.exception)
    assert r.exit_code == 2, r.output
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), r.stderr
    assert "Traceback" not in r.output
    named = str(run) if file is None else file  # the file, or the folder that is not a run
    assert named in lines[0], lines[0]
    assert says in lines[0], lines[0]
    assert _listing(tmp_path) == before  # nothing written, nothing half-written, nothing left behind
