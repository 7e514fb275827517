"""Deprecated: the old path fem_validation.grade_cli, kept one release."""

from fem_validation._deprecated import alias

alias(__name__, "fem_validation.cli.grade", "fem_validation.cli.common")
