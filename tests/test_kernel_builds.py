"""The installed core gives the same bits as a plain build.

The installed hertz._ufuncs (on x86-64 Linux: AVX2 clones and the AVX2 start path chosen at
load time) against hertz._ufuncs rebuilt here by setup.py, with the same per-compiler flags,
from every hertz/*.c with -DHERTZ_PLAIN (plain C only); see tests/rebuild.py. On other
platforms the comparison still checks that a fresh build gives the installed bits.
"""

from rebuild import assert_same_bits, build

from hertz import _ufuncs


def test_multiversioned_kernel_matches_a_baseline_build(tmp_path):
    plain = build(tmp_path, plain=True)
    assert "-DHERTZ_PLAIN" in plain.build_log and "-ffp-contract=off" in plain.build_log
    assert_same_bits(_ufuncs, plain)
