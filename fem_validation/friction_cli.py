"""Deprecated: the old path fem_validation.friction_cli, kept one release."""

from fem_validation._deprecated import alias

alias(__name__,
      "fem_validation.cli.friction",
      "fem_validation.runs.friction",
      "fem_validation.reports.friction")
