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

/* x 2^e, rounded once. */
static inline double
scale2(double x, int e)
{
    if (e >= -1000 && e <= 1000) {
        return x * pow2i(e);
    }
    return ldexp(x, e);
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

/* x = m 2^e with m in [1, 2), for a finite x > 0. */
static inline hertz_scaled
split(double x)
{
    int e = exponent_of(x);
    hertz_scaled s = {e >= -1022 ? x * pow2i(-e) : ldexp(x, -e), e};
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

int
hertz_geometry_block(ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY],
                     hertz_geometry *g, ptrdiff_t *bad, int with_theta)
{
    double alpha[HERTZ_BLOCK] = {0.0}, lam[HERTZ_BLOCK], m[HERTZ_BLOCK], K[HERTZ_BLOCK],
        E[HERTZ_BLOCK], rs[HERTZ_BLOCK];
    int ce[HERTZ_BLOCK];
    hertz_scaled es[HERTZ_BLOCK];
    for (ptrdiff_t i = 0; i < n; ++i) {
        double r[4] = {in[HERTZ_R1X][i], in[HERTZ_R1Y][i], in[HERTZ_R2X][i], in[HERTZ_R2Y][i]};
        double rx = 0.0, ry = 0.0;
        int code = curvatures(r, in[HERTZ_ANGLE][i], &rx, &ry, &rs[i], &ce[i], &g[i].theta,
                              with_theta);
        if (code == HERTZ_OK) {
            code = reduced_modulus(in[HERTZ_E1][i], in[HERTZ_NU1][i], in[HERTZ_E2][i],
                                   in[HERTZ_NU2][i], &es[i]);
        }
        if (code != HERTZ_OK) {
            g[i].rho_x = scale2(rx, ce[i]);
            g[i].rho_y = scale2(ry, ce[i]);
            *bad = i;
            return code;
        }
        alpha[i] = rx / ry;
        g[i].alpha = alpha[i];
        g[i].rho_x = scale2(rx, ce[i]);
        g[i].rho_y = scale2(ry, ce[i]);
        g[i].e_star = scale2(es[i].m, es[i].e);
    }
    hertz_ellipse_block(alpha, n, 1, lam, m, K, E);
    for (ptrdiff_t i = 0; i < n; ++i) {
        hertz_scaled rho = split(rs[i]);
        int er = rho.e + ce[i];
        double half_e = 0.5 / E[i];
        g[i].lam = lam[i];
        g[i].m = m[i];
        g[i].K = K[i];
        g[i].E = E[i];
        g[i].cb.m = 3.0 * E[i] / (PI * lam[i] * es[i].m * rho.m);
        g[i].cb.e = -(es[i].e + er);
        g[i].cd.m = K[i] * rho.m * half_e;
        g[i].cd.e = er;
        g[i].cp.m = es[i].m * rho.m * half_e;
        g[i].cp.e = es[i].e + er;
        g[i].cs.m = PI * lam[i] * es[i].m / K[i];
        g[i].cs.e = es[i].e;
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
        e = g->cb.e + v.e;
        q = floor_div(e, 3);
        double f = (double)(1 << (e - 3 * q));
        xh *= f;
        xl *= f;
        bh = cbrt(xh);
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
