"""Independent mpmath reference for the stresses of a tangential traction on a circular contact
(issue 17 item 4, a start): Cerruti's point-force stresses integrated over the traction
q = sqrt(1 - r^2/a^2) along +x (the sliding traction mu p with mu p0 = 1).  Does not import hertz.

Cerruti, a tangential point force Q along +x on the surface of the half-space z >= 0 (z into
the body, tension positive), at offset (x, y, z) from the force, rho^2 = x^2 + y^2 + z^2,
k = 1 - 2 nu (Johnson, Contact Mechanics, ch. 3):

    sxx = Q/2pi [-3x^3/rho^5 + k (x/rho^3 - 3x/(rho (rho+z)^2) + x^3/(rho^3 (rho+z)^2)
                                  + 2x^3/(rho^2 (rho+z)^3))]
    syy = Q/2pi [-3xy^2/rho^5 + k (x/rho^3 - x/(rho (rho+z)^2) + xy^2/(rho^3 (rho+z)^2)
                                   + 2xy^2/(rho^2 (rho+z)^3))]
    szz = -3Q x z^2/(2pi rho^5),   sxz = -3Q x^2 z/(2pi rho^5),   syz = -3Q x y z/(2pi rho^5)
    sxy = Q/2pi [-3x^2 y/rho^5 + k (-y/(rho (rho+z)^2) + x^2 y/(rho^3 (rho+z)^2)
                                    + 2x^2 y/(rho^2 (rho+z)^3))]

These were checked against Hooke's law applied to Cerruti's displacement field (with sympy
while writing this; by mpmath differentiation in tests/test_sliding_reference.py, with
equilibrium and the free surface); the field transmits the force through the plane z = 1
(sympy, mpmath.quad: -0.99999999999999569 at 20 digits of a unit force).

Quadrature, for a point (x0, y0, z0) with z0 > 0 above the contact (x0^2 + y0^2 < a^2): polar
coordinates (r, t) about (x0, y0), the source at (x0, y0) + r (cos t, sin t), the offset
-r (cos t, sin t).  Radially r = z0 sinh(s) makes r dr / rho^2 = tanh(s) ds bounded, and
s = S (1 - (1 - v)^2), S = asinh(R/z0) with R the distance to the edge along the ray, makes the
square-root zero of the traction at the edge analytic; Gauss-Legendre in v and the
trapezoid rule in t (periodic, analytic for a point inside the disc), all six stresses from
one pass.  Measured: converged to the working precision (1e-20 mu p0) with 96 x 48 points at
depths 0.05 a to 0.5 a; an adaptive mpmath.quad version of the same integral agreed to the 15
digits printed (at 300 s a point, against 3 s).
"""

import mpmath as mp

__all__ = ["DPS", "cerruti", "sliding_stress", "axis_shear"]

DPS = 20


def cerruti(nu, x, y, z):
    """Cerruti's stresses (sxx, syy, szz, sxy, sxz, syz) for a unit force along +x."""
    rho2 = x * x + y * y + z * z
    rho = mp.sqrt(rho2)
    rz = rho + z
    k = 1 - 2 * nu
    r5 = rho2 * rho2 * rho
    r3 = rho2 * rho
    t1 = 1 / (rho * rz * rz)
    t2 = 1 / (r3 * rz * rz)
    t3 = 2 / (rho2 * rz * rz * rz)
    c = 1 / (2 * mp.pi)
    sxx = c * (-3 * x ** 3 / r5 + k * (x / r3 - 3 * x * t1 + x ** 3 * (t2 + t3)))
    syy = c * (-3 * x * y * y / r5 + k * (x / r3 - x * t1 + x * y * y * (t2 + t3)))
    szz = -3 * c * x * z * z / r5
    sxy = c * (-3 * x * x * y / r5 + k * (-y * t1 + x * x * y * (t2 + t3)))
    sxz = -3 * c * x * x * z / r5
    syz = -3 * c * x * y * z / r5
    return sxx, syy, szz, sxy, sxz, syz


def _gauss_legendre(n):
    """Gauss-Legendre nodes and weights on (0, 1) at the working precision."""
    nodes = []
    for k in range(1, n + 1):
        x = mp.cos(mp.pi * (k - mp.mpf(1) / 4) / (n + mp.mpf(1) / 2))
        for _ in range(100):  # Newton on P_n
            p0, p1 = mp.mpf(1), x
            for j in range(2, n + 1):
                p0, p1 = p1, ((2 * j - 1) * x * p1 - (j - 1) * p0) / j
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < mp.eps * 4:
                break
        p0, p1 = mp.mpf(1), x
        for j in range(2, n + 1):
            p0, p1 = p1, ((2 * j - 1) * x * p1 - (j - 1) * p0) / j
        dp = n * (x * p1 - p0) / (x * x - 1)
        nodes.append(((1 - x) / 2, 1 / ((1 - x * x) * dp * dp)))
    return nodes


def sliding_stress(a, nu, x0, y0, z0, n_angle=96, n_radial=48):
    """The six stresses (sxx, syy, szz, sxy, sxz, syz) at (x0, y0, z0), z0 > 0, under the
    traction sqrt(1 - r^2/a^2) along +x on the disc r <= a (multiply by mu p0 [Pa]).

    The trapezoid rule over the full circle of ray angles (the integrand is periodic and
    analytic for a point inside the disc) with n_angle points, Gauss-Legendre in v with
    n_radial points; compare two sizes to see the error."""
    with mp.workdps(DPS):
        a, nu, x0, y0, z0 = (mp.mpf(v) for v in (a, nu, x0, y0, z0))
        c0 = 1 - (x0 * x0 + y0 * y0) / (a * a)
        if not (z0 > 0 and c0 > 0):
            raise ValueError("the reference takes points below the contact: z0 > 0, r0 < a")
        rule = _gauss_legendre(n_radial)
        A = 1 / (a * a)
        total = [mp.mpf(0)] * 6
        for i in range(n_angle):
            t = 2 * mp.pi * i / n_angle
            ct, st = mp.cos(t), mp.sin(t)
            B = (x0 * ct + y0 * st) / (a * a)
            R = (mp.sqrt(B * B + A * c0) - B) / A  # distance to the edge along the ray
            top = mp.asinh(R / z0)
            for v, w in rule:
                u = 1 - v
                s = top * (1 - u * u)
                r = z0 * mp.sinh(s)
                q2 = c0 - 2 * B * r - A * r * r  # 1 - |source|^2 / a^2
                q = mp.sqrt(q2) if q2 > 0 else mp.mpf(0)
                # ds = 2 top u dv;  r dr = r z0 cosh(s) ds
                weight = w * q * r * z0 * mp.cosh(s) * 2 * top * u
                kern = cerruti(nu, -r * ct, -r * st, z0)
                for c in range(6):
                    total[c] += weight * kern[c]
        return tuple(x * 2 * mp.pi / n_angle for x in total)


def axis_shear(a, z0):
    """sxz on the axis (0, 0, z0) as a 1-D integral (the other stresses vanish there by
    symmetry): -(3 z0 / 2) int_0^a sqrt(1 - r^2/a^2) r^3 / (r^2 + z0^2)^(5/2) dr."""
    with mp.workdps(DPS):
        a, z0 = mp.mpf(a), mp.mpf(z0)
        return -3 * z0 / 2 * mp.quad(
            lambda r: mp.sqrt(1 - (r / a) ** 2) * r ** 3 / (r * r + z0 * z0) ** mp.mpf(2.5),
            [0, a])
