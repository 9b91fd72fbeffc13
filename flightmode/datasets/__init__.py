"""Read a dataset made by ``flightmode dataset``: :func:`open` (a ``pyarrow.dataset.Dataset``) and
:func:`windows` (fixed-length labelled windows for machine learning)."""

from __future__ import annotations


def open(path, part: str = "samples"):
    from flightmode.datasets.make import open_dataset

    return open_dataset(path, part)


def windows(path, length_s: float, step_s: float | None = None, label: str = "in_flight_window"):
    from flightmode.datasets.make import windows as _windows

    return _windows(path, length_s, step_s, label)


__all__ = ["open", "windows"]
