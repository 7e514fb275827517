"""The import graph of a package, read from its source (AST, nothing imported): one
implementation for tests/test_import_graph.py (hertz) and tests/test_layers.py
(fem_validation's floors).

Every import counts: at module level, inside functions and under ``if TYPE_CHECKING:``.
"""

from __future__ import annotations

import ast
from importlib.machinery import EXTENSION_SUFFIXES
from pathlib import Path


def modules(package_dir: Path) -> dict[str, tuple[Path | None, bool]]:
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
    mods = modules(package_dir)

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
