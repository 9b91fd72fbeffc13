"""Seed 001's spectrum-based (in)activity detectors (section 2.2, eq. 6-8): the Long Term Spectral
Detector (LTSD; Ramirez et al., the seed's ref. [21]) and the Framed Spectrum Detector (FSD).

The flexible input x(k) (``signal``: |a|, |w|, their sum or product) is cut into frames of
``window`` samples every ``shift`` samples, at fixed global positions: frame n holds samples
n*shift ... n*shift + window - 1. Each frame's amplitude spectrum X(l, n) = |DFT_512(frame)| (the
frame zero-padded to N_FFT = 512, the seed's resolution; no taper, the seed names none). Then

    LTSE(l, n) = max_{j = -order..order} X(l, n + j)                       seed 001, eq. (6)
    LTSD: V(n) = 10 log10( 1/N_FFT sum_{l=0}^{N_FFT-1} LTSE^2(l, n) / N^2(l) )   seed 001, eq. (7)
    FSD:  V(n) = 10 log10( 1/N_FFT sum_{l=0}^{N_FFT-1} X^2(l, n) / N^2(l) )      seed 001, eq. (8)

in dB; FSD is LTSD of order 0. For a real x the spectrum is symmetric, so the sum over l = 0..511 is
taken as the bands 0 and 256 once and the bands 1..255 twice (the one-sided rfft).

Choices where the seed is silent or garbled:

- The LTSE order: the seed writes "the N-order long-term spectral envelope", with N also the window
  length of eq. (1)-(4) and the noise spectrum N(l) of eq. (7): the letter is overloaded, and its
  tables give LTSD a window, a shift and a threshold but no order. We keep the order a parameter
  of its own (``order`` frames on each side, default 6: our choice), as in ref. [21].
- The frame mean is not removed: X(l, n) is the spectrum of the signal as the seed writes it, so for
  "acc" the 1 g of |a| fills the low bands of both X and N(l). A frame shorter than about half a
  period of the motion then sees a swing of |a| as a level change (on the test streams, 16-sample frames at
  the peaks of a 2 Hz swing fall to 10 dB; 32-sample frames stay above 19 dB).
- N(l), "the average noise spectrum magnitude": the mean of X(l, n) over the first ``noise_frames``
  (default 20) frames of the stream, which must then be still, or a given one-sided
  ``noise_spectrum`` (257 bands, in the signal's unit) measured on a still recording.
- Causality: LTSE(l, n) needs the frames up to n + order. The merit of sample k is that of the last
  frame whose envelope is complete at k: V(m - order), m the last frame ending at or before k. It is
  NaN before that frame exists (m < order), and before the noise spectrum is known (m <
  noise_frames - 1, when it is estimated). At the start of the stream the envelope is the maximum
  over the frames that exist (n + j >= 0).
"""

from __future__ import annotations

import numpy as np

from flightmode.detector.activity.common import (
    ActivityResult,
    StreamInput,
    batch_rate,
    check_signal,
    check_threshold,
    check_window,
    decide,
    flexible_signal,
    run_batch,
    signal_needs_gyro,
)
from flightmode.errors import DetectorError

N_FFT = 512  # the seed's FFT resolution (section 2.2.1)
N_BANDS = N_FFT // 2 + 1  # one-sided bands of a real signal's spectrum


def _band_weights() -> np.ndarray:
    """Weight of each one-sided band in the two-sided sum over l = 0 .. N_FFT - 1."""
    w = np.full(N_BANDS, 2.0)
    w[0] = w[-1] = 1.0
    return w


def amplitude_spectra(frames: np.ndarray) -> np.ndarray:
    """X(l, n): the one-sided amplitude spectrum (F, 257) of (F, window) frames, zero-padded to N_FFT."""
    return np.abs(np.fft.rfft(frames, n=N_FFT, axis=1))


def spectral_merit(envelope: np.ndarray, noise: np.ndarray) -> np.ndarray:
    """Eq. (7)/(8) for (F, 257) envelopes (or spectra) against the (257,) noise spectrum, in dB. The sum
    over bands is a cumulative sum (a fixed order of additions, the same bits for any F)."""
    r = envelope / noise
    total = np.cumsum(r * r * _band_weights(), axis=1)[:, -1]
    with np.errstate(divide="ignore"):
        return 10.0 * np.log10(total / N_FFT)  # seed 001, eq. (7), (8)


class SpectralStream:
    """LTSD (``order`` >= 1) or FSD (``order`` = 0) over chunks of any length."""

    name = "LTSD"

    def __init__(
        self,
        *,
        window: int,
        shift: int,
        threshold: float,
        fs_hz: float,
        signal: str = "acc",
        order: int = 6,
        noise_frames: int = 20,
        noise_spectrum: np.ndarray | None = None,
    ):
        self.window = check_window(window)
        if self.window > N_FFT:
            raise DetectorError(
                f"{self.name}: window = {window} samples is longer than the FFT (N_FFT = {N_FFT})"
            )
        self.shift = _check_count(shift, "shift", 1, self.name)
        self.order = _check_count(order, "order", 0, self.name)
        self.noise_frames = _check_count(noise_frames, "noise_frames", 1, self.name)
        self.threshold = check_threshold(threshold, False, "dB")
        self.signal = check_signal(signal)
        self._input = StreamInput(fs_hz, signal_needs_gyro(signal), self.name)
        self._noise: np.ndarray | None = None
        self._noise_from = self.noise_frames - 1  # the first frame that has a merit (noise known)
        if noise_spectrum is not None:
            self._noise = _check_noise(np.asarray(noise_spectrum, dtype=float), self.name)
            self._noise_from = 0
        self._noise_buf: list[np.ndarray] = []  # spectra of the first frames, until the noise is known
        # spectra of the last 2 order frames (zeros stand for the frames before frame 0)
        self._ring = np.zeros((2 * self.order, N_BANDS))
        self._tail = np.zeros(0)  # the last window - 1 samples of x
        self._last_v = np.nan  # merit of the last completed frame

    @property
    def n_samples(self) -> int:
        return self._input.n

    def push(self, t_s, acc_g, gyr_dps=None) -> ActivityResult:
        g0 = self._input.n  # global index of the chunk's first sample
        _, a, g = self._input.take(t_s, acc_g, gyr_dps)
        x = flexible_signal(self.signal, a, g)
        c, w, s = x.shape[0], self.window, self.shift
        buf = np.concatenate([self._tail, x])
        b0 = g0 - self._tail.shape[0]  # global index of buf[0]
        # frames completing in this chunk: end n*s + w - 1 in [g0, g0 + c - 1]
        n_lo = max(0, -((w - 1 - g0) // s))  # ceil((g0 - w + 1) / s)
        n_hi = (g0 + c - w) // s if g0 + c >= w else -1
        v_new = np.zeros(0)
        if n_hi >= n_lo:
            starts = np.arange(n_lo, n_hi + 1) * s - b0
            spec = amplitude_spectra(buf[starts[:, None] + np.arange(w)])
            frame_idx = np.arange(n_lo, n_hi + 1)
            self._learn_noise(spec, n_lo)
            v_new = self._merits(spec, frame_idx)
        # per sample: the merit available at it (the last completed frame's)
        k = g0 + np.arange(c)
        m = np.where(k >= w - 1, (k - w + 1) // s, -1)  # the last frame ending at or before k
        vals = np.concatenate([[self._last_v], v_new])  # frame n_lo - 1, n_lo, ..., n_hi
        merit = vals[np.clip(m - (n_lo - 1), 0, None)] if c else np.zeros(0)
        merit = np.where(m >= 0, merit, np.nan)
        if v_new.shape[0]:
            self._last_v = float(v_new[-1])
        self._tail = buf[max(0, buf.shape[0] - (w - 1)) :].copy()
        self._input.commit()
        return ActivityResult(decide(merit, self.threshold), merit)

    def _learn_noise(self, spec: np.ndarray, n_lo: int) -> None:
        """N(l): the mean spectrum of the first ``noise_frames`` frames (a cumulative sum in frame order)."""
        if self._noise is not None:
            return
        frames = [*self._noise_buf, *spec[: max(0, self.noise_frames - n_lo)]]
        if len(frames) >= self.noise_frames:
            mean = np.cumsum(np.stack(frames), axis=0)[-1] / self.noise_frames
            self._noise = _check_noise(mean, self.name, estimated=True)  # raises before any change
            frames = []
        self._noise_buf = frames

    def _merits(self, spec: np.ndarray, frame_idx: np.ndarray) -> np.ndarray:
        """The merit available at the end of each new frame m: V(m - order) (NaN when the envelope or
        the noise is not complete yet)."""
        allf = np.concatenate([self._ring, spec])  # frames m - 2 order ... (zeros before frame 0)
        env = spec
        if self.order:
            f = spec.shape[0]
            env = allf[0:f].copy()
            for j in range(1, 2 * self.order + 1):  # max over frames m - 2 order .. m: seed 001, eq. (6)
                np.maximum(env, allf[j : j + f], out=env)
            self._ring = allf[-2 * self.order :].copy()
        v = np.full(spec.shape[0], np.nan)
        ok = (frame_idx >= self.order) & (frame_idx >= self._noise_from)
        if ok.any():
            assert self._noise is not None  # _learn_noise has learnt it by frame _noise_from
            v[ok] = spectral_merit(env[ok], self._noise)
        return v


def _check_count(value, name: str, least: int, who: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer, float)) or int(value) != value:
        raise DetectorError(f"{who}: {name} = {value!r}: must be a whole number")
    if value < least:
        raise DetectorError(f"{who}: {name} = {value}: must be >= {least}")
    return int(value)


def _check_noise(noise: np.ndarray, who: str, estimated: bool = False) -> np.ndarray:
    if noise.shape != (N_BANDS,):
        raise DetectorError(
            f"{who}: noise_spectrum must hold the {N_BANDS} one-sided bands of a {N_FFT}-point FFT, "
            f"got shape {noise.shape}"
        )
    bad = ~(np.isfinite(noise) & (noise > 0))
    if bad.any():
        how = (
            "the first noise_frames frames are noiseless in it (an exactly constant input?): "
            "give noise_spectrum"
            if estimated
            else "every band must be finite and > 0"
        )
        band = int(np.flatnonzero(bad)[0])
        raise DetectorError(f"{who}: the noise spectrum N(l) is zero or not finite in band {band}: {how}")
    return noise


class LTSDStream(SpectralStream):
    """Long Term Spectral Detector (seed 001, section 2.2.1): streaming. Merit in dB."""

    name = "LTSD"


class FSDStream(SpectralStream):
    """Framed Spectrum Detector (seed 001, section 2.2.2): streaming. Merit in dB."""

    name = "FSD"

    def __init__(
        self,
        *,
        window: int,
        shift: int,
        threshold: float,
        fs_hz: float,
        signal: str = "acc",
        noise_frames: int = 20,
        noise_spectrum: np.ndarray | None = None,
    ):
        super().__init__(
            window=window,
            shift=shift,
            threshold=threshold,
            fs_hz=fs_hz,
            signal=signal,
            order=0,
            noise_frames=noise_frames,
            noise_spectrum=noise_spectrum,
        )


def detect_ltsd(
    t_s,
    acc_g,
    gyr_dps=None,
    *,
    window: int,
    shift: int,
    threshold: float,
    signal: str = "acc",
    order: int = 6,
    noise_frames: int = 20,
    noise_spectrum: np.ndarray | None = None,
    fs_hz: float | None = None,
) -> ActivityResult:
    """LTSD over a whole stream. ``window`` (frame length) and ``shift`` in samples, ``threshold`` in
    dB (the seed's Tables 3 and 9: a few dB to ~17 dB), ``order`` frames each side of the envelope."""
    fs = batch_rate(t_s, fs_hz, LTSDStream.name)
    det = LTSDStream(
        window=window,
        shift=shift,
        threshold=threshold,
        fs_hz=fs,
        signal=signal,
        order=order,
        noise_frames=noise_frames,
        noise_spectrum=noise_spectrum,
    )
    return run_batch(det, t_s, acc_g, gyr_dps, window)


def detect_fsd(
    t_s,
    acc_g,
    gyr_dps=None,
    *,
    window: int,
    shift: int,
    threshold: float,
    signal: str = "acc",
    noise_frames: int = 20,
    noise_spectrum: np.ndarray | None = None,
    fs_hz: float | None = None,
) -> ActivityResult:
    """FSD over a whole stream: ``window`` (frame length) and ``shift`` in samples, ``threshold`` in dB."""
    fs = batch_rate(t_s, fs_hz, FSDStream.name)
    det = FSDStream(
        window=window,
        shift=shift,
        threshold=threshold,
        fs_hz=fs,
        signal=signal,
        noise_frames=noise_frames,
        noise_spectrum=noise_spectrum,
    )
    return run_batch(det, t_s, acc_g, gyr_dps, window)
