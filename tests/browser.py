"""The browser gate shared by the tests that render in a real browser: Debian's chromium, driven by
Playwright. Without it the test skips with one line naming the package, unless
FLIGHTMODE_REQUIRE_BROWSER=1 (set by .ci/run, which installs it), where it fails."""

from __future__ import annotations

import os
import shutil

import pytest


def chromium_or_skip() -> str:
    chromium = shutil.which("chromium")
    if not chromium:
        if os.environ.get("FLIGHTMODE_REQUIRE_BROWSER") == "1":
            pytest.fail(
                "FLIGHTMODE_REQUIRE_BROWSER=1 but no chromium on PATH (.ci/run installs it: apt-get install chromium)"
            )
        pytest.skip("needs a browser: install Debian's chromium (apt-get install chromium)")
    return chromium
