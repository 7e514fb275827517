/*
 * hertz._ufuncs, contact formulas: from the principal radii of two bodies,
 * the angle between their principal planes and their moduli to the Hertz
 * contact ellipse, peak pressure, approach and stiffness, one element at a
 * time (the ellipse ratio comes from the solver in _kernel.c).
 *
 * Relative curvatures (Johnson, Contact Mechanics, 1985, sec. 4.2), with
 * k_ix = 1/R_ix, psi the angle from body 1's x axis to body 2's:
 *
 *     Sx = k1x + k2x,  Sy = k1y + k2y,  g_i = k_ix - k_iy,
 *     rho_x + rho_y = Sx + Sy,
 *     rho_x rho_y   = Sx Sy + g1 g2 sin^2 psi,                          (1)
 *     (rho_x - rho_y)^2 = (g1 - g2)^2 + 4 g1 g2 cos^2 psi
 *                       = (g1 + g2)^2 - 4 g1 g2 sin^2 psi.              (2)
 *
 * A pair sum of a concave and a convex radius is taken as (Ra + Rb)/(Ra Rb),
 * exact however closely the surfaces conform; (1) and the form of (2) whose
 * terms have one sign keep every digit, and all three are symmetric in the
 * two bodies, so swapping them (psi -> -psi) gives the same bits.
 *
 * Contact (Hokada, Iizuka & Takada sec. 2; Johnson sec. 4.2), with
 * lambda = a/b, K, E at m = 1 - 1/lambda^2 and rho = rho_x + rho_y, written
 * in powers of the semi-minor axis b (exact rearrangements of the seed's
 * b = (3 E P / (pi lambda E* rho))^(1/3), p0 = 3P/(2 pi a b) and
 * delta = (K/2)(9 rho P^2 / (E (pi lambda E*)^2))^(1/3)):
 *
 *     b^3 = cb P,          cb = 3 E / (pi lambda E* rho),
 *     delta = cd b^2,      cd = K rho / (2 E),
 *     p0 = cp b,           cp = E* rho / (2 E),
 *     dP/d(delta) = cs b,  cs = pi lambda E* / K,      a = lambda b,
 *
 * so a given load, approach or peak pressure first gives b and then the rest.
 * The coefficients and b carry their binary exponent apart (hertz_scaled):
 * P = 1e300 or E* = 5e-324 never overflow or lose digits before the root.
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "_contact_kernel.h"

#define PI 3.14159265358979323846

/* 2^e for -1022 <= e <= 1023. */
static inline double
pow2i(int e)
{
    uint64_t bits = (uint64_t)(e + 1023) << 52;
    double d;
    memcpy(&d, &bits, sizeof d);
    return d;
}

/* x 2^e, rounded once where the result is normal (two exact steps that
 * never leave the range between x and the result). */
static inline double
scale2(double x, int e)
{
    e = e < -2044 ? -2044 : (e > 2046 ? 2046 : e);
    int h = e / 2;
    return x * pow2i(h) * pow2i(e - h);
}

/* Binary exponent of a finite x != 0 (subnormals included). */
static inline int
exponent_of(double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    int biased = (int)((bits >> 52) & 0x7FF);
    return biased ? biased - 1023 : ilogb(x);
}

/* x = m 2^e with m in [1, 2), for a finite x > 0 (subnormals included). */
static inline hertz_scaled
split(double x)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    hertz_scaled s;
    if ((bits >> 52) & 0x7FF) {
        s.e = (int)((bits >> 52) & 0x7FF) - 1023;
        bits = (bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull;
        memcpy(&s.m, &bits, sizeof s.m);
    }
    else {
        s.e = ilogb(x);
        s.m = ldexp(x, -s.e);
    }
    return s;
}

/* 1/ra + 1/rb, a concave-convex pair without cancellation. */
static inline double
pair_sum(double ra, double rb)
{
    if (isfinite(ra) && isfinite(rb) && (ra < 0) != (rb < 0)) {
        double prod = ra * rb;
        if (isfinite(prod)) {
            return (ra + rb) / prod;
        }
    }
    return 1.0 / ra + 1.0 / rb;
}

/* 1/rx - 1/ry, without cancellation when rx and ry have one sign. */
static inline double
pair_difference(double rx, double ry)
{
    if (isfinite(rx) && isfinite(ry) && (rx < 0) == (ry < 0)) {
        double prod = rx * ry;
        if (isfinite(prod)) {
            return (ry - rx) / prod;
        }
    }
    return 1.0 / rx - 1.0 / ry;
}

/* Validate the moduli and return E* as a scaled value:
 * 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2, taken as E* = E_lo / (c_lo + c_hi
 * E_lo/E_hi) with E_lo <= E_hi (symmetric in the bodies; E_lo may be
 * subnormal). */
static int
reduced_modulus(double e1, double nu1, double e2, double nu2, hertz_scaled *e_star)
{
    if (!(e1 > 0.0 && e1 <= DBL_MAX)) {
        return 1 + HERTZ_E1;
    }
    if (!(nu1 > -1.0 && nu1 <= 0.5)) {
        return 1 + HERTZ_NU1;
    }
    if (!(e2 > 0.0 && e2 <= DBL_MAX)) {
        return 1 + HERTZ_E2;
    }
    if (!(nu2 > -1.0 && nu2 <= 0.5)) {
        return 1 + HERTZ_NU2;
    }
    double c1 = (1.0 - nu1) * (1.0 + nu1), c2 = (1.0 - nu2) * (1.0 + nu2);
    int swap = e1 > e2 || (e1 == e2 && c1 > c2);
    double elo = swap ? e2 : e1, ehi = swap ? e1 : e2;
    double clo = swap ? c2 : c1, chi = swap ? c1 : c2;
    hertz_scaled s = split(elo);
    s.m /= clo + chi * (elo / ehi);
    *e_star = s;
    return HERTZ_OK;
}

/* Principal relative curvatures rho_x >= rho_y (as rx 2^e, ry 2^e), their
 * sum (rs 2^e) and the major-axis angle of one geometry.  HERTZ_OK or an
 * error code; rx, ry are set for the contact errors. */
static int
curvatures(const double r[4], double angle, double *rx, double *ry, double *rs,
           int *e, double *theta, int with_theta)
{
    static const int names[4] = {HERTZ_R1X, HERTZ_R1Y, HERTZ_R2X, HERTZ_R2Y};
    double radius[4];
    int lo = INT32_MAX, scale = 0;
    for (int k = 0; k < 4; ++k) {
        if (!(r[k] != 0.0) || isnan(r[k])) {
            return 1 + names[k];
        }
        if (isfinite(r[k])) {
            int ek = exponent_of(r[k]);
            lo = ek < lo ? ek : lo;
            scale |= ek < -300 || ek > 300;
        }
    }
    if (!isfinite(angle)) {
        return 1 + HERTZ_ANGLE;
    }
    /* With a radius beyond 2^+-300, divide all by 2^lo (exactly) first, so
     * that no curvature overflows; a radius that then overflows is flat to
     * within 2^-1023 of the others. */
    int shift = scale ? lo : 0;
    for (int k = 0; k < 4; ++k) {
        radius[k] = shift ? scale2(r[k], -shift) : r[k];
    }
    double sx = pair_sum(radius[0], radius[2]), sy = pair_sum(radius[1], radius[3]);
    double g1 = pair_difference(radius[0], radius[1]);
    double g2 = pair_difference(radius[2], radius[3]);
    /* Normalise so that the largest of them lies in [1, 2): products below
     * cannot overflow, and a subnormal determinant means alpha > 1e300. */
    double big = fmax(fmax(fabs(sx), fabs(sy)), fmax(fabs(g1), fabs(g2)));
    int t = big > 0.0 ? exponent_of(big) : 0;
    double f = pow2i(-t < -1022 ? -1022 : (-t > 1023 ? 1023 : -t));
    sx *= f;
    sy *= f;
    g1 *= f;
    g2 *= f;
    *e = t - shift; /* true curvature = normalised one * 2^e */
    double s = sin(angle), c = cos(angle);
    double rho_x, rho_y, th;
    if (s == 0.0) {
        rho_x = fmax(sx, sy);
        rho_y = fmin(sx, sy);
        th = sx > sy ? 0.5 * PI : 0.0;
    }
    else {
        double ss = s * s, gg = g1 * g2;
        double trace = sx + sy;
        double det = sx * sy + gg * ss;                                      /* (1) */
        double dg = gg >= 0.0 ? g1 - g2 : g1 + g2;
        double d = sqrt(dg * dg + 4.0 * fabs(gg) * (gg >= 0.0 ? c * c : ss)); /* (2) */
        rho_x = 0.5 * (trace + d);
        rho_y = d <= 0.5 * trace ? 0.5 * (trace - d) : (rho_x > 0.0 ? det / rho_x : 0.0);
        rho_y = fmin(rho_y, rho_x);
        if (rho_x > 0.0 && rho_y > 0.0 && !(det >= DBL_MIN)) {
            rho_y = det > 0.0 ? det / rho_x : rho_y; /* for the message */
            *rx = rho_x;
            *ry = rho_y;
            return HERTZ_LIMIT;
        }
        /* rho_x lies along atan2(g2 sin 2psi, g1 + g2 cos 2psi)/2; the major
         * axis (along rho_y) is normal to it. */
        th = 0.0;
        if (with_theta && d != 0.0) {
            th = 0.5 * atan2(2.0 * g2 * s * c, g1 + g2 * (c - s) * (c + s)) + 0.5 * PI;
            th = th > 0.5 * PI ? th - PI : th;
        }
    }
    *rx = rho_x;
    *ry = rho_y;
    if (!(rho_x > 0.0 && rho_y > 0.0)) {
        if (rho_x > 0.0 && rho_y == 0.0) {
            return HERTZ_LINE;
        }
        return rho_x == 0.0 && rho_y == 0.0 ? HERTZ_FLAT : HERTZ_CONFORM;
    }
    if (!(rho_y >= DBL_MIN) || !(rho_x / rho_y <= DBL_MAX)) {
        return HERTZ_LIMIT;
    }
    *rs = sx + sy;
    *theta = th;
    return HERTZ_OK;
}

/* sin x and cos x for |x| <= FAST_ANGLE: x = k pi/2 + r with pi/2 split in
 * three parts (the first two with 33 significant bits, so k P1 and k P2 are
 * exact for |k| < 2^20), then the Taylor series of sin r and cos r to
 * r^17 and r^18 (truncation below 1e-18 for |r| <= pi/4).  Branch-free, so
 * that a block vectorises; odd and even in x exactly. */
#define FAST_ANGLE 1e5

static inline void
sin_cos(double x, double *sin_x, double *cos_x)
{
    static const double P1 = 0x1.921fb54400000p+0, P2 = 0x1.0b4611a600000p-34,
                        P3 = 0x1.3198a2e037073p-69, TWO_OVER_PI = 0x1.45f306dc9c883p-1,
                        ROUND = 0x1.8p52;
    double t = x * TWO_OVER_PI + ROUND;
    double k = t - ROUND;
    uint64_t bits;
    memcpy(&bits, &t, sizeof bits);
    int quadrant = (int)(bits & 3);
    double r = ((x - k * P1) - k * P2) - k * P3, z = r * r;
    double sp = -1.0 / 6, cp = -1.0 / 2;
    sp = -1.0 / 355687428096000.0;               /* -1/17! */
    sp = 1.0 / 1307674368000.0 + z * sp;         /* 1/15! */
    sp = -1.0 / 6227020800.0 + z * sp;           /* -1/13! */
    sp = 1.0 / 39916800.0 + z * sp;              /* 1/11! */
    sp = -1.0 / 362880.0 + z * sp;               /* -1/9! */
    sp = 1.0 / 5040.0 + z * sp;                  /* 1/7! */
    sp = -1.0 / 120.0 + z * sp;                  /* -1/5! */
    sp = 1.0 / 6.0 + z * sp;                     /* 1/3! */
    double sr = r - r * z * sp;
    cp = 1.0 / 6402373705728000.0;               /* 1/18! */
    cp = -1.0 / 20922789888000.0 + z * cp;       /* -1/16! */
    cp = 1.0 / 87178291200.0 + z * cp;           /* 1/14! */
    cp = -1.0 / 479001600.0 + z * cp;            /* -1/12! */
    cp = 1.0 / 3628800.0 + z * cp;               /* 1/10! */
    cp = -1.0 / 40320.0 + z * cp;                /* -1/8! */
    cp = 1.0 / 720.0 + z * cp;                   /* 1/6! */
    cp = -1.0 / 24.0 + z * cp;                   /* -1/4! */
    cp = 0.5 + z * cp;                           /* 1/2! */
    double cr = 1.0 - z * cp;
    double sv = (quadrant & 1) ? cr : sr, cv = (quadrant & 1) ? sr : cr;
    *sin_x = (quadrant & 2) ? -sv : sv;
    *cos_x = ((quadrant + 1) & 2) ? -cv : cv;
}

/* m in [1, 2) and e with x = m 2^e, for a normal x > 0 (bits only). */
static inline double
split_normal(double x, int *e)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    *e = (int)((bits >> 52) & 0x7FF) - 1023;
    bits = (bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull;
    memcpy(&x, &bits, sizeof x);
    return x;
}

/* Stage 1 of a block, the common case, branch-free: inputs in range
 * (finite radii within 2^+-300, normal moduli within 2^+-1000, |angle| <=
 * FAST_ANGLE) and a valid contact.  Elements outside it are flagged in
 * `other` and done by the scalar code (curvatures, reduced_modulus), which
 * also names any error. */
HERTZ_MULTIVERSION static void
fast_geometry(ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY], double *restrict alpha,
              double *restrict rho_sum, int *restrict ce, double *restrict es_m,
              int *restrict es_e, double *restrict rho_x, double *restrict rho_y,
              int *restrict other)
{
    const double *restrict R1X = in[HERTZ_R1X], *restrict R1Y = in[HERTZ_R1Y];
    const double *restrict R2X = in[HERTZ_R2X], *restrict R2Y = in[HERTZ_R2Y];
    const double *restrict ANGLE = in[HERTZ_ANGLE];
    const double *restrict E1 = in[HERTZ_E1], *restrict NU1 = in[HERTZ_NU1];
    const double *restrict E2 = in[HERTZ_E2], *restrict NU2 = in[HERTZ_NU2];
    for (ptrdiff_t i = 0; i < n; ++i) {
        double r1x = R1X[i], r1y = R1Y[i], r2x = R2X[i], r2y = R2Y[i];
        double angle = ANGLE[i];
        double e1 = E1[i], nu1 = NU1[i], e2 = E2[i], nu2 = NU2[i];
        const double lo = 0x1p-300, hi = 0x1p300;
#define RADIUS_OK(r) ((fabs(r) >= lo && fabs(r) <= hi) || fabs(r) == INFINITY)
        int ok = RADIUS_OK(r1x) && RADIUS_OK(r1y) && RADIUS_OK(r2x) && RADIUS_OK(r2y)
                 && fabs(angle) <= FAST_ANGLE && e1 >= 0x1p-1000 && e1 <= 0x1p1000
                 && e2 >= 0x1p-1000 && e2 <= 0x1p1000 && nu1 > -1.0 && nu1 <= 0.5
                 && nu2 > -1.0 && nu2 <= 0.5;
#undef RADIUS_OK
        /* sanitised inputs where not ok, so that nothing below traps or
         * takes long; the element is redone by the scalar code */
        r1x = ok ? r1x : 1.0;
        r1y = ok ? r1y : 1.0;
        r2x = ok ? r2x : 1.0;
        r2y = ok ? r2y : 1.0;
        angle = ok ? angle : 0.0;
        e1 = ok ? e1 : 1.0;
        e2 = ok ? e2 : 1.0;
        double px = r1x * r2x, py = r1y * r2y, q1 = r1x * r1y, q2 = r2x * r2y;
        double k1x = 1.0 / r1x, k1y = 1.0 / r1y, k2x = 1.0 / r2x, k2y = 1.0 / r2y;
        double sx = (px < 0.0 && px > -INFINITY) ? (r1x + r2x) / px : k1x + k2x;
        double sy = (py < 0.0 && py > -INFINITY) ? (r1y + r2y) / py : k1y + k2y;
        double g1 = (q1 > 0.0 && q1 < INFINITY) ? (r1y - r1x) / q1 : k1x - k1y;
        double g2 = (q2 > 0.0 && q2 < INFINITY) ? (r2y - r2x) / q2 : k2x - k2y;
        double big = fabs(sx) > fabs(sy) ? fabs(sx) : fabs(sy);
        big = fabs(g1) > big ? fabs(g1) : big;
        big = fabs(g2) > big ? fabs(g2) : big;
        ok = ok && big > 0.0;
        int t;
        split_normal(ok ? big : 1.0, &t);
        double f = pow2i(-t);
        sx *= f;
        sy *= f;
        g1 *= f;
        g2 *= f;
        double sn, cs;
        sin_cos(angle, &sn, &cs);
        double ss = sn * sn, cc = cs * cs, gg = g1 * g2;
        double trace = sx + sy, det = sx * sy + gg * ss;                        /* (1) */
        double dg = gg >= 0.0 ? g1 - g2 : g1 + g2;
        double d = sqrt(dg * dg + 4.0 * fabs(gg) * (gg >= 0.0 ? cc : ss));      /* (2) */
        double rx = 0.5 * (trace + d);
        double ry = d <= 0.5 * trace ? 0.5 * (trace - d) : det / rx;
        ry = ry < rx ? ry : rx;
        int aligned = sn == 0.0;
        double rx0 = sx > sy ? sx : sy, ry0 = sx > sy ? sy : sx;
        rx = aligned ? rx0 : rx;
        ry = aligned ? ry0 : ry;
        ok = ok && rx > 0.0 && ry >= DBL_MIN && (aligned || det >= DBL_MIN)
             && rx / ry <= DBL_MAX;
        other[i] = !ok;
        alpha[i] = ok ? rx / ry : 1.0;
        rho_sum[i] = ok ? sx + sy : 1.0;
        ce[i] = t;
        rho_x[i] = rx * pow2i(t);
        rho_y[i] = ry * pow2i(t);
        /* E* as in reduced_modulus, normal moduli only */
        double c1 = (1.0 - nu1) * (1.0 + nu1), c2 = (1.0 - nu2) * (1.0 + nu2);
        int swap = e1 > e2 || (e1 == e2 && c1 > c2);
        double elo = swap ? e2 : e1, ehi = swap ? e1 : e2;
        double clo = swap ? c2 : c1, chi = swap ? c1 : c2;
        int ee;
        double em = split_normal(elo, &ee);
        es_m[i] = em / (clo + chi * (elo / ehi));
        es_e[i] = ee;
    }
}

int
hertz_geometry_block(ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY],
                     hertz_geometry *g, ptrdiff_t *bad, int with_theta)
{
    double alpha[HERTZ_BLOCK] = {0.0}, lam[HERTZ_BLOCK], m[HERTZ_BLOCK], K[HERTZ_BLOCK],
        E[HERTZ_BLOCK], rs[HERTZ_BLOCK], esm[HERTZ_BLOCK], rx[HERTZ_BLOCK], ry[HERTZ_BLOCK];
    int ce[HERTZ_BLOCK], ese[HERTZ_BLOCK];
    int other[HERTZ_BLOCK];
    fast_geometry(n, in, alpha, rs, ce, esm, ese, rx, ry, other);
    for (ptrdiff_t i = 0; i < n; ++i) {
        g[i].theta = 0.0;
        g[i].rho_x = rx[i];
        g[i].rho_y = ry[i];
        if (!other[i] && !with_theta) {
            continue;
        }
        double r[4] = {in[HERTZ_R1X][i], in[HERTZ_R1Y][i], in[HERTZ_R2X][i], in[HERTZ_R2Y][i]};
        double rxi = 0.0, ryi = 0.0, rsi, theta = 0.0;
        int cei;
        hertz_scaled esi;
        int code = curvatures(r, in[HERTZ_ANGLE][i], &rxi, &ryi, &rsi, &cei, &theta,
                              with_theta);
        if (!other[i]) { /* only the angle was missing */
            g[i].theta = theta;
            continue;
        }
        if (code == HERTZ_OK) {
            code = reduced_modulus(in[HERTZ_E1][i], in[HERTZ_NU1][i], in[HERTZ_E2][i],
                                   in[HERTZ_NU2][i], &esi);
        }
        g[i].rho_x = scale2(rxi, cei);
        g[i].rho_y = scale2(ryi, cei);
        if (code != HERTZ_OK) {
            *bad = i;
            return code;
        }
        alpha[i] = rxi / ryi;
        rs[i] = rsi;
        ce[i] = cei;
        esm[i] = esi.m;
        ese[i] = esi.e;
        g[i].theta = theta;
    }
    hertz_ellipse_block(alpha, n, 1, lam, m, K, E);
    for (ptrdiff_t i = 0; i < n; ++i) {
        int er;
        double rho_m = split_normal(rs[i], &er);
        er += ce[i];
        double half_e = 0.5 / E[i];
        g[i].e_star = scale2(esm[i], ese[i]);
        g[i].alpha = alpha[i];
        g[i].lam = lam[i];
        g[i].m = m[i];
        g[i].K = K[i];
        g[i].E = E[i];
        g[i].cb.m = 3.0 * E[i] / (PI * lam[i] * esm[i] * rho_m);
        g[i].cb.e = -(ese[i] + er);
        g[i].cd.m = K[i] * rho_m * half_e;
        g[i].cd.e = er;
        g[i].cp.m = esm[i] * rho_m * half_e;
        g[i].cp.e = ese[i] + er;
        g[i].cs.m = PI * lam[i] * esm[i] / K[i];
        g[i].cs.e = ese[i];
    }
    return HERTZ_OK;
}

/* Double-double helpers (Dekker 1971, no fused multiply-add needed): the
 * load-dependent outputs are c b^k rounded once, with b carried as hi + lo,
 * so that scaling the load, or going from load to approach or p0 and back,
 * moves them by a unit in the last place or two, not by the sum of the
 * roundings of every step. */
static inline void
veltkamp(double a, double *hi, double *lo)
{
    double t = 134217729.0 * a; /* 2^27 + 1 */
    *hi = t - (t - a);
    *lo = a - *hi;
}

/* a b = p + *err exactly. */
static inline double
two_prod(double a, double b, double *err)
{
    double p = a * b, ah, al, bh, bl;
    veltkamp(a, &ah, &al);
    veltkamp(b, &bh, &bl);
    *err = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    return p;
}

/* (h + l) (x + y) as a double-double. */
static inline double
dd_mul(double h, double l, double x, double y, double *lo)
{
    double e, p = two_prod(h, x, &e);
    e += h * y + l * x;
    double s = p + e;
    *lo = e - (s - p);
    return s;
}

/* (h + l) / c, rounded once. */
static inline double
dd_div(double h, double l, double c)
{
    double q = h / c, e, p = two_prod(q, c, &e);
    return q + (((h - p) - e) + l) / c;
}

/* c (h + l), rounded once. */
static inline double
dd_scale(double c, double h, double l)
{
    double e, p = two_prod(c, h, &e);
    return p + (e + c * l);
}

/* x^(1/3) for 1 <= x < 8 to about 1e-10 (a degree-4 least-squares
 * polynomial for [1, 2], times 2^(j/3), then one Newton step); the caller's
 * double-double Newton step completes it. */
static inline double
cube_root(double x)
{
    static const double C[5] = {1.1447129219983228, 0.2542825412449247, -0.05643544389416345,
                                0.02247174566566939, -0.010274592492448192};
    static const double ROOT2[3] = {1.0, 1.2599210498948732, 1.5874010519681994};
    int j = (x >= 2.0) + (x >= 4.0);
    double m = x / (j == 0 ? 1.0 : (j == 1 ? 2.0 : 4.0)), t = m - 1.5;
    double y = (C[0] + t * (C[1] + t * (C[2] + t * (C[3] + t * C[4])))) * ROOT2[j];
    return y - (y * y * y - x) / (3.0 * y * y);
}

static inline int
floor_div(int e, int k)
{
    return e >= 0 ? e / k : -((k - 1 - e) / k);
}

int
hertz_contact_given(const hertz_geometry *g, int mode, double value,
                    double out[HERTZ_NGIVEN])
{
    if (!(value >= 0.0 && value <= DBL_MAX)) {
        return HERTZ_BAD_VALUE;
    }
    if (value == 0.0) {
        for (int k = 0; k < 6; ++k) {
            out[k] = 0.0;
        }
        return HERTZ_OK;
    }
    hertz_scaled v = split(value);
    double bh, bl, b2h, b2l, load;
    int e, q;
    if (mode == HERTZ_GIVEN_LOAD) {
        /* b^3 = cb P = (xh + xl) 2^(3q): cube root, one Newton step in double-double */
        double xl, xh = two_prod(g->cb.m, v.m, &xl);
        int xe;
        double xm = split_normal(xh, &xe);
        xl *= xm / xh; /* a power of two: exact */
        e = g->cb.e + v.e + xe;
        q = floor_div(e, 3);
        double f = (double)(1 << (e - 3 * q));
        xh = xm * f;
        xl *= f;
        bh = cube_root(xh);
        double sl, sh = two_prod(bh, bh, &sl), cl, ch = dd_mul(sh, sl, bh, 0.0, &cl);
        bl = ((xh - ch) - cl + xl) / (3.0 * sh);
        load = value;
    }
    else if (mode == HERTZ_GIVEN_APPROACH) {
        /* b^2 = t = delta / cd = (th + tl) 2^(2q); P = t b / cb */
        double th = v.m / g->cd.m, pe, pp = two_prod(th, g->cd.m, &pe);
        double tl = ((v.m - pp) - pe) / g->cd.m;
        e = v.e - g->cd.e;
        q = floor_div(e, 2);
        double f = (double)(1 << (e - 2 * q));
        th *= f;
        tl *= f;
        bh = sqrt(th);
        double sl, sh = two_prod(bh, bh, &sl);
        bl = ((th - sh) - sl + tl) / (2.0 * bh);
        double ll, lh = dd_mul(th, tl, bh, bl, &ll);
        load = scale2(dd_div(lh, ll, g->cb.m), 3 * q - g->cb.e);
    }
    else {
        /* b = p0 / cp; P = b^3 / cb */
        bh = v.m / g->cp.m;
        double pe, pp = two_prod(bh, g->cp.m, &pe);
        bl = ((v.m - pp) - pe) / g->cp.m;
        q = v.e - g->cp.e;
        load = 0.0; /* below */
    }
    b2h = dd_mul(bh, bl, bh, bl, &b2l);
    if (mode == HERTZ_GIVEN_P0) {
        double ll, lh = dd_mul(b2h, b2l, bh, bl, &ll);
        load = scale2(dd_div(lh, ll, g->cb.m), 3 * q - g->cb.e);
    }
    out[0] = scale2(dd_scale(g->lam, bh, bl), q);
    out[1] = scale2(bh + bl, q);
    out[2] = load;
    out[3] = mode == HERTZ_GIVEN_P0 ? value : scale2(dd_scale(g->cp.m, bh, bl), g->cp.e + q);
    out[4] = mode == HERTZ_GIVEN_APPROACH ? value
                                          : scale2(dd_scale(g->cd.m, b2h, b2l), g->cd.e + 2 * q);
    out[5] = scale2(dd_scale(g->cs.m, bh, bl), g->cs.e + q);
    return HERTZ_OK;
}

void
hertz_geometry_fields(const hertz_geometry *g, double out[HERTZ_NOUT - HERTZ_NGIVEN])
{
    out[0] = g->lam;
    out[1] = g->alpha;
    out[2] = g->m;
    out[3] = g->K;
    out[4] = g->E;
    out[5] = g->e_star;
    out[6] = g->rho_x;
    out[7] = g->rho_y;
    out[8] = g->theta;
}

/* Line contact (Johnson sec. 4.3): half_width^2 = 4 P' / (pi E* rho),
 * p0^2 = P' E* rho / pi. */
int
hertz_line_contact(const double in[8], double load, double out[5], double *rho_x,
                   double *rho_y)
{
    double rx = 0.0, ry = 0.0, rs, theta;
    int e;
    int code = curvatures(in, 0.0, &rx, &ry, &rs, &e, &theta, 0);
    *rho_x = scale2(rx, e);
    *rho_y = scale2(ry, e);
    if (code == HERTZ_LINE) {
        code = HERTZ_OK;
    }
    else if (code == HERTZ_OK || code == HERTZ_FLAT || code == HERTZ_CONFORM
             || code == HERTZ_LIMIT) {
        code = HERTZ_NOT_LINE;
    }
    hertz_scaled es;
    if (code == HERTZ_OK) {
        code = reduced_modulus(in[4], in[5], in[6], in[7], &es);
        /* reduced_modulus numbers its errors for the point contact's inputs */
    }
    if (code != HERTZ_OK) {
        return code;
    }
    if (!(load >= 0.0 && load <= DBL_MAX)) {
        return HERTZ_BAD_VALUE;
    }
    hertz_scaled rho = split(rx);
    rho.e += e;
    out[2] = scale2(es.m, es.e);
    out[3] = scale2(rho.m, rho.e);
    out[4] = load;
    if (load == 0.0) {
        out[0] = out[1] = 0.0;
        return HERTZ_OK;
    }
    hertz_scaled p = split(load);
    /* w^2 = 4 P / (pi E* rho) and p0^2 = P E* rho / pi, square roots of m 2^e */
    double wm = 4.0 * p.m / (PI * es.m * rho.m), pm = p.m * es.m * rho.m / PI;
    int we = p.e - es.e - rho.e, pe = p.e + es.e + rho.e;
    int wq = we >= 0 ? we / 2 : -((1 - we) / 2), pq = pe >= 0 ? pe / 2 : -((1 - pe) / 2);
    out[0] = scale2(sqrt(wm * (double)(1 << (we - 2 * wq))), wq);
    out[1] = scale2(sqrt(pm * (double)(1 << (pe - 2 * pq))), pq);
    return HERTZ_OK;
}
