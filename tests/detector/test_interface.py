"""The detector interface (detector/interface.py): a factory loaded from a module path and from an
entry point (a real ``*.dist-info/entry_points.txt`` on sys.path, read by importlib.metadata), its
parameters and context keywords, and the one-line errors (unknown name with the nearest, a factory
that raises, decisions of the wrong length or type, something not callable)."""

from __future__ import annotations

import sys
import textwrap
import uuid

import numpy as np
import pytest

from flightmode.detector import interface
from flightmode.errors import DetectorError

MODULE = '''
import numpy as np

LIMIT_G2 = 1e-4


class Still:
    """At rest when the acceleration's magnitude has varied less than limit_g2 over the last n samples."""

    def __init__(self, n, limit_g2):
        self.n, self.limit = n, limit_g2
        self.tail = np.zeros(0)

    def push(self, t_s, x):
        mag = np.sqrt((np.asarray(x) ** 2).sum(axis=1))
        buf = np.concatenate([self.tail, mag])
        out = np.zeros(mag.shape[0], bool)
        for i in range(mag.shape[0]):
            j = self.tail.shape[0] + i
            w = buf[max(0, j - self.n + 1) : j + 1]
            out[i] = w.shape[0] == self.n and w.var() < self.limit
        self.tail = buf[-(self.n - 1):]
        return out


def make(fs_hz, channels, *, window_s=0.5, limit_g2=LIMIT_G2, rest=None):
    make.seen = {"fs_hz": fs_hz, "channels": list(channels), "rest_rows": None if rest is None else len(rest)}
    return Still(int(round(window_s * fs_hz)), limit_g2)


def raises(fs_hz, channels, **params):
    raise ValueError("no calibration table for this unit")


class Short:
    def push(self, t_s, x):
        return np.ones(max(0, len(t_s) - 1), bool)


class Words:
    def push(self, t_s, x):
        return ["yes"] * len(t_s)


class Twos:
    def push(self, t_s, x):
        out = np.ones(len(t_s), int)
        out[np.isclose(t_s, 3.5)] = 2  # sample 350 at 100 Hz, whatever the chunks
        return out


class Boom:
    def push(self, t_s, x):
        raise RuntimeError("stack overflow in the filter")


def short(fs_hz, channels):
    return Short()


def words(fs_hz, channels):
    return Words()


def twos(fs_hz, channels):
    return Twos()


def boom(fs_hz, channels):
    return Boom()


def nothing(fs_hz, channels):
    return 42


NOT_CALLABLE = 3.5
'''


@pytest.fixture()
def plugin(tmp_path, monkeypatch):
    """A user's detector module on the path, under a name of its own (the module cache never
    mixes two tests' copies); returns its name."""
    name = f"mydet_{uuid.uuid4().hex[:8]}"
    (tmp_path / f"{name}.py").write_text(textwrap.dedent(MODULE))
    monkeypatch.syspath_prepend(str(tmp_path))
    yield name
    sys.modules.pop(name, None)


def _stream(n=400, fs=100.0, seed=0):
    rng = np.random.default_rng(seed)
    x = rng.normal(0, 2e-3, (n, 3)) + [0.0, 0.0, 1.0]
    x[n // 2 :] += rng.normal(0, 0.1, (n - n // 2, 3))  # moving in the second half
    return np.arange(n) / fs, x


def test_a_factory_loads_from_a_module_path_and_decides(plugin):
    loaded = interface.load(f"{plugin}:make")
    assert loaded.source == f"{plugin}:make" and loaded.channels == interface.ACC_CHANNELS
    assert loaded.takes_rest and interface.parameters(loaded.factory) == ("window_s", "limit_g2")
    assert interface.parameters(interface.load("nmv").factory)[-1] == "sensor_lsb_g"  # settable by --param
    t, x = _stream()
    det = interface.build(loaded, 100.0, loaded.channels, {"window_s": 0.2}, rest=x[:100], sensor_lsb_g=0.018)
    assert loaded.factory.seen == {"fs_hz": 100.0, "channels": list(interface.ACC_CHANNELS), "rest_rows": 100}
    d = interface.decisions(loaded.name, det, t, x, chunk=37)
    # at rest (2 mg noise: variance of |a| ~ 4e-6 g^2 < 1e-4) after its 20-sample window fills; moving
    # (0.1 g: variance ~ 1e-2 g^2) never
    assert not d[:19].any() and d[19:200].all() and not d[220:].any()
    # a parameter the factory does not take: named, with the ones it takes
    with pytest.raises(DetectorError, match=r"no parameter 'limit' \(it takes window_s, limit_g2\)"):
        interface.build(loaded, 100.0, loaded.channels, {"limit": 1.0})


def test_a_factory_loads_by_entry_point_from_a_dist_info(tmp_path, monkeypatch, plugin):
    """The real mechanism: an installed distribution's entry_points.txt names the factory in the
    group flightmode.detectors; importlib.metadata finds it on sys.path."""
    site = tmp_path / "site"
    info = site / "mydet-0.1.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: mydet\nVersion: 0.1\n")
    ep = f"still-{plugin[-8:]}"
    (info / "entry_points.txt").write_text(f"[flightmode.detectors]\n{ep} = {plugin}:make\n")
    monkeypatch.syspath_prepend(str(site))
    assert ep in interface.names() and "nmv" in interface.names()
    loaded = interface.load(ep)
    assert loaded.name == ep and loaded.source == f"entry point {ep} ({plugin}:make)"
    t, x = _stream()
    assert interface.decisions(ep, interface.build(loaded, 100.0, loaded.channels, {}, x[:100]), t, x).any()
    # by name, the nearest is suggested
    with pytest.raises(DetectorError, match=f'did you mean "{ep}"'):
        interface.load(ep[:-1])


@pytest.mark.parametrize(
    "attr,words",
    [
        ("short", "returned shape (399,) for the 400 samples starting at sample 0"),
        ("words", "returned <U3 decisions from sample 0"),
        ("twos", "decision 2 at sample 350"),
        ("boom", "raised RuntimeError on the samples from 0 (stack overflow in the filter)"),
        ("nothing", "returned int, which has no push(t_s, x)"),
        ("raises", "raised ValueError: no calibration table for this unit"),
    ],
)
def test_a_detector_that_misbehaves_is_one_line_naming_it(plugin, attr, words):
    t, x = _stream()
    loaded = interface.load(f"{plugin}:{attr}")
    with pytest.raises(DetectorError) as e:
        interface.decisions(attr, interface.build(loaded, 100.0, loaded.channels, {}), t, x)
    assert words in str(e.value) and "\n" not in str(e.value)


def test_a_detector_is_checked_chunk_by_chunk_naming_the_sample(plugin):
    t, x = _stream()
    loaded = interface.load(f"{plugin}:twos")
    with pytest.raises(DetectorError, match="decision 2 at sample 350"):
        interface.decisions("twos", interface.build(loaded, 100.0, loaded.channels, {}), t, x, chunk=300)


def test_specs_that_name_no_factory_are_one_line(plugin):
    cases = [
        ("mvcd", "use 'nmv' or 'emv' (seed 000)"),
        ("nmv+gps", "nmv+baro"),  # listed
        (f"{plugin}:NOT_CALLABLE", "is not callable"),
        (f"{plugin}:missing", f"module '{plugin}' has no 'missing'"),
        ("no_such_pkg_xyz.mod:make", "module 'no_such_pkg_xyz.mod' does not import (ModuleNotFoundError"),
    ]
    for spec, words in cases:
        with pytest.raises(DetectorError) as e:
            interface.load(spec)
        assert words in str(e.value) and "\n" not in str(e.value), (spec, str(e.value))
    assert interface.load("EMV").name == "emv"  # one name matches in another case


def test_params_are_toml_values_and_channels_are_checked():
    assert interface.parse_params(["k=4", "window_s=1.5", "name=abc", "axes=[1, 2]", "sub={k = 3}"]) == {
        "k": 4,
        "window_s": 1.5,
        "name": "abc",
        "axes": [1, 2],
        "sub": {"k": 3},
    }
    for items, words in ((["k"], "write key=value"), (["k=1", "k=2"], "given twice"), (["k=nan"], "finite")):
        with pytest.raises(DetectorError, match=words):
            interface.parse_params(items)
    with pytest.raises(DetectorError, match='did you mean "acc_x_g"'):
        interface.check_channels(["acc_x"], "--channels")
    with pytest.raises(DetectorError, match="named twice"):
        interface.check_channels(["acc_x_g", "acc_x_g"], "--channels")


def test_the_stream_matrix_holds_the_barometer_between_its_readings():
    t = np.arange(10) / 100.0
    cols = {
        "t_s": t,
        "acc_g": np.tile([0.0, 0.0, 1.0], (10, 1)),
        "baro_pa": np.repeat([100.0, 101.0, 102.0], [4, 4, 2]).astype(float),
        "baro_new": np.isin(np.arange(10), [0, 4, 8]),
    }
    _, x = interface.stream_matrix(cols, ["pressure_pa", "acc_z_g"])
    assert x[:, 0].tolist() == [100.0] * 4 + [101.0] * 4 + [102.0] * 2 and (x[:, 1] == 1.0).all()
    with pytest.raises(DetectorError, match="no gyroscope"):
        interface.stream_matrix(cols, ["gyro_x_dps"])


def test_the_documented_example_runs_as_written(tmp_path, monkeypatch):
    """docs/detectors.md's mypkg/still.py, taken from the page: loaded by module path, it streams
    (the same decisions in chunks of 37 as in one push) and tells rest from motion."""
    import re
    from pathlib import Path

    page = (Path(__file__).resolve().parents[2] / "docs" / "detectors.md").read_text()
    code = re.search(r"as `mypkg/still.py`.*?```python\n(.*?)```", page, re.S).group(1)
    pkg = tmp_path / f"docpkg_{uuid.uuid4().hex[:8]}"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "still.py").write_text(code)
    monkeypatch.syspath_prepend(str(tmp_path))
    loaded = interface.load(f"{pkg.name}.still:make")
    assert loaded.channels == interface.ACC_CHANNELS and loaded.takes_rest
    t, x = _stream(n=2000)
    rest = _stream(n=600, seed=1)[1][:300]
    runs = [
        interface.decisions(
            "still", interface.build(loaded, 100.0, loaded.channels, {"k": 6.0}, rest), t, x, c
        )
        for c in (None, 37)
    ]
    assert np.array_equal(*runs)
    # at rest (first 10 s) it allows transmission after its 1 s window and 4 s hold; moving, never
    # (0.1 g of motion: a variance of |a| 2,500 times the 2 mg noise's)
    d = runs[0]
    assert d[600:1000].all() and not d[:99].any() and not d[1010:].any()
    sys.modules.pop(pkg.name, None)
    sys.modules.pop(f"{pkg.name}.still", None)
