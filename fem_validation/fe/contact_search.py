"""Node-to-surface contact search between non-matching surface meshes.

Slave points (nodes of one body's surface) are projected onto the master
surface (triangles of the other body's boundary): the closest point of the
triangulated surface, found with k-d trees over the triangles' centroids and
certified against every triangle (:func:`project`).  The gap of a slave
node is measured along the outward normal n of the master triangle it
projects onto,

    g = n . (x_s - x_c) + n . (u_s - sum_j N_j u_j),

x_c the closest point, N_j its barycentric coordinates in the triangle and
u_j the master nodes' displacements: the gap linearised about the undeformed
geometry (small strain), g = g0 + C u with a constant operator C
(:func:`gap_operator`).  Lengths are in metres (any consistent unit works).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import sparse
from scipy.spatial import cKDTree

#: Triangles of the first guess per slave point (see :func:`project`).
CANDIDATES = 16


def closest_point_on_triangles(points: np.ndarray, tri: np.ndarray,
                               ) -> tuple[np.ndarray, np.ndarray]:
    """Closest point of each triangle to each point (paired, vectorised).

    Parameters
    ----------
    points : ndarray, shape (n, 3)
        Points [m].
    tri : ndarray, shape (n, 3, 3)
        tri[i, j] is vertex j of the triangle paired with point i [m].

    Returns
    -------
    closest : ndarray, shape (n, 3)
        The closest points [m].
    bary : ndarray, shape (n, 3)
        Their barycentric coordinates (non-negative, summing to 1).
    """
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    v0, v1, v2 = b - a, c - a, points - a
    d00 = np.einsum("ij,ij->i", v0, v0)
    d01 = np.einsum("ij,ij->i", v0, v1)
    d11 = np.einsum("ij,ij->i", v1, v1)
    d20 = np.einsum("ij,ij->i", v2, v0)
    d21 = np.einsum("ij,ij->i", v2, v1)
    denom = d00 * d11 - d01 * d01
    v = (d11 * d20 - d01 * d21) / denom
    w = (d00 * d21 - d01 * d20) / denom
    bary = np.column_stack([1 - v - w, v, w])
    outside = np.any(bary < 0, axis=1)
    if np.any(outside):
        p, best, best_bary = points[outside], None, None
        corners = (a[outside], b[outside], c[outside])
        for i, j in ((0, 1), (1, 2), (2, 0)):
            e0, e1 = corners[i], corners[j]
            d = e1 - e0
            t = np.clip(np.einsum("ij,ij->i", p - e0, d) / np.einsum("ij,ij->i", d, d), 0, 1)
            q = e0 + t[:, None] * d
            dist = np.einsum("ij,ij->i", p - q, p - q)
            bb = np.zeros((len(p), 3))
            bb[:, i], bb[:, j] = 1 - t, t
            if best is None:
                best, best_bary = dist, bb
            else:
                closer = dist < best
                best = np.where(closer, dist, best)
                best_bary[closer] = bb[closer]
        bary[outside] = best_bary
    closest = np.einsum("ij,ijk->ik", bary, tri)
    return closest, bary


def outward_normals(p: np.ndarray, t: np.ndarray, facets: np.ndarray) -> np.ndarray:
    """Unit normals of boundary triangles, pointing out of the body.

    Parameters
    ----------
    p : ndarray, shape (3, n)
        Node coordinates [m].
    t : ndarray of int, shape (4, m)
        Tetrahedra.
    facets : ndarray of int, shape (k, 3)
        Boundary triangles (node indices); each must be a face of one tetrahedron.

    Returns
    -------
    ndarray, shape (k, 3)

    Raises
    ------
    ValueError
        If a triangle is not a face of any tetrahedron.
    """
    n = p.shape[1]
    faces = np.array([[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])
    opposite = np.array([3, 2, 1, 0])

    def key(tri):
        s = np.sort(tri, axis=1).astype(np.int64)
        return (s[:, 0] * n + s[:, 1]) * n + s[:, 2]

    tet_keys = np.concatenate([key(t[f].T) for f in faces])
    tet_opp = np.concatenate([t[o] for o in opposite])
    order = np.argsort(tet_keys, kind="stable")
    fkey = key(facets)
    pos = np.clip(np.searchsorted(tet_keys[order], fkey), 0, len(order) - 1)
    if np.any(tet_keys[order][pos] != fkey):
        raise ValueError("a facet is not a face of any tetrahedron")
    opp = p[:, tet_opp[order][pos]].T
    x = p[:, facets.T]  # (3, 3 corners, k)
    normal = np.cross((x[:, 1] - x[:, 0]).T, (x[:, 2] - x[:, 0]).T)
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    inward = np.einsum("ij,ij->i", normal, opp - x[:, 0].T) > 0
    normal[inward] *= -1
    return normal


def surface_lumped_area(xyz: np.ndarray, tri: np.ndarray, n: int) -> np.ndarray:
    """Each node's third of the area of its surface triangles (P1 lumped mass) [m**2].

    Parameters
    ----------
    xyz : ndarray, shape (N, 3)
        Node coordinates [m].
    tri : ndarray of int, shape (m, 3)
        Triangles (indices into ``xyz``).
    n : int
        Length of the result (the number of nodes).
    """
    x = xyz[tri]
    area = 0.5 * np.linalg.norm(np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]), axis=1)
    out = np.zeros(n)
    np.add.at(out, tri.ravel(), np.repeat(area / 3, 3))
    return out


@dataclass
class Projection:
    """Slave points projected onto a master surface.

    Attributes
    ----------
    triangle : ndarray of int, shape (n,)
        Index of the master triangle each point projects onto.
    bary : ndarray, shape (n, 3)
        Barycentric coordinates of the closest point in it.
    closest : ndarray, shape (n, 3)
        The closest points [m].
    normal : ndarray, shape (n, 3)
        Outward unit normal of that master triangle.
    gap : ndarray, shape (n,)
        Signed gap n . (x - closest) [m], positive outside the master body.
    distance : ndarray, shape (n,)
        |x - closest| [m].
    """

    triangle: np.ndarray
    bary: np.ndarray
    closest: np.ndarray
    normal: np.ndarray
    gap: np.ndarray
    distance: np.ndarray


def project(points: np.ndarray, xyz: np.ndarray, tri: np.ndarray, normals: np.ndarray,
            candidates: int = CANDIDATES) -> Projection:
    """Project points onto a triangulated surface: the closest point, certified.

    A first guess from the k triangles with the nearest centroids gives an
    upper bound d_ub of each point's distance.  A triangle of circumradius
    about r (largest centroid-to-vertex distance) can only be closer if its
    centroid lies within d_ub + r of the point; the triangles are binned by r
    (factors of 2), and every bin is searched within d_ub + its largest r, so
    the answer is exact for any mix of element sizes.

    Parameters
    ----------
    points : ndarray, shape (n, 3)
        Slave points [m].
    xyz : ndarray, shape (N, 3)
        Master nodes [m].
    tri : ndarray of int, shape (m, 3)
        Master triangles.
    normals : ndarray, shape (m, 3)
        Their outward unit normals (:func:`outward_normals`).
    candidates : int
        Triangles of the first guess per point.
    """
    corners = xyz[tri]
    centroid = corners.mean(axis=1)
    radius = np.linalg.norm(corners - centroid[:, None], axis=2).max(axis=1)
    n = len(points)
    k = min(candidates, len(tri))
    _, idx = cKDTree(centroid).query(points, k=k)
    idx = idx.reshape(n, -1)
    rep = np.repeat(points, k, axis=0)
    closest, _ = closest_point_on_triangles(rep, corners[idx.ravel()])
    upper = np.linalg.norm(rep - closest, axis=1).reshape(n, k).min(axis=1)
    pt, tt = [], []
    bins = np.floor(np.log2(radius / radius.min())).astype(int)
    for b in np.unique(bins):
        members = np.nonzero(bins == b)[0]
        near = cKDTree(centroid[members]).query_ball_point(points,
                                                           upper + radius[members].max())
        counts = np.fromiter((len(c) for c in near), dtype=np.int64, count=n)
        pt.append(np.repeat(np.arange(n), counts))
        tt.append(members[np.concatenate([np.asarray(c, dtype=np.int64) for c in near])])
    pt, tt = np.concatenate(pt), np.concatenate(tt)
    closest, _ = closest_point_on_triangles(points[pt], corners[tt])
    dist = np.linalg.norm(points[pt] - closest, axis=1)
    order = np.lexsort((dist, pt))  # by point, nearest first
    first = order[np.r_[0, np.nonzero(np.diff(pt[order]))[0] + 1]]
    best_t = tt[first]
    closest, bary = closest_point_on_triangles(points, corners[best_t])
    normal = normals[best_t]
    gap = np.einsum("ij,ij->i", normal, points - closest)
    return Projection(best_t, bary, closest, normal, gap, dist[first])


def gap_operator(proj: Projection, slave_dofs: np.ndarray, master_tri_dofs: np.ndarray,
                 ndofs: int) -> sparse.csr_matrix:
    """The linearised gap's operator C: g = g0 + C u (u all dofs, interleaved x, y, z).

    Parameters
    ----------
    proj : Projection
        The slave points' projection.
    slave_dofs : ndarray of int, shape (n,)
        First dof (x component) of each slave node; y and z follow.
    master_tri_dofs : ndarray of int, shape (m, 3)
        First dof of each master triangle's vertices.
    ndofs : int
        Total number of dofs.

    Returns
    -------
    scipy.sparse.csr_matrix, shape (n, ndofs)
        Row i: n_i on the slave node's dofs, -N_ij n_i on vertex j's.
    """
    n = len(slave_dofs)
    nrm = proj.normal
    rows = np.repeat(np.arange(n), 12)
    mdofs = master_tri_dofs[proj.triangle]  # (n, 3)
    cols = np.concatenate([slave_dofs[:, None], mdofs], axis=1)[:, :, None] + np.arange(3)
    weights = np.concatenate([np.ones((n, 1)), -proj.bary], axis=1)  # (n, 4)
    vals = weights[:, :, None] * nrm[:, None, :]
    return sparse.csr_matrix((vals.ravel(), (rows, cols.ravel())), shape=(n, ndofs))
