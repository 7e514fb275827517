"""Mesh the two blocks of a scene with gmsh (meshes/blocks.geo) and split them.

The geometry is parametrised in units of the Hertz minor semi-axis b at the
scene's target load; node coordinates are returned in metres.  The blocks are
meshed together so that their faces at z = 0 match node for node; each body
then gets its own copy of those nodes, and the copies are the contact pairs.

The mesh is structured around the contact (a grid cut into tetrahedra, see
meshes/blocks.geo), so that every contact node has the same patch of elements,
and unstructured elsewhere.  Mesh levels scale every element size at once:
level n uses LEVEL_SCALE[n] times the default level's sizes (grid spacing,
unstructured size around the grid, its growth with distance, far field), so
that each level is close to a uniform refinement of the one before, by
LEVEL_RATIO = sqrt 2.  gmsh runs on one thread with a fixed seed: the same
scene and level give the same mesh, node for node.
"""

from __future__ import annotations

import importlib.resources
import logging
import time
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from skfem import MeshTet

from ..errors import FEMValidationError
from ..fe.surface import lumped_area
from ..scenes import Scene

log = logging.getLogger("fem_validation")

#: The geometry file, looked up by :func:`geometry_file`.
GEOMETRY = "blocks.geo"

#: Refinement between consecutive levels: every element size divides by this.
LEVEL_RATIO = 2.0 ** 0.5
DEFAULT_LEVEL = 4
#: The levels and their size factors relative to the default level.
LEVEL_SCALE = {n: LEVEL_RATIO ** (DEFAULT_LEVEL - n) for n in range(6)}
#: Grid spacing of the structured block (across the major axis, and in depth) at the
#: default level, in units of b.
HS = 0.05
#: Largest spacing along the major axis over HS, and the semi-major axis per unit of it:
#: st = clip(ea / ANISOTROPY_PER_A, 1, MAX_ANISOTROPY).
MAX_ANISOTROPY = 4.0
ANISOTROPY_PER_A = 2.0
#: Unstructured element size around the structured block at the default level [b], and
#: its growth per unit distance from the zone (both scale with the level).
H0 = 0.07
GRADE = 0.1
#: Block half-width and depth in units of the semi-major axis a.
EXTENT_OVER_A = 40.0
#: Largest element size at the default level, over the block's half-width.
HMAX_OVER_EXTENT = 0.25
#: The structured block covers ZONE times the semi-axes and is ZONE_DEPTH b deep; the
#: unstructured elements keep the size h0 down to H0_DEPTH b.  The largest von Mises
#: stress lies 0.48 b (a circle) to 0.72 b (a/b = 18) deep: measured on alpha 100,
#: level 4, a block 0.7 b deep put the maximum at the grid's edge and missed it by -1.1%
#: (depth -5.9%) in body 2; 1.0 b deep (836k dofs against 705k): -0.36% (depth -1.0%);
#: 1.2 b (923k): -0.29% (+0.5%).
ZONE = 1.25
ZONE_DEPTH = 1.0
H0_DEPTH = 1.3

#: Grid spacing of the structured block per level, in units of b.
LEVEL_H0 = {n: HS * f for n, f in LEVEL_SCALE.items()}
#: The most mesh vertices (both blocks) :func:`build` lets gmsh make.  gmsh took about
#: 1.4 kB of memory per vertex (a 47k-vertex mesh: 64 MB), the quadratic deck model as
#: much again per mid-side node (about 7 per vertex): 2 million vertices are about 3 GB in
#: gmsh and 15 GB for a deck.  The default validation scenes need at most about 1 million
#: at level 5 (crossed-30deg, a whole model), alpha = 1000 (a/b = 68) 1.5 million at
#: level 4; a needle-like contact (a/b in the hundreds and more) at a fine level needs more.
MAX_MESH_NODES = 2_000_000
#: Unstructured vertices per unit volume over h**-3 (h the target size): fitted to gmsh's
#: HXT meshes of blocks.geo (see :func:`estimate_nodes`).
UNSTRUCTURED_DENSITY = 1.1


@dataclass
class BlockMesh:
    """Two tetrahedral meshes and what the solver needs to know about them.

    Attributes
    ----------
    bodies : tuple of skfem.MeshTet
        Body 1 (z >= 0) and body 2 (z <= 0), coordinates in m.
    top, bottom : ndarray of int
        Nodes of body 1 on z = H and of body 2 on z = -H.
    sym_x, sym_y : tuple of two int arrays, or None
        Nodes of (body 1, body 2) on the symmetry planes x = 0 and y = 0
        (quarter model only).
    axis : tuple of two int arrays
        Nodes of (body 1, body 2) on the z axis (x = y = 0), ordered by depth.
    pairs : ndarray of int, shape (n, 2)
        Node of body 1 and node of body 2 at the same point of z = 0.
    pair_area : ndarray, shape (n,)
        Lumped (P1) area of the contact face belonging to each pair [m**2].
    triangles : ndarray of int, shape (m, 3)
        The contact face's triangles, as indices into ``pairs``.
    h0 : float
        Grid spacing of the structured block across the major axis [m] (sets the
        penalty stiffness).
    quarter : bool
        True for the quarter model (x >= 0, y >= 0).
    extent, depth : float
        Half-width and depth of each block [m].
    level : int
        The mesh level.
    parameters : dict
        The ONELAB parameters of meshes/blocks.geo that made it (units of b).
    """

    bodies: tuple[MeshTet, MeshTet]
    top: np.ndarray
    bottom: np.ndarray
    sym_x: tuple[np.ndarray, np.ndarray] | None
    sym_y: tuple[np.ndarray, np.ndarray] | None
    axis: tuple[np.ndarray, np.ndarray]
    pairs: np.ndarray
    pair_area: np.ndarray
    triangles: np.ndarray
    h0: float
    quarter: bool
    extent: float
    depth: float
    level: int
    parameters: dict


def geometry_file(name: str = GEOMETRY):
    """The geometry file ``name``: packaged beside the code, else in the checkout's meshes/.

    Looks first for ``importlib.resources.files("fem_validation") / "meshes" / name``
    (where a wheel carries it), then for ``meshes/name`` beside the package in a
    source checkout.

    Returns
    -------
    importlib.resources.abc.Traversable or pathlib.Path
        Use with :func:`importlib.resources.as_file` to get a path on disk.

    Raises
    ------
    FEMValidationError
        If neither exists.
    """
    packaged = importlib.resources.files("fem_validation") / "meshes" / name
    if packaged.is_file():
        return packaged
    source = Path(__file__).resolve().parents[2] / "meshes" / name
    if source.is_file():
        return source
    raise FEMValidationError(f"geometry {name!r} not found: neither {packaged} (installed "
                             f"package) nor {source} (source checkout) exists")


def anisotropy(ellipticity: float) -> float:
    """Spacing along the major axis over the spacing across it in the structured block.

    ``clip(a / b / ANISOTROPY_PER_A, 1, MAX_ANISOTROPY)``: the spacing stays
    about 2.5% of a along the major axis, at most 4 times the spacing across.
    """
    if not ellipticity >= 1:
        raise ValueError(f"ellipticity must be >= 1, got {ellipticity!r}")
    return min(max(ellipticity / ANISOTROPY_PER_A, 1.0), MAX_ANISOTROPY)


def mesh_parameters(scene: Scene, level: int = DEFAULT_LEVEL) -> dict[str, float]:
    """ONELAB parameters of meshes/blocks.geo for a scene at a level (lengths in units of b).

    Parameters
    ----------
    scene : Scene
        The scene; its Hertz ellipse at the target load sets the refined zone.
    level : int
        Mesh level, a key of :data:`LEVEL_SCALE`; every element size is
        LEVEL_SCALE[level] times the default level's.

    Returns
    -------
    dict
        L, H, quarter, ea, eb, etheta, zone, zi, hs, st, zz, h0, grade, hmax.
    """
    if level not in LEVEL_SCALE:
        raise ValueError(f"level must be one of {sorted(LEVEL_SCALE)}, got {level!r}")
    c = scene.hertz()
    f = LEVEL_SCALE[level]
    extent = EXTENT_OVER_A * c.ellipticity
    return {"L": extent, "H": extent, "quarter": 1.0 if scene.symmetric else 0.0,
            "ea": c.ellipticity, "eb": 1.0, "etheta": c.major_axis_angle, "zone": ZONE,
            "zi": ZONE_DEPTH, "hs": HS * f, "st": anisotropy(c.ellipticity),
            "zz": H0_DEPTH, "h0": H0 * f, "grade": GRADE * f,
            "hmax": HMAX_OVER_EXTENT * extent * f}


def _axis_cells(inner: float, outer: float, step: float) -> tuple[np.ndarray, np.ndarray]:
    """Cell midpoints and widths on [0, outer]: uniform up to ``inner``, geometric beyond."""
    inner = min(inner, outer)
    edges = np.linspace(0.0, inner, 17)
    if outer > inner:
        edges = np.concatenate([edges, inner + np.geomspace(min(step, outer - inner) * 1e-2,
                                                            outer - inner, 48)])
    return 0.5 * (edges[1:] + edges[:-1]), np.diff(edges)


def estimate_nodes(params: dict) -> float:
    """The number of mesh vertices (both blocks) that :func:`build` would make.

    The structured block holds one vertex per grid cell (spacing hs across the
    major axis and in depth, st hs along it); elsewhere the target size h
    of meshes/blocks.geo (h0 growing by ``grade`` per unit distance from the
    zone, at most hmax) gives UNSTRUCTURED_DENSITY / h**3 vertices per unit
    volume, integrated over the blocks (taken as squares in the ellipse's frame).
    Within a factor of 1.5 of gmsh's count on the default scenes at levels 0-3
    (measured); used to refuse a mesh before gmsh runs.

    Parameters
    ----------
    params : dict
        The parameters of :func:`mesh_parameters` (units of b).

    Returns
    -------
    float
        The estimated number of vertices [-].
    """
    ext, depth = params["L"], params["H"]
    xi, yi = params["zone"] * params["ea"], params["zone"] * params["eb"]
    hs, st, zi, zz = params["hs"], params["st"], params["zi"], params["zz"]
    x, dx = _axis_cells(xi, ext, params["h0"])
    y, dy = _axis_cells(yi, ext, params["h0"])
    z, dz = _axis_cells(max(zi, zz), depth, params["h0"])
    gx = np.maximum(x - xi, 0.0)[:, None, None]
    gy = np.maximum(y - yi, 0.0)[None, :, None]
    gz = np.maximum(z - zz, 0.0)[None, None, :]
    h = np.minimum(params["hmax"], params["h0"] + params["grade"]
                   * np.sqrt(gx * gx + gy * gy + gz * gz))
    density = UNSTRUCTURED_DENSITY / h ** 3
    grid = ((x <= xi)[:, None, None] & (y <= yi)[None, :, None] & (z <= zi)[None, None, :])
    density = np.where(grid, 1.0 / (hs * hs * st * hs), density)
    octant = float(np.einsum("ijk,i,j,k->", density, dx, dy, dz))
    # the octant x, y, z >= 0 of the ellipse's frame: 2 (quarter: z < 0 too) or 8 of them
    return octant * (2.0 if params["quarter"] else 8.0)


def check_mesh_size(params: dict, what: str) -> float:
    """The estimate of :func:`estimate_nodes`, or ValueError above :data:`MAX_MESH_NODES`.

    ``what`` names the scene and level in the message.
    """
    nodes = estimate_nodes(params)
    if not nodes <= MAX_MESH_NODES:
        raise ValueError(f"{what}: the blocks' mesh would have about {nodes:.3g} vertices, more "
                         f"than the {MAX_MESH_NODES:.3g} allowed (memory: about 1.4 kB each in "
                         f"gmsh): lower the level, or make the contact less elongated (a/b = "
                         f"{params['ea'] / params['eb']:.3g})")
    return nodes


def _physical(gmsh, dim: int, name: str) -> int:
    for d, tag in gmsh.model.getPhysicalGroups(dim):
        if gmsh.model.getPhysicalName(d, tag) == name:
            return tag
    raise FEMValidationError(f"the geometry defines no physical group {name!r} "
                             f"(dimension {dim})")


def _elements(gmsh, dim: int, name: str, etype: int, nnodes: int) -> np.ndarray:
    """Connectivity (gmsh node tags) of the elements of one type in a physical group."""
    blocks = []
    for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, _physical(gmsh, dim, name)):
        types, _, nodes = gmsh.model.mesh.getElements(dim, entity)
        for t, conn in zip(types, nodes, strict=True):
            if dim == 3 and t != etype:
                raise FEMValidationError(f"gmsh returned element type {t} in {name}, "
                                         f"expected linear tetrahedra ({etype})")
            if t == etype:
                blocks.append(np.asarray(conn, dtype=np.int64).reshape(-1, nnodes))
    if not blocks:
        raise FEMValidationError(f"physical group {name!r} has no elements of type {etype}")
    return np.concatenate(blocks)


def _group_nodes(gmsh, dim: int, name: str) -> np.ndarray:
    tags, _ = gmsh.model.mesh.getNodesForPhysicalGroup(dim, _physical(gmsh, dim, name))
    return np.asarray(tags, dtype=np.int64)


def positively_oriented(p: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Tetrahedra ``t`` (n, 4) reordered to positive volume on nodes ``p`` (m, 3).

    Raises
    ------
    FEMValidationError
        If a tetrahedron is degenerate (zero volume).
    """
    v = p[t]
    vol = np.einsum("ij,ij->i", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]),
                    v[:, 3] - v[:, 0])
    if np.any(vol == 0):
        raise FEMValidationError(f"{int(np.sum(vol == 0))} degenerate tetrahedra")
    t = t.copy()
    t[vol < 0] = t[vol < 0][:, [0, 2, 1, 3]]
    return t


class _Numbering:
    """Local node numbers of one body: gmsh tag -> index, -1 where absent."""

    def __init__(self, tets: np.ndarray, max_tag: int):
        self.tags = np.unique(tets)
        self.local = np.full(max_tag + 1, -1, dtype=np.int64)
        self.local[self.tags] = np.arange(len(self.tags))

    def __call__(self, tags: np.ndarray, only_present: bool = False) -> np.ndarray:
        out = self.local[tags]
        if only_present:
            return out[out >= 0]
        if np.any(out < 0):
            raise FEMValidationError("a boundary node is not a node of its body's mesh")
        return out


def build(scene: Scene, level: int = DEFAULT_LEVEL, parameters: dict | None = None,
          ) -> BlockMesh:
    """Mesh the scene's two blocks at a mesh level.

    Parameters
    ----------
    scene : Scene
        The scene to mesh.
    level : int
        Mesh level (keys of :data:`LEVEL_SCALE`; 0 coarse).
    parameters : dict, optional
        Overrides of :func:`mesh_parameters` (units of b), for experiments.

    Returns
    -------
    BlockMesh

    Raises
    ------
    ValueError
        If the mesh would have more than :data:`MAX_MESH_NODES` vertices
        (:func:`estimate_nodes`, before gmsh runs).
    FEMValidationError
        If gmsh fails or the geometry lacks a physical group the solver needs.
    """
    import gmsh

    params = {**mesh_parameters(scene, level), **(parameters or {})}
    check_mesh_size(params, f"scene {scene.name!r} at level {level}")
    b = scene.hertz().b
    t0 = time.perf_counter()
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        for key, value in params.items():
            gmsh.onelab.setNumber(f"Parameters/{key}", [float(value)])
        with importlib.resources.as_file(geometry_file()) as geo:
            gmsh.open(str(geo))
        # after the file, so that it cannot override: deterministic meshes
        gmsh.option.setNumber("General.NumThreads", 1)
        gmsh.option.setNumber("Mesh.RandomSeed", 1)
        gmsh.model.mesh.generate(3)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        tags = np.asarray(tags, dtype=np.int64)
        coords = np.zeros((tags.max() + 1, 3))
        coords[tags] = np.asarray(xyz).reshape(-1, 3)
        tets = [_elements(gmsh, 3, name, 4, 4) for name in ("body1", "body2")]
        contact = _group_nodes(gmsh, 2, "contact")
        face = _elements(gmsh, 2, "contact", 2, 3)
        boundary = {name: _group_nodes(gmsh, 2, name) for name in ("top", "bottom")}
        if params["quarter"]:
            for name in ("sym_x", "sym_y"):
                boundary[name] = _group_nodes(gmsh, 2, name)
        axis = _group_nodes(gmsh, 1, "axis")
    except FEMValidationError:
        raise
    except Exception as exc:  # gmsh reports its failures as plain Exceptions
        raise FEMValidationError(f"gmsh failed to mesh {scene.name} at level {level} "
                                 f"(parameters {params}): {exc}") from exc
    finally:
        gmsh.finalize()
    seconds = time.perf_counter() - t0

    coords *= b
    numbering = [_Numbering(t, len(coords) - 1) for t in tets]
    bodies = tuple(_body(coords, n, t) for n, t in zip(numbering, tets, strict=True))
    pairs = np.column_stack([numbering[0](contact), numbering[1](contact)])
    pair_of = np.full(len(coords), -1, dtype=np.int64)
    pair_of[contact] = np.arange(len(contact))
    triangles = pair_of[face]
    sym = {}
    if params["quarter"]:
        for name in ("sym_x", "sym_y"):
            sym[name] = tuple(n(boundary[name], only_present=True) for n in numbering)
    axis_nodes = []
    for i, n in enumerate(numbering):
        nodes = n(axis, only_present=True)
        depth = np.abs(bodies[i].p[2, nodes])
        axis_nodes.append(nodes[np.argsort(depth, kind="stable")])
    xy = bodies[0].p[:2, pairs[:, 0]].T
    out = BlockMesh(bodies, numbering[0](boundary["top"]), numbering[1](boundary["bottom"]),
                    sym.get("sym_x"), sym.get("sym_y"), tuple(axis_nodes), pairs,
                    lumped_area(xy, triangles), triangles, params["hs"] * b,
                    bool(params["quarter"]), params["L"] * b, params["H"] * b, level, params)
    log.info("%s: meshed level %d in %.1f s: %d + %d tetrahedra, %d contact pairs, "
             "spacing %.3g b x %.3g", scene.name, level, seconds, bodies[0].nelements,
             bodies[1].nelements, len(pairs), params["hs"], params["st"])
    return out


def _body(coords: np.ndarray, numbering: _Numbering, tets: np.ndarray) -> MeshTet:
    """A MeshTet with the body's own node numbering, positively oriented."""
    p = coords[numbering.tags]
    t = positively_oriented(p, numbering(tets))
    return MeshTet(np.ascontiguousarray(p.T), np.ascontiguousarray(t.T))


def mirrored(mesh: BlockMesh) -> BlockMesh:
    """The same blocks with body 2 replaced by body 1's mirror image in z = 0.

    Node i of body 2 is then the mirror of node i of body 1, so that the
    contact pairs are (i, i).  With elastically similar bodies this makes the
    discrete model symmetric under the mirror, as the half-spaces are: a
    tangential traction then changes the gap nowhere (Mindlin's uncoupled
    problem holds for the discrete model too, not only in the limit).
    """
    m1 = mesh.bodies[0]
    p2 = m1.p * np.array([[1.0], [1.0], [-1.0]])
    t2 = m1.t[[0, 2, 1, 3]]  # the mirror turns every tetrahedron inside out
    body2 = MeshTet(np.ascontiguousarray(p2), np.ascontiguousarray(t2))
    pairs = np.column_stack([mesh.pairs[:, 0], mesh.pairs[:, 0]])
    sym = {name: (s[0], s[0]) if s is not None else None
           for name, s in (("sym_x", mesh.sym_x), ("sym_y", mesh.sym_y))}
    axis = (mesh.axis[0], mesh.axis[0])
    return replace(mesh, bodies=(m1, body2), bottom=mesh.top, pairs=pairs, axis=axis, **sym)
