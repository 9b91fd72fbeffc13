"""The detector interface: how any flight-mode detector (a built-in, a user's Python, firmware over a
pipe) is made, fed and judged, so that ``detect``, ``sweep`` and ``certify`` run them all the same way.

A detector is made by a *factory* ``make(fs_hz, channels, **params) -> Detector``:

- ``fs_hz``: the stream's sample rate; ``channels``: the names of the columns of ``x``, units in the
  name (:data:`CHANNELS`: ``acc_x_g`` ..., ``gyro_x_dps`` ..., ``pressure_pa``);
- ``params``: the detector's own parameters (``--param key=value``, a grid point of a TOML grid);
- if the factory takes a keyword ``rest``, the harness passes the unit's rest recording as an array
  (m, len(channels)) in the same channels (the bench recording of the unit, or the stream's static
  samples before the flight, as ``--sigma2-from`` says): a detector calibrates on it as a tracker
  calibrates on the bench.
- other keywords the harness offers when the factory names them (:data:`CONTEXT`):
  ``sensor_lsb_g`` (the recording's accelerometer resolution in g, None when unknown: a variance
  floor for a quantised sensor), ``baro_fs_hz`` (the barometer's own reading rate: ``pressure_pa``
  holds each reading until the next) and ``arrival_ground_pa`` (the destination's expected ground
  pressure when the route is known). A ``--param`` of the same name wins.
- A factory may say which channels it reads with an attribute ``channels`` (a tuple of names), or,
  when they depend on its parameters, a function ``channels_for(**params)``; the harness's default
  is the three accelerometer axes.

``Detector.push(t_s, x)`` takes consecutive chunks (``t_s`` shape (n,) in seconds, ``x`` shape
(n, len(channels))) and returns one decision per sample (True: at rest, the radio may transmit). An
optional ``decide(t_s, x)`` does a whole stream at once and must agree with the chunks; an optional
``close()`` frees what the detector holds (a child process). Entry points of the group
``flightmode.detectors`` name factories (the built-ins are registered there too); a spec
``package.module:make`` loads one from a module path.

This module imports NumPy only inside its functions and no detector.
"""

from __future__ import annotations

import importlib
import inspect
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

from flightmode.errors import DetectorError, did_you_mean

GROUP = "flightmode.detectors"
ACC_CHANNELS = ("acc_x_g", "acc_y_g", "acc_z_g")
GYRO_CHANNELS = ("gyro_x_dps", "gyro_y_dps", "gyro_z_dps")
CHANNELS = (*ACC_CHANNELS, *GYRO_CHANNELS, "pressure_pa")
# keywords the harness passes to a factory that names them (module docstring); ``rest`` is the first
CONTEXT = ("rest", "sensor_lsb_g", "baro_fs_hz", "arrival_ground_pa")


@runtime_checkable
class Detector(Protocol):
    """What a factory returns (module docstring)."""

    def push(self, t_s: Any, x: Any) -> Any: ...


Factory = Callable[..., Detector]


@dataclass(frozen=True, slots=True)
class Loaded:
    """A factory found by :func:`load`: its ``name`` (the entry point's, or the spec as given), the
    ``factory``, where it came from (``source``: ``entry point NAME (module:attr)`` or ``module:attr``),
    the ``channels`` it reads and its default ``params`` (from the spec's TOML, or empty)."""

    name: str
    factory: Factory
    source: str
    channels: tuple[str, ...] = ACC_CHANNELS
    params: dict = field(default_factory=dict)

    @property
    def takes_rest(self) -> bool:
        """The factory takes the unit's rest recording (a keyword ``rest``)."""
        return takes_rest(self.factory)

    def channels_for(self, params: dict) -> tuple[str, ...]:
        """The channels the detector reads with these parameters: the factory's ``channels_for(**params)``
        when it has one, else :attr:`channels`."""
        fn = getattr(self.factory, "channels_for", None)
        if not callable(fn):
            return self.channels
        try:
            ch = tuple(str(c) for c in fn(**params))
        except DetectorError:
            raise
        except Exception as e:
            raise DetectorError(
                f"detector {self.name}: channels_for({_kw(params)}) raised {type(e).__name__}: {e}"
            ) from None
        check_channels(ch, f"detector {self.name}")
        return ch


def _entry_points() -> dict:
    from importlib.metadata import entry_points

    return {e.name: e for e in entry_points(group=GROUP)}


def names() -> tuple[str, ...]:
    """The detectors registered under the entry-point group, sorted."""
    return tuple(sorted(_entry_points()))


def _channels_of(factory: Any, spec: str) -> tuple[str, ...]:
    ch = getattr(factory, "channels", None)
    if ch is None:
        return ACC_CHANNELS
    ch = tuple(str(c) for c in ch)
    check_channels(ch, f"detector {spec}")
    return ch


def check_channels(channels: Sequence[str], what: str) -> None:
    """Every name known (:data:`CHANNELS`), none twice, at least one; a DetectorError otherwise."""
    if not channels:
        raise DetectorError(f"{what}: no channels (use some of {', '.join(CHANNELS)})")
    for c in channels:
        if c not in CHANNELS:
            raise DetectorError(
                f"{what}: unknown channel {c!r} (use {', '.join(CHANNELS)}){did_you_mean(c, CHANNELS)}"
            )
    if len(set(channels)) != len(channels):
        raise DetectorError(f"{what}: a channel is named twice in {list(channels)}")


def load(spec: str, what: str = "--detector") -> Loaded:
    """The factory named by ``spec``: an entry point of the group ``flightmode.detectors`` (``nmv``,
    ``mbcd``, a plugin's name; a name in other case when only one matches), or
    ``package.module:attr`` (a module on the path). A DetectorError says which and why (unknown name
    with the nearest, a module that does not import, no such attribute, not callable); ``what``
    names the option in it."""
    spec = str(spec).strip()
    eps = _entry_points()
    if spec not in eps:
        same = [n for n in eps if n.lower() == spec.lower()]
        spec = same[0] if len(same) == 1 else spec
    if spec in eps:
        ep = eps[spec]
        try:
            factory = ep.load()
        except Exception as e:
            raise DetectorError(
                f"detector {spec!r} ({ep.value}): cannot load ({type(e).__name__}: {e})"
            ) from None
        source = f"entry point {spec} ({ep.value})"
    elif ":" in spec:
        mod, _, attr = spec.partition(":")
        try:
            module = importlib.import_module(mod)
        except Exception as e:
            raise DetectorError(
                f"{what} {spec}: module {mod!r} does not import ({type(e).__name__}: {e}); "
                "give package.module:factory on the Python path"
            ) from None
        factory = module
        for part in attr.split("."):
            if not part or not hasattr(factory, part):
                raise DetectorError(f"{what} {spec}: module {mod!r} has no {attr!r}")
            factory = getattr(factory, part)
        source = spec
    else:
        raise DetectorError(
            f"{what} {spec!r}: use 'nmv' or 'emv' (seed 000) or one of seed 001's detectors or another "
            f"registered one ({', '.join(sorted(eps))}), or package.module:make for a detector of "
            f"your own{did_you_mean(spec.lower(), tuple(eps))}"
        )
    if not callable(factory):
        raise DetectorError(
            f"detector {spec!r}: {source} is not callable (a factory make(fs_hz, channels, **params))"
        )
    return Loaded(spec, factory, source, _channels_of(factory, spec))


def _signature(factory: Any):
    try:
        return inspect.signature(factory).parameters
    except (TypeError, ValueError):
        return None


def accepts(factory: Any, name: str) -> bool:
    """True when ``factory`` has a parameter called ``name`` (not merely ``**params``)."""
    sig = _signature(factory)
    return sig is not None and name in sig and sig[name].kind is not inspect.Parameter.VAR_KEYWORD


def takes_rest(factory: Any) -> bool:
    """True when ``factory`` has a parameter called ``rest`` (the harness then passes the rest recording)."""
    return accepts(factory, "rest")


def parameters(factory: Any) -> tuple[str, ...] | None:
    """The parameters a user may set on ``factory``: its keywords after ``fs_hz`` and ``channels``
    but ``rest`` (the context keywords it names among them: a ``--param`` overrides what the harness
    offers); None when it takes any (``**params``) or has no signature."""
    sig = _signature(factory)
    if sig is None or any(p.kind is inspect.Parameter.VAR_KEYWORD for p in sig.values()):
        return None
    names = [
        n
        for n, p in sig.items()
        if p.kind in (inspect.Parameter.KEYWORD_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD)
    ]
    return tuple(n for n in names[2:] if n != "rest")


def check_params(loaded: Loaded, params: dict) -> None:
    """A DetectorError for a parameter the factory does not take, naming those it takes."""
    allowed = parameters(loaded.factory)
    if allowed is None:
        return
    for key in params:
        if key not in allowed:
            raise DetectorError(
                f"detector {loaded.name}: no parameter {key!r} (it takes "
                f"{', '.join(allowed) or 'none'}){did_you_mean(key, allowed)}"
            )


def _kw(params: dict) -> str:
    return ", ".join(f"{k}={v!r}" for k, v in params.items())


def parse_params(items: Sequence[str]) -> dict:
    """``["k=4", "window_s=1.5", "name=abc", "axes=[1, 2]"]`` as a dict: each value read as a TOML value
    (numbers, booleans, strings in quotes, arrays), a bare word kept as a string. A DetectorError for an
    item without ``=`` or a key given twice."""
    import tomllib

    out: dict = {}
    for item in items:
        key, eq, value = str(item).partition("=")
        key = key.strip()
        if not eq or not key:
            raise DetectorError(f"--param {item!r}: write key=value (e.g. --param k=4)")
        if key in out:
            raise DetectorError(f"--param {key}: given twice")
        try:
            out[key] = tomllib.loads(f"v = {value.strip()}")["v"]
        except tomllib.TOMLDecodeError:
            out[key] = value.strip()
        if isinstance(out[key], float) and not math.isfinite(out[key]):
            raise DetectorError(f"--param {key}={value}: not a finite number")
    return out


def build(
    loaded: Loaded, fs_hz: float, channels: Sequence[str], params: dict, rest: Any = None, **context: Any
) -> Detector:
    """Call the factory with ``params`` (each one it takes: :func:`check_params`), ``rest`` when it
    takes one, and each of ``context`` (:data:`CONTEXT`) it names and ``params`` does not set.
    Whatever the factory raises becomes a DetectorError naming the detector and the parameters; so
    does a result with no ``push``."""
    check_params(loaded, params)
    kwargs = dict(params)
    if loaded.takes_rest:
        kwargs["rest"] = rest
    for key, value in context.items():
        if key not in CONTEXT:
            raise DetectorError(f"build: {key!r} is not a context keyword ({', '.join(CONTEXT)})")
        if key not in kwargs and accepts(loaded.factory, key):
            kwargs[key] = value
    try:
        det = loaded.factory(float(fs_hz), list(channels), **kwargs)
    except DetectorError:
        raise
    except Exception as e:
        raise DetectorError(
            f"detector {loaded.name}: make(fs_hz={fs_hz:g}, channels={list(channels)}, "
            f"{_kw(params)}) raised {type(e).__name__}: {e}"
        ) from None
    if not callable(getattr(det, "push", None)):
        raise DetectorError(
            f"detector {loaded.name}: its factory returned {type(det).__name__}, which has no push(t_s, x)"
        )
    return det


def _checked(name: str, out: Any, start: int, n: int):
    import numpy as np

    try:
        a = np.asarray(out)
    except Exception as e:
        raise DetectorError(
            f"detector {name}: returned {type(out).__name__} for samples {start}-{start + n - 1}, "
            f"not an array of decisions ({e})"
        ) from None
    if a.shape != (n,):
        raise DetectorError(
            f"detector {name}: returned shape {a.shape} for the {n} samples starting at sample {start}; "
            f"one decision per sample, shape ({n},)"
        )
    if a.dtype == bool:
        return a
    if a.dtype.kind in "iuf" and a.size and not np.isin(a, (0, 1)).all():
        bad = int(np.flatnonzero(~np.isin(a, (0, 1)))[0])
        raise DetectorError(
            f"detector {name}: decision {a[bad].item()!r} at sample {start + bad}: decisions are True/False (or 1/0)"
        )
    if a.dtype.kind not in "iufb":
        raise DetectorError(
            f"detector {name}: returned {a.dtype} decisions from sample {start}; decisions are True/False (or 1/0)"
        )
    return a.astype(bool)


def decisions(name: str, det: Detector, t_s: Any, x: Any, chunk: int | None = None):
    """Run ``det`` over a whole stream: ``decide`` when it has one and ``chunk`` is None, else ``push``
    in chunks of ``chunk`` samples (None with no ``decide``: one push). Returns a bool array (n,).
    Whatever the detector raises, or a result of the wrong length or type, is a DetectorError naming
    the detector and the first sample of the chunk; ``close()`` is called in any case."""
    import numpy as np

    t_s = np.asarray(t_s, float)
    x = np.asarray(x, float)
    n = t_s.shape[0]
    try:
        decide = getattr(det, "decide", None)
        if chunk is None and callable(decide):
            return _call(name, decide, t_s, x, 0)
        step = n if chunk is None else max(1, int(chunk))
        parts = [_call(name, det.push, t_s[i : i + step], x[i : i + step], i) for i in range(0, n, step)]
        return np.concatenate(parts) if parts else np.zeros(0, bool)
    finally:
        close = getattr(det, "close", None)
        if callable(close):
            close()


def checked_push(name: str, det: Detector, t_s: Any, x: Any, start: int = 0):
    """``det.push(t_s, x)`` checked as :func:`decisions` checks it (``start``: the global index of the
    chunk's first sample, for the messages): a bool array (n,) or a DetectorError."""
    return _call(name, det.push, t_s, x, start)


def _call(name: str, fn: Callable, t_s: Any, x: Any, start: int):
    try:
        out = fn(t_s, x)
    except DetectorError:
        raise
    except Exception as e:
        raise DetectorError(
            f"detector {name}: raised {type(e).__name__} on the samples from {start} ({e})"
        ) from None
    return _checked(name, out, start, t_s.shape[0])


def stream_matrix(cols: dict, channels: Sequence[str], source: str = "the stream"):
    """``(t_s, x)`` of a stream's columns (:func:`flightmode.runs.run_io.read_samples`, a dataset
    flight): ``x`` (n, len(channels)) in the channels' order. ``pressure_pa`` is the barometer's last
    reading at each sample (held between its readings; the first reading before it). A DetectorError
    names a channel the stream does not have."""
    import numpy as np

    check_channels(channels, source)
    t = np.asarray(cols["t_s"], float)
    out = np.empty((t.shape[0], len(channels)))
    for j, c in enumerate(channels):
        if c in ACC_CHANNELS:
            out[:, j] = cols["acc_g"][:, ACC_CHANNELS.index(c)]
        elif c in GYRO_CHANNELS:
            if cols.get("gyro_dps") is None:
                raise DetectorError(
                    f'{source}: no gyroscope ({c}); fly with [sensor].gyro (e.g. gyro = "bmi270")'
                )
            out[:, j] = cols["gyro_dps"][:, GYRO_CHANNELS.index(c)]
        else:
            if "baro_pa" not in cols or "baro_new" not in cols:
                raise DetectorError(
                    f'{source}: no barometer (pressure_pa); fly with [sensor].baro = "bmp581"'
                )
            new = np.asarray(cols["baro_new"], bool)
            if not new.any():
                raise DetectorError(f"{source}: the barometer gave no reading")
            idx = np.maximum.accumulate(np.where(new, np.arange(t.shape[0]), -1))
            idx[idx < 0] = int(np.flatnonzero(new)[0])
            out[:, j] = np.asarray(cols["baro_pa"], float)[idx]
    return t, out


__all__ = [
    "ACC_CHANNELS",
    "CHANNELS",
    "CONTEXT",
    "GROUP",
    "GYRO_CHANNELS",
    "Detector",
    "Factory",
    "Loaded",
    "accepts",
    "build",
    "check_channels",
    "check_params",
    "checked_push",
    "decisions",
    "load",
    "names",
    "parameters",
    "parse_params",
    "stream_matrix",
    "takes_rest",
]
