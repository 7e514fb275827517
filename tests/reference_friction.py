"""Independent mpmath reference for the stress of a sliding traction (does not import hertz).

The traction q = p = sqrt(1 - x^2/a^2 - y^2/b^2) (p0 = 1, mu = 1) along +x over the ellipse
acts on the half-space z >= 0 (z into the body, tension positive). The stress at a point is
Cerruti's point-force solution integrated over it. Cerruti, unit force along +x at the
origin, at offset (X, Y, z), R^2 = X^2 + Y^2 + z^2, k = 1 - 2 nu (Johnson, Contact Mechanics,
eq. 3.87; checked here with sympy against Hooke's law applied to Cerruti's displacements:
equilibrium, free surface, and the resultant of sxz over a plane is -1):

    sxx = X/(2pi R^3) [-3 X^2/R^2 + k (R^2 - Y^2 - 2 R Y^2/(R+z)) / (R+z)^2]
    syy = X/(2pi R^3) [-3 Y^2/R^2 + k (3 R^2 - X^2 - 2 R X^2/(R+z)) / (R+z)^2]
    sxy = Y/(2pi R^3) [-3 X^2/R^2 + k (-R^2 + X^2 + 2 R X^2/(R+z)) / (R+z)^2]
    szz = -3 X z^2/(2pi R^5),  sxz = -3 X^2 z/(2pi R^5),  syz = -3 X Y z/(2pi R^5)

Every component is A + k B; the reference returns A and B separately (12 numbers), so one
quadrature serves every nu.

Quadrature: polar coordinates (r, theta) centred on the field point, the source at
(x, y) + r (cos theta, sin theta) (so X = -r cos theta, Y = -r sin theta); for z > 0 the
radial variable u = asinh(r/z) makes the kernel times r dr bounded and analytic
(dA = z^2 sinh u cosh u du dtheta); the chord of the ellipse along the ray ends at square-
root zeros of q. Both integrals by vector-valued tanh-sinh (tests/reference_stress.py's
_ts, which halves the step until two levels agree); angularly on four pieces ending at the
directions tangent to the edge (field point inside the ellipse) or over the cone of rays
meeting the ellipse, split at the direction of the centre (outside). On the surface z = 0
only points outside the contact are taken (the kernel is then bounded; inside it would be a
principal value, and at the edge the integral is singular).

Accuracy: each tanh-sinh integral is refined until two levels agree to tol (1e-17 by
default, relative to 1). The committed table (tests/data/friction_reference.csv, dps 25) was
recomputed at dps = 40, tol = 1e-22 (tools/friction_reference.py --check): all 33 entries
differed by at most 7.7e-27 (absolute, per unit mu p0): far below the doubles' rounding.
"""

import mpmath as mp
from reference_stress import _ts
from reference_stress import chord as _chord

__all__ = ["friction_ref12", "friction_ref"]


def _kernel(ox, oy, z, R):
    """[A..., B...] of Cerruti's six components (order sxx, syy, szz, syz, sxz, sxy)."""
    tp = 2 * mp.pi
    R2, r3 = R * R, R * R * R
    rz = R + z
    rz2 = rz * rz
    ox2, oy2 = ox * ox, oy * oy
    c3 = -3 / (tp * r3 * R2)
    a_xx = c3 * ox * ox2
    a_yy = c3 * ox * oy2
    a_zz = c3 * ox * z * z
    a_yz = c3 * ox * oy * z
    a_xz = c3 * ox2 * z
    a_xy = c3 * oy * ox2
    b_xx = ox / (tp * r3 * rz2) * (R2 - oy2 - 2 * R * oy2 / rz)
    b_yy = ox / (tp * r3 * rz2) * (3 * R2 - ox2 - 2 * R * ox2 / rz)
    b_xy = oy / (tp * r3 * rz2) * (-R2 + ox2 + 2 * R * ox2 / rz)
    zero = mp.mpf(0)
    return [a_xx, a_yy, a_zz, a_yz, a_xz, a_xy, b_xx, b_yy, zero, zero, zero, b_xy]


def _radial(a, b, x, y, z, theta, tol):
    c, s = mp.cos(theta), mp.sin(theta)
    ch = _chord(a, b, x, y, c, s)
    if ch is None:
        return [mp.mpf(0)] * 12
    qa, r1, r2 = ch
    if z > 0:
        lo = mp.asinh(max(r1, 0) / z)
        hi = mp.asinh(r2 / z)

        def f(u, dlo, dhi):
            r = z * mp.sinh(u)
            R = z * mp.cosh(u)
            q = mp.sqrt(max(qa * (r2 - r) * (r - r1), 0))
            k = _kernel(-r * c, -r * s, z, R)
            jac = q * r * R
            return [v * jac for v in k]
    else:
        if r1 <= 0:
            raise ValueError("z = 0 is only taken outside the contact")
        lo, hi = r1, r2

        def f(r, dlo, dhi):
            q = mp.sqrt(qa * dlo * dhi)
            k = _kernel(-r * c, -r * s, z, r)
            return [v * q * r for v in k]
    return _ts(f, lo, hi, 12, tol)


def _angular(a, b, x, y, z, tol):
    def g(theta, *ends):
        return _radial(a, b, x, y, z, theta, tol / 10)

    qc = (x / a) ** 2 + (y / b) ** 2 - 1
    total = [mp.mpf(0)] * 12
    if qc <= 0:
        nx, ny = x / a ** 2, y / b ** 2
        tn = mp.atan2(ny, nx) if (nx != 0 or ny != 0) else mp.pi / 2
        pieces = [(tn + j * mp.pi / 2, tn + (j + 1) * mp.pi / 2) for j in range(4)]
    else:
        # tangents from (x, y): x/a = rho cos al, y/b = rho sin al; the tangent points are
        # (a cos ph, b sin ph) with cos(ph - al) = 1/rho
        rho = mp.sqrt((x / a) ** 2 + (y / b) ** 2)
        al = mp.atan2(y / b, x / a)
        t0 = mp.atan2(-y, -x)
        ends = []
        for sign in (-1, 1):
            ph = al + sign * mp.acos(1 / rho)
            th = mp.atan2(b * mp.sin(ph) - y, a * mp.cos(ph) - x)
            while th > t0 + mp.pi:
                th -= 2 * mp.pi
            while th < t0 - mp.pi:
                th += 2 * mp.pi
            ends.append(th)
        pieces = [(min(ends), t0), (t0, max(ends))]
    for lo, hi in pieces:
        part = _ts(g, lo, hi, 12, tol)
        total = [t + p for t, p in zip(total, part, strict=True)]
    return total


def friction_ref12(a, b, x, y, z, dps=25, tol=1e-17):
    """[A (6), B (6)] with stress / (mu p0) = A + (1 - 2 nu) B, components in the order
    sxx, syy, szz, syz, sxz, sxy, as mpf; traction along +x."""
    with mp.workdps(dps):
        a, b, x, y, z = (mp.mpf(v) for v in (a, b, x, y, z))
        if z < 0:
            raise ValueError("z < 0")
        return _angular(a, b, x, y, z, mp.mpf(tol))


def friction_ref(a, b, nu, x, y, z, dps=25, tol=1e-17):
    """The stress / (mu p0) of the sliding traction along +x, as a 3x3 mpmath matrix."""
    v = friction_ref12(a, b, x, y, z, dps, tol)
    with mp.workdps(dps):
        k = 1 - 2 * mp.mpf(nu)
        sxx, syy, szz, syz, sxz, sxy = (v[i] + k * v[i + 6] for i in range(6))
        return mp.matrix([[sxx, sxy, sxz], [sxy, syy, syz], [sxz, syz, szz]])
