"""Per-burst DFT (seed 003 section 11) and the standard deviation after a high-pass (section 12).

Section 11.1: the decoder's DFT values are ``r_n = (1/N) | sum_k exp(-2 pi i n k / N) a_k |`` for
the N samples a_k of one axis of one burst, n = 0 .. floor(N/2) (section 11.2: N/2 + 1 values,
rounded down: N = 6 and N = 7 both give 4), at the frequencies ``f_n = n / N * f_s`` with f_s the
sampling frequency *per axis* (section 11.3). The a_k are raw counts, so r_0 is the burst's mean
count (the note's DFT example starts with 1872, the average of its option-9 example).

Section 12: per axis, a low-pass "Bessel filter 10th order, forward-backward algorithm", its output
subtracted from the samples, then the population standard deviation (1/N) of the remainder, on raw
counts. The note gives no cut-off frequency: it is a required argument here. Nor does it say how the
Bessel filter is normalised or how the forward-backward pass treats the burst's ends; our choices:
scipy's digital Bessel design with ``norm='mag'`` (the cut-off is the -3 dB frequency of one pass, so
-6 dB forward-backward), as second-order sections, run by ``scipy.signal.sosfiltfilt`` with its
default odd extension of the ends, whose length (3 x (2 x sections + 1) = 33 samples at order 10)
is shortened to N - 1 for bursts shorter than that.
"""

from __future__ import annotations

import numpy as np

from flightmode.eobs.burst import AccBurst
from flightmode.errors import SensorError

HP_BESSEL_ORDER = 10  # seed 003 section 12


def _axis_samples(a) -> np.ndarray:
    x = np.asarray(a, dtype=float)
    if x.ndim != 1 or x.size < 1:
        raise SensorError(f"one axis of one burst: need a 1-D array of >= 1 samples, got shape {x.shape}")
    if not np.all(np.isfinite(x)):
        raise SensorError("one axis of one burst: samples must be finite")
    return x


def n_dft_values(n_samples: int) -> int:
    """floor(N/2) + 1 (section 11.2)."""
    return n_samples // 2 + 1


def dft_magnitudes(a) -> np.ndarray:
    """r_n, n = 0 .. floor(N/2), of one axis's N samples (section 11.1): |DFT| / N."""
    x = _axis_samples(a)
    return np.abs(np.fft.rfft(x)) / x.size  # rfft returns exactly n = 0 .. floor(N/2)


def dft_frequencies_hz(n_samples: int, fs_hz: float) -> np.ndarray:
    """f_n = n / N * f_s for n = 0 .. floor(N/2), f_s per axis (section 11.3)."""
    if n_samples < 1 or not fs_hz > 0:
        raise SensorError(f"DFT frequencies: need N >= 1 and f_s > 0 (got {n_samples}, {fs_hz})")
    return np.arange(n_dft_values(n_samples)) / n_samples * fs_hz


def burst_dft(burst: AccBurst) -> tuple[np.ndarray, np.ndarray]:
    """(frequencies in Hz, shape (m,); r_n per axis, shape (m, n_axes)), m = floor(N/2) + 1."""
    mags = np.abs(np.fft.rfft(burst.raw.astype(float), axis=0)) / burst.n_samples
    return dft_frequencies_hz(burst.n_samples, burst.rate_hz), mags


def bessel_sos(fs_hz: float, cutoff_hz: float, order: int = HP_BESSEL_ORDER) -> np.ndarray:
    """The low-pass of section 12 as second-order sections (module docstring for the normalisation)."""
    from scipy.signal import bessel

    if not (fs_hz > 0 and 0 < cutoff_hz < fs_hz / 2):
        raise SensorError(
            f"Bessel low-pass: cut-off {cutoff_hz:g} Hz must lie in (0, f_s/2 = {fs_hz / 2:g} Hz)"
        )
    return bessel(order, cutoff_hz, btype="low", norm="mag", output="sos", fs=fs_hz)


def lowpass_forward_backward(a, fs_hz: float, cutoff_hz: float, order: int = HP_BESSEL_ORDER) -> np.ndarray:
    """The Bessel low-pass run forward and backward over one axis's samples (section 12)."""
    from scipy.signal import sosfiltfilt

    x = _axis_samples(a)
    sos = bessel_sos(fs_hz, cutoff_hz, order)
    padlen = 3 * (2 * len(sos) + 1)  # scipy's default for sections without zero coefficients
    if x.size < 2:
        return x.copy()
    return sosfiltfilt(sos, x, padlen=min(padlen, x.size - 1))


def hp_std(a, fs_hz: float, cutoff_hz: float, order: int = HP_BESSEL_ORDER) -> float:
    """Standard deviation (1/N) of one axis after the high-pass of section 12, in the samples' unit."""
    x = _axis_samples(a)
    r = x - lowpass_forward_backward(x, fs_hz, cutoff_hz, order)
    return float(np.sqrt(np.mean((r - r.mean()) ** 2)))  # section 12's formula, population (1/N)


def burst_hp_std(burst: AccBurst, cutoff_hz: float, order: int = HP_BESSEL_ORDER) -> np.ndarray:
    """Section 12's statistic for each axis of ``burst``, in counts, shape (n_axes,)."""
    return np.array(
        [hp_std(burst.raw[:, j], burst.rate_hz, cutoff_hz, order) for j in range(len(burst.axes))]
    )
