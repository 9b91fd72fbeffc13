"""Named random streams: one :class:`numpy.random.SeedSequence` per run, a child per name.

A run's randomness comes from one integer seed. Each stage and each draw inside it asks for its own
stream by a stable name (``"flight/turbulence"``, ``"sensor/noise"``, ...): the stream is the
``SeedSequence(seed)`` child whose spawn key is the path of names, each name hashed to a 64-bit
integer (SHA-256, so the key is the same in any process, on any machine, in any Python). Adding a
stage, or a draw in one stage, therefore never shifts another stage's numbers, and any stream can be
regenerated alone.

    >>> s = Streams(7)
    >>> a = s.rng("sensor/noise").normal(size=3)
    >>> b = Streams(7).child("sensor").rng("noise").normal(size=3)
    >>> bool((a == b).all())
    True
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass

import numpy as np


def name_key(name: str) -> int:
    """The stable 64-bit spawn-key word of one stream name."""
    return int.from_bytes(hashlib.sha256(name.encode("utf-8")).digest()[:8], "little")


@dataclass(frozen=True, slots=True)
class Streams:
    """The named random streams of one run (or of a stage, below a run's :meth:`child`)."""

    seed: int
    path: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if isinstance(self.seed, bool) or not isinstance(self.seed, (int, np.integer)) or self.seed < 0:
            from flightmode.errors import FlightmodeError

            raise FlightmodeError(f"seed {self.seed!r}: must be an integer >= 0")

    def child(self, name: str) -> Streams:
        """The streams below ``name`` (a stage hands these to its own sub-stages)."""
        return Streams(self.seed, self.path + tuple(name.split("/")))

    def seed_sequence(self, name: str) -> np.random.SeedSequence:
        names = self.path + tuple(name.split("/"))
        return np.random.SeedSequence(int(self.seed), spawn_key=tuple(name_key(n) for n in names))

    def rng(self, name: str) -> np.random.Generator:
        """A fresh generator for the stream ``name`` (``a/b`` is the same as ``child("a").rng("b")``)."""
        return np.random.Generator(np.random.PCG64(self.seed_sequence(name)))

    def integer_seed(self, name: str, high: int = 2**31 - 1) -> int:
        """An integer seed in [0, high) for a library that takes one (JSBSim's random seed)."""
        return int(self.seed_sequence(name).generate_state(1, np.uint64)[0] % high)


def as_streams(source: Streams | np.random.Generator | int) -> Streams:
    """Streams from a run's :class:`Streams`, an integer seed, or a Generator (one draw of it seeds
    the streams, so the same generator state gives the same streams)."""
    if isinstance(source, Streams):
        return source
    if isinstance(source, np.random.Generator):
        return Streams(int(source.integers(0, 2**63 - 1)))
    return Streams(source)
