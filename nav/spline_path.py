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

from flightmode.errors import NavError


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
    # uniform up to the rounding of the time stamps themselves (t = k / fs has ulp-level jitter:
    # 9e-13 s at t = 7200 s), so the eq. 16 fast path applies to real sampled streams
    if np.ptp(h) <= 1e-9 * h[0] + 8.0 * np.finfo(float).eps * float(np.abs(t).max()):
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
    a_{i-1} - 2 a_i + a_{i+1} = h^2/6 (acc_{i-1} + 4 acc_i + acc_{i+1}).

    Memory is the cost at these sizes (the first touch of fresh pages and cache misses; see
    benchmarks/bench_path.py), so nothing is allocated but the PPoly's own (4, n, ...) coefficient
    array: the right-hand side (Fortran order, LAPACK's layout, solved in place) lives in the
    memory of coef[0:2] and the band matrix in that of coef[2:4] (when it fits: 3 axes or more).
    coef[3] and coef[2] are written from the solution before coef[0:2] are overwritten, and every
    elementwise pass runs in cache-sized blocks."""
    n = t.shape[0] - 1
    shape = acc.shape[1:]
    k = int(np.prod(shape, dtype=int))
    coef = np.empty((4, n) + shape)
    flat = coef.reshape(4, n * k)
    a2 = acc.reshape(n + 1, k)
    rhs = flat[0:2].reshape(-1)[: (n + 1) * k].reshape((n + 1, k), order="F")
    if 3 * (n + 1) <= 2 * n * k:
        ab = flat[2:4].reshape(-1)[: 3 * (n + 1)].reshape(3, n + 1)
    else:  # a single axis: the band does not fit in coef[2:4]
        ab = np.empty((3, n + 1))
    ab[0], ab[1], ab[2] = 1.0, -2.0, 1.0
    _boundary_rows(ab)
    for s0 in range(1, n, BLOCK):  # rows 1..n-1, in cache-sized blocks
        s1 = min(n, s0 + BLOCK)
        inner = rhs[s0:s1]
        np.multiply(a2[s0:s1], 4.0, out=inner)
        inner += a2[s0 - 1 : s1 - 1]
        inner += a2[s0 + 1 : s1 + 1]
        inner *= hh * hh / 6.0
    rhs[0] = np.broadcast_to(np.asarray(pos_start, float), shape).reshape(k)
    rhs[-1] = np.broadcast_to(np.asarray(pos_end, float), shape).reshape(k)
    a = solve_banded((1, 1), ab, rhs, overwrite_ab=True, overwrite_b=True, check_finite=False)
    c0, c1, c2, c3 = (coef[i].reshape(n, k) for i in range(4))
    # coef[3] and coef[2] first, from the solution (which may live in coef[0:2]), block by block
    for s0 in range(0, n, BLOCK):
        s1 = min(n, s0 + BLOCK)
        c3[s0:s1] = a[s0:s1]
        np.subtract(a[s0 + 1 : s1 + 1], a[s0:s1], out=c2[s0:s1])
    for s0 in range(0, n, BLOCK):
        s1 = min(n, s0 + BLOCK)
        lo, hi, nx = a2[s0:s1], c0[s0:s1], a2[s0 + 1 : s1 + 1]
        b = c2[s0:s1]
        b *= 1.0 / hh
        np.add(lo, nx, out=hi)
        hi += lo
        hi *= hh / 6.0  # (2 c_i + c_{i+1}) h / 3
        b -= hi  # eq. 13: b_i = (a_{i+1} - a_i) / h - (2 c_i + c_{i+1}) h / 3
        np.subtract(nx, lo, out=hi)
        hi *= 1.0 / (6.0 * hh)  # eq. 12: d_i = (c_{i+1} - c_i) / (3 h)
        np.multiply(lo, 0.5, out=c1[s0:s1])  # c_i = acc_i / 2
    return PPoly.construct_fast(coef, t, extrapolate=True)


BLOCK = 1 << 15  # rows per block in the recurrence (about 0.8 MB per (rows, 3) array)


def _extend(al, bl, cl, hb, acc, a, b, c) -> None:
    """Eq. 17-18 for one block of new samples, continued from the last sample's (a, b, c)."""
    np.multiply(acc, 0.5, out=c)
    # eq. 17: b_i = b_{i-1} + (c_{i-1} + c_i) h_{i-1}   (running sum continued from b_last)
    np.add(c[:-1], c[1:], out=b[1:])
    b[0] = cl + c[0]
    b *= hb
    b[0] += bl
    np.cumsum(b, axis=0, out=b)
    # eq. 18: a_i = a_{i-1} + b_{i-1} h_{i-1} + (2 c_{i-1} + c_i)/3 h_{i-1}^2
    np.multiply(c[:-1], 2.0, out=a[1:])
    a[0] = 2.0 * cl
    a += c
    a /= 3.0
    a *= hb
    a *= hb
    a[1:] += b[:-1] * hb[1:]
    a[0] += bl * hb[0]
    a[0] += al
    np.cumsum(a, axis=0, out=a)


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
        n = t.shape[0]
        if n == 0:
            return
        if self._last is None:
            # the first sample carries the initial state: stored as row 0 of this chunk's arrays
            tl, cl = t[0], 0.5 * acc[0]
            al = np.broadcast_to(self._a0, cl.shape).astype(float)
            bl = np.broadcast_to(self._b0, cl.shape).astype(float)
            first = 1
        else:
            tl, al, bl, cl = self._last
            first = 0
        m = n - first  # new pieces
        if m == 0:
            self._append(t, al[None], bl[None], cl[None])
            self._last = (tl, al, bl, cl)
            return
        tn, accn = t[first:], acc[first:]
        h = np.diff(np.concatenate([[tl], tn]))
        if np.any(h <= 0) or not np.isfinite(accn).all() or not np.isfinite(tn).all():
            # name the first bad sample (index within this chunk)
            _check(np.concatenate([[tl], tn]), np.concatenate([2.0 * cl[None], accn]), min_samples=2)
        a = np.empty((n,) + cl.shape)
        b = np.empty_like(a)
        c = np.empty_like(a)
        if first:
            a[0], b[0], c[0] = al, bl, cl
        # blocks of BLOCK rows keep every pass in cache; each block continues the running sums of
        # the one before exactly as a separate push would (bit-identical for any chunking)
        for s0 in range(0, m, BLOCK):
            s1 = min(m, s0 + BLOCK)
            sl = slice(first + s0, first + s1)
            _extend(al, bl, cl, _hb(h[s0:s1], accn.ndim), accn[s0:s1], a[sl], b[sl], c[sl])
            al, bl, cl = a[first + s1 - 1], b[first + s1 - 1], c[first + s1 - 1]
        self._append(t, a, b, c)
        self._last = (t[-1], a[-1].copy(), b[-1].copy(), c[-1].copy())

    def restart(self, vel) -> None:
        """Zero-velocity update (or any known velocity) at the last pushed sample."""
        if self._last is None:
            raise NavError("restart before the first sample")
        tl, al, bl, cl = self._last
        nb = np.broadcast_to(np.asarray(vel, float), bl.shape).astype(float)
        self._last = (tl, al, nb, cl)
        self._b[-1][-1] = nb  # each chunk's arrays are owned by this object

    def _append(self, t, a, b, c) -> None:
        self._t.append(t)
        self._a.append(a)
        self._b.append(b)
        self._c.append(c)

    @property
    def position(self) -> np.ndarray:
        return self._a[0] if len(self._a) == 1 else np.concatenate(self._a)

    def ppoly(self) -> PPoly:
        one = len(self._t) == 1
        t = self._t[0] if one else np.concatenate(self._t)
        if t.shape[0] < 3:
            raise NavError(f"{t.shape[0]} sample(s) pushed: a cubic-spline path needs at least 3")
        a, b, c = ((x[0] if one else np.concatenate(x)) for x in (self._a, self._b, self._c))
        # the velocity the piece i starts with is b_i; after a restart at sample j, b_j was replaced,
        # so piece j starts from the restarted velocity (and piece j-1 ends with its own)
        return _ppoly(t, a, b[:-1], c, np.diff(t))


def recurrence_path(t_s, acc, pos0, vel0) -> PPoly:
    """Seed 002 section III in one call: positions from accelerations, initial position and velocity.

    The same arithmetic as :class:`RecurrencePath` (the same blocks of :func:`_extend`, so the two
    agree bit for bit), written straight into the PPoly's coefficient array: at 1e7 samples the
    cost is the memory written, so no intermediate a, b, c arrays are kept."""
    t, acc, h = _check(t_s, acc)
    n = t.shape[0]
    shape = acc.shape[1:]
    coef = np.empty((4, n - 1) + shape)
    d_, c_, b_, a_ = coef
    al = np.broadcast_to(np.asarray(pos0, float), shape).astype(float)
    bl = np.broadcast_to(np.asarray(vel0, float), shape).astype(float)
    cl = 0.5 * acc[0]
    a_[0], b_[0], c_[0] = al, bl, cl
    c_last = None
    for s0 in range(1, n, BLOCK):
        s1 = min(n, s0 + BLOCK)
        hb = _hb(h[s0 - 1 : s1 - 1], acc.ndim)
        if s1 <= n - 1:
            ta, tb, tc = a_[s0:s1], b_[s0:s1], c_[s0:s1]
            _extend(al, bl, cl, hb, acc[s0:s1], ta, tb, tc)
        else:  # the block holding the last sample, which has no piece of its own
            ta, tb, tc = (np.empty((s1 - s0,) + shape) for _ in range(3))
            _extend(al, bl, cl, hb, acc[s0:s1], ta, tb, tc)
            a_[s0:], b_[s0:], c_[s0:] = ta[:-1], tb[:-1], tc[:-1]
            c_last = tc[-1]
        al, bl, cl = ta[-1], tb[-1], tc[-1]
    # eq. 12: d_i = (c_{i+1} - c_i) / (3 h_i), as _ppoly computes it
    np.subtract(c_[1:], c_[:-1], out=d_[:-1])
    d_[-1] = c_last - c_[-1]
    d_ /= 3.0 * _hb(h, acc.ndim)
    return PPoly.construct_fast(coef, t, extrapolate=True)
