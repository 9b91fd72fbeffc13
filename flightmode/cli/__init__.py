"""The ``flightmode`` command line: a thin shell over the library."""
