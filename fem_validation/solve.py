"""Deprecated: the old path fem_validation.solve, kept one release."""

from fem_validation._deprecated import alias

alias(__name__, "fem_validation.solvers.solve", "fem_validation.halfspace")
