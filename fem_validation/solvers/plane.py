"""Our own 2-D Hertz models: plane strain (a line contact) and axisymmetric (a point
contact of bodies of revolution), solved with scikit-fem, as second FE evidence beside
the 3-D blocks.

The model
---------
An elastic half-space, cut to a square of side ``depth`` (x, or the radius r, in
[0, depth], y in [-depth, 0]; the bottom fixed, x = 0 a plane of symmetry or the axis),
pressed at its surface by a rigid parabolic indenter of radius R with a given force:
the gap is x**2 / (2 R) (Hertz's own geometry, so the comparison is with Hertz's
solution itself, not with the departure of real cylinders or spheres from it), and
Hertz's E* is the half-space's E / (1 - nu**2).  Plane strain: the force per unit length
P' [N/m], Hertz b = sqrt(4 P' R / (pi E*)), p0 = 2 P' / (pi b); axisymmetric: the force
P [N], a = (3 P R / (4 E*))**(1/3), p0 = 3 P / (2 pi a**2).

Quadratic triangles (P2) on a tensor mesh: uniform cells of side ``h`` over the contact
and a margin (x and depth below 2.5 times the Hertz size), then cells growing
geometrically to ``depth``.  Contact: the active set on the surface nodes (a node in
contact has u_y = g(x) - d; a node with a tensile reaction leaves the set, a node that
penetrates enters), the indenter's approach d solved with the set so that the reactions
sum to the force (the solution is linear in d for a given set: two right-hand sides of
one factorisation).  The stiffness is assembled once.

What is measured
----------------
The reactions of the contact nodes are the consistent nodal forces of the pressure,
f_i = integral of p phi_i (times r in the axisymmetric model, per radian), and P2 shape
functions reproduce x**2 exactly, so the second moment of the nodal forces is that of
the pressure: the half-width from sum f x^2 / sum f = b^2 / 4 (plane strain), the radius
from sum f r^2 / sum f = 2 a^2 / 5 (axisymmetric: the moments of p0 sqrt(1 - r^2/a^2)
r dr).  The pressure at the first point of contact, p0, is recovered from the nodal
forces by the consistent mass matrix of the contact line (its own P2 trace).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = ["PlaneSolution", "hertz_reference", "refinement_study", "solve_plane"]

#: The models this module solves.
MODELS = ("plane-strain", "axisymmetric")


@dataclass(frozen=True)
class PlaneSolution:
    """One 2-D solve against Hertz.

    Attributes
    ----------
    model : {"plane-strain", "axisymmetric"}
    h : float
        Side of the uniform cells over the contact [m].
    force : float
        The force reached: per unit length [N/m] (plane strain) or of the full circle [N].
    size : float
        The half-width b (plane strain) or contact radius a (axisymmetric) from the second
        moment of the nodal forces [m].
    p0 : float
        The pressure at the first point of contact, recovered from the nodal forces [Pa].
    size_hertz, p0_hertz : float
        Hertz's values at ``force`` [m], [Pa].
    approach : float
        The indenter's displacement d [m] (of the finite domain: no Hertz value).
    dofs : int
        Unknowns of the model.
    x, pressure : ndarray
        The contact line's nodes [m] and the recovered pressure there [Pa].
    """

    model: str
    h: float
    force: float
    size: float
    p0: float
    size_hertz: float
    p0_hertz: float
    approach: float
    dofs: int
    x: np.ndarray
    pressure: np.ndarray

    def to_result(self):
        """The solution as a :class:`~fem_validation.results.plane.PlaneResult` (the
        contact line x >= 0: a half model in plane strain), for the graders."""
        from ..results.plane import PlaneResult

        return PlaneResult(self.model, self.x, np.clip(self.pressure, 0.0, None), self.force,
                           source=f"fem_validation.solvers.plane (h = {self.h:.3g} m)",
                           half_model=self.model == "plane-strain",
                           details={"solver": "scikit-fem P2, active set"})

    @property
    def size_rel_err(self) -> float:
        """(size - Hertz) / Hertz."""
        return self.size / self.size_hertz - 1.0

    @property
    def p0_rel_err(self) -> float:
        """(p0 - Hertz) / Hertz."""
        return self.p0 / self.p0_hertz - 1.0


def hertz_reference(model: str, R: float, E: float, nu: float, force: float):
    """Hertz's half-width or contact radius [m] and p0 [Pa] for a rigid parabolic indenter
    of radius R [m] on an elastic half-space (E [Pa], nu), ``force`` per unit length
    [N/m] (plane strain) or total [N] (axisymmetric), from hertz.line_contact /
    hertz.contact with a rigid flat body."""
    import warnings

    import hertz

    _check_model(model)
    indenter = hertz.Body(R, math.inf, 1e300, 0.0) if model == "plane-strain" else \
        hertz.Body.sphere(R, 1e300, 0.0)
    half_space = hertz.Body.plane(E, nu)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hertz.HertzValidityWarning)
        if model == "plane-strain":
            c = hertz.line_contact(indenter, half_space, force)
            return c.half_width, c.p0
        c = hertz.contact(indenter, half_space, load=force)
        return c.a, c.p0


def _check_model(model):
    if model not in MODELS:
        raise ValueError(f"model must be one of {', '.join(MODELS)}, got {model!r}")


def _graded(h: float, fine: float, depth: float, growth: float) -> np.ndarray:
    """0, h, ..., >= fine uniformly, then cells growing by ``growth`` up to depth."""
    n = max(1, math.ceil(fine / h))
    x = list(np.arange(n + 1) * h)
    step = h
    while x[-1] < depth:
        step *= growth
        x.append(min(depth, x[-1] + step))
    if depth - x[-2] < 0.5 * (x[-2] - x[-3]):  # no sliver at the far end
        x.pop(-2)
    return np.array(x)


def solve_plane(model: str, R: float, E: float, nu: float, force: float, *,
                h: float | None = None, depth_factor: float = 400.0,
                growth: float = 1.15, max_iterations: int = 100) -> PlaneSolution:
    """Solve the 2-D Hertz model (see the module docstring).

    Parameters
    ----------
    model : {"plane-strain", "axisymmetric"}
    R : float
        Radius of the rigid parabolic indenter [m], > 0.
    E, nu : float
        The half-space's Young's modulus [Pa] and Poisson's ratio (in [0, 0.5)).
    force : float
        Per unit length [N/m] (plane strain) or total [N] (axisymmetric), > 0.
    h : float, optional
        Side of the uniform cells over the contact [m] (default: Hertz's size / 16).
    depth_factor : float
        The domain's side over Hertz's size (default 400: the finite domain's effect on
        the pressure is then below 1e-4).
    growth : float
        Ratio of neighbouring cells outside the uniform zone.
    max_iterations : int
        Active-set iterations before giving up.

    Returns
    -------
    PlaneSolution

    Raises
    ------
    ValueError
        For a model not in MODELS, a non-positive R, E, force or h, nu outside [0, 0.5),
        or an active set that does not settle.

    Examples
    --------
    >>> from fem_validation.solvers.plane import solve_plane
    >>> s = solve_plane("axisymmetric", R=0.01, E=210e9, nu=0.3, force=100.0)
    >>> abs(s.size_rel_err) < 2e-3 and abs(s.p0_rel_err) < 2e-3
    True
    """
    from scipy.sparse.linalg import splu
    from skfem import Basis, BilinearForm, ElementTriP2, ElementVector, MeshTri, asm

    _check_model(model)
    for name, value in (("R", R), ("E", E), ("force", force)):
        if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    if not 0 <= nu < 0.5:
        raise ValueError(f"nu must be in [0, 0.5), got {nu!r}")
    size_h, p0_h = hertz_reference(model, R, E, nu, force)
    h = size_h / 16 if h is None else h
    if not (math.isfinite(h) and 0 < h < size_h):
        raise ValueError(f"h must be in (0, {size_h:.4g}) m (the Hertz size), got {h!r}")
    depth = depth_factor * size_h
    xs = _graded(h, 2.5 * size_h, depth, growth)
    mesh = MeshTri.init_tensor(xs, -xs[::-1])
    basis = Basis(mesh, ElementVector(ElementTriP2()))
    mu_, lam = E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))

    if model == "plane-strain":
        @BilinearForm
        def stiffness(u, v, w):
            eu = (u.grad[0, 0], u.grad[1, 1], u.grad[0, 1] + u.grad[1, 0])
            ev = (v.grad[0, 0], v.grad[1, 1], v.grad[0, 1] + v.grad[1, 0])
            return (lam * (eu[0] + eu[1]) * (ev[0] + ev[1])
                    + 2 * mu_ * (eu[0] * ev[0] + eu[1] * ev[1]) + mu_ * eu[2] * ev[2])
    else:
        @BilinearForm
        def stiffness(u, v, w):
            r = w.x[0]
            eu = (u.grad[0, 0], u.grad[1, 1], u[0] / r, u.grad[0, 1] + u.grad[1, 0])
            ev = (v.grad[0, 0], v.grad[1, 1], v[0] / r, v.grad[0, 1] + v.grad[1, 0])
            tu, tv = eu[0] + eu[1] + eu[2], ev[0] + ev[1] + ev[2]
            return (lam * tu * tv + 2 * mu_ * (eu[0] * ev[0] + eu[1] * ev[1] + eu[2] * ev[2])
                    + mu_ * eu[3] * ev[3]) * r

    K = asm(stiffness, basis).tocsr()
    dofs = basis.get_dofs
    fixed = np.union1d(dofs(lambda x: np.isclose(x[1], -depth)).all(),
                       dofs(lambda x: np.isclose(x[0], 0.0)).all("u^1"))
    top = dofs(lambda x: np.isclose(x[1], 0.0))
    uy = top.all("u^2")
    xy = basis.doflocs[:, uy]
    order = np.argsort(xy[0])
    uy, x_top = uy[order], xy[0, order]
    gap = x_top ** 2 / (2 * R)
    # the force of the nodal reactions: per unit length (plane strain, a half model:
    # times 2) or per radian (axisymmetric: times 2 pi)
    scale = 2.0 if model == "plane-strain" else 2 * math.pi
    active = x_top < size_h
    n = K.shape[0]
    for _ in range(max_iterations):
        c = uy[active]
        known = np.union1d(fixed, c)
        free = np.setdiff1d(np.arange(n), known)
        lu = splu(K[free][:, free].tocsc())
        # u = u0 + d u1 on the set: u_y = gap (u0), u_y = -1 (u1)
        u0, u1 = np.zeros(n), np.zeros(n)
        u0[c], u1[c] = gap[active], -1.0
        u0[free] = lu.solve(-(K[free][:, c] @ u0[c]))
        u1[free] = lu.solve(-(K[free][:, c] @ u1[c]))
        r0, r1 = K[c] @ u0, K[c] @ u1  # the constraint's forces on the body
        # the indenter pushes down (y < 0): its force on the body sums to -force
        d = (-force / scale - r0.sum()) / r1.sum()
        u = u0 + d * u1
        reaction = r0 + d * r1
        tensile = reaction > 0
        penetrating = (~active) & (u[uy] > gap - d + 1e-12 * abs(d))
        if not tensile.any() and not penetrating.any():
            break
        keep = active.copy()
        keep[np.flatnonzero(active)[tensile]] = False
        active = keep | penetrating
    else:
        raise ValueError(f"the active set did not settle in {max_iterations} iterations")
    f = np.zeros(uy.size)
    f[active] = -reaction
    pressure = _recover_pressure(x_top, f, model)
    moment = (f * x_top ** 2).sum() / f.sum()
    size = 2 * math.sqrt(moment) if model == "plane-strain" else math.sqrt(2.5 * moment)
    return PlaneSolution(model, h, force, size, float(pressure[0]), size_h, p0_h, d, n,
                         x_top, pressure)


def _recover_pressure(x: np.ndarray, f: np.ndarray, model: str) -> np.ndarray:
    """The nodal pressures whose consistent forces on the contact line's P2 trace are f:
    the line's mass matrix (weighted by r in the axisymmetric model) solved."""
    from scipy.sparse import lil_matrix
    from scipy.sparse.linalg import spsolve

    # the P2 trace: cells of three nodes (x[0], x[1], x[2]), (x[2], x[3], x[4]), ...
    n = x.size
    gauss, weights = np.polynomial.legendre.leggauss(5)
    mass = lil_matrix((n, n))
    for i in range(0, n - 2, 2):
        xa, xm, xb = x[i], x[i + 1], x[i + 2]
        s = 0.5 * (gauss + 1)
        phi = np.array([2 * (s - 0.5) * (s - 1), -4 * s * (s - 1), 2 * s * (s - 0.5)])
        xq = xa + s * (xb - xa)
        w = 0.5 * weights * (xb - xa) * (xq if model == "axisymmetric" else 1.0)
        local = (phi * w) @ phi.T
        idx = [i, i + 1, i + 2]
        for a in range(3):
            for b in range(3):
                mass[idx[a], idx[b]] += local[a, b]
        del xm
    return spsolve(mass.tocsr(), f)


def refinement_study(model: str, R: float, E: float, nu: float, force: float,
                     divisions=(4, 8, 16, 32)) -> tuple[list[PlaneSolution], dict]:
    """Solve with cells of Hertz's size / n for each n in ``divisions``; the observed
    orders of the size and p0 errors (slopes of log |err| against log h).

    Returns
    -------
    solutions : list of PlaneSolution
    rates : dict
        ``{"size": order, "p0": order}``.
    """
    size_h, _ = hertz_reference(model, R, E, nu, force)
    runs = [solve_plane(model, R, E, nu, force, h=size_h / n) for n in divisions]
    h = np.log([s.h for s in runs])
    rates = {name: float(np.polyfit(h, np.log([abs(getattr(s, f"{name}_rel_err"))
                                               for s in runs]), 1)[0])
             for name in ("size", "p0")}
    return runs, rates
