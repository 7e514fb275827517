"""Linear tetrahedra for isotropic small-strain elasticity: stiffness, stresses, modes.

Pure functions of node coordinates p (3, n) [m] and tetrahedra t (4, m), the
layout of scikit-fem's MeshTet.  Displacements are (n, 3) [m], or flat with
the three components of each node together (dof 3 i + c).  The stiffness is
assembled element by element in chunks, so that its memory is that of the
matrix plus one chunk (scikit-fem's asm holds all 144 entries of every element
at once).
"""

from __future__ import annotations

import numpy as np
from scipy import sparse

#: Elements assembled at once.
CHUNK = 100_000


def lame(E: float, nu: float) -> tuple[float, float]:
    """Lame's parameters (mu, lmbda) [Pa] from Young's modulus E [Pa] and Poisson's ratio.

    Raises
    ------
    ValueError
        If E <= 0 or nu is outside (-1, 0.5).
    """
    if not E > 0:
        raise ValueError(f"E must be > 0, got {E!r}")
    if not -1 < nu < 0.5:
        raise ValueError(f"nu must be in (-1, 0.5), got {nu!r}")
    return E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))


def shape_gradients(p: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Gradients of the four P1 shape functions and the volume of each tetrahedron.

    Parameters
    ----------
    p : ndarray, shape (3, n)
        Node coordinates [m].
    t : ndarray of int, shape (4, m)
        Tetrahedra.

    Returns
    -------
    grad : ndarray, shape (m, 4, 3)
        grad[e, i] is the gradient of vertex i's shape function in element e [1/m].
    volume : ndarray, shape (m,)
        Volumes [m**3] (absolute values: the orientation does not matter).
    """
    v = p.T[t.T]  # (m, 4, 3)
    edges = (v[:, 1:] - v[:, :1]).transpose(0, 2, 1)  # columns are the edges from vertex 0
    inv = np.linalg.inv(edges)  # rows: gradients of the barycentric coordinates 1..3
    grad = np.concatenate([-inv.sum(axis=1, keepdims=True), inv], axis=1)
    return grad, np.abs(np.linalg.det(edges)) / 6.0


def stiffness(p: np.ndarray, t: np.ndarray, E: float, nu: float) -> sparse.csr_matrix:
    """Stiffness matrix of linear tetrahedra [N/m], dofs interleaved (3 i + component).

    Assembled by 3x3 node blocks: the sparsity pattern from the 16 node pairs
    of each element, the blocks summed with one bincount per component.

    Parameters
    ----------
    p : ndarray, shape (3, n)
        Node coordinates [m].
    t : ndarray of int, shape (4, m)
        Tetrahedra.
    E : float
        Young's modulus [Pa].
    nu : float
        Poisson's ratio.

    Returns
    -------
    scipy.sparse.csr_matrix, shape (3 n, 3 n)
    """
    mu, lmbda = lame(E, nu)
    nn = p.shape[1]
    tt = np.asarray(t.T, dtype=np.int64)
    key = (tt[:, :, None] * nn + tt[:, None, :]).ravel()  # node pair (i, j) of each element
    pattern, slot = np.unique(key, return_inverse=True)
    del key
    blocks = np.zeros((len(pattern), 3, 3))
    for start in range(0, tt.shape[0], CHUNK):
        g, vol = shape_gradients(p, t[:, start:start + CHUNK])
        s = slot[16 * start:16 * (start + len(vol))]
        gg = np.einsum("eic,ejc->eij", g, g)
        gv = g * np.sqrt(vol)[:, None, None]
        for a in range(3):
            for b in range(3):
                # k[e, i, j] = V (mu (gi . gj) d_ab + mu gi_b gj_a + lmbda gi_a gj_b)
                k = (mu * gv[:, :, None, b] * gv[:, None, :, a]
                     + lmbda * gv[:, :, None, a] * gv[:, None, :, b])
                if a == b:
                    k += mu * gg * vol[:, None, None]
                blocks[:, a, b] += np.bincount(s, weights=k.ravel(), minlength=len(pattern))
    rows = pattern // nn
    indptr = np.searchsorted(rows, np.arange(nn + 1))
    out = sparse.bsr_matrix((blocks, pattern % nn, indptr), shape=(3 * nn, 3 * nn))
    return out.tocsr()


def element_stress(p: np.ndarray, t: np.ndarray, u: np.ndarray, E: float,
                   nu: float) -> np.ndarray:
    """Cauchy stress of a P1 displacement, constant in each tetrahedron [Pa].

    Parameters
    ----------
    p, t : node coordinates (3, n) [m] and tetrahedra (4, m)
    u : ndarray, shape (n, 3)
        Nodal displacements [m].
    E, nu : Young's modulus [Pa] and Poisson's ratio

    Returns
    -------
    ndarray, shape (m, 3, 3)
        sigma = 2 mu eps + lmbda tr(eps) I, tension positive.
    """
    mu, lmbda = lame(E, nu)
    g, _ = shape_gradients(p, t)
    grad_u = np.einsum("eia,eib->eab", u[t.T], g)  # du_a/dx_b
    eps = 0.5 * (grad_u + grad_u.transpose(0, 2, 1))
    tr = np.trace(eps, axis1=1, axis2=2)
    return 2 * mu * eps + lmbda * tr[:, None, None] * np.eye(3)


def nodal_average(p: np.ndarray, t: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Element values averaged to the nodes, weighted by element volume.

    Parameters
    ----------
    p, t : node coordinates (3, n) [m] and tetrahedra (4, m)
    values : ndarray, shape (m, ...)
        One value (scalar or array) per element.

    Returns
    -------
    ndarray, shape (n, ...)
        NaN at nodes of no element.
    """
    _, vol = shape_gradients(p, t)
    flat = values.reshape(len(vol), -1) * vol[:, None]
    total = np.zeros((p.shape[1], flat.shape[1]))
    weight = np.zeros(p.shape[1])
    for corner in t:
        np.add.at(total, corner, flat)
        np.add.at(weight, corner, vol)
    mean = np.divide(total, weight[:, None], out=np.full_like(total, np.nan),
                     where=weight[:, None] > 0)
    return mean.reshape((p.shape[1],) + values.shape[1:])


def von_mises(stress: np.ndarray) -> np.ndarray:
    """Von Mises equivalent stress of stress tensors (..., 3, 3) [Pa]."""
    tr = np.trace(stress, axis1=-2, axis2=-1)
    dev = stress - tr[..., None, None] / 3 * np.eye(3)
    return np.sqrt(1.5 * np.einsum("...ij,...ij->...", dev, dev))


def rigid_body_modes(p: np.ndarray) -> np.ndarray:
    """The 6 rigid-body displacement fields of nodes p (3, n), dofs interleaved: (3 n, 6)."""
    n = p.shape[1]
    modes = np.zeros((3 * n, 6))
    x, y, z = p
    for c in range(3):
        modes[c::3, c] = 1.0
    modes[1::3, 3], modes[2::3, 3] = -z, y
    modes[0::3, 4], modes[2::3, 4] = z, -x
    modes[0::3, 5], modes[1::3, 5] = -y, x
    return modes


def patch_recovery(p: np.ndarray, t: np.ndarray, values: np.ndarray,
                   directions: np.ndarray | None = None, min_elements: int = 4) -> np.ndarray:
    """Element values recovered at the nodes by a linear least-squares fit over each patch.

    Patch recovery (Zienkiewicz and Zhu 1992) for linear tetrahedra: for each
    node, the values of the elements that share it, sampled at their
    centroids, are fitted by a polynomial linear in the node's fit
    directions, weighted by element volume; the fit's value at the node is
    returned.  Unlike :func:`nodal_average` (the constant fit of the same
    patch) this is not biased where the patch's centroids are not centred on
    the node: on surfaces, on symmetry planes, and wherever the tetrahedra
    around a node are not arranged symmetrically (the cut cells of a
    structured grid); the error there is of second order in the element size
    instead of first.

    Parameters
    ----------
    p, t : node coordinates (3, n) [m] and tetrahedra (4, m)
    values : ndarray, shape (m, ...)
        One value (scalar or array) per element.
    directions : ndarray, shape (3, 3) or (n, 3, 3), optional
        Rows: unit vectors along which the fit is linear, for all nodes or
        per node; a zero row drops a direction.  Default: the three axes
        everywhere.  Drop the normal of a symmetry plane at its nodes (the
        field's even components have no gradient across it, and a fit across
        a one-sided patch extrapolates its scatter): e.g. only z on the axis
        of a quarter model.
    min_elements : int
        Nodes of fewer elements, or whose centroids do not span the fit's
        directions (smallest over largest eigenvalue of the scaled normal
        matrix below 1e-8), get the volume-weighted average instead.

    Returns
    -------
    ndarray, shape (n, ...)
        NaN at nodes of no element.
    """
    _, vol = shape_gradients(p, t)
    flat = values.reshape(len(vol), -1)
    n = p.shape[1]
    if directions is None:
        directions = np.eye(3)
    directions = np.asarray(directions, dtype=float)
    centroid = p[:, t].mean(axis=1)  # (3, m)
    node = t.ravel()  # corner k of element e is entry k * m + e
    elem = np.tile(np.arange(t.shape[1]), t.shape[0])
    d = (centroid[:, elem] - p[:, node]).T  # (4 m, 3)
    d = d @ directions.T if directions.ndim == 2 else np.einsum("kij,kj->ki", directions[node], d)
    count = np.bincount(node, minlength=n)
    # scale the offsets by the patch's size, so that the eigenvalue test is unit-free
    size = np.sqrt(np.bincount(node, weights=(d * d).sum(axis=1), minlength=n)
                   / np.maximum(count, 1))
    d /= np.where(size > 0, size, 1.0)[node, None]
    basis = np.column_stack([np.ones(len(node)), d])  # (4 m, 4)
    w = vol[elem]
    normal = np.zeros((n, 4, 4))
    rhs = np.zeros((n, 4, flat.shape[1]))
    for i in range(4):
        for j in range(i, 4):
            normal[:, i, j] = np.bincount(node, weights=w * basis[:, i] * basis[:, j],
                                          minlength=n)
            normal[:, j, i] = normal[:, i, j]
        for c in range(flat.shape[1]):
            rhs[:, i, c] = np.bincount(node, weights=w * basis[:, i] * flat[elem, c],
                                       minlength=n)
    out = np.full((n, flat.shape[1]), np.nan)
    has = count > 0
    out[has] = rhs[has, 0] / normal[has, 0, 0][:, None]  # the average, the fallback
    # a dropped direction (zero row) gives a zero row and column: make its coefficient 0
    unused = np.einsum("kii->ki", normal)[:, 1:] == 0
    np.einsum("kii->ki", normal)[:, 1:] += unused * normal[:, :1, 0]
    eig = np.linalg.eigvalsh(normal[has])
    good = np.zeros(n, dtype=bool)
    good[has] = (eig[:, 0] > 1e-8 * eig[:, -1]) & (count[has] >= min_elements)
    out[good] = np.linalg.solve(normal[good], rhs[good])[:, 0]
    return out.reshape((n,) + values.shape[1:])
