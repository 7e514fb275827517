"""What any finite-element code's contact result is, in SI: the input of the one grader.

A :class:`ContactResult` is filled by a source (our own block and curved-body
solvers, a reader of a CalculiX ``.frd``, of a meshio file, of a CSV, a DEM
force-overlap curve is graded separately) and handed to
:func:`fem_validation.grading.contact.grade`, which compares it with Hertz.  Nothing in
it refers to a solver: it holds numbers, in SI units, in the model's own
coordinates, and says how to read them.

How to fill one (a reader-writer's checklist):

1. Convert to SI first: metres, newtons, pascals (a deck in mm, N, MPa: lengths
   times 1e-3, forces as they are, pressures and stresses times 1e6).
2. ``points``: the undeformed coordinates of the nodes of ONE contact surface
   (the slave surface, where a code reports contact pressure), shape (n, 3).
   Only nodes of that surface, not of the whole mesh.  Nodes outside the
   pressed region are welcome (pressure 0): they give the edge of contact.
3. ``pressure`` [Pa] at those nodes (compressive contact pressure is positive;
   CalculiX CPRESS, Abaqus CPRESS), and/or ``normal_force`` [N], the nodal
   normal contact force of the MODELLED part (a quarter model's own forces,
   not multiplied by 4).  At least one of them.
4. ``force`` [N]: the total normal force of the WHOLE contact (a quarter
   model's reaction times 4, a half model's times 2), positive.
5. ``symmetry``: "whole", "half" or "quarter"; the symmetry planes contain the
   contact normal and pass through the frame's origin; a quarter model holds
   x >= 0, y >= 0 of the frame, a half model x >= 0 or y >= 0.
6. ``frame`` (:class:`ContactFrame`): the first point of contact (origin), the
   unit normal pointing INTO BODY 1 (the scene's first body), and body 1's x
   axis (the direction of its radius Rx) in the contact plane.  The default is
   the origin, +z, +x.  :func:`fem_validation.grading.contact.find_frame` finds one from
   the data where a file does not say.
7. Optional: ``triangles`` (m, 3), the surface's triangles as indices into
   ``points`` (used for pressure profiles, nodal areas and the edge of
   contact; without them the grader triangulates the points in the contact
   plane); ``active`` (n,) the code's contact status per node; ``approach``
   [m], the approach of the bodies comparable with Hertz's delta (any
   correction for finite bodies already applied, and said in ``details``);
   ``reaction`` [N, whole model], a force measured independently of the
   contact forces (a support reaction); ``stress``, one :class:`BodyStress`
   per body with its nodes' coordinates and the nodal stress tensor.
8. ``source``: the file (or solver) the result came from; every error message
   names it.  ``details``: anything a report should quote (solver, mesh size,
   penalty); plain Python values.

Construction validates every field and raises :class:`ResultError` (a
ValueError) naming the source, the field, the offending value or index, and
what is allowed.  Arrays are copied and made read-only.

Examples
--------
>>> import numpy as np
>>> from fem_validation.results.contact import ContactResult
>>> xy = np.array([[0.0, 0.0], [1e-4, 0.0], [0.0, 1e-4], [2e-4, 0.0]])
>>> r = ContactResult(points=np.column_stack([xy, np.zeros(4)]),
...                   pressure=np.array([1e9, 8e8, 8e8, 0.0]), force=10.0)
>>> r.symmetry, r.multiplicity, r.points.flags.writeable
('whole', 1, False)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

#: Symmetries of a model and how many copies of it make the whole contact.
MULTIPLICITY = {"whole": 1, "half": 2, "quarter": 4}


class ResultError(ValueError):
    """A contact result (or the file it came from) that cannot be graded.

    The message names the source (file), the field, the offending value and
    what is allowed.
    """


def _where(source: str) -> str:
    return f"{source}: " if source else ""


def _array(value, name: str, source: str, shape: tuple, dtype=np.float64,
           finite: bool = True) -> np.ndarray:
    """A read-only copy of ``value`` with the given shape (None: any length)."""
    try:
        a = np.array(value, dtype=dtype, copy=True)
    except (TypeError, ValueError) as exc:
        raise ResultError(f"{_where(source)}field {name!r} must be an array of "
                          f"{np.dtype(dtype).name}, got {type(value).__name__} ({exc})") from None
    if a.ndim != len(shape) or any(s is not None and s != n for s, n in zip(shape, a.shape,
                                                                            strict=False)):
        want = "(" + ", ".join("n" if s is None else str(s) for s in shape) + ")"
        raise ResultError(f"{_where(source)}field {name!r} must have shape {want}, "
                          f"got {a.shape}")
    if finite and a.dtype.kind == "f":
        bad = ~np.isfinite(a)
        if bad.any():
            index = tuple(int(i) for i in np.argwhere(bad)[0])
            raise ResultError(f"{_where(source)}field {name!r} has {int(bad.sum())} non-finite "
                              f"value(s), first {a[index]!r} at index "
                              f"{index[0] if len(index) == 1 else index}; all must be finite")
    a.flags.writeable = False
    return a


#: The bounds of a contact surface's coordinates [m]: within 1000 km of the model's origin,
#: spanning at least a picometre, and spanning at least this fraction of their distance
#: from the origin (else double precision cannot tell its nodes apart).
MAX_COORDINATE = 1e6
MIN_EXTENT = 1e-12
MIN_RELATIVE_EXTENT = 1e-8
#: The farthest a frame's origin may lie from a node of the contact surface, in spans of
#: the surface: it is the first point of contact, and frame coordinates of nodes much
#: farther away than they are apart lose the digits that tell them apart.
FRAME_REACH = 1e4
#: Nodes whose second principal spread is below this fraction of the first lie on a line.
LINE_TOLERANCE = 1e-9


def _on_a_line(xy: np.ndarray) -> bool:
    """True where points (n, d) lie on one straight line (or one point), to LINE_TOLERANCE."""
    centred = xy - xy.mean(axis=0)
    size = np.abs(centred).max()
    if not size > 0:
        return True
    spread = np.linalg.svd(centred / size, compute_uv=False)
    return not spread[1] > LINE_TOLERANCE * spread[0]


def surface_points(points, source: str) -> np.ndarray:
    """The (n, 3) contact-surface nodes of a result, validated and read-only.

    Raises
    ------
    ResultError
        Fewer than 3 nodes, a non-finite coordinate, coordinates beyond
        :data:`MAX_COORDINATE` m, a surface spanning less than :data:`MIN_EXTENT` m or
        less than :data:`MIN_RELATIVE_EXTENT` of its distance from the origin (a unit
        mistake, or a scale at which no triangulation can be made), nodes on one line.
    """
    w = _where(source)
    pts = _array(points, "points", source, (None, 3))
    if len(pts) < 3:
        raise ResultError(f"{w}field 'points' must hold 3 or more contact-surface "
                          f"nodes, got {len(pts)}")
    scale = float(np.abs(pts).max())
    extent = float(np.ptp(pts, axis=0).max())
    if not scale <= MAX_COORDINATE:
        raise ResultError(f"{w}field 'points': a coordinate is {scale:.6g} m; a contact "
                          f"surface lies within {MAX_COORDINATE:g} m of its model's origin: "
                          f"are the units right?")
    if not extent >= MIN_EXTENT:
        raise ResultError(f"{w}field 'points': the contact surface spans {extent:.6g} m; it "
                          f"must span at least {MIN_EXTENT:g} m: are the units right?")
    if not extent >= MIN_RELATIVE_EXTENT * scale:
        raise ResultError(f"{w}field 'points': the contact surface spans {extent:.6g} m at "
                          f"{scale:.6g} m from the model's origin: too far for double precision "
                          f"to resolve its nodes; move the origin nearer to the contact")
    if _on_a_line(pts):
        raise ResultError(f"{w}field 'points': the {len(pts)} nodes lie on one line: a "
                          f"contact surface spans an area")
    return pts


def unit_vector(value, name: str, source: str = "") -> np.ndarray:
    """``value`` (3 finite numbers, not all 0) scaled to length 1.

    Scaled by its largest component first, so that a direction of huge (1e308) or
    subnormal (5e-324) components is the direction it gives, not 0 or NaN (its norm
    overflows or underflows).

    Raises
    ------
    ResultError
        Naming ``source`` and the field ``name``: not 3 finite numbers, or all 0.
    """
    v = np.array(_array(value, name, source, (3,)))
    largest = np.abs(v).max()
    if not largest > 0:
        raise ResultError(f"{_where(source)}field {name!r} must be a nonzero vector, got "
                          f"{v.tolist()}")
    if not 1e-150 < largest < 1e150:  # its squares would overflow or underflow
        v /= largest
    return v / np.linalg.norm(v)


def _check_symmetry(symmetry, source: str) -> None:
    if symmetry not in MULTIPLICITY:
        raise ResultError(f"{_where(source)}field 'symmetry' must be one of "
                          f"{', '.join(MULTIPLICITY)}, got {symmetry!r}")


def _check_frame_and_triangles(result, n: int) -> None:
    """Validate a result's ``frame`` and ``triangles`` (indices into its n points); the
    triangles are stored as a read-only int64 array."""
    w = _where(result.source)
    if not isinstance(result.frame, ContactFrame):
        raise ResultError(f"{w}field 'frame' must be a ContactFrame, "
                          f"got {type(result.frame).__name__}")
    pts, origin = result.points, result.frame.origin
    extent = float(np.ptp(pts, axis=0).max())
    distance = float(np.abs(pts - origin).max())
    if not distance <= FRAME_REACH * extent:
        raise ResultError(f"{w}field 'frame.origin' {origin.tolist()} lies {distance:.6g} m "
                          f"from nodes of the contact surface, which spans {extent:.6g} m; "
                          f"the origin is the first point of contact, within {FRAME_REACH:g} "
                          f"times the surface's span of its nodes (are its units right?)")
    if _on_a_line(result.frame.to_frame(result.points)[:, :2]):
        raise ResultError(f"{w}field 'frame': seen along its normal {result.frame.normal}, "
                          f"the {n} nodes lie on one line: the normal lies in the surface")
    if result.triangles is not None:
        tri = _array(result.triangles, "triangles", result.source, (None, 3), dtype=np.int64)
        if tri.size and (tri.min() < 0 or tri.max() >= n):
            raise ResultError(f"{w}field 'triangles' must index the {n} points, got "
                              f"values {tri.min()}..{tri.max()}")
        object.__setattr__(result, "triangles", tri)


def _number(value, name: str, source: str, positive: bool = False) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ResultError(f"{_where(source)}field {name!r} must be a number, "
                          f"got {value!r}") from None
    if not math.isfinite(x) or (positive and not x > 0):
        raise ResultError(f"{_where(source)}field {name!r} must be "
                          f"{'a finite number > 0' if positive else 'finite'}, got {x!r}")
    return x


@dataclass(frozen=True)
class ContactFrame:
    """The contact point, the contact normal and body 1's x axis, in model coordinates.

    Attributes
    ----------
    origin : ndarray, shape (3,)
        The first point of contact (the centre of the Hertz ellipse) [m].
    normal : ndarray, shape (3,)
        Unit normal of the contact plane pointing into body 1 [-]; depths below
        the surface of body 1 are measured along it, of body 2 against it.
    x_axis : ndarray, shape (3,)
        Unit vector in the contact plane along body 1's x axis (its radius Rx)
        [-]: the scene's angle and Hertz's major-axis angle are measured from it.
        Orthogonal to ``normal`` (to 1e-6; it is made exactly so).

    Examples
    --------
    >>> f = ContactFrame(origin=[0, 0, 1.0], normal=[0, 0, 2.0], x_axis=[0, 1.0, 0])
    >>> f.to_frame([[1.0, 2.0, 4.0]])
    array([[ 2., -1.,  3.]])
    """

    origin: np.ndarray = field(default_factory=lambda: np.zeros(3))
    normal: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, 1.0]))
    x_axis: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0]))
    source: str = ""

    def __post_init__(self):
        s = self.source
        origin = _array(self.origin, "frame.origin", s, (3,))
        far = float(np.abs(origin).max())
        if not far <= MAX_COORDINATE:
            raise ResultError(f"{_where(s)}field 'frame.origin': a coordinate is {far:.6g} m; "
                              f"the first point of contact lies within {MAX_COORDINATE:g} m "
                              f"of its model's origin: are the units right?")
        normal = unit_vector(self.normal, "frame.normal", s)
        x_axis = unit_vector(self.x_axis, "frame.x_axis", s)
        if abs(normal @ x_axis) > 1e-6:
            raise ResultError(f"{_where(s)}field 'frame.x_axis' must lie in the contact plane "
                              f"(orthogonal to the normal {normal}), got {x_axis} "
                              f"(cosine {normal @ x_axis:.3g})")
        x_axis -= (normal @ x_axis) * normal
        x_axis /= np.linalg.norm(x_axis)
        for name, v in (("origin", origin), ("normal", normal), ("x_axis", x_axis)):
            v = np.array(v)
            v.flags.writeable = False
            object.__setattr__(self, name, v)

    @property
    def y_axis(self) -> np.ndarray:
        """normal x x_axis: the in-plane axis that makes (x, y, normal) right-handed."""
        return np.cross(self.normal, self.x_axis)

    @property
    def rotation(self) -> np.ndarray:
        """Rows x_axis, y_axis, normal: model coordinates -> frame coordinates (3, 3)."""
        return np.array([self.x_axis, self.y_axis, self.normal])

    @property
    def is_standard(self) -> bool:
        """The origin at 0, normal +z, x axis +x (frame coordinates are model coordinates)."""
        return (not self.origin.any() and np.array_equal(self.rotation, np.eye(3)))

    def to_frame(self, points) -> np.ndarray:
        """Points (n, 3) [m] in frame coordinates: x, y in the plane, height along the normal."""
        p = np.asarray(points, dtype=float)
        if self.is_standard:
            return np.array(p, dtype=float)
        return (p - self.origin) @ self.rotation.T


@dataclass(frozen=True)
class BodyStress:
    """The nodal stress field of one body.

    Attributes
    ----------
    body : int
        1 or 2, as in the scene (body 1 lies on the side the frame's normal
        points to).
    points : ndarray, shape (k, 3)
        Node coordinates (undeformed) [m], model frame.
    stress : ndarray, shape (k, 3, 3)
        Cauchy stress at the nodes [Pa], tension positive, model frame (for a
        code that writes Voigt components, see :func:`stress_from_voigt`).
    tetrahedra : ndarray of int, shape (e, 4), optional
        Linear tetrahedra (corner nodes) as indices into ``points``: the field is
        interpolated in them (stress-field RMS).  Quadratic elements: give their
        corners.
    axis : ndarray of int, optional
        Nodes on the contact axis (through the frame's origin along the normal),
        ordered by depth; found from the coordinates where not given.
    """

    body: int
    points: np.ndarray
    stress: np.ndarray
    tetrahedra: np.ndarray | None = None
    axis: np.ndarray | None = None
    source: str = ""

    def __post_init__(self):
        s = self.source
        if self.body not in (1, 2):
            raise ResultError(f"{_where(s)}field 'stress.body' must be 1 or 2, got {self.body!r}")
        pts = _array(self.points, f"stress[body {self.body}].points", s, (None, 3))
        sig = _array(self.stress, f"stress[body {self.body}].stress", s, (len(pts), 3, 3))
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "stress", sig)
        for name in ("tetrahedra", "axis"):
            value = getattr(self, name)
            if value is None:
                continue
            idx = _array(value, f"stress[body {self.body}].{name}", s,
                         (None, 4) if name == "tetrahedra" else (None,), dtype=np.int64)
            if idx.size and (idx.min() < 0 or idx.max() >= len(pts)):
                raise ResultError(f"{_where(s)}field 'stress[body {self.body}].{name}' must "
                                  f"index the {len(pts)} points, got values "
                                  f"{idx.min()}..{idx.max()}")
            object.__setattr__(self, name, idx)


def stress_from_voigt(voigt, order: str = "xx yy zz xy yz xz") -> np.ndarray:
    """(k, 6) Voigt components in the given order -> (k, 3, 3) symmetric tensors.

    ``order`` names the six columns (CalculiX and Abaqus: "xx yy zz xy yz xz",
    the default; VTK/ParaView's 6-component tensors: "xx yy zz xy yz xz" too).

    >>> stress_from_voigt([[1, 2, 3, 4, 5, 6]])[0]
    array([[1., 4., 6.],
           [4., 2., 5.],
           [6., 5., 3.]])
    """
    v = np.asarray(voigt, dtype=float)
    names = order.split()
    if v.ndim != 2 or v.shape[1] != 6 or sorted(names) != sorted("xx yy zz xy yz xz".split()):
        raise ValueError(f"voigt must be (k, 6) with order a permutation of xx yy zz xy yz xz, "
                         f"got shape {v.shape} and order {order!r}")
    index = {"x": 0, "y": 1, "z": 2}
    out = np.zeros((len(v), 3, 3))
    for col, name in enumerate(names):
        i, j = index[name[0]], index[name[1]]
        out[:, i, j] = out[:, j, i] = v[:, col]
    return out


@dataclass(frozen=True)
class ContactResult:
    """One contact result of any finite-element (or other) code, in SI.

    See the module docstring for how to fill it.

    Attributes
    ----------
    points : ndarray, shape (n, 3)
        Nodes of one contact surface, undeformed [m], model frame.
    force : float
        Total normal contact force of the whole contact [N], > 0.
    pressure : ndarray, shape (n,), optional
        Nodal contact pressure [Pa], compressive positive.
    normal_force : ndarray, shape (n,), optional
        Nodal normal contact force of the modelled part [N].
    symmetry : {"whole", "half", "quarter"}
    frame : ContactFrame
    triangles : ndarray of int, shape (m, 3), optional
    active : ndarray of bool, shape (n,), optional
    approach : float, optional
        Approach comparable with Hertz's delta [m].
    reaction : float, optional
        An independently measured total force [N], whole model.
    stress : tuple of BodyStress
    source : str
    details : dict
    """

    points: np.ndarray
    force: float
    pressure: np.ndarray | None = None
    normal_force: np.ndarray | None = None
    symmetry: str = "whole"
    frame: ContactFrame = field(default_factory=ContactFrame)
    triangles: np.ndarray | None = None
    active: np.ndarray | None = None
    approach: float | None = None
    reaction: float | None = None
    stress: tuple = ()
    source: str = ""
    details: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self):
        s = self.source
        w = _where(s)
        pts = surface_points(self.points, s)
        n = len(pts)
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "force", _number(self.force, "force", s, positive=True))
        if self.pressure is None and self.normal_force is None:
            raise ResultError(f"{w}no contact pressure and no nodal contact force: a result "
                              f"needs field 'pressure' [Pa] or 'normal_force' [N]")
        for name in ("pressure", "normal_force"):
            value = getattr(self, name)
            if value is None:
                continue
            a = _array(value, name, s, (n,))
            if not (a > 0).any():
                raise ResultError(f"{w}field {name!r}: the contact is empty (no node carries "
                                  f"a positive value; largest {a.max():.6g})")
            object.__setattr__(self, name, a)
        _check_symmetry(self.symmetry, s)
        _check_frame_and_triangles(self, n)
        if self.active is not None:
            object.__setattr__(self, "active", _array(self.active, "active", s, (n,),
                                                      dtype=bool))
        for name in ("approach", "reaction"):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, _number(value, name, s,
                                                       positive=name == "reaction"))
        stress = tuple(self.stress)
        for st in stress:
            if not isinstance(st, BodyStress):
                raise ResultError(f"{w}field 'stress' must hold BodyStress objects, "
                                  f"got {type(st).__name__}")
        bodies = [st.body for st in stress]
        if len(set(bodies)) != len(bodies):
            raise ResultError(f"{w}field 'stress' has body {bodies} more than once")
        object.__setattr__(self, "stress", stress)
        object.__setattr__(self, "details", dict(self.details))

    @property
    def multiplicity(self) -> int:
        """Copies of the modelled part in the whole contact (1, 2 or 4)."""
        return MULTIPLICITY[self.symmetry]

    @property
    def xy(self) -> np.ndarray:
        """The points in the contact plane, frame coordinates, (n, 2) [m]."""
        return self.frame.to_frame(self.points)[:, :2]

    def stress_of(self, body: int) -> BodyStress | None:
        """The stress field of body 1 or 2, or None."""
        return next((st for st in self.stress if st.body == body), None)
