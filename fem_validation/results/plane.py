"""2-D contact results, in SI: plane strain (a line contact) and axisymmetric (a point
contact of bodies of revolution), and the scenes they are graded against.

A :class:`PlaneResult` is what a 2-D source fills (a reader of a CalculiX ``.frd`` of
CPE*/CPS*/CAX* elements, of a meshio file with 2-D cells, of a CSV of x, p; our own 2-D
solvers) and :func:`fem_validation.grading.plane.grade_plane` grades.  The checklist:

1. SI: metres, newtons, pascals (a deck in mm, N, MPa: lengths times 1e-3, pressures and
   stresses times 1e6, forces as they are).
2. ``model``: ``"plane-strain"`` (the contact line runs out of the plane; x across it) or
   ``"axisymmetric"`` (x is the radius r >= 0, the axis of revolution through the first
   point of contact).
3. ``x`` [m]: the position of each node of ONE contact line (the slave side) measured from
   the first point of contact along the contact plane (plane strain: either sign;
   axisymmetric: the radius), ``pressure`` [Pa] there (compressive positive).  Nodes out of
   contact (p = 0) are welcome: they show the edge.
4. ``force``: the normal force of the WHOLE contact; plane strain: per unit length of the
   contact line [N/m] (a half model's times 2; a code's force for a thickness t divided by
   t); axisymmetric: of the full circle [N] (a code that reports a sector: times 2 pi over
   the sector's angle; CalculiX's .frd already holds the full circle, see
   :mod:`fem_validation.readers.calculix_plane`).
5. ``half_model`` (plane strain): the model holds x >= 0 only (symmetric about x = 0).
6. Optional: ``active`` the code's contact status per node; ``reaction`` (same unit as
   force), a force measured independently (the other body's support); ``approach`` [m]
   where the model defines one comparable with Hertz (axisymmetric bodies: the approach of
   two points far from the contact, corrected for the finite bodies, said in ``details``);
   ``axis``: the von Mises stress along the axis of symmetry below the first point of
   contact, per body, as :class:`AxisStress`.

Construction validates every field and raises
:class:`~fem_validation.results.contact.ResultError` naming the source, the field and the
value.  Arrays are copied and made read-only.

Examples
--------
>>> import numpy as np
>>> from fem_validation.results.plane import PlaneResult
>>> r = PlaneResult("axisymmetric", x=[0.0, 1e-4, 2e-4], pressure=[1e9, 8.7e8, 0.0],
...                 force=10.0)
>>> r.model, r.symmetric, r.x.flags.writeable
('axisymmetric', True, False)
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

import hertz

from .contact import ResultError

__all__ = ["MODELS", "AxisStress", "PlaneResult", "PlaneScene", "plane_scene_from_toml"]

#: The 2-D models: plane strain (line contact) and axisymmetric (point contact).
MODELS = ("plane-strain", "axisymmetric")
#: The force's unit of each model.
FORCE_UNITS = {"plane-strain": "N/m", "axisymmetric": "N"}
#: The most nodes a contact line may hold (a reader's bound on memory and time).
MAX_NODES = 10_000_000


def _array(value, name: str, where: str, *, dtype=float) -> np.ndarray:
    try:
        a = np.array(value, dtype=dtype)
    except (TypeError, ValueError) as exc:
        raise ResultError(f"{where}{name} must be an array of numbers: {exc}") from None
    if a.ndim != 1:
        raise ResultError(f"{where}{name} must be one-dimensional, got shape {a.shape}")
    if dtype is float:
        bad = np.flatnonzero(~np.isfinite(a))
        if bad.size:
            raise ResultError(f"{where}{name}[{bad[0]}] must be finite, got {float(a[bad[0]])!r}")
    a.flags.writeable = False
    return a


@dataclass(frozen=True)
class AxisStress:
    """The von Mises stress along the axis of symmetry below the first point of contact,
    in one body.

    Attributes
    ----------
    depth : ndarray, shape (n,)
        Depth below the contact surface [m], increasing, >= 0.
    von_mises : ndarray, shape (n,)
        The von Mises stress there [Pa] (of all six components: the out-of-plane stress
        of plane strain, the hoop stress of an axisymmetric model).
    """

    depth: np.ndarray
    von_mises: np.ndarray

    def __post_init__(self):
        depth = _array(self.depth, "axis depth", "")
        vm = _array(self.von_mises, "axis von_mises", "")
        if depth.shape != vm.shape:
            raise ResultError(f"axis depth and von_mises differ in length: {depth.size} and "
                              f"{vm.size}")
        order = np.argsort(depth, kind="stable")
        depth, vm = depth[order], vm[order]
        depth.flags.writeable = vm.flags.writeable = False
        object.__setattr__(self, "depth", depth)
        object.__setattr__(self, "von_mises", vm)


@dataclass(frozen=True)
class PlaneResult:
    """A plane-strain or axisymmetric contact result (SI).

    Attributes
    ----------
    model : {"plane-strain", "axisymmetric"}
    x : ndarray, shape (n,)
        Position of the contact line's nodes from the first point of contact [m]
        (axisymmetric: the radius, >= 0).
    pressure : ndarray, shape (n,)
        Contact pressure there [Pa], >= 0 (a negative value down to -1e-6 of the largest
        is read as 0: a code's rounding).
    force : float
        Normal force of the whole contact: [N/m] per unit length (plane strain), [N] the
        full circle (axisymmetric); > 0.
    source : str
        The file or solver (every message names it).
    half_model : bool
        Plane strain: the model holds x >= 0 only (mirrored about x = 0).
    active : ndarray of bool or None
        The code's contact status per node.
    reaction : float
        An independently measured force, same unit as ``force`` (NaN: none).
    approach : float
        The approach comparable with Hertz's [m] (NaN: none).
    axis : dict
        ``{1: AxisStress, 2: AxisStress}`` for the bodies whose stresses the file holds.
    details : dict
        What a report should quote (units, element types, penalty, conventions applied).
    """

    model: str
    x: np.ndarray
    pressure: np.ndarray
    force: float
    source: str = ""
    half_model: bool = False
    active: np.ndarray | None = None
    reaction: float = math.nan
    approach: float = math.nan
    axis: dict = field(default_factory=dict)
    details: dict = field(default_factory=dict)

    def __post_init__(self):
        where = f"{self.source}: " if self.source else ""
        if self.model not in MODELS:
            raise ResultError(f"{where}model must be one of {', '.join(MODELS)}, got "
                              f"{self.model!r}")
        x = _array(self.x, "x", where)
        p = _array(self.pressure, "pressure", where)
        if x.shape != p.shape:
            raise ResultError(f"{where}x and pressure differ in length: {x.size} and {p.size}")
        if x.size < 3:
            raise ResultError(f"{where}the contact line needs 3 or more nodes, got {x.size}")
        if x.size > MAX_NODES:
            raise ResultError(f"{where}the contact line holds {x.size} nodes, more than "
                              f"{MAX_NODES}")
        top = float(p.max())
        if not top > 0:
            raise ResultError(f"{where}pressure: no node is in contact (the largest pressure "
                              f"is {top!r}; expected a positive compressive pressure)")
        low = np.flatnonzero(p < -1e-6 * top)
        if low.size:
            raise ResultError(f"{where}pressure[{low[0]}] = {float(p[low[0]])!r} is negative "
                              f"beyond rounding (compressive contact pressure is positive)")
        p = np.clip(p, 0.0, None)
        scale = float(np.abs(x).max())
        if self.model == "axisymmetric":
            neg = np.flatnonzero(x < -1e-9 * scale)
            if neg.size:
                raise ResultError(f"{where}x[{neg[0]}] = {float(x[neg[0]])!r}: an axisymmetric "
                                  f"model holds radii x >= 0 (the axis at x = 0)")
            x = np.abs(x)
        elif self.half_model:
            neg = np.flatnonzero(x < -1e-9 * scale)
            if neg.size:
                raise ResultError(f"{where}x[{neg[0]}] = {float(x[neg[0]])!r}: a half model holds "
                                  f"x >= 0 only")
            x = np.abs(x)
        order = np.argsort(x, kind="stable")
        x, p = x[order], p[order]
        x.flags.writeable = p.flags.writeable = False
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "pressure", p)
        if self.active is not None:
            active = np.array(self.active, dtype=bool).reshape(-1)
            if active.shape != order.shape:
                raise ResultError(f"{where}active must hold one flag per node ({order.size}), "
                                  f"got {active.size}")
            active = active[order]
            active.flags.writeable = False
            object.__setattr__(self, "active", active)
        for name in ("force", "reaction", "approach"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | float | np.floating
                                                         | np.integer):
                raise ResultError(f"{where}{name} must be a number, got "
                                  f"{type(value).__name__}")
            object.__setattr__(self, name, float(value))
        unit = FORCE_UNITS[self.model]
        if not (math.isfinite(self.force) and self.force > 0):
            raise ResultError(f"{where}force must be a finite force > 0 [{unit}], got "
                              f"{self.force!r}")
        if not (math.isnan(self.reaction) or (math.isfinite(self.reaction)
                                              and self.reaction > 0)):
            raise ResultError(f"{where}reaction must be NaN (none) or a finite force > 0 "
                              f"[{unit}], got {self.reaction!r}")
        if not (math.isnan(self.approach) or math.isfinite(self.approach)):
            raise ResultError(f"{where}approach must be NaN (none) or finite [m], got "
                              f"{self.approach!r}")
        for body, stress in self.axis.items():
            if body not in (1, 2) or not isinstance(stress, AxisStress):
                raise ResultError(f"{where}axis must map body 1 or 2 to an AxisStress, got "
                                  f"{body!r}: {type(stress).__name__}")
        object.__setattr__(self, "details", dict(self.details))

    @property
    def symmetric(self) -> bool:
        """The result holds one side of the first point of contact only (a half model in
        plane strain; every axisymmetric model)."""
        return self.model == "axisymmetric" or self.half_model

    def pressure_integral(self) -> float:
        """The nodal pressure integrated by the trapezoidal rule, in the unit of
        :attr:`force`: over x (times 2 for a half model) in plane strain, 2 pi r p over r
        in an axisymmetric model."""
        x, p = self.x, self.pressure
        if self.model == "axisymmetric":
            return float(np.trapezoid(2 * math.pi * x * p, x))
        return float(np.trapezoid(p, x)) * (2 if self.half_model else 1)

    @property
    def force_unit(self) -> str:
        """The unit of :attr:`force`: N/m (plane strain) or N (axisymmetric)."""
        return FORCE_UNITS[self.model]


@dataclass(frozen=True)
class PlaneScene:
    """Two bodies of a 2-D model.

    Attributes
    ----------
    name : str
    model : {"plane-strain", "axisymmetric"}
        Plane strain: parallel cylinders (``Rx`` the radius in the model's plane, ``Ry``
        inf) or a cylinder on a plane; axisymmetric: bodies of revolution (``Rx == Ry``:
        spheres, planes, a sphere in a spherical seat).
    body1, body2 : hertz.Body
    load : float
        The scene's target: load per length [N/m] (plane strain) or load [N]; NaN where
        the file gives none (a grade brings its own force).
    """

    name: str
    model: str
    body1: hertz.Body
    body2: hertz.Body
    load: float = math.nan

    def hertz(self, force: float):
        """Hertz's solution at ``force`` ([N/m] plane strain: a LineContact; [N]
        axisymmetric: a Contact)."""
        if self.model == "plane-strain":
            return hertz.line_contact(self.body1, self.body2, force)
        return hertz.contact(self.body1, self.body2, load=force)

    @property
    def radius(self) -> float:
        """The effective radius 1 / (1/R1 + 1/R2) in the model's plane [m]."""
        return 1.0 / (1.0 / self.body1.Rx + 1.0 / self.body2.Rx)

    @property
    def smallest_radius(self) -> float:
        """The smallest |radius| of the two bodies in the model's plane [m] (for a/R)."""
        return min(abs(b.Rx) for b in (self.body1, self.body2) if math.isfinite(b.Rx))


def plane_scene_from_toml(path, model: str | None = None) -> PlaneScene:
    """A :class:`PlaneScene` from a ``hertz`` TOML scene file.

    Parameters
    ----------
    path : path
        The scene: complete ``[body1]``, ``[body2]`` (Rx, Ry, E, nu in SI); a line contact
        gives ``load_per_length`` [N/m] (or no target), an axisymmetric one ``load`` [N]
        (or ``approach`` [m], or none).
    model : {"plane-strain", "axisymmetric"}, optional
        Default: plane strain where the file gives ``load_per_length`` or both bodies are
        cylinders along y (Ry = inf) or planes, axisymmetric where both are bodies of
        revolution (Rx == Ry).

    Raises
    ------
    ValueError
        Naming the file: the format's errors (:func:`hertz._scene.read_scene`), bodies that
        do not fit the model (named with their radii), a target of the other model.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "roller.toml"
    >>> _ = f.write_text('load_per_length = 1e5\\n[body1]\\nRx = 5e-3\\nRy = "inf"\\n'
    ...                  'E = 210e9\\nnu = 0.3\\n[body2]\\nRx = "inf"\\nRy = "inf"\\n'
    ...                  'E = 210e9\\nnu = 0.3\\n')
    >>> s = plane_scene_from_toml(f)
    >>> s.model, round(s.hertz(s.load).half_width * 1e6, 2)
    ('plane-strain', 74.28)
    """
    from hertz._scene import read_scene

    path = Path(path)
    where = f"scene file {str(path)!r}"
    data = read_scene(path, complete=True)
    if model is not None and model not in MODELS:
        raise ValueError(f"model must be one of {', '.join(MODELS)}, got {model!r}")
    bodies = []
    for name in ("body1", "body2"):
        try:
            bodies.append(hertz.Body(**data[name]))
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{where}: [{name}]: {exc}") from None
    line = all(math.isinf(b.Ry) for b in bodies)
    revolution = all(b.Rx == b.Ry for b in bodies)
    if model is None:
        model = "plane-strain" if "load_per_length" in data or (line and not revolution) \
            else "axisymmetric" if revolution else None
        if model is None:
            raise ValueError(f"{where}: the bodies make neither a line contact (both Ry = "
                             f"inf) nor an axisymmetric one (Rx == Ry for both): "
                             f"{_radii(bodies)}")
    if model == "plane-strain" and not line:
        raise ValueError(f"{where}: a plane-strain model needs parallel cylinders along y "
                         f"(Ry = inf for both bodies; Rx the radius in the plane), got "
                         f"{_radii(bodies)}")
    if model == "axisymmetric" and not revolution:
        raise ValueError(f"{where}: an axisymmetric model needs bodies of revolution (Rx == "
                         f"Ry for both), got {_radii(bodies)}")
    if model == "axisymmetric" and "load_per_length" in data:
        raise ValueError(f"{where}: load_per_length is the target of a line contact; an "
                         f"axisymmetric scene takes load [N] or approach [m]")
    if model == "plane-strain" and ("load" in data or "approach" in data):
        raise ValueError(f"{where}: a plane-strain scene takes load_per_length [N/m], not "
                         f"{'load' if 'load' in data else 'approach'}")
    load = data.get("load_per_length", data.get("load", math.nan))
    try:
        if "approach" in data:
            load = hertz.contact(*bodies, approach=data["approach"]).load
        scene = PlaneScene(str(data.get("name", path.stem)), model, *bodies, float(load))
        with warnings.catch_warnings():  # a grade notes Hertz's range at its own force
            warnings.simplefilter("ignore", hertz.HertzValidityWarning)
            scene.hertz(1.0 if math.isnan(load) else load)  # do these bodies touch?
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{where}: {exc}") from None
    return scene


def _radii(bodies) -> str:
    return "; ".join(f"body{i} Rx = {b.Rx:g}, Ry = {b.Ry:g}" for i, b in enumerate(bodies, 1))
