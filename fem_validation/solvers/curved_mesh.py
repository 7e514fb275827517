"""Curved bodies for the validation: a ball on a flat block or in a grooved block (gmsh OCC).

The ball (radius R, body 1) touches the block (body 2) at the origin; z points
up, from the block into the ball.  Quarter models (x >= 0, y >= 0; x = 0 and
y = 0 are planes of symmetry of both scenes):

* **ball**: the lower hemisphere of the sphere centred at (0, 0, R), cut at its
  equator z = R, which is moved down rigidly by the imposed approach.  The
  truncation is harmless for a, b and p0: a far field changes the contact only
  through the curvature of its displacement across the contact area, about
  P / (E R**3) against the geometric curvature 1/R, a relative effect of order
  (a/R)**3.  It does change the approach (the hemisphere is not a half-space):
  see :mod:`fem_validation.solvers.curved`.
* **flat block**: [0, 2R] x [0, 2R] x [-2R, 0], bottom clamped.
* **grooved block**: [0, 2R] x [0, 2R] x [-2R, R_g/2] less the cylinder of
  radius R_g whose axis is the line y = 0, z = R_g (along x), bottom clamped.

The geometry is built in units of R with gmsh's OpenCASCADE kernel (sphere,
box and cylinder, boolean intersection and cut) and each body is meshed on
its own, so the two contact surfaces do not match.  Element size (a gmsh
size callback): h0 in a zone around the expected contact (ZONE times the
Hertz semi-axes at the target load in x and y, down to ZONE_DEPTH b below
each body's curved surface, b the minor semi-axis), growing linearly with the
distance from that zone by ``grade`` per unit length up to HMAX_OVER_R R.  So
the refinement is local and scales with the Hertz contact: the number of
elements hardly depends on a/R.  gmsh runs on one thread with a fixed seed
(deterministic meshes).  Node coordinates are returned in metres.
"""

from __future__ import annotations

import logging
import math
import time
from dataclasses import dataclass, field

import numpy as np
from skfem import MeshTet

import hertz

from ..errors import FEMValidationError
from ..fe.contact_search import outward_normals, surface_lumped_area
from ..scenes import STEEL
from .mesh import LEVEL_RATIO, positively_oriented

log = logging.getLogger("fem_validation")

#: Levels of the curved scenes, and the default.
CURVED_LEVELS = (0, 1, 2, 3, 4)
DEFAULT_CURVED_LEVEL = 3
#: Element size in the contact zone at the default level, in units of the Hertz minor
#: semi-axis b; each level divides every size by LEVEL_RATIO (sqrt 2).
H0_OVER_B = 0.06
#: The groove's contact is about 8 times longer than wide (alpha = 26): elements of the
#: sphere's h0/b would need about 4 times its dofs, so the groove's h0 (and every other
#: size) is this factor larger, the sphere's next-coarser level.
GROOVE_COARSENING = LEVEL_RATIO
#: Growth of the element size per unit distance from the zone, at the default level.
GRADE = 0.12
#: Largest element size at the default level, in units of R.
HMAX_OVER_R = 0.2
#: The refined box covers ZONE times the Hertz semi-axes and ZONE_DEPTH b in depth.
ZONE = 1.3
ZONE_DEPTH = 1.0
#: Contact search region (slave nodes and master triangles), in units of the zone.
SEARCH = 2.0
#: Block half-width and depth, and groove block's top, in units of R (of R_g).
BLOCK_OVER_R = 2.0
GROOVE_TOP_OVER_RG = 0.5
#: Nodes closer than this (units of R) to a plane lie on it.
PLANE_TOL = 1e-9
#: The range of a/R (Hertz's semi-major axis over the ball's radius) the curved meshes are
#: built for.  Above MAX_A_OVER_R the contact leaves the hemisphere's quarter.  Below
#: MIN_A_OVER_R the elements at the contact approach gmsh's geometric tolerance in units
#: of R: measured at level 0, a/R = 1e-8 meshed in 1.3 s, 1e-10 not in 40 s (23 GB when
#: left to run); the ball in a groove at a/R = 1e-5 (b/R = 1.2e-6) meshed at level 4 in
#: 65 s, 170k vertices.  The number of vertices grows only with log(R/b) (the sizes grow
#: linearly away from the contact), so within the range every level stays below 0.2
#: million vertices per body.
MIN_A_OVER_R = 1e-5
MAX_A_OVER_R = 0.5


def level_scale(level: int) -> float:
    """Size factor of ``level`` relative to the default level."""
    if level not in CURVED_LEVELS:
        raise ValueError(f"level must be one of {list(CURVED_LEVELS)}, got {level!r}")
    return LEVEL_RATIO ** (DEFAULT_CURVED_LEVEL - level)


@dataclass(frozen=True)
class CurvedScene:
    """A steel ball pressed onto a flat block or into a grooved block.

    Attributes
    ----------
    name : str
        "sphere-plane" or "ball-groove".
    radius : float
        Ball radius R [m].
    groove_radius : float or None
        Groove radius R_g [m] (groove axis along x); None for a flat block.
    a_over_r : float
        Target Hertz semi-major axis over R; sets the load; in
        [MIN_A_OVER_R, MAX_A_OVER_R] = [1e-5, 0.5].
    material : dict
        E [Pa] and nu of both bodies.
    """

    name: str
    radius: float
    groove_radius: float | None
    a_over_r: float
    material: dict = field(default_factory=lambda: dict(STEEL))

    def __post_init__(self):
        if not MIN_A_OVER_R <= self.a_over_r <= MAX_A_OVER_R:
            raise ValueError(f"a_over_r must be in [{MIN_A_OVER_R:g}, {MAX_A_OVER_R:g}] (a "
                             f"contact on the hemisphere, of elements well above gmsh's "
                             f"tolerance), got {self.a_over_r!r}")

    @property
    def body1(self) -> hertz.Body:
        """The ball."""
        return hertz.Body(self.radius, self.radius, **self.material)

    @property
    def body2(self) -> hertz.Body:
        """The block: flat, or concave with radius R_g across the groove (in y)."""
        if self.groove_radius is None:
            return hertz.Body(math.inf, math.inf, **self.material)
        return hertz.Body(math.inf, -self.groove_radius, **self.material)

    @property
    def load(self) -> float:
        """Target load [N]: the one whose Hertz semi-major axis is a_over_r R (a ~ P**(1/3))."""
        return (self.a_over_r * self.radius / self.hertz(1.0).a) ** 3

    def hertz(self, load: float | None = None) -> hertz.Contact:
        """Hertz's solution at ``load`` [N] (default: the target load)."""
        return hertz.contact(self.body1, self.body2, load=self.load if load is None else load)

    @property
    def e_star(self) -> float:
        return self.hertz().e_star


def sphere_plane(a_over_r: float, radius: float = 0.01) -> CurvedScene:
    """A steel ball of radius R on a flat steel block at Hertz a = a_over_r R."""
    return CurvedScene("sphere-plane", radius, None, a_over_r)


#: Groove radius over ball radius: osculation R_g / (2 R) = 0.52, a deep-groove ball
#: bearing's inner race (Hertz: alpha = 26, a/b = 8.1).
GROOVE_OVER_R = 1.04


def ball_groove(a_over_r: float, radius: float = 0.01,
                groove_over_r: float = GROOVE_OVER_R) -> CurvedScene:
    """A steel ball of radius R in a steel groove of radius groove_over_r R along x."""
    if not groove_over_r > 1:
        raise ValueError(f"groove_over_r must be > 1, got {groove_over_r!r}")
    return CurvedScene("ball-groove", radius, groove_over_r * radius, a_over_r)


@dataclass
class CurvedMesh:
    """The two meshed bodies and their contact surfaces (coordinates in m).

    Attributes
    ----------
    bodies : tuple of skfem.MeshTet
        Ball (body 1) and block (body 2).
    fixed : tuple of two int arrays
        Ball nodes on its equator (moved rigidly) and block nodes on its bottom (clamped).
    sym_x, sym_y : tuple of two int arrays
        Nodes of (ball, block) on the planes x = 0 and y = 0.
    slave : ndarray of int
        Ball nodes on its spherical surface within the search region.
    slave_area : ndarray
        Their lumped areas on the sphere's surface mesh [m**2].
    slave_triangles : ndarray of int, shape (k, 3)
        The ball's surface triangles within the search region, as indices into ``slave``.
    master : ndarray of int, shape (m, 3)
        Block surface triangles (block node indices) within the search region.
    master_normals : ndarray, shape (m, 3)
        Their outward unit normals.
    h0 : float
        Element size in the contact zone [m] (sets the penalty stiffness).
    block_depth : float
        Depth of the block's clamped bottom below the contact point [m].
    level : int
    parameters : dict
        Geometry and sizes in units of R.
    """

    bodies: tuple[MeshTet, MeshTet]
    fixed: tuple[np.ndarray, np.ndarray]
    sym_x: tuple[np.ndarray, np.ndarray]
    sym_y: tuple[np.ndarray, np.ndarray]
    slave: np.ndarray
    slave_area: np.ndarray
    slave_triangles: np.ndarray
    master: np.ndarray
    master_normals: np.ndarray
    h0: float
    block_depth: float
    level: int
    parameters: dict


def mesh_parameters(scene: CurvedScene, level: int = DEFAULT_CURVED_LEVEL) -> dict:
    """Element sizes, the refined zone and the blocks in units of R (see the module docstring)."""
    f = level_scale(level) * (1.0 if scene.groove_radius is None else GROOVE_COARSENING)
    c = scene.hertz()
    along_x = abs(math.cos(c.major_axis_angle)) >= 0.5
    ax, ay = (c.a, c.b) if along_x else (c.b, c.a)
    r = scene.radius
    zx, zy = ZONE * ax / r, ZONE * ay / r
    h0, hmax, grade = H0_OVER_B * f * c.b / r, HMAX_OVER_R * f, GRADE * f
    return {"zx": zx, "zy": zy, "zd": ZONE_DEPTH * c.b / r, "h0": h0, "hmax": hmax,
            "grade": grade, "L": BLOCK_OVER_R, "H": BLOCK_OVER_R,
            "groove": None if scene.groove_radius is None else scene.groove_radius / r,
            "level": level}


def _mesh_body(build_geometry, depth, params: dict) -> tuple[np.ndarray, np.ndarray, float]:
    """Mesh one body with gmsh: nodes (3, n) and tetrahedra (4, m), units of R.

    ``depth(x, y, z)`` is the distance below the body's contact surface (units of R).
    """
    import gmsh

    t0 = time.perf_counter()
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.option.setNumber("Mesh.RandomSeed", 1)
        gmsh.model.add("body")
        build_geometry(gmsh.model.occ)
        gmsh.model.occ.synchronize()
        gmsh.model.mesh.setSizeCallback(_size(params, depth))
        for option, value in (("Mesh.MeshSizeFromPoints", 0),
                              ("Mesh.MeshSizeFromCurvature", 0),
                              ("Mesh.MeshSizeExtendFromBoundary", 0),
                              ("Mesh.MeshSizeMax", params["hmax"]),
                              ("Mesh.Algorithm3D", 10)):
            gmsh.option.setNumber(option, value)
        gmsh.model.mesh.generate(3)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        types, _, conn = gmsh.model.mesh.getElements(3)
        if list(types) != [4]:
            raise FEMValidationError(f"gmsh returned element types {list(types)}, "
                                     f"expected linear tetrahedra (4) only")
    except FEMValidationError:
        raise
    except Exception as exc:  # gmsh reports its failures as plain Exceptions
        raise FEMValidationError(f"gmsh failed (parameters {params}): {exc}") from exc
    finally:
        gmsh.finalize()
    tags = np.asarray(tags, dtype=np.int64)
    coords = np.zeros((tags.max() + 1, 3))
    coords[tags] = np.asarray(xyz).reshape(-1, 3)
    tets = np.asarray(conn[0], dtype=np.int64).reshape(-1, 4)
    used, local = np.unique(tets, return_inverse=True)
    p = coords[used]
    t = positively_oriented(p, local.reshape(-1, 4))
    return p.T, t.T, time.perf_counter() - t0


def _size(params: dict, depth):
    """gmsh size callback: h0 in the zone, + grade per unit distance from it, <= hmax."""
    zx, zy, zd = params["zx"], params["zy"], params["zd"]
    h0, grade, hmax = params["h0"], params["grade"], params["hmax"]

    def size(dim, tag, x, y, z, lc):
        ex, ey = max(abs(x) - zx, 0.0), max(abs(y) - zy, 0.0)
        ez = max(depth(x, y, z) - zd, 0.0)
        return min(hmax, h0 + grade * math.sqrt(ex * ex + ey * ey + ez * ez))

    return size


def _ball_depth(x, y, z):
    return 1.0 - math.sqrt(x * x + y * y + (z - 1.0) * (z - 1.0))


def _block_depth(groove):
    if groove is None:
        return lambda x, y, z: -z
    return lambda x, y, z: math.sqrt(y * y + (z - groove) * (z - groove)) - groove


def _ball(occ) -> None:
    """Quarter of the lower hemisphere of the unit sphere centred at (0, 0, 1)."""
    sphere = occ.addSphere(0, 0, 1, 1)
    # poles (and the seam) away from the contact point at the origin
    occ.rotate([(3, sphere)], 0, 0, 1, 1, 0, 0, math.pi / 2)
    box = occ.addBox(0, 0, 0, 2, 2, 1)
    occ.intersect([(3, sphere)], [(3, box)])


def _block(params: dict):
    width, depth, rg = params["L"], params["H"], params["groove"]

    def build(occ):
        if rg is None:
            occ.addBox(0, 0, -depth, width, width, depth)
            return
        top = GROOVE_TOP_OVER_RG * rg
        box = occ.addBox(0, 0, -depth, width, width, depth + top)
        cyl = occ.addCylinder(-0.5, 0, rg, width + 1, 0, 0, rg)
        # the cylinder's seam away from the contact line y = 0, z = 0
        occ.rotate([(3, cyl)], 0, 0, rg, 1, 0, 0, math.pi / 2)
        occ.cut([(3, box)], [(3, cyl)])

    return build


def _boundary(p: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Boundary triangles (k, 3) of a tetrahedral mesh."""
    faces = np.sort(np.concatenate([t[[0, 1, 2]].T, t[[0, 1, 3]].T, t[[0, 2, 3]].T,
                                    t[[1, 2, 3]].T]), axis=1)
    uniq, count = np.unique(faces, axis=0, return_counts=True)
    return uniq[count == 1]


def _on_plane(p: np.ndarray, facets: np.ndarray, axis: int, value: float) -> np.ndarray:
    return np.all(np.abs(p[axis, facets] - value) < PLANE_TOL, axis=1)


def _nodes_on(p: np.ndarray, axis: int, value: float) -> np.ndarray:
    return np.nonzero(np.abs(p[axis] - value) < PLANE_TOL)[0]


def build_curved(scene: CurvedScene, level: int = DEFAULT_CURVED_LEVEL) -> CurvedMesh:
    """Mesh the ball and the block of a scene and find their contact surfaces.

    Raises
    ------
    FEMValidationError
        If gmsh fails, or a contact surface within the search region is empty.
    """
    params = mesh_parameters(scene, level)
    r = scene.radius
    pb, tb, s1 = _mesh_body(_ball, _ball_depth, params)
    pk, tk, s2 = _mesh_body(_block(params), _block_depth(params["groove"]), params)
    top = None if params["groove"] is None else GROOVE_TOP_OVER_RG * params["groove"]

    fb = _boundary(pb, tb)
    on_planes = _on_plane(pb, fb, 0, 0) | _on_plane(pb, fb, 1, 0) | _on_plane(pb, fb, 2, 1)
    sphere = fb[~on_planes]
    sx, sy = SEARCH * params["zx"], SEARCH * params["zy"]
    inside = np.all((pb[0, sphere] <= sx) & (pb[1, sphere] <= sy), axis=1)
    sphere = sphere[inside]
    slave, slave_tri = np.unique(sphere, return_inverse=True)
    slave_tri = slave_tri.reshape(-1, 3)
    slave_area = surface_lumped_area(pb.T * r, sphere, pb.shape[1])[slave]

    fk = _boundary(pk, tk)
    planes = (_on_plane(pk, fk, 0, 0) | _on_plane(pk, fk, 1, 0)
              | _on_plane(pk, fk, 0, params["L"]) | _on_plane(pk, fk, 1, params["L"])
              | _on_plane(pk, fk, 2, -params["H"]))
    if top is not None:
        planes |= _on_plane(pk, fk, 2, top)
    master = fk[~planes]
    near = np.all((pk[0, master] <= 1.5 * sx) & (pk[1, master] <= 1.5 * sy), axis=1)
    master = master[near]
    if not len(slave) or not len(master):
        raise FEMValidationError(f"{scene.name}: empty contact surface ({len(slave)} slave "
                                 f"nodes, {len(master)} master triangles)")
    pb_m, pk_m = np.ascontiguousarray(pb * r), np.ascontiguousarray(pk * r)
    normals = outward_normals(pk_m, tk, master)
    ball, block = MeshTet(pb_m, np.ascontiguousarray(tb)), MeshTet(pk_m, np.ascontiguousarray(tk))
    out = CurvedMesh(
        bodies=(ball, block),
        fixed=(_nodes_on(pb, 2, 1.0), _nodes_on(pk, 2, -params["H"])),
        sym_x=(_nodes_on(pb, 0, 0.0), _nodes_on(pk, 0, 0.0)),
        sym_y=(_nodes_on(pb, 1, 0.0), _nodes_on(pk, 1, 0.0)),
        slave=slave, slave_area=slave_area, slave_triangles=slave_tri, master=master,
        master_normals=normals, h0=params["h0"] * r, block_depth=params["H"] * r,
        level=level, parameters=params)
    log.info("%s (a/R %.3g): meshed level %d in %.1f + %.1f s: %d + %d tetrahedra, %d slave "
             "nodes, %d master triangles, h0 = %.3g b", scene.name, scene.a_over_r, level, s1,
             s2, ball.nelements, block.nelements, len(slave), len(master),
             params["h0"] * r / scene.hertz().b)
    return out
