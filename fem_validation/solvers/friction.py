"""Coulomb friction on the blocks: a normal load held, then a tangential displacement path.

Cattaneo-Mindlin and Mindlin-Deresiewicz by finite elements.  The normal
problem is solved first (:func:`fem_validation.solvers.solve.solve_contact`); then
body 1's loaded face is moved along a principal axis of the contact (the mesh's
x or y axis) through a path of displacements (ramp, unloading, reloading), and
each step solves the tangential problem with Coulomb's law at every contact
pair.

Why the two problems are solved one after the other.  The bodies are
elastically similar and the blocks mirror images of each other in z = 0, so a
tangential traction changes the gap nowhere (Mindlin's uncoupled problem is
exact for them, up to the mesh's own departure from that mirror symmetry):
the pressure stays what the normal problem gave.  The tangential field of a
load along x is even in x for u_x, odd for u_y and u_z, so the quarter model
holds it with u_y = u_z = 0 on x = 0 and u_y = 0 on y = 0 (for a load along y,
x and y swap roles).  The normal penalty springs stay in the tangential system,
so a gap change is resisted as in the coupled problem; the largest pressure
they carry (``coupling_pressure``) measures what the separation neglects.

Friction at a pair (node i1 of body 1, i2 of body 2, both at the same point of
z = 0): s = u1(i1) - u2(i2), the relative tangential displacement (x and y
components), and the force f that body 1 exerts on body 2 through the pair,

    stick:  f = k_t (s - s_p),            |f| <= mu N
    slip:   f = mu N e,  e = k_t (s - s_p) / |k_t (s - s_p)|,

with N the pair's normal force, k_t = kappa E* A / h0 the penalty stiffness
(the normal one) and s_p the pair's slip so far (return mapping: a step's
trial force is k_t (s - s_p) with s_p from the previous converged step; at
convergence a sliding pair's s_p becomes s - f / k_t).  Each step iterates the
stick set and the slip directions: stick pairs carry springs, sliding pairs
their force mu N e as a load, until neither changes.
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass, field

import numpy as np
from scipy import sparse

from ..errors import FEMValidationError
from ..fe.elasticity import rigid_body_modes, stiffness
from ..halfspace import cerruti_settlement
from ..results.tangential import TangentialResult, path_reversals
from ..scenes import Scene
from .mesh import BlockMesh
from .solve import (
    AMG_MODES,
    KAPPA,
    SETTLED_FRACTION,
    ContactSolution,
    _amg,
    cg_solve,
    solve_contact,
)

log = logging.getLogger("fem_validation")

#: Axes of the mesh a tangential load may follow (the quarter model's symmetry planes).
AXES = ("x", "y")
#: Stick-set iterations per step before giving up.
MAX_STICK_ITERATIONS = 40
#: A step has converged when no pair changes state and no sliding pair's direction turns
#: by more than this [rad].
DIRECTION_TOL = 1e-4
#: The blocks of a frictional run are this many times wider and deeper than the normal
#: validation's (40 a): a tangential load finds a finite block more compliant than a half-
#: space by about twice Cerruti's displacement on the axis at the block's depth, which is
#: all that :func:`settlement_compliance` adds back.  Measured at level 3 (alpha 1, Q = 0.1
#: mu P, force at the displacement against Mindlin): -0.45%, +0.57%, +1.07% for blocks 40 a,
#: 80 a and 160 a deep, halving towards the mesh's own +1.6%; 160 a costs 8% more dofs.
EXTENT_FACTOR = 4.0
#: Relative rounding allowed in |trial| <= mu N.
STICK_ROUNDING = 1e-9
#: Rebuild the AMG preconditioner when more than this fraction of the active pairs changed
#: between stick and slip since its setup.
REBUILD_FRACTION = 0.05


def friction_mesh(scene: Scene, level: int) -> BlockMesh:
    """The mirrored blocks of a frictional run (:func:`fem_validation.solvers.mesh.mirrored`),
    EXTENT_FACTOR times the normal validation's width and depth."""
    from .mesh import build, mesh_parameters, mirrored

    base = mesh_parameters(scene, level)
    return mirrored(build(scene, level, parameters={
        key: EXTENT_FACTOR * base[key] for key in ("L", "H", "hmax")}))


def settlement_compliance(scene: Scene, mesh: BlockMesh) -> float:
    """Tangential displacement per newton that the two clamped blocks miss [m/N]."""
    return sum(cerruti_settlement(1.0, b.E, b.nu, mesh.depth) for b in (scene.body1, scene.body2))


def hertz_direction(scene: Scene, axis: str) -> float:
    """The direction of a load along the mesh's ``axis`` in hertz's ellipse frame [rad]
    (0 along the major axis)."""
    if axis not in AXES:
        raise ValueError(f"axis must be one of {AXES}, got {axis!r}")
    theta = scene.hertz().major_axis_angle
    d = (0.0 if axis == "x" else np.pi / 2) - theta
    return float(np.round(d / (np.pi / 2)) * (np.pi / 2)) % np.pi


@dataclass
class FrictionStep:
    """The state after one converged step of the path (whole-contact forces).

    Attributes
    ----------
    top_displacement : float
        Imposed displacement of body 1's loaded face along the axis [m].
    force : float
        Tangential contact force Q along the axis [N] (the sum of the pair forces).
    top_reaction : float
        The same force from the loaded face's reaction [N]: equal to ``force`` up to
        the CG residual (a solver diagnostic, not a check).
    stick : int
        Pairs that stick (of the quarter model).
    sliding : int
        Pairs that slide.
    iterations : int
        Stick-set iterations of the step.
    cg_iterations : list of int
    """

    top_displacement: float
    force: float
    top_reaction: float
    stick: int
    sliding: int
    iterations: int
    cg_iterations: list[int] = field(default_factory=list)


@dataclass
class FrictionSolution:
    """A frictional run: the normal solution, the path and the snapshot at the first peak.

    Attributes
    ----------
    normal : ContactSolution
        The normal problem's solution.
    mu : float
        Coefficient of friction.
    axis : {"x", "y"}
        The mesh axis the load follows.
    normal_force : ndarray, shape (n_pairs,)
        N of each pair [N] (the quarter model's own).
    steps : list of FrictionStep
        One per path point after the start (which is Q = 0).
    snapshot_shear : ndarray, shape (n_pairs, 2)
        Traction body 1 exerts on body 2 at the end of the first ramp [Pa] (x, y).
    snapshot_stick : ndarray of bool, shape (n_pairs,)
        Stick flags there (inactive pairs False).
    snapshot : int
        Index of that state in the path (0 is the start).
    coupling_pressure : float
        Largest pressure the normal springs carry in the tangential problem [Pa] over
        the path: what solving the two problems separately neglects.
    compliance_correction : float
        Tangential displacement per newton the clamped blocks miss [m/N]
        (:func:`settlement_compliance`).
    dofs : int
    amg_setups : int
    seconds : dict
    """

    normal: ContactSolution
    mu: float
    axis: str
    normal_force: np.ndarray
    steps: list[FrictionStep]
    snapshot_shear: np.ndarray
    snapshot_stick: np.ndarray
    snapshot: int
    coupling_pressure: float
    compliance_correction: float
    dofs: int
    amg_setups: int
    seconds: dict[str, float] = field(default_factory=dict)

    @property
    def force(self) -> np.ndarray:
        """Q along the path [N], starting with 0."""
        return np.array([0.0] + [s.force for s in self.steps])

    @property
    def displacement(self) -> np.ndarray:
        """Relative tangential displacement of remote points along the path [m]: the
        imposed one plus what the clamped blocks miss (:func:`cerruti_settlement`)."""
        top = np.array([0.0] + [s.top_displacement for s in self.steps])
        return top + self.compliance_correction * self.force


class _TangentialSystem:
    """Both blocks' stiffness with the tangential problem's boundary conditions."""

    def __init__(self, scene: Scene, mesh: BlockMesh, axis: str):
        if not mesh.quarter:
            raise FEMValidationError(
                f"{scene.name}: the frictional run needs the quarter model (a scene whose "
                f"principal planes are the mesh's x = 0 and y = 0 planes)")
        m1, m2 = mesh.bodies
        self.n1 = 3 * m1.nvertices
        self.n = self.n1 + 3 * m2.nvertices
        d = AXES.index(axis)
        e = 1 - d
        self.K1 = stiffness(m1.p, m1.t, scene.body1.E, scene.body1.nu)
        self.K = sparse.block_diag([self.K1, stiffness(m2.p, m2.t, scene.body2.E,
                                                        scene.body2.nu)], format="csr")
        self.B = np.vstack([rigid_body_modes(m1.p), rigid_body_modes(m2.p)])[:, :AMG_MODES]
        fixed = [3 * mesh.top[:, None] + np.arange(3),
                 self.n1 + 3 * mesh.bottom[:, None] + np.arange(3)]
        # the plane normal to the load: u_e = u_z = 0 (odd there); the other plane: u_e = 0
        across = mesh.sym_x if d == 0 else mesh.sym_y
        along = mesh.sym_y if d == 0 else mesh.sym_x
        for comp in (e, 2):
            fixed += [3 * across[0] + comp, self.n1 + 3 * across[1] + comp]
        fixed += [3 * along[0] + e, self.n1 + 3 * along[1] + e]
        self.fixed = np.unique(np.concatenate([f.ravel() for f in fixed]))
        self.keep = np.ones(self.n)
        self.keep[self.fixed] = 0.0
        self.top_dofs = 3 * mesh.top + d
        self.d = d
        # dofs of the pairs: (n_pairs, 3) for each body
        self.dof1 = 3 * mesh.pairs[:, :1] + np.arange(3)
        self.dof2 = self.n1 + 3 * mesh.pairs[:, 1:] + np.arange(3)
        self._pattern = None

    def assemble(self, k_normal: np.ndarray, tangential: np.ndarray):
        """K plus the pair springs: k_normal on z [N/m] and the 2x2 matrices
        ``tangential`` (n_pairs, 2, 2) on x and y [N/m], with the fixed dofs eliminated
        (rows and columns cleared, unit diagonal)."""
        if self._pattern is None:
            K = self.K.tocsr(copy=True)
            rows = np.repeat(np.arange(self.n), np.diff(K.indptr))
            K.data *= self.keep[rows] * self.keep[K.indices]
            self._eliminated = (K + sparse.diags(1.0 - self.keep)).tocsr()
            rows, cols = [], []
            for ci in range(3):
                for cj in range(3):
                    i1, i2 = self.dof1[:, ci], self.dof2[:, ci]
                    j1, j2 = self.dof1[:, cj], self.dof2[:, cj]
                    rows += [i1, i2, i1, i2]
                    cols += [j1, j2, j2, j1]
            rows, cols = np.concatenate(rows), np.concatenate(cols)
            self._pattern = (rows, cols, self.keep[rows] * self.keep[cols])
        rows, cols, mask = self._pattern
        block = np.zeros((len(k_normal), 3, 3))
        block[:, :2, :2] = tangential
        block[:, 2, 2] = k_normal
        vals = np.concatenate([v for ci in range(3) for cj in range(3)
                               for v in (block[:, ci, cj], block[:, ci, cj],
                                         -block[:, ci, cj], -block[:, ci, cj])])
        springs = sparse.csr_matrix((vals * mask, (rows, cols)), shape=(self.n, self.n))
        A = (self._eliminated + springs).tocsr()
        A.sort_indices()
        return A

    def rhs(self, top: float, pair_load1: np.ndarray) -> np.ndarray:
        """Right-hand side for a top displacement ``top`` [m] and the pairs' loads on
        body 1's nodes (n_pairs, 3) [N] (body 2 gets the opposite)."""
        values = np.zeros(self.n)
        values[self.top_dofs] = top
        b = -(self.K @ values)
        np.add.at(b, self.dof1.ravel(), pair_load1.ravel())
        np.add.at(b, self.dof2.ravel(), -pair_load1.ravel())
        b *= self.keep
        b[self.fixed] = values[self.fixed]
        return b

    def relative(self, x: np.ndarray) -> np.ndarray:
        """u1 - u2 at the pairs, (n_pairs, 3) [m]."""
        return x[self.dof1] - x[self.dof2]


def _trial(k_pair, rel, slip, limit, active):
    """Trial forces k (s - s_p) (n, 2) [N], the stick flags (|trial| <= mu N on active
    pairs), the directions of the trial forces and their sizes."""
    trial = k_pair[:, None] * (rel[:, :2] - slip)
    size = np.hypot(trial[:, 0], trial[:, 1])
    # a pair left exactly at the limit by the last step starts the next one sticking
    stick = active & (size <= limit * (1 + STICK_ROUNDING))
    direction = np.divide(trial, size[:, None], out=np.zeros_like(trial),
                          where=size[:, None] > 0)
    return trial, stick, direction, size


def path_for(peak: float, ramp_steps: int, cycle: bool = True) -> np.ndarray:
    """A displacement path: 0 -> peak in ``ramp_steps`` equal steps, then (``cycle``)
    peak -> -peak and -peak -> peak in twice as many each."""
    if not ramp_steps >= 1:
        raise ValueError(f"ramp_steps must be >= 1, got {ramp_steps!r}")
    ramp = np.linspace(0.0, peak, ramp_steps + 1)[1:]
    if not cycle:
        return ramp
    down = np.linspace(peak, -peak, 2 * ramp_steps + 1)[1:]
    return np.concatenate([ramp, down, -down])


def peak_displacement(scene: Scene, mesh: BlockMesh, mu: float, ratio: float, axis: str,
                      load: float) -> float:
    """The top displacement at which Cattaneo-Mindlin gives Q = ratio mu P (P = ``load``),
    less what the clamped blocks miss [m]."""
    c = scene.hertz(load)
    t = c.tangential(ratio * mu * load, mu, hertz_direction(scene, axis))
    return float(t.displacement) - settlement_compliance(scene, mesh) * ratio * mu * load


def solve_friction(scene: Scene, mesh: BlockMesh, mu: float, axis: str = "x",
                   path: np.ndarray | None = None, ratio: float = 0.8, ramp_steps: int = 6,
                   normal: ContactSolution | None = None, kappa: float = KAPPA,
                   rebuild_fraction: float = REBUILD_FRACTION) -> FrictionSolution:
    """The normal contact of ``scene``, then a tangential displacement path with friction.

    Parameters
    ----------
    scene : Scene
        Elastically similar bodies (the tangential and normal problems do not couple).
    mesh : BlockMesh
        A quarter model.
    mu : float
        Coefficient of friction (> 0).
    axis : {"x", "y"}
        The mesh axis along which body 1's loaded face moves.
    path : ndarray, optional
        Displacements of the loaded face [m], one per step after the start at 0; the
        first reversal ends the ramp (the snapshot).  Default: :func:`path_for` of the
        displacement that Cattaneo-Mindlin gives for Q = ``ratio`` mu P.
    ratio : float
        Q*/(mu P) of the default path, in (0, 1).
    ramp_steps : int
        Steps of the default path's ramp (the unloading and reloading take twice as many).
    normal : ContactSolution, optional
        The normal solution on ``mesh`` if already computed.
    kappa : float
        Penalty factor of the normal and the tangential springs.
    rebuild_fraction : float
        See :data:`REBUILD_FRACTION`.

    Raises
    ------
    ValueError
        For a bad mu, axis, ratio or path, or dissimilar bodies.
    FEMValidationError
        If a step's stick set does not settle or CG does not converge.
    """
    if not (isinstance(mu, int | float) and mu > 0 and np.isfinite(mu)):
        raise ValueError(f"mu must be a finite number > 0, got {mu!r}")
    if axis not in AXES:
        raise ValueError(f"axis must be one of {AXES}, got {axis!r}")
    b1, b2 = scene.body1, scene.body2
    if not (b1.E == b2.E and b1.nu == b2.nu):
        raise ValueError(f"{scene.name}: the frictional run needs elastically similar bodies "
                         f"(E {b1.E:g} and {b2.E:g} Pa, nu {b1.nu:g} and {b2.nu:g}): "
                         f"otherwise the normal and tangential problems couple")
    t0 = time.perf_counter()
    seconds = {}
    if normal is None:
        normal = solve_contact(scene, mesh, kappa=kappa)
    seconds["normal"] = time.perf_counter() - t0
    if path is None:
        if not 0 < ratio < 1:
            raise ValueError(f"ratio must be in (0, 1), got {ratio!r}")
        path = path_for(peak_displacement(scene, mesh, mu, ratio, axis, normal.force),
                        ramp_steps)
    path = np.asarray(path, dtype=np.float64)
    if path.ndim != 1 or len(path) < 1 or not np.all(np.isfinite(path)):
        raise ValueError(f"path must be a non-empty 1-D array of finite displacements, "
                         f"got {path!r}"[:200])
    reversals = path_reversals(np.concatenate([[0.0], path]))
    snapshot = reversals[0] if reversals else len(path)

    system = _TangentialSystem(scene, mesh, axis)
    seconds["assembly"] = time.perf_counter() - t0 - seconds["normal"]
    active = normal.active
    k_pair = normal.penalty * mesh.pair_area  # the normal springs' stiffness [N/m]
    k_normal = np.where(active, k_pair, 0.0)
    limit = mu * k_normal * np.maximum(-normal.gap, 0.0)  # mu N [N]
    npairs = len(k_pair)
    slip = np.zeros((npairs, 2))  # s_p, the slip so far
    rel = np.zeros((npairs, 3))  # u1 - u2 at the pairs, latest solve
    factor = 4.0
    x = np.zeros(system.n)
    preconditioner, built_on, setups = None, None, 0
    steps, coupling = [], 0.0
    snap_shear = snap_stick = None
    seconds["amg setup"] = seconds["cg"] = 0.0
    eye = np.eye(2)
    for n_step, top in enumerate(path, start=1):
        cg_counts = []
        accurate = False
        trial, stick, direction, size = _trial(k_pair, rel, slip, limit, active)
        for iteration in range(1, MAX_STICK_ITERATIONS + 1):
            t1 = time.perf_counter()
            # Stick: f = k (s - s_p).  Slide: f = mu N e(s), linearised about the latest s
            # (the return mapping's consistent tangent, mu N k / |trial| (I - e e^T)), so
            # that the slip directions converge as Newton's method does.
            sliding = active & ~stick
            ratio_k = np.where(sliding, limit / np.where(sliding, size, 1.0), 0.0) * k_pair
            tangent = (np.where(stick, k_pair, 0.0)[:, None, None] * eye
                       + ratio_k[:, None, None] * (eye - direction[:, :, None]
                                                   * direction[:, None, :]))
            A = system.assemble(k_normal, tangent)
            if preconditioner is None or (np.sum(stick != built_on)
                                          > rebuild_fraction * max(active.sum(), 1)):
                preconditioner, built_on = _amg(A, system.B), stick.copy()
                setups += 1
                seconds["amg setup"] += time.perf_counter() - t1
            load1 = np.zeros((npairs, 3))
            slide_force = (limit[:, None] * direction
                           - np.einsum("nij,nj->ni", tangent, rel[:, :2]))
            load1[:, :2] = np.where(stick[:, None], k_pair[:, None] * slip,
                                    np.where(sliding[:, None], -slide_force, 0.0))
            b = system.rhs(top, load1)
            x[system.fixed] = b[system.fixed]
            x, count, info, residual, rtol = cg_solve(A, b, x, preconditioner, accurate,
                                                      seconds)
            if info != 0 or not residual < 10 * rtol:
                raise FEMValidationError(
                    f"{scene.name}: conjugate gradients did not converge at step {n_step}, "
                    f"stick iteration {iteration} (info {info}, relative residual "
                    f"{residual:.2e})")
            cg_counts.append(count)
            rel = system.relative(x)
            trial, new_stick, new_dir, size = _trial(k_pair, rel, slip, limit, active)
            # a sliding pair whose slip reverses between two iterations sticks for the next
            # one (it would otherwise swing between +e and -e: it has no stiffness along e)
            reverses = sliding & ~new_stick & (np.einsum("ni,ni->n", new_dir, direction) < 0)
            new_stick = new_stick | reverses
            now_sliding = active & ~new_stick
            changed = int(np.sum(new_stick != stick))
            turn = np.max(np.abs(new_dir[now_sliding & sliding]
                                 - direction[now_sliding & sliding]), initial=0.0)
            log.info("%s: step %d (top %.3e m), iteration %d: %d stick, %d sliding, "
                     "%d changed, largest turn %.1e, %d CG iterations (%.1f s)", scene.name,
                     n_step, top, iteration, new_stick.sum(), now_sliding.sum(), changed,
                     turn, count, time.perf_counter() - t1)
            done = changed == 0 and turn <= DIRECTION_TOL
            stick, direction = new_stick, new_dir
            if done and accurate:
                break
            accurate = changed <= SETTLED_FRACTION * max(now_sliding.sum(), 1) and \
                turn <= 100 * DIRECTION_TOL
        else:
            raise FEMValidationError(
                f"{scene.name}: the stick set still changed by {changed} pairs (largest "
                f"turn {turn:.1e} rad) after {MAX_STICK_ITERATIONS} iterations at step "
                f"{n_step}; try more steps or a smaller penalty (kappa = {kappa:g})")
        sliding = active & ~stick
        force_pair = np.where(stick[:, None], trial, limit[:, None] * direction)
        force_pair[~active] = 0.0
        # a sliding pair's slip so far: s - f / k_t
        slip = np.where(sliding[:, None],
                        rel[:, :2] - force_pair / np.where(active, k_pair, 1.0)[:, None], slip)
        coupling = max(coupling, float(np.max(np.abs(k_normal * rel[:, 2]) / mesh.pair_area)))
        force = factor * float(force_pair[:, system.d].sum())
        reaction = system.K1 @ x[: system.n1]
        top_reaction = factor * float(reaction[system.top_dofs].sum())
        steps.append(FrictionStep(float(top), force, top_reaction, int(stick.sum()),
                                  int(sliding.sum()), iteration, cg_counts))
        log.info("%s: step %d: Q = %.6g N (reaction %.6g N), %d stick, %d sliding",
                 scene.name, n_step, force, top_reaction, stick.sum(), sliding.sum())
        if n_step == snapshot:
            snap_shear = force_pair / mesh.pair_area[:, None]
            snap_stick = stick.copy()
    seconds["total"] = time.perf_counter() - t0
    return FrictionSolution(normal, float(mu), axis, k_normal * np.maximum(-normal.gap, 0.0),
                            steps, snap_shear, snap_stick, snapshot, coupling,
                            settlement_compliance(scene, mesh), system.n, setups, seconds)


def friction_result(scene: Scene, mesh: BlockMesh, sol: FrictionSolution):
    """The run as a :class:`~fem_validation.results.tangential.TangentialResult` (what the
    grader sees): body 1's contact nodes, the pressure and the shear at the snapshot,
    the path's displacement (with what the clamped blocks miss) and force."""
    return TangentialResult(
        points=mesh.bodies[0].p[:, mesh.pairs[:, 0]].T,
        pressure=sol.normal_force / mesh.pair_area, shear=sol.snapshot_shear,
        normal_force=sol.normal.force, mu=sol.mu,
        direction=0.0 if sol.axis == "x" else np.pi / 2,
        displacement=sol.displacement, force=sol.force, snapshot=sol.snapshot,
        symmetry="quarter", triangles=mesh.triangles, stick=sol.snapshot_stick,
        source=f"fem_validation blocks {scene.name} with friction, level {mesh.level}",
        details={"compliance_correction_m_per_N": sol.compliance_correction,
                 "correction": "displacement = imposed + Q (3 - 2 nu)/(8 pi G H) per block "
                               "(Cerruti on the axis at the block's depth H)",
                 "coupling_pressure_Pa": sol.coupling_pressure,
                 "by_construction": ["top reaction = Q (CG residual)",
                                     "|q| = mu p at sliding pairs (Coulomb's law)",
                                     "no gap change from the tangential load (mirrored "
                                     "blocks)"]})
