"""One line describing the machine and library versions, for benchmark reports."""

from __future__ import annotations

import platform


def cpu_name() -> str:
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def describe() -> str:
    import numpy
    import scipy

    import hertz

    return (f"hertz {hertz.__version__}, numpy {numpy.__version__}, scipy {scipy.__version__}, "
            f"Python {platform.python_version()}, {cpu_name()}")
