"""The gate for real data nobody here wrote (the ADS-B taxi tracks, the albatross Movebank file). It
lies in shared/data beside the checkout, where CI has it; a user's clone does not, and its licence
terms are not ours to pass on, so it is not copied into the repository. Without it a test skips with
one line naming the folder, unless FLIGHTMODE_REQUIRE_DATA=1 (set by .ci/run), where it fails."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

SHARED_DATA = Path(__file__).resolve().parents[1].parent / "shared" / "data"


def shared_data_or_skip(relative: str) -> Path:
    """``shared/data/<relative>`` beside the checkout, or a skip (a failure under
    FLIGHTMODE_REQUIRE_DATA=1) when it is not there."""
    path = SHARED_DATA / relative
    if not path.exists():
        if os.environ.get("FLIGHTMODE_REQUIRE_DATA") == "1":
            pytest.fail(f"FLIGHTMODE_REQUIRE_DATA=1 but {path} is missing (shared/data beside the checkout)")
        reason = f"needs the real data in shared/data/{relative} beside the checkout (not shipped)"
        pytest.skip(reason)  # the allowed form: under FLIGHTMODE_REQUIRE_DATA=1 (.ci/run) it fails above
    return path
