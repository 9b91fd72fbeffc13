"""Content digests of flightmode's frozen dataclasses (FlightTrack, Recording): equal digests mean
bit-identical contents, the determinism tests' yardstick."""

from __future__ import annotations

import dataclasses
import hashlib

import numpy as np


def digest(obj) -> str:
    """SHA-256 over ``obj``: every array's dtype, shape and bytes; nested dataclasses (field by field)
    and tuples walked; every other value by its repr."""
    h = hashlib.sha256()
    _feed(h, obj)
    return h.hexdigest()


def _feed(h, v) -> None:
    if isinstance(v, np.ndarray):
        h.update(f"{v.dtype}{v.shape}".encode())
        # the array's own buffer (C order), not a tobytes() copy: the same bytes, without a second
        # 250 MB of memory and its copy for a long flight's track
        h.update(np.ascontiguousarray(v))
    elif dataclasses.is_dataclass(v) and not isinstance(v, type):
        for f in dataclasses.fields(v):
            h.update(f.name.encode())
            _feed(h, getattr(v, f.name))
    elif isinstance(v, (tuple, list)):
        h.update(b"(")
        for x in v:
            _feed(h, x)
        h.update(b")")
    else:
        h.update(repr(v).encode())
