"""Mesh the two blocks of a scene with gmsh (meshes/blocks.geo) and split them.

The geometry is parametrised in units of the Hertz minor semi-axis b at the
scene's target load; node coordinates are returned in metres.  The blocks are
meshed together so that their faces at z = 0 match node for node; each body
then gets its own copy of those nodes, and the copies are the contact pairs.
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from skfem import MeshTet

from .errors import FEMValidationError
from .scenes import Scene

log = logging.getLogger("fem_validation")

def _geometry_path(name: str = "blocks.geo") -> Path:
    """The geometry: packaged beside the code (where a wheel carries it, copied from meshes/
    by setup.py), else in the source checkout's meshes/ (the place to read and edit it)."""
    packaged = Path(__file__).resolve().parent / "meshes" / name
    return packaged if packaged.is_file() else Path(__file__).resolve().parents[1] / "meshes" / name


GEO = _geometry_path()

#: Element size in the contact zone, in units of b, for each mesh level.
LEVEL_H0 = {0: 0.4, 1: 0.2, 2: 0.1, 3: 0.05}
DEFAULT_LEVEL = 3
#: Block half-width and depth in units of the semi-major axis a.
EXTENT_OVER_A = 40.0
#: Element size at the edge of the contact ellipse, relative to h0.
EDGE_REFINEMENT = 0.5
#: Depth of the refined zone in units of b.
ZONE_DEPTH = 0.6


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
    pairs : ndarray of int, shape (n, 2)
        Node of body 1 and node of body 2 at the same point of z = 0.
    pair_area : ndarray, shape (n,)
        Lumped (P1) area of the contact face belonging to each pair [m**2].
    triangles : ndarray of int, shape (m, 3)
        The contact face's triangles, as indices into ``pairs``.
    h0 : float
        Element size in the contact zone [m].
    quarter : bool
        True for the quarter model (x >= 0, y >= 0).
    extent, depth : float
        Half-width and depth of each block [m].
    """

    bodies: tuple[MeshTet, MeshTet]
    top: np.ndarray
    bottom: np.ndarray
    sym_x: tuple[np.ndarray, np.ndarray] | None
    sym_y: tuple[np.ndarray, np.ndarray] | None
    pairs: np.ndarray
    pair_area: np.ndarray
    triangles: np.ndarray
    h0: float
    quarter: bool
    extent: float
    depth: float


def mesh_parameters(scene: Scene, level: int) -> dict[str, float]:
    """ONELAB parameters of meshes/blocks.geo for a scene (lengths in units of b)."""
    if level not in LEVEL_H0:
        raise ValueError(f"level must be one of {sorted(LEVEL_H0)}, got {level!r}")
    c = scene.hertz()
    extent = EXTENT_OVER_A * c.ellipticity
    h0 = LEVEL_H0[level]
    return {"L": extent, "H": extent, "quarter": 1.0 if scene.symmetric else 0.0,
            "ea": c.ellipticity, "eb": 1.0, "etheta": c.major_axis_angle, "zone": 1.2,
            "rz": ZONE_DEPTH, "h0": h0, "he": EDGE_REFINEMENT * h0, "grade": 0.3, "ge": 0.5,
            "hmax": extent / 4}


def _tets_of(gmsh, name: str) -> np.ndarray:
    tag = _physical(gmsh, 3, name)
    blocks = []
    for entity in gmsh.model.getEntitiesForPhysicalGroup(3, tag):
        types, _, nodes = gmsh.model.mesh.getElements(3, entity)
        for etype, conn in zip(types, nodes, strict=True):
            if etype != 4:
                raise FEMValidationError(f"gmsh returned element type {etype} in {name}, "
                                         "expected linear tetrahedra (4)")
            blocks.append(np.asarray(conn, dtype=np.int64).reshape(-1, 4))
    return np.concatenate(blocks)


def _physical(gmsh, dim: int, name: str) -> int:
    for d, tag in gmsh.model.getPhysicalGroups(dim):
        if gmsh.model.getPhysicalName(d, tag) == name:
            return tag
    raise FEMValidationError(f"meshes/blocks.geo defines no physical group {name!r} "
                             f"(dimension {dim})")


def _surface_nodes(gmsh, name: str) -> np.ndarray:
    tags, _ = gmsh.model.mesh.getNodesForPhysicalGroup(2, _physical(gmsh, 2, name))
    return np.asarray(tags, dtype=np.int64)


def _surface_triangles(gmsh, name: str) -> np.ndarray:
    out = []
    for entity in gmsh.model.getEntitiesForPhysicalGroup(2, _physical(gmsh, 2, name)):
        types, _, nodes = gmsh.model.mesh.getElements(2, entity)
        for etype, conn in zip(types, nodes, strict=True):
            if etype == 2:
                out.append(np.asarray(conn, dtype=np.int64).reshape(-1, 3))
    return np.concatenate(out)


def _body_mesh(coords_of, tets: np.ndarray, scale: float):
    """A MeshTet with its own node numbering, and the map gmsh tag -> local index."""
    tags = np.unique(tets)
    local = {int(t): i for i, t in enumerate(tags)}
    index = np.vectorize(local.__getitem__, otypes=[np.int64])
    t = index(tets)
    p = coords_of(tags) * scale
    # positive orientation for scikit-fem
    v = p[t]
    vol = np.einsum("ij,ij->i", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]), v[:, 3] - v[:, 0])
    t[vol < 0] = t[vol < 0][:, [0, 2, 1, 3]]
    return MeshTet(p.T, t.T), local


def build(scene: Scene, level: int = DEFAULT_LEVEL) -> BlockMesh:
    """Mesh the scene's two blocks at a mesh level (0 coarse .. 3 fine)."""
    import gmsh

    if not GEO.exists():
        raise FEMValidationError(f"scene geometry {GEO} not found: fem_validation runs from "
                                 "a source checkout (pip install -e '.[fem]')")
    params = mesh_parameters(scene, level)
    b = scene.hertz().b
    t0 = time.perf_counter()
    gmsh.initialize(interruptible=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 2)
        for key, value in params.items():
            gmsh.onelab.setNumber(f"Parameters/{key}", [value])
        gmsh.open(str(GEO))
        gmsh.model.mesh.generate(3)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        tags = np.asarray(tags, dtype=np.int64)
        order = np.argsort(tags)
        tags, xyz = tags[order], np.asarray(xyz).reshape(-1, 3)[order]

        def coords_of(t):
            return xyz[np.searchsorted(tags, t)]

        mesh1, local1 = _body_mesh(coords_of, _tets_of(gmsh, "body1"), b)
        mesh2, local2 = _body_mesh(coords_of, _tets_of(gmsh, "body2"), b)
        contact_tags = _surface_nodes(gmsh, "contact")
        pairs = np.array([[local1[int(t)], local2[int(t)]] for t in contact_tags], dtype=np.int64)
        pair_of = {int(t): i for i, t in enumerate(contact_tags)}
        tri = np.vectorize(pair_of.__getitem__, otypes=[np.int64])(
            _surface_triangles(gmsh, "contact"))
        top = np.array([local1[int(t)] for t in _surface_nodes(gmsh, "top")], dtype=np.int64)
        bottom = np.array([local2[int(t)] for t in _surface_nodes(gmsh, "bottom")],
                          dtype=np.int64)
        sym = {}
        if params["quarter"]:
            for name in ("sym_x", "sym_y"):
                nodes = _surface_nodes(gmsh, name)
                sym[name] = (np.array([local1[int(t)] for t in nodes if int(t) in local1]),
                             np.array([local2[int(t)] for t in nodes if int(t) in local2]))
    except FEMValidationError:
        raise
    except Exception as exc:  # gmsh reports its failures as plain Exceptions
        raise FEMValidationError(f"gmsh failed to mesh {scene.name} at level {level} "
                                 f"(parameters {params}): {exc}") from exc
    finally:
        gmsh.finalize()

    xy = mesh1.p[:2, pairs[:, 0]].T
    area = _lumped_area(xy, tri)
    out = BlockMesh((mesh1, mesh2), top, bottom, sym.get("sym_x"), sym.get("sym_y"), pairs,
                    area, tri, params["h0"] * b, bool(params["quarter"]), params["L"] * b,
                    params["H"] * b)
    log.info("%s: meshed level %d in %.1f s: %d + %d tetrahedra, %d contact pairs, "
             "h0 = %.3g b", scene.name, level, time.perf_counter() - t0, mesh1.nelements,
             mesh2.nelements, len(pairs), params["h0"])
    return out


def _lumped_area(xy: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """Each node's third of the area of its triangles (the P1 lumped face mass)."""
    d1, d2 = xy[tri[:, 1]] - xy[tri[:, 0]], xy[tri[:, 2]] - xy[tri[:, 0]]
    tri_area = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    area = np.zeros(len(xy))
    np.add.at(area, tri.ravel(), np.repeat(tri_area / 3, 3))
    return area
