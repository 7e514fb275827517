"""Deprecated: the old path fem_validation.curved_mesh, kept one release."""

from fem_validation._deprecated import alias

alias(__name__, "fem_validation.solvers.curved_mesh")
