"""How the compiled core was built and which code path it runs: :func:`show_config`."""

from __future__ import annotations

import platform
import sys


def _cpu_name() -> str:
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def build_config() -> dict:
    """The build of ``hertz._ufuncs`` and the versions around it, as a dict.

    ``compiler``, ``command`` (the compile command, CFLAGS included), ``flags`` (those
    setup.py added), ``paths`` (the SIMD code paths compiled in: ``avx512``, ``avx2``,
    ``plain``), ``path`` (the one this processor runs), ``fma`` (exact products by fused
    multiply-add: the same bits either way), ``plain`` (built with ``HERTZ_PLAIN=1``),
    ``fast_math`` and ``optimized``; then ``hertz``, ``python``, ``numpy``, ``machine``
    and ``processor``.
    """
    import importlib.metadata

    import numpy

    from ._ufuncs import build_info

    try:
        version = importlib.metadata.version("hertz-contact")
    except importlib.metadata.PackageNotFoundError:  # a checkout built in place
        version = "unknown (not installed)"
    info = dict(build_info())
    info.update(hertz=version, python=sys.version.split()[0], numpy=numpy.__version__,
                machine=platform.machine(), processor=_cpu_name())
    return info


def show_config(file=None) -> None:
    """Print how hertz's compiled core was built and which code path it runs.

    For bug reports and speed questions: the compiler and its flags, the SIMD code paths
    compiled in and the one this processor uses (all give the same bits), with the
    versions of hertz, Python and numpy.

    >>> import hertz
    >>> hertz.show_config()  # doctest: +SKIP
    hertz 0.1.0, Python 3.11.7, numpy 2.4.6
    processor: Intel(R) Xeon(R) Processor (x86_64)
    compiler: GCC 12.2.0
    ...
    """
    info = build_config()
    lines = [
        f"hertz {info['hertz']}, Python {info['python']}, numpy {info['numpy']}",
        f"processor: {info['processor']} ({info['machine']})",
        f"compiler: {info['compiler']}",
        f"compile command: {info['command'] or '(not recorded)'}",
        f"flags added by setup.py: {info['flags'] or '(not recorded)'}",
        f"code paths compiled in: {', '.join(info['paths'])}"
        + (" (HERTZ_PLAIN build)" if info["plain"] else ""),
        f"code path in use: {info['path']}"
        + (", exact products by fused multiply-add" if info["fma"] else ""),
    ]
    if info["fast_math"]:
        lines.append("WARNING: built with fast-math (results are not the tested bits)")
    if not info["optimized"]:
        lines.append("WARNING: built without optimisation (-O0): slow")
    print("\n".join(lines), file=file if file is not None else sys.stdout)
