"""Independent mpmath reference for the stresses below a Hertz contact (does not import hertz).

The stress at a point is Boussinesq's point-load solution integrated over the Hertz pressure
p = p0 sqrt(1 - x^2/a^2 - y^2/b^2); the line contact integrates Flamant's solution over
p = p0 sqrt(1 - x^2/b^2). Nothing here uses the closed forms of hertz/_stress_kernel.c.

Boussinesq, unit normal force pressing on the half-space z >= 0 (z into the body, tension
positive), at horizontal offset (dx, dy) = r (cos t, sin t) from the force, R^2 = r^2 + z^2
(derived here from Boussinesq's displacement field by Hooke's law, checked with sympy for
equilibrium and the free surface; cf. Johnson, Contact Mechanics, sec. 3.2):

    sxx = [(1-2nu) (cos 2t / (R (R+z)) + z sin^2 t / R^3) - 3 z r^2 cos^2 t / R^5] / 2pi
    syy = [(1-2nu) (-cos 2t / (R (R+z)) + z cos^2 t / R^3) - 3 z r^2 sin^2 t / R^5] / 2pi
    szz = -3 z^3 / (2pi R^5)
    sxz = -3 r cos t z^2 / (2pi R^5),   syz = -3 r sin t z^2 / (2pi R^5)
    sxy = [(1-2nu) sin 2t (1/(R (R+z)) - z / (2 R^3)) - 3 z r^2 sin t cos t / R^5] / 2pi

The integral is taken in polar coordinates (r, theta) centred on the field point (x, y), the
source at (x, y) + r (cos theta, sin theta), so the offset is -r (cos theta, sin theta) and
the singularity of the kernel is at r = 0. Radially, for z > 0, the substitution
r = z sinh(s) turns every radial kernel into a bounded function of s (tanh(s/2),
tanh s sech s, tanh^3 s sech s, tanh s sech^3 s, tanh^2 s sech^2 s), and a further map
s = s1 + (s2 - s1) sin^2(pi v/2) (or s = S (1 - (1-v)^2)) makes the square-root zeros of p at
the ends of the chord analytic; nested Clenshaw-Curtis in v. For z = 0 the limits of the
kernels are used exactly: the delta-like parts give p at the field point, and the 1/r
part is a principal value taken by subtracting p(x, y) (its log term cancels over the full
circle of angles). Angularly: the trapezoid rule over the full circle for points well
inside a moderate ellipse (periodic analytic integrand); otherwise tanh-sinh on pieces
ending at the directions tangent to the edge (inside), or over the cone of rays that meet
the ellipse (outside), where the integrand has square-root ends.

Accuracy, measured: with dps = 25 and tol = 1e-17 it agreed with the closed forms of
hertz/_stress_kernel.c (themselves checked against a 50-digit evaluation of the same
formulas) to 1.5e-15 p0 or better at 173 points: b/a = 1, 1/1.0001, 0.5, 0.1, 1e-3, 1e-6;
on the surface inside, outside and on the edge (at axis ends and at an angle); at depths
1e-8 b to 10 b and out to 140 a; nu = -0.5 to 0.5. With the faster dps = 20, tol = 1e-15
of the tests the error was up to 3e-15. The convergence tests compare successive levels of
each rule, so a quadrature can stop early on a feature it has not resolved: the
tolerance is not a guarantee. Not trusted on the surface (z = 0) within about 1e-10 a of
the edge: at 6e-17 a outside it the error was 1.6e-7 (the angular integrand then has
features far narrower than the nodes); at 1e-8 a it was 7e-16. At the defaults a point
costs 0.1 s to 30 s, median 3 s, on a shared 2-core machine (long ellipses and points
just below or beside the edge are the slow ones; one outlier took 100 s). The 2-D line
reference uses mpmath.quad and is good to about 1e-25.
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


def _converged(diff, pdiff, scale, tol, squaring=False):
    """Stop when two estimates differ by less than tol, or when the error of the last one,
    extrapolated from the decrease of the differences, is below tol. For the trapezoid
    rule on a periodic analytic integrand and Clenshaw-Curtis on an analytic one the error
    decreases geometrically in the number of points, so doubling it squares the error
    (squaring=True: the error is about diff^2 / scale). Double exponential quadrature
    near singular integrands converges geometrically in the level only, so that the
    error is about diff^2 / pdiff."""
    if diff <= tol:
        return True
    if pdiff is None or not diff <= pdiff / 10:
        return False
    return diff * diff <= tol * (scale if squaring else pdiff)


def _ts(f, lo, hi, n, tol, maxlevel=12, minlevel=2):
    """Integral of the vector function f (list of n mpf) over [lo, hi] by tanh-sinh.
    f(x, dlo, dhi) receives the distances to both ends, exact near the ends. The step is
    halved until two levels differ by less than sqrt(tol * scale): the error of
    double-exponential quadrature roughly squares from one level to the next, so the last
    level is then good to about tol."""
    lo, hi = mp.mpf(lo), mp.mpf(hi)
    half = (hi - lo) / 2
    mid = (hi + lo) / 2
    total = [mp.mpf(0)] * n
    prev, pdiff = None, None
    dps = mp.mp.dps
    for level in range(0, maxlevel + 1):
        for x, comp, w in _level_nodes(level, dps):
            if x == 0:
                vals = f(mid, half, half)
                total = [t + w * v for t, v in zip(total, vals, strict=True)]
                continue
            d = half * comp
            v1 = f(hi - d, 2 * half - d, d)
            v2 = f(lo + d, d, 2 * half - d)
            total = [t + w * (p + q) for t, p, q in zip(total, v1, v2, strict=True)]
        # weights carry the step h of their own level: the level-l sum is the previous
        # total halved plus the new (odd) nodes
        est = [t * half for t in total]
        if prev is not None and level >= minlevel:
            diff = max(abs(e - p) for e, p in zip(est, prev, strict=True))
            scale = max(max(abs(e) for e in est), mp.mpf(1) if n == 6 else abs(half))
            if _converged(diff, pdiff, scale, tol):
                return est
            pdiff = diff
        prev = est
        total = [t / 2 for t in total]
    return est


# ---------------------------------------------------------------- Clenshaw-Curtis on [0, 1]
_CCN = {}


def _cc_rule(n, dps):
    """Clenshaw-Curtis rule with n + 1 points on [0, 1]: lists v, 1 - v, sin(pi v),
    sin^2(pi v / 2), cos^2(pi v / 2), weights."""
    key = (n, dps)
    if key not in _CCN:
        with mp.workdps(dps + 10):
            rows = []
            for j in range(n + 1):
                th = mp.pi * j / n
                c = 1 if j in (0, n) else 2
                acc = mp.mpf(1)
                for k in range(1, n // 2 + 1):
                    bk = 1 if 2 * k == n else 2
                    acc -= bk * mp.cos(2 * k * th) / (4 * k * k - 1)
                w = c * acc / n / 2
                v, om = mp.sin(th / 2) ** 2, mp.cos(th / 2) ** 2   # (1 -+ cos th)/2
                pv = mp.pi * v
                rows.append((v, om, mp.sin(pv), mp.sin(pv / 2) ** 2, mp.cos(pv / 2) ** 2, w))
            _CCN[key] = rows
    return _CCN[key]


def _cc(f, n_out, tol, nmin=8, nmax=2048):
    """Integral over [0, 1] of the vector function f(v, 1 - v, sin(pi v), sin^2(pi v/2),
    cos^2(pi v/2)) by nested Clenshaw-Curtis, doubling n until two estimates differ by
    less than sqrt(tol) relative to the scale (the error then is about tol, convergence
    being geometric)."""
    dps = mp.mp.dps
    vals = {}
    n = nmin
    prev, pdiff = None, None
    while True:
        rule = _cc_rule(n, dps)
        est = [mp.mpf(0)] * n_out
        step = nmax // n
        for j, (v, om, sp, s2, c2, w) in enumerate(rule):
            key = j * step
            if key not in vals:
                vals[key] = f(v, om, sp, s2, c2)
            est = [e + w * y for e, y in zip(est, vals[key], strict=True)]
        if prev is not None:
            diff = max(abs(e - p) for e, p in zip(est, prev, strict=True))
            scale = max([abs(e) for e in est] + [mp.mpf(1)])
            if _converged(diff, pdiff, scale, tol, squaring=True) or n >= nmax:
                return est
            pdiff = diff
        prev = est
        n *= 2


# ---------------------------------------------------------------- point contact
def chord(a, b, x, y, c, s):
    """(qa, r1, r2): the ray (x, y) + r (c, s) is inside the ellipse for r1 < r < r2, and
    1 - X^2/a^2 - Y^2/b^2 = qa (r2 - r)(r - r1) there; None if the ray misses it."""
    qa = (c / a) ** 2 + (s / b) ** 2
    qb = x * c / a ** 2 + y * s / b ** 2
    qc = (x / a) ** 2 + (y / b) ** 2 - 1
    disc = qb * qb - qa * qc
    if disc <= 0:
        return None
    sq = mp.sqrt(disc)
    # the source (x + r c, y + r s) is on the edge where qa r^2 + 2 qb r + qc = 0
    if qb >= 0:
        ra = -(qb + sq) / qa
        rb = qc / (qa * ra)
    else:
        rb = (sq - qb) / qa
        ra = qc / (qa * rb) if rb != 0 else mp.mpf(0)
    r1, r2 = min(ra, rb), max(ra, rb)
    if r2 <= 0:
        return None
    return qa, r1, r2


def _radial(a, b, x, y, z, theta, tol):
    """Radial integrals j1..j5 (see _angular) along the ray from (x, y) in direction theta,
    and cos, sin of theta; None if the ray misses the ellipse."""
    c, s = mp.cos(theta), mp.sin(theta)
    ch = chord(a, b, x, y, c, s)
    if ch is None:
        return None
    qa, r1, r2 = ch
    qc = (x / a) ** 2 + (y / b) ** 2 - 1
    inside = r1 <= 0            # the chord starts at the field point

    def cosmap(lo, hi, v0):
        """x = lo + (hi - lo) sin^2(pi v/2) for v = v0 + (1 - v0) t: x - lo and hi - x are
        squares of analytic functions of t. Returns a function of the CC node giving
        (x - lo, hi - x, dx/dt)."""
        L = hi - lo
        if v0 == 0:
            return lambda v, om, sp, s2, c2: (L * s2, L * c2, L * mp.pi * sp / 2)
        w = 1 - v0

        def m(v, om, sp, s2, c2):
            ph = mp.pi * (v0 + w * v) / 2
            return L * mp.sin(ph) ** 2, L * mp.cos(ph) ** 2, L * mp.pi * mp.sin(2 * ph) * w / 2
        return m

    if z > 0:
        s_hi = mp.asinh(r2 / z)
        e_shi = mp.exp(s_hi)
        s1 = mp.asinh(r1 / z)
        es1 = mp.exp(s1)
        if inside and s1 < -1:
            # s = s_hi (1 - om^2) on [0, s_hi]; the zero of p at s1 is far enough
            def smap(v, om, sp, s2, c2):
                dhi = s_hi * om * om
                return s_hi - dhi, dhi, 2 * s_hi * om
        else:
            v0 = 2 / mp.pi * mp.asin(mp.sqrt(-s1 / (s_hi - s1))) if inside else mp.mpf(0)
            cm = cosmap(s1, s_hi, v0)

            def smap(v, om, sp, s2, c2):
                dlo, dhi, ds = cm(v, om, sp, s2, c2)
                return s1 + dlo, dhi, ds

        def f(*node):
            sv, dhi, ds = smap(*node)
            if ds == 0:
                return [mp.mpf(0)] * 5
            e = mp.exp(sv)
            sh = (e - 1 / e) / 2 if abs(sv) > mp.mpf("0.1") else mp.sinh(sv)
            ch = (e + 1 / e) / 2
            r = z * sh
            # r2 - r = z (sinh s_hi - sinh s), r - r1 = z (sinh s - sinh s1), exact near the ends
            d2 = r2 - r if dhi > mp.mpf("0.5") else \
                z * e * mp.expm1(dhi) * (1 + 1 / (e * e_shi)) / 2
            dlo = sv - s1
            d1 = r - r1 if dlo > mp.mpf("0.5") else \
                z * es1 * mp.expm1(dlo) * (1 + 1 / (e * es1)) / 2
            p = mp.sqrt(qa * max(d2, 0) * max(d1, 0)) * ds
            th, se = sh / ch, 1 / ch
            pse = p * se
            return [p * sh / (ch + 1), pse * th, pse * th ** 3, pse * th * se * se,
                    pse * se * th * th]

        jr = _cc(f, 5, tol)
    else:
        L = r2 - r1
        if inside:
            pc = mp.sqrt(max(-qc, 0))
            v0 = 2 / mp.pi * mp.asin(mp.sqrt(-r1 / L))
            w = 1 - v0
            ph0 = mp.pi * v0 / 2

            def f(v, om, sp, s2, c2):
                # r = r1 + L sin^2(ph) = L sin(ph - ph0) sin(ph + ph0), ph = ph0 + pi w v/2;
                # (p - pc)/r = qa (r2 + r1 - r)/(p + pc) without cancellation
                ph = ph0 + mp.pi * w * v / 2
                r = L * mp.sin(mp.pi * w * v / 2) * mp.sin(ph + ph0)
                dr = L * mp.pi * mp.sin(2 * ph) * w / 2
                p = mp.sqrt(qa) * L * mp.sin(2 * ph) / 2
                if p + pc == 0:          # on the edge, at the field point
                    return [mp.sqrt(qa) * L * mp.pi * w]
                return [qa * (r2 + r1 - r) / (p + pc) * dr]

            j1 = _cc(f, 1, tol)[0] + (pc * mp.log(r2) if pc != 0 else 0)
            jr = [j1, pc, 2 * pc / 3, pc / 3, mp.mpf(0)]
        else:
            cm = cosmap(r1, r2, 0)

            def f(*node):
                d1, d2, dr = cm(*node)
                return [mp.sqrt(qa * d1 * d2) / (r1 + d1) * dr]

            jr = [_cc(f, 1, tol)[0], 0, 0, 0, 0]
    return jr, c, s


def _angular(a, b, x, y, z, nu, tol):
    """The stress as an integral over the direction theta of the ray from the field point,
    of radial integrals along it (s = asinh(r/z), R^2 = r^2 + z^2, p the pressure):

        j1 = int p r/(R(R+z)) dr = int p tanh(s/2) ds      j2 = int p z r/R^3 dr
        j3 = int p z r^3/R^5 dr     j4 = int p z^3 r/R^5 dr     j5 = int p z^2 r^2/R^5 dr
    """
    k = 1 - 2 * nu

    def g(theta, *ends):
        res = _radial(a, b, x, y, z, theta, tol / 10)
        if res is None:
            return [mp.mpf(0)] * 6
        (j1, j2, j3, j4, j5), c, s = res
        c2, s2, cs = c * c, s * s, c * s
        return [k * ((c2 - s2) * j1 + s2 * j2) - 3 * c2 * j3,
                k * (-(c2 - s2) * j1 + c2 * j2) - 3 * s2 * j3,
                -3 * j4,
                3 * s * j5,
                3 * c * j5,
                k * (2 * cs * j1 - cs * j2) - 3 * cs * j3]

    qc = (x / a) ** 2 + (y / b) ** 2 - 1
    total = [mp.mpf(0)] * 6
    if qc <= 0 and b * 4 >= a and qc <= mp.mpf("-0.1"):
        # well inside a moderate ellipse: the integrand is analytic and periodic in theta,
        # the trapezoid rule converges geometrically
        n, prev, pdiff, vals = 16, None, None, {}
        nmax = 4096
        while True:
            step = nmax // n
            for j in range(n):
                if j * step not in vals:
                    vals[j * step] = g(2 * mp.pi * j / n)
            est = [sum(vals[j * step][i] for j in range(n)) / n * 2 * mp.pi for i in range(6)]
            if prev is not None:
                diff = max(abs(e - p) for e, p in zip(est, prev, strict=True))
                if _converged(diff, pdiff, mp.mpf(1), tol, squaring=True) or n >= nmax:
                    total = est
                    break
                pdiff = diff
            prev = est
            n *= 2
    elif qc <= 0:
        # near the edge, or a long ellipse: the integrand has narrow features at the
        # directions tangent to the edge (normal +- pi/2); tanh-sinh on pieces ending there
        nx, ny = x / a ** 2, y / b ** 2
        tn = mp.atan2(ny, nx) if (nx != 0 or ny != 0) else mp.pi / 2
        br = [tn + j * mp.pi / 2 for j in range(5)]
        for lo, hi in zip(br[:-1], br[1:], strict=True):
            part = _ts(g, lo, hi, 6, tol)
            total = [t + p for t, p in zip(total, part, strict=True)]
    else:
        # outside: the cone of directions that meet the ellipse, between the two tangents
        # qa2 c^2 + 2 qb2 c s + qc2 s^2 = 0 (double root of the chord equation)
        qa2 = (x / a ** 2) ** 2 - qc / a ** 2
        qb2 = x * y / (a * a * b * b)
        qc2 = (y / b ** 2) ** 2 - qc / b ** 2
        t0 = mp.atan2(-y, -x)            # towards the centre, inside the cone
        ct, st = mp.cos(t0), mp.sin(t0)
        # theta = t0 + phi, P + 2 qh tan(phi) + R tan(phi)^2 = 0
        P = qa2 * ct * ct + 2 * qb2 * ct * st + qc2 * st * st
        qh = -qa2 * ct * st + qb2 * (ct * ct - st * st) + qc2 * st * ct
        R = qa2 * st * st - 2 * qb2 * ct * st + qc2 * ct * ct
        dq = mp.sqrt(qh * qh - P * R)
        ends = []
        for tan_phi in ((-qh - dq) / R, (-qh + dq) / R):
            # the line t0 + atan(tan_phi) (mod pi): the tangent is the direction along it that
            # points towards the ellipse (x c/a^2 + y s/b^2 < 0)
            th = t0 + mp.atan(tan_phi)
            if x * mp.cos(th) / a ** 2 + y * mp.sin(th) / b ** 2 > 0:
                th += mp.pi
            while th > t0 + mp.pi:
                th -= 2 * mp.pi
            while th < t0 - mp.pi:
                th += 2 * mp.pi
            ends.append(th)
        lo, hi = min(ends), max(ends)
        for p_lo, p_hi in ((lo, t0), (t0, hi)):
            part = _ts(g, p_lo, p_hi, 6, tol)
            total = [t + p for t, p in zip(total, part, strict=True)]
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


# ---------------------------------------------------------------- the z axis (closed form)
def axis_stress_ref(a, b, nu, z, dps=30):
    """(sxx, syy, szz) / p0 on the z axis of an elliptical contact, the published closed
    form (Johnson, Contact Mechanics sec. 3.5; Thomas & Hoersch 1930) with mpmath's own
    Carlson integral; s = z^2, A = a^2 + s, B = b^2 + s:

        szz = -a b / sqrt(A B)
        sxx = a b [2(1-nu)/3 z R_D(s,B,A) - 2nu/3 z R_D(A,B,s) - (1-2nu)/(sqrt A (sqrt A + sqrt B))]
        syy = a b [2(1-nu)/3 z R_D(s,A,B) - 2nu/3 z R_D(A,B,s) - (1-2nu)/(sqrt B (sqrt A + sqrt B))]

    (the last terms are (1 - sqrt(B/A))/(a^2 - b^2) and (sqrt(A/B) - 1)/(a^2 - b^2) written
    without the division). tests/test_stress_kernel.py checks it against stress_ref6."""
    with mp.workdps(max(dps, mp.mp.dps)):      # never below the caller's (mpmath.diff)
        a, b, nu, z = (mp.mpf(v) for v in (a, b, nu, z))
        s = z * z
        A, B = a * a + s, b * b + s
        r_a, r_b = mp.sqrt(A), mp.sqrt(B)
        if z == 0:
            ja = jb = mp.mpf(0)
            jw = 2 / (r_a * r_b)
        else:
            ja = 2 * z * mp.elliprd(s, B, A) / 3
            jb = 2 * z * mp.elliprd(s, A, B) / 3
            jw = 2 * z * mp.elliprd(A, B, s) / 3
        c1 = 1 - 2 * nu
        sxx = a * b * ((1 - nu) * ja - nu * jw - c1 / (r_a * (r_a + r_b)))
        syy = a * b * ((1 - nu) * jb - nu * jw - c1 / (r_b * (r_a + r_b)))
        return sxx, syy, -a * b / (r_a * r_b)


def axis_maxima_ref(a, b, nu, dps=30, npts=160):
    """Largest (s1 - s3)/2 and von Mises stress on the z axis, as {"tau": (value, z),
    "von_mises": (value, z)}: for each of (sxx - szz)/2, (syy - szz)/2 (szz is the smallest
    principal stress on the axis) and the von Mises stress, a scan of depths (the surface,
    and geometric from 1e-8 b to 3 b), then the root of the derivative (mpmath.diff at twice
    the precision) bracketed by the neighbours of the best point of the scan."""

    def target(z, i, d):
        sxx, syy, szz = axis_stress_ref(a, b, nu, z, d)
        if i == 0:
            return (sxx - szz) / 2
        if i == 1:
            return (syy - szz) / 2
        return mp.sqrt(((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) / 2)

    with mp.workdps(dps):
        bm = mp.mpf(b)
        step = mp.log10(3 * mp.mpf(10) ** 8) / npts
        zs = [mp.mpf(0)] + [bm * mp.mpf(10) ** (-8 + j * step) for j in range(npts + 1)]
        scan = []
        for z in zs:
            sxx, syy, szz = axis_stress_ref(a, b, nu, z, dps)
            scan.append(((sxx - szz) / 2, (syy - szz) / 2, mp.sqrt(
                ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) / 2)))
        out = {}
        for name, funcs in (("tau", (0, 1)), ("von_mises", (2,))):
            best = None
            for i in funcs:
                vals = [v[i] for v in scan]
                j = max(range(len(vals)), key=lambda m: vals[m])
                if j == 0:
                    cand = (vals[0], mp.mpf(0))
                else:
                    with mp.workdps(2 * dps):
                        lo, hi = zs[j - 1], zs[min(j + 1, len(zs) - 1)]
                        zz = mp.findroot(
                            lambda z, i=i: mp.diff(lambda t: target(t, i, 2 * dps), z),
                            (lo, hi), solver="illinois", tol=mp.mpf(10) ** (-2 * dps + 10))
                        cand = (target(zz, i, 2 * dps), zz)
                if best is None or cand[0] > best[0]:
                    best = cand
            out[name] = (+best[0], +best[1])
        return out
