"""A scene -> a two-body quadratic-tetrahedron model that any FE code can take.

Two geometries:

* **true curved bodies** (gmsh OpenCASCADE, :mod:`fem_validation.solvers.curved_mesh`) when
  the scene is a ball on a flat block or in a groove along x (one material):
  the quarter of a hemisphere on a block, the ball's equator moved down
  rigidly, the block's bottom clamped;
* **paraboloid-faced blocks** for every other scene: the two blocks of
  :mod:`fem_validation.solvers.mesh` (structured grid around the contact), whose flat
  faces at z = 0 are then mapped onto the bodies' paraboloids,
  z -> z + h1(x, y) (1 - z/H) in body 1 and z -> z - h2(x, y) (1 + z/H) in
  body 2 (h_i = x_i**2 / (2 R_ix) + y_i**2 / (2 R_iy) in body i's frame), so
  that the initial gap is Hertz's h1 + h2 and the far faces stay flat.
  Body 1's top is moved down rigidly, body 2's bottom clamped.

The linear tetrahedra are made quadratic here (C3D10 node order: vertices,
then the mid-side nodes of edges 1-2, 2-3, 3-1, 1-4, 2-4, 3-4); mid-side nodes
on the sphere or the groove are projected onto it, those of the blocks are
mapped with the vertices.  Coordinates are in metres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

import hertz

from ..errors import FEMValidationError
from ..scenes import Scene

#: C3D10 / Abaqus mid-side nodes: the vertex pairs of nodes 5..10 (0-based).
TET10_EDGES = ((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))
#: C3D4 / C3D10 faces S1..S4 (0-based vertices); on a positive tetrahedron the right-hand
#: normal of each vertex triple points into the element.
TET_FACES = ((0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0))
#: Penalty stiffness of the contact over E* / h0 (h0 the element size at the contact).
PENALTY_FACTOR = 10.0
#: The penalty factors a deck takes, [low, high].  The overclosure at the contact's centre,
#: p0 h0 / (factor E*), is 0.05 to 0.13 of Hertz's approach over the factor at the deck
#: levels 0-2 (0.5-1.3% at the default 10): at 0.1 it is the approach itself, so that the
#: penalty, not Hertz, sets the contact.  Above 1e6 the contact is a million times stiffer
#: than the elements (E/h0): the system's condition number grows by as much, a
#: double-precision solve keeps about 10 digits, and the overclosure (1e-7 of the approach)
#: is far below anything a grade sees.
PENALTY_FACTOR_RANGE = (0.1, 1e6)
#: _EDGE_OF[i, j]: the C3D10 mid-side node (minus 4) between vertices i and j.
_EDGE_OF = np.full((4, 4), -1)
for _k, (_i, _j) in enumerate(TET10_EDGES):
    _EDGE_OF[_i, _j] = _EDGE_OF[_j, _i] = _k
#: Slave faces: centroids within this many semi-axes of the contact centre; master: MASTER.
SLAVE_REGION = 2.5
MASTER_REGION = 3.5
#: The blocks' half-width and depth: at most EXTENT_OVER_A semi-major axes, and small
#: enough that the paraboloid rises at most MAX_RISE times the depth at the edge.
EXTENT_OVER_A = 40.0
MIN_EXTENT_OVER_A = 8.0
MAX_RISE = 0.3
#: The largest a / R_min of paraboloid-faced blocks.  Up to MAX_RISE / MIN_EXTENT_OVER_A
#: (0.0375) the paraboloids are mapped whole; beyond, on convex bodies, each face is the
#: paraboloid where it rises less than RISE_KNEE of the cap MAX_RISE times the depth, and
#: levels off smoothly to the cap beyond (:func:`capped_height`), so that the mapped
#: elements stay sound.  At a/R_min = 0.2 the faces are exact paraboloids out to 5.5 a
#: (the slave faces reach 2.5 a): the gap Hertz's theory assumes, on blocks 20 a wide.
#: Beyond 0.2 the contact would reach into the levelled part; Hertz's own small-contact
#: assumption is then off by more than the grades' tolerances anyway (the curved-body
#: FEM measures the departure, docs/explanation/curved-bodies.md).
MAX_BLOCK_A_OVER_R = 0.2
#: The rise, as a fraction of the cap, up to which a capped face is the exact paraboloid.
RISE_KNEE = 0.5
#: The blocks' half-width and depth, in semi-major axes, where the faces level off: wide
#: enough that the far faces' Boussinesq correction of the approach holds (the issue's
#: ellipsoid at a/R 0.05, level 0, ccx 2.20: approach +2.1% with blocks of 8 a, +1.1% with
#: 20 a; a -0.4%, b +0.5%, p0 -1.2%: passed), narrow enough that the
#: faces' slope where they level off stays moderate (sqrt(6 a / R): 1.1 at a/R = 0.2).
CAPPED_EXTENT_OVER_A = 20.0


@dataclass
class DeckModel:
    """A two-body contact model in the form decks are written from (SI units).

    Attributes
    ----------
    nodes : ndarray, shape (n, 3)
        Node coordinates [m]; node i has the number i + 1 in a deck.
    elements : ndarray of int, shape (m, 10)
        Quadratic tetrahedra in C3D10 order (0-based node indices); element j
        has the number j + 1.
    body : ndarray of int, shape (m,)
        1 or 2: the body of each element.
    node_sets : dict of str -> int array
        Named node sets (0-based): MOVED, FIXED, SYMX, SYMY (quarter only),
        BODY1, BODY2, SLAVE, MASTER.
    surfaces : dict of str -> (elements, faces)
        Element-face surfaces: 0-based element indices and face numbers 1..4.
    slave, master : str
        Names of the slave and master surfaces (keys of ``surfaces``).
    scene : Scene
        The scene (bodies, target load, angle).
    approach : float
        Prescribed downward displacement of MOVED [m].
    penalty : float
        Linear pressure-overclosure slope [Pa/m].
    h0 : float
        Element size at the contact [m] (edge of the linear mesh).
    quarter : bool
        True for the quarter model (x >= 0, y >= 0).
    geometry : str
        "sphere-plane", "ball-groove" or "paraboloid-blocks".
    level : int
    info : dict
        Further figures for problem.json (block sizes, settlement correction).
    """

    nodes: np.ndarray
    elements: np.ndarray
    body: np.ndarray
    node_sets: dict
    surfaces: dict
    slave: str
    master: str
    scene: Scene
    approach: float
    penalty: float
    h0: float
    quarter: bool
    geometry: str
    level: int
    info: dict = field(default_factory=dict)

    @property
    def contact(self) -> hertz.Contact:
        """Hertz's solution at the scene's target load."""
        return self.scene.hertz()

    @property
    def symmetry(self) -> str:
        """"quarter" (x >= 0, y >= 0), "half" (y >= 0) or "whole"."""
        return "quarter" if self.quarter else self.info.get("symmetry", "whole")

    @property
    def multiplicity(self) -> int:
        """Copies of the model in the whole contact (the factor on its forces)."""
        return {"quarter": 4, "half": 2, "whole": 1}[self.symmetry]


def quadratic(p: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Mid-side nodes for linear tetrahedra.

    Parameters
    ----------
    p : ndarray, shape (n, 3)
        Vertices.
    t : ndarray of int, shape (m, 4)
        Positively oriented tetrahedra.

    Returns
    -------
    nodes : ndarray, shape (n + k, 3)
        Vertices, then the k edge midpoints (straight edges).
    tet10 : ndarray of int, shape (m, 10)
        C3D10 connectivity.
    edges : ndarray of int, shape (k, 2)
        The vertex pair of each mid-side node (node n + i is the middle of edges[i]).
    """
    pairs = np.stack([t[:, list(e)] for e in TET10_EDGES], axis=1)  # (m, 6, 2)
    flat = np.sort(pairs.reshape(-1, 2), axis=1)
    edges, inverse = np.unique(flat, axis=0, return_inverse=True)
    mid = 0.5 * (p[edges[:, 0]] + p[edges[:, 1]])
    tet10 = np.hstack([t, len(p) + inverse.reshape(-1, 6)])
    return np.vstack([p, mid]), tet10, edges


def boundary_faces(t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Boundary faces of a tetrahedral mesh as (vertices (k, 3), element, face 1..4)."""
    faces = np.concatenate([t[:, list(f)] for f in TET_FACES])  # face-major
    m = len(t)
    elem = np.tile(np.arange(m), 4)
    number = np.repeat(np.arange(1, 5), m)
    key = np.sort(faces, axis=1)
    _, inverse, count = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    outer = count[inverse.ravel()] == 1
    return faces[outer], elem[outer], number[outer]


def face_nodes(conn: np.ndarray, face: np.ndarray) -> np.ndarray:
    """The six nodes of faces of quadratic tetrahedra: (k, 6), vertices then mid-sides.

    ``conn`` (k, 10) in C3D10 order, ``face`` the face numbers 1..4.
    """
    local = np.array(TET_FACES)[face - 1]  # (k, 3)
    rows = np.arange(len(conn))[:, None]
    verts = conn[rows, local]
    mids = conn[rows, 4 + _EDGE_OF[local, np.roll(local, -1, axis=1)]]
    return np.hstack([verts, mids])


def _extend_set(vertex_set: np.ndarray, edges: np.ndarray, n_vertices: int) -> np.ndarray:
    """A vertex set plus the mid-side nodes of the edges with both ends in it."""
    inside = np.zeros(n_vertices, dtype=bool)
    inside[vertex_set] = True
    mids = np.nonzero(inside[edges[:, 0]] & inside[edges[:, 1]])[0] + n_vertices
    return np.concatenate([np.asarray(vertex_set, dtype=np.int64), mids])


def _select_faces(faces, elem, number, p, keep_vertices, centre_ok):
    """Boundary faces whose three vertices are in ``keep_vertices`` and whose centroid passes."""
    mask = np.all(keep_vertices[faces], axis=1)
    c = p[faces[mask]].mean(axis=1)
    ok = centre_ok(c)
    idx = np.nonzero(mask)[0][ok]
    return elem[idx], number[idx]


def _ellipse_radius(scene: Scene, xy: np.ndarray) -> np.ndarray:
    """sqrt((X/a)^2 + (Y/b)^2) in the Hertz ellipse's frame at the target load."""
    c = scene.hertz()
    cs, sn = math.cos(c.major_axis_angle), math.sin(c.major_axis_angle)
    along = xy[:, 0] * cs + xy[:, 1] * sn
    across = -xy[:, 0] * sn + xy[:, 1] * cs
    return np.hypot(along / c.a, across / c.b)


def paraboloid_height(body: hertz.Body, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """x**2 / (2 Rx) + y**2 / (2 Ry) in the body's frame [m] (0 for an infinite radius)."""
    h = np.zeros_like(x)
    for r, u in ((body.Rx, x), (body.Ry, y)):
        if math.isfinite(r):
            h = h + u * u / (2.0 * r)
    return h


def capped_height(h: np.ndarray, cap: float, knee: float = RISE_KNEE) -> np.ndarray:
    """A paraboloid's height ``h`` [m] levelled off below ``cap`` [m]: ``h`` itself up to
    ``knee * cap``, then ``k + (cap - k)(1 - exp(-(h - k)/(cap - k)))`` with k = knee cap,
    which is continuous with its slope, increasing, and below ``cap``.

    Examples
    --------
    >>> import numpy as np
    >>> capped_height(np.array([0.0, 0.4, 1.0, 100.0]), 1.0).round(4).tolist()
    [0.0, 0.4, 0.8161, 1.0]
    """
    h = np.asarray(h, dtype=float)
    k = knee * cap
    span = cap - k
    over = np.maximum(h - k, 0.0)
    return np.where(h <= k, h, k + span * -np.expm1(-over / span))


def _all_convex(scene: Scene) -> bool:
    """Both bodies convex or flat: every principal radius > 0 (inf for flat)."""
    return all(r > 0 for b in (scene.body1, scene.body2) for r in (b.Rx, b.Ry))


def _min_a_over_r() -> float:
    from ..solvers.curved_mesh import MIN_A_OVER_R

    return MIN_A_OVER_R


def smallest_radius(scene: Scene) -> float:
    """The smallest finite principal radius of the two bodies, in absolute value [m]."""
    return min(abs(r) for body in (scene.body1, scene.body2) for r in (body.Rx, body.Ry)
               if math.isfinite(r))


def check_scene(scene: Scene) -> hertz.Contact:
    """Hertz's contact at the scene's target load, if a deck model can be meshed for it.

    A deck needs a target load that is a finite number > 0 [N], and a contact whose
    semi-major axis a lies between MIN_A_OVER_R = 1e-5 times the smallest radius R_min
    of the bodies and the largest its model takes: 0.5 R for a true ball on a plane or
    in a groove, 0.2 R_min for paraboloid-faced blocks (0.0375 for a conformal contact,
    see :func:`block_extent`).  Below 1e-5 the curved meshes' elements approach gmsh's
    geometric tolerance (gmsh then meshes until it runs out of memory); the blocks,
    built in units of b, would mesh any contact, but a contact of less than 1e-5 of the
    radii is far more likely a load or a modulus in the wrong unit (load = 1e-300 N, E =
    1e300 Pa), and is refused as well.  This runs before gmsh.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    hertz.Contact
        Hertz at the target load.

    Raises
    ------
    ValueError
        Naming the scene, the load or the ratio a/R_min, and the range allowed.
    """
    load = scene.load
    if not in_range(load, math.ulp(0.0), math.inf, open_high=True):
        raise ValueError(f"scene {scene.name!r}: load must be a finite number > 0 [N] (a deck "
                         f"prescribes the approach that reaches it), got {load!r}")
    c = scene.hertz()
    r_min = smallest_radius(scene)
    low = _min_a_over_r()
    if not c.a >= low * r_min:
        raise ValueError(f"scene {scene.name!r}: the contact is too small for the meshes: "
                         f"Hertz's a = {c.a:.3g} m is {c.a / r_min:.3g} times the smallest "
                         f"radius {r_min:.3g} m; a deck needs a/R_min >= {low:g} (and at most "
                         f"0.5 for a ball on a plane or in a groove, "
                         f"{MAX_BLOCK_A_OVER_R:g} otherwise): check the load and "
                         f"the moduli (SI units: N, Pa)")
    return c


def in_range(value, low: float, high: float, *, kind=int | float, open_high: bool = False) -> bool:
    """Whether ``value`` is a number of ``kind`` (never a bool) with low <= value <= high
    (< high with ``open_high``): the test behind every deck option's range check."""
    if isinstance(value, bool) or not isinstance(value, kind):
        return False
    return low <= value < high if open_high else low <= value <= high


def check_penalty_factor(penalty_factor) -> float:
    """``penalty_factor`` (the penalty slope over E*/h0) if it is in :data:`PENALTY_FACTOR_RANGE`.

    Raises
    ------
    ValueError
        Naming the parameter, the range and the value.
    """
    low, high = PENALTY_FACTOR_RANGE
    if not in_range(penalty_factor, low, high):
        raise ValueError(f"penalty_factor must be a finite number > 0 in [{low:g}, {high:g}] "
                         f"(the penalty slope over E*/h0: below {low:g} the overclosure "
                         f"exceeds Hertz's approach, above {high:g} the contact swamps the "
                         f"elements' stiffness), got {penalty_factor!r}")
    return penalty_factor


def _check_options(slave_body, penalty_factor) -> None:
    """The options of a model, checked before anything is meshed."""
    if slave_body not in (1, 2) or isinstance(slave_body, bool):
        raise ValueError(f"slave_body must be 1 or 2, got {slave_body!r}")
    check_penalty_factor(penalty_factor)


# --------------------------------------------------------------------------- curved
def curved_scene_for(scene: Scene):
    """The :class:`CurvedScene` of a ball on a plane or in a groove along x, or None.

    True geometry needs: body 1 a sphere (Rx = Ry > 0), body 2 flat or a groove
    (Rx infinite, Ry = -R_g with R_g > R), one material, and a semi-axis at the
    target load between 1e-5 and 0.5 times the ball's radius
    (:data:`fem_validation.solvers.curved_mesh.MIN_A_OVER_R`, ``MAX_A_OVER_R``).
    """
    from ..solvers.curved_mesh import (
        MAX_A_OVER_R,
        MIN_A_OVER_R,
        CurvedScene,
        ball_groove,
        sphere_plane,
    )

    b1, b2 = scene.body1, scene.body2
    if not (math.isfinite(b1.Rx) and b1.Rx == b1.Ry and b1.Rx > 0):
        return None
    if (b1.E, b1.nu) != (b2.E, b2.nu) or scene.angle != 0.0:
        return None
    radius = b1.Rx
    a_over_r = scene.hertz().a / radius
    if not MIN_A_OVER_R <= a_over_r <= MAX_A_OVER_R:
        return None
    material = {"E": b1.E, "nu": b1.nu}
    if math.isinf(b2.Rx) and math.isinf(b2.Ry):
        c = sphere_plane(a_over_r, radius)
    elif math.isinf(b2.Rx) and math.isfinite(b2.Ry) and -b2.Ry > radius:
        c = ball_groove(a_over_r, radius, -b2.Ry / radius)
    else:
        return None
    return CurvedScene(c.name, c.radius, c.groove_radius, c.a_over_r, material)


def build_curved_model(scene: Scene, level: int, slave_body: int = 1,
                       penalty_factor: float = PENALTY_FACTOR) -> DeckModel:
    """Quarter model of a ball on a block (or in a groove) with quadratic tetrahedra.

    Raises
    ------
    ValueError
        Before meshing: the scene is not a ball on a plane or in a groove, or
        :func:`check_scene` refuses it, or an option is out of range.
    """
    from ..solvers.curved import imposed_approach
    from ..solvers.curved_mesh import build_curved

    _check_options(slave_body, penalty_factor)
    check_scene(scene)
    cscene = curved_scene_for(scene)
    if cscene is None:
        raise ValueError(f"scene {scene.name!r} is not a ball on a plane or in a groove")
    mesh = build_curved(cscene, level)
    r = cscene.radius
    parts, sets = [], {}
    offset_n = 0
    # node sets on the linear meshes (vertex indices per body)
    vsets = {"MOVED": (mesh.fixed[0], None), "FIXED": (None, mesh.fixed[1]),
             "SYMX": mesh.sym_x, "SYMY": mesh.sym_y}
    region = {}
    for i, m in enumerate(mesh.bodies):
        p, t = m.p.T, m.t.T
        nodes, tet10, edges = quadratic(p, t)
        faces, elem, number = boundary_faces(t)
        # project the curved surface's mid-side nodes onto the sphere or the cylinder
        if i == 0:
            centre = np.array([0.0, 0.0, r])
            on = np.abs(np.linalg.norm(p - centre, axis=1) - r) < 1e-9 * r
            mids = np.nonzero(on[edges[:, 0]] & on[edges[:, 1]])[0] + len(p)
            d = nodes[mids] - centre
            nodes[mids] = centre + r * d / np.linalg.norm(d, axis=1)[:, None]
        elif cscene.groove_radius is not None:
            rg = cscene.groove_radius
            yz = p[:, 1:] - np.array([0.0, rg])
            on = np.abs(np.linalg.norm(yz, axis=1) - rg) < 1e-9 * rg
            mids = np.nonzero(on[edges[:, 0]] & on[edges[:, 1]])[0] + len(p)
            d = nodes[mids, 1:] - np.array([0.0, rg])
            nodes[mids, 1:] = np.array([0.0, rg]) + rg * d / np.linalg.norm(d, axis=1)[:, None]
        for name, pair in vsets.items():
            if pair[i] is not None:
                sets.setdefault(name, []).append(_extend_set(pair[i], edges, len(p)) + offset_n)
        sets[f"BODY{i + 1}"] = [np.arange(len(nodes)) + offset_n]
        # contact faces: the ball's slave triangles, the block's master triangles
        if i == 0:
            tri = mesh.slave[mesh.slave_triangles]
        else:
            tri = mesh.master
        key = {tuple(sorted(f)): k for k, f in enumerate(faces)}
        idx = np.array([key[tuple(sorted(f))] for f in tri])
        region[i] = (elem[idx], number[idx])
        parts.append((nodes, tet10, edges, len(p)))
        offset_n += len(nodes)
    return _assemble(scene, parts, sets, region, slave_body, level, quarter=True,
                     geometry=cscene.name, h0=mesh.h0,
                     approach=imposed_approach(cscene, mesh), penalty_factor=penalty_factor,
                     info={"ball_radius": r, "groove_radius": cscene.groove_radius,
                           "block_half_width": mesh.parameters["L"] * r,
                           "block_depth": mesh.block_depth,
                           "moved": "the ball's equator (z = R)",
                           "far_face_depths": [r, mesh.block_depth]})


# --------------------------------------------------------------------------- blocks
def block_extent(scene: Scene) -> float:
    """Half-width = depth of the paraboloid-faced blocks, in units of b.

    EXTENT_OVER_A semi-major axes, less where a paraboloid would rise more than
    MAX_RISE of the depth at the block's edge (the mapped elements stay sound), and at
    least MIN_EXTENT_OVER_A semi-major axes.  Up to a/R_min = MAX_RISE /
    MIN_EXTENT_OVER_A = 0.0375 (R_min the smallest radius) the faces are whole
    paraboloids; beyond, up to :data:`MAX_BLOCK_A_OVER_R` = 0.2 for two convex (or flat)
    bodies, the blocks are CAPPED_EXTENT_OVER_A (20) semi-major axes wide and their faces
    level off where they would rise too far (:func:`capped_height`).  A conformal contact
    (a concave body) keeps 0.0375: levelled faces of a convex and a concave body would
    meet away from the contact.  The lower end, 1e-5, is :func:`check_scene`'s.

    Raises
    ------
    ValueError
        Naming the scene, a and R_min, the limit and why.
    """
    c = check_scene(scene)
    r_min = smallest_radius(scene)
    curv = 1 / r_min
    # rise at the corner (distance sqrt 2 L) over depth L: curv * 2 L**2 / 2 / L = curv L
    extent = min(EXTENT_OVER_A * c.a, MAX_RISE / curv)
    if extent >= MIN_EXTENT_OVER_A * c.a:
        return extent / c.b
    ratio = c.a / r_min
    whole = MAX_RISE / MIN_EXTENT_OVER_A
    if not _all_convex(scene):
        raise ValueError(f"scene {scene.name!r}: the contact is too large for the radii: "
                         f"Hertz's a = {c.a:.3g} m is {ratio:.3g} times the smallest radius "
                         f"{r_min:.3g} m; for a conformal contact (a concave body) "
                         f"paraboloid-faced blocks of {MIN_EXTENT_OVER_A:g} a need a/R_min <= "
                         f"{whole:g}, where the whole paraboloid rises at most {MAX_RISE:g} "
                         f"of the block's depth (and >= {_min_a_over_r():g}): lower the load")
    if ratio > MAX_BLOCK_A_OVER_R:
        raise ValueError(f"scene {scene.name!r}: the contact is too large for the radii: "
                         f"Hertz's a = {c.a:.3g} m is {ratio:.3g} times the smallest radius "
                         f"{r_min:.3g} m; paraboloid-faced blocks take a/R_min <= "
                         f"{MAX_BLOCK_A_OVER_R:g} (beyond, the faces are steep where they "
                         f"level off and the elements there distorted, and Hertz's "
                         f"small-contact theory itself departs by more than a grade's "
                         f"tolerances): lower the load")
    return CAPPED_EXTENT_OVER_A * c.a / c.b


def build_block_model(scene: Scene, level: int, quarter: bool | None = None,
                      slave_body: int = 1, penalty_factor: float = PENALTY_FACTOR) -> DeckModel:
    """Two paraboloid-faced blocks with quadratic tetrahedra.

    Raises
    ------
    ValueError
        Before meshing: :func:`block_extent` refuses the contact's size, the mesh
        would have more vertices than :data:`fem_validation.solvers.mesh.MAX_MESH_NODES`,
        or an option is out of range.
    """
    from ..solvers.mesh import build
    from ..solvers.solve import imposed_approach

    _check_options(slave_body, penalty_factor)
    if quarter is None:
        quarter = scene.symmetric
    if quarter and not scene.symmetric:
        raise ValueError(f"scene {scene.name!r} has no quarter symmetry (principal planes at "
                         f"{math.degrees(scene.angle):g} deg): use --model whole")
    extent = block_extent(scene)
    mesh = build(scene, level, parameters={"L": extent, "H": extent,
                                           "hmax": 0.25 * extent * _level_scale(level),
                                           "quarter": 1.0 if quarter else 0.0})
    depth = mesh.depth
    # the faces level off (a/R_min beyond 0.0375) where a paraboloid would rise too far
    capped = smallest_radius(scene) * MAX_RISE < depth * (1 - 1e-12)
    cos, sin = math.cos(scene.angle), math.sin(scene.angle)
    parts, sets, region = [], {}, {}
    offset_n = 0
    vsets = {"MOVED": (mesh.top, None), "FIXED": (None, mesh.bottom)}
    if quarter:
        vsets["SYMX"], vsets["SYMY"] = mesh.sym_x, mesh.sym_y
    for i, m in enumerate(mesh.bodies):
        p, t = m.p.T, m.t.T
        nodes, tet10, edges = quadratic(p, t)
        x, y, z = nodes.T
        if i == 0:
            h = paraboloid_height(scene.body1, x, y)
        else:
            h = paraboloid_height(scene.body2, x * cos + y * sin, -x * sin + y * cos)
        if capped:
            h = capped_height(h, MAX_RISE * depth)
        nodes[:, 2] = z + h * (1.0 - z / depth) if i == 0 else z - h * (1.0 + z / depth)
        for name, pair in vsets.items():
            if pair[i] is not None:
                sets.setdefault(name, []).append(_extend_set(pair[i], edges, len(p)) + offset_n)
        sets[f"BODY{i + 1}"] = [np.arange(len(nodes)) + offset_n]
        faces, elem, number = boundary_faces(t)
        on_contact = np.zeros(len(p), dtype=bool)
        on_contact[mesh.pairs[:, i]] = True
        reach = SLAVE_REGION if i + 1 == slave_body else MASTER_REGION
        region[i] = _select_faces(faces, elem, number, p, on_contact,
                                  lambda c, reach=reach: _ellipse_radius(scene, c) <= reach)
        parts.append((nodes, tet10, edges, len(p)))
        offset_n += len(nodes)
    return _assemble(scene, parts, sets, region, slave_body, level, quarter=quarter,
                     geometry="paraboloid-blocks", h0=mesh.h0,
                     approach=imposed_approach(scene, mesh), penalty_factor=penalty_factor,
                     info={"block_half_width": mesh.extent, "block_depth": depth,
                           "faces": ("paraboloids levelled off beyond a rise of "
                                     f"{RISE_KNEE * MAX_RISE:g} of the depth" if capped
                                     else "paraboloids"),
                           "moved": "body 1's top face (z = H)",
                           "far_face_depths": [depth, depth]})


def _level_scale(level: int) -> float:
    from ..solvers.mesh import LEVEL_SCALE

    if level not in LEVEL_SCALE:
        raise ValueError(f"level must be one of {sorted(LEVEL_SCALE)}, got {level!r}")
    return LEVEL_SCALE[level]


def _assemble(scene, parts, sets, region, slave_body, level, *, quarter, geometry, h0,
              approach, penalty_factor, info) -> DeckModel:
    nodes = np.vstack([q[0] for q in parts])
    offsets = np.cumsum([0] + [len(q[0]) for q in parts])
    elements = np.vstack([q[1] + off for q, off in zip(parts, offsets, strict=False)])
    body = np.concatenate([np.full(len(q[1]), i + 1) for i, q in enumerate(parts)])
    eoff = np.cumsum([0] + [len(q[1]) for q in parts])
    surfaces = {}
    for i in (0, 1):
        elem, face = region[i]
        if not len(elem):
            raise FEMValidationError(f"{scene.name}: no contact faces on body {i + 1}")
        surfaces[f"CONTACT{i + 1}"] = (elem + eoff[i], face)
    node_sets = {k: np.unique(np.concatenate(v)) for k, v in sets.items()}
    for i in (0, 1):
        el, fc = surfaces[f"CONTACT{i + 1}"]
        name = "SLAVE" if i + 1 == slave_body else "MASTER"
        node_sets[name] = np.unique(face_nodes(elements[el], fc))
    c = scene.hertz()
    penalty = penalty_factor * c.e_star / h0
    if not math.isfinite(penalty):
        raise ValueError(f"scene {scene.name!r}: the penalty slope penalty_factor E*/h0 "
                         f"overflows (E* = {c.e_star:.3g} Pa, h0 = {h0:.3g} m): check the "
                         f"moduli (SI units: Pa)")
    info = {**info, "penalty_factor": penalty_factor}
    return DeckModel(nodes, elements, body, node_sets, surfaces,
                     f"CONTACT{slave_body}", f"CONTACT{3 - slave_body}", scene, approach,
                     penalty, h0, quarter, geometry, level, info)


#: A quarter model's C3D10 connectivity mirrored in x = 0 (the mirror turns a tetrahedron
#: inside out: vertices 2 and 3 swap, and the mid-side nodes follow their edges).
_MIRROR_TET10 = [0, 2, 1, 3, 6, 5, 4, 7, 9, 8]
#: Faces S1..S4 of the mirrored element: the old face numbers (S2 and S4 swap).
_MIRROR_FACE = np.array([0, 1, 4, 3, 2])


def half_model(quarter: DeckModel) -> DeckModel:
    """The half model (y >= 0) of a quarter model: its mirror image in x = 0 added.

    A tangential load along x breaks the symmetry in x = 0 but keeps the one in
    y = 0 (the plane containing the load), so a frictional deck loaded along
    x is a half model with u_y = 0 on y = 0 (node set SYMY).  The nodes on
    x = 0 are shared by the two halves; every other node, element and face gets
    a mirror image.

    Parameters
    ----------
    quarter : DeckModel
        A quarter model (x >= 0, y >= 0).

    Returns
    -------
    DeckModel
        ``quarter`` False, ``info["symmetry"] == "half"``; node set SYMX gone.
    """
    if not quarter.quarter:
        raise ValueError(f"half_model needs a quarter model, got a {quarter.symmetry} one")
    n = len(quarter.nodes)
    x = quarter.nodes[:, 0]
    on_plane = np.abs(x) <= 1e-12 * np.abs(quarter.nodes).max()
    image = np.arange(n)
    image[~on_plane] = n + np.arange(int((~on_plane).sum()))
    nodes = np.vstack([quarter.nodes, quarter.nodes[~on_plane] * np.array([-1.0, 1.0, 1.0])])
    mirrored = image[quarter.elements][:, _MIRROR_TET10]
    # element order: body 1, its mirror, body 2, its mirror (each ELSET stays contiguous)
    new_index = np.empty(len(quarter.elements), dtype=np.int64)
    new_mirror = np.empty(len(quarter.elements), dtype=np.int64)
    elements, body, start = [], [], 0
    for b in (1, 2):
        idx = np.nonzero(quarter.body == b)[0]
        new_index[idx] = start + np.arange(len(idx))
        new_mirror[idx] = start + len(idx) + np.arange(len(idx))
        elements += [quarter.elements[idx], mirrored[idx]]
        body += [np.full(2 * len(idx), b)]
        start += 2 * len(idx)
    surfaces = {name: (np.concatenate([new_index[e], new_mirror[e]]),
                       np.concatenate([f, _MIRROR_FACE[f]]))
                for name, (e, f) in quarter.surfaces.items()}
    node_sets = {name: np.unique(np.concatenate([s, image[s]]))
                 for name, s in quarter.node_sets.items() if name != "SYMX"}
    return DeckModel(nodes, np.vstack(elements), np.concatenate(body), node_sets, surfaces,
                     quarter.slave, quarter.master, quarter.scene, quarter.approach,
                     quarter.penalty, quarter.h0, False, quarter.geometry, quarter.level,
                     {**quarter.info, "symmetry": "half"})


def check_model(scene: Scene, level: int, model: str = "auto", slave_body: int = 1,
                penalty_factor: float = PENALTY_FACTOR) -> str:
    """Check what :func:`build_model` is given, without meshing; the geometry it would build.

    The model's name, the slave body, the penalty factor
    (:data:`PENALTY_FACTOR_RANGE`), the scene's target load and contact size
    (:func:`check_scene`, and :func:`block_extent` for paraboloid-faced blocks), the
    symmetry a quarter or half model of blocks needs, and the mesh level: 0-4 for true
    curved bodies (:data:`fem_validation.solvers.curved_mesh.CURVED_LEVELS`), 0-5 for
    the blocks (:data:`fem_validation.solvers.mesh.LEVEL_SCALE`).

    Returns
    -------
    str
        "sphere-plane" or "ball-groove" (true curved bodies), or "paraboloid-blocks".

    Raises
    ------
    ValueError
        Naming the parameter or the scene, the value and what is allowed.
    """
    from ..solvers.curved_mesh import CURVED_LEVELS
    from ..solvers.mesh import LEVEL_SCALE

    if model not in ("auto", "quarter", "half", "whole"):
        raise ValueError(f"model must be 'auto', 'quarter', 'half' or 'whole', got {model!r}")
    _check_options(slave_body, penalty_factor)
    check_scene(scene)
    curved = curved_scene_for(scene) if model in ("auto", "quarter") else None
    if curved is not None:
        geometry, levels = curved.name, tuple(CURVED_LEVELS)
    else:
        geometry, levels = "paraboloid-blocks", tuple(sorted(LEVEL_SCALE))
        if model in ("quarter", "half") and not scene.symmetric:
            raise ValueError(f"scene {scene.name!r} has no quarter symmetry (principal planes "
                             f"at {math.degrees(scene.angle):g} deg): use --model whole")
        block_extent(scene)
    if isinstance(level, bool) or not isinstance(level, int) or level not in levels:
        raise ValueError(f"level must be one of {list(levels)} (the mesh levels of "
                         f"{geometry}), got {level!r}")
    return geometry


def build_model(scene: Scene, level: int, model: str = "auto", slave_body: int = 1,
                penalty_factor: float = PENALTY_FACTOR) -> DeckModel:
    """The deck model of a scene: true curved bodies where possible, else paraboloid blocks.

    Parameters
    ----------
    scene : Scene
    level : int
        Mesh level (0 coarse): the curved levels 0-4 of
        :mod:`fem_validation.solvers.curved_mesh`, or the block levels 0-5 of
        :mod:`fem_validation.solvers.mesh`.
    model : {"auto", "quarter", "half", "whole"}
        Quarter, half (y >= 0, :func:`half_model`) or whole model; "auto" takes
        the quarter model where the scene allows it.  True curved bodies are
        quarter models only: "half" and "whole" give paraboloid-faced blocks.
    slave_body : {1, 2}
        The body whose contact face is the slave surface.
    penalty_factor : float
        Penalty slope over E*/h0, in :data:`PENALTY_FACTOR_RANGE` ([0.1, 1e6]).

    Raises
    ------
    ValueError
        Before gmsh runs (:func:`check_model`): a target load that is not a finite
        number > 0, a contact outside 1e-5 <= a/R_min <= 0.2 (0.0375 for a conformal
        contact, 0.5 for a ball on a plane or in a groove: :func:`check_scene`,
        :func:`block_extent`), a mesh of more
        than :data:`fem_validation.solvers.mesh.MAX_MESH_NODES` vertices, or an option
        out of range (a level outside the geometry's).
    """
    check_model(scene, level, model, slave_body, penalty_factor)
    if model == "half":
        # paraboloid-faced blocks: the tangential displacement's correction for the
        # clamped far faces (Cerruti at the block's depth) is a block's
        return half_model(build_block_model(scene, level, True, slave_body, penalty_factor))
    if model != "whole" and curved_scene_for(scene) is not None:
        return build_curved_model(scene, level, slave_body, penalty_factor)
    quarter = None if model == "auto" else model == "quarter"
    return build_block_model(scene, level, quarter, slave_body, penalty_factor)
