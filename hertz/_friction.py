"""Stresses that a tangential (frictional) traction adds to the Hertz field.

The sliding traction q = mu p(x, y) = mu p0 sqrt(1 - x^2/a^2 - y^2/b^2) along the major
axis x acts on the half-space z >= 0 (z into the body, tension positive). Cerruti's
point-force solution, written with Love's potential B = int q Omega dA,
Omega = z ln(rho + z) - rho (Johnson, Contact Mechanics, sec. 3.2; derived and checked here
with sympy against Cerruti's displacements: equilibrium, free surface, resultant), gives

    2 pi sxx = 2 (1+nu) V_x - z W_xxx + 2 nu B_xxx      2 pi szz = -z V_xz
    2 pi syy = z W_xxx + z V_xz - 2 nu B_xxx            2 pi sxz = V_z - z V_xx
    2 pi sxy = V_y - z W_xxy + 2 nu B_xxy               2 pi syz = -z V_xy

with V = B_zz = int q / rho dA and W = B_z = int q ln(rho + z) dA (B, W, V harmonic; syy
uses B_xyy = -B_xxx - V_x, W_xyy = -W_xxx - V_xz). V is mu times the potential of the
normal problem (Thomas & Hoersch 1930; Johnson sec. 3.5),

    V = (kappa/2) int_l^inf (T(w) - z^2) dw / (w D(w)),  kappa = pi a b mu p0,
    T(w) = w (1 - x^2/(a^2+w) - y^2/(b^2+w)),  D(w) = sqrt((a^2+w)(b^2+w) w),

l the ellipsoidal coordinate (T(l) = z^2). Integrating in z under the w integral (the region
z' > z, w > l(z') is w > l, z < z' < t(w), t = sqrt T) gives W and B with T - z^2 replaced by
h1 = -(t-z)^2 (2t+z)/3 and h2 = (t-z)^3 (3t+z)/12 (d h2/dz = h1, d h1/dz = t^2 - z^2, both
zero at t = z, so their first derivatives need no end terms). Their third x, y derivatives
by the chain rule in T (T is quadratic in x and y) reduce, with s(w) = T/w, to

    J1 = int x^3 dw / (A^3 sqrt(AB) s^(3/2))      J2 = int x dw / (A^2 sqrt(AB s))
    J3 = int x^2 y dw / (A^2 B sqrt(AB) s^(3/2))  J4 = int y dw / (A B sqrt(AB s))
    J5 = int x sqrt(w) dw / (A^2 sqrt(AB))        J6 = int y sqrt(w) dw / (A B sqrt(AB))

(A = a^2 + w, B = b^2 + w, all from l to infinity, times kappa), with
W_xxx = -J1 - 3 J2 + e1/z, W_xxy = -J3 - J4 + e2/z, B_xxx = -z J1 + 3 J5 - 3 z J2,
B_xxy = -z J3 + J6 - z J4 (the end terms e1, e2 come from the l dependence of W's third
derivatives; e/z stays finite). V's first and second derivatives are closed forms in
Carlson's R_D of (l, a^2 + l, b^2 + l), as in the normal problem.

The six J are integrated numerically: with w = l + e^v the integrands are analytic in the
strip |Im v| < pi (every singularity of s, A, B, and the zeros of T lie at w <= l on the
real axis), so the trapezoid rule in v converges like exp(-2 pi^2 / h); h = 0.4 and the
range chosen from the scales l, z^2/T'(l) and a^2 give about 1e-15 relative.
s(w) = z^2/l + (w - l) (x^2/(A_l A) + y^2/(B_l B)) is a sum of non-negative terms.

On the surface z = 0 the terms z W vanish (W's third derivatives stay finite outside the
contact), but z J1 and z J3 in B_xxx, B_xxy tend to e1 and e2 outside the contact (z/s^(3/2)
concentrates at w = l); inside (l = 0) they vanish. Check there:
sxx = -pi (4 + nu) mu p0 x / (8 a) for a circle (Hamilton 1983; Johnson eq. 7.47),
mu p0 pi (4 + nu)/8 at the trailing edge.

Beyond 3e4 times the larger semi-axis the field is Cerruti's field of the resultant
(2/3) pi a b mu p0 (_far_along_x), within (a/R)^2 of the traction's: the quadrature's
cancellations grow with the distance there, and its powers of x/a overflow beyond 1e51 a.

Traction along y is the same with the axes exchanged; any direction is their sum.
Checked against an mpmath quadrature of Cerruti's solution (tests/reference_friction.py):
within 6.7e-16 mu p0 at 33 points (b/a = 1, 0.5, 0.2; depths 0.01 a to 3 a and the surface
outside the contact) for nu = 0.25, 0.3, 0.5, and within 3.5e-18 at 2.2e-11 a below the
surface (tests/test_tangential_api.py). About 4.2 us per point (numpy; 190 nodes on
average), 9 times the normal field's C kernel (benchmarks/friction.py, AMD EPYC, one
core shared); a call at one point costs about 0.6 ms (numpy's overhead per operation).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize, special

from ._stress import point_stress
from ._validate import as_float_array, index_text

__all__ = ["SlidingMaxima", "partial_slip_stress", "sliding_maxima", "sliding_stress",
           "surface_von_mises_mu"]

# trapezoid step in v = log(w - l); the integrands are analytic for |Im v| < pi
_STEP = 0.4
# the integrands fall as exp(v) (w - l -> 0, z > 0), exp(v/2) (l = 0 on the surface)
# and at least exp(-3v/2) (w -> infinity); ends where they are below 1e-17 of their peak
_LOW, _LOW_SURFACE, _HIGH = 40.0, 80.0, 27.0
_CHUNK = 2048
# points per block of the trapezoid sums: (_ROWS, nodes) temporaries of about 150 kB, a
# few of which fit in a 512 kB L2 cache (96 to 128 were fastest; 256 took 1.5 times as long)
_ROWS = 96
# the most nodes whose exp(k h) (at most e^680) come from one table
_TABLE_NODES = 1700
_LOG_Z_MIN = np.log(1e-7)


def _ellipsoidal_coordinate(a2, b2, x2, y2, z2):
    """The positive root l of x^2/(a^2+l) + y^2/(b^2+l) + z^2/l = 1 (0 on the contact).

    Newton's method on f(l) = l - z^2 - x^2 l/(a^2+l) - y^2 l/(b^2+l), increasing and
    convex in l, from the right of the root: the iterates fall monotonically onto it.

    The start: with f(l) = l (e0 + l g(l)) - z^2, g(l) = x^2/(a^2 A) + y^2/(b^2 B)
    decreasing, the root of the quadratic l (e0 + l g(u)) = z^2 for an upper bound u of
    the root lies between the root and u (it undercuts f left of u).  Two such steps from
    u = x^2 + y^2 + z^2 leave Newton one to three steps (from u itself, up to 40 where
    the root is far below u, near the surface).
    """
    # 1 - x^2/(a^2+l) - y^2/(b^2+l) = e0 + l (x^2/(a^2 A) + y^2/(b^2 B)): no cancellation
    # for l << a^2 beyond the rounding of e0 itself
    e0 = 1.0 - x2 / a2 - y2 / b2
    inside = (z2 == 0) & (e0 >= 0)
    lam = x2 + y2 + z2
    with np.errstate(divide="ignore", invalid="ignore"):
        for _ in range(2):
            g = x2 / (a2 * (a2 + lam)) + y2 / (b2 * (b2 + lam))
            root = np.sqrt(e0 * e0 + 4.0 * g * z2)
            # the positive root of g l^2 + e0 l - z^2, in its form without cancellation
            model = np.where(e0 >= 0, 2.0 * z2 / (e0 + root), (root - e0) / (2.0 * g))
            lam = np.where(model < lam, model, lam)   # (NaN where 0/0: keep the bound)
    lam = np.where(inside, 0.0, np.maximum(lam, z2))
    # each point stops at its own last step (a point's iterations do not depend on the
    # others of its batch: one point alone and in an array get the same bits)
    active = np.ones(np.shape(lam), dtype=bool)
    for _ in range(200):
        A, B = a2 + lam, b2 + lam
        f = lam * (e0 + lam * (x2 / (a2 * A) + y2 / (b2 * B))) - z2
        df = e0 + lam * (x2 * (2.0 * a2 + lam) / (a2 * A * A)
                         + y2 * (2.0 * b2 + lam) / (b2 * B * B))
        step = np.where(inside | (f <= 0), 0.0, f / np.where(df > 0, df, 1.0))
        new = np.maximum(lam - step, z2)      # l >= z^2 (rounding near l = z^2)
        done = ~(new < lam) | (step <= 4e-16 * lam)
        lam = np.where(active & (new < lam), new, lam)
        active &= ~done
        if not active.any():
            break
    return lam


@functools.lru_cache(maxsize=64)
def _node_factors(n):
    """exp(k h) for the n nodes k = 0 .. n-1 of the trapezoid rule (read-only)."""
    out = np.exp(_STEP * np.arange(n))
    out.flags.writeable = False
    return out


def _trapezoid_sums(n, low, lam, zeta2, x2_a, y2_b, a2, b2):
    """The six integrals J / (kappa x^3, kappa x, kappa x^2 y, kappa y, kappa x, kappa y) by
    the trapezoid rule with n nodes v = low + k h in v = log(w - l), h = _STEP.

    Blocks of _ROWS points at a time (the temporaries stay in the cache), the node
    offsets w - l = exp(low) exp(k h) from one table of exp(k h) (no exp per node), the
    divisions by A and B as products with their reciprocals, two square roots per node
    (sqrt(1/(AB s)) and sqrt(w/(AB))), each sum a dot product (no temporary) and the
    weight h applied to the sums.
    """
    # exp(k h) overflows beyond k h = 709 (and exp(low) is then subnormal): the points
    # within about 1e-139 a of the surface need that many nodes; they take an exp per node
    factors = _node_factors(n) if n <= _TABLE_NODES else _STEP * np.arange(n)
    out = np.empty((6, lam.size))
    for i in range(0, lam.size, _ROWS):
        rows = slice(i, i + _ROWS)
        if n <= _TABLE_NODES:
            dw = np.exp(low[rows])[:, None] * factors  # w - l, and dw/dv
        else:
            dw = np.exp(low[rows, None] + factors)
        w = lam[rows, None] + dw
        ia = np.add(a2, w)
        np.divide(1.0, ia, out=ia)                    # 1/A
        ib = np.add(b2[rows, None], w)
        np.divide(1.0, ib, out=ib)                    # 1/B
        s = x2_a[rows, None] * ia                     # s(w) = z^2/l + (w - l)(...)
        s += y2_b[rows, None] * ib
        s *= dw
        s += zeta2[rows, None]
        iab = ia * ib
        k2 = np.divide(iab, s)
        np.sqrt(k2, out=k2)
        k2 *= dw                                      # dw / sqrt(AB s)
        k3 = k2 / s                                   # dw / (sqrt(AB) s^(3/2))
        k5 = np.multiply(iab, w, out=w)
        np.sqrt(k5, out=k5)
        k5 *= dw                                      # dw sqrt(w / (AB))
        ia2 = ia * ia
        k3a2 = np.multiply(k3, ia2, out=k3)
        for j, (p, q) in enumerate(((k3a2, ia), (k2, ia2), (k3a2, ib), (k2, iab), (k5, ia2),
                                    (k5, iab))):
            out[j, rows] = np.einsum("ij,ij->i", p, q)
    out *= _STEP                                      # the weight h of every node
    return out


def _sliding_along_x(a, b, nu, x, y, z):
    """sxx, syy, szz, syz, sxz, sxy / (mu p0) for traction along x; 1-d arrays, a = 1."""
    a2, b2 = a * a, np.asarray(b * b)
    x2, y2, z2 = x * x, y * y, z * z
    # below z = 1.5e-154 a, z^2 underflows to 0: the surface (the field differs from it by
    # O(z), O(sqrt(z)) at the edge), taken as such (z^2/T' = 0 has no logarithm)
    z = np.where(z2 == 0, 0.0, z)
    lam = _ellipsoidal_coordinate(a2, b2, x2, y2, z2)
    A, B = a2 + lam, b2 + lam
    kappa = np.pi * a * b
    sq_ab = np.sqrt(A * B)
    pos = lam > 0
    lam_safe = np.where(pos, lam, 1.0)
    # zeta^2 = z^2 / l = s(l); on the contact (l = 0) its limit 1 - x^2/a^2 - y^2/b^2
    zeta2 = np.where(pos, z2 / lam_safe, np.maximum(1.0 - x2 / a2 - y2 / b2, 0.0))
    zeta = np.sqrt(zeta2)
    # dT/dw at w = l, a sum of non-negative terms (T' = x^2 l/A^2 + y^2 l/B^2 + z^2/l)
    t_w = x2 * lam / (A * A) + y2 * lam / (B * B) + zeta2
    t_w_safe = np.where(t_w > 0, t_w, 1.0)

    # V = mu phi: closed forms (I_A = 2/3 R_D(l, B, A), I_B = 2/3 R_D(l, A, B))
    i_a = 2.0 / 3.0 * special.elliprd(lam, B, A)
    i_b = 2.0 / 3.0 * special.elliprd(lam, A, B)
    v_x = -kappa * x * i_a
    v_y = -kappa * y * i_b
    # V_z = -kappa z I_w, z I_w = 2 zeta / sqrt(AB) - z (I_A + I_B)
    v_z = -kappa * (2.0 * zeta / sq_ab - z * (i_a + i_b))
    # z V_xx, z V_xy, z V_xz from the derivatives of l (dl/dx = 2 x l / (A T'), ...)
    d_l = sq_ab * np.sqrt(lam_safe)
    zg = np.where(pos & (z > 0), z / (d_l * t_w_safe), 0.0)       # z / (D(l) T'(l))
    zv_xx = -kappa * z * i_a + 2.0 * kappa * x2 * lam * zg / (A * A)
    zv_xy = 2.0 * kappa * x * y * lam * zg / (A * B)
    zv_xz = 2.0 * kappa * x * z * zg / A
    # end terms of z W_xxx, z W_xxy: 2 kappa x^3 l^2 / (D A^3 T'), 2 kappa x^2 y l^2 / (D A^2 B T')
    g = np.where(pos, 1.0 / (d_l * t_w_safe), 0.0)
    e1 = 2.0 * kappa * x2 * x * lam * lam * g / (A * A * A)
    e2 = 2.0 * kappa * x2 * y * lam * lam * g / (A * A * B)

    # the six J by the trapezoid rule in v = log(w - l)
    low = np.where(pos, np.log(np.where(pos & (z > 0), z2 / t_w_safe, lam_safe)) - _LOW,
                   np.log(np.minimum(a2, b2)) - _LOW_SURFACE)
    low = np.minimum(low, np.log(lam_safe) - _LOW)
    high = np.log(np.maximum(a2, b2) + lam) + _HIGH
    # points need from 150 to 400 nodes: group them by their count (a multiple of 16; the
    # last node at or beyond high)
    count = 16 * np.ceil((np.ceil((high - low) / _STEP) + 1) / 16).astype(int)
    sums = np.empty((6, lam.size))
    for n in np.unique(count):
        k = count == n
        sums[:, k] = _trapezoid_sums(int(n), low[k], lam[k], zeta2[k], (x2 / A)[k],
                                     (y2 / B)[k], a2, b2[k])
    j1 = kappa * x2 * x * sums[0]
    j2 = kappa * x * sums[1]
    j3 = kappa * x2 * y * sums[2]
    j4 = kappa * y * sums[3]
    j5 = kappa * x * sums[4]
    j6 = kappa * y * sums[5]

    # W_xxx = -J1 - 3 J2 + e1/z, B_xxx = -z J1 + 3 J5 - 3 z J2 (and the xxy pair). On the
    # surface outside the contact z J1 and z J3 do not vanish: z / s^(3/2) concentrates at
    # w = l, and z J1 -> e1, z J3 -> e2 (so that z W_xxx, z W_xxy -> 0 there)
    zw_xxx = np.where(z > 0, -z * j1 - 3.0 * z * j2 + e1, 0.0)
    zw_xxy = np.where(z > 0, -z * j3 - z * j4 + e2, 0.0)
    b_xxx = 3.0 * j5 - np.where(z > 0, z * j1 + 3.0 * z * j2, e1)
    b_xxy = j6 - np.where(z > 0, z * j3 + z * j4, e2)

    f = 1.0 / (2.0 * np.pi)
    sxx = f * (2.0 * (1.0 + nu) * v_x - zw_xxx + 2.0 * nu * b_xxx)
    syy = f * (zw_xxx + zv_xz - 2.0 * nu * b_xxx)
    szz = -f * zv_xz
    syz = -f * zv_xy
    sxz = f * (v_z - zv_xx)
    sxy = f * (v_y - zw_xxy + 2.0 * nu * b_xxy)
    return sxx, syy, szz, syz, sxz, sxy


def _far_along_x(a, b, nu, x, y, z):
    """sxx, syy, szz, syz, sxz, sxy / (mu p0) for traction along x far from the contact:
    Cerruti's field of the resultant (2/3) pi a b mu p0 (Johnson, Contact Mechanics,
    eq. 3.86; the potentials of the module docstring for a point force), 1-d arrays in m.

    The traction is even in x and y, so the field differs from the point force's by
    terms (a/R)^2 smaller (the quadrupole (a^2/10) d^2/dx^2 + (b^2/10) d^2/dy^2 of it,
    derived with sympy: at R = 3e4 max(a, b), within 3e-7 of the largest component and
    6e-19 mu p0; the quadrature's cancellations there cost 2e-6 of it).  Written with
    the unit vector (l, m, n) = (x, y, z)/R and the factor (a/R)(b/R), nothing overflows
    or underflows before the result does (the quadrature's powers of x/a overflow beyond
    R = 1e51 a).  With Q/(2 pi) = a b / 3 and rho = 1:
    V_x = -l, V_y = -m, V_z = -n, z V_xz = 3 l n^2, z V_xy = 3 l m n, z V_xx = n (3 l^2 - 1),
    z W_xxx = l n (2 l^2 - (m^2 + n^2)(3 n^2 + 9 n + 6)) / (1 + n)^3,
    B_xxx = l ((n + 3)(m^2 + n^2) + 2 n) / (1 + n)^3 (l^2 - 1 = -(m^2 + n^2): no
    cancellation), z W_xxy = m n (l^2 (3 n^2 + 9 n + 8) - (n + 1)(n + 2)) / (1 + n)^3,
    B_xxy = -m (l^2 (n + 3) - (n + 1)) / (1 + n)^3."""
    big = np.maximum(np.maximum(np.abs(x), np.abs(y)), z)
    xs, ys, zs = x / big, y / big, z / big
    norm = np.sqrt(xs * xs + ys * ys + zs * zs)
    l, m, n = xs / norm, ys / norm, zs / norm
    radius = big * norm
    factor = (a / radius) * (b / radius) / 3.0
    l2, m2n2 = l * l, m * m + n * n
    cube = (1.0 + n) * (1.0 + n) * (1.0 + n)
    zw_xxx = l * n * (2.0 * l2 - m2n2 * (3.0 * n * n + 9.0 * n + 6.0)) / cube
    b_xxx = l * ((n + 3.0) * m2n2 + 2.0 * n) / cube
    zw_xxy = m * n * (l2 * (3.0 * n * n + 9.0 * n + 8.0) - (n + 1.0) * (n + 2.0)) / cube
    b_xxy = -m * (l2 * (n + 3.0) - (n + 1.0)) / cube
    zv_xz = 3.0 * l * n * n
    sxx = 2.0 * (1.0 + nu) * -l - zw_xxx + 2.0 * nu * b_xxx
    syy = zw_xxx + zv_xz - 2.0 * nu * b_xxx
    szz = -zv_xz
    syz = -3.0 * l * m * n
    sxz = -3.0 * l2 * n
    sxy = -m - zw_xxy + 2.0 * nu * b_xxy
    return tuple(factor * v for v in (sxx, syy, szz, syz, sxz, sxy))


# beyond this many times the larger semi-axis the field is Cerruti's of the resultant
# (_far_along_x), nearer than it the quadrature's: where the two errors cross
_FAR = 3e4


def _unit_field(a, b, nu, x, y, z):
    """The six components / (mu p0) for a sliding traction along x, flat arrays: the
    quadrature near the contact, the resultant's field beyond _FAR max(a, b) (each point
    on its own: one point alone and in an array get the same bits)."""
    out = [np.empty(x.shape) for _ in range(6)]
    far = np.maximum(np.maximum(np.abs(x), np.abs(y)), z) > _FAR * np.maximum(a, b)
    if far.any():
        parts = _far_along_x(a[far], b[far], nu[far], x[far], y[far], z[far])
        for o, p in zip(out, parts, strict=True):
            o[far] = p
    near = np.flatnonzero(~far)
    for i in range(0, near.size, _CHUNK):
        k = near[i:i + _CHUNK]
        scale = a[k]
        parts = _sliding_along_x(1.0, b[k] / scale, nu[k], x[k] / scale, y[k] / scale,
                                 z[k] / scale)
        for o, p in zip(out, parts, strict=True):
            o[k] = p
    return out


def _unit_fields(problems):
    """_unit_field of each problem (a, b, nu, x, y, z, along_y), the traction along y
    being that along x with the axes exchanged.  Small problems go through one call
    (numpy's cost per operation, not per point, dominates them: the search for the
    maxima evaluates one point at a time, with up to four problems per point)."""
    turned = [(b, a, nu, y, x, z) if along_y else (a, b, nu, x, y, z)
              for a, b, nu, x, y, z, along_y in problems]
    sizes = [p[3].size for p in turned]
    if len(turned) > 1 and sum(sizes) <= _CHUNK:
        joined = np.array(_unit_field(*(np.concatenate(column)
                                        for column in zip(*turned, strict=True))))
        ends = np.cumsum([0] + sizes)
        fields = [joined[:, i:j] for i, j in zip(ends[:-1], ends[1:], strict=True)]
    else:
        fields = [_unit_field(*p) for p in turned]
    # as (6, n) arrays; a problem turned: (sxx, syy, szz, syz, sxz, sxy) of the turned
    # axes, back
    return [np.asarray(f)[[1, 0, 2, 4, 3, 5] if problem[-1] else slice(None)]
            for f, problem in zip(fields, problems, strict=True)]


def _check(a, b, p0, mu, nu, x, y, z, direction):
    names = ("a", "b", "p0", "mu", "nu", "x", "y", "z", "direction")
    arrs = [as_float_array(v, n) for v, n in zip((a, b, p0, mu, nu, x, y, z, direction),
                                                   names, strict=True)]
    rules = {"a": (lambda v: (v > 0) & np.isfinite(v), "a positive, finite length in m"),
             "b": (lambda v: (v > 0) & np.isfinite(v), "a positive, finite length in m"),
             "p0": (lambda v: (v >= 0) & np.isfinite(v), "a finite pressure >= 0 in Pa"),
             "mu": (lambda v: (v >= 0) & np.isfinite(v), "a finite friction coefficient >= 0"),
             "nu": (lambda v: (v > -1) & (v <= 0.5), "a Poisson's ratio in (-1, 0.5]"),
             "x": (np.isfinite, "a finite coordinate in m"),
             "y": (np.isfinite, "a finite coordinate in m"),
             "z": (lambda v: (v >= 0) & np.isfinite(v), "a finite depth >= 0 in m"),
             "direction": (np.isfinite, "a finite angle in rad")}
    for name, arr in zip(names, arrs, strict=True):
        ok, allowed = rules[name]
        good = ok(arr)
        if not np.all(good):
            i = int(np.argmin(np.asarray(good).reshape(-1)))
            raise ValueError(f"{name} must be {allowed}, got "
                             f"{arr.reshape(-1)[i].item()!r}{index_text(arr.shape, i)}")
    return arrs


def sliding_stress(a, b, p0, mu, nu, x, y, z, direction=0.0):
    """The stress a sliding traction q = mu p adds to the Hertz field.

    The traction mu p0 sqrt(1 - x^2/a^2 - y^2/b^2) acts on the surface of the body over the
    contact ellipse, along ``direction``; add the result to the frictionless field
    (:meth:`hertz.Contact.stress`) for the stress under a sliding contact.

    Parameters
    ----------
    a, b : float or array_like
        Semi-axes of the contact ellipse along x and y [m] (any order).
    p0 : float or array_like
        Peak Hertz pressure [Pa].
    mu : float or array_like
        Coefficient of friction (the traction is mu times the pressure), >= 0.
    nu : float or array_like
        Poisson's ratio of the body.
    x, y : float or array_like
        Position in the ellipse frame (x along a, y along b) [m].
    z : float or array_like
        Depth below the surface, >= 0 [m].
    direction : float or array_like, optional
        Direction of the traction acting on this body, from the x axis [rad].

    Returns
    -------
    ndarray, shape (..., 3, 3)
        The Cauchy stress [Pa], tension positive.

    Notes
    -----
    Cerruti's solution integrated over the ellipse through Love's potentials; the potential
    of the pressure is closed form (Carlson's R_D), the two higher potentials are integrated
    over the ellipsoidal coordinate by the trapezoid rule in log(w - l), to about 1e-14 p0
    (measured against an mpmath quadrature of Cerruti's solution). With traction along +x
    the surface is in tension behind the contact: at the trailing edge of a circle
    sxx = p0 [(1 - 2 nu)/3 + mu pi (4 + nu)/8] with the normal field (Hamilton 1983).

    Examples
    --------
    >>> import numpy as np
    >>> s = sliding_stress(1e-3, 1e-3, 1e9, 0.2, 0.3, -1e-3, 0.0, 0.0)
    >>> round(float(s[0, 0] / (0.2 * 1e9 * np.pi * (4 + 0.3) / 8)), 12)
    1.0
    """
    return _sliding(*_check(a, b, p0, mu, nu, x, y, z, direction))


def _sliding(a, b, p0, mu, nu, x, y, z, direction):
    """:func:`sliding_stress` of checked inputs (float64 arrays or floats)."""
    return _tractions([(a, b, p0)], mu, nu, x, y, z, direction)[0]


def _tractions(ellipses, mu, nu, x, y, z, direction):
    """The sliding fields of the traction mu p over each ellipse (a, b, p0) [Pa], for
    checked inputs (float64 arrays or floats): one stress tensor array per ellipse."""
    shape = np.broadcast_shapes(*(np.shape(v) for v in (mu, nu, x, y, z, direction)),
                                *(np.shape(v) for e in ellipses for v in e))

    def flat(v):
        return np.broadcast_to(v, shape).reshape(-1)

    nu_, x_, y_, z_ = (flat(v) for v in (nu, x, y, z))
    c, s = np.cos(direction), np.sin(direction)
    weights = [(along_y, w) for along_y, w in ((False, c), (True, s)) if np.any(w != 0)]
    problems = [(flat(a), flat(b), nu_, x_, y_, z_, along_y)
                for a, b, _ in ellipses for along_y, _ in weights]
    fields = iter(_unit_fields(problems))
    out = []
    for _, _, p0 in ellipses:
        total = None
        for _, weight in weights:
            part = np.broadcast_to(weight, shape).reshape(-1) * next(fields)
            total = part if total is None else total + part
        if total is None:  # no traction (direction with cos = sin = 0 cannot occur)
            total = np.zeros((6, math.prod(shape)))
        # (sxx, syy, szz, syz, sxz, sxy) -> the symmetric tensor, row by row
        stress = total[[0, 5, 4, 5, 1, 3, 4, 3, 2]].T.reshape(shape + (3, 3))
        stress *= np.asarray(mu * p0)[..., None, None]
        out.append(stress)
    return out


def partial_slip_stress(a, b, p0, mu, nu, x, y, z, stick_ratio, direction=0.0):
    """The stress a Cattaneo-Mindlin partial-slip traction adds to the Hertz field.

    The traction is mu p over the contact ellipse minus (c/a) mu p0 sqrt(1 - x^2/c^2 -
    y^2/c_b^2) over the stick ellipse c = stick_ratio a, c_b = stick_ratio b (Mindlin's
    solution along a principal axis), so the field is the sliding field of the contact minus
    that of the stick ellipse with peak pressure stick_ratio p0.

    Parameters
    ----------
    a, b, p0, mu, nu, x, y, z, direction
        As in :func:`sliding_stress`.
    stick_ratio : float or array_like
        c/a = (1 - Q/(mu P))^(1/3) in [0, 1]: 0 is full sliding, 1 no tangential force.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        The Cauchy stress [Pa], tension positive.

    Examples
    --------
    >>> import numpy as np
    >>> s = partial_slip_stress(1e-3, 5e-4, 1e9, 0.3, 0.3, 2e-4, 1e-4, 1e-4, 1.0)
    >>> float(np.max(np.abs(s)))
    0.0
    """
    ratio = as_float_array(stick_ratio, "stick_ratio")
    ok = (ratio >= 0) & (ratio <= 1)
    if not np.all(ok):
        i = int(np.argmin(ok.reshape(-1)))
        raise ValueError(f"stick_ratio must be c/a in [0, 1], got "
                         f"{ratio.reshape(-1)[i].item()!r}{index_text(ratio.shape, i)}")
    return _partial_slip(*_check(a, b, p0, mu, nu, x, y, z, direction), ratio)


def _partial_slip(a, b, p0, mu, nu, x, y, z, direction, ratio):
    """:func:`partial_slip_stress` of checked inputs (float64 arrays or floats)."""
    has_stick = ratio > 0
    if not np.any(has_stick):
        return _sliding(a, b, p0, mu, nu, x, y, z, direction)
    # a zero stick ellipse is replaced by a unit one with zero traction
    r = np.where(has_stick, ratio, 1.0)
    full, stick = _tractions([(a, b, p0), (r * a, r * b, np.where(has_stick, r, 0.0) * p0)],
                             mu, nu, x, y, z, direction)
    return full - stick


# ---------------------------------------------------------------- maxima of the combined field
@dataclass(frozen=True, slots=True)
class SlidingMaxima:
    """The largest stresses in a body under a sliding Hertz contact (normal + friction).

    Stresses in Pa, positions in m in the ellipse frame (x along a, y along b, z depth).
    Floats for one contact; arrays of the contacts' shape from
    :meth:`hertz.Tangential.maxima` of an array of contacts.

    Attributes
    ----------
    von_mises, x_von_mises, y_von_mises, z_von_mises : float or ndarray
        The largest von Mises stress [Pa] and where it is [m] (z = 0: on the surface).
    tau_max, x_tau_max, y_tau_max, z_tau_max : float or ndarray
        The largest principal shear stress (s1 - s3)/2 (Tresca/2) [Pa] and where it is [m].
    tensile, x_tensile, y_tensile : float or ndarray
        The largest principal stress on the surface [Pa] (tension, at the trailing edge)
        and where it is [m].
    """

    von_mises: float | np.ndarray
    x_von_mises: float | np.ndarray
    y_von_mises: float | np.ndarray
    z_von_mises: float | np.ndarray
    tau_max: float | np.ndarray
    x_tau_max: float | np.ndarray
    y_tau_max: float | np.ndarray
    z_tau_max: float | np.ndarray
    tensile: float | np.ndarray
    x_tensile: float | np.ndarray
    y_tensile: float | np.ndarray


def _principal(s):
    return np.linalg.eigvalsh(s)


class _Field:
    """The combined normal + sliding stress / p0 of the contact a = 1, b = ratio; in_plane:
    only the symmetry plane through the traction (y = 0 for traction along x, x = 0 along
    y) is searched."""

    def __init__(self, ratio, mu, nu, direction, stick_ratio=0.0):
        self.ratio, self.mu, self.nu, self.direction = ratio, mu, nu, direction
        self.stick_ratio = stick_ratio
        c, s = np.cos(direction), np.sin(direction)
        # (cos(pi/2) and sin(pi) are 6e-17 and 1.2e-16 in double precision)
        self.plane = "y" if abs(s) < 1e-12 else ("x" if abs(c) < 1e-12 else None)

    def stress(self, x, y, z):
        x, y, z = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x, y, z)))
        if self.ratio <= 1:
            normal = point_stress(1.0, self.ratio, 1.0, self.nu, x, y, z)
        else:   # the normal kernel wants the major axis along x
            turned = point_stress(self.ratio, 1.0, 1.0, self.nu, y, x, z)
            normal = turned[..., [1, 0, 2], :][..., [1, 0, 2]]
        # the inputs are checked (sliding_maxima) and the points the search's own
        if self.stick_ratio > 0:
            return normal + _partial_slip(1.0, self.ratio, 1.0, self.mu, self.nu, x, y, z,
                                          self.direction, self.stick_ratio)
        return normal + _sliding(1.0, self.ratio, 1.0, self.mu, self.nu, x, y, z,
                                 self.direction)

    def values(self, x, y, z):
        """von Mises, (s1 - s3)/2, s1."""
        e = _principal(self.stress(x, y, z))
        d = np.stack([e[..., 0] - e[..., 1], e[..., 1] - e[..., 2], e[..., 2] - e[..., 0]], -1)
        return np.sqrt(0.5 * np.sum(d * d, axis=-1)), 0.5 * (e[..., 2] - e[..., 0]), e[..., 2]

    def grid(self, surface):
        """Points of a coarse grid over the surface or below it."""
        b = self.ratio
        x = np.linspace(-1.3, 1.3, 53)
        y = np.linspace(-1.3 * b, 1.3 * b, 27)
        if self.plane == "y":
            y = np.zeros(1)
        elif self.plane == "x":
            x = np.zeros(1)
            y = np.linspace(-1.3 * b, 1.3 * b, 53)
        z = np.zeros(1) if surface else np.concatenate(
            [np.geomspace(1e-3, 0.1, 8), np.linspace(0.15, 1.2, 22)]) * max(b, 0.2)
        return np.meshgrid(x, y, z, indexing="ij")

    def edge(self, n=721):
        """Points on the edge of the contact: angles, x, y."""
        if self.plane is not None:
            phi = np.array([0.0, np.pi]) if self.plane == "y" else np.array([-np.pi, np.pi]) / 2
        else:
            phi = np.linspace(-np.pi, np.pi, n)
        return phi, np.cos(phi), self.ratio * np.sin(phi)


def _refine(field, which, start, surface):
    """Local maximum from start: Nelder-Mead over the surface (x, y) or below it
    (x, y, log z), within the symmetry plane if there is one; (value, x, y, z)."""
    free = [k for k in (0, 1) if not (field.plane == "y" and k == 1)
            and not (field.plane == "x" and k == 0)]
    x0 = list(start[:2]) + [np.log(max(start[2], 1e-6))]
    keys = free + ([] if surface else [2])

    def point(p):
        q = list(x0)
        for k, v in zip(keys, p, strict=True):
            q[k] = v
        # below 1e-7 a the field is the surface's (the surface candidate covers it)
        return q[0], q[1], (0.0 if surface else np.exp(max(q[2], _LOG_Z_MIN)))

    def f(p):
        return -float(field.values(*point(p))[which])

    p0 = np.array([x0[k] for k in keys])
    simplex = [p0] + [p0 + 0.02 * np.eye(len(p0))[k] for k in range(len(p0))]
    res = optimize.minimize(f, p0, method="Nelder-Mead", options={
        "initial_simplex": simplex, "xatol": 1e-8, "fatol": 1e-15, "maxiter": 3000,
        "maxfev": 6000})
    return (-res.fun,) + point(res.x)


def _edge_maximum(field, which):
    """The largest value on the edge of the contact (where the field has square-root
    kinks that a search over the surface cannot resolve); (value, x, y, 0)."""
    phi, x, y = field.edge()
    val = field.values(x, y, 0.0)[which]
    k = int(np.argmax(val))
    if field.plane is None:
        b = field.ratio
        step = phi[1] - phi[0]
        res = optimize.minimize_scalar(
            lambda p: -float(field.values(np.cos(p), b * np.sin(p), 0.0)[which]),
            method="bounded", bounds=(phi[k] - step, phi[k] + step), options={"xatol": 1e-12})
        if -res.fun > val[k]:
            return -res.fun, np.cos(res.x), b * np.sin(res.x), 0.0
    return val[k], x[k], y[k], 0.0


def _maximum(field, which, grids, surface_only=False):
    """The global maximum (value, x, y, z) over the surface (its edge included) and below."""
    cands = [_edge_maximum(field, which)]
    for surface in ((True,) if surface_only else (True, False)):
        gx, gy, gz, vals = grids[surface]
        i = np.unravel_index(int(np.argmax(vals[which])), vals[which].shape)
        cands.append(_refine(field, which, (gx[i], gy[i], gz[i]), surface))
    return max(cands, key=lambda r: r[0])


def _grids(field):
    out = {}
    for surface in (True, False):
        gx, gy, gz = field.grid(surface)
        out[surface] = (gx, gy, gz, field.values(gx, gy, gz))
    return out


def _scalar_inputs(a, b, p0, mu, nu, direction):
    vals = _check(a, b, p0, mu, nu, 0.0, 0.0, 0.0, direction)
    out = []
    for name, v in zip(("a", "b", "p0", "mu", "nu"), vals[:5], strict=True):
        if v.ndim:
            raise TypeError(f"{name} must be a scalar here (one contact at a time), "
                            f"got an array of shape {v.shape}")
        out.append(float(v))
    return out + [float(vals[8])]


def check_maxima_inputs(a, b, p0, mu, nu, direction, stick_ratio, shape):
    """The inputs of :func:`sliding_maxima` for an array of contacts of ``shape``, each
    broadcast to it and checked: the first bad element is a ValueError naming the input,
    its value and its index in ``shape``."""
    values = [np.broadcast_to(as_float_array(v, name), shape) for v, name in zip(
        (a, b, p0, mu, nu, direction, stick_ratio),
        ("a", "b", "p0", "mu", "nu", "direction", "stick_ratio"), strict=True)]
    a, b, p0, mu, nu, direction, ratio = values
    _check(a, b, p0, mu, nu, 0.0, 0.0, 0.0, direction)
    ok = (ratio >= 0) & (ratio <= 1)
    if not np.all(ok):
        i = int(np.argmin(ok.reshape(-1)))
        raise ValueError(f"stick_ratio must be c/a in [0, 1], got "
                         f"{ratio.reshape(-1)[i].item()!r}{index_text(shape, i)}")
    return values


def sliding_maxima(a, b, p0, mu, nu, direction=0.0, stick_ratio=0.0) -> SlidingMaxima:
    """The largest stresses under a sliding Hertz contact (normal + friction), one body.

    With ``stick_ratio`` > 0 the tangential traction is Cattaneo-Mindlin's partial-slip
    traction instead (:func:`partial_slip_stress`).

    Parameters
    ----------
    a, b : float
        Semi-axes of the contact ellipse along x and y [m].
    p0 : float
        Peak Hertz pressure [Pa].
    mu : float
        Coefficient of friction: the traction is mu p along ``direction``.
    nu : float
        Poisson's ratio of the body.
    direction : float, optional
        Direction of the traction on this body, from the x axis [rad].
    stick_ratio : float, optional
        c/a of the stick ellipse in [0, 1]; 0 (the default) is full sliding.

    Returns
    -------
    SlidingMaxima

    Notes
    -----
    A grid over the surface and one below it, each refined by Nelder-Mead, and the edge of
    the contact (where the field has square-root kinks) searched over its angle; the largest
    wins. For traction along a principal axis only the plane of symmetry containing it is
    searched. For a circle and nu = 0.3 the von Mises maximum leaves the depth 0.48 a for
    the surface (the trailing edge) at mu = 0.3047 (:func:`surface_von_mises_mu`). The
    values agree with an mpmath quadrature of Boussinesq's and Cerruti's solutions at the
    positions found within 4.4e-16 p0 (tests/test_friction.py). Scalars only (an array of
    contacts: :meth:`hertz.Tangential.maxima`). Mostly Nelder-Mead's evaluations of the
    field at one point (about 0.5 ms sliding, 0.7 ms in partial slip off the axes): about
    0.4 s per contact in partial slip along a principal axis, 2.5 s at 0.5 rad off it,
    b/a = 0.5, c/a = 0.8 (benchmarks/friction.py, AMD EPYC; 0.9 s and 9.1 s before the
    field's evaluation at few points was batched).

    Examples
    --------
    >>> m = sliding_maxima(1e-3, 1e-3, 1e9, 0.0, 0.3)
    >>> round(m.von_mises / 1e9, 4), round(m.z_von_mises / 1e-3, 4)
    (0.62, 0.4809)
    """
    a, b, p0, mu, nu, direction = _scalar_inputs(a, b, p0, mu, nu, direction)
    ratio = as_float_array(stick_ratio, "stick_ratio")
    if ratio.ndim or not 0 <= ratio <= 1:
        raise ValueError(f"stick_ratio must be one c/a in [0, 1], got {stick_ratio!r}")
    field = _Field(b / a, mu, nu, direction, float(ratio))
    grids = _grids(field)
    vm = _maximum(field, 0, grids)
    tau = _maximum(field, 1, grids)
    tens = _maximum(field, 2, grids, surface_only=True)
    return SlidingMaxima(*(float(v) for v in (
        vm[0] * p0, vm[1] * a, vm[2] * a, vm[3] * a, tau[0] * p0, tau[1] * a, tau[2] * a,
        tau[3] * a, tens[0] * p0, tens[1] * a, tens[2] * a)))


def surface_von_mises_mu(b_over_a, nu, direction=0.0):
    """The coefficient of friction at which the von Mises maximum reaches the surface.

    Below it the largest von Mises stress of the sliding contact lies below the surface
    (the frictionless maximum, moved towards the leading edge), above it on the surface.
    Found as the root of (surface maximum - subsurface local maximum) in mu. For nu = 0.3
    and traction along the major axis: 0.3047 for a circle (Hamilton 1983: about 0.3),
    0.3380 for b/a = 0.5, 0.3155 for b/a = 0.2.

    Parameters
    ----------
    b_over_a : float
        Axis ratio of the contact ellipse (b along y).
    nu : float
        Poisson's ratio.
    direction : float, optional
        Direction of the traction from the x axis [rad].

    Returns
    -------
    float

    Examples
    --------
    >>> round(surface_von_mises_mu(1.0, 0.3), 2)
    0.3
    """
    _, ratio, _, _, nu, direction = _scalar_inputs(1.0, b_over_a, 1.0, 0.0, nu, direction)
    return _surface_von_mises_mu(ratio, nu, direction)


@functools.lru_cache(maxsize=64)
def _surface_von_mises_mu(ratio, nu, direction):
    memo = {"sub": None}

    def gap(mu):
        field = _Field(ratio, mu, nu, direction)
        gx, gy, gz = field.grid(True)
        grids = {True: (gx, gy, gz, field.values(gx, gy, gz))}
        surf = _maximum(field, 0, grids, surface_only=True)
        if memo["sub"] is None:
            gx, gy, gz = field.grid(False)
            vals = field.values(gx, gy, gz)[0]
            i = np.unravel_index(int(np.argmax(vals)), vals.shape)
            memo["sub"] = (gx[i], gy[i], gz[i])
        sub = _refine(field, 0, memo["sub"], False)
        memo["sub"] = sub[1:]
        return surf[0] - sub[0]

    # scan upwards from small mu in steps of 0.02, tracking the subsurface maximum from one
    # step to the next, to a change of sign; then Brent's method in that step
    lo, lo_sub = None, None
    for hi in np.arange(1, 51) * 0.02:
        g = gap(hi)
        if g >= 0:
            if lo is None:
                raise ValueError("the von Mises maximum is on the surface already at "
                                 "mu = 0.02")
            memo["sub"] = lo_sub
            return optimize.brentq(gap, lo, hi, xtol=1e-10)
        lo, lo_sub = hi, memo["sub"]
    raise ValueError("the von Mises maximum stays below the surface up to mu = 1")
