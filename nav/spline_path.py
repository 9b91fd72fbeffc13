"""Cubic-spline paths from accelerations: the two methods of seed 002 (Revesz 2014).

The path is a cubic spline ``S_i(t) = a_i + b_i (t - t_i) + c_i (t - t_i)^2 + d_i (t - t_i)^3`` on
``[t_i, t_{i+1}]`` (seed 002 eq. 1) whose second derivative at each sample is the measured
acceleration: ``2 c_i = acc(t_i)``. Continuity of position, velocity and acceleration (eq. 4-6)
gives eq. 7-13, and the unknown positions ``a_i`` follow by one of:

- **tridiagonal** (section II): boundary positions ``f(t_0)`` and ``f(t_n)``; rows 1..n-1 are eq. 15
  (non-uniform steps ``h_i``), which for a uniform step is eq. 16 times ``3/h``; solved in O(n)
  with ``scipy.linalg.solve_banded``. ``b_i`` from eq. 13, ``d_i`` from eq. 12.
- **recurrence** (section III): initial position ``a_0`` and velocity ``b_0``; ``b_i`` by eq. 17,
  ``a_i`` by eq. 18 (the sums of eq. 19), ``d_i`` by eq. 12. :class:`RecurrencePath` is the
  streaming form: each new sample extends the spline by one piece in O(1), and any chunking gives
  bit-identical coefficients to the batch call (the running sums continue exactly across chunks).

Both return a :class:`scipy.interpolate.PPoly` (breakpoints ``t_0..t_n``; coefficients
``[d, c, b, a]``, trailing axes for 3D: seed 002 section V, each axis with its own boundary
conditions), so position, velocity (``.derivative()``) and acceleration (``.derivative(2)``) can be
evaluated anywhere. Outside ``[t_0, t_n]`` the end pieces extrapolate.

Seed 002's worked example (section IV) says "f(4) = 0" for the final boundary; with samples at
t = 0..5 s it must be f(5) = 0 (its own matrix and solution have a_5 = 0), and its "n = 6" counts
samples, not intervals. Both are typos; tests/nav/test_spline_path.py reproduces the example.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import PPoly
from scipy.linalg import solve_banded

from sim.errors import FlightmodeError


class NavError(FlightmodeError):
    """Bad input to the path estimator."""


def _check(t_s, acc, min_samples: int = 3) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    t = np.asarray(t_s, dtype=float)
    a = np.asarray(acc, dtype=float)
    if t.ndim != 1:
        raise NavError(f"time must be a 1-D array, got shape {t.shape}")
    if a.shape[:1] != t.shape:
        raise NavError(f"acceleration has {a.shape[0] if a.ndim else 0} rows but time has {t.shape[0]}")
    if t.shape[0] < min_samples:
        raise NavError(f"{t.shape[0]} sample(s): a cubic-spline path needs at least 3 (two pieces)")
    if not np.isfinite(t).all():
        raise NavError(f"time has NaN or inf (first at sample {int(np.flatnonzero(~np.isfinite(t))[0])})")
    if not np.isfinite(a).all():
        bad = int(np.flatnonzero(~np.isfinite(a.reshape(a.shape[0], -1)).all(axis=1))[0])
        raise NavError(f"acceleration has NaN or inf at sample {bad}: clean or cut the stream first")
    h = np.diff(t)
    if np.any(h <= 0):
        i = int(np.flatnonzero(h <= 0)[0])
        raise NavError(f"time is not increasing at sample {i + 1} ({t[i]!r} then {t[i + 1]!r})")
    return t, a, h


def _hb(h: np.ndarray, ndim: int) -> np.ndarray:
    return h.reshape(h.shape + (1,) * (ndim - 1))


def _ppoly(t: np.ndarray, a: np.ndarray, b: np.ndarray, c: np.ndarray, h: np.ndarray) -> PPoly:
    """Coefficients of the n pieces from a_i, b_i (i < n) and c_i (i <= n), written straight into
    the PPoly's (4, n, ...) array (no intermediate stack)."""
    n = t.shape[0] - 1
    coef = np.empty((4, n) + c.shape[1:])
    hb = _hb(h, c.ndim)
    np.subtract(c[1:], c[:-1], out=coef[0])
    coef[0] /= 3.0 * hb  # eq. 12: d_i = (c_{i+1} - c_i) / (3 h_i)
    coef[1] = c[:-1]
    coef[2] = b[:n]
    coef[3] = a[:n]
    return PPoly.construct_fast(coef, t, extrapolate=True)


def tridiagonal_path(t_s, acc, pos_start, pos_end) -> PPoly:
    """Seed 002 section II: positions from accelerations and the two boundary positions.

    ``acc`` is (n+1,) or (n+1, k); ``pos_start``/``pos_end`` scalars or (k,) (per axis)."""
    t, acc, h = _check(t_s, acc)
    n = t.shape[0] - 1
    if np.ptp(h) <= 1e-12 * h[0]:
        return _tridiagonal_uniform(t, acc, float(np.mean(h)), pos_start, pos_end)
    # eq. 15 for rows 1..n-1:  3/h_{i-1} a_{i-1} - (3/h_{i-1} + 3/h_i) a_i + 3/h_i a_{i+1}
    #                          = h_{i-1} c_{i-1} + 2 (h_{i-1} + h_i) c_i + h_i c_{i+1}
    # scaled by h_{i-1} h_i / 3 (for a uniform step this is eq. 16 exactly: 1, -2, 1 and h^2/3 (...))
    c = 0.5 * acc  # 2 c_i = f''(t_i)
    ab = np.empty((3, n + 1))
    h0, h1 = h[:-1], h[1:]
    s = h0 * h1 / 3.0
    ab[0, 2:] = 3.0 / h1 * s  # super-diagonal: coefficient of a_{i+1} in row i (column i+1)
    ab[1, 1:-1] = -(3.0 / h0 + 3.0 / h1) * s
    ab[2, :-2] = 3.0 / h0 * s  # sub-diagonal: coefficient of a_{i-1} in row i (column i-1)
    _boundary_rows(ab)
    rhs = np.empty_like(c)
    hb0, hb1, sb = _hb(h0, c.ndim), _hb(h1, c.ndim), _hb(s, c.ndim)
    rhs[1:-1] = (hb0 * c[:-2] + 2.0 * (hb0 + hb1) * c[1:-1] + hb1 * c[2:]) * sb
    rhs[0], rhs[-1] = pos_start, pos_end
    a = solve_banded((1, 1), ab, rhs, overwrite_ab=True, overwrite_b=True, check_finite=False)
    hb = _hb(h, c.ndim)
    b = (a[1:] - a[:-1]) / hb - (2.0 * c[:-1] + c[1:]) / 3.0 * hb  # eq. 13
    return _ppoly(t, a, b, c, h)


def _boundary_rows(ab: np.ndarray) -> None:
    ab[0, :2] = 0.0  # row 0 is a_0 = f(t_0): no super-diagonal entry (ab[0, 0] is unused)
    ab[2, -2:] = 0.0  # row n is a_n = f(t_n): no sub-diagonal entry (ab[2, -1] is unused)
    ab[1, 0] = ab[1, -1] = 1.0  # a_0 = f(t_0), a_n = f(t_n)


def _tridiagonal_uniform(t, acc, hh: float, pos_start, pos_end) -> PPoly:
    """Eq. 16 (uniform step h), with c = acc / 2:
    a_{i-1} - 2 a_i + a_{i+1} = h^2/6 (acc_{i-1} + 4 acc_i + acc_{i+1});
    the coefficients are then written in place into the PPoly's (4, n, ...) array."""
    n = t.shape[0] - 1
    ab = np.empty((3, n + 1))
    ab[0], ab[1], ab[2] = 1.0, -2.0, 1.0
    _boundary_rows(ab)
    rhs = np.empty(acc.shape)
    inner = rhs[1:-1]
    np.multiply(acc[1:-1], 4.0, out=inner)
    inner += acc[:-2]
    inner += acc[2:]
    inner *= hh * hh / 6.0
    rhs[0], rhs[-1] = pos_start, pos_end
    a = solve_banded((1, 1), ab, rhs, overwrite_ab=True, overwrite_b=True, check_finite=False)
    coef = np.empty((4, n) + acc.shape[1:])
    np.add(acc[:-1], acc[1:], out=coef[0])
    coef[0] += acc[:-1]
    coef[0] *= hh / 6.0  # (2 c_i + c_{i+1}) h / 3
    np.subtract(a[1:], a[:-1], out=coef[2])
    coef[2] *= 1.0 / hh
    coef[2] -= coef[0]  # eq. 13: b_i = (a_{i+1} - a_i) / h - (2 c_i + c_{i+1}) h / 3
    np.subtract(acc[1:], acc[:-1], out=coef[0])
    coef[0] *= 1.0 / (6.0 * hh)  # eq. 12: d_i = (c_{i+1} - c_i) / (3 h)
    np.multiply(acc[:-1], 0.5, out=coef[1])  # c_i = acc_i / 2
    coef[3] = a[:-1]
    return PPoly.construct_fast(coef, t, extrapolate=True)


class RecurrencePath:
    """Seed 002 section III in streaming form: ``push(t, acc)`` extends the spline by one piece per
    new sample in O(1) (chunks of any length); ``ppoly()`` returns the spline so far. ``restart``
    sets the velocity (zero-velocity update) at the last sample, keeping the position."""

    def __init__(self, pos0, vel0):
        self._a0 = np.asarray(pos0, float)
        self._b0 = np.asarray(vel0, float)
        self._t: list[np.ndarray] = []
        self._a: list[np.ndarray] = []
        self._b: list[np.ndarray] = []
        self._c: list[np.ndarray] = []
        self._last = None  # (t, a, b, c) of the last sample

    def push(self, t_s, acc) -> None:
        t = np.asarray(t_s, float)
        acc = np.asarray(acc, float)
        if t.shape[0] == 0:
            return
        if self._last is None:
            if t.shape[0] < 1:
                return
            first_t, first_c = t[0], 0.5 * acc[0]
            self._last = (first_t, np.broadcast_to(self._a0, first_c.shape).astype(float),
                          np.broadcast_to(self._b0, first_c.shape).astype(float), first_c)
            self._append(t[:1], self._last[1][None], self._last[2][None], self._last[3][None])
            t, acc = t[1:], acc[1:]
            if t.shape[0] == 0:
                return
        tl, al, bl, cl = self._last
        tt = np.concatenate([[tl], t])
        _, _, h = _check(tt, np.concatenate([cl[None] * 2.0, acc]), min_samples=2)
        c = 0.5 * acc
        cc = np.concatenate([cl[None], c])
        hb = _hb(h, cc.ndim)
        # eq. 17: b_i = b_{i-1} + (c_{i-1} + c_i) h_{i-1}
        b = np.cumsum(np.concatenate([bl[None], (cc[:-1] + cc[1:]) * hb]), axis=0)
        # eq. 18: a_i = a_{i-1} + b_{i-1} h_{i-1} + (2 c_{i-1} + c_i)/3 h_{i-1}^2
        a = np.cumsum(np.concatenate([al[None], b[:-1] * hb + (2.0 * cc[:-1] + cc[1:]) / 3.0 * hb * hb]), axis=0)
        self._append(t, a[1:], b[1:], c)
        self._last = (t[-1], a[-1], b[-1], c[-1])

    def restart(self, vel) -> None:
        """Zero-velocity update (or any known velocity) at the last pushed sample."""
        if self._last is None:
            raise NavError("restart before the first sample")
        tl, al, bl, cl = self._last
        nb = np.broadcast_to(np.asarray(vel, float), bl.shape).astype(float)
        self._last = (tl, al, nb, cl)
        self._b[-1] = self._b[-1].copy()
        self._b[-1][-1] = nb

    def _append(self, t, a, b, c) -> None:
        self._t.append(t)
        self._a.append(a)
        self._b.append(b)
        self._c.append(c)

    @property
    def position(self) -> np.ndarray:
        return np.concatenate(self._a)

    def ppoly(self) -> PPoly:
        t = np.concatenate(self._t)
        if t.shape[0] < 3:
            raise NavError(f"{t.shape[0]} sample(s) pushed: a cubic-spline path needs at least 3")
        a, b, c = (np.concatenate(x) for x in (self._a, self._b, self._c))
        # the velocity the piece i starts with is b_i; after a restart at sample j, b_j was replaced,
        # so piece j starts from the restarted velocity (and piece j-1 ends with its own)
        return _ppoly(t, a, b[:-1], c, np.diff(t))


def recurrence_path(t_s, acc, pos0, vel0) -> PPoly:
    """Seed 002 section III in one call: positions from accelerations, initial position and velocity."""
    _check(t_s, acc)
    r = RecurrencePath(pos0, vel0)
    r.push(t_s, acc)
    return r.ppoly()
