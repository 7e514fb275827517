"""What a DEM code's tangential force law gives out, in SI: a force-displacement history of
one contact, the input of :func:`fem_validation.grading.tangential_history.grade_history`.

A DEM code has no contact surface: it has, step by step, the relative tangential
displacement of the two bodies, the tangential force it computed and the normal force.
A :class:`TangentialHistory` holds them, checked:

* ``displacement`` (k,) [m]: the relative tangential displacement of the moved body
  (body 1) with respect to the other, projected on the contact plane, along the line
  it first moves; it starts at 0 and rises first.
* ``force`` (k,) [N]: the tangential force along that line that drives the displacement
  (the force body 1 exerts on body 2), projected on the contact plane: on the ramp it has
  the sign of the displacement.  The force ON the moved body (LAMMPS's ``f_x`` of the
  atom that ``fix move`` drives) is the opposite: it is refused, naming the convention.
* ``normal_force`` (k,) [N]: P at each row, >= 0 (constant where the file gives one
  value).
* ``mu`` > 0.

Examples
--------
>>> from fem_validation.results.tangential_history import TangentialHistory
>>> h = TangentialHistory(displacement=[0.0, 1e-8, 2e-8, 1e-8], force=[0.0, 0.1, 0.2, 0.05],
...                       normal_force=[10.0] * 4, mu=0.3)
>>> h.reversals, h.varying
((2,), False)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .contact import ResultError, _array, _number, _where
from .tangential import check_path, path_reversals

__all__ = ["TangentialHistory", "VARYING"]

#: A normal force whose rows differ by more than this (relative to the largest) varies.
VARYING = 1e-9


@dataclass(frozen=True)
class TangentialHistory:
    """One contact's tangential path from a DEM code (or any force law), in SI.

    Attributes
    ----------
    displacement : ndarray, shape (k,)
        Relative tangential displacement [m], from 0, rising first.
    force : ndarray, shape (k,)
        Tangential force driving it [N], the displacement's sign on the ramp.
    normal_force : ndarray, shape (k,)
        Normal force P at each row [N], >= 0.
    mu : float
        Coefficient of friction [-], > 0.
    source : str
        The file (named in every message).
    lines : ndarray of int, shape (k,), optional
        The file's line of each row (messages name it).
    details : dict
        Plain values a report quotes (units, where P came from, ...).
    """

    displacement: np.ndarray
    force: np.ndarray
    normal_force: np.ndarray
    mu: float
    source: str = ""
    lines: np.ndarray | None = None
    details: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self):
        s = self.source
        w = _where(s)
        d, q = check_path(self.displacement, self.force, s, lines=self.lines)
        k = len(d)
        p = self.normal_force
        p = _array(np.full(k, p) if np.ndim(p) == 0 else p, "normal_force", s, (k,)).copy()
        bad = np.flatnonzero(p < 0)
        if bad.size:
            raise ResultError(f"{w}field 'normal_force' must be >= 0 (compressive), got "
                              f"{float(p[bad[0]])!r} at {self.at(int(bad[0]))}")
        if not (p > 0).any():
            raise ResultError(f"{w}field 'normal_force' is 0 throughout: the bodies never "
                              f"touch")
        p.setflags(write=False)
        object.__setattr__(self, "displacement", d)
        object.__setattr__(self, "force", q)
        object.__setattr__(self, "normal_force", p)
        object.__setattr__(self, "mu", _number(self.mu, "mu", s, positive=True))
        object.__setattr__(self, "details", dict(self.details))
        self._check_sign()

    def at(self, i: int) -> str:
        """``"line L"`` (the file's) or ``"index i"`` of row ``i``."""
        return f"line {int(self.lines[i])}" if self.lines is not None else f"index {i}"

    def _check_sign(self) -> None:
        """Refuse a force that opposes the displacement on the ramp (the other convention)."""
        d, q = self.displacement, self.force
        end = self.reversals[0] if self.reversals else len(d) - 1
        ramp = np.arange(1, end + 1)
        ramp = ramp[(d[ramp] > 0) & (q[ramp] != 0)]
        if not ramp.size:
            return
        if np.count_nonzero(q[ramp] < 0) > ramp.size / 2:
            i = int(ramp[np.argmax(np.abs(q[ramp]))])
            raise ResultError(
                f"{_where(self.source)}the force opposes the displacement on the ramp "
                f"({q[i]:.6g} N at displacement {d[i]:.6g} m, {self.at(i)}): the force "
                f"graded is the one that drives the displacement (body 1 on body 2, the "
                f"displacement's sign: Q = k delta at first); this file holds the force ON "
                f"the moved body (as LAMMPS's f_x of the atom fix move drives): negate the "
                f"force column")

    @property
    def reversals(self) -> tuple[int, ...]:
        """Indices where the displacement turns back (:func:`path_reversals`)."""
        return path_reversals(self.displacement)

    @property
    def varying(self) -> bool:
        """Whether the normal force changes along the path."""
        p = self.normal_force
        return bool(p.max() - p.min() > VARYING * p.max())
