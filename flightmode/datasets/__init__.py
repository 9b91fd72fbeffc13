"""Read a dataset made by ``flightmode dataset``: :func:`open` (a ``pyarrow.dataset.Dataset``),
:func:`windows` (fixed-length labelled windows for machine learning), :func:`ok_flights` (the
manifest's flown flights) and :func:`flight_track` (one flight's FlightTrack from its full-rate
truth). The public face of the room: code outside the run, dataset and study rooms (the e-obs
toolkit) reaches datasets only through these."""

from __future__ import annotations


def open(path, part: str = "samples"):
    from flightmode.datasets.make import open_dataset

    return open_dataset(path, part)


def windows(path, length_s: float, step_s: float | None = None, label: str = "in_flight_window"):
    from flightmode.datasets.make import windows as _windows

    return _windows(path, length_s, step_s, label)


def ok_flights(path, purpose: str = "sweep", full_truth_for: str | None = None):
    """(flown rows, failed rows, the manifest's metadata) of a dataset: see
    :func:`flightmode.datasets.make.ok_flights`."""
    from flightmode.datasets.make import ok_flights as _ok_flights

    return _ok_flights(path, purpose, full_truth_for=full_truth_for)


def flight_track(path, row: dict):
    """One flight's FlightTrack, rebuilt from its full-rate truth: see
    :func:`flightmode.datasets.flight.flight_track`."""
    from flightmode.datasets.flight import flight_track as _flight_track

    return _flight_track(path, row)


__all__ = ["flight_track", "ok_flights", "open", "windows"]
