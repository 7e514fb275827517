"""The installed core (AVX2 clones on x86-64 Linux) gives the same bits as a plain build."""

import importlib.machinery
import importlib.util
import platform
import subprocess
import sys
import sysconfig
from pathlib import Path

import numpy as np
import pytest
from reference import load_table

import hertz
from hertz import _ufuncs

SOURCES = ("_ufuncs.c", "_kernel.c", "_contact_kernel.c")


def plain_build(tmp_path):
    """hertz._ufuncs compiled again with -DHERTZ_PLAIN (no AVX2 clones), loaded under
    another module object."""
    src = Path(hertz.__file__).parent
    so = tmp_path / ("_ufuncs" + sysconfig.get_config_var("EXT_SUFFIX"))
    cc = (sysconfig.get_config_var("CC") or "cc").split()
    subprocess.run([*cc, "-O3", "-fPIC", "-shared", "-DHERTZ_PLAIN", "-fno-math-errno",
                    "-fno-trapping-math", "-ffp-contract=off",
                    f"-I{sysconfig.get_paths()['include']}", f"-I{np.get_include()}", f"-I{src}",
                    *(str(src / name) for name in SOURCES), "-o", str(so), "-lm"], check=True)
    loader = importlib.machinery.ExtensionFileLoader("hertz._ufuncs", str(so))
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader("hertz._ufuncs",
                                                                             loader))
    loader.exec_module(module)
    return module


@pytest.mark.skipif(not (sys.platform.startswith("linux") and platform.machine() == "x86_64"),
                    reason="the kernel is compiled for a single target elsewhere")
def test_multiversioned_kernel_matches_a_baseline_build(tmp_path):
    plain = plain_build(tmp_path)
    rng = np.random.default_rng(1)
    alpha = np.concatenate([[r["alpha"] for r in load_table()],
                            np.exp(rng.uniform(-60, 60, 50_001))])
    for name in ("ellipticity0", "ellipticity1", "ellipticity2", "ellipse0", "ellipse1"):
        ours, baseline = getattr(_ufuncs, name)(alpha), getattr(plain, name)(alpha)
        np.testing.assert_array_equal(ours, baseline, err_msg=name)
    n = 20_000
    geometry = [rng.uniform(1e-3, 1e-1, n), rng.uniform(1e-3, 1e-1, n),
                -rng.uniform(0.11, 0.2, n), rng.uniform(1e-3, 1e-1, n), rng.uniform(-3, 3, n),
                np.full(n, 210e9), np.full(n, 0.3), rng.uniform(7e10, 4e11, n), np.full(n, 0.25)]
    load = 10 ** rng.uniform(-3, 5, n)
    np.testing.assert_array_equal(_ufuncs.contact_load(*geometry, load),
                                  plain.contact_load(*geometry, load))
