"""Shared for the e-obs tests: the real Movebank file (public Movebank study 2911040, Galapagos
albatrosses; 2-axis XY tags at 5 Hz per axis), read where the project keeps it and never copied."""

from __future__ import annotations

from pathlib import Path

import pytest

# beside the checkout (shared/data/eobs: data nobody here wrote, not copied into the repository)
REAL_MOVEBANK = (
    Path(__file__).resolve().parents[2].parent
    / "shared"
    / "data"
    / "eobs"
    / "albatrosses_movebank_format.csv"
)


@pytest.fixture(scope="module")
def real_movebank() -> Path:
    assert REAL_MOVEBANK.is_file(), (
        f"the real e-obs Movebank file is expected at {REAL_MOVEBANK} (shared/data beside the checkout)"
    )
    return REAL_MOVEBANK
