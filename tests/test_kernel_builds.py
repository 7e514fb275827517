"""The installed kernel (AVX2 clones on x86-64 Linux) gives the same bits as a plain build."""

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
from hertz import _kernel

MULTIVERSION = '#define MULTIVERSION __attribute__((target_clones("avx2", "default")))'


@pytest.mark.skipif(not (sys.platform.startswith("linux") and platform.machine() == "x86_64"),
                    reason="the kernel is compiled for a single target elsewhere")
def test_multiversioned_kernel_matches_a_baseline_build(tmp_path):
    src = Path(hertz.__file__).with_name("_kernel.c")
    text = src.read_text()
    assert MULTIVERSION in text
    (tmp_path / "_kernel.c").write_text(text.replace(MULTIVERSION, "#define MULTIVERSION"))
    (tmp_path / "_coefficients.h").write_text(src.with_name("_coefficients.h").read_text())
    so = tmp_path / ("_kernel" + sysconfig.get_config_var("EXT_SUFFIX"))
    cc = (sysconfig.get_config_var("CC") or "cc").split()
    subprocess.run([*cc, "-O3", "-fPIC", "-shared", "-fno-math-errno", "-fno-trapping-math",
                    "-ffp-contract=off", f"-I{sysconfig.get_paths()['include']}",
                    str(tmp_path / "_kernel.c"), "-o", str(so)], check=True)
    loader = importlib.machinery.ExtensionFileLoader("_kernel", str(so))
    plain = importlib.util.module_from_spec(importlib.util.spec_from_loader("_kernel", loader))
    loader.exec_module(plain)
    rng = np.random.default_rng(1)
    alpha = np.concatenate([[r["alpha"] for r in load_table()],
                            np.exp(rng.uniform(-60, 60, 50_001))])
    for iterations in (0, 1, 2):
        outputs = []
        for module in (_kernel, plain):
            arrays = [np.empty_like(alpha) for _ in range(4)]
            assert module.solve(alpha, *arrays, iterations) == -1
            outputs.append(arrays)
        for ours, baseline in zip(*outputs, strict=True):
            np.testing.assert_array_equal(ours, baseline)
