"""Small-strain elasticity of both blocks with frictionless penalty contact.

Each body is discretised with linear tetrahedra (fem_validation.fe.elasticity).  A
contact pair (node i1 of body 1, node i2 of body 2, at the same point of z = 0)
has the gap

    g = g0(x, y) + u1z(i1) - u2z(i2),   g0 = (x, y) S (x, y)^T / 2,

with S the relative curvature tensor of the scene: Hertz's quadratic gap
between two half-spaces.  An active pair (g < 0) carries the penalty force
k (-g), k = kappa E* A / h0 (A its lumped area, h0 the element size in the
contact zone), so that the pressure is kappa E* (-g) / h0.  The active set is
iterated until it no longer changes.  Body 1's top face is moved down by the
imposed approach, body 2's bottom face is fixed, and the symmetry planes of a
quarter model carry zero normal displacement.

Linear systems are solved by conjugate gradients preconditioned with pyamg's
smoothed aggregation (3x3 blocks, the translations as near-nullspace).
The preconditioner is built on the first active set and rebuilt when more than
REBUILD_FRACTION of the pairs active when it was built have changed state:
the penalty springs are far stiffer than the elements, so a preconditioner
built for another contact area leaves CG with slowly converging modes there.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
import pyamg
from scipy import sparse
from scipy.sparse.linalg import cg

from ..errors import FEMValidationError
from ..fe.elasticity import rigid_body_modes, stiffness
from ..halfspace import boussinesq_settlement
from ..scenes import Scene
from .mesh import BlockMesh

log = logging.getLogger("fem_validation")

#: Penalty factor; measured: kappa = 100 gives a penetration of about 4e-4 of the approach
#: and changes a, b, p0 by < 0.05% against kappa = 1000, with half the CG iterations.
KAPPA = 100.0
CG_RTOL = 1e-9
CG_MAXITER = 3000
MAX_ACTIVE_SET_ITERATIONS = 40
#: Rebuild the AMG preconditioner when more than this fraction of the pairs active at its
#: setup have changed state since.
REBUILD_FRACTION = 0.05
#: pyamg's prolongation smoothing, coarsest size and near-nullspace (the first AMG_MODES
#: rigid-body modes: the translations).  Measured on alpha-3, level 4 (211k dofs, one
#: accurate solve): setup 2.6 s and 32 CG iterations of 0.30 s with the 3 translations,
#: against 5.9 s and 25 of 0.37 s with all 6 modes and 9.3 s and 34 of 0.30 s with pyamg's
#: defaults; a cheap setup matters when the active set changes and it is rebuilt.  The
#: coarsest level is solved by sparse LU (pyamg's default pseudo-inverse costs 0.9 s there).
AMG_SMOOTH = "energy"
AMG_MAX_COARSE = 500
AMG_MODES = 3
#: While the active set still changes by more than SETTLED_FRACTION of its pairs, each
#: solve only reduces its residual LOOSE_REDUCTION times (CG's work per decade of residual
#: is about the same, so loose solves followed by an accurate one cost about what one
#: accurate solve does).
LOOSE_REDUCTION = 1e-3
SETTLED_FRACTION = 0.05
#: First active sets: Hertz's ellipse at the target load, the rigid interpenetration of
#: the undeformed bodies (g0 < approach), no pair, every pair.
INITIAL_ACTIVE = ("hertz", "interpenetration", "none", "all")


@dataclass
class ContactSolution:
    """Displacements, contact state and solver statistics of one run.

    Forces are for the whole contact (the quarter model's are multiplied by 4).

    Attributes
    ----------
    u1, u2 : ndarray, shape (n1, 3), (n2, 3)
        Displacements of body 1 and body 2 [m].
    gap : ndarray, shape (n_pairs,)
        Final gap [m] (negative: penetration of an active pair).
    pressure : ndarray, shape (n_pairs,)
        Contact pressure [Pa], kappa E* (-gap) / h0 on active pairs, else 0.
    active : ndarray of bool, shape (n_pairs,)
    force : float
        Total contact force [N].
    top_reaction : float
        Force on body 1's loaded face [N]: equal to ``force`` up to the CG
        residual (a solver diagnostic, not a check of the model).
    approach : float
        Imposed approach of the far faces [m].
    penalty : float
        kappa E* / h0 [Pa/m].
    dofs : int
    active_set_iterations : int
    cg_iterations : list of int
        Per active-set iteration.
    amg_setups : int
        Number of times the preconditioner was built.
    seconds : dict
        Wall time of the stages [s].
    """

    u1: np.ndarray
    u2: np.ndarray
    gap: np.ndarray
    pressure: np.ndarray
    active: np.ndarray
    force: float
    top_reaction: float
    approach: float
    penalty: float
    dofs: int
    active_set_iterations: int
    cg_iterations: list[int] = field(default_factory=list)
    amg_setups: int = 0
    seconds: dict[str, float] = field(default_factory=dict)


def gap0(scene: Scene, xy: np.ndarray) -> np.ndarray:
    """Initial gap (x, y) S (x, y)^T / 2 at points xy (n, 2) [m]."""
    s = scene.curvature_tensor
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * (s[0, 0] * x * x + 2 * s[0, 1] * x * y + s[1, 1] * y * y)


def imposed_approach(scene: Scene, mesh: BlockMesh) -> float:
    """Approach of the far faces that should give the scene's load [m]: Hertz's delta
    less the Boussinesq settlement the clamped blocks do not show."""
    c = scene.hertz()
    return c.delta - sum(boussinesq_settlement(scene.load, b.E, b.nu, mesh.depth)
                         for b in (scene.body1, scene.body2))


def initial_active_set(scene: Scene, xy: np.ndarray, approach: float,
                       how: str = "hertz") -> np.ndarray:
    """The first active set of the iteration.

    Parameters
    ----------
    scene : Scene
    xy : ndarray, shape (n, 2)
        Positions of the contact pairs [m].
    approach : float
        Imposed approach [m].
    how : {"hertz", "interpenetration", "none", "all"}
        Hertz's ellipse at the target load; the pairs where the undeformed
        bodies would overlap (g0 < approach); no pair; every pair.
    """
    if how == "hertz":
        c = scene.hertz()
        t = c.major_axis_angle
        major = xy[:, 0] * np.cos(t) + xy[:, 1] * np.sin(t)
        minor = -xy[:, 0] * np.sin(t) + xy[:, 1] * np.cos(t)
        return (major / c.a) ** 2 + (minor / c.b) ** 2 < 1.0
    if how == "interpenetration":
        return gap0(scene, xy) < approach
    if how == "none":
        return np.zeros(len(xy), dtype=bool)
    if how == "all":
        return np.ones(len(xy), dtype=bool)
    raise ValueError(f"initial_active must be one of {INITIAL_ACTIVE}, got {how!r}")


class _System:
    """The assembled two-body system; contact springs are added per active set.

    Dirichlet dofs are eliminated symmetrically (rows and columns cleared, unit
    diagonal); the contact dofs are never Dirichlet dofs.
    """

    def __init__(self, scene: Scene, mesh: BlockMesh, approach: float):
        self.mesh = mesh
        m1, m2 = mesh.bodies
        self.n1 = 3 * m1.nvertices
        self.n = self.n1 + 3 * m2.nvertices
        self.K1 = stiffness(m1.p, m1.t, scene.body1.E, scene.body1.nu)
        K = sparse.block_diag([self.K1, stiffness(m2.p, m2.t, scene.body2.E, scene.body2.nu)],
                              format="csr")
        self.B = np.vstack([rigid_body_modes(m1.p), rigid_body_modes(m2.p)])[:, :AMG_MODES]
        fixed = [3 * mesh.top[:, None] + np.arange(3),
                 self.n1 + 3 * mesh.bottom[:, None] + np.arange(3)]
        values = np.zeros(self.n)
        values[3 * mesh.top + 2] = -approach
        for plane, comp in ((mesh.sym_x, 0), (mesh.sym_y, 1)):
            if plane is not None:
                fixed += [3 * plane[0] + comp, self.n1 + 3 * plane[1] + comp]
        self.fixed = np.unique(np.concatenate([f.ravel() for f in fixed]))
        self.values = values
        keep = np.ones(self.n)
        keep[self.fixed] = 0.0
        self.keep = keep
        self.dz1 = 3 * mesh.pairs[:, 0] + 2
        self.dz2 = self.n1 + 3 * mesh.pairs[:, 1] + 2
        if np.any(keep[self.dz1] == 0) or np.any(keep[self.dz2] == 0):
            raise FEMValidationError("a contact dof is also a Dirichlet dof")
        self.load = -keep * (K @ values)
        rows = np.repeat(np.arange(self.n), np.diff(K.indptr))
        K.data *= keep[rows] * keep[K.indices]  # clear the Dirichlet rows and columns
        self.K = (K + sparse.diags(1.0 - keep)).tocsr()
        self.K.sort_indices()

    def matrix_and_rhs(self, k: np.ndarray, g0: np.ndarray):
        """System with penalty springs k (zero for inactive pairs) [N/m]."""
        rows = np.concatenate([self.dz1, self.dz2, self.dz1, self.dz2])
        cols = np.concatenate([self.dz1, self.dz2, self.dz2, self.dz1])
        vals = np.concatenate([k, k, -k, -k])
        A = self.K + sparse.csr_matrix((vals, (rows, cols)), shape=(self.n, self.n))
        b = self.load.copy()
        b[self.dz1] -= k * g0
        b[self.dz2] += k * g0
        b[self.fixed] = self.values[self.fixed]
        return A, b


def transferred_active_set(coarse: BlockMesh, coarse_sol: ContactSolution,
                           fine: BlockMesh) -> np.ndarray:
    """Active set of ``fine``'s pairs from a solution on a coarser mesh of the same scene.

    A fine pair is active where the coarse gap, interpolated linearly on the
    coarse contact face, is negative (nested iteration: a start that needs
    neither Hertz's ellipse nor many iterations on the fine mesh).
    """
    import matplotlib.tri as mtri

    cxy = coarse.bodies[0].p[:2, coarse.pairs[:, 0]].T
    fxy = fine.bodies[0].p[:2, fine.pairs[:, 0]].T
    tri = mtri.Triangulation(cxy[:, 0], cxy[:, 1], coarse.triangles)
    gap = mtri.LinearTriInterpolator(tri, coarse_sol.gap)(fxy[:, 0], fxy[:, 1])
    return np.asarray(np.ma.filled(gap, 1.0) < 0)


def _amg(A, B):
    ml = pyamg.smoothed_aggregation_solver(A.tobsr(blocksize=(3, 3)), B=B,
                                           symmetry="symmetric", smooth=AMG_SMOOTH,
                                           improve_candidates=None, max_coarse=AMG_MAX_COARSE,
                                           coarse_solver="splu")
    return ml.aspreconditioner(cycle="V")


def cg_solve(A, b: np.ndarray, x: np.ndarray, preconditioner, accurate: bool,
             seconds: dict) -> tuple[np.ndarray, int, int, float, float]:
    """One preconditioned CG solve of A x = b from ``x``.

    Accurate: to |r| <= CG_RTOL |b|; loose: until the residual has fallen
    1/LOOSE_REDUCTION times.  Adds its wall time to ``seconds["cg"]``.

    Returns
    -------
    x, iterations, info, residual, rtol
        The solution, CG's iterations and status, the relative residual reached and
        the relative tolerance asked (the caller refuses residual >= 10 rtol).
    """
    count = [0]

    def step(_xk):
        count[0] += 1

    t0 = time.perf_counter()
    bnorm = np.linalg.norm(b)
    atol = 0.0 if accurate else LOOSE_REDUCTION * np.linalg.norm(b - A @ x)
    x, info = cg(A, b, x0=x, rtol=CG_RTOL, atol=atol, maxiter=CG_MAXITER, M=preconditioner,
                 callback=step)
    seconds["cg"] += time.perf_counter() - t0
    residual = np.linalg.norm(b - A @ x) / bnorm
    return x, count[0], info, residual, max(CG_RTOL, atol / bnorm)


@dataclass
class ActiveSetResult:
    """What :func:`iterate_active_set` leaves: the solution, the final gap and active set,
    and the solver's counts (iterations, CG iterations per solve, AMG setups)."""

    x: np.ndarray
    gap: np.ndarray
    active: np.ndarray
    iterations: int
    cg_iterations: list[int]
    amg_setups: int


def iterate_active_set(name: str, system_for: Callable, gap_of: Callable, active: np.ndarray,
                       x: np.ndarray, B: np.ndarray, rebuild_fraction: float, accurate: bool,
                       seconds: dict, what: str = "pairs", hint: str = "") -> ActiveSetResult:
    """The penalty contact's active-set iteration, shared by the blocks and the curved bodies.

    Each iteration assembles the system for the current active set, solves it by
    AMG-preconditioned conjugate gradients from the previous solution, and takes the
    contacts with a negative gap as the next active set, until it no longer changes.  While
    the set changes by more than SETTLED_FRACTION, a solve only reduces its residual
    1/LOOSE_REDUCTION times; the AMG preconditioner is rebuilt when more than
    ``rebuild_fraction`` of the contacts changed state since its setup.

    Parameters
    ----------
    name : str
        The scene, for messages.
    system_for : callable
        active (bool array) -> (A, b), the sparse matrix [N/m] and right-hand side [N].
    gap_of : callable
        x -> the gap of every contact [m] (negative: penetration).
    active : ndarray of bool
        The first active set.
    x : ndarray
        The first guess [m], with the prescribed values at the fixed dofs.
    B : ndarray
        Near-nullspace modes for the AMG setup.
    rebuild_fraction : float
        See above (``inf``: build once).
    accurate : bool
        Whether the first solve is already to CG_RTOL (a first set that is likely final).
    seconds : dict
        Accumulates "amg setup" and "cg" [s].
    what, hint : str
        The contacts' name ("pairs", "nodes") and a hint for the cycling error.

    Raises
    ------
    FEMValidationError
        If CG does not converge, the active set cycles or it still changes after
        MAX_ACTIVE_SET_ITERATIONS.
    """
    cg_iterations, seen = [], []
    preconditioner, built_on, setups = None, None, 0
    seconds["amg setup"] = seconds["cg"] = 0.0
    for iteration in range(1, MAX_ACTIVE_SET_ITERATIONS + 1):
        t1 = time.perf_counter()
        A, b = system_for(active)
        if preconditioner is None or (np.sum(active != built_on)
                                      > rebuild_fraction * max(built_on.sum(), 1)):
            preconditioner, built_on = _amg(A, B), active.copy()
            setups += 1
            seconds["amg setup"] += time.perf_counter() - t1
        x, count, info, residual, rtol = cg_solve(A, b, x, preconditioner, accurate, seconds)
        if info != 0 or not residual < 10 * rtol:
            raise FEMValidationError(
                f"{name}: conjugate gradients did not converge at active-set iteration "
                f"{iteration} (info {info}, {count} iterations, relative residual "
                f"{residual:.2e}, {len(x)} dofs, {active.sum()} active {what})")
        cg_iterations.append(count)
        gap = gap_of(x)
        new_active = gap < 0
        changed = int(np.sum(new_active != active))
        log.info("%s: active-set iteration %d: %d active %s, %d changed, %d CG iterations "
                 "to %.0e (%.1f s)", name, iteration, new_active.sum(), what, changed,
                 count, rtol, time.perf_counter() - t1)
        if changed == 0 and accurate:
            return ActiveSetResult(x, gap, active, iteration, cg_iterations, setups)
        if accurate and any(np.array_equal(new_active, s) for s in seen):
            raise FEMValidationError(
                f"{name}: the active set cycles at iteration {iteration} "
                f"({new_active.sum()} active {what}, {changed} changing){hint}")
        if accurate:
            seen.append(active)
        accurate = changed <= SETTLED_FRACTION * max(new_active.sum(), 1)
        active = new_active
    raise FEMValidationError(
        f"{name}: the active set still changed by {changed} {what} after "
        f"{MAX_ACTIVE_SET_ITERATIONS} iterations ({new_active.sum()} active)")


def solve_contact(scene: Scene, mesh: BlockMesh, approach: float | None = None,
                  kappa: float = KAPPA, initial_active: str | np.ndarray = "hertz",
                  rebuild_fraction: float = REBUILD_FRACTION) -> ContactSolution:
    """Solve the contact problem of ``scene`` on ``mesh`` at an imposed approach.

    Parameters
    ----------
    scene : Scene
    mesh : BlockMesh
    approach : float, optional
        Approach of the far faces [m]; default :func:`imposed_approach`.
    kappa : float
        Penalty factor (stiffness kappa E*/h0 per unit area).
    initial_active : {"hertz", "interpenetration", "none", "all"} or array of bool
        First active set (see :func:`initial_active_set`), or one flag per pair.
    rebuild_fraction : float
        Rebuild the preconditioner when more than this fraction of the pairs
        active at its setup (at least one pair) have changed state; ``inf``
        builds it once.

    Raises
    ------
    ValueError
        For a bad kappa, initial_active or rebuild_fraction.
    FEMValidationError
        If the active set cycles or does not settle in
        MAX_ACTIVE_SET_ITERATIONS, or conjugate gradients do not converge.
    """
    if not kappa > 0:
        raise ValueError(f"kappa must be > 0, got {kappa!r}")
    if not rebuild_fraction > 0:
        raise ValueError(f"rebuild_fraction must be > 0, got {rebuild_fraction!r}")
    seconds = {}
    t0 = time.perf_counter()
    if approach is None:
        approach = imposed_approach(scene, mesh)
    xy = mesh.bodies[0].p[:2, mesh.pairs[:, 0]].T
    if isinstance(initial_active, str):
        active = initial_active_set(scene, xy, approach, initial_active)
    else:
        active = np.asarray(initial_active, dtype=bool)
        if active.shape != (len(xy),):
            raise ValueError(f"initial_active must have one flag per contact pair "
                             f"({len(xy)}), got shape {active.shape}")
    system = _System(scene, mesh, approach)
    seconds["assembly"] = time.perf_counter() - t0
    penalty = kappa * scene.e_star / mesh.h0
    k_all = penalty * mesh.pair_area
    g0 = gap0(scene, xy)
    x = np.zeros(system.n)
    x[system.fixed] = system.values[system.fixed]
    # Loose solves until the active set changes little; the first solve is accurate
    # only from Hertz's ellipse, which is usually the final set already.
    run = iterate_active_set(
        scene.name, lambda act: system.matrix_and_rhs(np.where(act, k_all, 0.0), g0),
        lambda u: g0 + u[system.dz1] - u[system.dz2], active, x, system.B, rebuild_fraction,
        isinstance(initial_active, str) and initial_active == "hertz", seconds,
        hint=f"; try a finer mesh or a smaller penalty (kappa = {kappa:g})")
    x, gap, active = run.x, run.gap, run.active
    u1 = x[: system.n1].reshape(-1, 3)
    u2 = x[system.n1 :].reshape(-1, 3)
    symmetry_factor = 4.0 if mesh.quarter else 1.0
    force = symmetry_factor * float(np.sum(k_all[active] * -gap[active]))
    reaction = system.K1 @ x[: system.n1]
    top_reaction = -symmetry_factor * float(reaction[3 * mesh.top + 2].sum())
    seconds["solve"] = time.perf_counter() - t0
    return ContactSolution(u1, u2, gap, np.where(active, penalty * -gap, 0.0), active, force,
                           top_reaction, approach, penalty, system.n, run.iterations,
                           run.cg_iterations, run.amg_setups, seconds)
