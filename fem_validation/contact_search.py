"""Deprecated: the old path fem_validation.contact_search, kept one release."""

from fem_validation._deprecated import alias

alias(__name__, "fem_validation.fe.contact_search")
