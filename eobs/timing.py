"""When each sample of an e-obs burst was taken (seed 003 sections 4.2 and 5.4).

Section 4.2: the samples of one axis follow each other at the period T = 1/f, f the sampling
frequency *per axis*; time 0 is the beginning of the burst. "The first acceleration sample is not
exact at the time of the acceleration timestamp ... Especially for older e-obs Tags, there is a small
delay (up to one second) between the timestamp and the first acceleration sample." Section 5.4 adds
that the delay is larger "especially when the ACC-pinger is enabled (4 pings before the start of each
ACC burst)", still "up to 1 second".

So sample k (k = 0 .. N-1) of a burst is at ``start + d + k / f``, with d the start delay.

Choices where the note is silent:

* which tags are "older": the note dates the new acceleration sensor from tag 2242 (section 2) and
  gives no other generation boundary, so tags up to 2241 are the older ones here;
* the delay's distribution: only its bound (1 s) is given, so a tag's delay is drawn uniformly in
  [0, 1) s (the least committal law on a bounded interval) and, being the tag's firmware timing,
  held for all its bursts (one draw per tag); the ACC-pinger's share is not quantified and not
  modelled apart;
* newer tags: "especially for older" admits a delay on newer tags too, but the note gives no figure:
  they get 0;
* the axes of one sample set: section 4.2 counts a rate "for all axes together" (n_axes times the
  per-axis rate), which would fit one ADC reading the axes in turn, but the note does not say so.
  By default the axes of sample k share its time; ``stagger_axes=True`` puts axis j of the set at
  ``j / (n_axes f)`` after it instead.
"""

from __future__ import annotations

import numpy as np

from flightmode.eobs.burst import AccBurst
from flightmode.eobs.tag import is_old_tag
from flightmode.errors import SensorError

OLD_TAG_MAX_START_DELAY_S = 1.0  # seed 003 sections 4.2 and 5.4: "up to one second" (older tags)
NEW_TAG_START_DELAY_S = 0.0  # not quantified by the note for newer tags (module docstring)


def max_start_delay_s(tag_number: int) -> float:
    """Upper bound of the delay between a burst's timestamp and its first sample for this tag."""
    return OLD_TAG_MAX_START_DELAY_S if is_old_tag(tag_number) else NEW_TAG_START_DELAY_S


def draw_start_delay_s(tag_number: int, rng: np.random.Generator) -> float:
    """One tag's start delay: uniform in [0, 1) s for tags up to 2241, 0 for newer ones. One uniform
    is drawn for every tag, old or new, so the generator's stream does not depend on the generation."""
    u = float(rng.random())
    return u * max_start_delay_s(tag_number)


def sample_offsets_s(
    n_samples: int, rate_hz: float, start_delay_s: float = 0.0, n_axes: int = 1, stagger_axes: bool = False
) -> np.ndarray:
    """Seconds after the burst's timestamp of each sample, shape (n_samples, n_axes):
    ``d + k / f`` (section 4.2), plus ``j / (n_axes f)`` for axis j when ``stagger_axes``."""
    if n_samples < 0 or not rate_hz > 0 or n_axes not in (1, 2, 3):
        raise SensorError(
            f"burst timing: need n_samples >= 0, rate > 0 Hz and 1-3 axes "
            f"(got {n_samples}, {rate_hz}, {n_axes})"
        )
    if not 0.0 <= start_delay_s <= OLD_TAG_MAX_START_DELAY_S:
        raise SensorError(
            f"start delay {start_delay_s} s: seed 003 bounds it to 0-{OLD_TAG_MAX_START_DELAY_S} s"
        )
    k = np.arange(n_samples, dtype=float)[:, None]
    j = np.arange(n_axes, dtype=float)[None, :] / n_axes if stagger_axes else np.zeros((1, n_axes))
    return start_delay_s + (k + j) / rate_hz


def sample_times(burst: AccBurst, start_delay_s: float = 0.0, stagger_axes: bool = False) -> np.ndarray:
    """Absolute UTC time (datetime64[ns]) of every sample of ``burst``, shape (n, n_axes), rounded to
    the nanosecond."""
    off = sample_offsets_s(burst.n_samples, burst.rate_hz, start_delay_s, len(burst.axes), stagger_axes)
    return burst.start_time + np.rint(off * 1e9).astype(np.int64).astype("timedelta64[ns]")
