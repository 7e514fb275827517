"""Finite-element validation of hertz (placeholder until its own issue)."""
