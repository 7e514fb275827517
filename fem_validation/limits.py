"""Bounds on what a file from outside may make fem_validation read or allocate.

Every text input a person writes by hand (a scene, a tolerance table, a force-approach
curve, a problem.json) is read through :func:`read_small_text`, capped at
:data:`MAX_TEXT_BYTES` as ``hertz --scene`` is; a count announced inside a file (the nodes
of a .frd block, say) is checked by :func:`check_count` against what the rest of the file
can hold before anything is allocated for it.  Both raise one-line :class:`ValueError`\\ s
naming the file (and the line, where there is one).
"""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["MAX_TEXT_BYTES", "check_count", "file_size", "read_small_text"]

#: The largest hand-written text file read whole [bytes] (1 MiB, as ``hertz --scene``).
MAX_TEXT_BYTES = 1 << 20


def read_small_text(path, what: str, limit: int = MAX_TEXT_BYTES) -> str:
    """The text of a small file, read at most ``limit + 1`` bytes far.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    what : str
        What the file is, for the message (``"scene file"``, ``"--tolerances file"``).
    limit : int, optional
        The largest size accepted [bytes].

    Returns
    -------
    str
        The text, decoded as UTF-8 (a byte-order mark, as Excel writes, is dropped).

    Raises
    ------
    ValueError
        The file is larger than ``limit`` (``/dev/zero`` too), is not UTF-8 text, or
        cannot be read (the OS's reason, with the path).
    """
    path = Path(path)
    try:
        with open(path, "rb") as f:
            data = f.read(limit + 1)
    except OSError as exc:
        raise ValueError(f"{what} {str(path)!r} cannot be read: "
                         f"{exc.strerror or exc}") from None
    if len(data) > limit:
        raise ValueError(f"{what} {str(path)!r} is larger than {limit} bytes: a "
                         "hand-written file of this kind is far smaller (is it the right file?)")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise ValueError(f"{what} {str(path)!r}, line {line}: not UTF-8 text "
                         f"(byte {data[exc.start]:#04x} at offset {exc.start})") from None


def check_count(count: int, bytes_each: int, available: int, where: str, what: str) -> int:
    """``count`` if ``count`` items of at least ``bytes_each`` bytes fit in ``available``.

    Parameters
    ----------
    count : int
        The number of items a file announces.
    bytes_each : int
        The fewest bytes one item takes in the file.
    available : int
        The bytes left in the file after the announcement.
    where : str
        File and line or record, for the message (``"run.frd, line 12"``).
    what : str
        What is counted (``"nodes"``).

    Raises
    ------
    ValueError
        ``count`` is negative or more than the file can hold.
    """
    if count < 0:
        raise ValueError(f"{where}: the number of {what} is {count}; it must be 0 or more")
    if count * bytes_each > available:
        raise ValueError(f"{where}: announces {count} {what} but only {available} bytes "
                         f"follow (each takes at least {bytes_each}): the file is cut or "
                         "corrupt")
    return count


def file_size(path) -> int:
    """The size of a regular file [bytes]; that of a device or pipe is taken as unbounded."""
    try:
        st = os.stat(path)
    except OSError:
        return 0
    return st.st_size if st.st_size > 0 else 1 << 62
