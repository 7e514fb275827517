"""Build hertz._ufuncs again from the source tree beside these tests, and compare builds.

:func:`build` runs the project's own setup.py (``build_ext``, so the same C files and the
same per-compiler flags as ``pip install``) into a temporary directory and loads the result
under another module object; :func:`assert_same_bits` compares two builds on the inputs of
tests/test_kernel_builds.py. Used by tests/test_kernel_builds.py and tests/test_packaging.py.
"""

import importlib.machinery
import importlib.util
import os
import shlex
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import numpy as np
import pytest
from reference import load_table

#: The project root: setup.py, hertz/*.c (a checkout, the unpacked sdist, cibuildwheel's
#: {project}).
ROOT = Path(__file__).resolve().parents[1]


def compiler_command(cc=None):
    """The C compiler setuptools would run (``cc``, else $CC, else Python's CC) or None."""
    command = cc or os.environ.get("CC") or sysconfig.get_config_var("CC")
    if not command or not shlex.split(command):
        return None
    return shutil.which(shlex.split(command)[0])


def build(tmp_path, *, cc=None, plain=False):
    """hertz._ufuncs built by ``setup.py build_ext`` into ``tmp_path``, loaded as a module.

    ``cc``: the compiler ($CC for setuptools; the linker follows it); ``plain``: with
    HERTZ_PLAIN=1 (no AVX2 code). Skips when there is no setup.py beside the tests, on
    Windows (MSVC is found by setuptools, not on PATH; its builds take the plain path
    anyway) or when the compiler is not on PATH; fails with the compiler's output when the
    build fails.
    """
    if not (ROOT / "setup.py").is_file() or not (ROOT / "hertz" / "_kernel.c").is_file():
        pytest.skip(f"no source tree at {ROOT} (setup.py, hertz/*.c)")
    if sys.platform == "win32":
        pytest.skip("rebuilds are tested with Unix-style compilers only")
    if compiler_command(cc) is None:
        pytest.skip(f"no C compiler on PATH ({cc or os.environ.get('CC') or 'cc'})")
    pytest.importorskip("setuptools")
    env = {k: v for k, v in os.environ.items() if k not in ("HERTZ_PLAIN", "LDSHARED")}
    if cc:
        env["CC"] = cc
    if plain:
        env["HERTZ_PLAIN"] = "1"
    lib, temp = tmp_path / "lib", tmp_path / "temp"
    done = subprocess.run([sys.executable, "setup.py", "build_ext", "--build-lib", str(lib),
                           "--build-temp", str(temp)], cwd=ROOT, env=env, capture_output=True,
                          text=True)
    if done.returncode != 0:
        pytest.fail(f"setup.py build_ext failed ({cc or 'default compiler'}, plain={plain}):\n"
                    f"{done.stdout[-4000:]}\n{done.stderr[-4000:]}")
    so = lib / "hertz" / ("_ufuncs" + sysconfig.get_config_var("EXT_SUFFIX"))
    assert so.is_file(), f"setup.py build_ext wrote no {so}:\n{done.stdout[-2000:]}"
    loader = importlib.machinery.ExtensionFileLoader("hertz._ufuncs", str(so))
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader("hertz._ufuncs",
                                                                             loader))
    loader.exec_module(module)
    module.build_log = done.stdout
    return module


def assert_same_bits(ours, other):
    """The ellipse ufuncs (the 50-digit table's alphas and 50001 log-uniform ones in
    [e^-60, e^60]), contact_load, contact_approach, contact_p0 (at random angles and at
    angle 0, ordinary and extreme values) and contact_coefficients (20000 random scenes)
    and the stress ufuncs give identical arrays."""
    rng = np.random.default_rng(1)
    alpha = np.concatenate([[r["alpha"] for r in load_table()],
                            np.exp(rng.uniform(-60, 60, 50_001))])
    for name in ("ellipticity0", "ellipticity1", "ellipticity2", "ellipse0", "ellipse1"):
        np.testing.assert_array_equal(getattr(ours, name)(alpha), getattr(other, name)(alpha),
                                      err_msg=name)
    n = 20_000
    geometry = [rng.uniform(1e-3, 1e-1, n), rng.uniform(1e-3, 1e-1, n),
                -rng.uniform(0.11, 0.2, n), rng.uniform(1e-3, 1e-1, n), rng.uniform(-3, 3, n),
                np.full(n, 210e9), np.full(n, 0.3), rng.uniform(7e10, 4e11, n), np.full(n, 0.25)]
    # ordinary loads (the fast scaling) and loads to 1e+-300 (blocks redone with the exact
    # scaling); random angles, then all at angle 0 (the aligned geometry)
    load = np.concatenate([10 ** rng.uniform(-3, 5, n // 2), 10 ** rng.uniform(-300, 300, n // 2)])
    # then blocks that mix the kernel's geometry variants: infinite radii, angles at and one
    # ulp either side of 2^-500 (the bound of the variant for finite radii and angles),
    # subnormal, multiples of pi/2, large
    special = np.array([0.0, 2.0**-500, np.nextafter(2.0**-500, 0), np.nextafter(2.0**-500, 1),
                        -(2.0**-500), 2.0**-501, 1e-320, np.pi / 2, np.pi, 2e5, -2e5])
    mixed = geometry[4].copy()
    mixed[::7] = np.resize(special, mixed[::7].size)
    flat_y = geometry[3].copy()
    flat_y[::5] = np.inf  # body 2 a concave groove, straight along y
    scenes = ([*geometry[:4], geometry[4], *geometry[5:]],
              [*geometry[:4], np.zeros(n), *geometry[5:]],
              [*geometry[:3], flat_y, mixed, *geometry[5:]])
    for scene in scenes:
        for name, value in (("contact_load", load), ("contact_approach", load * 1e-9),
                            ("contact_p0", load * 1e6)):
            np.testing.assert_array_equal(getattr(ours, name)(*scene, value),
                                          getattr(other, name)(*scene, value), err_msg=name)
    np.testing.assert_array_equal(ours.contact_coefficients(*geometry[:9]),
                                  other.contact_coefficients(*geometry[:9]),
                                  err_msg="contact_coefficients")
    m = 2_000
    a, b = rng.uniform(1.0, 30.0, m), np.ones(m)
    nu = rng.uniform(-0.5, 0.5, m)
    point = [rng.uniform(-3, 3, m) * a, rng.uniform(-3, 3, m), rng.uniform(0, 3, m)]
    np.testing.assert_array_equal(ours.point_stress(a, b, nu, *point),
                                  other.point_stress(a, b, nu, *point), err_msg="point_stress")
    np.testing.assert_array_equal(ours.subsurface(a[:200], b[:200], nu[:200]),
                                  other.subsurface(a[:200], b[:200], nu[:200]),
                                  err_msg="subsurface")
