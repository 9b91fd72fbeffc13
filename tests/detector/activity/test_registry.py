"""The table of seed 001's nine detectors: every name resolves to a batch function and a stream
class whose signatures match the table; an unknown name fails loudly with the nearest name."""

from __future__ import annotations

import inspect
import subprocess
import sys

import pytest

from flightmode.detector.activity import registry
from flightmode.errors import DetectorError


def test_the_nine_detectors_in_the_seeds_order():
    assert registry.NAMES == ("amvd", "amd", "ared", "shod", "frd", "ltsd", "fsd", "mbgtd", "mbcd")


@pytest.mark.parametrize("name", registry.NAMES)
def test_each_entry_matches_its_function_and_class(name):
    d = registry.get(name)
    assert d is registry.get(name.upper())  # case-insensitive
    f = d.detect
    assert f.__name__ == f"detect_{name}" and d.stream.__name__ == d.stream_class
    sig = inspect.signature(f)
    assert list(sig.parameters)[:3] == ["t_s", "acc_g", "gyr_dps"]
    required = {p.name for p in sig.parameters.values() if p.kind is p.KEYWORD_ONLY and p.default is p.empty}
    assert required == {"threshold", *d.parameters}
    assert ("signal" in sig.parameters) == bool(d.signals)
    # the stream takes the same keywords, with fs_hz required
    cls = inspect.signature(d.stream.__init__).parameters
    assert set(sig.parameters) - {"t_s", "acc_g", "gyr_dps"} == set(cls) - {"self"}
    assert cls["fs_hz"].default is inspect.Parameter.empty


@pytest.mark.parametrize("name", registry.NAMES)
def test_every_stream_has_the_shared_protocol(name):
    from flightmode.detector.activity.common import ActivityStream

    d = registry.get(name)
    kw = {p: 8 if p in ("window", "shift") else 1.0 for p in d.parameters}
    det = d.stream(threshold=1.0, fs_hz=100.0, **kw)
    assert isinstance(det, ActivityStream) and det.n_samples == 0


def test_an_unknown_name_suggests_the_nearest():
    with pytest.raises(DetectorError, match="no \\(in\\)activity detector 'mbgd'.*did you mean \"mbgtd\""):
        registry.get("mbgd")
    with pytest.raises(DetectorError, match="use one of amvd, amd"):
        registry.get("variance")


def test_importing_the_registry_loads_no_detector_and_no_numpy():
    code = (
        "import sys; from flightmode.detector.activity import registry; registry.get('shod');"
        "print(sorted(m for m in sys.modules"
        " if m.startswith('numpy') or m.endswith(('magnitude', 'memory', 'spectrum')))[:3])"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert r.stdout.strip() == "[]"
