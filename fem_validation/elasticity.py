"""Deprecated: the old path fem_validation.elasticity, kept one release."""

from fem_validation._deprecated import alias

alias(__name__, "fem_validation.fe.elasticity")
