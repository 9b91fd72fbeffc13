"""Shared for the e-obs tests: the real Movebank file (public Movebank study 2911040, Galapagos
albatrosses; 2-axis XY tags at 5 Hz per axis), read where the project keeps it and never copied."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.shared_data import shared_data_or_skip


@pytest.fixture(scope="module")
def real_movebank() -> Path:
    return shared_data_or_skip("eobs/albatrosses_movebank_format.csv")
