"""Shared for the e-obs tests: the real Movebank file (public Movebank study 2911040, Galapagos
albatrosses; 2-axis XY tags at 5 Hz per axis), read where the project keeps it and never copied."""

from __future__ import annotations

from pathlib import Path

import pytest

REAL_MOVEBANK = Path("/work/shared/data/eobs/albatrosses_movebank_format.csv")


@pytest.fixture(scope="module")
def real_movebank() -> Path:
    if not REAL_MOVEBANK.is_file():
        pytest.skip(f"the real e-obs Movebank file is not on this machine ({REAL_MOVEBANK})")
    return REAL_MOVEBANK
