"""Rerun recordings and plots; the only room that imports rerun. Not yet built: see the issues."""
