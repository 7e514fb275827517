"""The build guards the speed, not the clock: how the core was built and which code paths
it has, for the installed module and for a build with the flags of a distro's Python.

Debian's and Ubuntu's Python 3.12+ put ``-O2 -fno-strict-overflow`` in sysconfig's CFLAGS,
so that is what ``pip install`` from source compiles with there; with GCC's -O2 cost model
no block loop of the kernels was vectorised (3-5x slower, issue 24). These tests check,
without timing anything, that such a build still has every SIMD path and picks the one the
processor supports, and that each loop marked ``/* vectorised */`` in hertz/*.c is
vectorised by GCC and Clang under those flags plus setup.py's own (the compilers' own
reports: ``-fopt-info-vec-optimized``, ``-Rpass=loop-vectorize``).
"""

import platform
import re
import shutil
import subprocess
import sys
import sysconfig

import numpy as np
import pytest
from rebuild import ROOT, build

from hertz import _ufuncs

DISTRO_CFLAGS = "-O2 -fno-strict-overflow"
X86_LINUX = sys.platform.startswith("linux") and platform.machine() in ("x86_64", "AMD64")


def cpu_flags():
    try:
        with open("/proc/cpuinfo") as f:
            return next((line.split(":", 1)[1].split() for line in f
                         if line.startswith("flags")), [])
    except OSError:
        return []


def expected_path(info):
    """The path a build with ``info['paths']`` should run on this processor."""
    flags = set(cpu_flags())
    if "avx512" in info["paths"] and {"avx512f", "avx512dq", "avx512vl", "avx512bw", "avx2",
                                      "fma"} <= flags:
        return "avx512"
    if "avx2" in info["paths"] and {"avx2", "fma"} <= flags:
        return "avx2"
    return "plain"


def check_info(info):
    assert set(info) >= {"compiler", "command", "flags", "paths", "path", "fma", "plain",
                         "fast_math", "optimized"}
    assert not info["fast_math"]
    assert info["optimized"]
    assert "plain" in info["paths"] and info["path"] in info["paths"]
    if info["plain"]:
        assert info["paths"] == ("plain",)
    elif X86_LINUX and not info["compiler"].startswith("MSVC"):
        assert info["paths"] == ("avx512", "avx2", "plain")
    if cpu_flags():
        assert info["path"] == expected_path(info)
    assert info["fma"] == (info["path"] != "plain" or platform.machine() in ("aarch64", "arm64")
                           and not info["plain"])


def test_the_installed_module_reports_its_build():
    info = _ufuncs.build_info()
    check_info(info)
    if info["command"]:  # built by this setup.py (an older build records nothing)
        assert "-ffp-contract=off" in info["flags"] or "/fp:precise" in info["flags"]


def test_show_config_prints_the_build(capsys):
    from hertz._build_info import build_config, show_config

    show_config()
    out = capsys.readouterr().out
    info = build_config()
    assert info["compiler"] in out and f"code path in use: {info['path']}" in out


def test_the_path_can_be_limited_and_restored():
    before = _ufuncs.path()
    try:
        assert _ufuncs.path("plain") == "plain" and not _ufuncs.simd()
        alpha = np.linspace(1.0, 50.0, 999)
        plain = _ufuncs.ellipticity1(alpha)
        for name in _ufuncs.build_info()["paths"]:
            _ufuncs.path(name)
            np.testing.assert_array_equal(_ufuncs.ellipticity1(alpha), plain)
        with pytest.raises(ValueError, match="no code path"):
            _ufuncs.path("sse9")
    finally:
        _ufuncs.path("avx512")
    assert _ufuncs.path() == before


@pytest.mark.parametrize("cc", [None, "clang"], ids=["default-compiler", "clang"])
def test_a_build_with_distro_cflags_keeps_every_code_path(tmp_path, monkeypatch, cc):
    monkeypatch.setenv("CFLAGS", DISTRO_CFLAGS)
    module = build(tmp_path, cc=cc)
    info = module.build_info()
    check_info(info)
    assert DISTRO_CFLAGS in info["command"]
    assert "-ffp-contract=off" in info["flags"]
    gcc = info["compiler"].startswith("GCC")
    assert ("-fvect-cost-model=dynamic" in info["flags"]) == gcc
    assert ("vectoriser flags: -ftree-vectorize -fvect-cost-model=dynamic"
            in module.build_log) == gcc


def setup_flags(compiler):
    """setup.py's flags for ``compiler`` (a distutils CCompiler)."""
    namespace = {"__name__": "hertz_setup", "__file__": str(ROOT / "setup.py")}
    exec(compile((ROOT / "setup.py").read_text(), str(ROOT / "setup.py"), "exec"), namespace)
    return namespace["float_flags"](compiler) + namespace["vector_flags"](compiler)


def marked_loops(path):
    return {n for n, line in enumerate(path.read_text().splitlines(), 1)
            if "/* vectorised */" in line}


@pytest.mark.parametrize("cc", ["gcc", "clang"])
@pytest.mark.parametrize("source", ["_contact_kernel.c", "_kernel.c"])
def test_the_marked_loops_vectorise_with_distro_cflags(tmp_path, cc, source):
    if not (ROOT / "setup.py").is_file() or not (ROOT / "hertz" / source).is_file():
        pytest.skip(f"no source tree at {ROOT}")
    if shutil.which(cc) is None:
        pytest.skip(f"no {cc} on PATH")
    if not X86_LINUX:
        pytest.skip("the SIMD paths are built on x86-64 Linux")
    pytest.importorskip("setuptools")
    from setuptools._distutils.ccompiler import new_compiler
    from setuptools._distutils.sysconfig import customize_compiler

    compiler = new_compiler()
    customize_compiler(compiler)
    compiler.set_executables(compiler_so=[cc, "-fPIC"])
    flags = setup_flags(compiler)
    assert "-ffp-contract=off" in flags
    report = ["-fopt-info-vec-optimized"] if cc == "gcc" else ["-Rpass=loop-vectorize"]
    command = [cc, *DISTRO_CFLAGS.split(), "-fPIC", *flags, *report,
               f"-I{np.get_include()}", f"-I{sysconfig.get_paths()['include']}",
               "-c", str(ROOT / "hertz" / source), "-o", str(tmp_path / "kernel.o")]
    done = subprocess.run(command, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-4000:]
    text = done.stdout + done.stderr
    pattern = (rf"{re.escape(source)}:(\d+):\d+: optimized: loop vectorized" if cc == "gcc"
               else rf"{re.escape(source)}:(\d+):\d+: remark: vectorized loop")
    vectorised = {int(m) for m in re.findall(pattern, text)}
    marked = marked_loops(ROOT / "hertz" / source)
    assert marked, f"no loop of hertz/{source} is marked /* vectorised */"
    assert marked <= vectorised, (f"{cc} {DISTRO_CFLAGS} {' '.join(flags)} leaves the loops "
                                  f"at lines {sorted(marked - vectorised)} of hertz/{source} "
                                  "scalar")
