"""What a DEM code's impact of two bodies is, in SI: the input of the impact grader.

An :class:`ImpactTrajectory` is the record of one contact of two bodies that approach,
touch, and part: the time, the overlap and the normal contact force at each output step
of the DEM run, from before the contact starts to after it ends; optionally the normal
relative velocity, and for an oblique impact the tangential force, the tangential
velocity of body 1's centre and body 1's spin.  It is filled by a reader
(:func:`fem_validation.readers.impact_csv.read_impact`) or by hand, and handed to
:func:`fem_validation.grading.impact.grade_impact`.

Conventions:

* ``t`` [s] strictly increasing; ``overlap`` [m] > 0 in contact (what the code writes
  outside the contact, negative gaps or 0, is kept); ``normal_force`` [N] > 0 in contact,
  0 (or the code's attractive value, <= 0) outside.
* ``v_n`` [m/s]: the normal relative velocity, any sign convention (the grader takes
  ratios: restitution = -v_n(after) / v_n(before)).
* ``tangential_force`` [N] on body 1, ``v_t`` [m/s] body 1's centre, positive along the
  incoming tangential velocity; ``omega`` [rad/s] body 1's spin, positive when it rolls
  forward (the contact point slips at ``v_t - R omega``).

Construction validates every field once and raises
:class:`~fem_validation.results.contact.ResultError` (a ValueError) naming the source,
the field, the row (or the file's line) and what is allowed.  Arrays are copied and made
read-only.

Examples
--------
>>> from fem_validation.results.impact import ImpactTrajectory
>>> r = ImpactTrajectory(t=[0.0, 1e-6, 2e-6, 3e-6], overlap=[-1e-6, 1e-6, 1e-6, -1e-6],
...                      normal_force=[0.0, 5.0, 5.0, 0.0])
>>> r.rows, r.oblique
(4, False)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .contact import ResultError

__all__ = ["MAX_ABS", "OBLIQUE_FIELDS", "ImpactTrajectory"]

#: The largest magnitude a value may have in SI (no time, overlap, force, speed or spin of a
#: DEM run comes near it; beyond it the grader's squares and powers would overflow).
MAX_ABS = 1e100

#: The fields an oblique impact adds (all three, or none).
OBLIQUE_FIELDS = ("tangential_force", "v_t", "omega")


def _field(value, name: str, n: int | None, where) -> np.ndarray:
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ResultError(f"{where(None)}field {name!r} must be an array of numbers") from None
    if a.ndim != 1:
        raise ResultError(f"{where(None)}field {name!r} must be one-dimensional, got shape "
                          f"{a.shape}")
    if n is not None and len(a) != n:
        raise ResultError(f"{where(None)}field {name!r} has {len(a)} values, 't' has {n}")
    bad = ~np.isfinite(a)
    if bad.any():
        k = int(np.argmax(bad))
        raise ResultError(f"{where(k)}field {name!r} is {float(a[k])!r}: every value must "
                          f"be a finite number ({int(bad.sum())} are not)")
    big = np.abs(a) > MAX_ABS
    if big.any():
        k = int(np.argmax(big))
        raise ResultError(f"{where(k)}field {name!r} is {float(a[k])!r}: every value must "
                          f"lie within +-{MAX_ABS:g} (SI units)")
    a.flags.writeable = False
    return a


@dataclass(frozen=True)
class ImpactTrajectory:
    """One impact of two bodies as a DEM code recorded it (SI).

    Attributes
    ----------
    t : ndarray, shape (n,)
        Time [s], strictly increasing, n >= 3.
    overlap : ndarray, shape (n,)
        Overlap (approach) of the bodies [m], > 0 in contact.
    normal_force : ndarray, shape (n,)
        Normal contact force [N], > 0 in contact.
    v_n : ndarray, shape (n,), or None
        Normal relative velocity [m/s] (any sign convention).
    tangential_force, v_t, omega : ndarray, shape (n,), or None
        Oblique impacts (all three or none): tangential force on body 1 [N], tangential
        velocity of body 1's centre [m/s], body 1's spin [rad/s] (positive rolling
        forward).
    source : str
        The file (named in every error).
    lines : ndarray of int, shape (n,), or None
        The file's line of each row (messages name it), or None (messages name the row).
    details : dict
        Plain values a report should quote (the units of the file, the columns read).
    """

    t: Any
    overlap: Any
    normal_force: Any
    v_n: Any = None
    tangential_force: Any = None
    v_t: Any = None
    omega: Any = None
    source: str = ""
    lines: Any = None
    details: dict = field(default_factory=dict)

    def __post_init__(self):
        src = self.source
        lines = None if self.lines is None else np.asarray(self.lines, dtype=np.int64)

        def where(k):
            head = f"{src}" if src else ""
            if k is None:
                return f"{head}: " if head else ""
            at = f"line {int(lines[k])}" if lines is not None and k < len(lines) else f"row {k}"
            return f"{head}, {at}: " if head else f"{at}: "

        t = _field(self.t, "t", None, where)
        n = len(t)
        if n < 3:
            raise ResultError(f"{where(None)}an impact needs 3 or more rows (before, in and "
                              f"after the contact), got {n}")
        if lines is not None and len(lines) != n:
            raise ResultError(f"{where(None)}lines has {len(lines)} values, 't' has {n}")
        steps = np.diff(t)
        if not (steps > 0).all():
            k = int(np.argmax(~(steps > 0))) + 1
            raise ResultError(f"{where(k)}field 't' must increase strictly, got "
                              f"{float(t[k])!r} after {float(t[k - 1])!r}")
        set_ = object.__setattr__
        set_(self, "t", t)
        set_(self, "lines", lines)
        for name in ("overlap", "normal_force"):
            set_(self, name, _field(getattr(self, name), name, n, where))
        if self.v_n is not None:
            set_(self, "v_n", _field(self.v_n, "v_n", n, where))
        given = [name for name in OBLIQUE_FIELDS if getattr(self, name) is not None]
        if given and len(given) != len(OBLIQUE_FIELDS):
            missing = [name for name in OBLIQUE_FIELDS if name not in given]
            raise ResultError(f"{where(None)}an oblique impact needs all of "
                              f"{', '.join(OBLIQUE_FIELDS)}; missing {', '.join(missing)}")
        for name in given:
            set_(self, name, _field(getattr(self, name), name, n, where))
        set_(self, "details", dict(self.details))

    @property
    def rows(self) -> int:
        """The number of rows."""
        return len(self.t)

    @property
    def oblique(self) -> bool:
        """True where the tangential fields are given."""
        return self.v_t is not None

    def where(self, k: int) -> str:
        """``"file, line L"`` (or ``"row k"``) of row ``k``, for messages."""
        at = (f"line {int(self.lines[k])}" if self.lines is not None else f"row {k}")
        return f"{self.source}, {at}" if self.source else at
