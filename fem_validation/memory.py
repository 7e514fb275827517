"""Peak resident memory of this process, resettable between runs (Linux)."""

from __future__ import annotations

import math
from pathlib import Path

_STATUS = Path("/proc/self/status")
_CLEAR_REFS = Path("/proc/self/clear_refs")


def reset_peak() -> bool:
    """Reset the process's peak resident memory (VmHWM) to its current size.

    Returns False where the kernel does not allow it (then :func:`peak_mb`
    reports the peak since the process started).
    """
    try:
        _CLEAR_REFS.write_text("5")
    except OSError:
        return False
    return True


def peak_mb() -> float:
    """Peak resident memory since the last :func:`reset_peak` [MB]; NaN if unknown."""
    try:
        for line in _STATUS.read_text().splitlines():
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) / 1024.0
    except OSError:
        pass
    return math.nan
