"""Deprecated: the old path fem_validation.curved, kept one release."""

from fem_validation._deprecated import alias

alias(__name__, "fem_validation.solvers.curved", "fem_validation.runs.curved")
