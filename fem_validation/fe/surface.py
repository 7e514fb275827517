"""Surface geometry that knows no scene: triangles and lumped areas of a contact
face, and the rotation of a body's frame into the contact ellipse's."""

from __future__ import annotations

import math

import numpy as np


def lumped_area(xy: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """Each node's third of the area of its triangles (the P1 lumped face mass) [m**2].

    Parameters
    ----------
    xy : ndarray, shape (n, 2)
        Node coordinates [m].
    tri : ndarray of int, shape (m, 3)
        Triangles as indices into ``xy``.
    """
    d1, d2 = xy[tri[:, 1]] - xy[tri[:, 0]], xy[tri[:, 2]] - xy[tri[:, 0]]
    tri_area = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    area = np.zeros(len(xy))
    np.add.at(area, tri.ravel(), np.repeat(tri_area / 3, 3))
    return area


def surface_triangles(xy: np.ndarray) -> np.ndarray:
    """A Delaunay triangulation of points (n, 2) in the contact plane, (m, 3).

    For results that give no surface triangles.  Slivers along the convex hull
    (aspect ratio above 50) are dropped: they join nodes that are not neighbours
    on a surface whose outline is not convex.
    """
    from scipy.spatial import Delaunay

    tri = Delaunay(xy).simplices
    p = xy[tri]
    e = np.linalg.norm(p - np.roll(p, 1, axis=1), axis=2)
    d1, d2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    area = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    keep = area > e.max(axis=1) ** 2 / 50 / 2
    return tri[keep]


def ellipse_rotation(theta: float, body: int) -> np.ndarray:
    """Rows: the ellipse frame's axes in the contact frame, for body 1 or 2.

    x along the major axis (at angle ``theta`` [rad] from the frame's x axis),
    y along the minor axis, z into the body (the frame's normal for body 1, its
    opposite for body 2).  A tensor S in the contact frame is R S R^T in the
    ellipse frame.
    """
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0 if body == 1 else -1.0]])


def interpolate(m, nodal: np.ndarray, points: np.ndarray, neighbours: int = 32) -> np.ndarray:
    """Piecewise-linear interpolation of nodal values at points of a tetrahedral mesh.

    Parameters
    ----------
    m : object with ``p`` (3, n) node coordinates and ``t`` (4, e) tetrahedra
        (a skfem.MeshTet, or a SimpleNamespace)
    nodal : ndarray, shape (n, ...)
        Values at the mesh's nodes.
    points : ndarray, shape (k, 3)
        Points in the mesh [m].
    neighbours : int
        Elements tried per point: those with the nearest centroids (then 20 times
        more for points not found).

    Raises
    ------
    ValueError
        If a point lies outside the mesh.
    """
    from scipy.spatial import cKDTree

    lo, hi = points.min(axis=0), points.max(axis=0)
    margin = 0.05 * (hi - lo).max() + 1e-12
    box = np.all((m.p[:, m.t].min(axis=1).T <= hi + margin)
                 & (m.p[:, m.t].max(axis=1).T >= lo - margin), axis=1)
    elements = np.nonzero(box)[0]
    if not len(elements):
        raise ValueError(f"the points lie outside the mesh, e.g. {points[0]}")
    vertices = m.p.T[m.t[:, elements].T]  # (e, 4, 3)
    jacobian = (vertices[:, 1:] - vertices[:, :1]).transpose(0, 2, 1)
    volume = np.abs(np.linalg.det(jacobian))
    flat = volume <= 1e-12 * volume.max()
    if flat.any():  # degenerate tetrahedra (a Delaunay of a regular grid) hold no point
        elements, vertices, jacobian = elements[~flat], vertices[~flat], jacobian[~flat]
    inverse = np.linalg.inv(jacobian)
    tree = cKDTree(vertices.mean(axis=1))

    def barycentric(candidates, pts):
        lam = np.einsum("kcij,kcj->kci", inverse[candidates],
                        pts[:, None, :] - vertices[candidates, 0])
        return np.concatenate([1 - lam.sum(axis=2, keepdims=True), lam], axis=2)

    best_elem = np.zeros(len(points), dtype=np.int64)
    best_lam = np.zeros((len(points), 4))
    todo = np.arange(len(points))
    for k in (neighbours, 20 * neighbours):
        k = min(k, len(elements))
        candidates = tree.query(points[todo], k)[1].reshape(len(todo), k)
        lam = barycentric(candidates, points[todo])
        j = np.argmax(lam.min(axis=2), axis=1)
        rows = np.arange(len(todo))
        best_elem[todo] = candidates[rows, j]
        best_lam[todo] = lam[rows, j]
        todo = todo[best_lam[todo].min(axis=1) < -1e-9]
        if not len(todo):
            break
    if len(todo):
        raise ValueError(f"{len(todo)} points lie outside the mesh, e.g. {points[todo[0]]}")
    corners = m.t[:, elements[best_elem]].T  # (k, 4)
    return np.einsum("kc,kc...->k...", best_lam, nodal[corners])
