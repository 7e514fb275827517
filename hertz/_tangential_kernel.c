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
 * Every expression is evaluated in the order the numpy code used before this
 * kernel (same operations, libm's cos, sin and cbrt), so the results are those
 * bits; the build forbids contraction into fused multiply-adds (setup.py).
 */
#include <math.h>

#include "_tangential_kernel.h"

#define PI 3.141592653589793

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
        double twice = 2.0 * t;
        double along = unit_compliance(in[0][i], in[1][i], in[2][i], in[4][i], in[5][i],
                                       in[6][i], in[7][i], cos(twice), 0.0).along;
        out[i] = (PI * in[3][i]) / along;
    }
    return HERTZ_T_OK;
}

/* The arithmetic of one chunk of m elements from `start` (q, cos 2t, sin 2t and s
 * computed): restrict-qualified parameters, so that the compiler vectorises it. */
static inline void
slip_chunk_arrays(ptrdiff_t m, const double *restrict K, const double *restrict alpha,
                  const double *restrict lam, const double *restrict a,
                  const double *restrict b, const double *restrict limit_mu,
                  const double *restrict load, const double *restrict nu1,
                  const double *restrict nu2, const double *restrict e1,
                  const double *restrict e2, const double *restrict ratio,
                  const double *restrict cos2, const double *restrict sin2,
                  const double *restrict cube, double *restrict stick_a,
                  double *restrict stick_b, double *restrict slip_area,
                  double *restrict disp, double *restrict transverse,
                  double *restrict tangent, double *restrict no_slip,
                  double *restrict sliding)
{
    for (ptrdiff_t i = 0; i < m; ++i) {
        unit_compliances unit = unit_compliance(K[i], alpha[i], lam[i], nu1[i], nu2[i], e1[i],
                                                e2[i], cos2[i], sin2[i]);
        double per_area = PI * a[i];
        double along = unit.along / per_area, across = unit.across / per_area;
        double q = ratio[i], s = cube[i];
        double virgin = q * (1.0 + s) / (1.0 + s + s * s); /* 1 - s^2 */
        double reach = 1.5 * (limit_mu[i] * load[i]);      /* 3 mu P / 2 */
        double k = 1.0 / along;
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
           const double *ratio, const double *cos2, const double *sin2, const double *cube)
{
#define IN(k) (in[k] + start)
#define OUT(k) (out[k] + start)
    slip_chunk_arrays(m, IN(HERTZ_T_K), IN(HERTZ_T_ALPHA), IN(HERTZ_T_LAMBDA), IN(HERTZ_T_A),
                      IN(HERTZ_T_B), IN(HERTZ_T_MU), IN(HERTZ_T_LOAD), IN(HERTZ_T_NU1),
                      IN(HERTZ_T_NU2), IN(HERTZ_T_E1), IN(HERTZ_T_E2), ratio, cos2, sin2, cube,
                      OUT(HERTZ_T_STICK_A), OUT(HERTZ_T_STICK_B), OUT(HERTZ_T_SLIP_AREA),
                      OUT(HERTZ_T_DISPLACEMENT), OUT(HERTZ_T_TRANSVERSE), OUT(HERTZ_T_TANGENT),
                      OUT(HERTZ_T_NO_SLIP), OUT(HERTZ_T_SLIDING));
#undef IN
#undef OUT
}

/* Chunks of this many elements: the calls to libm (cos, sin, cbrt) and the
 * checks first, then the arithmetic in a loop the compiler can vectorise. */
#define CHUNK 64

int
hertz_partial_slip_block(ptrdiff_t n, const double *const *in, double *const *out,
                         ptrdiff_t *bad)
{
    double cos2[CHUNK], sin2[CHUNK], cube[CHUNK], ratio[CHUNK];
    for (ptrdiff_t start = 0; start < n; start += CHUNK) {
        ptrdiff_t m = n - start < CHUNK ? n - start : CHUNK;
        const double *mu = in[HERTZ_T_MU] + start, *t = in[HERTZ_T_DIRECTION] + start;
        const double *load = in[HERTZ_T_LOAD] + start, *force = in[HERTZ_T_FORCE] + start;
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
            double q = force[i] / (mu[i] * load[i]);
            double twice = 2.0 * t[i];
            ratio[i] = q;
            double c = cos(twice), sn = sin(twice); /* one sincos call */
            cos2[i] = c;
            sin2[i] = sn;
            cube[i] = cbrt(1.0 - q);
        }
        slip_chunk(m, in, out, start, ratio, cos2, sin2, cube);
    }
    return HERTZ_T_OK;
}
