/*
 * hertz/_tangential_kernel.c -- per contact, from the contact's own fields
 * (K(m), alpha = rho_x / rho_y, lambda = a / b, a, b, P) and the bodies'
 * moduli (nu1, nu2, E1, E2):
 *
 * - the no-slip tangential stiffness k along a force at angle t from the major
 *   axis (Mindlin 1949; the ellipse: Deresiewicz 1957), 1/k = c_x cos^2 t +
 *   c_y sin^2 t with
 *       pi a c_x = W K - Wn B,  pi a c_y = W K - Wn D,
 *       W = sum (1 + nu)/E,  Wn = sum nu (1 + nu)/E   (1/(2 pi G) = (1 + nu)/(pi E)),
 *   D = K / (1 + alpha / lambda^2) and B = K - D (Hertz's alpha = B/((1-m) D),
 *   no cancellation), so that
 *       pi a / k = W K - Wn (K/2 + (K/2 - D) cos 2t)
 *   and the transverse compliance is pi a c_t = Wn (K/2 - D) sin 2t;
 * - the Cattaneo-Mindlin partial slip under a force Q <= mu P rising from 0
 *   (Cattaneo 1938, Mindlin 1949): q = Q/(mu P), s = (1 - q)^(1/3); stick
 *   semi-axes s a, s b; slip area pi a b (1 - s^2); displacement along the
 *   force and across it (3 mu P / 2)(c_along, c_across)(1 - s^2); tangent
 *   stiffness s k; sliding where q = 1.  1 - s^2 = q (1 + s)/(1 + s + s^2)
 *   keeps full precision as q -> 0.
 *
 * The derivations and their checks against a Cerruti quadrature in mpmath are
 * in hertz/_tangential.py (module docstring) and tests/reference_tangential.py.
 * cos 2t, sin 2t and s are computed here, in code the compiler vectorises
 * (sin_cos: within 2 ulp, 85% correctly rounded; cube_root_unit: within 1 ulp,
 * 89% correctly rounded; measured against mpmath on 20000 arguments, where
 * glibc's cbrt was within 3 ulp; libm's cos and sin beyond |2t| = 1e5, of t beyond
 * |t| = 2^1022, where 2t overflows),
 * the rest in the order of operations of the numpy code this kernel replaced;
 * the build forbids contraction into fused multiply-adds (setup.py), so every
 * vector width gives the same bits.
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "_tangential_kernel.h"
#include "_fastmath.h"

#define PI 3.141592653589793
#define FAST_ANGLE 1e5   /* |2t| up to which sin_cos reduces exactly */

/* sin x and cos x for |x| <= FAST_ANGLE: x = k pi/2 + r, pi/2 in three parts
 * (Cody-Waite; the first two of 33 significant bits, so k P1 and k P2 are
 * exact for |k| < 2^20), |r| <= pi/4, the Taylor series of sin r to r^17 and
 * of cos r to r^18 (truncation below 1e-17 relative), then the quadrant. */
static inline void
sin_cos(double x, double *sin_x, double *cos_x)
{
    double k, r = reduce_half_pi(x, &k), z = r * r;
    double sr = sin_reduced(r, z);
    double cp = 1.0 / 6402373705728000.0; /* 1/18! */
    cp = -1.0 / 20922789888000.0 + z * cp; /* -1/16! */
    cp = 1.0 / 87178291200.0 + z * cp;     /* 1/14! */
    cp = -1.0 / 479001600.0 + z * cp;      /* -1/12! */
    cp = 1.0 / 3628800.0 + z * cp;         /* 1/10! */
    cp = -1.0 / 40320.0 + z * cp;          /* -1/8! */
    cp = 1.0 / 720.0 + z * cp;             /* 1/6! */
    cp = -1.0 / 24.0 + z * cp;             /* -1/4! */
    cp = 0.5 + z * cp;                     /* 1/2! */
    double cr = 1.0 - z * cp;
    double n = k - 4.0 * ((k * 0.25 + ROUND) - ROUND); /* quadrant, -2 <= n <= 2 */
    *sin_x = n == 0.0 ? sr : (n == 1.0 ? cr : (n == -1.0 ? -cr : -sr));
    *cos_x = n == 0.0 ? cr : (n == 1.0 ? -sr : (n == -1.0 ? sr : -cr));
}

/* u^(1/3) for u = 0 or DBL_MIN <= u <= 1 (u = 1 - q): u = m 2^(3p + j) with
 * 1 <= m < 2, j in {0, 1, 2}; a degree-4 least-squares polynomial for m^(1/3)
 * (fitted at 64 Chebyshev nodes, error 1.2e-5) times 2^(j/3), two Newton steps
 * c <- c + (x - c^3)/(3 c^2) for x = m 2^j (error 1e-10, then rounding), and
 * the exact scaling by 2^p. */
static inline double
cube_root_unit(double u)
{
    const double C0 = 1.1447129219983214, C1 = 0.2542825412449245,
                 C2 = -0.05643544389415758, C3 = 0.022471745665671682,
                 C4 = -0.010274592492471802;
    double e, m = split_normal(u > 0.0 ? u : 1.0, &e);
    double p = (e * (1.0 / 3.0) + ROUND) - ROUND, j = e - 3.0 * p;
    p = j < 0.0 ? p - 1.0 : p;
    j = j < 0.0 ? j + 3.0 : j;
    double x = m * (j >= 2.0 ? 4.0 : (j >= 1.0 ? 2.0 : 1.0)), t = m - 1.5;
    double c = (C0 + t * (C1 + t * (C2 + t * (C3 + t * C4))))
               * (j >= 2.0 ? 1.5874010519681994 : (j >= 1.0 ? 1.2599210498948732 : 1.0));
    c = c + (x - c * c * c) / (3.0 * (c * c));
    c = c + (x - c * c * c) / (3.0 * (c * c));
    double scale = as_double(as_bits(p + (0x1p52 + 1023.0)) << 52); /* 2^p */
    return u > 0.0 ? c * scale : 0.0;
}

/* sin 2t and cos 2t from libm, for |2t| > FAST_ANGLE.  Beyond |t| = 2^1022
 * (8.99e307) 2t overflows: then from libm's sin t and cos t (reduced exactly
 * by libm) through the double-angle formulas, 2 sin t cos t and
 * (cos t - sin t)(cos t + sin t) (within a few ulp of 1). */
static inline void
libm_sin_cos_twice(double t, double *sin2, double *cos2)
{
    double twice = 2.0 * t;
    if (isfinite(twice)) {
        *sin2 = sin(twice);
        *cos2 = cos(twice);
    }
    else {
        double s = sin(t), c = cos(t);
        *sin2 = 2.0 * s * c;
        *cos2 = (c - s) * (c + s);
    }
}

/* pi a / k along the force and pi a c_across [1/Pa]. */
typedef struct {
    double along, across;
} unit_compliances;

static inline unit_compliances
unit_compliance(double K, double alpha, double lam, double nu1, double nu2, double e1,
                double e2, double cos2, double sin2)
{
    double w1 = (1.0 + nu1) / e1;
    double w2 = (1.0 + nu2) / e2;
    double w_sum = w1 + w2, wnu_sum = w1 * nu1 + w2 * nu2;
    double D = K / (1.0 + alpha / lam / lam);
    double half_k = 0.5 * K;
    double split = half_k - D; /* (B - D)/2 */
    unit_compliances c = {w_sum * K - wnu_sum * (half_k + split * cos2),
                          wnu_sum * split * sin2};
    return c;
}

int
hertz_tangential_stiffness_block(ptrdiff_t n, const double *const *in, double *out,
                                 ptrdiff_t *bad)
{
    /* inputs K, alpha, lambda, a, nu1, nu2, E1, E2, direction */
    for (ptrdiff_t i = 0; i < n; ++i) {
        double t = in[8][i];
        if (!isfinite(t)) {
            *bad = i;
            return HERTZ_T_BAD_DIRECTION;
        }
        double twice = 2.0 * t, sin2, cos2;
        if (fabs(twice) <= FAST_ANGLE) {
            sin_cos(twice, &sin2, &cos2);
        }
        else {
            libm_sin_cos_twice(t, &sin2, &cos2);
        }
        double along = unit_compliance(in[0][i], in[1][i], in[2][i], in[4][i], in[5][i],
                                       in[6][i], in[7][i], cos2, 0.0).along;
        out[i] = (PI * in[3][i]) / along;
    }
    return HERTZ_T_OK;
}

/* One chunk of m checked elements: restrict-qualified parameters, so that the
 * compiler vectorises the loop (`libm`: cos and sin from libm, for |2t| >
 * FAST_ANGLE). */
static inline void
slip_chunk_arrays(ptrdiff_t m, const double *restrict K, const double *restrict alpha,
                  const double *restrict lam, const double *restrict a,
                  const double *restrict b, const double *restrict load,
                  const double *restrict nu1, const double *restrict nu2,
                  const double *restrict e1, const double *restrict e2,
                  const double *restrict force, const double *restrict mu,
                  const double *restrict direction, double *restrict stick_a,
                  double *restrict stick_b, double *restrict slip_area,
                  double *restrict disp, double *restrict transverse,
                  double *restrict tangent, double *restrict no_slip,
                  double *restrict sliding, const int libm)
{
    for (ptrdiff_t i = 0; i < m; ++i) {
        double limit = mu[i] * load[i];
        double q = force[i] / limit;
        double sin2, cos2;
        if (libm) {
            libm_sin_cos_twice(direction[i], &sin2, &cos2);
        }
        else {
            sin_cos(2.0 * direction[i], &sin2, &cos2);
        }
        unit_compliances unit = unit_compliance(K[i], alpha[i], lam[i], nu1[i], nu2[i], e1[i],
                                                e2[i], cos2, sin2);
        double per_area = PI * a[i];
        double along = unit.along / per_area, across = unit.across / per_area;
        double s = cube_root_unit(1.0 - q);
        double virgin = q * (1.0 + s) / (1.0 + s + s * s); /* 1 - s^2 */
        double reach = 1.5 * limit;                         /* 3 mu P / 2 */
        double k = per_area / unit.along; /* as hertz_tangential_stiffness_block */
        stick_a[i] = a[i] * s;
        stick_b[i] = b[i] * s;
        slip_area[i] = PI * a[i] * b[i] * virgin;
        disp[i] = reach * along * virgin;
        transverse[i] = reach * across * virgin;
        tangent[i] = k * s;
        no_slip[i] = k;
        sliding[i] = q == 1.0 ? 1.0 : 0.0;
    }
}

static inline void
slip_chunk(ptrdiff_t m, const double *const *in, double *const *out, ptrdiff_t start,
           const int libm)
{
#define IN(k) (in[k] + start)
#define OUT(k) (out[k] + start)
    slip_chunk_arrays(m, IN(HERTZ_T_K), IN(HERTZ_T_ALPHA), IN(HERTZ_T_LAMBDA), IN(HERTZ_T_A),
                      IN(HERTZ_T_B), IN(HERTZ_T_LOAD), IN(HERTZ_T_NU1), IN(HERTZ_T_NU2),
                      IN(HERTZ_T_E1), IN(HERTZ_T_E2), IN(HERTZ_T_FORCE), IN(HERTZ_T_MU),
                      IN(HERTZ_T_DIRECTION), OUT(HERTZ_T_STICK_A), OUT(HERTZ_T_STICK_B),
                      OUT(HERTZ_T_SLIP_AREA), OUT(HERTZ_T_DISPLACEMENT),
                      OUT(HERTZ_T_TRANSVERSE), OUT(HERTZ_T_TANGENT), OUT(HERTZ_T_NO_SLIP),
                      OUT(HERTZ_T_SLIDING), libm);
#undef IN
#undef OUT
}

/* Chunks of this many elements: the checks first, then the vectorised loop,
 * then libm's cos and sin for the rare |2t| > FAST_ANGLE. */
#define CHUNK 64

int
hertz_partial_slip_block(ptrdiff_t n, const double *const *in, double *const *out,
                         ptrdiff_t *bad)
{
    for (ptrdiff_t start = 0; start < n; start += CHUNK) {
        ptrdiff_t m = n - start < CHUNK ? n - start : CHUNK;
        const double *mu = in[HERTZ_T_MU] + start, *t = in[HERTZ_T_DIRECTION] + start;
        const double *load = in[HERTZ_T_LOAD] + start, *force = in[HERTZ_T_FORCE] + start;
        int far = 0;
        for (ptrdiff_t i = 0; i < m; ++i) {
            int code = !(mu[i] > 0.0 && mu[i] < INFINITY) ? HERTZ_T_BAD_MU
                       : !isfinite(t[i])                   ? HERTZ_T_BAD_DIRECTION
                       : !(load[i] > 0.0)                  ? HERTZ_T_BAD_LOAD
                       : !(force[i] >= 0.0 && force[i] < INFINITY) ? HERTZ_T_BAD_FORCE
                       : !(force[i] <= mu[i] * load[i])    ? HERTZ_T_ABOVE_LIMIT
                                                           : HERTZ_T_OK;
            if (code != HERTZ_T_OK) {
                *bad = start + i;
                return code;
            }
            far |= !(fabs(2.0 * t[i]) <= FAST_ANGLE);
        }
        slip_chunk(m, in, out, start, 0);
        for (ptrdiff_t i = 0; far && i < m; ++i) {
            if (!(fabs(2.0 * t[i]) <= FAST_ANGLE)) {
                slip_chunk(1, in, out, start + i, 1);
            }
        }
    }
    return HERTZ_T_OK;
}
