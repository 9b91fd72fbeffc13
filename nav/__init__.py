"""Cubic-spline inertial path estimation (seed 002). Not yet built: see the issues."""
