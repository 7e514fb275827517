"""The documentation is tested: the site builds with warnings as errors, and every example
in README.md and in the site's pages runs.

Pages that are MyST notebooks (``file_format: mystnb``) have their ``{code-cell}`` blocks
executed by the build itself (myst-nb, an error fails the build). Every other block is run
here, by its fence's language:

* ``python``: executed, the blocks of one page in order in one namespace, in a temporary
  folder;
* ``pycon``: a doctest (the output shown must be the output printed);
* ``toml``: a scene file, given to the ``hertz`` command, which must accept it;
* ``console``: each ``$ hertz ...`` line is run (as ``python -m hertz.cli``) and must exit 0;
  a ``--scene NAME`` in it gets the page's first TOML block as NAME; other command lines
  (installs, FEM runs, other programs) are shown, not run;
* ``text`` (or no language): shown, not run: output, install lines, and commands too long
  for a test (FEM runs) or of tools that are not part of this project.

A page whose Python examples read the output of a program that a test cannot run is listed
in ``EXTERNAL`` with the test that runs it instead.
"""

from __future__ import annotations

import doctest
import importlib
import importlib.util
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
README = ROOT / "README.md"
TEST_COMMAND = 'pip install -e ".[test,fem,docs]" && python -m pytest'
MARKERS = ("solver-table", "memory-table", "stress-table", "speed-vs-error", "fem-validation",
           "fem-study", "fem-curved", "builds-table", "plane-study", "lammps-models",
           "dem-laws")
RUN = ("python", "pycon", "toml", "console")
#: pages whose Python examples need a program's output that this test cannot make, and why
EXTERNAL = {"docs/howto/calculix.md": "its Python examples read the .frd of a CalculiX run "
                                      "(ccx, minutes); tests/test_decks.py runs deck, ccx "
                                      "and grade end to end"}
SHOWN = ("text", "", "ipython3", "{code-cell}", "{eval-rst}", "{toctree}", "{figure}",
         "{only}")

FENCE = re.compile(r"^(?P<indent> *)(?P<ticks>```+)(?P<info>[^\n`]*)\n(?P<body>.*?)^(?P=indent)"
                   r"(?P=ticks)[ \t]*$", re.M | re.S)
ROLE = re.compile(r"\{(?:py:)?(?:func|class|meth|data|obj|mod|attr|exc)\}`(?:[^`<]*<)?~?"
                  r"(?P<target>[\w.]+)>?`")


def pages() -> list[Path]:
    skip = {DOCS / "speed_vs_error.md"}
    found = [p for p in DOCS.rglob("*.md")
             if "_build" not in p.parts and "generated" not in p.parts
             and "jupyter_execute" not in p.parts and p not in skip]
    return [README, *sorted(found)]


def blocks(path: Path) -> list[tuple[str, str]]:
    """(language, body) of every fenced block, in order."""
    return [(m["info"].strip().split(" ")[0].lower(), m["body"])
            for m in FENCE.finditer(path.read_text())]


def is_notebook(path: Path) -> bool:
    head = path.read_text().split("\n---\n", 1)[0]
    return path.read_text().startswith("---\n") and "file_format: mystnb" in head


def page_id(path: Path) -> str:
    return str(path.relative_to(ROOT))


if not (DOCS / "conf.py").exists():
    pytest.skip("no docs/ here (an unpacked sdist or a wheel test carries no documentation)",
                allow_module_level=True)


def _env() -> dict:
    env = dict(os.environ)  # the hertz under test: installed, or on the caller's PYTHONPATH
    env.setdefault("MPLBACKEND", "Agg")
    return env


def _hertz(args: list[str], cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "hertz.cli", *args], cwd=cwd, env=_env(),
                          capture_output=True, text=True, timeout=120)


# --- the site --------------------------------------------------------------------------


@pytest.mark.slow
def test_site_builds_without_warnings(tmp_path):
    for module in ("sphinx", "myst_nb", "numpydoc", "furo", "ipykernel"):
        if importlib.util.find_spec(module) is None:
            pytest.skip(f"{module} is not installed (pip install -e '.[docs]')")
    cmd = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-b", "html", "-q",
           "-d", str(tmp_path / "doctrees"), str(DOCS), str(tmp_path / "html")]
    out = subprocess.run(cmd, cwd=ROOT, env=_env(), capture_output=True, text=True,
                         timeout=900)
    warnings = [line for line in out.stderr.splitlines()
                if "WARNING" in line and "IPKernelApp" not in line or "ERROR" in line]
    assert out.returncode == 0, "\n".join(warnings) or out.stderr[-3000:]
    for page in ("index", "tutorials/first-contact", "tutorials/ball-bearing",
                 "howto/crossed-cylinders", "explanation/stresses", "api/index"):
        assert (tmp_path / "html" / f"{page}.html").exists(), page
    # the executed pages show their output: the first contact's printed semi-axes
    html = (tmp_path / "html" / "tutorials" / "first-contact.html").read_text()
    assert "a = 186.63 um" in html


# --- every example runs ---------------------------------------------------------------


@pytest.mark.parametrize("path", pages(), ids=page_id)
def test_every_block_is_run_somewhere(path):
    """No fenced block has a language this test neither runs nor knowingly shows."""
    for lang, _body in blocks(path):
        assert lang in RUN + SHOWN, f"{page_id(path)}: a ```{lang} block: run it or mark it"
        if lang == "{code-cell}":
            assert is_notebook(path), f"{page_id(path)}: code cells outside a notebook page"


@pytest.mark.parametrize("path", [p for p in pages() if any(lang in RUN for lang, _ in
                                                                blocks(p))], ids=page_id)
def test_examples_run(path, tmp_path, monkeypatch):
    found = blocks(path)
    code = "\n".join(body for lang, body in found if lang in ("python", "pycon"))
    if "fem_validation" in code and importlib.util.find_spec("gmsh") is None:
        pytest.skip("the example runs fem_validation, which needs the fem extra")
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    namespace: dict = {"__name__": "__docs__"}
    scenes = [body for lang, body in found if lang == "toml"]
    external = EXTERNAL.get(page_id(path))
    for i, (lang, body) in enumerate(found):
        where = f"{page_id(path)}, block {i + 1} ({lang})"
        if lang in ("python", "pycon") and external:
            continue  # see EXTERNAL: run elsewhere
        if lang == "python":
            exec(compile(body, where, "exec"), namespace)  # noqa: S102
        elif lang == "pycon":
            test = doctest.DocTestParser().get_doctest(body, namespace, where, str(path), 0)
            runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS
                                           | doctest.NORMALIZE_WHITESPACE)
            report: list[str] = []
            result = runner.run(test, out=report.append)
            assert result.failed == 0, f"{where}:\n" + "".join(report)
        elif lang == "toml":
            scene = tmp_path / f"scene{i}.toml"
            scene.write_text(body)
            out = _hertz(["--scene", str(scene)], tmp_path)
            assert out.returncode == 0, f"{where}: {out.stderr}"
        elif lang == "console":
            for line in body.splitlines():
                if not line.startswith("$ "):
                    continue
                if line[2:].split(" ", 1)[0] != "hertz":
                    continue  # shown, not run: installs, FEM runs, other programs
                argv = shlex.split(line[2:])
                if "--plot" in argv and importlib.util.find_spec("matplotlib") is None:
                    continue  # the plot extra is not installed: the option says so itself
                if "--scene" in argv:
                    name = argv[argv.index("--scene") + 1]
                    assert scenes, f"{where}: --scene {name} but the page has no TOML block"
                    (tmp_path / name).write_text(scenes[0])
                out = _hertz(argv[1:], tmp_path)
                assert out.returncode == 0, f"{where}: {line}: {out.stderr}"
                assert out.stdout.strip(), f"{where}: {line} printed nothing"


# --- the front page and the regenerated sections ----------------------------------------


def test_readme_is_a_front_page_with_the_two_commands():
    text = README.read_text()
    assert len(text.splitlines()) <= 150
    commands = [body.strip() for lang, body in blocks(README) if lang in ("", "text")]
    assert "pip install . && hertz" in commands
    assert TEST_COMMAND in commands
    ci = (ROOT / ".ci" / "run").read_text().rstrip("\n").splitlines()
    assert ci[-1] == TEST_COMMAND, ".ci/run's last line must be the README's test command"


def test_readme_links_exist():
    for target in re.findall(r"\]\(([^)#\s]+)\)", README.read_text()):
        if not target.startswith(("http://", "https://")):
            assert (ROOT / target).exists(), target


def test_each_regenerated_section_is_in_exactly_one_file():
    sys.path.insert(0, str(ROOT / "benchmarks"))
    try:
        from _common import marked_files
    finally:
        sys.path.remove(str(ROOT / "benchmarks"))
    files = marked_files(README)
    for marker in MARKERS:
        holders = [p for p in files if f"<!-- {marker} -->" in p.read_text()
                   and f"<!-- /{marker} -->" in p.read_text()]
        assert len(holders) == 1, (marker, holders)


def test_replace_section_finds_a_docs_page_and_fails_clearly(tmp_path):
    sys.path.insert(0, str(ROOT / "benchmarks"))
    try:
        from _common import replace_readme_section
    finally:
        sys.path.remove(str(ROOT / "benchmarks"))
    (tmp_path / "docs" / "explanation").mkdir(parents=True)
    readme = tmp_path / "README.md"
    readme.write_text("# front page\n")
    page = tmp_path / "docs" / "explanation" / "page.md"
    page.write_text("before\n<!-- table -->\nold\n<!-- /table -->\nafter\n")
    assert replace_readme_section("table", "new\n", readme) == page
    assert page.read_text() == "before\n<!-- table -->\nnew\n<!-- /table -->\nafter\n"
    assert readme.read_text() == "# front page\n"
    with pytest.raises(SystemExit, match="<!-- other -->.*found in 0"):
        replace_readme_section("other", "x", readme)


# --- intersphinx without network --------------------------------------------------------


def _inventory_module():
    spec = importlib.util.spec_from_file_location(
        "make_inventories", DOCS / "_inventories" / "make_inventories.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_inventories_are_the_scripts_output_and_cover_the_references():
    inv = _inventory_module()
    for project, entries in inv.OBJECTS.items():
        committed = (DOCS / "_inventories" / f"{project}.inv").read_bytes()
        assert committed == inv.inventory(project, entries), "re-run make_inventories.py"
    known = {name for entries in inv.OBJECTS.values() for name, *_ in entries}
    for path in pages():
        for m in ROLE.finditer(path.read_text()):
            target = m["target"]
            if target.split(".")[0] in ("numpy", "scipy", "dask", "meshio"):
                assert target in known, f"{page_id(path)}: {target} is not in the inventories"


# --- the API reference lists every public name ------------------------------------------


def test_the_api_reference_lists_every_public_name():
    pytest.importorskip("sphinx", reason="the docs extra is not installed")
    pytest.importorskip("skfem", reason="fem_validation needs the fem extra")
    spec = importlib.util.spec_from_file_location("docs_conf", DOCS / "conf.py")
    conf = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(conf)  # also writes docs/api/public_names.rst
    rst = conf.api_names_rst()
    assert "api/public_names.rst" in conf.autosummary_generate
    assert ".. include:: public_names.rst" in (DOCS / "api" / "index.md").read_text()
    for module in conf.API_MODULES:
        section = rst.split(f"``{module}``\n")[1].split("\n``")[0]
        listed = set(re.findall(r"^   (\w+)$", section, re.M))
        listed |= set(re.findall(rf"^\.\. py:data:: {re.escape(module)}\.(\w+)$", section,
                                 re.M))
        missing = sorted(set(importlib.import_module(module).__all__) - listed)
        assert missing == [], f"{module}: {missing} missing from the API reference"
