/*
 * hertz._ufuncs, contact formulas: from the principal radii of two bodies,
 * the angle between their principal planes and their moduli to the Hertz
 * contact ellipse, peak pressure, approach and stiffness, one element at a
 * time (lambda, K and E come from the table of _ellipse_table.c).
 *
 * Relative curvatures (Johnson, Contact Mechanics, 1985, sec. 4.2), with
 * k_ix = 1/R_ix, psi the angle from body 1's x axis to body 2's:
 *
 *     Sx = k1x + k2x,  Sy = k1y + k2y,  g_i = k_ix - k_iy,
 *     rho_x + rho_y = Sx + Sy,
 *     rho_x rho_y   = Sx Sy + g1 g2 sin^2 psi,                          (1)
 *                   = Sx Sy cos^2 psi + Cx Cy sin^2 psi,                (1')
 *     (rho_x - rho_y)^2 = (g1 - g2)^2 + 4 g1 g2 cos^2 psi
 *                       = (g1 + g2)^2 - 4 g1 g2 sin^2 psi,              (2)
 *     g1 - g2 = Cx - Cy,  g1 + g2 = Sx - Sy,  Cx = k1x + k2y,  Cy = k1y + k2x.
 *
 * Sx, Sy, g1, g2 are formed times Pi = |r1x r1y r2x r2y| (curvature_products):
 * a pair sum of a concave and a convex radius is (Ra + Rb) times a product of
 * radii, exact however closely the surfaces conform, and one division by Pi
 * replaces eight.  The form of (1)-(1') and of (2) whose terms have one sign
 * keeps every digit ((1') for two convex bodies, whatever the angle), and all
 * are symmetric in the two bodies, so swapping them (psi -> -psi) gives the
 * same bits.  Of the eigenvalues (trace +- d)/2 the one of larger modulus is
 * taken from that sum and the other as rho_x rho_y divided by it: a concave
 * pair (trace < 0) keeps the signs and digits of both, and whether the bodies
 * touch at a point (trace > 0 and rho_x rho_y > 0) follows the true signs.
 * g1 -+ g2 are taken as differences of the pair sums Cx, Cy or Sx, Sy: for
 * two nearly conforming bodies g1 and -g2 nearly cancel, while the pair sums,
 * each exact, differ by an amount of the order of rho_x + rho_y (the contact
 * is valid only then).
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
 * b is carried in double-double (exact products by fma() where the processor
 * has it, by Dekker's splitting elsewhere: the same bits) and every output is
 * c b^k rounded once.
 *
 * Layout: a block of up to HERTZ_BLOCK elements goes through stages, each a
 * loop over arrays written with doubles and 64-bit bit patterns only (no
 * integer-double conversions, no branches), so that the compiler
 * vectorises it: geometry (fast_geometry, fast_moduli), the ellipse table,
 * the coefficients, the load-dependent outputs (given_*).  Elements outside
 * the common case (radii beyond 2^+-240, moduli beyond [2^-900, 2^1000],
 * |angle| > 1e5, no valid contact, a cancelling trace or (1')) are flagged
 * and done by the scalar code (curvatures(): exponent-scaled double-double,
 * the pair sums exact at any exponent), which also names errors; zero,
 * subnormal and bad values and outputs beyond 2^+-1000 make their block take
 * the exact variants of the load stage.  A
 * single contact goes through the same block code (n = 1), so it has the same
 * bits as in an array.
 */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "_contact_kernel.h"
#include "_fastmath.h"

#define PI 3.14159265358979323846

/* ---------------------------------------------------------- binary scaling */

/* 2^e for an integer-valued e in [-1022, 1023]: the bits of e + 1023 + 2^52,
 * shifted into the exponent field. */
HERTZ_INLINE double
pow2(double e)
{
    return as_double(as_bits(e + (1023.0 + 0x1p52)) << 52);
}

/* x 2^e (e integer-valued), rounded once where the result is normal: two
 * exact steps whose intermediate lies between x and the result. */
HERTZ_INLINE double
scale2(double x, double e)
{
    e = e < -2044.0 ? -2044.0 : (e > 2046.0 ? 2046.0 : e);
    double h = (e * 0.5 + ROUND) - ROUND;
    return x * pow2(h) * pow2(e - h);
}

/* The same for any finite x > 0, subnormals included. */
static hertz_scaled
split(double x)
{
    hertz_scaled s;
    if (x >= DBL_MIN) {
        s.m = split_normal(x, &s.e);
    }
    else {
        int e = ilogb(x);
        s.m = ldexp(x, -e);
        s.e = e;
    }
    return s;
}

/* Binary exponent of a finite x != 0. */
static int
exponent_of(double x)
{
    return ilogb(x);
}

/* Whether any of flags[0..n) (each 0.0 or 1.0) is set.  The block loops store
 * their flags and this loop ORs the bit patterns apart: a reduction inside the
 * loops (a conditional assignment, which GCC 12 vectorises and Clang 14 does
 * not, or an OR of integers, the other way round) would keep one of the two
 * compilers from vectorising them. */
HERTZ_INLINE int
any_flag(ptrdiff_t n, const double *flags)
{
    uint64_t any = 0;
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        any |= as_bits(flags[i]);
    }
    return any != 0;
}

/* ------------------------------------------------ double-double arithmetic */

/* HERTZ_INLINE (hertz/_kernel.h): inlined into each caller, so that a constant
 * `fused` argument selects the code at compile time.
 *
 * a b = p + err exactly: with a fused multiply-add (fused = 1, only where the
 * processor has one: the AVX2 and AVX-512 paths, aarch64) or by Dekker's
 * splitting (1971).  Both are exact, so both give the same bits. */
HERTZ_INLINE void
veltkamp(double a, double *hi, double *lo)
{
    /* a rounded to 26 significant bits on its bits (add half of bit 27 of the
     * significand, clear the 27 below: a carry into the exponent is right) and
     * lo = a - hi exactly, |lo| <= 2^26 ulp(a): the halves of Veltkamp's
     * splitting (2^27 + 1) a, which take three floating-point operations to
     * this one integer addition and one AND, with what Dekker's product needs
     * (each half of at most 26 bits).  For finite a below 2^1023 (no product
     * of the kernels comes near). */
    *hi = as_double((as_bits(a) + 0x4000000ull) & 0xFFFFFFFFF8000000ull);
    *lo = a - *hi;
}

HERTZ_INLINE double
two_prod(double a, double b, double *err, const int fused)
{
    double p = a * b;
    if (fused) {
        *err = fma(a, b, -p);
    }
    else {
        double ah, al, bh, bl;
        veltkamp(a, &ah, &al);
        veltkamp(b, &bh, &bl);
        *err = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    }
    return p;
}

/* two_prod for a b26 of at most 26 significant bits: a's halves times b26
 * are exact, and so is their sum with the rounding of the product. */
HERTZ_INLINE double
two_prod_26(double a, double b26, double *err, const int fused)
{
    double p = a * b26;
    if (fused) {
        *err = fma(a, b26, -p);
    }
    else {
        double ah, al;
        veltkamp(a, &ah, &al);
        *err = (ah * b26 - p) + al * b26;
    }
    return p;
}

/* (h + l)(x + y) as a double-double. */
HERTZ_INLINE double
dd_mul(double h, double l, double x, double y, double *lo, const int fused)
{
    double e, p = two_prod(h, x, &e, fused);
    e += h * y + l * x;
    double s = p + e;
    *lo = e - (s - p);
    return s;
}

/* c (h + l), rounded once, for an h of at most 26 significant bits. */
HERTZ_INLINE double
dd_scale_26(double c, double h, double l, const int fused)
{
    double e, p = two_prod_26(c, h, &e, fused);
    return p + (e + c * l);
}

/* (h + l) / c, rounded once. */
HERTZ_INLINE double
dd_div(double h, double l, double c, const int fused)
{
    double q = h / c, e, p = two_prod(q, c, &e, fused);
    return q + (((h - p) - e) + l) / c;
}

/* c (h + l), rounded once. */
HERTZ_INLINE double
dd_scale(double c, double h, double l, const int fused)
{
    double e, p = two_prod(c, h, &e, fused);
    return p + (e + c * l);
}

/* a + b = s + err exactly (Knuth), either order of a and b. */
HERTZ_INLINE double
two_sum(double a, double b, double *err)
{
    double s = a + b, bb = s - a;
    *err = (a - (s - bb)) + (b - bb);
    return s;
}

/* (ah + al) + (bh + bl) as a double-double, to 2^-104 relative however much
 * the two cancel. */
HERTZ_INLINE double
dd_add(double ah, double al, double bh, double bl, double *lo)
{
    double e, s = two_sum(ah, bh, &e), f, t = two_sum(al, bl, &f);
    e += t;
    double u = s + e;
    e = e - (u - s) + f;
    s = u + e;
    *lo = e - (s - u);
    return s;
}

/* -------------------------------------------------- elementary functions */

/* sin^2 x and cos^2 x for |x| <= FAST_ANGLE: x = k pi/2 + r with pi/2 in
 * three parts (the first two of 33 significant bits, so k P1 and k P2 are
 * exact for |k| < 2^20), the Taylor series of sin r to r^17 (truncation below
 * 1e-18 for |r| <= pi/4), and cos^2 r = 1 - sin^2 r (at least 1/2, so without
 * cancellation); an odd quadrant swaps the two.  Each keeps its relative
 * accuracy however small it is, and both are even in x exactly. */
#define FAST_ANGLE 1e5

HERTZ_INLINE void
sin2_cos2(double x, double *sin2_x, double *cos2_x)
{
    double k, r = reduce_half_pi(x, &k), z = r * r;
    double sr = sin_reduced(r, z);
    double s2 = sr * sr, c2 = 1.0 - s2;
    /* k odd: sin^2 x = cos^2 r; the parity of k is the last bit of k + ROUND
     * (exact, |k| < 2^20), and the two are swapped on their bits */
    uint64_t odd = 0 - (as_bits(k + ROUND) & 1), swap = (as_bits(s2) ^ as_bits(c2)) & odd;
    *sin2_x = as_double(as_bits(s2) ^ swap);
    *cos2_x = as_double(as_bits(c2) ^ swap);
}

/* sin^2 x and cos^2 x as double-doubles (to about 2^-100 relative) for
 * |x| <= FAST_ANGLE, for the scenes whose curvature determinant cancels: the
 * reduction of sin2_cos2 carried in double-double with a fourth part of pi/2,
 * the sine series to r^27 (the terms below 1e-16 summed in double). */
static void
sin2_cos2_dd(double x, double ss[2], double cc[2])
{
    const double P1 = 0x1.921fb54400000p+0, P2 = 0x1.0b4611a600000p-34,
                 P3 = 0x1.3198a2e037073p-69, P4 = 0x1.129024e088a68p-123,
                 TWO_OVER_PI = 0x1.45f306dc9c883p-1;
    double k = (x * TWO_OVER_PI + ROUND) - ROUND;
    double rl, rh = two_sum(x - k * P1, -(k * P2), &rl); /* k P1, k P2 and x - k P1 exact */
    double pl, ph = two_prod(k, P3, &pl, 0);
    rh = dd_add(rh, rl, -ph, -(pl + k * P4), &rl);
    double zl, zh = dd_mul(rh, rl, rh, rl, &zl, 0);
    /* sin r / r = sum_j (-1)^j z^j / (2j + 1)!: j >= 8 in double, j <= 7 in
     * double-double with 1/(2j + 1)! = hi + lo (the factorials are exact). */
    double tail = 0.0, factorial[14];
    factorial[0] = 1.0;
    for (int j = 1; j < 14; ++j) {
        factorial[j] = factorial[j - 1] * (2.0 * j) * (2.0 * j + 1.0);
    }
    for (int j = 13; j >= 8; --j) {
        tail = (j % 2 ? -1.0 : 1.0) / factorial[j] + zh * tail;
    }
    double al = 0.0, ah = tail;
    for (int j = 7; j >= 0; --j) {
        double h = 1.0 / factorial[j], e, p = two_prod(h, factorial[j], &e, 0);
        double l = ((1.0 - p) - e) / factorial[j];
        h = j % 2 ? -h : h;
        l = j % 2 ? -l : l;
        ah = dd_mul(ah, al, zh, zl, &al, 0);
        ah = dd_add(h, l, ah, al, &al);
    }
    double sl, sh = dd_mul(rh, rl, ah, al, &sl, 0);
    double s2l, s2h = dd_mul(sh, sl, sh, sl, &s2l, 0);
    double c2l, c2h = dd_add(1.0, 0.0, -s2h, -s2l, &c2l);
    int odd = fmod(k, 2.0) != 0.0;
    ss[0] = odd ? c2h : s2h;
    ss[1] = odd ? c2l : s2l;
    cc[0] = odd ? s2h : c2h;
    cc[1] = odd ? s2l : c2l;
}

/* x^(-1/3) for x = m 2^j, 1 <= m < 2, j in {0, 1, 2}, to 3e-9 without a
 * division: a degree-4 least-squares polynomial for m^(-1/3) (fitted at 64
 * Chebyshev nodes, error 3.9e-5) times 2^(-j/3), then one Newton step
 * r <- r (4 - x r^3)/3 (error 2 (3.9e-5)^2).  The caller's double-double step
 * completes the cube root. */
HERTZ_INLINE double
inverse_cube_root(double m, double j)
{
    const double C0 = 0.8735853831770144, C1 = -0.1938092862297736,
                 C2 = 0.08593193062435243, C3 = -0.049690080091560035,
                 C4 = 0.028427719739719047;
    double x = m * pow2(j), t = m - 1.5; /* 2^j by its bits: no select */
    /* Estrin's scheme and the Newton step as r/3 (4 - (r r)(r x)): fewer
     * operations in a row (the chain's latency bounds the narrow vectors of
     * the plain path) */
    double t2 = t * t;
    double r = ((C0 + C1 * t) + t2 * ((C2 + C3 * t) + C4 * t2))
               * (j >= 2.0 ? 0.6299605249474366 : (j >= 1.0 ? 0.7937005259840998 : 1.0));
    return (r * (1.0 / 3.0)) * (4.0 - (r * r) * (r * x));
}

/* -------------------------------------------- the exact scalar geometry */

/* The relative curvature sums and differences of eq. (1)-(2) multiplied by
 * Pi = |r1x r1y r2x r2y|, so that one division (by Pi, where a true
 * curvature is needed) replaces eight:
 *
 *     Sx Pi = (r1x + r2x) r1y r2y,   Sy Pi = (r1y + r2y) r1x r2x,
 *     g1 Pi = (r1y - r1x) r2x r2y,   g2 Pi = (r2y - r2x) r1x r1y,
 *     Cx Pi = (r1x + r2y) r1y r2x,   Cy Pi = (r1y + r2x) r1x r2y,
 *
 * each times the sign of r1x r1y r2x r2y.  A pair sum of a concave and a
 * convex radius and a difference of radii of one sign are single roundings
 * of exact differences: no cancellation, however closely the surfaces
 * conform.  An infinite radius (a plane, a cylinder's axis) counts as 1 in
 * the products and 0 in the sums.  Swapping the bodies gives the same bits.
 * For radii within 2^+-RADIUS_RANGE nothing overflows or underflows. */
#define RADIUS_RANGE 240

/* The six quantities of curvature_products, in the order Sx, Sy, g1, g2, Cx,
 * Cy, are sign (p[k] + q[k]) (a[k] b[k]), each of p, q, a, b a radius, 1 or 0.
 * Returns r1x r1y r2x r2y (for its sign); *pabs = Pi.  finite = 1 (a constant)
 * where every radius is known to be finite: u = r and w = 1, the same bits
 * without the selects that stand in for an infinite radius. */
HERTZ_INLINE double
curvature_terms(double r1x, double r1y, double r2x, double r2y, double p[6], double q[6],
                double a[6], double b[6], double *pabs, const int finite)
{
    double u1x = r1x, u1y = r1y, u2x = r2x, u2y = r2y;
    /* w = 1 for a finite radius, 0 for an infinite one: 1/r = w/u */
    double w1x = 1.0, w1y = 1.0, w2x = 1.0, w2y = 1.0;
    if (!finite) {
        double f1x = fabs(r1x) == INFINITY ? 0.0 : r1x, f1y = fabs(r1y) == INFINITY ? 0.0 : r1y;
        double f2x = fabs(r2x) == INFINITY ? 0.0 : r2x, f2y = fabs(r2y) == INFINITY ? 0.0 : r2y;
        u1x = f1x == 0.0 ? 1.0 : r1x;
        u1y = f1y == 0.0 ? 1.0 : r1y;
        u2x = f2x == 0.0 ? 1.0 : r2x;
        u2y = f2y == 0.0 ? 1.0 : r2y;
        w1x = f1x == 0.0 ? 0.0 : 1.0;
        w1y = f1y == 0.0 ? 0.0 : 1.0;
        w2x = f2x == 0.0 ? 0.0 : 1.0;
        w2y = f2y == 0.0 ? 0.0 : 1.0;
    }
    const double sum[6][2] = {{w1x * u2x, w2x * u1x}, {w1y * u2y, w2y * u1y},
                              {w1x * u1y, -(w1y * u1x)}, {w2x * u2y, -(w2y * u2x)},
                              {w1x * u2y, w2y * u1x}, {w1y * u2x, w2x * u1y}};
    const double product[6][2] = {{u1y, u2y}, {u1x, u2x}, {u2x, u2y},
                                  {u1x, u1y}, {u1y, u2x}, {u1x, u2y}};
    HERTZ_UNROLL(6)
    for (int k = 0; k < 6; ++k) {
        p[k] = sum[k][0];
        q[k] = sum[k][1];
        a[k] = product[k][0];
        b[k] = product[k][1];
    }
    double pi = (u1x * u1y) * (u2x * u2y);
    *pabs = fabs(pi);
    return pi;
}

HERTZ_INLINE void
curvature_products(double r1x, double r1y, double r2x, double r2y, double *sx, double *sy,
                   double *g1, double *g2, double *cx, double *cy, double *pabs,
                   const int finite)
{
    double p[6], q[6], a[6], b[6], v[6];
    double pi = curvature_terms(r1x, r1y, r2x, r2y, p, q, a, b, pabs, finite);
    /* sign (p + q) (a b) with the sign of pi: its sign bit XORed in (a
     * product's sign is the XOR of its factors', its modulus the same) */
    uint64_t sign = as_bits(pi) & 0x8000000000000000ull;
    HERTZ_UNROLL(6)
    for (int k = 0; k < 6; ++k) {
        v[k] = as_double(as_bits((p[k] + q[k]) * (a[k] * b[k])) ^ sign);
    }
    *sx = v[0];
    *sy = v[1];
    *g1 = v[2];
    *g2 = v[3];
    *cx = v[4];
    *cy = v[5];
}

/* rho_x rho_y of eq. (1) in the form whose two terms have one sign where
 * there is one (Sx Sy c^2 + Cx Cy s^2 = Sx Sy + g1 g2 s^2, as g1 g2 =
 * Cx Cy - Sx Sy):
 *
 *     rho_x rho_y = Sx Sy + g1 g2 sin^2 psi            (g1 g2 and Sx Sy of one sign)
 *                 = Sx Sy cos^2 psi + Cx Cy sin^2 psi  (otherwise),        (1')
 *
 * the second a sum of non-negative terms for two convex bodies, and never
 * more cancelling than the first.  *terms = the sum of the terms' moduli
 * (for cancels). */
HERTZ_INLINE double
curvature_determinant(double sx, double sy, double cx, double cy, double gg, double ss,
                      double cc, double *terms)
{
    /* (a product p gg below 2^-1074 counts as one sign: the cancels() test remains) */
    double p = sx * sy, one_sign = p * gg >= 0.0 ? 1.0 : 0.0;
    double u = one_sign != 0.0 ? p : p * cc, v = one_sign != 0.0 ? gg * ss : (cx * cy) * ss;
    *terms = fabs(u) + fabs(v);
    return u + v;
}

/* Whether rho_x + rho_y or rho_x rho_y, eq. (1'), loses more than one bit to
 * cancellation (then the scalar code recomputes them in double-double). */
HERTZ_INLINE int
cancels(double sx, double sy, double trace, double det, double terms)
{
    return (fabs(trace) < 0.5 * (fabs(sx) + fabs(sy))) | (fabs(det) < 0.5 * terms);
}

/* ------------------------------- exponent-scaled double-double arithmetic */

/* (h + l) 2^e, |h| in [1, 2) (or h = l = e = 0) and |l| <= ulp(h)/2: the
 * numbers of the scalar geometry, about 2^-104 relative at any exponent, so
 * that a curvature of a radius of 1e-310 meets one of 1e300 without overflow,
 * underflow or cancellation. */
typedef struct {
    double h, l;
    int e;
} xdd;

static const xdd XDD_ZERO = {0.0, 0.0, 0};

static xdd
xdd_make(double h, double l, int e)
{
    double s = h + l;
    l = l - (s - h);
    if (s == 0.0) {
        return XDD_ZERO;
    }
    int k = ilogb(s);
    xdd x = {ldexp(s, -k), ldexp(l, -k), e + k};
    return x;
}

static xdd
xdd_of(double x) /* x finite */
{
    return xdd_make(x, 0.0, 0);
}

static xdd
xdd_neg(xdd a)
{
    a.h = -a.h;
    a.l = -a.l;
    return a;
}

static xdd
xdd_mul(xdd a, xdd b)
{
    if (a.h == 0.0 || b.h == 0.0) {
        return XDD_ZERO;
    }
    double l, h = dd_mul(a.h, a.l, b.h, b.l, &l, 0);
    return xdd_make(h, l, a.e + b.e);
}

/* a + b, either order giving the same bits. */
static xdd
xdd_add(xdd a, xdd b)
{
    if (a.h == 0.0) {
        return b;
    }
    if (b.h == 0.0) {
        return a;
    }
    if (a.e < b.e) {
        xdd t = a;
        a = b;
        b = t;
    }
    int k = b.e - a.e;
    if (k < -120) { /* b below 2^-118 of a: beyond the precision */
        return a;
    }
    double l, h = dd_add(a.h, a.l, ldexp(b.h, k), ldexp(b.l, k), &l);
    return xdd_make(h, l, a.e);
}

static xdd
xdd_div(xdd a, xdd b) /* b != 0 */
{
    if (a.h == 0.0) {
        return XDD_ZERO;
    }
    double q = a.h / b.h, pl, ph = dd_mul(q, 0.0, b.h, b.l, &pl, 0);
    double rl, rh = dd_add(a.h, a.l, -ph, -pl, &rl);
    double q2 = (rh + rl) / b.h, s = q + q2;
    return xdd_make(s, q2 - (s - q), a.e - b.e);
}

static xdd
xdd_sqrt(xdd a) /* a >= 0 */
{
    if (a.h <= 0.0) {
        return XDD_ZERO;
    }
    double h = a.h, l = a.l;
    int e = a.e;
    if (e % 2 != 0) {
        h *= 2.0;
        l *= 2.0;
        e -= 1;
    }
    double s = sqrt(h), pl, ph = two_prod(s, s, &pl, 0);
    double c = (((h - ph) - pl) + l) / (2.0 * s), r = s + c;
    return xdd_make(r, c - (r - s), e / 2);
}

static xdd
xdd_scale2(xdd a, int k)
{
    a.e = a.h == 0.0 ? 0 : a.e + k;
    return a;
}

/* The rounded mantissa of a at exponent e: (h + l) 2^(a.e - e). */
static double
xdd_at(xdd a, int e)
{
    return ldexp(a.h + a.l, a.e - e);
}

/* 1/ra + 1/rb = (ra + rb) / (ra rb) for radii ra, rb (inf counting as a zero
 * curvature) at any exponents: both are scaled by a common power of two, so
 * the sum is exact however closely a concave and a convex radius conform and
 * the product exact however large or small they are.  Symmetric in ra, rb. */
static xdd
xdd_pair(double ra, double rb)
{
    int fa = isfinite(ra), fb = isfinite(rb);
    if (!fa || !fb) {
        return fa || fb ? xdd_div(xdd_of(1.0), xdd_of(fa ? ra : rb)) : XDD_ZERO;
    }
    hertz_scaled a = split(fabs(ra)), b = split(fabs(rb));
    double ma = ra < 0.0 ? -a.m : a.m, mb = rb < 0.0 ? -b.m : b.m;
    double top = a.e > b.e ? a.e : b.e;
    /* a part of the smaller radius below 2^-1074 of the larger is lost: it is
     * below 2^-1000 of the sum */
    double sl, sh = two_sum(ldexp(ma, (int)(a.e - top)), ldexp(mb, (int)(b.e - top)), &sl);
    double pl, ph = two_prod(ma, mb, &pl, 0);
    xdd sum = xdd_make(sh, sl, (int)top), product = xdd_make(ph, pl, (int)(a.e + b.e));
    return xdd_div(sum, product);
}

/* The moduli ordered so that E_lo <= E_hi (ties by c = 1 - nu^2), which makes
 * E* symmetric in the bodies. */
HERTZ_INLINE void
order_moduli(double e1, double nu1, double e2, double nu2, double *elo, double *ehi,
             double *clo, double *chi)
{
    double c1 = (1.0 - nu1) * (1.0 + nu1), c2 = (1.0 - nu2) * (1.0 + nu2);
    double swap = e1 > e2 ? 1.0 : (e1 == e2 ? (c1 > c2 ? 1.0 : 0.0) : 0.0);
    *elo = swap != 0.0 ? e2 : e1;
    *ehi = swap != 0.0 ? e1 : e2;
    *clo = swap != 0.0 ? c2 : c1;
    *chi = swap != 0.0 ? c1 : c2;
}

/* E* = E_lo / (c_lo + c_hi E_lo / E_hi) as em 2^ee (E_lo = em 2^ee) with one
 * division, for moduli in [2^-900, 2^1000] (where no product below leaves the
 * normal range). */
HERTZ_INLINE double
modulus_mantissa(double elo, double ehi, double clo, double chi, double *ee)
{
    double em = split_normal(elo, ee);
    return em * ehi / (clo * ehi + chi * elo);
}

/* Validate the moduli and return E* as a scaled value:
 * 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2, with the formula of the block code
 * where it applies, else as E_lo / (c_lo + c_hi E_lo/E_hi) (E_lo may be
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
    double elo, ehi, clo, chi;
    order_moduli(e1, nu1, e2, nu2, &elo, &ehi, &clo, &chi);
    hertz_scaled s;
    if (elo >= 0x1p-900 && ehi <= 0x1p1000) {
        s.m = modulus_mantissa(elo, ehi, clo, chi, &s.e); /* as in fast_moduli */
    }
    else {
        s = split(elo);
        s.m /= clo + chi * (elo / ehi);
    }
    *e_star = s;
    return HERTZ_OK;
}

/* The major-axis angle in [-pi/2, pi/2] from g2, Sx - Sy (at one scale) and
 * the angle (0 where they leave it undefined): rho_x lies along
 * atan2(g2 sin 2psi, g1 + g2 cos 2psi)/2, with g1 + g2 cos 2psi =
 * (Sx - Sy) - 2 g2 sin^2 psi; the major axis (along rho_y) is normal to it. */
static double
axis_angle(double g2, double sxmsy, double ss, double angle)
{
    double s = sin(angle), c = cos(angle), y = 2.0 * g2 * s * c, x = sxmsy - 2.0 * g2 * ss;
    if (y == 0.0 && x == 0.0) { /* a circle */
        return 0.0;
    }
    double th = 0.5 * atan2(y, x) + 0.5 * PI;
    return th > 0.5 * PI ? th - PI : th;
}

/* The major-axis angle of an element the block code did (radii within
 * 2^+-RADIUS_RANGE, |angle| <= FAST_ANGLE), from the same products. */
static double
block_axis_angle(const double r[4], double angle)
{
    double sx, sy, g1, g2, cx, cy, pabs, ss, cc;
    curvature_products(r[0], r[1], r[2], r[3], &sx, &sy, &g1, &g2, &cx, &cy, &pabs, 0);
    sin2_cos2(angle, &ss, &cc);
    if (ss == 0.0) {
        return sx > sy ? 0.5 * PI : 0.0;
    }
    double big = fmax(fmax(fabs(sx), fabs(sy)), fmax(fabs(g1), fabs(g2)));
    double f = big > 0.0 ? pow2(-(double)exponent_of(big)) : 1.0;
    return axis_angle(g2 * f, (sx - sy) * f, ss, angle);
}

/* Principal relative curvatures rho_x >= rho_y (as rx 2^e and ry 2^e), their
 * sum (rs 2^rse) and the major-axis angle of one geometry, for any
 * input: the scalar code, in exponent-scaled double-double (xdd).  The six
 * pair sums of eq. (1)-(2) are exact at any exponent (xdd_pair), rho_x rho_y
 * is (1'), and of the two eigenvalues
 *
 *     (trace +- d) / 2,  d = |rho_x - rho_y| from (2),
 *
 * the one of larger modulus is taken from this sum (no cancellation) and the
 * other as det divided by it, so that both keep their sign and digits for
 * concave pairs (trace < 0) as for convex ones.  HERTZ_OK or an error code;
 * named = {rho_x, rho_y} (the true curvatures, each with its own exponent)
 * for the contact errors. */
static int
curvatures(const double r[4], double angle, double *rx, double *ry, double *rs,
           double *rse, double *e, double *theta, int with_theta, hertz_scaled named[2])
{
    static const int names[4] = {HERTZ_R1X, HERTZ_R1Y, HERTZ_R2X, HERTZ_R2Y};
    for (int k = 0; k < 4; ++k) {
        if (!(r[k] != 0.0) || isnan(r[k])) {
            return 1 + names[k];
        }
    }
    if (!isfinite(angle)) {
        return 1 + HERTZ_ANGLE;
    }
    xdd Sx = xdd_pair(r[0], r[2]), Sy = xdd_pair(r[1], r[3]);
    xdd Cx = xdd_pair(r[0], r[3]), Cy = xdd_pair(r[1], r[2]);
    xdd G1 = xdd_pair(r[0], -r[1]), G2 = xdd_pair(r[2], -r[3]);
    xdd SS, CC;
    if (fabs(angle) <= FAST_ANGLE) {
        double s2[2], c2[2];
        sin2_cos2_dd(angle, s2, c2);
        SS = xdd_make(s2[0], s2[1], 0);
        CC = xdd_make(c2[0], c2[1], 0);
    }
    else {
        double s = sin(angle), c = cos(angle), l, h = two_prod(s, s, &l, 0);
        SS = xdd_make(h, l, 0);
        h = two_prod(c, c, &l, 0);
        CC = xdd_make(h, l, 0);
    }
    xdd trace = xdd_add(Sx, Sy), rho_x, rho_y;
    if (SS.h == 0.0) {
        int sx_larger = xdd_add(Sx, xdd_neg(Sy)).h > 0.0;
        rho_x = sx_larger ? Sx : Sy;
        rho_y = sx_larger ? Sy : Sx;
    }
    else {
        xdd gg = xdd_mul(G1, G2), sxy = xdd_mul(Sx, Sy);
        int one_sign = (sxy.h >= 0.0) == (gg.h >= 0.0);
        xdd det = one_sign ? xdd_add(sxy, xdd_mul(gg, SS))                       /* (1) */
                           : xdd_add(xdd_mul(sxy, CC), xdd_mul(xdd_mul(Cx, Cy), SS)); /* (1') */
        /* (2): the form whose terms have one sign */
        xdd dg = gg.h >= 0.0 ? xdd_add(Cx, xdd_neg(Cy)) : xdd_add(Sx, xdd_neg(Sy));
        xdd four_gg = xdd_scale2(gg.h >= 0.0 ? gg : xdd_neg(gg), 2);
        xdd d = xdd_sqrt(xdd_add(xdd_mul(dg, dg), xdd_mul(four_gg, gg.h >= 0.0 ? CC : SS)));
        if (trace.h >= 0.0) {
            rho_x = xdd_scale2(xdd_add(trace, d), -1);
            rho_y = rho_x.h != 0.0 ? xdd_div(det, rho_x) : XDD_ZERO;
        }
        else {
            rho_y = xdd_scale2(xdd_add(trace, xdd_neg(d)), -1);
            rho_x = xdd_div(det, rho_y);
        }
    }
    /* one exponent for both, that of the larger modulus */
    *e = rho_x.h == 0.0 || (rho_y.h != 0.0 && rho_y.e > rho_x.e) ? rho_y.e : rho_x.e;
    *rx = xdd_at(rho_x, (int)*e);
    *ry = xdd_at(rho_y, (int)*e);
    named[0].m = xdd_at(rho_x, rho_x.e); /* each at its own exponent, for the errors */
    named[0].e = rho_x.e;
    named[1].m = xdd_at(rho_y, rho_y.e);
    named[1].e = rho_y.e;
    if (!(rho_y.h > 0.0)) {
        if (rho_x.h > 0.0 && rho_y.h == 0.0) {
            return HERTZ_LINE;
        }
        return rho_x.h == 0.0 && rho_y.h == 0.0 ? HERTZ_FLAT : HERTZ_CONFORM;
    }
    if (!(*ry >= DBL_MIN) || !(*rx / *ry <= DBL_MAX)) {
        return HERTZ_LIMIT;
    }
    *rs = xdd_at(trace, trace.e);
    *rse = trace.e;
    *theta = 0.0;
    if (with_theta && SS.h == 0.0) {
        *theta = xdd_add(Sx, xdd_neg(Sy)).h > 0.0 ? 0.5 * PI : 0.0;
    }
    else if (with_theta) {
        xdd x = xdd_add(xdd_add(Sx, xdd_neg(Sy)), xdd_neg(xdd_scale2(xdd_mul(G2, SS), 1)));
        int top = x.e > G2.e ? x.e : G2.e;
        double g2 = xdd_at(G2, top), sxmsy = xdd_at(x, top);
        /* axis_angle with ss = 0 in place of sin^2: x already holds it */
        *theta = axis_angle(g2, sxmsy, 0.0, angle);
    }
    return HERTZ_OK;
}
/* ------------------------------------------------------ the block stages */

/* What stage 1 leaves per element of a block (structure of arrays): alpha;
 * the sum of the relative curvatures, rs 2^rse; E* = esm 2^ese; rho_x, rho_y
 * as rx 2^ce / pabs and ry 2^ce / pabs; other = 1 for elements left to the
 * scalar code. */
typedef struct {
    double alpha[HERTZ_BLOCK], rs[HERTZ_BLOCK], rse[HERTZ_BLOCK], ce[HERTZ_BLOCK];
    double pabs[HERTZ_BLOCK], esm[HERTZ_BLOCK], ese[HERTZ_BLOCK], rx[HERTZ_BLOCK];
    double ry[HERTZ_BLOCK], other[HERTZ_BLOCK];
} stage1;

/* Stage 1, the common case: finite radii within 2^+-RADIUS_RANGE (or inf),
 * moduli within [2^-900, 2^1000], |angle| <= FAST_ANGLE, a valid contact.
 * The same formulas as curvatures() and reduced_modulus(); `other` flags the
 * rest.  Four divisions an element: rs, alpha, rho_y = det/rho_x, E*.
 * aligned = 1 for a block whose angles are all zero: the principal planes
 * coincide, rho_x and rho_y are the pair sums (no sine, no square root, no
 * det/rho_x), with the bits the general code gives at angle 0.
 * common = 1 for a block of finite radii and angles of modulus at least
 * COMMON_ANGLE: no infinite radius to stand in for, and sin^2 psi is never 0
 * there (psi = k pi/2 + r with r = psi for k = 0, |r| > 2^-70 for any double
 * psi at k != 0), so that the aligned case inside the general formulas cannot
 * arise; the same bits with fewer operations. */
#define COMMON_ANGLE 0x1p-500

HERTZ_INLINE double
fast_geometry_common(ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY], stage1 *restrict s,
                     const int aligned, const int common)
{
    const double *restrict R1X = in[HERTZ_R1X], *restrict R1Y = in[HERTZ_R1Y];
    const double *restrict R2X = in[HERTZ_R2X], *restrict R2Y = in[HERTZ_R2Y];
    const double *restrict ANGLE = in[HERTZ_ANGLE];
    const double lo = 0x1p-240, hi = 0x1p240;
#if RADIUS_RANGE != 240
#error "lo and hi are 2^-+RADIUS_RANGE"
#endif
    /* the block in four loops: which elements are in the common case and the
     * sines of their angles; the curvature products; the eigenvalues; their
     * ratio (short loops: the processor overlaps their iterations, where one
     * long body leaves the latency of its chains exposed on narrow vectors) */
    double ssa[HERTZ_BLOCK], cca[HERTZ_BLOCK], oka[HERTZ_BLOCK], sxa[HERTZ_BLOCK];
    double sya[HERTZ_BLOCK], g1a[HERTZ_BLOCK], g2a[HERTZ_BLOCK], cxa[HERTZ_BLOCK];
    double cya[HERTZ_BLOCK];
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        double angle = ANGLE[i];
        if (!aligned) { /* first: the long chain, the tests beside it */
            sin2_cos2(fabs(angle) <= FAST_ANGLE ? angle : 0.0, &ssa[i], &cca[i]);
        }
        double a1x = fabs(R1X[i]), a1y = fabs(R1Y[i]), a2x = fabs(R2X[i]), a2y = fabs(R2Y[i]);
        /* ok = 0 where the element leaves the common case (NaN included): the
         * tests are ANDed as truth values (compares and ANDs of masks on vectors,
         * where a chain of selects would cost three operations a test) */
        int ok;
        if (common) {
            ok = (a1x >= lo) & (a1x <= hi) & (a1y >= lo) & (a1y <= hi) & (a2x >= lo)
                 & (a2x <= hi) & (a2y >= lo) & (a2y <= hi) & (fabs(angle) <= FAST_ANGLE);
        }
        else {
            ok = (a1x >= lo) & ((a1x <= hi) | (a1x == INFINITY)) & (a1y >= lo)
                 & ((a1y <= hi) | (a1y == INFINITY)) & (a2x >= lo)
                 & ((a2x <= hi) | (a2x == INFINITY)) & (a2y >= lo)
                 & ((a2y <= hi) | (a2y == INFINITY)) & (fabs(angle) <= FAST_ANGLE);
        }
        oka[i] = ok ? 1.0 : 0.0;
    }
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        double r1x = R1X[i], r1y = R1Y[i], r2x = R2X[i], r2y = R2Y[i];
        int ok = oka[i] != 0.0;
        /* where not ok, what is computed does not matter: geometry_stage does
         * the element again (every field it stores), before any later stage
         * reads it (no stand-ins: each select costs three operations in SSE2) */
        double sx, sy, g1, g2, cx, cy, pabs;
        curvature_products(r1x, r1y, r2x, r2y, &sx, &sy, &g1, &g2, &cx, &cy, &pabs, common);
        double rs = (sx + sy) / pabs;
        double big = fabs(sx) > fabs(sy) ? fabs(sx) : fabs(sy);
        if (!aligned) {
            big = fabs(g1) > big ? fabs(g1) : big;
            big = fabs(g2) > big ? fabs(g2) : big;
        }
        ok &= big > 0.0;
        double t;
        split_normal(big, &t); /* (any bits where not ok) */
        double f = pow2(-t);
        oka[i] = ok ? 1.0 : 0.0;
        sxa[i] = sx * f;
        sya[i] = sy * f;
        g1a[i] = g1 * f;
        g2a[i] = g2 * f;
        cxa[i] = cx * f;
        cya[i] = cy * f;
        s->rs[i] = rs;
        s->rse[i] = 0.0;
        s->ce[i] = t;
        s->pabs[i] = pabs;
    }
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        int ok = oka[i] != 0.0;
        double sx = sxa[i], sy = sya[i], rx, ry;
        if (aligned) {
            rx = sx > sy ? sx : sy;
            ry = sx > sy ? sy : sx;
        }
        else {
            double g1 = g1a[i], g2 = g2a[i], cx = cxa[i], cy = cya[i];
            double ss = ssa[i], cc = cca[i];
            double gg = g1 * g2, terms, trace = sx + sy;
            double det = curvature_determinant(sx, sy, cx, cy, gg, ss, cc, &terms); /* (1') */
            double dg = gg >= 0.0 ? cx - cy : sx - sy; /* g1 - g2 or g1 + g2 */
            double d = sqrt(dg * dg + 4.0 * fabs(gg) * (gg >= 0.0 ? cc : ss));  /* (2) */
            /* trace > 0 (else no point contact or a cancelling trace: flagged) */
            rx = 0.5 * (trace + d);
            ry = d <= 0.5 * trace ? 0.5 * (trace - d) : det / rx;
            ry = ry < rx ? ry : rx;
            /* (1') or the trace cancelling: the scalar code's double-double */
            int valid = (det >= DBL_MIN) & (trace > 0.0) & !cancels(sx, sy, trace, det, terms);
            if (!common) {
                rx = ss == 0.0 ? (sx > sy ? sx : sy) : rx; /* aligned principal planes */
                ry = ss == 0.0 ? (sx > sy ? sy : sx) : ry;
                valid |= ss == 0.0;
            }
            ok &= valid;
        }
        oka[i] = ok ? 1.0 : 0.0;
        s->rx[i] = rx;
        s->ry[i] = ry;
    }
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        double rx = s->rx[i], ry = s->ry[i];
        int ok = (oka[i] != 0.0) & (rx > 0.0) & (ry >= DBL_MIN) & (rx / ry <= DBL_MAX);
        s->other[i] = ok ? 0.0 : 1.0;
        s->alpha[i] = rx / ry; /* (a flagged element is done again) */
    }
    return any_flag(n, s->other);
}

/* E* of moduli within [2^-900, 2^1000]; *bad = 1 for others. */
HERTZ_INLINE double
fast_modulus(double e1, double nu1, double e2, double nu2, double *ee, double *bad)
{
    double b = 0.0;
    b = e1 >= 0x1p-900 ? (e1 <= 0x1p1000 ? b : 1.0) : 1.0;
    b = e2 >= 0x1p-900 ? (e2 <= 0x1p1000 ? b : 1.0) : 1.0;
    b = nu1 > -1.0 ? (nu1 <= 0.5 ? b : 1.0) : 1.0;
    b = nu2 > -1.0 ? (nu2 <= 0.5 ? b : 1.0) : 1.0;
    *bad = b;
    double elo, ehi, clo, chi;
    order_moduli(e1, nu1, e2, nu2, &elo, &ehi, &clo, &chi);
    return modulus_mantissa(elo, ehi, clo, chi, ee); /* garbage where b = 1, never used */
}

/* E* per element into s (flagging elements in `other`), computed once for a
 * block whose moduli are all equal.  Returns 1 if any was flagged. */
#define GEOMETRY_PARAMETERS ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY], stage1 *restrict s
#define GEOMETRY_NAMES n, in, s

HERTZ_INLINE double
fast_moduli_body(GEOMETRY_PARAMETERS, const int fused)
{
    (void)fused;
    const double *restrict E1 = in[HERTZ_E1], *restrict NU1 = in[HERTZ_NU1];
    const double *restrict E2 = in[HERTZ_E2], *restrict NU2 = in[HERTZ_NU2];
    double *restrict esm = s->esm, *restrict ese = s->ese, *restrict flag = s->other;
    double varied[HERTZ_BLOCK];
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        double v = E1[i] == E1[0] ? 0.0 : 1.0;
        v = NU1[i] == NU1[0] ? v : 1.0;
        v = E2[i] == E2[0] ? v : 1.0;
        varied[i] = NU2[i] == NU2[0] ? v : 1.0;
    }
    if (!any_flag(n, varied)) {
        double ee, bad, em = fast_modulus(E1[0], NU1[0], E2[0], NU2[0], &ee, &bad);
        for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
            esm[i] = em;
            ese[i] = ee;
            flag[i] = flag[i] > bad ? flag[i] : bad; /* both 0 or 1 */
        }
        return bad;
    }
    double bad[HERTZ_BLOCK];
    for (ptrdiff_t i = 0; i < n; ++i) {
        double ee;
        esm[i] = fast_modulus(E1[i], NU1[i], E2[i], NU2[i], &ee, &bad[i]);
        ese[i] = ee;
        flag[i] = flag[i] > bad[i] ? flag[i] : bad[i];
    }
    return any_flag(n, bad);
}
HERTZ_VERSIONS(double, fast_moduli, GEOMETRY_PARAMETERS, GEOMETRY_NAMES)

HERTZ_INLINE double
fast_geometry_body(GEOMETRY_PARAMETERS, const int fused)
{
    (void)fused;
    return fast_geometry_common(n, in, s, 0, 0);
}
HERTZ_VERSIONS(double, fast_geometry, GEOMETRY_PARAMETERS, GEOMETRY_NAMES)

HERTZ_INLINE double
fast_geometry_finite_body(GEOMETRY_PARAMETERS, const int fused)
{
    (void)fused;
    return fast_geometry_common(n, in, s, 0, 1);
}
HERTZ_VERSIONS(double, fast_geometry_finite, GEOMETRY_PARAMETERS, GEOMETRY_NAMES)

HERTZ_INLINE double
fast_geometry_aligned_body(GEOMETRY_PARAMETERS, const int fused)
{
    (void)fused;
    return fast_geometry_common(n, in, s, 1, 0);
}
HERTZ_VERSIONS(double, fast_geometry_aligned, GEOMETRY_PARAMETERS, GEOMETRY_NAMES)

/* Which variant of the block code: 1 if an angle is not 0 (else aligned), |
 * 2 if a radius is infinite or an angle below COMMON_ANGLE in modulus (else
 * common, where an angle is not 0). */
#define KIND_PARAMETERS ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY]
#define KIND_NAMES n, in

HERTZ_INLINE int
geometry_kind_body(KIND_PARAMETERS, const int fused)
{
    (void)fused;
    double turned[HERTZ_BLOCK], special[HERTZ_BLOCK];
    const double *restrict R1X = in[HERTZ_R1X], *restrict R1Y = in[HERTZ_R1Y];
    const double *restrict R2X = in[HERTZ_R2X], *restrict R2Y = in[HERTZ_R2Y];
    const double *restrict ANGLE = in[HERTZ_ANGLE];
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        double angle = fabs(ANGLE[i]);
        int odd = (fabs(R1X[i]) == INFINITY) | (fabs(R1Y[i]) == INFINITY)
                  | (fabs(R2X[i]) == INFINITY) | (fabs(R2Y[i]) == INFINITY)
                  | !(angle >= COMMON_ANGLE);
        turned[i] = angle == 0.0 ? 0.0 : 1.0;
        special[i] = odd ? 1.0 : 0.0;
    }
    return any_flag(n, turned) | (any_flag(n, special) << 1);
}
HERTZ_VERSIONS(int, geometry_kind, KIND_PARAMETERS, KIND_NAMES)

/* Stage 1 for a block, with the scalar code for the flagged elements (and
 * for the major-axis angle when asked).  HERTZ_OK, or an error code with
 * *bad the element and its curvatures in *rho_x, *rho_y. */
static int
geometry_stage(ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY], stage1 *s,
               double *theta, ptrdiff_t *bad, hertz_scaled *rho_x, hertz_scaled *rho_y)
{
    int kind = HERTZ_PICK(geometry_kind)(n, in);
    double any;
    if (!(kind & 1)) {
        any = HERTZ_PICK(fast_geometry_aligned)(n, in, s);
    }
    else if (!(kind & 2)) {
        any = HERTZ_PICK(fast_geometry_finite)(n, in, s);
    }
    else {
        any = HERTZ_PICK(fast_geometry)(n, in, s);
    }
    any += HERTZ_PICK(fast_moduli)(n, in, s);
    if (any == 0.0 && !theta) {
        return HERTZ_OK;
    }
    for (ptrdiff_t i = 0; i < n; ++i) {
        if (theta) {
            theta[i] = 0.0;
        }
        if (s->other[i] == 0.0 && !theta) {
            continue;
        }
        double r[4] = {in[HERTZ_R1X][i], in[HERTZ_R1Y][i], in[HERTZ_R2X][i], in[HERTZ_R2Y][i]};
        if (s->other[i] == 0.0) { /* only the major-axis angle */
            theta[i] = block_axis_angle(r, in[HERTZ_ANGLE][i]);
            continue;
        }
        double rx = 0.0, ry = 0.0, rs = 1.0, rse = 0.0, e = 0.0, th = 0.0;
        hertz_scaled named[2] = {{0.0, 0.0}, {0.0, 0.0}};
        int code = curvatures(r, in[HERTZ_ANGLE][i], &rx, &ry, &rs, &rse, &e, &th,
                              theta != NULL, named);
        if (theta) {
            theta[i] = th;
        }
        hertz_scaled es = {1.0, 0.0};
        if (code == HERTZ_OK) {
            code = reduced_modulus(in[HERTZ_E1][i], in[HERTZ_NU1][i], in[HERTZ_E2][i],
                                   in[HERTZ_NU2][i], &es);
        }
        s->rx[i] = rx;
        s->ry[i] = ry;
        s->ce[i] = e;
        s->pabs[i] = 1.0;
        if (code != HERTZ_OK) {
            *bad = i;
            *rho_x = named[0];
            *rho_y = named[1];
            return code;
        }
        s->alpha[i] = rx / ry;
        s->rs[i] = rs;
        s->rse[i] = rse;
        s->esm[i] = es.m;
        s->ese[i] = es.e;
    }
    return HERTZ_OK;
}

/* Coefficients per element (stage 3): c = {lam, cb.m, cb.e, cd.m, cd.e,
 * cp.m, cp.e, cs.m, cs.e}, each an array of n. */
#define COEFFICIENTS_PARAMETERS                                                          \
    ptrdiff_t n, const double *restrict rs, const double *restrict rse,                  \
        const double *restrict es_m, const double *restrict es_e, const double *restrict lam, \
        const double *restrict K, const double *restrict E, double *restrict cl,         \
        double *restrict cbm, double *restrict cbe, double *restrict cdm,                \
        double *restrict cde, double *restrict cpm, double *restrict cpe,                \
        double *restrict csm, double *restrict cse
#define COEFFICIENTS_NAMES n, rs, rse, es_m, es_e, lam, K, E, cl, cbm, cbe, cdm, cde, cpm, cpe, \
                           csm, cse

HERTZ_INLINE int
coefficients_loop_body(COEFFICIENTS_PARAMETERS, const int fused)
{
    (void)fused;
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        double er, rho_m = split_normal(rs[i], &er);
        er += rse[i];
        double half_e = 0.5 / E[i], esm = es_m[i], ese = es_e[i];
        cl[i] = lam[i];
        cbm[i] = 3.0 * E[i] / (PI * lam[i] * esm * rho_m);
        cbe[i] = -(ese + er);
        cdm[i] = K[i] * rho_m * half_e;
        cde[i] = er;
        cpm[i] = esm * rho_m * half_e;
        cpe[i] = ese + er;
        csm[i] = PI * lam[i] * esm / K[i];
        cse[i] = ese;
    }
    return 0;
}
HERTZ_VERSIONS(int, coefficients_loop, COEFFICIENTS_PARAMETERS, COEFFICIENTS_NAMES)

static void
coefficients_stage(ptrdiff_t n, const stage1 *s, const double *lam, const double *K,
                   const double *E, double *const c[HERTZ_NCOEFFICIENTS])
{
    HERTZ_PICK(coefficients_loop)(n, s->rs, s->rse, s->esm, s->ese, lam, K, E, c[0], c[1], c[2],
                                  c[3], c[4], c[5], c[6], c[7], c[8]);
}

/* Stage 4: the load-dependent outputs from the value v = vm 2^ve (vm in
 * [1, 2)); out = {a, b, load, p0, delta, stiffness}.  One body per mode,
 * instantiated three times (HERTZ_INLINE, constant flags):
 *
 *   fast (fast = 1): an output x 2^e is x * 2^e, exact while |e| <= 1000,
 *     and the body returns 1 if any element of the block needs more;
 *   exact (fast = 0): every output rounded once into any range (scale2);
 *   fused = 1 only where the processor has a fused multiply-add.
 *
 * The three give the same bits wherever the fast one is used. */
#define GIVEN_PARAMETERS                                                                \
    ptrdiff_t n, const double *restrict cl, const double *restrict cbm,                 \
        const double *restrict cbe, const double *restrict cdm, const double *restrict cde, \
        const double *restrict cpm, const double *restrict cpe, const double *restrict csm, \
        const double *restrict cse, const double *restrict vm, const double *restrict ve,   \
        const double *restrict v, double *restrict oa, double *restrict ob,                 \
        double *restrict oload, double *restrict op0, double *restrict odelta,             \
        double *restrict ostiff
#define GIVEN_NAMES n, cl, cbm, cbe, cdm, cde, cpm, cpe, csm, cse, vm, ve, v, oa, ob, oload, \
                    op0, odelta, ostiff

/* x 2^e; in the fast variant, *wide becomes the largest |e| placed (the
 * caller flags the element where that is beyond 1000: its block is then done
 * again by the exact variant, so the value placed there does not matter). */
HERTZ_INLINE double
place(double x, double e, double *wide, const int fast)
{
    if (!fast) {
        return scale2(x, e);
    }
    *wide = fabs(e) > *wide ? fabs(e) : *wide;
    return x * pow2(e);
}

/* The given value as vm 2^ve: split here in the fast variants (every value of
 * the block is then a normal double), read from the arrays in the exact ones. */
HERTZ_INLINE double
value_of(const double *restrict vm, const double *restrict ve, const double *restrict v,
         ptrdiff_t i, double *e, const int fast)
{
    if (fast) {
        return split_normal(v[i], e);
    }
    *e = ve[i];
    return vm[i];
}

HERTZ_INLINE double
given_load_body(GIVEN_PARAMETERS, const int fused, const int fast)
{
    /* three loops: the seed of the cube root, its double-double Newton step,
     * the outputs (short loops: the processor overlaps their iterations, where
     * one long body leaves its chain's latency exposed on narrow vectors) */
    double wide[HERTZ_BLOCK], bhs[HERTZ_BLOCK], bls[HERTZ_BLOCK], qs[HERTZ_BLOCK];
    double shs[HERTZ_BLOCK], xhs[HERTZ_BLOCK], xls[HERTZ_BLOCK];
    double rs[HERTZ_BLOCK];
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        /* b^3 = cb P = (xh + xl) 2^(3q) */
        double vme, vmi = value_of(vm, ve, v, i, &vme, fast);
        double xl, xh = two_prod(cbm[i], vmi, &xl, fused);
        double xe, xm = split_normal(xh, &xe);
        xl *= pow2(-xe); /* xm / xh, exactly */
        double e = cbe[i] + vme + xe;
        double q = (e * (1.0 / 3.0) + ROUND) - ROUND, j = e - 3.0 * q;
        double below = j < 0.0 ? 1.0 : 0.0; /* (one AND of the mask: cheaper than selects) */
        q -= below;
        j += 3.0 * below; /* e = 3q + j, j in {0, 1, 2} */
        double f = pow2(j);
        xhs[i] = xm * f;
        xls[i] = xl * f;
        qs[i] = q;
        rs[i] = inverse_cube_root(xm, j);
    }
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        /* b = bh + bl: bh = x r^2 (r = x^(-1/3)) rounded to 26 bits, so that
         * bh^2 is exact and the products c bh of the outputs take half of
         * Dekker's operations (eps = b/bh - 1 <= 2^-26 with r's 3e-9); then
         * one Newton step in double-double, bl0 = (x - bh^3) / (3 bh^2) (x -
         * bh^3 exact but for its last rounding), overshoots by bh (eps^2 +
         * eps^3/3), and bl = bl0 - bl0^2 r takes eps^2 back: b to (5/3) eps^3,
         * about 2^-77 */
        double xh = xhs[i], xl = xls[i], r = rs[i], r2 = r * r;
        double bh, unused;
        veltkamp(xh * r2, &bh, &unused); /* 26 bits: bh^2 exact, bh c in two parts */
        double sh = bh * bh, cl3, ch = two_prod_26(sh, bh, &cl3, fused);
        double bl = (((xh - ch) - cl3) + xl) / (3.0 * sh);
        bhs[i] = bh;
        bls[i] = bl - bl * (bl * r); /* the Newton step's error, bh eps^2 */
        shs[i] = sh;
    }
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        double w = 0.0, bh = bhs[i], bl = bls[i], q = qs[i];
        /* b^2 = bh^2 + (2 bh bl + bl^2) (bl is up to 2^-26 of b: its square counts) */
        double b2e = (bh * bl + bl * bh) + bl * bl, b2h = shs[i] + b2e;
        double b2l = b2e - (b2h - shs[i]);
        oa[i] = place(dd_scale_26(cl[i], bh, bl, fused), q, &w, fast);
        ob[i] = place(bh + bl, q, &w, fast);
        oload[i] = v[i];
        op0[i] = place(dd_scale_26(cpm[i], bh, bl, fused), cpe[i] + q, &w, fast);
        odelta[i] = place(dd_scale(cdm[i], b2h, b2l, fused), cde[i] + 2.0 * q, &w, fast);
        ostiff[i] = place(dd_scale_26(csm[i], bh, bl, fused), cse[i] + q, &w, fast);
        wide[i] = w <= 1000.0 ? 0.0 : 1.0;
    }
    return fast && any_flag(n, wide) ? 1.0 : 0.0;
}

HERTZ_INLINE double
given_approach_body(GIVEN_PARAMETERS, const int fused, const int fast)
{
    double wide[HERTZ_BLOCK];
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        double w = 0.0;
        /* b^2 = t = delta / cd = (th + tl) 2^(2q); P = t b / cb */
        double vme, vmi = value_of(vm, ve, v, i, &vme, fast);
        double th = vmi / cdm[i], pe, pp = two_prod(th, cdm[i], &pe, fused);
        double tl = ((vmi - pp) - pe) / cdm[i];
        double e = vme - cde[i];
        double q = (e * 0.5 + ROUND) - ROUND, j = e - 2.0 * q;
        double below = j < 0.0 ? 1.0 : 0.0;
        q -= below;
        j += 2.0 * below; /* e = 2q + j, j in {0, 1} */
        double f = pow2(j);
        th *= f;
        tl *= f;
        double bh = sqrt(th);
        double sl, sh = two_prod(bh, bh, &sl, fused);
        double bl = ((th - sh) - sl + tl) / (2.0 * bh);
        double ll, lh = dd_mul(th, tl, bh, bl, &ll, fused);
        oa[i] = place(dd_scale(cl[i], bh, bl, fused), q, &w, fast);
        ob[i] = place(bh + bl, q, &w, fast);
        oload[i] = place(dd_div(lh, ll, cbm[i], fused), 3.0 * q - cbe[i], &w, fast);
        op0[i] = place(dd_scale(cpm[i], bh, bl, fused), cpe[i] + q, &w, fast);
        odelta[i] = v[i];
        ostiff[i] = place(dd_scale(csm[i], bh, bl, fused), cse[i] + q, &w, fast);
        wide[i] = w <= 1000.0 ? 0.0 : 1.0;
    }
    return fast && any_flag(n, wide) ? 1.0 : 0.0;
}

HERTZ_INLINE double
given_p0_body(GIVEN_PARAMETERS, const int fused, const int fast)
{
    double wide[HERTZ_BLOCK];
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        double w = 0.0;
        /* b = p0 / cp; P = b^3 / cb */
        double vme, vmi = value_of(vm, ve, v, i, &vme, fast);
        double bh = vmi / cpm[i], pe, pp = two_prod(bh, cpm[i], &pe, fused);
        double bl = ((vmi - pp) - pe) / cpm[i];
        double q = vme - cpe[i];
        double b2l, b2h = dd_mul(bh, bl, bh, bl, &b2l, fused);
        double ll, lh = dd_mul(b2h, b2l, bh, bl, &ll, fused);
        oa[i] = place(dd_scale(cl[i], bh, bl, fused), q, &w, fast);
        ob[i] = place(bh + bl, q, &w, fast);
        oload[i] = place(dd_div(lh, ll, cbm[i], fused), 3.0 * q - cbe[i], &w, fast);
        op0[i] = v[i];
        odelta[i] = place(dd_scale(cdm[i], b2h, b2l, fused), cde[i] + 2.0 * q, &w, fast);
        ostiff[i] = place(dd_scale(csm[i], bh, bl, fused), cse[i] + q, &w, fast);
        wide[i] = w <= 1000.0 ? 0.0 : 1.0;
    }
    return fast && any_flag(n, wide) ? 1.0 : 0.0;
}

/* MODE_fast in every version of the build (fused in the SIMD versions, which
 * have FMA), MODE_exact plain. */
#define GIVEN_VARIANTS(MODE)                                                            \
    HERTZ_INLINE double MODE##_fast_body(GIVEN_PARAMETERS, const int fused)             \
    {                                                                                   \
        return MODE##_body(GIVEN_NAMES, fused, 1);                                      \
    }                                                                                   \
    HERTZ_VERSIONS(double, MODE##_fast, GIVEN_PARAMETERS, GIVEN_NAMES)                  \
    static double MODE##_exact(GIVEN_PARAMETERS)                                        \
    {                                                                                   \
        return MODE##_body(GIVEN_NAMES, 0, 0);                                          \
    }
GIVEN_VARIANTS(given_load)
GIVEN_VARIANTS(given_approach)
GIVEN_VARIANTS(given_p0)

/* ---------------------------------------------------------- entry points */

int
hertz_given_block(ptrdiff_t n, int mode, const double *const c[HERTZ_NCOEFFICIENTS],
                  const double *value, double *const out[HERTZ_NGIVEN], ptrdiff_t *bad)
{
    double vm[HERTZ_BLOCK], ve[HERTZ_BLOCK];
    double flags[HERTZ_BLOCK]; /* 1 for a value zero, subnormal, infinite or NaN */
    for (ptrdiff_t i = 0; i < n; ++i) {
        double v = value[i];
        flags[i] = v >= DBL_MIN ? (v <= DBL_MAX ? 0.0 : 1.0) : 1.0;
    }
    int odd = any_flag(n, flags);
    if (odd != 0) {
        for (ptrdiff_t i = 0; i < n; ++i) {
            if (!(value[i] >= 0.0 && value[i] <= DBL_MAX)) {
                *bad = i;
                return HERTZ_BAD_VALUE;
            }
        }
    }
#define GIVEN_ARGUMENTS n, c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8], vm, ve, value, \
                        out[0], out[1], out[2], out[3], out[4], out[5]
    /* The fast variant splits the values itself; the exact one, for a block
     * with an odd value or an output beyond 2^+-1000, reads them split here. */
    int exact = odd != 0;
    if (!exact) {
        double wide;
        if (mode == HERTZ_GIVEN_LOAD) {
            wide = HERTZ_PICK(given_load_fast)(GIVEN_ARGUMENTS);
        }
        else if (mode == HERTZ_GIVEN_APPROACH) {
            wide = HERTZ_PICK(given_approach_fast)(GIVEN_ARGUMENTS);
        }
        else {
            wide = HERTZ_PICK(given_p0_fast)(GIVEN_ARGUMENTS);
        }
        exact = wide != 0.0;
    }
    if (exact) {
        for (ptrdiff_t i = 0; i < n; ++i) {
            hertz_scaled sv = split(value[i] > 0.0 ? value[i] : 1.0); /* zero is set below */
            vm[i] = sv.m;
            ve[i] = sv.e;
        }
        if (mode == HERTZ_GIVEN_LOAD) {
            given_load_exact(GIVEN_ARGUMENTS);
        }
        else if (mode == HERTZ_GIVEN_APPROACH) {
            given_approach_exact(GIVEN_ARGUMENTS);
        }
        else {
            given_p0_exact(GIVEN_ARGUMENTS);
        }
    }
#undef GIVEN_ARGUMENTS
    if (odd != 0) {
        for (ptrdiff_t i = 0; i < n; ++i) {
            if (value[i] == 0.0) {
                for (int k = 0; k < HERTZ_NGIVEN; ++k) {
                    out[k][i] = 0.0;
                }
            }
        }
    }
    return HERTZ_OK;
}

/* Stages 1-3 into the coefficient arrays c and, when g is given, the
 * geometry fields. */
static int
geometry_and_coefficients(ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY],
                          double *const c[HERTZ_NCOEFFICIENTS], double *const g,
                          int with_theta, ptrdiff_t *bad, hertz_scaled *rho_x,
                          hertz_scaled *rho_y)
{
    stage1 s;
    double lam[HERTZ_BLOCK], m[HERTZ_BLOCK], K[HERTZ_BLOCK], E[HERTZ_BLOCK];
    double theta[HERTZ_BLOCK];
    int code = geometry_stage(n, in, &s, with_theta ? theta : NULL, bad, rho_x, rho_y);
    if (code != HERTZ_OK) {
        return code;
    }
    hertz_ellipse_table(s.alpha, n, lam, K, E);
    coefficients_stage(n, &s, lam, K, E, c);
    if (g) {
        /* m from the solver, which keeps its relative accuracy as alpha -> 1
         * (1 - 1/lambda^2 would not); the rest as the outputs were made. */
        double lam_solver[HERTZ_BLOCK];
        hertz_ellipse_block(s.alpha, n, 1, lam_solver, m, NULL, NULL);
        /* g[k * n + i]: lambda, alpha, m, K, E, e_star, rho_x, rho_y, theta */
        for (ptrdiff_t i = 0; i < n; ++i) {
            double row[HERTZ_NFIELDS] = {lam[i], s.alpha[i], m[i], K[i], E[i],
                                         scale2(s.esm[i], s.ese[i]),
                                         scale2(s.rx[i], s.ce[i]) / s.pabs[i],
                                         scale2(s.ry[i], s.ce[i]) / s.pabs[i],
                                         /* 0 for every circle */
                                         with_theta && s.alpha[i] != 1.0 ? theta[i] : 0.0};
            for (int k = 0; k < HERTZ_NFIELDS; ++k) {
                g[k * n + i] = row[k];
            }
        }
    }
    return HERTZ_OK;
}

int
hertz_geometry_block(ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY],
                     double *const c[HERTZ_NCOEFFICIENTS], double *fields, ptrdiff_t *bad,
                     hertz_scaled *rho_x, hertz_scaled *rho_y)
{
    return geometry_and_coefficients(n, in, c, fields, fields != NULL, bad, rho_x, rho_y);
}

int
hertz_contact_block(ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY + 1], int mode,
                    double *const out[HERTZ_NGIVEN], ptrdiff_t *bad, hertz_scaled *rho_x,
                    hertz_scaled *rho_y)
{
    double cbuf[HERTZ_NCOEFFICIENTS][HERTZ_BLOCK];
    double *c[HERTZ_NCOEFFICIENTS];
    for (int k = 0; k < HERTZ_NCOEFFICIENTS; ++k) {
        c[k] = cbuf[k];
    }
    int code = geometry_and_coefficients(n, in, c, NULL, 0, bad, rho_x, rho_y);
    if (code != HERTZ_OK) {
        return code;
    }
    return hertz_given_block(n, mode, (const double *const *)c, in[HERTZ_NGEOMETRY], out, bad);
}

/* Line contact (Johnson sec. 4.3): half_width^2 = 4 P' / (pi E* rho),
 * p0^2 = P' E* rho / pi. */
int
hertz_line_contact(const double in[8], double load, double out[5], hertz_scaled *rho_x,
                   hertz_scaled *rho_y)
{
    double rx = 0.0, ry = 0.0, rs, rse, theta, e = 0.0;
    hertz_scaled named[2] = {{0.0, 0.0}, {0.0, 0.0}};
    int code = curvatures(in, 0.0, &rx, &ry, &rs, &rse, &e, &theta, 0, named);
    *rho_x = named[0];
    *rho_y = named[1];
    if (code == HERTZ_LINE) {
        code = HERTZ_OK;
    }
    else if (code == HERTZ_OK || code == HERTZ_FLAT || code == HERTZ_CONFORM
             || code == HERTZ_LIMIT) {
        code = HERTZ_NOT_LINE;
    }
    hertz_scaled es = {1.0, 0.0};
    if (code == HERTZ_OK) {
        code = reduced_modulus(in[4], in[5], in[6], in[7], &es);
    }
    if (code != HERTZ_OK) {
        return code;
    }
    if (!(load >= 0.0 && load <= DBL_MAX)) {
        return HERTZ_BAD_VALUE;
    }
    hertz_scaled rho = split(rx); /* rx in [1, 2) */
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
    double we = p.e - es.e - rho.e, pe = p.e + es.e + rho.e;
    double wq = floor(we * 0.5), pq = floor(pe * 0.5);
    out[0] = scale2(sqrt(wm * (we - 2.0 * wq >= 1.0 ? 2.0 : 1.0)), wq);
    out[1] = scale2(sqrt(pm * (pe - 2.0 * pq >= 1.0 ? 2.0 : 1.0)), pq);
    return HERTZ_OK;
}
