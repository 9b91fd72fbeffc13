"""The e-obs tag toolkit of seed 003: Movebank files in and out, the data decoder's output formats, calibration, per-burst DFT and high-pass statistics."""
