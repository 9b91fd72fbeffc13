"""Flight-mode detectors (seed 000) and comparative detectors (seed 001). Not yet built: see the issues."""
