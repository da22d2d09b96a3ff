"""Stability: support polygons, verdicts, tilt limits and resting poses."""
