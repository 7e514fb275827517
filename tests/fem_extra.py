"""The one guard for test modules that need the ``fem`` extra.

``require("skfem", "gmsh")`` at the top of a test module skips the module, naming the
missing package, where the extra is not installed (a wheel's tests, ``pip install .[test]``);
where a run must exercise the finite elements (CI sets ``HERTZ_REQUIRE_FEM=1``) a missing
package is a collection error instead of a silent skip.
"""

from __future__ import annotations

import importlib
import os

import pytest

#: Every package of the fem extra (pyproject.toml).
FEM_EXTRA = ("skfem", "meshio", "gmsh", "pyamg", "matplotlib")


def require(*modules: str) -> None:
    """Skip the calling test module unless every one of ``modules`` imports."""
    for module in modules or FEM_EXTRA:
        if os.environ.get("HERTZ_REQUIRE_FEM") == "1":
            importlib.import_module(module)
        else:
            pytest.importorskip(module, reason=f"{module} is not installed: these tests need "
                                "the fem extra (pip install -e '.[test,fem]')")
