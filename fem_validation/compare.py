"""Deprecated: the old path fem_validation.compare, kept one release."""

from fem_validation._deprecated import alias

alias(__name__,
      "fem_validation.solvers.blocks",
      "fem_validation.runs.validate",
      "fem_validation.grading.contact")
