"""Independent mpmath reference for the stresses below a Hertz contact (does not import hertz).

The stress at a point is Boussinesq's point-load solution integrated over the Hertz pressure
p = p0 sqrt(1 - x^2/a^2 - y^2/b^2); the line contact integrates Flamant's solution over
p = p0 sqrt(1 - x^2/b^2). Nothing here uses the closed forms of hertz/_stress_kernel.c.

Boussinesq, unit normal force pressing on the half-space z >= 0 (z into the body, tension
positive), at horizontal offset (dx, dy) = r (cos t, sin t) from the force, R^2 = r^2 + z^2
(derived here from the displacement field by Hooke's law and checked with sympy; Johnson,
Contact Mechanics, eq. 3.22 with the factor 2 of tau_xy):

    sxx = [(1-2nu) (cos 2t / (R (R+z)) + z sin^2 t / R^3) - 3 z r^2 cos^2 t / R^5] / 2pi
    syy = [(1-2nu) (-cos 2t / (R (R+z)) + z cos^2 t / R^3) - 3 z r^2 sin^2 t / R^5] / 2pi
    szz = -3 z^3 / (2pi R^5),      sxz = -3 r cos t z^2 / (2pi R^5),   syz = -3 r sin t z^2 / (2pi R^5)
    sxy = [(1-2nu) sin 2t (1/(R (R+z)) - z / (2 R^3)) - 3 z r^2 sin t cos t / R^5] / 2pi

The integral is taken in polar coordinates (r, theta) centred on the field point (x, y), the
source at (x, y) + r (cos theta, sin theta), so the offset is -r (cos theta, sin theta); the
singularity of the kernel at r = 0 is then the origin of the radial variable. For z > 0 the
substitution r = z sinh(s) turns every radial kernel into a bounded function of s
(tanh(s/2), tanh s sech s, tanh^3 s sech s, tanh s sech^3 s, tanh^2 s sech^2 s), and the
square-root zeros of p at the ends of the chord are left to double-exponential (tanh-sinh)
quadrature, which is insensitive to them. For z = 0 the limits of these kernels are used
exactly: the delta-like parts give p at the field point, and the 1/r part is a principal
value taken by subtracting p(x, y) (its log term cancels over the full circle of angles).
The angular integral is tanh-sinh as well, split at the axis directions and at the
direction of the nearest point of the edge (inside) or over the cone of rays that meet the
ellipse (outside), where the integrand has square-root ends.

Accuracy (measured by comparing levels of the quadratures and with closed forms on the
axis; see tests/test_stress_kernel.py): with the default dps = 30 and tol = 1e-17 the
components agree to better than 1e-14 p0 everywhere tried: depth 0 to 1e6 a, inside,
outside and at the edge of the ellipse, b/a from 1e-6 to 1. It is not trusted within about
1e-10 a of the edge *at* z = 0 and 0 < z < 1e-10 b, where the angular integrand develops
features narrower than the node spacing at the default levels. A point costs about 0.5 to 5 s.
"""

import mpmath as mp

__all__ = ["stress_ref", "stress_ref6", "line_stress_ref", "line_stress_ref4"]


# ---------------------------------------------------------------- tanh-sinh, vector valued
_NODES = {}


def _level_nodes(level, dps):
    """Nodes of level `level` (step h = 2^-level; odd multiples only for level > 0) on
    (-1, 1): list of (x, 1 - |x|, weight) with x >= 0 (use +-x)."""
    key = (level, dps)
    if key in _NODES:
        return _NODES[key]
    with mp.workdps(dps + 10):
        h = mp.mpf(2) ** (-level)
        out = []
        k = 0 if level == 0 else 1
        eps = mp.mpf(10) ** (-(dps + 8))
        while True:
            t = k * h
            u = mp.pi / 2 * mp.sinh(t)
            c = mp.cosh(u)
            w = h * mp.pi / 2 * mp.cosh(t) / c ** 2
            comp = 1 / (mp.exp(u) * c)      # 1 - tanh(u)
            out.append((1 - comp, comp, w))
            if w < eps or comp < eps:
                break
            k += 1 if level == 0 else 2
    _NODES[key] = out
    return out


def _ts(f, lo, hi, n, tol, maxlevel=12, minlevel=3):
    """Integral of the vector function f (list of n mpf) over [lo, hi] by tanh-sinh.
    f(x, dlo, dhi) receives the distances to both ends, exact near the ends."""
    lo, hi = mp.mpf(lo), mp.mpf(hi)
    half = (hi - lo) / 2
    mid = (hi + lo) / 2
    total = [mp.mpf(0)] * n
    prev = None
    dps = mp.mp.dps
    for level in range(0, maxlevel + 1):
        for x, comp, w in _level_nodes(level, dps):
            if x == 0:
                vals = f(mid, half, half)
                total = [t + w * v for t, v in zip(total, vals)]
                continue
            d = half * comp
            v1 = f(hi - d, 2 * half - d, d)
            v2 = f(lo + d, d, 2 * half - d)
            total = [t + w * (p + q) for t, p, q in zip(total, v1, v2)]
        # weights carry the step h of their own level: the level-l sum is the previous
        # total halved plus the new (odd) nodes
        est = [t * half for t in total]
        if prev is not None and level >= minlevel:
            if max(abs(e - p) for e, p in zip(est, prev)) <= tol:
                return est
        prev = est
        total = [t / 2 for t in total]
    return est


# ---------------------------------------------------------------- point contact
def _radial(a, b, x, y, z, theta, n_tol):
    """Radial integrals J1..J5 along the ray from (x, y) in direction theta, and
    cos/sin of theta. Returns None if the ray misses the ellipse."""
    c, s = mp.cos(theta), mp.sin(theta)
    qa = (c / a) ** 2 + (s / b) ** 2
    qb = x * c / a ** 2 + y * s / b ** 2
    qc = (x / a) ** 2 + (y / b) ** 2 - 1
    disc = qb * qb - qa * qc
    if disc <= 0:
        return None
    sq = mp.sqrt(disc)
    # roots of qa r^2 + 2 qb r + qc = 0
    if qb >= 0:
        r1 = -(qb + sq) / qa
        r2 = qc / (qa * r1) if r1 != 0 else mp.mpf(0)
    else:
        r2 = (-qb + sq) / qa
        r1 = qc / (qa * r2)
    r1, r2 = min(r1, r2), max(r1, r2)
    if r2 <= 0:
        return None
    lo = max(r1, mp.mpf(0))
    inside = r1 <= 0

    if z > 0:
        slo = mp.asinh(lo / z)
        shi = mp.asinh(r2 / z)

        def f(sv, dlo, dhi):
            r = z * mp.sinh(sv)
            # r2 - r and r - r1 from the distances to the ends, exact near the ends
            d2 = 2 * z * mp.cosh((shi + sv) / 2) * mp.sinh(dhi / 2)
            d1 = r - r1 if inside else 2 * z * mp.cosh((slo + sv) / 2) * mp.sinh(dlo / 2)
            p = mp.sqrt(qa * max(d2, 0) * max(d1, 0))
            th, sh = mp.tanh(sv), 1 / mp.cosh(sv)
            return [p * mp.tanh(sv / 2), p * th * sh, p * th ** 3 * sh,
                    p * th * sh ** 3, p * th ** 2 * sh ** 2]

        J = _ts(f, slo, shi, 5, n_tol)
    else:
        if inside:
            pc = mp.sqrt(max(-qc, 0))

            def f(r, dlo, dhi):
                p = mp.sqrt(qa * dhi * (r - r1))
                return [(p - pc) / r if r != 0 else mp.mpf(0)]

            J1 = _ts(f, 0, r2, 1, n_tol)[0] + (pc * mp.log(r2) if pc != 0 else 0)
            J = [J1, pc, 2 * pc / 3, pc / 3, mp.mpf(0)]
        else:
            def f(r, dlo, dhi):
                return [mp.sqrt(qa * dhi * dlo) / r]

            J = [_ts(f, r1, r2, 1, n_tol)[0], 0, 0, 0, 0]
    return J, c, s


def _angular(a, b, x, y, z, nu, tol):
    def g(theta, dlo, dhi):
        res = _radial(a, b, x, y, z, theta, tol / 10)
        if res is None:
            return [mp.mpf(0)] * 6
        (J1, J2, J3, J4, J5), c, s = res
        c2, s2, cs = c * c, s * s, c * s
        k = 1 - 2 * nu
        return [k * ((c2 - s2) * J1 + s2 * J2) - 3 * c2 * J3,
                k * (-(c2 - s2) * J1 + c2 * J2) - 3 * s2 * J3,
                -3 * J4,
                3 * s * J5,
                3 * c * J5,
                k * (2 * cs * J1 - cs * J2) - 3 * cs * J3]

    qc = (x / a) ** 2 + (y / b) ** 2 - 1
    total = [mp.mpf(0)] * 6
    if qc <= 0:
        # full circle: break at the axis directions and the inward/outward normals
        breaks = {mp.mpf(0), mp.pi / 2, mp.pi, 3 * mp.pi / 2, 2 * mp.pi}
        nx, ny = x / a ** 2, y / b ** 2
        if nx != 0 or ny != 0:
            tn = mp.atan2(ny, nx) % (2 * mp.pi)
            breaks |= {(tn + k * mp.pi / 2) % (2 * mp.pi) for k in range(4)}
        br = sorted(breaks)
        for lo, hi in zip(br[:-1], br[1:]):
            if hi - lo > mp.mpf(10) ** (-mp.mp.dps + 3):
                part = _ts(g, lo, hi, 6, tol)
                total = [t + p for t, p in zip(total, part)]
    else:
        # cone of directions that meet the ellipse: tangent directions from (x, y)
        # (x + r c)^2/a^2 + (y + r s)^2/b^2 = 1 has a double root when
        # (x c/a^2 + y s/b^2)^2 = qc (c^2/a^2 + s^2/b^2)
        A2 = (x / a ** 2) ** 2 - qc / a ** 2
        B2 = x * y / (a * a * b * b)
        C2 = (y / b ** 2) ** 2 - qc / b ** 2
        # A2 c^2 + 2 B2 c s + C2 s^2 = 0; parametrise by the angle
        t0 = mp.atan2(-y, -x)            # direction to the centre
        # solve in tan of (theta - t0) numerically-exactly via the quadratic form rotated
        ct, st = mp.cos(t0), mp.sin(t0)
        # theta = t0 + phi: c = ct cos phi - st sin phi, s = st cos phi + ct sin phi
        P = A2 * ct * ct + 2 * B2 * ct * st + C2 * st * st
        Qh = -A2 * ct * st + B2 * (ct * ct - st * st) + C2 * st * ct
        R = A2 * st * st - 2 * B2 * ct * st + C2 * ct * ct
        # P + 2 Qh tan(phi) + R tan^2(phi) = 0
        dq = mp.sqrt(Qh * Qh - P * R)
        roots = sorted([mp.atan((-Qh - dq) / R), mp.atan((-Qh + dq) / R)])
        lo, hi = t0 + roots[0], t0 + roots[1]
        mid = t0
        for l, h in ((lo, mid), (mid, hi)):
            part = _ts(g, l, h, 6, tol)
            total = [t + p for t, p in zip(total, part)]
    return [t / (2 * mp.pi) for t in total]


def stress_ref6(a, b, nu, x, y, z, dps=30, tol=1e-17):
    """[sxx, syy, szz, syz, sxz, sxy] / p0 at (x, y, z), as mpf; a along x, b along y,
    z >= 0 into the body, tension positive."""
    with mp.workdps(dps):
        a, b, nu, x, y, z = (mp.mpf(v) for v in (a, b, nu, x, y, z))
        if z < 0:
            raise ValueError("z < 0")
        return _angular(a, b, x, y, z, nu, mp.mpf(tol))


def stress_ref(a, b, nu, x, y, z, dps=30, tol=1e-17):
    """The Cauchy stress / p0 at (x, y, z) as a 3x3 mpmath matrix."""
    sxx, syy, szz, syz, sxz, sxy = stress_ref6(a, b, nu, x, y, z, dps, tol)
    with mp.workdps(dps):
        return mp.matrix([[sxx, sxy, sxz], [sxy, syy, syz], [sxz, syz, szz]])


# ---------------------------------------------------------------- line contact
def line_stress_ref4(nu, x, z, dps=30):
    """[sxx, szz, sxz, syy] / p0 of the plane-strain line contact of semi-width 1:
    Flamant's solution integrated over p = sqrt(1 - s^2), |s| <= 1.

    Flamant, unit line force per length at s, offset X = x - s: sxx = -2 X^2 z/(pi rho^4),
    szz = -2 z^3/(pi rho^4), sxz = -2 X z^2/(pi rho^4), rho^2 = X^2 + z^2. With
    s = x - z sinh(t) every kernel times ds is bounded. Good to about 1e-25."""
    with mp.workdps(dps):
        x, z, nu = mp.mpf(x), mp.mpf(z), mp.mpf(nu)
        if z == 0:
            p = mp.sqrt(max((1 - x) * (1 + x), 0))
            sxx, szz, sxz = -p, -p, mp.mpf(0)
        else:
            # s = x - z sinh t runs from 1 (t = tlo) to -1 (t = thi)
            tlo, thi = mp.asinh((x - 1) / z), mp.asinh((x + 1) / z)

            def p(t):
                s = x - z * mp.sinh(t)
                return mp.sqrt(max((1 - s) * (1 + s), 0))

            pts = [tlo, thi] if not (tlo < 0 < thi) else [tlo, 0, thi]
            c = -2 / mp.pi
            sxx = c * mp.quad(lambda t: p(t) * mp.sinh(t) ** 2 / mp.cosh(t) ** 3, pts)
            szz = c * mp.quad(lambda t: p(t) / mp.cosh(t) ** 3, pts)
            sxz = c * mp.quad(lambda t: p(t) * mp.sinh(t) / mp.cosh(t) ** 3, pts)
        return [sxx, szz, sxz, nu * (sxx + szz)]


def line_stress_ref(nu, x, z, dps=30):
    """Line-contact stress / p0 at (x, z) (semi-width 1) as a 3x3 mpmath matrix in the
    order (x, y, z), y along the strip."""
    sxx, szz, sxz, syy = line_stress_ref4(nu, x, z, dps)
    with mp.workdps(dps):
        return mp.matrix([[sxx, 0, sxz], [0, syy, 0], [sxz, 0, szz]])
