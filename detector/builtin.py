"""The built-in detectors as factories of the detector interface (:mod:`flightmode.detector.interface`),
registered under the entry-point group ``flightmode.detectors`` (pyproject.toml): each ``make(fs_hz,
channels, **params)`` returns a streaming detector whose ``push(t_s, x)`` gives one decision per
sample, the same for any chunking, and whose ``decide`` is one push of the whole stream.

The maths is the existing modules', run as they run alone:

- ``nmv``, ``emv``: seed 000's moving-variance detector (:class:`~flightmode.detector.flight_mode.
  FlightModeDetector`, eq. 1-9);
- ``amvd`` ... ``mbcd``: seed 001's nine (in)activity detectors (their streaming classes, registry
  :mod:`flightmode.detector.activity.registry`) under seed 000's decision rule
  (:mod:`flightmode.detector.activity.flight`);
- ``nmv+baro``, ``emv+baro``: the redundant rule (:mod:`flightmode.detector.pressure`): the moving
  variance OR the pressure source to suspend, both to resume, combined at each accelerometer check;
- ``two-source``: any two detectors combined per sample (EASA's two independent means: suspend
  when ANY says flying, resume only when ALL say on the ground), by default the recommended NMV and
  the pressure source alone (:func:`pressure`, loaded as ``flightmode.detector.builtin:pressure``).

**Per-sample decisions from checks** (seed 000's rule): a check closes every W_s at a sample; a
sample's decision is the final static of the last check closed at or before it, False (transmission
not allowed) before the first check.

**Parameters** (keywords, defaults seed 000's recommended point, :data:`~flightmode.detector.
recommended_point.POINT`): ``window_s`` (W_s), ``k`` (T_sigma = k sigma^2, or k times the rest level
of an activity detector's merit), ``time_threshold_s`` (T_th); ``weight`` (EMV), ``signal`` (the
flexible activity detectors' input); the pressure source's ``baro_rate_pa_s``, ``baro_margin_hpa``,
``baro_hold_s``. **Calibration** from the keyword ``rest`` (the unit's rest recording in the same
channels): sigma^2 per axis as :func:`~flightmode.detector.flight_mode.calibrate_sigma2` computes it
on the bench (with the ``sensor_lsb_g`` floor), an activity detector's noise figures and rest level as
:func:`~flightmode.detector.activity.flight.rest_figures` does. ``sigma2`` may be given instead.

**Internals for the rich report**: every built-in detector has a ``kind`` (``moving_variance``,
``activity``, ``redundant``, ``pressure``, ``two_source``) and those with checks an
``evaluation(t_s, x, labels)`` after the stream has been pushed (the check-based
:class:`~flightmode.detector.evaluation.Evaluation`, or :class:`~flightmode.detector.pressure.
RedundantEvaluation`), besides ``params``, ``sigma2``, ``rest_figures`` as they apply.

Importing this module imports no NumPy and no detector.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any, cast

from flightmode.detector.interface import ACC_CHANNELS, GYRO_CHANNELS
from flightmode.detector.recommended_point import POINT
from flightmode.errors import DetectorError

PRESSURE_CHANNELS = ("pressure_pa",)
BARO_FS_HZ = 25.0  # the BMP581's reading rate in flightmode's sensor presets (sim.sensor.barometer)
# the pressure source's defaults: detector.pressure.PressureParams (its module docstring justifies them)
BARO_RATE_PA_S = 1.0
BARO_MARGIN_HPA = 25.0
BARO_HOLD_S = 120.0
PRESSURE_SPEC = "flightmode.detector.builtin:pressure"


def _declare(kind: str, channels: tuple[str, ...], title: str) -> Callable:
    """Mark a factory: the ``channels`` it reads, its ``kind`` and ``title`` (what ``detect`` prints)."""

    def mark(f: Callable) -> Callable:
        vars(f).update(channels=channels, kind=kind, title=title)  # function attributes the harness reads
        return f

    return mark


def columns(channels: Sequence[str], wanted: Sequence[str], who: str) -> list[int]:
    """The indices of ``wanted`` in ``channels``; a DetectorError naming the first missing one."""
    ch = list(channels)
    for c in wanted:
        if c not in ch:
            raise DetectorError(f"{who} reads {', '.join(wanted)}; the channels {ch} have no {c}")
    return [ch.index(c) for c in wanted]


def take(a, cols):
    """The columns ``cols`` of ``a`` as a C-ordered float array (NumPy's fancy indexing on the second
    axis gives a Fortran-ordered one, over which pairwise sums, hence variances, round differently:
    the built-ins see exactly the arrays the modules they wrap see)."""
    import numpy as np

    return np.ascontiguousarray(np.asarray(a, float)[:, cols])


def gap_starts(t, t_prev: float | None, fs_hz: float):
    """Positions in the chunk ``t`` where a time gap starts (a sample more than 1.5 sample periods after
    the one before it, ``t_prev`` the previous chunk's last time): where seed 000's detector resets
    (:mod:`flightmode.detector.flight_mode`)."""
    import numpy as np

    period = 1.0 / float(fs_hz)
    gaps = np.flatnonzero(np.diff(t) > 1.5 * period) + 1
    if t_prev is not None and t.shape[0] and t[0] - t_prev > 1.5 * period:
        gaps = np.concatenate([[0], gaps])
    return gaps


def held(n0: int, n: int, index, decision, state: bool, resets=()):
    """Per-sample decisions of samples ``n0 .. n0 + n - 1`` from checks closing at the global sample
    ``index`` with ``decision``: the last check's at or before each sample
    (:func:`flightmode.detector.decisions.held`), ``state`` (the last check's before the chunk) until
    the first. At ``resets`` (positions in the chunk where a time gap starts: :func:`gap_starts`) the
    decision falls to False until the next check, as the detector's own state does (no check after a
    reset is static until T_th of clean data: the radio never keeps a permission across a gap).
    Returns (decisions, the new state)."""
    import numpy as np

    from flightmode.detector.decisions import held as hold

    pos = np.asarray(index, np.int64) - n0
    dec = np.asarray(decision, bool)
    resets = np.asarray(resets, np.int64)
    if resets.size:  # a reset is a decision False at its sample, before any check closing there
        pos = np.concatenate([pos, resets])
        dec = np.concatenate([dec, np.zeros(resets.size, bool)])
        order = np.lexsort((np.concatenate([np.ones(len(index), int), np.zeros(resets.size, int)]), pos))
        pos, dec = pos[order], dec[order]
    out = hold(n, pos, dec)
    if not pos.size:
        out[:] = bool(state)
        return out, bool(state)
    out[: pos[0]] = bool(state)
    return out, bool(dec[-1])


def _cat_checks(parts: list):
    import numpy as np

    from flightmode.detector.flight_mode import Checks

    return Checks(*(np.concatenate([getattr(p, f) for p in parts]) for f in Checks.__slots__))


# ----------------------------------------------------------------------------------------------
# seed 000: NMV and EMV


class MovingVarianceDetector:
    """Seed 000's detector over the accelerometer channels (module docstring). ``params``: its
    :class:`~flightmode.detector.flight_mode.DetectorParams`; ``sigma2`` per axis."""

    kind = "moving_variance"

    def __init__(self, params, sigma2, channels: Sequence[str]):
        import numpy as np

        from flightmode.detector.flight_mode import FlightModeDetector

        self._acc = columns(channels, ACC_CHANNELS, params.method)
        self._engine = FlightModeDetector(params, sigma2)
        self.params, self.sigma2 = params, self._engine.sigma2
        self._parts = [self._engine.push(np.zeros(0), np.zeros((0, 3)))]
        self._n, self._state = 0, False
        self._t_prev: float | None = None

    def push(self, t_s, x):
        return self.push_checks(t_s, x)[0]

    def push_checks(self, t_s, x):
        """``push``'s decisions and the checks the chunk closed."""
        import numpy as np

        x = np.asarray(x, float)
        c = self._engine.push(t_s, take(x, self._acc))
        self._parts.append(c)
        self.last_resets = self._resets(t_s)  # where this chunk's gaps reset the detector
        out, self._state = held(self._n, x.shape[0], c.index, c.final_static, self._state, self.last_resets)
        self._n += x.shape[0]
        return out, c

    def _resets(self, t_s):
        """Where the chunk's time gaps reset the detector (:func:`gap_starts`), the chunk's end kept."""
        import numpy as np

        t = np.asarray(t_s, float)
        out = gap_starts(t, self._t_prev, self.params.fs_hz)
        if t.shape[0]:
            self._t_prev = float(t[-1])
        return out

    def decide(self, t_s, x):
        """The whole stream at once (one push)."""
        return self.push(t_s, x)

    @property
    def checks(self):
        """Every check pushed so far (:class:`~flightmode.detector.flight_mode.Checks`)."""
        return _cat_checks(self._parts)

    def evaluation(self, t_s, x, labels: dict):
        """The pushed stream's checks scored against its labels, as
        :func:`~flightmode.detector.evaluation.evaluate` scores them."""

        from flightmode.detector.evaluation import check_labels, score

        check_labels(t_s, labels)
        return score(self.checks, t_s, labels, self.params, self.sigma2)


def moving_variance_params(
    method: str, fs_hz: float, window_s: float, k: float, time_threshold_s: float, weight: float, threshold
):
    """The validated :class:`~flightmode.detector.flight_mode.DetectorParams` of a factory's keywords."""
    import dataclasses

    from flightmode.detector.flight_mode import DetectorParams

    p = DetectorParams(
        fs_hz=float(fs_hz),
        window_s=float(window_s),
        k_sigma=float(k),
        time_threshold_s=float(time_threshold_s),
        method=method,
        weight=float(weight),
    )
    if threshold is not None:  # per-axis or common (seed 000 eq. 12), where DetectorParams has it
        if "threshold" not in {f.name for f in dataclasses.fields(p)}:
            raise DetectorError("threshold: this version of the moving-variance detector has no such choice")
        p = dataclasses.replace(p, threshold=str(threshold))
    p.validate()
    return p


def sigma2_of(sigma2, rest, channels: Sequence[str], window: int, sensor_lsb_g, who: str):
    """sigma^2 per axis: ``sigma2`` as given (three positive variances, g^2), or from the rest
    recording's accelerometer channels by :func:`~flightmode.detector.flight_mode.calibrate_sigma2`
    (seed 000 section 5.1 step 1, the quantisation floor ``sensor_lsb_g^2 / 12``)."""
    import numpy as np

    from flightmode.detector.flight_mode import calibrate_sigma2

    if sigma2 is not None:
        s2 = np.asarray(sigma2, float).reshape(-1)
        if s2.shape != (3,) or not np.all(np.isfinite(s2) & (s2 > 0)):
            raise DetectorError(f"{who}: sigma2 = {sigma2!r}: three positive variances in g^2 (x, y, z)")
        return s2
    if rest is None:
        raise DetectorError(
            f"{who} needs the unit's noise variance: give its rest recording (the harness's rest) "
            "or sigma2 = [x, y, z] in g^2"
        )
    r = np.asarray(rest, float)
    return calibrate_sigma2(take(r, columns(channels, ACC_CHANNELS, who)), window, sensor_lsb_g)


@_declare("moving_variance", ACC_CHANNELS, "seed 000's normal moving variance (eq. 1-2)")
def nmv(
    fs_hz: float,
    channels: Sequence[str],
    *,
    window_s: float = POINT.window_s,
    k: float = POINT.k_sigma,
    time_threshold_s: float = POINT.time_threshold_s,
    sigma2: Any = None,
    threshold: str | None = None,
    rest: Any = None,
    sensor_lsb_g: float | None = None,
) -> MovingVarianceDetector:
    """Seed 000's NMV (eq. 1-2, 6-9): W_s ``window_s``, T_sigma = ``k`` sigma^2, T_th ``time_threshold_s``."""
    p = moving_variance_params("nmv", fs_hz, window_s, k, time_threshold_s, 1.0, threshold)
    return MovingVarianceDetector(
        p, sigma2_of(sigma2, rest, channels, p.window, sensor_lsb_g, "nmv"), channels
    )


@_declare("moving_variance", ACC_CHANNELS, "seed 000's exponential moving variance (eq. 3-5)")
def emv(
    fs_hz: float,
    channels: Sequence[str],
    *,
    window_s: float = POINT.window_s,
    k: float = POINT.k_sigma,
    time_threshold_s: float = POINT.time_threshold_s,
    weight: float = POINT.weight,
    sigma2: Any = None,
    threshold: str | None = None,
    rest: Any = None,
    sensor_lsb_g: float | None = None,
) -> MovingVarianceDetector:
    """Seed 000's EMV (eq. 3-5) with weighting factor ``weight`` (1, 5, 10 in the paper)."""
    p = moving_variance_params("emv", fs_hz, window_s, k, time_threshold_s, weight, threshold)
    return MovingVarianceDetector(
        p, sigma2_of(sigma2, rest, channels, p.window, sensor_lsb_g, "emv"), channels
    )


# ----------------------------------------------------------------------------------------------
# seed 001's nine under seed 000's decision rule


class ActivityDetector:
    """A seed 001 detector's streaming class and seed 000's eq. 8 over its markers: a check every W_s
    is temporarily static when every sample of its period was inactive (as
    :func:`~flightmode.detector.activity.flight.activity_checks` does it over a whole stream)."""

    kind = "activity"

    def __init__(self, p, rest_figures: dict, channels: Sequence[str]):
        from flightmode.detector.activity import registry
        from flightmode.detector.activity.flight import detector_kwargs

        self.params, self.rest_figures = p, rest_figures
        self.info = registry.get(p.name)
        self._acc = columns(channels, ACC_CHANNELS, p.name)
        ch = list(channels)
        self._gyr = [ch.index(c) for c in GYRO_CHANNELS] if all(c in ch for c in GYRO_CHANNELS) else None
        self._stream = self.info.stream(
            threshold=rest_figures["threshold"], **detector_kwargs(p, rest_figures)
        )
        self._pending: list = []  # the markers of the period not yet closed
        self._parts: list = []
        self._n = self._checks = self._run = 0
        self._state = False

    def push(self, t_s, x):
        import numpy as np

        from flightmode.detector.flight_mode import Checks, final_static

        t = np.asarray(t_s, float)
        x = np.asarray(x, float)
        res = self._stream.push(t, take(x, self._acc), None if self._gyr is None else take(x, self._gyr))
        w = self.params.window
        m = np.concatenate([*self._pending, res.marker])
        k = m.shape[0] // w
        # every sample of the period inactive (an array: the reshape is 2-D)
        temp = cast(np.ndarray, ~m[: k * w].reshape(k, w).astype(bool).any(axis=1))
        self._pending = [m[k * w :]]
        index = (self._checks + np.arange(k)) * w + w - 1  # global sample closing each check
        after = np.zeros(k, bool)
        if self._checks == 0 and k:
            after[0] = True
        fin = final_static(temp, after, self.params.checks_needed, self._run)  # seed 000, eq. 8
        if k:
            dyn = np.flatnonzero(~temp)
            self._run = k - 1 - int(dyn[-1]) if dyn.size else self._run + k
        local = index - self._n
        self._parts.append(
            Checks(index, t[local], np.repeat(res.merit[local][:, None], 3, axis=1), temp, fin, after)
        )
        self._checks += k
        out, self._state = held(self._n, t.shape[0], index, fin, self._state)
        self._n += t.shape[0]
        return out

    def decide(self, t_s, x):
        """The whole stream at once (one push)."""
        return self.push(t_s, x)

    @property
    def checks(self):
        import numpy as np

        from flightmode.detector.flight_mode import Checks

        if not self._parts:
            z = np.zeros(0)
            return Checks(z.astype(int), z, np.zeros((0, 3)), z.astype(bool), z.astype(bool), z.astype(bool))
        return _cat_checks(self._parts)

    def evaluation(self, t_s, x, labels: dict):
        """The pushed stream's checks scored as :func:`~flightmode.detector.activity.flight.
        evaluate_activity` scores them."""
        import dataclasses

        import numpy as np

        from flightmode.detector.evaluation import check_labels, score
        from flightmode.detector.flight_mode import DetectorParams

        p = self.params
        check_labels(t_s, labels)
        dp = dataclasses.replace(
            DetectorParams(fs_hz=p.fs_hz),
            window_s=p.window_s,
            k_sigma=p.k,
            time_threshold_s=p.time_threshold_s,
            method=p.name,
        )
        return score(self.checks, t_s, labels, dp, np.full(3, self.rest_figures["threshold"]))


def _activity(name: str, flexible: bool, needs_gyro: bool) -> Callable:
    """The factory of seed 001's detector ``name`` (``signal`` a keyword of the flexible ones only)."""

    def build(fs_hz, channels, window_s, k, time_threshold_s, signal, rest) -> ActivityDetector:
        import numpy as np

        from flightmode.detector.activity.flight import ActivityParams, rest_figures

        p = ActivityParams(
            name,
            fs_hz=float(fs_hz),
            window_s=float(window_s),
            k=float(k),
            time_threshold_s=float(time_threshold_s),
            signal=str(signal),
        )
        p.validate()
        if rest is None:
            raise DetectorError(f"{name} needs the unit's rest recording (its noise figures and rest level)")
        r = np.asarray(rest, float)
        ch = list(channels)
        gyr = take(r, [ch.index(c) for c in GYRO_CHANNELS]) if all(c in ch for c in GYRO_CHANNELS) else None
        figs = rest_figures(p, take(r, columns(channels, ACC_CHANNELS, name)), gyr)
        return ActivityDetector(p, figs, channels)

    if flexible:

        def make(
            fs_hz: float,
            channels: Sequence[str],
            *,
            window_s: float = POINT.window_s,
            k: float = POINT.k_sigma,
            time_threshold_s: float = POINT.time_threshold_s,
            signal: str = "acc",
            rest: Any = None,
        ) -> ActivityDetector:
            return build(fs_hz, channels, window_s, k, time_threshold_s, signal, rest)

        def channels_for(signal: str = "acc", **_: Any) -> tuple[str, ...]:
            return ACC_CHANNELS if signal == "acc" else (*ACC_CHANNELS, *GYRO_CHANNELS)

        vars(make)["channels_for"] = channels_for
    else:

        def make(  # type: ignore[misc]
            fs_hz: float,
            channels: Sequence[str],
            *,
            window_s: float = POINT.window_s,
            k: float = POINT.k_sigma,
            time_threshold_s: float = POINT.time_threshold_s,
            rest: Any = None,
        ) -> ActivityDetector:
            return build(fs_hz, channels, window_s, k, time_threshold_s, "acc", rest)

    make.__name__ = make.__qualname__ = name
    make.__doc__ = f"Seed 001's {name.upper()} under seed 000's decision rule (module docstring)."
    return _declare("activity", (*ACC_CHANNELS, *GYRO_CHANNELS) if needs_gyro else ACC_CHANNELS, name)(make)


amvd = _activity("amvd", False, False)
amd = _activity("amd", False, False)
ared = _activity("ared", False, True)
shod = _activity("shod", False, True)
frd = _activity("frd", True, False)
ltsd = _activity("ltsd", True, False)
fsd = _activity("fsd", True, False)
mbgtd = _activity("mbgtd", True, False)
mbcd = _activity("mbcd", True, False)


# ----------------------------------------------------------------------------------------------
# the pressure source, and the redundant rule


def pressure_params(
    baro_fs_hz: float, baro_rate_pa_s: float, baro_margin_hpa: float, baro_hold_s: float, arrival_ground_pa
):
    """The pressure detector's :class:`~flightmode.detector.pressure.PressureParams` (validated) of the
    factories' keywords; a margin of 0 hPa is no level bound."""
    from flightmode.detector.pressure import PressureParams

    if not baro_margin_hpa >= 0:
        raise DetectorError(f"--baro-margin-hpa {baro_margin_hpa:g}: must be >= 0 (0: no level bound)")
    pp = PressureParams(
        fs_hz=float(baro_fs_hz),
        rate_threshold_pa_s=float(baro_rate_pa_s),
        level_margin_pa=float(baro_margin_hpa) * 100.0 if baro_margin_hpa > 0 else None,  # hPa -> Pa
        hold_s=float(baro_hold_s),
        arrival_ground_pa=None if arrival_ground_pa is None else float(arrival_ground_pa),
    )
    pp.validate()
    return pp


class PressureSource:
    """The pressure detector over the held ``pressure_pa`` channel: a new reading is the first sample
    at or after each of the barometer's conversions ``t0 + k / baro_fs_hz`` (t0 the stream's first
    sample, as :func:`flightmode.sim.sensor.sensing.read_barometer` reads it), so the detector sees
    the barometer's own stream. ``push`` returns the chunk's pressure checks and its readings."""

    def __init__(self, pp):
        from flightmode.detector.pressure import PressureDetector

        self.params = pp
        self._engine = PressureDetector(pp)
        self._t0: float | None = None
        self._tick = -1
        self.readings_t: list = []
        self.readings_pa: list = []

    def push(self, t, p):
        import numpy as np

        if not t.shape[0]:
            return self._engine.push(t, p)
        if self._t0 is None:
            self._t0 = float(t[0])
        tick = np.floor((t - self._t0) * self.params.fs_hz + 1e-9).astype(np.int64)
        new = tick != np.concatenate([[self._tick], tick[:-1]])
        self._tick = int(tick[-1])
        tb, pb = t[new], p[new]
        self.readings_t.append(tb)
        self.readings_pa.append(pb)
        return self._engine.push(tb, pb)


def _state_at(t_checks, static, t, last: bool):
    """A source's state as of each time in ``t``: its last check at or before it, ``last`` before."""
    import numpy as np

    j = np.searchsorted(t_checks, t, side="right") - 1
    return np.where(j >= 0, np.asarray(static, bool)[np.maximum(j, 0)] if len(static) else last, last)


@_declare("pressure", PRESSURE_CHANNELS, "the pressure source alone")
def pressure(
    fs_hz: float,
    channels: Sequence[str],
    *,
    baro_rate_pa_s: float = BARO_RATE_PA_S,
    baro_margin_hpa: float = BARO_MARGIN_HPA,
    baro_hold_s: float = BARO_HOLD_S,
    baro_fs_hz: float = BARO_FS_HZ,
    arrival_ground_pa: float | None = None,
) -> PressureOnly:
    """The pressure source alone (:class:`~flightmode.detector.pressure.PressureDetector`): static when
    the cabin pressure has been quiet (rate and level bounds) for the hold time."""
    pp = pressure_params(baro_fs_hz, baro_rate_pa_s, baro_margin_hpa, baro_hold_s, arrival_ground_pa)
    return PressureOnly(pp, channels)


class PressureOnly:
    """The pressure source's decision per sample: its last check at or before it (False before)."""

    kind = "pressure"

    def __init__(self, pp, channels: Sequence[str]):
        self.params = pp
        self._col = columns(channels, PRESSURE_CHANNELS, "the pressure source")[0]
        self._source = PressureSource(pp)
        self._state = False

    def push(self, t_s, x):
        import numpy as np

        t = np.asarray(t_s, float)
        pc = self._source.push(t, np.asarray(x, float)[:, self._col])
        out = _state_at(pc.t_s, pc.static, t, self._state)
        if pc.static.size:
            self._state = bool(pc.static[-1])
        return out


class RedundantDetector:
    """Seed 000's detector and the pressure source, combined at each accelerometer check (the
    redundant rule of :mod:`flightmode.detector.pressure`: transmission allowed when the accelerometer
    is final static AND the pressure source static as of that check)."""

    kind = "redundant"

    def __init__(self, accel: MovingVarianceDetector, pp, channels: Sequence[str]):
        self.accel = accel
        self.params, self.sigma2, self.pressure_params = accel.params, accel.sigma2, pp
        self._acc = columns(channels, ACC_CHANNELS, "the redundant rule")
        self._col = columns(channels, PRESSURE_CHANNELS, "the redundant rule")[0]
        self._source = PressureSource(pp)
        self._p_state = False  # the pressure source's last state before the chunk
        self._n, self._state = 0, False

    def push(self, t_s, x):
        import numpy as np

        t = np.asarray(t_s, float)
        x = np.asarray(x, float)
        pc = self._source.push(t, x[:, self._col])  # every reading up to the chunk's last sample
        _, c = self.accel.push_checks(t, x)
        allowed = c.final_static & _state_at(pc.t_s, pc.static, c.t_s, self._p_state)
        if pc.static.size:
            self._p_state = bool(pc.static[-1])
        out, self._state = held(self._n, t.shape[0], c.index, allowed, self._state, self.accel.last_resets)
        self._n += t.shape[0]
        return out

    def decide(self, t_s, x):
        """The whole stream at once (one push)."""
        return self.push(t_s, x)

    def evaluation(self, t_s, x, labels: dict):
        """:func:`~flightmode.detector.pressure.evaluate_redundant` over the pushed stream (the
        barometer's readings as the detector saw them; the accelerometer's checks as pushed, not run
        again)."""
        import numpy as np

        from flightmode.detector.pressure import evaluate_redundant

        tb = np.concatenate([np.zeros(0), *self._source.readings_t])
        pb = np.concatenate([np.zeros(0), *self._source.readings_pa])
        acc = take(x, self._acc)
        return evaluate_redundant(
            t_s,
            acc,
            tb,
            pb,
            labels,
            self.params,
            self.sigma2,
            self.pressure_params,
            acc_checks=self.accel.checks,
        )


def _redundant(method: str) -> Callable:
    def make(
        fs_hz: float,
        channels: Sequence[str],
        *,
        window_s: float = POINT.window_s,
        k: float = POINT.k_sigma,
        time_threshold_s: float = POINT.time_threshold_s,
        weight: float = POINT.weight,
        sigma2: Any = None,
        baro_rate_pa_s: float = BARO_RATE_PA_S,
        baro_margin_hpa: float = BARO_MARGIN_HPA,
        baro_hold_s: float = BARO_HOLD_S,
        baro_fs_hz: float = BARO_FS_HZ,
        arrival_ground_pa: float | None = None,
        rest: Any = None,
        sensor_lsb_g: float | None = None,
    ) -> RedundantDetector:
        if method == "nmv" and weight != POINT.weight:
            raise DetectorError("nmv+baro: weight is the EMV's (use emv+baro)")
        pp = pressure_params(baro_fs_hz, baro_rate_pa_s, baro_margin_hpa, baro_hold_s, arrival_ground_pa)
        p = moving_variance_params(method, fs_hz, window_s, k, time_threshold_s, weight, None)
        s2 = sigma2_of(sigma2, rest, channels, p.window, sensor_lsb_g, f"{method}+baro")
        return RedundantDetector(MovingVarianceDetector(p, s2, channels), pp, channels)

    make.__name__ = make.__qualname__ = f"{method}_baro"
    make.__doc__ = (
        f"{method.upper()} OR the pressure source to suspend, both to resume (detector.pressure's rule)."
    )
    return _declare("redundant", (*ACC_CHANNELS, *PRESSURE_CHANNELS), f"{method.upper()} and the barometer")(
        make
    )


nmv_baro = _redundant("nmv")
emv_baro = _redundant("emv")


# ----------------------------------------------------------------------------------------------
# two sources, any two detectors


class TwoSource:
    """Two detectors, each on its own channels: a sample is at rest only when both say so (suspend
    when ANY says flying, resume only when ALL say on the ground)."""

    kind = "two_source"

    def __init__(self, parts: list[tuple[str, Any, list[int]]]):
        self.parts = parts  # (name, detector, its columns in x)
        self._n = 0

    def push(self, t_s, x):
        import numpy as np

        from flightmode.detector import interface

        x = np.asarray(x, float)
        out = np.ones(np.asarray(t_s).shape[0], bool)
        for name, det, cols in self.parts:
            out &= interface.checked_push(name, det, t_s, take(x, cols), self._n)
        self._n += out.shape[0]
        return out

    def close(self) -> None:
        for _, det, _ in self.parts:
            close = getattr(det, "close", None)
            if callable(close):
                close()


def _two_loaded(first: str, second: str, first_params, second_params):
    from flightmode.detector import interface

    out = []
    for key, spec, params in (("first", first, first_params), ("second", second, second_params)):
        if params is not None and not isinstance(params, dict):
            raise DetectorError(f"two-source: {key}_params = {params!r}: a table, e.g. {{k = 3}}")
        loaded = interface.load(str(spec), what=f"two-source {key}")
        out.append((loaded, dict(params or {})))
    return out


def _two_channels(
    first: str = "nmv", second: str = PRESSURE_SPEC, first_params=None, second_params=None, **_
):
    chans: list[str] = []
    for loaded, params in _two_loaded(first, second, first_params, second_params):
        chans += [c for c in loaded.channels_for(params) if c not in chans]
    return tuple(chans)


@_declare("two_source", (*ACC_CHANNELS, *PRESSURE_CHANNELS), "two sources")
def two_source(
    fs_hz: float,
    channels: Sequence[str],
    *,
    first: str = "nmv",
    second: str = PRESSURE_SPEC,
    first_params: dict | None = None,
    second_params: dict | None = None,
    rest: Any = None,
    sensor_lsb_g: float | None = None,
    baro_fs_hz: float | None = None,
    arrival_ground_pa: float | None = None,
) -> TwoSource:
    """Any two detectors (``first``, ``second``: a registered name or ``package.module:make``, with
    ``first_params``, ``second_params``), by default seed 000's recommended NMV and the pressure
    source: at rest only when both say so (EASA's two independent means)."""

    from flightmode.detector import interface

    context = {"sensor_lsb_g": sensor_lsb_g, "baro_fs_hz": baro_fs_hz, "arrival_ground_pa": arrival_ground_pa}
    parts = []
    for loaded, params in _two_loaded(first, second, first_params, second_params):
        ch = loaded.channels_for(params)
        cols = columns(channels, ch, f"two-source's {loaded.name}")
        sub_rest = None if rest is None else take(rest, cols)
        given = {k: v for k, v in context.items() if v is not None}
        parts.append((loaded.name, interface.build(loaded, fs_hz, ch, params, sub_rest, **given), cols))
    return TwoSource(parts)


vars(two_source)["channels_for"] = _two_channels

__all__ = [
    "ActivityDetector",
    "MovingVarianceDetector",
    "PressureOnly",
    "PressureSource",
    "RedundantDetector",
    "TwoSource",
    "amd",
    "amvd",
    "ared",
    "emv",
    "emv_baro",
    "fsd",
    "frd",
    "held",
    "ltsd",
    "mbcd",
    "mbgtd",
    "nmv",
    "nmv_baro",
    "pressure",
    "shod",
    "two_source",
]
