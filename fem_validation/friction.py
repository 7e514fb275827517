"""Deprecated: the old path fem_validation.friction, kept one release."""

from fem_validation._deprecated import alias

alias(__name__, "fem_validation.solvers.friction", "fem_validation.halfspace")
