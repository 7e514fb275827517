"""What the distributions hold and how they build: the sdist's file list, the geometry in
the wheel, the floating-point flags per compiler, and a Clang build giving the same bits.

Each runs the project's setup.py into a temporary directory (never into the source tree);
they skip when the tests run without the source tree beside them.
"""

import os
import runpy
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest
from rebuild import ROOT, assert_same_bits, build

from hertz import _ufuncs

needs_source_tree = pytest.mark.skipif(not (ROOT / "setup.py").is_file(),
                                       reason=f"no setup.py at {ROOT}")


def setup_py(*args, tmp_path):
    """Run ``python setup.py *args`` in the project root; its stdout."""
    pytest.importorskip("setuptools")
    env = {k: v for k, v in os.environ.items() if k != "HERTZ_PLAIN"}
    done = subprocess.run([sys.executable, "setup.py", *args], cwd=ROOT, env=env,
                          capture_output=True, text=True)
    assert done.returncode == 0, f"setup.py {' '.join(args)}:\n{done.stdout}\n{done.stderr}"
    return done.stdout


@pytest.mark.skipif(shutil.which("clang") is None,
                    reason="clang is not on PATH (.ci/run installs it with apt-get as root)")
def test_a_clang_build_gives_the_same_bits(tmp_path):
    clang = build(tmp_path, cc="clang")
    assert "building with clang" in clang.build_log
    if sys.platform.startswith("linux"):  # the ELF .comment section names the compiler
        assert b"clang version" in (tmp_path / "lib" / "hertz" / (
            "_ufuncs" + sysconfig.get_config_var("EXT_SUFFIX"))).read_bytes()
    assert_same_bits(_ufuncs, clang)


@needs_source_tree
def test_the_sdist_holds_the_sources_tests_and_geometry(tmp_path):
    setup_py("egg_info", "--egg-base", str(tmp_path), tmp_path=tmp_path)
    listed = set((tmp_path / "hertz_contact.egg-info" / "SOURCES.txt").read_text().split("\n"))
    wanted = {"README.md", "pyproject.toml", "setup.py", "MANIFEST.in"}
    for pattern in ("hertz/*.py", "hertz/*.c", "hertz/*.h", "fem_validation/*.py",
                    "meshes/*.geo", "tests/*.py", "tests/data/*", "benchmarks/*.py"):
        found = {p.relative_to(ROOT).as_posix() for p in ROOT.glob(pattern) if p.is_file()}
        assert found, pattern
        wanted |= found
    assert {"tests/conftest.py", "tests/reference.py", "tests/data/reference_lambda.csv",
            "meshes/blocks.geo", "hertz/_kernel.c", "hertz/_coefficients.h"} <= wanted
    assert sorted(wanted - listed) == []
    unwanted = [f for f in listed if f.endswith((".so", ".pyd", ".pyc", ".o"))
                or f.startswith(("build/", "dist/", "fem_out/", "out/"))]
    assert unwanted == []


@needs_source_tree
def test_the_distribution_is_hertz_contact_with_the_import_name_and_command_hertz(tmp_path):
    """``hertz`` on the package index is another project (a units package that also installs
    an import package ``hertz``): ours is ``hertz-contact``, importing as ``hertz`` with the
    ``hertz`` command, at the version ``hertz.__version__`` says."""
    import hertz

    setup_py("egg_info", "--egg-base", str(tmp_path), tmp_path=tmp_path)
    info = tmp_path / "hertz_contact.egg-info"
    fields = dict(line.split(": ", 1) for line in (info / "PKG-INFO").read_text().splitlines()
                  if line[:1].isalpha() and ": " in line)
    assert fields["Name"] == "hertz-contact"
    assert fields["Version"] == hertz.__version__
    assert "hertz = hertz.cli:main" in (info / "entry_points.txt").read_text()
    assert (info / "top_level.txt").read_text().split() == ["fem_validation", "hertz"]


@needs_source_tree
def test_the_wheel_carries_the_geometry_and_no_c_sources(tmp_path):
    setup_py("build_py", "--build-lib", str(tmp_path), tmp_path=tmp_path)
    for geo in (ROOT / "meshes").glob("*.geo"):
        packaged = tmp_path / "fem_validation" / "meshes" / geo.name
        assert packaged.read_bytes() == geo.read_bytes()
    assert (tmp_path / "fem_validation" / "meshes" / "blocks.geo").is_file()
    assert (tmp_path / "hertz" / "__init__.py").is_file()
    assert sorted(p.name for p in (tmp_path / "hertz").glob("*.[ch]")) == []
    # every Python module of the source tree, subpackages included (readers/ and decks/
    # were once left out of the wheel, so `grade` and `deck` failed from an install)
    for package in ("hertz", "fem_validation"):
        for module in (ROOT / package).rglob("*.py"):
            assert (tmp_path / module.relative_to(ROOT)).is_file(), module
    # every subpackage imports from the build, and finds its geometry there
    subpackages = sorted(".".join(p.parent.relative_to(tmp_path).parts)
                         for p in (tmp_path / "fem_validation").rglob("__init__.py"))
    assert {"fem_validation.cli", "fem_validation.grading", "fem_validation.readers",
            "fem_validation.reports", "fem_validation.results", "fem_validation.runs",
            "fem_validation.solvers"} <= set(subpackages)
    code = ("import importlib, sys; import fem_validation.solvers.mesh as m; "
            f"[importlib.import_module(n) for n in {subpackages!r}]; "
            "print(m.geometry_file('blocks.geo'))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=tmp_path, env={**os.environ, "PYTHONPATH": str(tmp_path)})
    assert done.returncode == 0, done.stderr
    assert Path(done.stdout.strip()).resolve() == (tmp_path / "fem_validation" / "meshes" /
                                                   "blocks.geo").resolve()


class FakeCompiler:
    """A distutils compiler of a given type; ``accepts`` is the set of flags it compiles."""

    def __init__(self, compiler_type, accepts=()):
        self.compiler_type, self.accepted = compiler_type, set(accepts)

    def compile(self, sources, output_dir=None, extra_postargs=()):
        if not set(extra_postargs) <= self.accepted:
            raise RuntimeError(f"unknown flag {extra_postargs}")
        return []


@needs_source_tree
def test_floating_point_flags_per_compiler():
    pytest.importorskip("setuptools")
    setup = runpy.run_path(str(ROOT / "setup.py"), run_name="hertz_setup")  # no setup() call
    float_flags = setup["float_flags"]
    assert float_flags(FakeCompiler("msvc")) == ["/fp:precise"]
    everything = ["-fno-fast-math", "-fno-math-errno", "-fno-trapping-math",
                  "-ffp-contract=off"]
    assert float_flags(FakeCompiler("unix", everything)) == everything
    # a compiler without the optional flags still gets -ffp-contract=off (and fails the
    # build if it does not take it: contraction would change the bits)
    assert float_flags(FakeCompiler("unix")) == ["-ffp-contract=off"]
    assert setup["SOURCES"] == sorted(p.relative_to(ROOT).as_posix()
                                      for p in (ROOT / "hertz").glob("*.c"))
    assert "hertz/_ufuncs.c" in setup["SOURCES"] and "hertz/_kernel.c" in setup["SOURCES"]
