"""The module paths of fem_validation before its layers (issue 23), kept for one release.

Each old module is a two-line file calling :func:`alias`: importing it warns with a
:class:`DeprecationWarning` naming the new modules, and gives it every name of those
modules, so that ``from fem_validation.grading.contact import grade`` keeps working.  No module of
the package imports an old path; the import-graph test (tests/test_import_graph.py) skips
these files.
"""

from __future__ import annotations

import importlib
import sys
import warnings


def alias(old: str, *new: str) -> None:
    """Fill the old module ``old`` with the names of the modules ``new`` and warn."""
    warnings.warn(f"{old} is deprecated and will be removed in the next release: import "
                  f"from {' or '.join(new)}", DeprecationWarning, stacklevel=3)
    module = sys.modules[old]
    for name in new:
        for key, value in vars(importlib.import_module(name)).items():
            if not key.startswith("__"):
                module.__dict__.setdefault(key, value)
