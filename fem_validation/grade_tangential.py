"""Deprecated: the old path fem_validation.grade_tangential, kept one release."""

from fem_validation._deprecated import alias

alias(__name__, "fem_validation.grading.tangential", "fem_validation.reports.tangential")
