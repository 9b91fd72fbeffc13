"""The CLI tests' fixtures beyond tests/conftest.py: the e-obs ones (a real Movebank file)."""

from tests.eobs.conftest import real_movebank  # noqa: F401  (a fixture, used by test_eobs.py)
