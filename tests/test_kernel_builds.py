"""Every build and every code path gives the same bits as a plain build.

The installed hertz._ufuncs (on x86-64 Linux: AVX-512, AVX2 and plain code paths, one
chosen at run time) against hertz._ufuncs rebuilt here by setup.py, with the same
per-compiler flags, from every hertz/*.c with -DHERTZ_PLAIN (plain C only); see
tests/rebuild.py. Each path of the installed module is compared (``_ufuncs.path`` limits
the one in use), and so are the builds users make: GCC with the CFLAGS of Debian's and
Ubuntu's Python 3.12+ (``-O2 -fno-strict-overflow``), and Clang's plain build (Clang's
default build is compared in tests/test_packaging.py). On other platforms the comparison
still checks that a fresh build gives the installed bits.
"""

import pytest
from rebuild import assert_same_bits, build

from hertz import _ufuncs


@pytest.fixture(scope="module")
def plain(tmp_path_factory):
    module = build(tmp_path_factory.mktemp("plain"), plain=True)
    assert "-DHERTZ_PLAIN" in module.build_log and "-ffp-contract=off" in module.build_log
    assert module.build_info()["paths"] == ("plain",)
    return module


def test_multiversioned_kernel_matches_a_baseline_build(plain):
    assert_same_bits(_ufuncs, plain)


def test_every_code_path_matches_a_baseline_build(plain):
    paths = _ufuncs.build_info()["paths"]
    try:
        for path in paths:
            used = _ufuncs.path(path)
            assert_same_bits(_ufuncs, plain)
            assert used in paths
    finally:
        _ufuncs.path("avx512")  # back to the best the processor has


def test_a_build_with_distro_cflags_gives_the_same_bits(tmp_path, monkeypatch, plain):
    monkeypatch.setenv("CFLAGS", "-O2 -fno-strict-overflow")
    distro = build(tmp_path)
    assert "-O2 -fno-strict-overflow" in distro.build_info()["command"]
    for path in distro.build_info()["paths"]:
        distro.path(path)
        assert_same_bits(distro, plain)


def test_a_plain_clang_build_gives_the_same_bits(tmp_path, plain):
    clang = build(tmp_path, cc="clang", plain=True)
    assert clang.build_info()["compiler"].startswith("Clang")
    assert_same_bits(clang, plain)


def test_every_code_path_of_a_clang_build_gives_the_same_bits(tmp_path, plain):
    clang = build(tmp_path, cc="clang")
    assert clang.build_info()["compiler"].startswith("Clang")
    for path in clang.build_info()["paths"]:
        clang.path(path)
        assert_same_bits(clang, plain)
