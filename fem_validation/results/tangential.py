"""What any code's frictional contact result is, in SI: the input of the tangential grader.

A :class:`TangentialResult` is a Hertz contact held at a normal force P and
then driven through a path of tangential displacements (a ramp, then
unloading and reloading: a fretting loop) with Coulomb friction.  It is filled
by a source (our own frictional solver, :mod:`fem_validation.solvers.friction`; a
reader of another code's files, :mod:`fem_validation.readers.tangential_csv`)
and handed to :func:`fem_validation.grading.tangential.grade_tangential`, which
compares it with Cattaneo-Mindlin (``hertz.Contact.tangential``) and
Mindlin-Deresiewicz (``hertz.tangential_history``, ``hertz.Contact.fretting``).

How to fill one (a reader-writer's checklist; see also
:mod:`fem_validation.results.contact` for the frame and the symmetry):

1. SI: metres, newtons, pascals.
2. ``points``: undeformed coordinates of the nodes of ONE contact surface,
   (n, 3); ``pressure`` (n,) [Pa] and ``shear`` (n, 2) [Pa] there at ONE state
   of the path, the ``snapshot``.  ``shear`` holds the tangential traction in
   the frame's x and y: the traction that body 1 exerts on body 2, which points
   along the tangential force Q when body 1 is pushed along ``direction``
   (a quarter model's own nodes; the field is even in both in-plane
   coordinates, so mirroring restores the whole contact).
3. ``normal_force`` P [N] of the WHOLE contact (a quarter model's reaction
   times 4), ``mu`` > 0, ``direction`` [rad]: the angle of the tangential
   loading from the frame's x axis (body 1's x axis).  A symmetric (quarter or
   half) model must be loaded along a frame axis (direction 0, pi/2, ...).
4. The path: ``displacement`` (k,) [m], the relative tangential displacement of
   body 1's remote points with respect to body 2's, along ``direction``, with
   any correction for finite bodies already applied (say which in
   ``details``); it starts at 0 and rises first.  ``force`` (k,) [N], the
   tangential force Q along ``direction`` of the WHOLE contact at each point.
5. ``snapshot``: the index into the path where ``pressure`` and ``shear``
   were taken; default the first reversal (the end of the monotonic ramp).
6. Optional: ``triangles`` (m, 3) of the surface; ``stick`` (n,) the code's
   own stick flags (information only); ``source`` (named in every error);
   ``details`` (plain values a report should quote).

Construction validates every field and raises
:class:`~fem_validation.results.contact.ResultError` (a ValueError) naming the source,
the field, the offending value or index and what is allowed.  Arrays are
copied and made read-only.

Examples
--------
>>> import numpy as np
>>> from fem_validation.results.tangential import TangentialResult
>>> xy = np.array([[0.0, 0.0], [1e-4, 0.0], [0.0, 1e-4], [2e-4, 0.0]])
>>> r = TangentialResult(points=np.column_stack([xy, np.zeros(4)]),
...                      pressure=[1e9, 8e8, 8e8, 0.0], shear=np.zeros((4, 2)),
...                      normal_force=10.0, mu=0.3, direction=0.0,
...                      displacement=[0.0, 1e-7, 2e-7, 1e-7, -2e-7, 0.0, 2e-7],
...                      force=[0.0, 1.0, 1.8, 0.5, -1.8, 0.1, 1.8])
>>> r.snapshot, r.reversals, r.multiplicity
(2, (2, 4), 1)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .contact import (
    MULTIPLICITY,
    ContactFrame,
    ResultError,
    _array,
    _check_frame_and_triangles,
    _check_symmetry,
    _number,
    _where,
    surface_points,
)

#: A symmetric model's load must lie along a frame axis to this [rad].
AXIS_TOLERANCE = 1e-9


def path_reversals(displacement) -> tuple[int, ...]:
    """Indices of the points where a displacement path turns back, in order.

    A reversal is the last point reached before the path moves the other way;
    steps of zero length (holds) are skipped.

    >>> path_reversals([0.0, 1.0, 2.0, 2.0, 1.0, -2.0, 0.0, 2.0])
    (3, 5)
    """
    d = np.asarray(displacement, dtype=float)
    steps = np.diff(d)
    moving = np.nonzero(steps != 0)[0]
    sense = np.sign(steps[moving])
    turns = np.nonzero(sense[1:] != sense[:-1])[0]
    return tuple(int(moving[j + 1]) for j in turns)  # the start of the step back


def check_path(displacement, force, source: str = "", lines=None):
    """A tangential path (displacement [m], force [N]) as read-only arrays, checked: two
    or more finite points of equal number, starting at 0 and rising first.

    Parameters
    ----------
    displacement, force : array_like, shape (k,)
    source : str
        The file (or solver) for the messages.
    lines : array_like of int, shape (k,), optional
        The file's line of each point: messages name the line instead of the index.

    Returns
    -------
    (ndarray, ndarray)

    Raises
    ------
    ResultError
        Naming the source, the field and the index (or line).
    """
    w = _where(source)

    def at(i):
        return f"line {int(lines[i])}" if lines is not None else f"index {i}"

    d = _array(displacement, "displacement", source, (None,))
    k = len(d)
    if k < 2:
        raise ResultError(f"{w}field 'displacement' must hold a path of 2 or more points, "
                          f"got {k}")
    q = _array(force, "force", source, (k,))
    scale = float(np.abs(d).max())
    if not scale > 0:
        raise ResultError(f"{w}field 'displacement' never leaves 0: nothing was loaded")
    if abs(d[0]) > 1e-9 * scale:
        raise ResultError(f"{w}field 'displacement' must start at 0 (the unloaded state), "
                          f"got {d[0]!r} at {at(0)}")
    first = int(np.argmax(d != d[0]))
    if d[first] < d[0]:
        raise ResultError(f"{w}field 'displacement' must rise first (the ramp along "
                          f"'direction'), got {d[first]!r} at {at(first)}: reverse the "
                          f"direction (add pi) and the signs of displacement and force")
    return d, q


@dataclass(frozen=True)
class TangentialResult:
    """One frictional contact result (normal load held, tangential path), in SI.

    See the module docstring for how to fill it.

    Attributes
    ----------
    points : ndarray, shape (n, 3)
        Nodes of one contact surface, undeformed [m], model frame.
    pressure : ndarray, shape (n,)
        Contact pressure at the snapshot [Pa], compressive positive.
    shear : ndarray, shape (n, 2)
        Tangential traction at the snapshot in the frame's x, y [Pa], exerted by
        body 1 on body 2.
    normal_force : float
        P of the whole contact [N], > 0.
    mu : float
        Coefficient of friction [-], > 0.
    direction : float
        Direction of the tangential loading from the frame's x axis [rad].
    displacement : ndarray, shape (k,)
        Relative tangential displacement along ``direction`` [m], from 0.
    force : ndarray, shape (k,)
        Tangential force Q along ``direction``, whole contact [N].
    snapshot : int, optional
        Index into the path of the pressure and shear; default the first
        reversal (the last point if the path never turns back).
    symmetry : {"whole", "half", "quarter"}
    frame : ContactFrame
    triangles : ndarray of int, shape (m, 3), optional
    stick : ndarray of bool, shape (n,), optional
        The code's own stick status (information only).
    source : str
    details : dict
    """

    points: np.ndarray
    pressure: np.ndarray
    shear: np.ndarray
    normal_force: float
    mu: float
    direction: float
    displacement: np.ndarray
    force: np.ndarray
    snapshot: int | None = None
    symmetry: str = "whole"
    frame: ContactFrame = field(default_factory=ContactFrame)
    triangles: np.ndarray | None = None
    stick: np.ndarray | None = None
    source: str = ""
    details: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self):
        s = self.source
        w = _where(s)
        pts = surface_points(self.points, s)
        n = len(pts)
        object.__setattr__(self, "points", pts)
        p = _array(self.pressure, "pressure", s, (n,))
        if not (p > 0).any():
            raise ResultError(f"{w}field 'pressure': the contact is empty (no node carries a "
                              f"positive pressure; largest {p.max():.6g})")
        object.__setattr__(self, "pressure", p)
        object.__setattr__(self, "shear", _array(self.shear, "shear", s, (n, 2)))
        object.__setattr__(self, "normal_force",
                           _number(self.normal_force, "normal_force", s, positive=True))
        object.__setattr__(self, "mu", _number(self.mu, "mu", s, positive=True))
        object.__setattr__(self, "direction", _number(self.direction, "direction", s))

        d, q = check_path(self.displacement, self.force, s)
        k = len(d)
        object.__setattr__(self, "displacement", d)
        object.__setattr__(self, "force", q)

        reversals = path_reversals(d)
        if self.snapshot is None:
            snap = reversals[0] if reversals else k - 1
        else:
            if isinstance(self.snapshot, bool) or not isinstance(self.snapshot,
                                                                 int | np.integer):
                raise ResultError(f"{w}field 'snapshot' must be an index into the path (int), "
                                  f"got {self.snapshot!r}")
            snap = int(self.snapshot)
            if not 1 <= snap < k:
                raise ResultError(f"{w}field 'snapshot' must be an index 1..{k - 1} into the "
                                  f"path of {k} points, got {snap}")
        object.__setattr__(self, "snapshot", snap)

        _check_symmetry(self.symmetry, s)
        if self.symmetry != "whole" and abs(math.sin(2 * self.direction)) > AXIS_TOLERANCE:
            raise ResultError(f"{w}field 'direction': a {self.symmetry} model must be loaded "
                              f"along a frame axis (0, pi/2, pi, ... rad: its symmetry planes), "
                              f"got {self.direction!r} rad")
        _check_frame_and_triangles(self, n)
        if self.stick is not None:
            object.__setattr__(self, "stick", _array(self.stick, "stick", s, (n,), dtype=bool))
        object.__setattr__(self, "details", dict(self.details))

    @property
    def multiplicity(self) -> int:
        """Copies of the modelled part in the whole contact (1, 2 or 4)."""
        return MULTIPLICITY[self.symmetry]

    @property
    def xy(self) -> np.ndarray:
        """The points in the contact plane, frame coordinates, (n, 2) [m]."""
        return self.frame.to_frame(self.points)[:, :2]

    @property
    def reversals(self) -> tuple[int, ...]:
        """Indices of the path's reversal points (:func:`path_reversals`)."""
        return path_reversals(self.displacement)

    @property
    def shear_along(self) -> np.ndarray:
        """The shear component along ``direction`` (n,) [Pa]."""
        return self.shear @ np.array([math.cos(self.direction), math.sin(self.direction)])

    @property
    def shear_across(self) -> np.ndarray:
        """The shear component 90 degrees counter-clockwise from ``direction`` (n,) [Pa]."""
        return self.shear @ np.array([-math.sin(self.direction), math.cos(self.direction)])
