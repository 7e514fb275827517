"""Deprecated: the old path fem_validation.output, kept one release."""

from fem_validation._deprecated import alias

alias(__name__,
      "fem_validation.reports.blocks",
      "fem_validation.solvers.vtu",
      "fem_validation.reports.grade",
      "fem_validation.cli.common")
