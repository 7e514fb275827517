"""Deprecated: the old path fem_validation.grade, kept one release."""

from fem_validation._deprecated import alias

alias(__name__, "fem_validation.grading.contact", "fem_validation.fe.surface")
