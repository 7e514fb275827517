"""The import graph of the project's packages, read from their source (AST, nothing imported).

Every import counts: at module level, inside functions and under ``if TYPE_CHECKING:``.
``import_graph`` and ``cycles`` are plain functions, for the checks of any package
(hertz's here; fem_validation's layer order can use the same two).

hertz's directions (docs/development.md): cli -> contact / tangential / load path ->
stress, friction, ellipse -> interop -> validate -> the compiled kernels; ``_interop``
knows no result type and ``_scene`` (the TOML scene format) imports nothing of hertz.
"""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest
from import_graph import cycles, import_graph

import hertz

HERTZ = Path(hertz.__file__).resolve().parent


# --- the functions themselves, on a package written for the purpose --------------------

def _package(tmp_path, files: dict[str, str]) -> Path:
    root = tmp_path / "pkg"
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text))
    return root


def test_every_kind_of_import_counts(tmp_path):
    root = _package(tmp_path, {
        "__init__.py": "from .a import f\n__version__ = '1'\n",
        "a.py": "import numpy\nfrom . import b\n",
        "b.py": "def g():\n    from .c import h\n",
        "c.py": ("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n"
                 "    from .sub.d import T\n"),
        "sub/__init__.py": "",
        "sub/d.py": "from .. import __version__\nimport pkg.a\nfrom ..sub import e\n",
        "sub/e.py": "from . import d\n",
    })
    graph = import_graph(root)
    assert graph == {"pkg": {"pkg.a"}, "pkg.a": {"pkg.b"}, "pkg.b": {"pkg.c"},
                     "pkg.c": {"pkg.sub.d"}, "pkg.sub": set(),
                     "pkg.sub.d": {"pkg", "pkg.a", "pkg.sub.e"}, "pkg.sub.e": {"pkg.sub.d"}}
    assert cycles(graph) == [["pkg", "pkg.a", "pkg.b", "pkg.c", "pkg.sub.d", "pkg.sub.e"]]
    # without the __init__ modules: the cycle through pkg.a still closes
    assert cycles(import_graph(root, inits=False)) == [
        ["pkg.a", "pkg.b", "pkg.c", "pkg.sub.d", "pkg.sub.e"]]


def test_a_cycle_only_through_an_init_is_no_cycle_without_inits(tmp_path):
    root = _package(tmp_path, {"__init__.py": "from .a import f\n",
                               "a.py": "from . import __version__\n"})
    assert cycles(import_graph(root)) == [["pkg", "pkg.a"]]
    assert cycles(import_graph(root, inits=False)) == []


# --- hertz ---------------------------------------------------------------------------------

def test_hertz_has_no_import_cycle():
    """No cycle among hertz's modules (issue 23: _interop rebuilt Contact, Tangential...
    by name, which tied _contact, _interop, _tangential and _ellipse in a circle)."""
    graph = import_graph(HERTZ, inits=False)
    assert "hertz._contact" in graph and "hertz._interop" in graph["hertz._contact"]
    assert cycles(graph) == []


@pytest.mark.parametrize("module,allowed", [
    ("hertz._validate", set()),
    ("hertz._interop", {"hertz._validate"}),  # generic wrapping: knows no result type
    ("hertz._scene", set()),  # the TOML scene format, for hertz.cli and fem_validation
    ("hertz._stress", {"hertz._ufuncs", "hertz._validate"}),
    ("hertz._ellipse", {"hertz._interop", "hertz._ufuncs", "hertz._validate"}),
])
def test_hertz_lower_modules_import_only_below_them(module, allowed):
    assert import_graph(HERTZ)[module] <= allowed
