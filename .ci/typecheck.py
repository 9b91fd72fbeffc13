#!/usr/bin/env python3
"""The type gate: mypy over the whole package, rooms included.

pyproject.toml maps the rooms into the package (``[tool.setuptools.package-dir]``: ``flightmode.sim``
is ``sim/``, ``flightmode.detector`` is ``detector/``, ...), which mypy cannot read: run on the
checkout it sees ``sim/`` as a package ``sim`` and every ``import flightmode.sim...`` as missing, so
the rooms' types would count as ``Any``. This script builds the package as Python imports it, in a
temporary folder of symbolic links (``flightmode/`` with each room linked in under its name), runs
mypy there with the checkout's ``[tool.mypy]`` settings, and prints each error with the file's path
in the checkout. Exit status: mypy's.

    python3 .ci/typecheck.py      (from anywhere; .ci/run calls it)
"""

from __future__ import annotations

import re
import sys
import tempfile
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def shadow_package(dest: Path) -> dict[str, str]:
    """Link the package into ``dest/flightmode`` as it is installed; returns {path in dest: path in the
    checkout} for each room, to name errors by their files in the checkout."""
    conf = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    dirs = conf["tool"]["setuptools"]["package-dir"]
    pkg = dest / "flightmode"
    pkg.mkdir()
    rooms = {name.removeprefix("flightmode."): d for name, d in dirs.items() if name != "flightmode"}
    if any("." in r for r in rooms):
        raise SystemExit(f"typecheck: nested package-dir entries are not handled: {sorted(rooms)}")
    for entry in (ROOT / dirs["flightmode"]).iterdir():
        if entry.name not in rooms and entry.name != "__pycache__":
            (pkg / entry.name).symlink_to(entry)
    for room, d in rooms.items():
        (pkg / room).symlink_to(ROOT / d, target_is_directory=True)
    return {f"flightmode/{room}/": f"{d}/" for room, d in rooms.items()} | {
        "flightmode/": f"{dirs['flightmode']}/"
    }


def main() -> int:
    from mypy import api

    with tempfile.TemporaryDirectory(prefix="flightmode-typecheck-") as d:
        where = shadow_package(Path(d))
        out, err, status = api.run(
            ["--config-file", str(ROOT / "pyproject.toml"), "--cache-dir", str(Path(d) / ".mypy_cache")]
            + [str(Path(d) / "flightmode")]  # instead of [tool.mypy]'s files: the whole package
        )
    prefix = re.escape(d.rstrip("/") + "/")
    rooms = sorted(where, key=len, reverse=True)
    for line in out.splitlines():
        line = re.sub("^" + prefix, "", line)
        for shadow in rooms:  # the longest first: flightmode/sim/ before flightmode/
            if line.startswith(shadow):
                line = where[shadow] + line[len(shadow) :]
                break
        print(line)
    sys.stderr.write(err)
    return status


if __name__ == "__main__":
    sys.exit(main())
