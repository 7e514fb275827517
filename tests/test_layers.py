"""fem_validation's layers, enforced on its import graph (issue 23).

Every import counts: module level, inside functions, under ``TYPE_CHECKING``.  The layers
(DESIGN of the package: fem_validation/__init__.py and docs/development.md):

    L7  __main__                 picks the mode
    L6  cli/                     argument parsing and exit statuses
    L5  runs/, decks/            our runs end to end; inputs for other codes
    L4  reports/                 files from results and grades handed to them
    L3  solvers/, readers/, grading/   our sources, other codes' files, graders
    L2  results/, fe/            the result types; FE numerics that know no scene
    L1  errors, memory, limits, scenes, halfspace  (and hertz)

A module may import its own folder and any layer below; never a sibling folder of its
layer (a grader never imports a source, a reader never a solver), never a layer above, and
never the package face ``fem_validation`` or an old module path kept as a deprecated
alias.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from import_graph import cycles, import_graph, modules

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "fem_validation"

LAYERS = {"__main__": 7, "cli": 6, "runs": 5, "decks": 5, "reports": 4, "solvers": 3,
          "readers": 3, "grading": 3, "results": 2, "fe": 2, "base": 1}
#: The ground floor: modules at the package root that import only each other and hertz.
BASE = {"errors", "memory", "limits", "scenes", "halfspace", "_deprecated"}


def deprecated(path: Path) -> bool:
    """An old module path kept one release (fem_validation._deprecated.alias)."""
    return "from fem_validation._deprecated import alias" in path.read_text()


def role(module: str) -> str:
    """The layer folder (or L1 module) a module of fem_validation belongs to."""
    parts = module.split(".")
    if len(parts) == 1:
        return "__init__"
    return "base" if parts[1] in BASE else parts[1]


GRAPH = import_graph(PACKAGE)
MODS = modules(PACKAGE)
OLD = {m for m, (path, _) in MODS.items() if deprecated(path)}
LIVE = {m: {t for t in ts} for m, ts in GRAPH.items() if m not in OLD}


def test_every_module_has_a_layer():
    unplaced = sorted(m for m in LIVE if m != "fem_validation" and role(m) not in LAYERS)
    assert unplaced == [], f"modules outside the layers: {unplaced}"


def test_no_import_cycle():
    """No cycle, counting function-level and TYPE_CHECKING imports; a package's face
    re-exporting its children is not one (it is not imported from inside)."""
    faces = {m for m, (_, is_init) in MODS.items() if is_init}
    inner = {m: {t for t in ts if t not in faces} for m, ts in LIVE.items() if m not in faces}
    assert cycles(inner) == []


@pytest.mark.parametrize("module", sorted(m for m in LIVE if m != "fem_validation"))
def test_imports_follow_the_layers(module):
    mine = role(module)
    wrong = []
    for target in sorted(LIVE[module] | (GRAPH[module] & OLD)):
        if target in OLD:
            wrong.append(f"{target} (a deprecated alias)")
        elif target == "fem_validation":
            wrong.append("fem_validation (the package face)")
        elif role(target) != mine and LAYERS[role(target)] >= LAYERS[mine]:
            wrong.append(f"{target} (L{LAYERS[role(target)]} from L{LAYERS[mine]})")
    assert wrong == [], f"{module} imports against the layers: {wrong}"


def test_the_graph_sees_every_kind_of_import(tmp_path):
    """The checks would fail on a wrong import in a function or under TYPE_CHECKING."""
    pkg = tmp_path / "fem_validation"
    (pkg / "grading").mkdir(parents=True)
    (pkg / "solvers").mkdir()
    for d in (pkg, pkg / "grading", pkg / "solvers"):
        (d / "__init__.py").write_text("")
    (pkg / "grading" / "a.py").write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from ..solvers.b import X\n")
    (pkg / "solvers" / "b.py").write_text("def f():\n    from ..grading import a\n")
    graph = import_graph(pkg)
    assert graph["fem_validation.grading.a"] == {"fem_validation.solvers.b"}
    assert "fem_validation.grading.a" in graph["fem_validation.solvers.b"]
    assert cycles(graph) == [["fem_validation.grading.a", "fem_validation.solvers.b"]]


def test_at_least_five_role_folders():
    folders = {p.parent.name for p in PACKAGE.glob("*/__init__.py")}
    assert {"results", "fe", "solvers", "readers", "grading", "reports", "runs", "cli",
            "decks"} <= folders


OLD_PATHS = {"fem_validation.grade": "grade", "fem_validation.result": "ContactResult",
             "fem_validation.output": "write_grade", "fem_validation.compare": "TARGETS",
             "fem_validation.curved": "run_curved", "fem_validation.friction":
             "cerruti_settlement", "fem_validation.readers.table": "read_csv",
             "fem_validation.readers.meshes": "read_mesh", "fem_validation.grade_tangential":
             "write_grade", "fem_validation.tangential_result": "TangentialResult"}


@pytest.mark.parametrize("old,name", sorted(OLD_PATHS.items()))
def test_old_module_paths_warn_and_still_work(old, name):
    """The paths before the layers import for one release, each with a DeprecationWarning
    naming where its names went (in a fresh interpreter: a module imports once)."""
    import subprocess
    import sys

    code = (f"import warnings; warnings.simplefilter('error', DeprecationWarning)\n"
            f"try:\n    import {old}\nexcept DeprecationWarning as w:\n    print(w)\n"
            f"warnings.simplefilter('ignore')\nimport {old} as m\nprint(callable(m.{name}) "
            f"or m.{name} is not None)")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=ROOT)
    assert done.returncode == 0, done.stderr
    warning, ok = done.stdout.strip().splitlines()
    assert f"{old} is deprecated" in warning and "fem_validation." in warning
    assert ok == "True"
