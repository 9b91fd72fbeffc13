"""Scenario files, their validation, the built-in library and the ``flightmode`` CLI."""
