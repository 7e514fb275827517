/* The stress field below a Hertz contact, in closed form, and its maxima (pure C99).
 *
 * Point contact. The Hertz pressure p = p0 sqrt(1 - x^2/a^2 - y^2/b^2) acting on the
 * half-space z >= 0 gives, with Boussinesq's potentials for a normal load (Johnson,
 * Contact Mechanics, sec. 3.2; Love 1929),
 *
 *   sxx = [2 nu phi_z - z phi_xx - (1-2nu) psi_xx] / 2pi     szz = [phi_z - z phi_zz] / 2pi
 *   syy = [2 nu phi_z - z phi_yy - (1-2nu) psi_yy] / 2pi     sxz = -z phi_xz / 2pi
 *   sxy = -[(1-2nu) psi_xy + z phi_xy] / 2pi                 syz = -z phi_yz / 2pi
 *
 * phi = int p / rho dA, psi = int p ln(rho + z) dA, psi_z = phi. For the Hertz pressure
 * phi is the potential of a flattened ellipsoid (Johnson sec. 3.5; Thomas & Hoersch 1930):
 *
 *   phi = (pi a b p0 / 2) int_l^inf [1 - x^2/(a^2+w) - y^2/(b^2+w) - z^2/w] dw / D(w),
 *   D(w) = sqrt((a^2+w)(b^2+w) w),
 *
 * l the ellipsoidal coordinate of the point (the positive root of
 * x^2/(a^2+l) + y^2/(b^2+l) + z^2/l = 1). Its derivatives need
 * I_A = int_l^inf dw/((a^2+w) D) = (2/3) R_D(l, B, A), I_B = (2/3) R_D(l, A, B) and
 * I_w = int_l^inf dw/(w D) = 2/D(l) - I_A - I_B (A = a^2 + l, B = b^2 + l; R_D is
 * Carlson's integral, DLMF 19.16.5, by duplication, DLMF 19.36; the last identity is the
 * sum rule of the three R_D, DLMF 19.21) and the derivatives of l (implicit
 * differentiation).
 *
 * psi_xx, psi_yy, psi_xy carry the (1-2nu) terms. They are derived here (the explicit
 * forms of Sackfield & Hills, J. Strain Anal. 18, 1983, were not at hand) from
 * psi_x = -int_z^inf phi_x dz' by exchanging the order of the z' and w integrations:
 * with t(w)^2 = w (1 - x^2/(a^2+w) - y^2/(b^2+w)),
 *
 *   psi_x = pi a b p0 x int_l^inf (t(w) - z) dw / ((a^2+w) D(w)),
 *
 * and t/D = sqrt(P(w))/((a^2+w)(b^2+w)) with P(w) = (a^2+w)(b^2+w) - x^2 (b^2+w)
 * - y^2 (a^2+w) a quadratic: the second derivatives of psi are elementary. With
 * P = (w - w1)(w - w2), X = l - w2, Y = l - w1, sigma = sqrt(XY), q = sqrt X + sqrt Y,
 * E_p = p + sigma:
 *
 *   g(p) = int_0^inf dt / ((t + p) sqrt((t + X)(t + Y))) = 2 R_C(E_p^2, p q^2)
 *        = (2 / E_p) T(eps_p),      eps_p = (p - X)(p - Y) / E_p^2,
 *
 * T(e) = artanh(sqrt e)/sqrt e (e > 0), arctan(sqrt(-e))/sqrt(-e) (e < 0), and exactly
 * eps_A = x^2 (a^2 - b^2) / E_A^2, eps_B = -y^2 (a^2 - b^2) / E_B^2. psi_xx needs g(A),
 * -g'(A) and the divided difference -(g(A) - g(B))/(A - B); with S(e) = (T(e) - 1)/e the
 * latter is 2/(E_A E_B) - 2 x^2 S(eps_A)/E_A^3 - 2 y^2 S(eps_B)/E_B^3, free of any
 * division by a - b: the circle a = b and a -> b need no special case. psi_yy is taken from
 * psi_xx + psi_yy = -phi_z (psi is harmonic): its own integrals are of order 1/b^2 and
 * cancel to order 1 for a long ellipse. Every term is written with zeta = z / sqrt(l)
 * (= p/p0 on the surface inside the contact, 0 outside) instead of z and l, so that the
 * surface z = 0 (Johnson sec. 3.5) is the same code. Near the edge the stresses depend
 * on sqrt(1 - x^2/a^2 - y^2/b^2), which is computed in double-double arithmetic.
 *
 * The ellipsoidal coordinate solves a form of the cubic in which every factor is a sum of
 * non-negative terms (solve_v): full relative precision for l ~ z^2 (near the surface)
 * and l ~ r^2 (far away).
 *
 * Line contact (plane strain): McEwen, Phil. Mag. 40 (1949); Johnson sec. 4.2, written
 * with the complex square root m + i n = sqrt(b^2 - (x - i z)^2) and
 * m - z = Re b^2 / (m + z + i (n + x)), free of cancellation at depth.
 *
 * Maxima on the axis: the axis stresses are principal; their z-derivatives are elementary
 * once the two R_D are known. For 0.25 <= nu <= 0.5 and b/a >= 1e-3 the maxima start
 * from fitted depths (one exact evaluation and a Halley step, axis_maxima_direct);
 * elsewhere they are found from a table of the targets and their first two derivatives at
 * a few depths (quintic Hermite interpolation), then by Halley's method on the derivative. Orthogonal shear: Lundberg & Palmgren (1947), closed form in
 * the root t of (b/a)^2 = (t^2 - 1)(2t - 1); the position y = b t/(t+1) sqrt((2t+1)/(2t-1))
 * was derived here (maximum of |syz| over the plane x = 0).
 *
 * Everything was checked against an mpmath quadrature of Boussinesq's and Flamant's
 * solutions (tests/reference_stress.py, tests/test_stress_kernel.py).
 */
#include <math.h>

#include "_stress_kernel.h"

/* ------------------------------------------------------------------ Carlson R_D */

/* R_D(x, y, z) and R_D(x, z, y) (DLMF 19.16.5), x >= 0, y, z > 0, by Carlson's
   duplication (DLMF 19.36.2, Carlson 1995 Numer. Algorithms 10, 13) run once for both:
   the duplicated triple is symmetric, only the sums and the final series differ. */
static double rd_series(double x, double y, double z)
{
    double A = (x + y + 3.0 * z) / 5.0;
    double X = (A - x) / A, Y = (A - y) / A, Z = -(X + Y) / 3.0;
    double XY = X * Y, Z2 = Z * Z;
    double E2 = XY - 6.0 * Z2, E3 = (3.0 * XY - 8.0 * Z2) * Z, E4 = 3.0 * (XY - Z2) * Z2;
    double E5 = XY * Z2 * Z;
    /* Carlson's series to seventh order (the terms of degree 6 and 7 are those of his
       R_J series with p = z; checked against mpmath: error 4e-18 at deviations 0.01) */
    double s = 1.0 - 3.0 / 14.0 * E2 + E3 / 6.0 + 9.0 / 88.0 * E2 * E2 - 3.0 / 22.0 * E4
               - 9.0 / 52.0 * E2 * E3 + 3.0 / 26.0 * E5 - E2 * E2 * E2 / 16.0
               + 3.0 / 40.0 * E3 * E3 + 3.0 / 20.0 * E2 * E4 + 45.0 / 272.0 * E2 * E2 * E3
               - 9.0 / 68.0 * (E3 * E4 + E2 * E5);
    return s / (A * sqrt(A));
}

static void rd_pair(double x, double y, double z, double *rd_xyz, double *rd_xzy)
{
    double sum_z = 0.0, sum_y = 0.0, fac = 1.0;
    int i;
    for (i = 0; i < 100; i++) {
        double m = (x + y + z) / 3.0;
        double dx = fabs(x - m), dy = fabs(y - m), dz = fabs(z - m);
        double dev = dx > dy ? dx : dy;   /* (comparisons: fmax is a libm call here) */
        double sx, sy, sz, lam;
        dev = dev > dz ? dev : dz;
        if (dev <= 1e-2 * m)
            break;
        sx = sqrt(x);
        sy = sqrt(y);
        sz = sqrt(z);
        lam = sx * (sy + sz) + sy * sz;
        {
            double pz = sz * (z + lam), py = sy * (y + lam), r = fac / (pz * py);
            sum_z += py * r;                  /* fac / pz */
            sum_y += pz * r;                  /* fac / py */
        }
        fac *= 0.25;
        x = 0.25 * (x + lam);
        y = 0.25 * (y + lam);
        z = 0.25 * (z + lam);
    }
    *rd_xyz = 3.0 * sum_z + fac * rd_series(x, y, z);
    *rd_xzy = 3.0 * sum_y + fac * rd_series(x, z, y);
}

#define RD_BATCH 16

/* The duplication stops once every deviation from the mean is below tol times the mean:
   RD_EXACT (1e-2) leaves a series error of about 4e-18; RD_ROUGH (0.1, two duplications
   fewer) one below 1e-9, enough for the table that only locates the maxima. */
#define RD_EXACT 1e-2
#define RD_ROUGH 1e-1

/* rd_pair for n <= RD_BATCH triples at once, in lockstep: the duplication steps of
   different triples are independent, so their square roots overlap in the processor
   (and may be vectorised) instead of waiting for each other. */
static void rd_pair_batch(int n, const double *x0, const double *y0, const double *z0,
                          double *rd_xyz, double *rd_xzy, double tol)
{
    double x[RD_BATCH], y[RD_BATCH], z[RD_BATCH], sum_z[RD_BATCH], sum_y[RD_BATCH];
    double fac = 1.0;
    int i, it;
    for (i = 0; i < n; i++) {
        x[i] = x0[i];
        y[i] = y0[i];
        z[i] = z0[i];
        sum_z[i] = sum_y[i] = 0.0;
    }
    for (it = 0; it < 100; it++) {
        int done = 1;
        for (i = 0; i < n; i++) {
            /* (comparisons, not fmax, which is a call into libm here) */
            double m = (x[i] + y[i] + z[i]) / 3.0;
            double dx = fabs(x[i] - m), dy = fabs(y[i] - m), dz = fabs(z[i] - m);
            double dev = dx > dy ? dx : dy;
            dev = dev > dz ? dev : dz;
            if (dev > tol * m)
                done = 0;
        }
        if (done)
            break;
        for (i = 0; i < n; i++) {
            double sx = sqrt(x[i]), sy = sqrt(y[i]), sz = sqrt(z[i]);
            double lam = sx * (sy + sz) + sy * sz;
            double pz = sz * (z[i] + lam), py = sy * (y[i] + lam), r = fac / (pz * py);
            sum_z[i] += py * r;
            sum_y[i] += pz * r;
            x[i] = 0.25 * (x[i] + lam);
            y[i] = 0.25 * (y[i] + lam);
            z[i] = 0.25 * (z[i] + lam);
        }
        fac *= 0.25;
    }
    for (i = 0; i < n; i++) {
        rd_xyz[i] = 3.0 * sum_z[i] + fac * rd_series(x[i], y[i], z[i]);
        rd_xzy[i] = 3.0 * sum_y[i] + fac * rd_series(x[i], z[i], y[i]);
    }
}

/* ------------------------------------------------------------------ elementary parts */

/* sqrt(p^2 + q^2): the plain formula where neither square can overflow or lose its
   digits to underflow (an error of one rounding more than hypot's), hypot elsewhere;
   glibc's hypot was a tenth of the cost of a stress. */
static inline double norm2(double p, double q)
{
    double ap = fabs(p), aq = fabs(q), m = ap > aq ? ap : aq;
    if (m > 1e-140 && m < 1e140)
        return sqrt(p * p + q * q);
    return hypot(p, q);
}

/* S(e) = (T(e) - 1)/e, T(e) = artanh(sqrt e)/sqrt e (e > 0) or arctan(sqrt -e)/sqrt -e
   (e < 0), for e < 1; om = 1 - e, given separately with full precision. Near e = 0 T - 1
   cancels; there the half-angle formulas of artanh and arctan, which give the same
   recurrence for both signs,
       S(e) = (2 S(e1)/(1 + c) + 1) / (1 + c)^2,  c = sqrt(om), e1 = e/(1+c)^2,
       1 - e1 = 2c/(1 + c),
   reduce |e| below 0.1 in at most three steps, and a Taylor series finishes. */
static double s_func(double e, double om)
{
    double t, T, c, acc = 0.0, mul = 1.0, s;
    if (e > 0.75) {
        t = sqrt(e);
        T = log((1.0 + t) * (1.0 + t) / om) / (2.0 * t);   /* artanh t = ln((1+t)/(1-t))/2 */
        return (T - 1.0) / e;
    }
    if (e < -2.0) {
        t = sqrt(-e);
        T = atan(t) / t;
        return (T - 1.0) / e;
    }
    while (fabs(e) >= 0.1) {
        c = sqrt(om);
        /* S(e) = acc + mul S(e) becomes acc + mul (1/(1+c)^2 + 2/(1+c)^3 S(e1)) */
        acc += mul / ((1.0 + c) * (1.0 + c));
        mul *= 2.0 / ((1.0 + c) * (1.0 + c) * (1.0 + c));
        e = e / ((1.0 + c) * (1.0 + c));
        om = 2.0 * c / (1.0 + c);
    }
    /* sum_k e^k / (2k + 3), k = 0..15 */
    s = 1.0 / 33.0;
    s = 1.0 / 31.0 + e * s;
    s = 1.0 / 29.0 + e * s;
    s = 1.0 / 27.0 + e * s;
    s = 1.0 / 25.0 + e * s;
    s = 1.0 / 23.0 + e * s;
    s = 1.0 / 21.0 + e * s;
    s = 1.0 / 19.0 + e * s;
    s = 1.0 / 17.0 + e * s;
    s = 1.0 / 15.0 + e * s;
    s = 1.0 / 13.0 + e * s;
    s = 1.0 / 11.0 + e * s;
    s = 1.0 / 9.0 + e * s;
    s = 1.0 / 7.0 + e * s;
    s = 1.0 / 5.0 + e * s;
    s = 1.0 / 3.0 + e * s;
    return acc + mul * s;
}

/* The positive root v of  v (K + v)(Y0 + v) = z2 (A0 + v)(B0 + v)  with K >= 0, Y0 > 0,
   A0 >= Y0, B0 >= K, z2 > 0. This is the equation for the ellipsoidal coordinate
   l = U0 + v, shifted so that every factor is a sum of non-negative terms: the root keeps
   full relative precision. phi(v) = v (K+v)(Y0+v) / ((A0+v)(B0+v)) is increasing, with
   1 <= d ln phi / d ln v <= 3; Newton's method on ln phi in ln v, from the geometric mean
   of two bounds (roots of quadratics with (Y0+v)/(A0+v) replaced by its bounds 1 and
   Y0/A0), bracketed by them. */
static double quad_root(double K, double B0, double c2)
{
    /* positive root of v (K + v) = c2 (B0 + v) */
    double c = K - c2, D = norm2(c, 2.0 * sqrt(c2 * B0));
    return c >= 0.0 ? 2.0 * c2 * B0 / (c + D) : (D - c) / 2.0;
}

static double solve_v(double K, double Y0, double A0, double B0, double z2)
{
    double lo = quad_root(K, B0, z2), hi = quad_root(K, B0, z2 * (A0 / Y0));
    double v = sqrt(lo * hi);
    int i;
    if (!(hi > lo))
        return lo;
    for (i = 0; i < 60; i++) {
        double q = (z2 / v) * ((A0 + v) / (K + v)) * ((B0 + v) / (Y0 + v));
        double dl = 1.0 / v + 1.0 / (K + v) + 1.0 / (Y0 + v) - 1.0 / (A0 + v) - 1.0 / (B0 + v);
        double t = q - 1.0, g, d, vn;
        if (fabs(t) < 1e-2)      /* g = ln q */
            g = t * (1.0 - t * (0.5 - t * (1.0 / 3.0 - t * (0.25 - t * (0.2 - t / 6.0)))));
        else
            g = log(q);
        if (g > 0.0)             /* phi(v) < z2: v below the root */
            lo = v;
        else
            hi = v;
        d = g / (v * dl);        /* Newton step in ln v */
        if (fabs(d) < 1e-2)
            vn = v * (1.0 + d * (1.0 + d * (0.5 + d * (1.0 / 6.0 + d / 24.0))));
        else
            vn = v * exp(d);
        /* quadratic convergence (the slope of ln phi in ln v is within [1, 3]): after
           a step below 3e-9 the error is below 1e-16 */
        if (fabs(d) <= 3e-9)
            return vn;
        if (!(vn > lo && vn < hi))
            vn = sqrt(lo * hi);
        if (!(hi > lo))
            return vn;
        v = vn;
    }
    return v;
}

/* ------------------------------------------------------------------ 1 - x^2/a^2 - y^2/b^2 */

/* Error-free transformations (Dekker 1971, Knuth): no fused multiply-add needed. */
static void two_prod(double a, double b, double *p, double *e)
{
    const double split = 134217729.0;    /* 2^27 + 1 */
    double ca = split * a, cb = split * b;
    double ah = ca - (ca - a), al = a - ah, bh = cb - (cb - b), bl = b - bh;
    *p = a * b;
    *e = ((ah * bh - *p) + ah * bl + al * bh) + al * bl;
}

static void two_sum(double a, double b, double *s, double *e)
{
    double bb;
    *s = a + b;
    bb = *s - a;
    *e = (a - (*s - bb)) + (b - bb);
}

/* F0 = 1 - x^2/a^2 - y^2/b^2 with a relative error of a few ulp even where it cancels
   (near the edge of the contact), in double-double arithmetic: the stresses at the surface
   depend on sqrt(F0), so a rounding of F0 at 1e-16 would be an error of 1e-8 there. */
static double edge_distance(double a, double b, double x, double y)
{
    double qx = x / a, qy = y / b, ph, pl, rx, ry, sx, ex, sy, ey, t, te, u, ue;
    two_prod(qx, a, &ph, &pl);
    rx = ((x - ph) - pl) / a;                  /* x/a = qx + rx */
    two_prod(qy, b, &ph, &pl);
    ry = ((y - ph) - pl) / b;
    two_prod(qx, qx, &sx, &ex);
    ex += 2.0 * qx * rx;
    two_prod(qy, qy, &sy, &ey);
    ey += 2.0 * qy * ry;
    two_sum(1.0, -sx, &t, &te);
    two_sum(t, -sy, &u, &ue);
    return u + (ue + te - ex - ey);
}

/* ------------------------------------------------------------------ the point contact */

/* Stress at (x, y, z) for a = 1, b = k <= 1, normalised coordinates; F0 = 1 - x^2 - y^2/k^2
   computed accurately from the original coordinates. */
static void point_stress(double k, double nu, double x, double y, double z, double F0,
                         double out[6])
{
    const double be = k * k, d = (1.0 - k) * (1.0 + k);       /* b^2, a^2 - b^2 */
    const double x2 = x * x, y2 = y * y, r2 = x2 + y2, z2 = z * z;
    double D, e1, e2, f1, f2, mw1, c0, w2, K, U0, X0, Y0, v, u, X, Y, A, B, su, zeta;
    double sAB, Q, H, g, gx, szz, sxz, syz, zIA, zIB, zIw;
    double sg, q2, EA, EB, epsA, epsB, omA, SA, SB, TA, T2A, AmS;
    double K1, K2, K3, Kx, Ky, c1 = 1.0 - 2.0 * nu;

    /* Roots of P: with E = a^2 + w the roots e1 <= e2 of E^2 - (d + r2) E + x^2 d, with
       F = b^2 + w the roots -f1 <= f2 of F^2 - (r2 - d) F - y^2 d; w1 = e1 - 1 = -(b^2+f1),
       w2 = e2 - 1 = f2 - b^2. D is their common discriminant. */
    D = norm2(r2 - d, 2.0 * fabs(y) * sqrt(d));
    e2 = 0.5 * (d + r2 + D);
    e1 = e2 > 0.0 ? x2 * d / e2 : 0.0;
    if (r2 >= d) {
        f2 = 0.5 * (r2 - d + D);
        f1 = f2 > 0.0 ? y2 * d / f2 : 0.0;
    } else {
        f1 = 0.5 * (d - r2 + D);
        f2 = y2 * d / f1;
    }
    (void)f2;
    mw1 = e1 <= 0.5 * d ? 1.0 - e1 : be + f1;          /* -w1, in [b^2, 1] */
    c0 = be * F0;                                        /* a^2 b^2 (1 - x^2/a^2 - y^2/b^2) */
    w2 = -c0 / mw1;                                      /* w1 w2 = c0 */
    if (w2 <= 0.0) {       /* above the contact: l = v, X = v + |w2| */
        U0 = 0.0;
        X0 = K = -w2;
    } else {               /* outside it: l = w2 + v, X = v */
        U0 = K = w2;
        X0 = 0.0;
    }
    Y0 = U0 + mw1;
    v = z2 > 0.0 ? solve_v(K, Y0, 1.0 + U0, be + U0, z2) : 0.0;
    u = U0 + v;
    X = X0 + v;
    Y = Y0 + v;
    A = 1.0 + u;
    B = be + u;
    su = sqrt(u);
    /* zeta = z / sqrt(l): on the surface p/p0 inside the contact, 0 outside */
    zeta = u > 0.0 ? z / su : sqrt(fmax(F0, 0.0));
    sAB = sqrt(A * B);
    Q = k / sAB;
    H = zeta * zeta + u * (x2 / (A * A) + y2 / (B * B));
    if (H > 0.0) {
        g = Q / H;
        szz = -g * zeta * zeta * zeta;
        sxz = -g * x * zeta * zeta * su / A;
        syz = -g * y * zeta * zeta * su / B;
        gx = g * zeta * u;
    } else {               /* the edge of the contact on the surface */
        szz = sxz = syz = gx = 0.0;
    }
    if (z > 0.0) {
        double rda, rdb;
        rd_pair(u, B, A, &rda, &rdb);
        zIA = z * (2.0 / 3.0) * rda;
        zIB = z * (2.0 / 3.0) * rdb;
        zIw = zeta * (2.0 / sAB - su * (2.0 / 3.0) * (rda + rdb));
    } else {
        zIA = zIB = 0.0;
        zIw = u > 0.0 ? 0.0 : 2.0 * zeta / sAB;
    }
    /* the (1 - 2 nu) terms */
    sg = sqrt(X * Y);
    q2 = X + Y + 2.0 * sg;
    EA = A + sg;
    EB = B + sg;
    /* (ratios rather than powers of EA, EB, which reach 1e120 at 1e60 a) */
    epsA = (x2 / EA) * (d / EA);
    epsB = -(y2 / EB) * (d / EB);
    omA = (A / EA) * (q2 / EA);                     /* 1 - epsA */
    SA = s_func(epsA, omA);
    SB = s_func(epsB, (B / EB) * (q2 / EB));
    TA = 1.0 + epsA * SA;
    T2A = 1.0 / omA - SA;                           /* 1/(1 - eps) - S */
    AmS = (e1 * X + A * e2) / EA;                   /* A - sigma */
    K1 = 2.0 * TA / EA;                             /* int dw / (A sqrt P) */
    K2 = (2.0 / EA) * (TA - 0.5 * (q2 / EA) * (AmS / EA) * T2A) / EA;    /* 1/(A^2 sqrt P) */
    K3 = (2.0 / EA - 2.0 * (x2 / EA) * SA / EA * (EB / EA) - 2.0 * (y2 / EB) * SB / EB) / EB;
    /* psi_xx / (pi a b p0) = Kx - z I_A; psi_yy from psi_xx + psi_yy = -phi_z (psi is
       harmonic): its own integrals are of order 1/b^2 and cancel for a long ellipse */
    Kx = K1 - 2.0 * x2 * K2 - y2 * K3;
    Ky = 2.0 * zeta / sAB - Kx;
    out[0] = k * ((1.0 - nu) * zIA - nu * zIw) - gx * x2 / (A * A) - c1 * 0.5 * k * Kx;
    out[1] = k * ((1.0 - nu) * zIB - nu * zIw) - gx * y2 / (B * B) - c1 * 0.5 * k * Ky;
    out[2] = szz;
    out[3] = syz;
    out[4] = sxz;
    out[5] = c1 * 0.5 * k * x * y * K3 - gx * x * y / (A * B);
}

/* Beyond 1e60 a the field is Boussinesq's for the total force (2/3) pi a b p0 to the
   last bit (the next term is of relative order (a/R)^2), written with the direction
   cosines so that nothing overflows: the point (x, y, z) is in the caller's unit, not
   divided by a (x/a overflows for x >= 1e306 m beside a = 1e-3 m); only a/R is formed.
   k = b/a. */
static void point_far(double a, double k, double nu, double x, double y, double z,
                      double out[6])
{
    double m = fmax(fabs(x), fmax(fabs(y), fabs(z)));
    double ex = x / m, ey = y / m, ez = z / m, n = sqrt(ex * ex + ey * ey + ez * ez);
    double q = (a / m) / n, c1 = 1.0 - 2.0 * nu, rh2, c2, sxy2, sy2, sx2, f;
    ex /= n;
    ey /= n;
    ez /= n;
    rh2 = ex * ex + ey * ey;
    if (rh2 > 0.0) {
        c2 = (ex * ex - ey * ey) / rh2;
        sxy2 = ex * ey / rh2;
        sy2 = ey * ey / rh2;
        sx2 = ex * ex / rh2;
    } else {
        c2 = sxy2 = 0.0;
        sy2 = sx2 = 0.5;
    }
    f = (k / 3.0) * q * q;      /* (2/3) pi k / (2 pi R^2), R in units of a */
    out[0] = f * (c1 * (c2 / (1.0 + ez) + ez * sy2) - 3.0 * ez * ex * ex);
    out[1] = f * (c1 * (-c2 / (1.0 + ez) + ez * sx2) - 3.0 * ez * ey * ey);
    out[2] = -3.0 * f * ez * ez * ez;
    out[3] = -3.0 * f * ey * ez * ez;
    out[4] = -3.0 * f * ex * ez * ez;
    out[5] = f * (c1 * (2.0 * sxy2 / (1.0 + ez) - ez * sxy2) - 3.0 * ez * ex * ey);
}

static int bad_nu(double nu)
{
    return !(nu > -1.0 && nu <= 0.5);
}

static void fill_nan(double *out, int n)
{
    int i;
    for (i = 0; i < n; i++)
        out[i] = NAN;
}

int hertz_point_stress(double a, double b, double nu, double x, double y, double z,
                       double out[6])
{
    int err = 0;
    if (!(b > 0.0 && a >= b && a < INFINITY && b >= 1e-70 * a))
        err = HERTZ_STRESS_EAXES;
    else if (bad_nu(nu))
        err = HERTZ_STRESS_ENU;
    else if (!(fabs(x) < INFINITY && fabs(y) < INFINITY && fabs(z) < INFINITY))
        err = HERTZ_STRESS_EPOINT;
    else if (z < 0.0)
        err = HERTZ_STRESS_EDEPTH;
    if (err) {
        fill_nan(out, 6);
        return err;
    }
    if (fmax(fabs(x), fmax(fabs(y), z)) > 1e60 * a)
        point_far(a, b / a, nu, x, y, z, out);
    else
        point_stress(b / a, nu, x / a, y / a, z / a, edge_distance(a, b, x, y), out);
    return 0;
}

/* ------------------------------------------------------------------ the z axis */

/* The principal stresses on the z axis (normalised: a = 1, b = k) and their first and
   second derivatives in z: s[i][0..2] for i = x, y, z. With s = z^2, A = 1 + s,
   B = k^2 + s (Johnson sec. 3.5; Thomas & Hoersch 1930; docs/bibliography.md):
     szz = -k / sqrt(AB)
     sxx = k [(1-nu) z I_A - nu z I_w - (1-2nu) / (sqrt A (sqrt A + sqrt B))]
     syy = k [(1-nu) z I_B - nu z I_w - (1-2nu) / (sqrt B (sqrt A + sqrt B))]
   z I_w = 2/sqrt(AB) - z I_A - z I_B, and d I_A/dz = -2 / (A sqrt(AB)) (the integrand at
   the lower limit w = s), d I_B/dz = -2 / (B sqrt(AB)). rda, rdb = R_D(s, B, A),
   R_D(s, A, B). */
static void axis_stress(double k, double nu, double z, double rda, double rdb, double s[3][4])
{
    const double be = k * k, c1 = 1.0 - 2.0 * nu, z2 = z * z;
    const double A = 1.0 + z2, B = be + z2, rA = sqrt(A), rB = sqrt(B), sAB = rA * rB;
    /* one division: t = 1/(sqrt A sqrt B (sqrt A + sqrt B)) */
    const double t = 1.0 / (sAB * (rA + rB)), P = t * (rA + rB);
    const double iA = P * P * B, iB = P * P * A;
    const double S1 = iA + iB, S2 = iA * iA + iB * iB, S3 = iA * iA * iA + iB * iB * iB;
    double IA, IB, JA[4], JB[4], W[4], Jw[4], hx[4], hy[4], ua, ub;
    double P1, P1p, P1pp, Pp, Ppp, Np, Npp, Nppp;
    int i, m;
    IA = (2.0 / 3.0) * rda;
    IB = (2.0 / 3.0) * rdb;
    /* P = (AB)^(-1/2), S_n = A^-n + B^-n: P' = -z P S1, P'' = P (-S1 + z^2 S1^2 + 2 z^2 S2),
       P''' = z P (3 S1^2 + 6 S2 - z^2 S1^3 - 6 z^2 S1 S2 - 8 z^2 S3) */
    Pp = -z * P * S1;
    Ppp = P * (-S1 + z2 * S1 * S1 + 2.0 * z2 * S2);
    /* z I_A, with I_A' = -2 P/A and u = 3/A + 1/B:
       (z I_A)'' = P/A (-4 + 2 z^2 u), (z I_A)''' = z P/A (8u - 2 z^2 u^2 - 4 z^2 (3/A^2 + 1/B^2)) */
    ua = 3.0 * iA + iB;
    ub = 3.0 * iB + iA;
    JA[0] = z * IA;
    JA[1] = IA - 2.0 * z * P * iA;
    JA[2] = P * iA * (-4.0 + 2.0 * z2 * ua);
    JA[3] = z * P * iA * (8.0 * ua - 2.0 * z2 * ua * ua - 4.0 * z2 * (3.0 * iA * iA + iB * iB));
    JB[0] = z * IB;
    JB[1] = IB - 2.0 * z * P * iB;
    JB[2] = P * iB * (-4.0 + 2.0 * z2 * ub);
    JB[3] = z * P * iB * (8.0 * ub - 2.0 * z2 * ub * ub - 4.0 * z2 * (3.0 * iB * iB + iA * iA));
    /* W = 2 / sqrt(AB) = 2P */
    W[0] = 2.0 * P;
    W[1] = 2.0 * Pp;
    W[2] = 2.0 * Ppp;
    W[3] = 2.0 * z * P * (3.0 * S1 * S1 + 6.0 * S2 - z2 * S1 * S1 * S1 - 6.0 * z2 * S1 * S2
                          - 8.0 * z2 * S3);
    for (i = 0; i < 4; i++)
        Jw[i] = W[i] - JA[i] - JB[i];
    /* h_x = 1/N, N = A + sqrt(AB) (h_y: B + sqrt(AB)); (sqrt(AB))' = z P1, P1 = (A+B) P;
       N' = z (2 + P1), N'' = 2 + P1 + z P1', N''' = 2 P1' + z P1'' (the same for both);
       h' = -N' h^2, h'' = (2 N'^2 h - N'') h^2, h''' = (6 N' N'' h - N''' - 6 N'^3 h^2) h^2 */
    P1 = (A + B) * P;
    P1p = 4.0 * z * P + (A + B) * Pp;
    P1pp = 4.0 * P + 8.0 * z * Pp + (A + B) * Ppp;
    Np = z * (2.0 + P1);
    Npp = 2.0 + P1 + z * P1p;
    Nppp = 2.0 * P1p + z * P1pp;
    hx[0] = rB * t;
    hy[0] = rA * t;
    for (m = 0; m < 2; m++) {
        double *h = m == 0 ? hx : hy, g = h[0], g2 = g * g;
        h[1] = -Np * g2;
        h[2] = (2.0 * Np * Np * g - Npp) * g2;
        h[3] = (6.0 * Np * Npp * g - Nppp - 6.0 * Np * Np * Np * g2) * g2;
    }
    for (i = 0; i < 4; i++) {
        s[0][i] = k * ((1.0 - nu) * JA[i] - nu * Jw[i] - c1 * hx[i]);
        s[1][i] = k * ((1.0 - nu) * JB[i] - nu * Jw[i] - c1 * hy[i]);
        s[2][i] = -k * W[i] / 2.0;
    }
}

/* The three functions maximised on the axis, with three derivatives:
   f[0] = (sxx - szz)/2, f[1] = (syy - szz)/2, f[2] = von Mises^2 (szz is the smallest
   principal stress on the axis for every b/a and nu: checked numerically), at n depths. */
static void axis_targets(double k, double nu, int n, const double *zs, double (*f)[3][4],
                         double tol)
{
    double s2[RD_BATCH], A[RD_BATCH], B[RD_BATCH], rda[RD_BATCH], rdb[RD_BATCH];
    int i, j, l;
    for (l = 0; l < n; l++) {
        s2[l] = zs[l] * zs[l];
        A[l] = 1.0 + s2[l];
        B[l] = k * k + s2[l];
    }
    rd_pair_batch(n, s2, B, A, rda, rdb, tol);
    for (l = 0; l < n; l++) {
        double s[3][4], d[3][4];
        axis_stress(k, nu, zs[l], rda[l], rdb[l], s);
        for (i = 0; i < 4; i++) {
            f[l][0][i] = 0.5 * (s[0][i] - s[2][i]);
            f[l][1][i] = 0.5 * (s[1][i] - s[2][i]);
        }
        for (j = 0; j < 3; j++) {          /* differences xy, yz, zx */
            int p = j, q = (j + 1) % 3;
            for (i = 0; i < 4; i++)
                d[j][i] = s[p][i] - s[q][i];
        }
        f[l][2][0] = f[l][2][1] = f[l][2][2] = f[l][2][3] = 0.0;
        for (j = 0; j < 3; j++) {
            f[l][2][0] += 0.5 * d[j][0] * d[j][0];
            f[l][2][1] += d[j][0] * d[j][1];
            f[l][2][2] += d[j][1] * d[j][1] + d[j][0] * d[j][2];
            f[l][2][3] += 3.0 * d[j][1] * d[j][2] + d[j][0] * d[j][3];
        }
    }
}

/* The quintic Hermite interpolant on [0, 1] of values and first and second derivatives
   (the derivatives scaled by h, h^2) at both ends: coefficients c[0..5]. */
static void hermite5(double f0, double g0, double k0, double f1, double g1, double k1,
                     double c[6])
{
    double F, G, Hh;
    c[0] = f0;
    c[1] = g0;
    c[2] = 0.5 * k0;
    F = f1 - f0 - c[1] - c[2];
    G = g1 - c[1] - 2.0 * c[2];
    Hh = k1 - 2.0 * c[2];
    c[3] = 10.0 * F - 4.0 * G + 0.5 * Hh;
    c[4] = -15.0 * F + 7.0 * G - Hh;
    c[5] = 6.0 * F - 3.0 * G + 0.5 * Hh;
}

static double hermite_d1(const double c[6], double t)
{
    return c[1] + t * (2.0 * c[2] + t * (3.0 * c[3] + t * (4.0 * c[4] + t * 5.0 * c[5])));
}

static double hermite_d2(const double c[6], double t)
{
    return 2.0 * c[2] + t * (6.0 * c[3] + t * (12.0 * c[4] + t * 20.0 * c[5]));
}

/* Root of p' in (lo, hi) where p'(lo) = dlo > 0 >= p'(hi) = dhi: bracketed Newton from
   the secant point, to 1e-9 (the root only starts the search on the true function, which
   needs a second round if the start is off by more than about 3e-4 of the depth). */
static double hermite_root(const double c[6], double lo, double hi, double dlo, double dhi)
{
    double t = lo + (hi - lo) * (dlo / (dlo - dhi));
    int i;
    for (i = 0; i < 30; i++) {
        double d1 = hermite_d1(c, t), d2 = hermite_d2(c, t), tn;
        if (d1 > 0.0)
            lo = t;
        else
            hi = t;
        tn = d2 < 0.0 ? t - d1 / d2 : 0.5 * (lo + hi);
        if (!(tn > lo && tn < hi))
            tn = 0.5 * (lo + hi);
        if (fabs(tn - t) < 1e-9)
            return tn;
        t = tn;
    }
    return t;
}

#define AXIS_GRID 5
#define AXIS_SUB 4
#define AXIS_CAND 12

/* ------------------------------------------------------------------ axis maxima, direct

   For 0.25 <= nu <= 0.5 and 1e-3 <= b/a <= 1 (steels and most other metals, polymers,
   rubber) the search below is not needed: there, on the z axis (checked at 2236 points of
   a grid and 3000 random points of that rectangle, with every stationary point of the
   three targets found on a fine table of depths and refined),
     - (syy - szz)/2 has exactly one interior maximum and no interior minimum,
     - von Mises^2 has exactly one interior maximum (and at most one interior minimum,
       between it and the surface),
     - the interior maximum of (sxx - szz)/2, if any, is below the larger of that of
       (syy - szz)/2 and the surface values (by 2e-7 relative at b/a = 1 - 1e-6, by 0.5%
       at b/a = 0.975, by 1.8% or more for b/a <= 0.9; equal for the circle, where the two
       targets are the same function).
   The depths of the two maxima, divided by b, are smooth in (b/a, nu) and are fitted by
   Chebyshev polynomials in x = 2 b/a - 1 and y = (nu - 0.375)/0.125 plus (b/a)^2j ln(b/a)
   times polynomials in y (the expansion about the line contact has such terms): largest
   relative error 5.7e-6 (tau) and 1.4e-5 (von Mises) over the same points (least
   squares; the fit and the checks above: tools/fit_axis_depths.py). One exact evaluation
   at the fitted depths and Halley's step, accepted as in the search (step below 3e-4 of
   the depth: error of order 1e-15 of the depth from these starts), give the maxima; the
   surface is evaluated exactly in the same batch, so three R_D pairs in all instead of
   eight (seven before the table used RD_ROUGH). If a step is not accepted after two rounds, or f'' >= 0 (never seen), the general
   search runs. Outside the rectangle the general search always runs; compiled with
   HERTZ_STRESS_SEARCH_ONLY, everywhere (tests/test_stress_kernel.py compares the two). */
#define FIT_DK 8
#define FIT_DN 5
#define FIT_DL 3
static const double fit_tau_c[9][6] = {
    {0.52437894321891443, -0.092897348651628131, 0.019046185856331891, 0.00097962098599041784, 0, 0},
    {-0.28177434677894014, -0.077791528329578918, 0.017597561462547307, 0.00093650399060903576, 0, 0},
    {0.072738698001394486, 0.080843303826449026, -0.012813892569394711, -0.0006379843033330197, 0, 0},
    {0.13714078670351781, 0.096230752267578601, -0.016994280101696058, -0.00090363784111817998, 0, 0},
    {0.049324020537613096, 0.033041611862331885, -0.006214633964069005, -0.00033884326581730195, 0, 0},
    {0.0045041505381701753, 0.0024524344943268441, -0.00052872966821892369, -2.7467923044244351e-05, 0, 0},
    {-0.00039013498290082767, -0.00010639610622207106, 5.0882591029209601e-05, 2.3978323586657836e-06, 0, 0},
    {3.1477359679554102e-05, -6.3504340370430715e-06, -5.9465473898930806e-06, -2.3310502256698614e-07, 0, 0},
    {0, 0, 0, 0, 0, 0},
};
static const double fit_tau_d[3][6] = {
    {0.36201960405526418, -0.19598197339675982, -0.0038586660589028984, -0.00075530275331870105, 0, 0},
    {-4.8676901235725074, -3.186795643278161, 0.59877874548995469, 0.032332193931481609, 0, 0},
    {0, 0, 0, 0, 0, 0},
};
static const double fit_vm_c[9][6] = {
    {2.0442701924789941, 0.88421277127017373, 0.18024958862717799, 0.04251019719363569, 0.010814904300525896, -0.0013744761313239096},
    {2.1139748149502831, 0.79644936955321222, 0.39533248719155345, 0.070835585170702764, 0.013352137016018922, 0.00015001219858065684},
    {0.44644119228007167, -0.50944096278469697, 0.19688307064909999, 0.019547455892415307, -0.0024660321858698472, 0.0031124608968731704},
    {-1.4093920363822312, -0.75217618378263607, -0.20073851344629429, -0.04308098846286379, -0.010274571053110471, 0.0010198176896523137},
    {-1.7085327890906967, -0.31730016711408648, -0.34826393395655614, -0.05624056129476479, -0.0078863188233971974, -0.0014633406140269801},
    {-0.81461973822033684, -0.055321446813644037, -0.18461824203593555, -0.027853691329836741, -0.0029778354596383116, -0.0011774857147802409},
    {-0.16052860329876062, -0.0041146647428760286, -0.037434823866511646, -0.005511806295239452, -0.00054119290235576933, -0.00025903226468407259},
    {-0.00588658067539094, -0.00058634941991195927, -0.0013203841455200205, -0.00020388000274253193, -2.2031379710241161e-05, -8.2086908908540757e-06},
    {0.00022770245375047793, 4.5036302566216907e-05, 4.8067810972440839e-05, 8.0623663116785593e-06, 9.3014237562139002e-07, 2.5716848814361093e-07},
};
static const double fit_vm_d[3][6] = {
    {0.011240532589863572, 0.046626983879354933, 0.032132701296982091, 0.012585293919698551, -0.0011029476930595195, 0.0012899940996165538},
    {-60.17507867585455, 21.727856739772598, -18.35839072420708, -2.2796596776547347, -0.018432701097938903, -0.20879494281282249},
    {184.99053451658958, 7.4941301256633919, 42.767692817254087, 6.3526643491055097, 0.63976241289309022, 0.28907155702098963},
};

#define FAST_NU_MIN 0.25
#define FAST_K_MIN 1e-3

static double fit_eval(const double c[FIT_DK + 1][FIT_DN + 1], const double d[FIT_DL][FIT_DN + 1],
                       const double *tx, const double *ty, const double *kl)
{
    double u = 0.0;
    int i, m;
    for (m = 0; m <= FIT_DN; m++) {
        double s = 0.0;
        for (i = 0; i <= FIT_DK; i++)
            s += c[i][m] * tx[i];
        for (i = 0; i < FIT_DL; i++)
            s += d[i][m] * kl[i];
        u += s * ty[m];
    }
    return u;
}

/* The maxima from the fitted depths; returns 0 (val, dep then undefined) when the general
   search must run instead. */
static int axis_maxima_direct(double k, double nu, double val[3], double dep[3])
{
    double tx[FIT_DK + 1], ty[FIT_DN + 1], kl[FIT_DL], x = 2.0 * k - 1.0,
           y = (nu - 0.375) / 0.125, lk = log(k), k2 = k * k;
    double zs[3], fz[3][3][4], cz[2], cv[2];
    int i, l, na, idx[2], done[2] = {0, 0}, round;
    if (!(nu >= FAST_NU_MIN && k >= FAST_K_MIN))
        return 0;
    tx[0] = ty[0] = 1.0;
    tx[1] = x;
    ty[1] = y;
    for (i = 2; i <= FIT_DK; i++)
        tx[i] = 2.0 * x * tx[i - 1] - tx[i - 2];
    for (i = 2; i <= FIT_DN; i++)
        ty[i] = 2.0 * y * ty[i - 1] - ty[i - 2];
    kl[0] = k2 * lk;
    for (i = 1; i < FIT_DL; i++)
        kl[i] = kl[i - 1] * k2;
    cz[0] = k * fit_eval(fit_tau_c, fit_tau_d, tx, ty, kl);   /* target 1: (syy - szz)/2 */
    cz[1] = k * fit_eval(fit_vm_c, fit_vm_d, tx, ty, kl);     /* target 2: von Mises^2 */
    for (round = 0; round < 2; round++) {
        na = 0;
        for (l = 0; l < 2; l++)
            if (!done[l])
                zs[na] = cz[l], idx[na++] = l;
        if (round == 0) {
            zs[na] = 0.0;             /* the surface, exactly */
            axis_targets(k, nu, na + 1, zs, fz, RD_EXACT);
        } else {
            axis_targets(k, nu, na, zs, fz, RD_EXACT);
        }
        for (i = 0; i < na; i++) {
            double *g = fz[i][idx[i] + 1], den, step;
            l = idx[i];
            if (!(g[2] < 0.0))
                return 0;
            den = 2.0 * g[2] * g[2] - g[1] * g[3];
            step = den > 0.0 ? -2.0 * g[1] * g[2] / den : -g[1] / g[2];
            if (fabs(step) <= 3e-4 * zs[i]) {
                /* as in the search: error of order step^3 / z^2, value from Taylor */
                cv[l] = g[0] + step * (g[1] + step * (0.5 * g[2] + step * g[3] / 6.0));
                done[l] = 1;
            }
            cz[l] = zs[i] + step;
            if (!(cz[l] > 0.0))
                return 0;
        }
        if (round == 0) {
            for (i = 0; i < 3; i++) {
                val[i] = fz[na][i][0];
                dep[i] = 0.0;
            }
        }
        if (done[0] && done[1])
            break;
    }
    if (!(done[0] && done[1]))
        return 0;
    for (l = 0; l < 2; l++) {
        if (cv[l] > val[l + 1]) {
            val[l + 1] = cv[l];
            dep[l + 1] = cz[l];
        }
    }
    if (k == 1.0) {
        val[0] = val[1];
        dep[0] = dep[1];
    }
    return 1;
}

/* Largest value of each target on the z axis: value and depth (normalised, b = k).
   The targets are tabulated with their first two derivatives on a grid of depths (with
   R_D good to 1e-9, enough to locate the maxima); in every cell the quintic Hermite
   interpolant locates the candidate maxima (also a maximum and a minimum in one cell,
   which the signs of f' at the grid points would miss). Candidates that cannot beat a
   value already known are dropped; the others are refined together by Halley's method
   on f' = 0 with the exact R_D (bisection when a step leaves its cell or f'' >= 0) and
   compared with the values at the surface, computed exactly with the first round. */
static void axis_maxima(double k, double nu, double val[3], double dep[3])
{
    static const double grid[AXIS_GRID] = {0.0, 0.25, 0.55, 0.9, 1.4};
    double z[AXIS_GRID + 8], f[AXIS_GRID + 8][3][4];
    double cz[AXIS_CAND], clo[AXIS_CAND], chi[AXIS_CAND], cest[AXIS_CAND];
    int ci[AXIS_CAND], cact[AXIS_CAND], nc = 0, n = AXIS_GRID, j, i, m, round;
    double known[2];   /* lower bounds of the answer: tau (targets 0, 1), von Mises^2 */
    for (j = 0; j < AXIS_GRID; j++)
        z[j] = grid[j] * k;
    axis_targets(k, nu, AXIS_GRID, z, f, RD_ROUGH);
    /* extend the grid while a target still increases at its deepest point */
    while (n < AXIS_GRID + 8 && (f[n - 1][0][1] > 0.0 || f[n - 1][1][1] > 0.0
                                 || f[n - 1][2][1] > 0.0)) {
        z[n] = 1.5 * z[n - 1];
        axis_targets(k, nu, 1, z + n, f + n, RD_ROUGH);
        n++;
    }
    known[0] = known[1] = 0.0;
    for (j = 0; j < n; j++) {
        known[0] = fmax(known[0], fmax(f[j][0][0], f[j][1][0]));
        known[1] = fmax(known[1], f[j][2][0]);
    }
    for (i = 0; i < 3; i++) {
        if (i == 1 && k == 1.0)
            continue;                         /* a circle: sxx = syy on the axis */
        for (j = 0; j + 1 < n; j++) {
            double h = z[j + 1] - z[j], c[6], prev, t0 = 0.0;
            hermite5(f[j][i][0], h * f[j][i][1], h * h * f[j][i][2],
                     f[j + 1][i][0], h * f[j + 1][i][1], h * h * f[j + 1][i][2], c);
            prev = c[1];
            for (m = 1; m <= AXIS_SUB; m++) {
                double t1 = (double)m / AXIS_SUB;
                double d1 = m == AXIS_SUB ? h * f[j + 1][i][1] : hermite_d1(c, t1);
                if (prev > 0.0 && d1 <= 0.0 && nc < AXIS_CAND) {
                    double tg = m == AXIS_SUB && d1 == 0.0 ? 1.0
                                : hermite_root(c, t0, t1, prev, d1);
                    double est = c[0] + tg * (c[1] + tg * (c[2] + tg * (c[3] + tg * (c[4]
                                 + tg * c[5]))));
                    /* the interpolant is good to far better than 1e-3 of the value */
                    if (est > known[i == 2] * (1.0 - 1e-3)) {
                        ci[nc] = i;
                        cz[nc] = z[j] + h * tg;
                        clo[nc] = z[j];
                        chi[nc] = z[j + 1];
                        cest[nc] = -INFINITY;
                        cact[nc] = 1;
                        nc++;
                    }
                }
                prev = d1;
                t0 = t1;
            }
        }
    }
    /* Halley's method for all candidates at once; the first round also evaluates the
       surface z = 0 (the last point of its batch) exactly */
    for (round = 0; round < 60; round++) {
        double zs[AXIS_CAND + 1], fz[AXIS_CAND + 1][3][4];
        int idx[AXIS_CAND], na = 0, l;
        for (l = 0; l < nc; l++)
            if (cact[l])
                zs[na] = cz[l], idx[na++] = l;
        if (round == 0) {
            zs[na] = 0.0;
            axis_targets(k, nu, na + 1, zs, fz, RD_EXACT);
            for (i = 0; i < 3; i++) {
                val[i] = fz[na][i][0];        /* the surface */
                dep[i] = 0.0;
            }
        } else if (na == 0) {
            break;
        } else {
            axis_targets(k, nu, na, zs, fz, RD_EXACT);
        }
        for (m = 0; m < na; m++) {
            double *g = fz[m][ci[idx[m]]], zg = zs[m], step, zn;
            l = idx[m];
            if (g[0] > cest[l]) {               /* the best point seen, if Newton fails */
                cest[l] = g[0];
                cz[l] = zg;
            }
            if (g[1] > 0.0)
                clo[l] = zg;
            else
                chi[l] = zg;
            if (g[2] < 0.0) {
                /* Halley's step (cubic convergence) on f' = 0 */
                double den = 2.0 * g[2] * g[2] - g[1] * g[3];
                step = den > 0.0 ? -2.0 * g[1] * g[2] / den : -g[1] / g[2];
                zn = zg + step;
                if (fabs(step) <= 3e-4 * zg || fabs(step) <= 1e-300) {
                    /* converged: the error after this step is of order step^3 / z^2
                       (measured below 1e-9 z); the value from Taylor's formula */
                    cest[l] = g[0] + step * (g[1] + step * (0.5 * g[2] + step * g[3] / 6.0));
                    cz[l] = zn;
                    cact[l] = 0;
                    continue;
                }
            } else {
                zn = g[1] > 0.0 ? chi[l] : clo[l];
            }
            if (!(zn > clo[l] && zn < chi[l]))
                zn = 0.5 * (clo[l] + chi[l]);
            if (chi[l] - clo[l] <= 1e-15 * chi[l])
                cact[l] = 0;
            else
                cz[l] = zn;
        }
    }
    for (m = 0; m < nc; m++) {
        i = ci[m];
        if (cest[m] > val[i]) {
            val[i] = cest[m];
            dep[i] = cz[m];
        }
    }
    if (k == 1.0) {
        val[1] = val[0];
        dep[1] = dep[0];
    }
}

/* t > 1 with (t^2 - 1)(2t - 1) = k^2, returned as t - 1 (Newton from the right on the
   convex 2e^3 + 5e^2 + 2e - k^2). */
static double lp_root(double k)
{
    double e = 0.5 * k * k;
    int i;
    for (i = 0; i < 60; i++) {
        double f = ((2.0 * e + 5.0) * e + 2.0) * e - k * k;
        double fp = (6.0 * e + 10.0) * e + 2.0;
        double en = e - f / fp;
        if (!(en < e))
            break;
        e = en;
    }
    return e;
}

int hertz_subsurface(double a, double b, double nu, double out[12])
{
    double k, val[3], dep[3], e, t;
    int i;
    if (!(b > 0.0 && a >= b && a < INFINITY && b >= 1e-70 * a)) {
        fill_nan(out, 12);
        return HERTZ_STRESS_EAXES;
    }
    if (bad_nu(nu)) {
        fill_nan(out, 12);
        return HERTZ_STRESS_ENU;
    }
    k = b / a;
#ifndef HERTZ_STRESS_SEARCH_ONLY     /* (defined by the tests: the general search alone) */
    if (!axis_maxima_direct(k, nu, val, dep))
#endif
        axis_maxima(k, nu, val, dep);
    i = val[1] > val[0] ? 1 : 0;
    out[0] = val[i];
    out[1] = dep[i] * a;
    out[2] = sqrt(val[2]);
    out[3] = dep[2] * a;
    /* orthogonal shear (Lundberg & Palmgren 1947), in units of b */
    e = lp_root(k);
    t = 1.0 + e;
    out[4] = sqrt(1.0 + 2.0 * e) / (2.0 * t * (t + 1.0));
    out[5] = b * t / (t + 1.0) * sqrt((2.0 * t + 1.0) / (1.0 + 2.0 * e));
    out[6] = b / ((t + 1.0) * sqrt(1.0 + 2.0 * e));
    /* surface tension: sxx at (a, 0), (1 - 2nu) (b/a) S(1 - b^2/a^2) (Johnson sec. 3.5) */
    out[7] = (1.0 - 2.0 * nu) * k * s_func((1.0 - k) * (1.0 + k), k * k);
    out[8] = a;
    out[9] = 0.0;
    out[10] = out[11] = NAN;
    return 0;
}

/* ------------------------------------------------------------------ line contact */

int hertz_line_stress(double b, double nu, double x, double z, double out[4])
{
    double X, Z, re, im, md, m, n, den, d, mn2;
    if (!(b > 0.0 && b < INFINITY)) {
        fill_nan(out, 4);
        return HERTZ_STRESS_EAXES;
    }
    if (bad_nu(nu)) {
        fill_nan(out, 4);
        return HERTZ_STRESS_ENU;
    }
    if (!(fabs(x) < INFINITY && fabs(z) < INFINITY)) {
        fill_nan(out, 4);
        return HERTZ_STRESS_EPOINT;
    }
    if (z < 0.0) {
        fill_nan(out, 4);
        return HERTZ_STRESS_EDEPTH;
    }
    if (fmax(fabs(x), z) > 1e60 * b) {
        /* Flamant's solution for the total force pi b p0 / 2 (exact to the last bit), from
           the direction cosines and b/R: x/b would overflow for x >= 1e306 m beside
           b = 1e-3 m */
        double mx = fmax(fabs(x), z), ex = x / mx, ez = z / mx, nn = sqrt(ex * ex + ez * ez);
        double f;
        ex /= nn;
        ez /= nn;
        f = -((b / mx) / nn);                /* -(2/pi) (pi/2) b / R */
        out[0] = f * ex * ex * ez;
        out[1] = f * ez * ez * ez;
        out[2] = f * ex * ez * ez;
        out[3] = nu * (out[0] + out[1]);
        return 0;
    }
    X = x / b;
    Z = z / b;
    /* m + i n = sqrt(1 - (X - iZ)^2), principal root (m >= 0, n of the sign of X) */
    re = (1.0 - fabs(X)) * (1.0 + fabs(X)) + Z * Z;
    im = 2.0 * X * Z;
    md = hypot(re, im);
    if (re >= 0.0) {
        m = sqrt(0.5 * (md + re));
        n = m > 0.0 ? im / (2.0 * m) : 0.0;
    } else {
        n = sqrt(0.5 * (md - re));
        m = fabs(im) / (2.0 * n);
        if (X < 0.0)
            n = -n;
    }
    mn2 = m * m + n * n;
    if (mn2 == 0.0) {          /* the edge of the contact on the surface */
        out[0] = out[1] = out[2] = out[3] = 0.0;
        return 0;
    }
    /* d = m - Z = Re 1/(m + Z + i (n + X)) */
    den = (m + Z) * (m + Z) + (n + X) * (n + X);
    d = (m + Z) / den;
    out[0] = -d * (m * d + 2.0 * n * n) / mn2;
    out[1] = -m * d * (m + Z) / mn2;
    out[2] = -n * d * (m + Z) / mn2;
    out[3] = nu * (out[0] + out[1]);
    return 0;
}

int hertz_line_subsurface(double b, double nu, double out[7])
{
    double D1, d1, f1, f2, D2, d2, al, a1, Ds, Dv, vm, Fv, F1;
    if (!(b > 0.0 && b < INFINITY)) {
        fill_nan(out, 7);
        return HERTZ_STRESS_EAXES;
    }
    if (bad_nu(nu)) {
        fill_nan(out, 7);
        return HERTZ_STRESS_ENU;
    }
    /* On the axis, with d = sqrt(1 + Z^2) - Z in (0, 1] and D = d^2 (Z = (1 - D)/(2d)):
       szz = -2d/(1+D), sxx = D szz, syy = nu (1 + D) szz; szz is the smallest.
       (sxx - szz)/2 = d (1 - D)/(1 + D), largest at D = sqrt 5 - 2;
       (syy - szz)/2 = d (1 - nu - nu D)/(1 + D), largest where
       nu D^2 + (1 + 2nu) D - (1 - nu) = 0, or at the surface D = 1 if nu <= 0. */
    D1 = sqrt(5.0) - 2.0;
    d1 = sqrt(D1);
    f1 = d1 * (1.0 - D1) / (1.0 + D1);
    if (nu > 0.0) {
        D2 = 2.0 * (1.0 - nu) / ((1.0 + 2.0 * nu) + sqrt(1.0 + 8.0 * nu));
        d2 = sqrt(D2);
        f2 = d2 * (1.0 - nu - nu * D2) / (1.0 + D2);
    } else {
        D2 = d2 = 1.0;
        f2 = 0.5 - nu;
    }
    if (f1 >= f2) {
        out[0] = f1;
        out[1] = b * (1.0 - D1) / (2.0 * d1);
    } else {
        out[0] = f2;
        out[1] = b * (1.0 - D2) / (2.0 * d2);
    }
    /* von Mises^2 = 2D (al D^2 + a1 D + al)/(1 + D)^2; its stationary points are the
       roots of g(D) = al D^3 + 3 al D^2 + (2 a1 - al) D + al (convex for D > 0,
       g(0) > 0): the first root is a maximum, compared with the surface D = 1. */
    al = nu * nu + (1.0 - nu) * (1.0 - nu) + 1.0;
    a1 = -4.0 * nu * (1.0 - nu) - 2.0;
    F1 = 2.0 * (2.0 * al + a1) / 4.0;            /* at D = 1 */
    vm = sqrt(F1);
    Dv = 1.0;
    Ds = -1.0 + sqrt(1.0 - (2.0 * a1 - al) / (3.0 * al));   /* minimum of g */
    if (Ds > 0.0) {
        double D = 0.0;
        int i;
        double gs = ((al * Ds + 3.0 * al) * Ds + (2.0 * a1 - al)) * Ds + al;
        if (gs < 0.0) {
            for (i = 0; i < 100; i++) {      /* Newton from the left: monotone */
                double g = ((al * D + 3.0 * al) * D + (2.0 * a1 - al)) * D + al;
                double gp = (3.0 * al * D + 6.0 * al) * D + (2.0 * a1 - al);
                double Dn = D - g / gp;
                if (!(Dn > D && Dn < Ds))
                    break;
                if (Dn - D <= 1e-16 * Dn) {
                    D = Dn;
                    break;
                }
                D = Dn;
            }
            if (D < 1.0) {
                Fv = 2.0 * D * ((al * D + a1) * D + al) / ((1.0 + D) * (1.0 + D));
                if (Fv > F1) {
                    vm = sqrt(Fv);
                    Dv = D;
                }
            }
        }
    }
    out[2] = vm;
    out[3] = b * (1.0 - Dv) / (2.0 * sqrt(Dv));
    /* largest |sxz|: p0/4 at x = +-b sqrt(3)/2, z = b/2 (Johnson sec. 4.2) */
    out[4] = 0.25;
    out[5] = b * sqrt(3.0) / 2.0;
    out[6] = 0.5 * b;
    return 0;
}
