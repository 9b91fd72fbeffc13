"""The installed distribution: every room under the one name ``flightmode`` (nothing called ``sim``
or ``nav`` lands in site-packages), and nothing heavy imported to start."""

from __future__ import annotations

import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
ROOMS = {
    "flightmode": "flightmode",
    "scenarios": "flightmode/scenarios",
    "sim": "flightmode/sim",
    "detector": "flightmode/detector",
    "nav": "flightmode/nav",
    "viz": "flightmode/viz",
    "eobs": "flightmode/eobs",
}
HEAVY = ("numpy", "scipy", "jsbsim", "rerun", "pyarrow", "pandas", "dask", "distributed", "matplotlib")


_IGNORE_ANYWHERE = shutil.ignore_patterns(
    "build", "*.egg-info", "__pycache__", ".pytest_cache", ".hypothesis"
)


def _ignore(folder: str, names: list[str]) -> set[str]:
    """What the copy leaves out: caches and build output anywhere; at the checkout's top also git and
    the output folders a user's runs leave there (``runs/``; flightmode/runs/ is a room and is kept)."""
    top = {".git", "runs", ".venv"} if Path(folder) == ROOT else set()
    return set(_IGNORE_ANYWHERE(folder, names)) | (top & set(names))


@pytest.fixture(scope="module")
def wheel(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    # built from a copy of the sources: setuptools builds in the source tree, and a build/ left in the
    # checkout is both clutter and a stale source (its build/lib can carry a module the tree no longer has)
    src = tmp_path_factory.mktemp("src") / "flightmode"
    shutil.copytree(
        ROOT,
        src,
        ignore=_ignore,
    )
    subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(out), str(src)],
        check=True,
        capture_output=True,
        text=True,
    )
    (whl,) = out.glob("flightmode-*.whl")
    return whl


def test_wheel_holds_every_room_under_flightmode_and_nothing_else(wheel):
    names = zipfile.ZipFile(wheel).namelist()
    tops = {n.split("/")[0] for n in names}
    assert tops == {"flightmode", "flightmode-0.1.0.dist-info"}, tops
    # every module of every repository room is in the wheel, at its place under flightmode/
    for room, dest in ROOMS.items():
        for f in (ROOT / room).rglob("*.py"):
            assert f"{dest}/{f.relative_to(ROOT / room).as_posix()}" in names, f
    # the built-in scenarios ship as package data
    for f in (ROOT / "scenarios" / "library").glob("*.toml"):
        assert f"flightmode/scenarios/library/{f.name}" in names


def test_installed_wheel_imports_flightmode_sim_and_not_sim(wheel, tmp_path):
    venv = tmp_path / "venv"
    # a fresh environment that sees the dependencies already installed here (no download), with the
    # wheel installed into it
    subprocess.run(
        [sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", str(venv)], check=True
    )
    py = venv / "bin" / "python"
    subprocess.run(
        [sys.executable, "-m", "pip", "--python", str(py), "install", "--no-deps", "-q", str(wheel)],
        check=True,
        capture_output=True,
        text=True,
    )
    code = (
        "import importlib, flightmode, flightmode.sim.flight.pilot.phases, flightmode.scenarios.scenario as s;"
        "print(flightmode.__file__); print(len(s.builtin_names()))\n"
        "try:\n import sim\n print('sim imported from', sim.__file__)\nexcept ModuleNotFoundError:\n print('no sim')"
    )
    r = subprocess.run([str(py), "-c", code], capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    where, n, sim = r.stdout.split("\n")[:3]
    assert Path(where).is_relative_to(venv), where  # the wheel's flightmode, not this checkout's
    assert int(n) >= 5 and sim == "no sim"


def test_importing_flightmode_and_its_cli_loads_nothing_heavy():
    """`flightmode --help` must start fast: jsbsim, scipy, rerun, pyarrow (and numpy) are imported
    only inside the commands that need them. Counted in a fresh interpreter, not timed."""
    code = (
        "import sys, flightmode, flightmode.cli.main;"
        f"print(','.join(m for m in {HEAVY!r} if m in sys.modules))"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert r.stdout.strip() == "", f"heavy modules imported at start: {r.stdout.strip()}"
    # rendering the help loads none of them either, nor Typer's Rich help (rich.markdown and
    # markdown_it: 0.15-0.2 s of the 0.5 s budget, measured with python -X importtime)
    code = (
        "import sys, contextlib, io; from flightmode.cli.main import app\n"
        "with contextlib.redirect_stdout(io.StringIO()) as out, contextlib.suppress(SystemExit):\n"
        "    app(['--help'])\n"
        "assert 'Commands:' in out.getvalue() and 'fly' in out.getvalue(), out.getvalue()\n"
        f"print(','.join(m for m in {HEAVY + ('typer.rich_utils', 'rich.markdown', 'markdown_it')!r} if m in sys.modules))"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert r.stdout.strip() == "", f"modules imported by --help: {r.stdout.strip()}"
    # and the API is there, loaded on first use
    r = subprocess.run(
        [sys.executable, "-c", "import flightmode; print(flightmode.Scenario.builtin('pattern').aircraft)"],
        capture_output=True,
        text=True,
        check=True,
    )
    assert r.stdout.strip() == "737"
