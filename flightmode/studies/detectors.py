"""Detectors of the interface in ``sweep`` and ``certify``: ``--detector SPEC`` (repeatable),
``--param key=value`` and ``--grid-file grid.toml``.

A detector entry is a factory (:func:`flightmode.detector.interface.load`: an entry point of the
group ``flightmode.detectors`` such as ``nmv``, ``two-source``, ``eobs-duty``, or
``package.module:make``), a label (the ``method`` column of the sweep's rows), the channels it
reads, and its grid points (parameter dicts). The grid file::

    [[detector]]
    name = "mine"                      # the label (default: the spec)
    spec = "mypkg.detect:make"         # an entry point's name or package.module:attr
    channels = ["acc_x_g", "acc_y_g", "acc_z_g", "pressure_pa"]   # default: the factory's
    grace_s = 1.0                      # optional (below)
    [detector.params]                  # fixed parameters of every point (optional)
    mode = "fast"
    [detector.grid]                    # the Cartesian product of these lists (optional)
    threshold = [1.0, 2.0, 3.0]
    window_s = [0.5, 1.0]

gives 6 points of ``mine``; several ``[[detector]]`` tables give several detectors, certified side
by side. ``--param`` adds its values to every point of every ``--detector`` of the command line.

Each point is run on every flight's stream (:func:`flightmode.detector.interface.decisions`: one
decision per sample) and scored per sample (:func:`flightmode.detector.decisions.score`). A rest
decision carried from before pushback into the in-flight window is the suspension latency; it counts
as a false static when it lasts ``grace_s`` or longer (default: seed 000's recommended W_s, the
resolution at which the built-ins' checks judge it, so that both are judged alike).

A registered built-in whose factory's ``kind`` has a grid (:data:`flightmode.detector.grid.GRID_KINDS`: ``nmv``, ``emv``,
``nmv+baro``, seed 001's), or any factory with an attribute ``grid_method`` (a method name of
:class:`flightmode.detector.grid.Grid`), whose points vary only ``weight``, ``window_s``, ``k`` and
``time_threshold_s``, is swept by the grid's fast path instead (each moving variance computed once,
judged at its checks as ``--method`` judges it); the rows are the grid's, under the detector's label.
"""

from __future__ import annotations

import itertools
import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from flightmode.detector.recommended_point import POINT as RECOMMENDED
from flightmode.errors import DetectorError, InputDataError

GRID_AXES = {"weight": "weight", "window_s": "windows_s", "k": "ks", "time_threshold_s": "time_thresholds_s"}
GRACE_S = RECOMMENDED.window_s  # seed 000 Table 9's W_s (module docstring)


@dataclass(frozen=True)
class Entry:
    """One detector to sweep: ``name`` (its label), ``spec``, ``channels`` (None: the factory's),
    ``points`` (parameter dicts, at least one), ``grace_s``."""

    name: str
    spec: str
    channels: tuple[str, ...] | None = None
    points: tuple[dict, ...] = field(default_factory=lambda: ({},))
    grace_s: float = GRACE_S

    def as_dict(self) -> dict:
        return {
            "name": self.name,
            "spec": self.spec,
            "channels": list(self.channels) if self.channels else None,
            "points": [dict(p) for p in self.points],
            "grace_s": self.grace_s,
        }


def params_text(params: dict) -> str:
    """A point's parameters as one line of JSON, keys sorted (the sweep's ``params`` column)."""
    return json.dumps(params, sort_keys=True, separators=(",", ":"), default=str)


def product(fixed: dict, grid: dict, where: str) -> tuple[dict, ...]:
    """The Cartesian product of ``grid``'s lists, each point with ``fixed``'s values."""
    for key, values in grid.items():
        if not isinstance(values, list) or not values:
            raise DetectorError(f"{where}: grid.{key} must be a non-empty list (e.g. {key} = [1, 2, 3])")
        if len({json.dumps(v, sort_keys=True) for v in values}) != len(values):
            raise DetectorError(f"{where}: grid.{key} gives a value twice; give each once")
        if key in fixed:
            raise DetectorError(f"{where}: {key} is both a fixed parameter and a grid axis")
    keys = list(grid)
    return tuple(fixed | dict(zip(keys, combo, strict=True)) for combo in itertools.product(*grid.values()))


def from_cli(specs: Sequence[str], params: Sequence[str] = (), grace_s: float | None = None) -> list[Entry]:
    """The ``--detector`` entries, each with the ``--param`` values as its one point."""
    from flightmode.detector.interface import parse_params

    fixed = parse_params(params)
    return [
        Entry(str(s), str(s), None, (dict(fixed),), GRACE_S if grace_s is None else float(grace_s))
        for s in specs
    ]


def from_toml(path: str | Path, grace_s: float | None = None) -> list[Entry]:
    """The ``[[detector]]`` tables of a grid file (module docstring); an InputDataError names the
    file and the key that is wrong."""
    import tomllib

    path = Path(path)
    try:
        doc = tomllib.loads(path.read_text())
    except FileNotFoundError:
        raise InputDataError(f"--grid-file {path}: no such file") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
        raise InputDataError(f"--grid-file {path}: not TOML ({e})") from None
    tables = doc.get("detector")
    if not isinstance(tables, list) or not tables:
        raise InputDataError(f'--grid-file {path}: no [[detector]] table (e.g. spec = "nmv")')
    unknown = sorted(set(doc) - {"detector"})
    if unknown:
        raise InputDataError(f"--grid-file {path}: unknown top-level key {unknown[0]!r} (use [[detector]])")
    out = []
    for i, t in enumerate(tables):
        where = f"--grid-file {path}: detector[{i}]"
        bad = sorted(set(t) - {"name", "spec", "channels", "params", "grid", "grace_s"})
        if bad:
            raise InputDataError(
                f"{where}: unknown key {bad[0]!r} (use name, spec, channels, params, grid, grace_s)"
            )
        if not isinstance(t.get("spec"), str):
            raise InputDataError(
                f'{where}: spec missing (an entry point name or package.module:make, e.g. "nmv")'
            )
        ch = t.get("channels")
        if ch is not None and not (isinstance(ch, list) and all(isinstance(c, str) for c in ch)):
            raise InputDataError(f'{where}: channels must be a list of names (e.g. ["acc_x_g"])')
        fixed, grid = t.get("params", {}), t.get("grid", {})
        if not isinstance(fixed, dict) or not isinstance(grid, dict):
            raise InputDataError(f"{where}: params and grid are tables ([detector.params], [detector.grid])")
        try:
            points = product(fixed, grid, where)
        except DetectorError as e:
            raise InputDataError(str(e)) from None
        g = t.get("grace_s", GRACE_S if grace_s is None else grace_s)
        out.append(
            Entry(str(t.get("name", t["spec"])), t["spec"], tuple(ch) if ch else None, points, float(g))
        )
    return out


def check(entries: Sequence[Entry], taken: Sequence[str] = ()) -> None:
    """Every factory loads, every label is given once (``taken``: the built-in grid's methods), the
    channels are known names, the grace is >= 0; a DetectorError (or InputDataError) otherwise."""
    from flightmode.detector.interface import check_channels, check_params, load

    seen = set(taken)
    for e in entries:
        if e.name in seen:
            raise InputDataError(
                f"detector {e.name!r} is named twice; give each a name of its own (name = ... in --grid-file)"
            )
        seen.add(e.name)
        loaded = load(e.spec)
        if e.channels is not None:
            check_channels(e.channels, f"detector {e.name}")
        if not (e.grace_s >= 0 and math.isfinite(e.grace_s)):
            raise InputDataError(f"detector {e.name}: grace_s {e.grace_s!r}: a duration >= 0 s")
        if not e.points:
            raise InputDataError(f"detector {e.name}: no grid point")
        for params in e.points:  # a parameter the factory does not take, before any flight
            check_params(loaded, params)
            if e.channels is None:
                loaded.channels_for(params)


def fast_grid(entry: Entry):
    """The built-in grid that sweeps ``entry`` by the fast path (module docstring), or None."""
    import inspect

    from flightmode.detector.grid import Grid
    from flightmode.detector.interface import load, names

    loaded = load(entry.spec)
    method = getattr(loaded.factory, "grid_method", None)
    from flightmode.detector.grid import GRID_KINDS

    if method is None and getattr(loaded.factory, "kind", None) in GRID_KINDS and entry.spec in names():
        method = entry.spec  # a registered built-in with a grid: its name is the grid's method
    if not isinstance(method, str) or entry.channels not in (None, loaded.channels):
        return None
    try:
        sig = inspect.signature(loaded.factory).parameters
    except (TypeError, ValueError):
        return None
    plain = Grid()  # an axis the factory does not take: the grid's default (NMV's weight 1)
    axes: dict[str, list] = {k: [] for k in GRID_AXES}
    for p in entry.points:
        if set(p) - set(GRID_AXES):
            return None
        for k in GRID_AXES:
            if k in p:
                v = p[k]
            elif k not in sig:
                v = plain.methods[0][1] if k == "weight" else getattr(plain, GRID_AXES[k])[0]
            elif sig[k].default is not inspect.Parameter.empty:
                v = sig[k].default
            else:
                return None
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                return None
            if float(v) not in axes[k]:
                axes[k].append(float(v))
    grid = Grid(
        tuple((method, w) for w in axes["weight"]),
        tuple(axes["window_s"]),
        tuple(axes["k"]),
        tuple(axes["time_threshold_s"]),
    )
    return grid if len(grid) == len(entry.points) else None  # a product of the axes, nothing more


def rest_matrix(channels: Sequence[str], cols: dict, row: dict, sigma2_from: str, fs: float, x, rest_of):
    """The rest recording a factory that takes ``rest`` gets, in its ``channels`` (``x``: the stream's
    matrix in them), as ``detect`` gives it (:func:`flightmode.runs.detect.rest_recording`):
    ``preset``, the unit's bench recording for the accelerometer (the stream the sweep's sigma^2
    comes from) and the longest truly static run before the flight for the other channels (held at its
    last value beyond it); ``rest``, the truly static samples before the flight (every static sample
    when those are fewer than one second)."""
    import numpy as np

    from flightmode.detector.evaluation import longest_static_run
    from flightmode.detector.interface import ACC_CHANNELS

    static = np.asarray(cols["sensor_static"], bool)
    window = np.asarray(cols["in_flight_window"], bool)
    before = static.copy()
    if window.any():
        before[int(np.flatnonzero(window)[0]) :] = False  # what a tracker saw before the flight
    if sigma2_from == "rest":
        return x[before if before.sum() >= fs else static]
    bench = np.asarray(rest_of(sigma2_from, row, cols, fs), float)
    a, b = longest_static_run(before) if before.any() else longest_static_run(static)
    out = np.empty((bench.shape[0], len(channels)))
    for j, c in enumerate(channels):
        if c in ACC_CHANNELS:
            out[:, j] = bench[:, ACC_CHANNELS.index(c)]
        else:
            run = x[a:b, j]
            out[:, j] = np.concatenate([run, np.full(max(0, bench.shape[0] - run.shape[0]), run[-1])])[
                : bench.shape[0]
            ]
    return out


def context_of(row: dict, cols: dict) -> dict:
    """The harness's context keywords for one dataset flight (:data:`flightmode.detector.interface.
    CONTEXT` but ``rest``): its accelerometer's resolution, and with a barometer its reading rate and
    the destination's expected ground pressure (from the flight's scenario, as its own run had them)."""
    from flightmode.runs import pipeline
    from flightmode.scenarios.scenario import Scenario

    sc = Scenario.from_toml_text(row["scenario_toml"], f"flight {row['flight_id']}")
    out: dict = {"sensor_lsb_g": pipeline.sensor_preset(sc.sensor).lsb_g}
    baro = pipeline.baro_preset(sc.sensor) if "baro_pa" in cols else None
    if baro is not None:
        out["baro_fs_hz"] = float(baro.odr_hz)
        out["arrival_ground_pa"] = pipeline.pressure_params(sc, baro.odr_hz).arrival_ground_pa
    from flightmode.detector.interface import CONTEXT

    return {k: v for k, v in out.items() if k in CONTEXT}  # what the interface offers, by its names


def run_entry(entry: Entry, cols: dict, row: dict, fs: float, sigma2_from: str, rest_of) -> list[tuple]:
    """(params, per-sample decisions, DecisionEvaluation) of every point of ``entry`` on one stream."""
    import numpy as np

    from flightmode.detector.decisions import score
    from flightmode.detector.interface import build, decisions, load, stream_matrix

    loaded = load(entry.spec)
    labels = {k: cols[k] for k in ("in_flight_window", "sensor_static", "phase")}
    context = context_of(row, cols)
    out = []
    for params in entry.points:
        channels = entry.channels or loaded.channels_for(params)
        t, x = stream_matrix(cols, channels, f"flight {row['flight_id']}")
        rest = rest_matrix(channels, cols, row, sigma2_from, fs, x, rest_of) if loaded.takes_rest else None
        det = build(loaded, fs, channels, params, rest, **context)
        try:
            dec = decisions(entry.name, det, t, x)
        except DetectorError as e:
            raise DetectorError(f"{e} (flight {row['flight_id']}, {params_text(params)})") from None
        out.append((params, np.asarray(dec, bool), score(t, dec, labels, grace_s=entry.grace_s)))
    return out


__all__ = [
    "GRACE_S",
    "Entry",
    "check",
    "context_of",
    "fast_grid",
    "from_cli",
    "from_toml",
    "params_text",
    "product",
    "rest_matrix",
    "run_entry",
]
