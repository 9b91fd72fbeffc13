"""Seed 000's printed numbers, and its section 7 hardware maths: eq. (15) and Tables 6-8.

The paper's tables as data (the one copy: :mod:`flightmode.studies.seed000` sets our measurements
beside them), with what our copy of the text garbles said where it is read:

- Table 1 (the LIS302DL): "Measurement range (g) +-2 or +-8". The datasheet's full scale +-2 g
  reads to about +-2.3 g (the 8-bit count at 18 mg/digit: 127 x 18 mg); the sensor presets
  (:mod:`flightmode.sim.sensor.accelerometer`) saturate there. Both are printed side by side.
- Table 2: P_M and TimeError = 1 / P_M (s) at 2, 2.5, 3, 4 sigma^2 (eq. 13).
- Table 3: "MV ~ 0.6 0.5 0.51 0.51" at W_s 0.5, 1, 2, 3 s. The unit is lost; with section 4.1's
  static variance "around 5 x 10^-6 g^2" and its "NMV responses ... approximately equal to 5 x 10^-6 g^2"
  (1 s windows) the row is in 10^-5 g^2, i.e. 1.2, 1.0, 1.02, 1.02 sigma^2.
- Tables 4 / 5: per-axis P_FA, P_FA^t and P_FA = (P_FA^t)^(T_th / W_s) (eq. 14). The paper's own rows
  are consistent with eq. 14 (the product and the power) except Table 4 at 3 sigma^2: its P_FA^t
  2e-10 is not the product of its axes (5e-2 x 7e-4 x 9e-7 = 3.2e-11, whose 4th power 1e-42 is the
  T_th = 4 s cell), and 6e-33 at T_th = 3 s is neither 2e-10^3 nor 3.2e-11^3 (:func:`paper_pfa_consistency`).
- Eq. (15): the N-point moving averager H(z) = (1/N)(1 + z^-1 + ... + z^-(N-1)), built as Fig. 19
  draws it (a comb x(n) - x(n - N) into an integrator, then 1/N): :func:`moving_average_eq15`. Fig. 20's
  NMV network is MA(x^2) - MA(x)^2 (:func:`nmv_network`), Fig. 21-22's exponential averager
  y(n) = y(n-1) + (alpha/N)(x(n) - y(n-1)) (:func:`exponential_averager`).
- Table 6 (logic cells per operation on R-bit input): delay R registers; adder R; integrator R logic +
  R registers; multiplication by a constant 0 (a power of two: a shift) or R; squaring R^2 + 4R.
- Table 7 (logic cells per algorithm) is garbled beyond reading except its last row, the EMV network
  R^2 + 13R + 12. The NMV row is recovered from Table 8, whose 24 NMV cells it fits exactly for N = 64:
  2R^2 + 16R + 15 logic elements with the delay line in memory, plus 3NR (the N samples of x, R bits,
  and of x^2, 2R bits) without memory; "Total of bits with memory" is that 3NR. Table 8's caption
  ("for N = NN", digits lost) is N = 64: 1536 bits / 8 = 192 = 3 x 64.
- Table 8 (LEs and bits for R = 8..18, 1 and 3 blocks): reproduced cell for cell by :func:`table8`.
- Table 9's "813 <= LEs <= 3405" (NMV) and "540 <= LEs <= 2016" (EMV) are the 3-block, memory
  figures for R = 8 and R = 20 (3 x (2 x 400 + 320 + 15) = 3405; 3 x (400 + 260 + 12) = 2016). Its
  EMV weight row "1/N <= alpha <= 5/N" is the EA's multiplier alpha/N of Fig. 21 for weights 1-5
  (footnote: alpha/N "a multiple of 2", i.e. a power of two, a shift), its window footnote N "a
  multiple of 2": at 60-70 Hz and W_s = 1 s, N = 64 = 2^6, the only power of two in that band.
"""

from __future__ import annotations

import numpy as np

from flightmode.errors import DetectorError

# ------------------------------------------------------------------------------ the paper's numbers
# seed 000, Table 1 (LIS302DL); the range beside the datasheet's reach (ST LIS302DL datasheet: 18
# mg/digit typ., 8-bit two's complement, so +-127 x 18 mg ~ +-2.3 g; 72 mg/digit: ~ +-9.2 g)
TABLE1 = (
    ("Noise (1 sigma)", "2.23 mg", "2.23 mg (the presets' noise_g)"),
    ("Measurement range", "+-2 g or +-8 g", "datasheet full scale +-2 g reads to +-2.3 g; +-8 g to +-9.2 g"),
    ("Output data rate", "100 or 400 Hz", "100 or 400 Hz"),
    ("Temperature range", "-40 to +85 degC", "-"),
    ("Power consumption", "< 1 mW", "-"),
)
# seed 000, Table 2: T_sigma (sigma^2) -> (P_M, TimeError as printed)
TABLE2 = {
    2.0: (6e-3, "166 s"),
    2.5: (8e-6, "35 hours"),
    3.0: (2e-11, "1585 years"),
    4.0: (6e-19, "5e10 years"),
}
# seed 000, Table 3: W_s (s) -> MV, in 1e-5 g^2 (module docstring), and sigma^2 = 5e-6 g^2 (section 4.1)
TABLE3_RAW = {0.5: 0.6, 1.0: 0.5, 2.0: 0.51, 3.0: 0.51}
TABLE3_UNIT_G2 = 1e-5
SIGMA2_PAPER_G2 = 5e-6
TABLE3 = {w: v * TABLE3_UNIT_G2 / SIGMA2_PAPER_G2 for w, v in TABLE3_RAW.items()}  # in sigma^2
# seed 000, Tables 4 and 5: P_FA per T_sigma (3, 4, 5 sigma^2): per axis, P_FA^t, and P_FA at T_th 3 / 4 s
PFA_KS = (3.0, 4.0, 5.0)
PFA_TTHS = (3.0, 4.0)
TABLES_4_5: dict[int, dict[str, tuple]] = {
    4: {
        "x": (5e-2, 8e-2, 1e-1),
        "y": (7e-4, 2e-3, 4e-3),
        "z": (9e-7, 2e-6, 2e-4),
        "t": (2e-10, 3e-10, 8e-8),
        "P_FA": ((6e-33, 1e-42), (3e-29, 1e-38), (5e-22, 4e-29)),  # (T_th 3 s, 4 s) per T_sigma
    },
    5: {
        "x": (3e-1, 6e-1, 7e-1),
        "y": (1e-2, 1e-1, 4e-1),
        "z": (7e-3, 7e-2, 2e-1),
        "t": (2e-5, 4e-3, 6e-2),
        "P_FA": ((9e-15, 2e-19), (7e-8, 3e-10), (2e-4, 1e-5)),
    },
}
# seed 000, Table 8 (N = 64): R -> (NMV LEs without memory 1/3 blocks, with memory 1/3, bits 1/3, EMV LEs 1/3)
TABLE8 = {
    8: (1807, 5421, 271, 813, 1536, 4608, 180, 540),
    10: (2295, 6885, 375, 1125, 1920, 5760, 242, 726),
    12: (2799, 8397, 495, 1485, 2304, 6912, 312, 936),
    14: (3319, 9957, 631, 1893, 2688, 8064, 390, 1170),
    16: (3855, 11565, 783, 2349, 3072, 9216, 476, 1428),
    18: (4407, 13221, 951, 2853, 3456, 10368, 570, 1710),
}
TABLE8_N = 64
TABLE8_COLUMNS = (
    "nmv_les_no_memory_1",
    "nmv_les_no_memory_3",
    "nmv_les_memory_1",
    "nmv_les_memory_3",
    "nmv_bits_memory_1",
    "nmv_bits_memory_3",
    "emv_les_1",
    "emv_les_3",
)
# seed 000, Table 9 (NMV and EMV columns alike except alpha and the resources)
TABLE9 = {
    "T_sigma": "2.5 sigma^2 - 4 sigma^2",
    "T_th": "4 s <= T_th <= 5 s",
    "alpha": ("- (NMV)", "1/N <= alpha <= 5/N (EMV)"),
    "W_s": "1 s <= W_s <= 2 s (N a multiple of 2)",
    "P_M": ">= 6e-19",
    "P_FA^t": "<= 4e-3",
    "P_FA": "<= 3e-10",
    "sampling": "60 Hz - 70 Hz",
    "resources": ("813 <= LEs <= 3405 (NMV)", "540 <= LEs <= 2016 (EMV)"),
}
TABLE9_RATE_HZ = (60.0, 70.0)
TABLE9_BITS = (8, 20)  # the R range behind Table 9's LE bounds (module docstring)


def paper_pfa_consistency() -> list[dict]:
    """Tables 4 / 5 against eq. 14 itself: the product of the printed axes beside the printed P_FA^t,
    and (P_FA^t)^(T_th / W_s), W_s = 1 s, beside the printed P_FA."""
    rows = []
    for table, t in TABLES_4_5.items():
        for i, k in enumerate(PFA_KS):
            prod = t["x"][i] * t["y"][i] * t["z"][i]
            for j, tth in enumerate(PFA_TTHS):
                rows.append(
                    {
                        "table": table,
                        "T_sigma": k,
                        "T_th_s": tth,
                        "P_FA_t_printed": t["t"][i],
                        "P_FA_t_product": prod,
                        "P_FA_printed": t["P_FA"][i][j],
                        "P_FA_from_printed_t": t["t"][i] ** tth,  # eq. 14, W_s = 1 s
                        "P_FA_from_product": prod**tth,
                    }
                )
    return rows


# ------------------------------------------------------------------------------------- eq. (15)
def moving_average_eq15(x: np.ndarray, n: int) -> np.ndarray:
    """Eq. (15)'s N-point moving averager as Fig. 19 builds it: the comb x(k) - x(k - N), an
    integrator (an adder fed back its own output through one delay) and the multiplication by 1/N.
    Output k is the mean of x(k - N + 1) .. x(k), the samples before the first taken as 0 (the
    delay line starts empty), along axis 0. Integer input stays exact up to the final 1/N."""
    x = np.asarray(x)
    if n < 1:
        raise DetectorError(f"moving averager of {n} points: N must be >= 1")
    delayed = np.zeros_like(x)
    delayed[n:] = x[:-n] if x.shape[0] > n else delayed[n:]
    acc = np.cumsum(x - delayed, axis=0)  # the integrator y(k) = y(k-1) + (x(k) - x(k-N))
    return acc / n


def eq15_response(n: int, f_over_fs: np.ndarray) -> np.ndarray:
    """|H(e^jw)| of eq. (15) at w = 2 pi f/fs: |sin(N w/2) / (N sin(w/2))| (1 at w = 0)."""
    w = 2.0 * np.pi * np.asarray(f_over_fs, float)
    num, den = np.sin(n * w / 2.0), n * np.sin(w / 2.0)
    safe = np.abs(den) > 1e-15
    return np.where(safe, np.abs(num / np.where(safe, den, 1.0)), 1.0)


def nmv_network(x: np.ndarray, n: int) -> np.ndarray:
    """Fig. 20's recursive N-point moving variance network: MA(x^2) - MA(x)^2 with MA eq. (15), i.e.
    eq. (1)'s NMV (1/N normalisation) once the delay line is full (from output N - 1)."""
    x = np.asarray(x, float)
    return moving_average_eq15(x * x, n) - moving_average_eq15(x, n) ** 2


def exponential_averager(x: np.ndarray, alpha_over_n: float, y0: float = 0.0) -> np.ndarray:
    """Fig. 21's exponential averager: y(k) = y(k-1) + (alpha/N) (x(k) - y(k-1)) (eq. 4)."""
    from scipy.signal import lfilter

    a = float(alpha_over_n)
    if not 0.0 < a <= 1.0:
        raise DetectorError(f"alpha/N = {a:g}: the exponential averager needs 0 < alpha/N <= 1")
    x = np.asarray(x, float)
    y, _ = lfilter([a], [1.0, -(1.0 - a)], x, axis=0, zi=np.full((1, *x.shape[1:]), (1.0 - a) * y0))
    return y


# ------------------------------------------------------------------------------- Tables 6 to 8
def table6(r: int) -> list[dict]:
    """Table 6: logic cells of the basic operations on an R-bit input (logic, registers, total)."""
    return [
        {"operation": "delay", "logic": 0, "registers": r, "cells": r},
        {"operation": "addition/subtraction", "logic": r, "registers": 0, "cells": r},
        {"operation": "integrator", "logic": r, "registers": r, "cells": r},
        {"operation": "multiplication by a constant", "logic": "0 or R", "registers": 0, "cells": "0 or R"},
        {"operation": "squaring", "logic": r * r + 4 * r, "registers": 0, "cells": r * r + 4 * r},
    ]


def nmv_les(r: int, n: int, memory: bool) -> int:
    """Table 7's NMV network per axis (recovered from Table 8, module docstring): 2R^2 + 16R + 15
    logic elements with the N-sample delay lines in memory, plus 3NR cells when they are in logic."""
    return 2 * r * r + 16 * r + 15 + (0 if memory else 3 * n * r)


def nmv_memory_bits(r: int, n: int) -> int:
    """The NMV network's delay lines: N samples of x (R bits) and of x^2 (2R bits)."""
    return 3 * n * r


def emv_les(r: int) -> int:
    """Table 7's exponential moving variance network per axis: R^2 + 13R + 12 (no delay line)."""
    return r * r + 13 * r + 12


def table8(n: int = TABLE8_N, bits=tuple(TABLE8)) -> dict[int, tuple[int, ...]]:
    """Table 8 from :func:`nmv_les`, :func:`nmv_memory_bits` and :func:`emv_les` (1 and 3 blocks)."""
    out = {}
    for r in bits:
        one = (nmv_les(r, n, False), nmv_les(r, n, True), nmv_memory_bits(r, n), emv_les(r))
        out[r] = tuple(v for x in one for v in (x, 3 * x))
    return out


def power_of_two_weights(n: int, w_max: float = 5.0) -> list[float]:
    """EMV weights alpha (1 <= alpha <= w_max, Table 9) whose multiplier alpha/N is a power of two
    (a shift, Table 9's footnote)."""
    out = []
    k = 0
    while 2.0 ** (-k) * n >= 1.0:
        w = 2.0 ** (-k) * n
        if 1.0 <= w <= w_max:
            out.append(w)
        k += 1
    return sorted(out)


def window_mvs(acc_g: np.ndarray, n: int, ddof: int = 0, keep: np.ndarray | None = None) -> np.ndarray:
    """The NMV of every non-overlapping n-sample window (the checks of seed 000 eq. 7), (m, 3);
    with ``keep`` (a boolean per sample), only the windows whose every sample it keeps."""
    m = acc_g.shape[0] // n
    w = acc_g[: m * n].reshape(m, n, -1)
    if keep is not None:
        w = w[np.asarray(keep, bool)[: m * n].reshape(m, n).all(axis=1)]
    return w.var(axis=1, ddof=ddof)
