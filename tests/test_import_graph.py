"""The import graph of the project's packages, read from their source (AST, nothing imported).

Every import counts: at module level, inside functions and under ``if TYPE_CHECKING:``.
``import_graph`` and ``cycles`` are plain functions, for the checks of any package
(hertz's here; fem_validation's layer order can use the same two).

hertz's directions (docs/development.md): cli -> contact / tangential / load path ->
stress, friction, ellipse -> interop -> validate -> the compiled kernels; ``_interop``
knows no result type and ``_scene`` (the TOML scene format) imports nothing of hertz.
"""

from __future__ import annotations

import ast
import textwrap
from importlib.machinery import EXTENSION_SUFFIXES
from pathlib import Path

import pytest

import hertz

HERTZ = Path(hertz.__file__).resolve().parent


def _modules(package_dir: Path) -> dict[str, tuple[Path | None, bool]]:
    """{dotted name: (file, is a package __init__)} of the modules under package_dir: the
    .py files, and the compiled extensions (file None: they import nothing of ours)."""
    package_dir = Path(package_dir)
    root = package_dir.parent
    mods = {}
    for f in sorted(package_dir.rglob("*")):
        if f.suffix == ".py":
            parts = list(f.relative_to(root).with_suffix("").parts)
        elif f.name.endswith(tuple(EXTENSION_SUFFIXES)):  # hertz/_ufuncs.cpython-311-....so
            parts = list(f.relative_to(root).parent.parts) + [f.name.partition(".")[0]]
            mods.setdefault(".".join(parts), (None, False))
            continue
        else:
            continue
        is_init = parts[-1] == "__init__"
        if is_init:
            parts = parts[:-1]
        mods[".".join(parts)] = (f, is_init)
    return mods


def _resolve(module: str | None, level: int, here: str, is_init: bool) -> str:
    """The absolute name of ``from <level dots><module> import ...`` written in ``here``."""
    if level == 0:
        return module or ""
    base = here.split(".")
    if not is_init:
        base = base[:-1]  # a module's relative imports start from its package
    base = base[:len(base) - (level - 1)]
    return ".".join(base + ([module] if module else []))


def import_graph(package_dir, *, inits: bool = True) -> dict[str, set[str]]:
    """{module: the modules of the same package that it imports}, module names dotted
    from the package (``hertz._contact``; a package is its ``__init__``: ``hertz``).

    Every ``import`` and ``from ... import`` in the file counts, wherever it stands
    (functions, ``if TYPE_CHECKING:``, ``try:``).  ``import a.b.c`` and ``from a.b import
    c`` point at the longest module of the package they name: ``from . import x`` at the
    module ``x`` where there is one, else at the package (``from . import __version__``
    imports the package's ``__init__``).  A compiled extension (``hertz._ufuncs``) is a
    module that imports none.  Imports of other packages are left out, and so is a module
    importing itself.  ``inits=False`` leaves the packages' ``__init__``
    modules out (as nodes and as targets): the graph of the modules that do the work.
    """
    mods = _modules(package_dir)

    def known(name: str) -> str | None:
        while name and name not in mods:
            name = name.rpartition(".")[0]
        return name or None

    graph: dict[str, set[str]] = {}
    for here, (path, is_init) in mods.items():
        targets = set()
        if path is None:  # a compiled extension
            graph[here] = targets
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
            if isinstance(node, ast.Import):
                targets.update(known(alias.name) for alias in node.names)
            elif isinstance(node, ast.ImportFrom):
                base = _resolve(node.module, node.level, here, is_init)
                for alias in node.names:
                    full = f"{base}.{alias.name}" if base else alias.name
                    targets.add(full if full in mods else known(base))
        targets.discard(None)
        targets.discard(here)
        graph[here] = targets
    if not inits:
        packages = {m for m, (_, is_init) in mods.items() if is_init}
        graph = {m: deps - packages for m, deps in graph.items() if m not in packages}
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The import cycles of ``graph``: its strongly connected components of more than one
    module (each sorted; the list sorted), found by Tarjan's algorithm without recursion."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph.get(start, ()))))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            v, children = work[-1]
            for w in children:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph.get(w, ())))))
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            else:
                work.pop()
                if work:
                    parent = work[-1][0]
                    low[parent] = min(low[parent], low[v])
                if low[v] == index[v]:
                    component = []
                    while True:
                        w = stack.pop()
                        on_stack.discard(w)
                        component.append(w)
                        if w == v:
                            break
                    if len(component) > 1:
                        found.append(sorted(component))
    return sorted(found)


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
