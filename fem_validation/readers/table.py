"""Deprecated: the old path fem_validation.readers.table, kept one release."""

from fem_validation._deprecated import alias

alias(__name__, "fem_validation.readers.csv_file")
