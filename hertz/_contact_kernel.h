/*
 * Hertz point and line contact per element (hertz/_contact_kernel.c): from
 * the radii, the angle and the moduli to a, b, p0, delta and stiffness.
 * Pure C; the numpy binding is hertz/_ufuncs.c.
 */
#ifndef HERTZ_CONTACT_KERNEL_H
#define HERTZ_CONTACT_KERNEL_H

#include <stddef.h>

#include "_kernel.h"

/* m * 2^e (e an integer held in a double), so that products and quotients of
 * extreme magnitudes never overflow or underflow before the final result. */
typedef struct {
    double m, e;
} hertz_scaled;

/* Geometry inputs, in this order. */
enum {
    HERTZ_R1X, HERTZ_R1Y, HERTZ_R2X, HERTZ_R2Y, HERTZ_ANGLE,
    HERTZ_E1, HERTZ_NU1, HERTZ_E2, HERTZ_NU2, HERTZ_NGEOMETRY
};

/* What the tenth input is. */
enum { HERTZ_GIVEN_LOAD, HERTZ_GIVEN_APPROACH, HERTZ_GIVEN_P0, HERTZ_NMODES };

/* Error codes.  1 + k (k < HERTZ_NGEOMETRY) names geometry input k. */
enum {
    HERTZ_OK = 0,
    HERTZ_BAD_VALUE = 1 + HERTZ_NGEOMETRY, /* load, approach or p0 not finite or < 0 */
    HERTZ_LINE,                           /* rho_x > 0, rho_y = 0 */
    HERTZ_FLAT,                           /* rho_x = rho_y = 0 */
    HERTZ_CONFORM,                        /* a principal relative curvature < 0 */
    HERTZ_LIMIT,                          /* rho_x / rho_y beyond the double range */
    HERTZ_NOT_LINE                        /* line_contact of bodies without a line contact */
};


/* Point-contact outputs, in this order: the load-dependent ones
 * (HERTZ_NGIVEN of them), then those of the geometry alone (HERTZ_NFIELDS). */
enum {
    HERTZ_OUT_A, HERTZ_OUT_B, HERTZ_OUT_LOAD, HERTZ_OUT_P0, HERTZ_OUT_DELTA,
    HERTZ_OUT_STIFFNESS, HERTZ_NGIVEN,
    HERTZ_OUT_LAMBDA = HERTZ_NGIVEN, HERTZ_OUT_ALPHA, HERTZ_OUT_M, HERTZ_OUT_K, HERTZ_OUT_E,
    HERTZ_OUT_ESTAR, HERTZ_OUT_RHOX, HERTZ_OUT_RHOY, HERTZ_OUT_THETA, HERTZ_NOUT
};
#define HERTZ_NFIELDS (HERTZ_NOUT - HERTZ_NGIVEN)

/* What the load-dependent outputs need of a geometry, with b the semi-minor
 * axis: lambda = a/b and b^3 = cb P, delta = cd b^2, p0 = cp b,
 * stiffness = cs b, each coefficient as (m, e) with value m 2^e:
 * c = {lambda, cb.m, cb.e, cd.m, cd.e, cp.m, cp.e, cs.m, cs.e}. */
#define HERTZ_NCOEFFICIENTS 9

/* n <= HERTZ_BLOCK elements, in[k][i] geometry input k of element i: the
 * coefficients into the arrays c[k] and, unless fields is NULL, the nine
 * geometry fields (lambda, alpha, m, K, E, e_star, rho_x, rho_y, theta) into
 * fields[k * n + i].  HERTZ_OK, or an error code with *bad the first bad
 * element and its relative curvatures in *rho_x, *rho_y (scaled: they may lie
 * beyond the double range). */
int hertz_geometry_block(ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY],
                         double *const c[HERTZ_NCOEFFICIENTS], double *fields, ptrdiff_t *bad,
                         hertz_scaled *rho_x, hertz_scaled *rho_y);

/* The load-dependent outputs {a, b, load, p0, delta, stiffness} of n <=
 * HERTZ_BLOCK elements from their coefficients and the given values (load,
 * approach or p0 by mode).  HERTZ_OK or HERTZ_BAD_VALUE with *bad. */
int hertz_given_block(ptrdiff_t n, int mode, const double *const c[HERTZ_NCOEFFICIENTS],
                      const double *value, double *const out[HERTZ_NGIVEN], ptrdiff_t *bad);

/* Both: in[HERTZ_NGEOMETRY] holds the given values. */
int hertz_contact_block(ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY + 1], int mode,
                        double *const out[HERTZ_NGIVEN], ptrdiff_t *bad, hertz_scaled *rho_x,
                        hertz_scaled *rho_y);

/* Line contact (2-D, plane strain): in = {r1x, r1y, r2x, r2y, E1, nu1, E2,
 * nu2}, the line along y.  out = {half_width, p0, e_star, rho, load}.
 * HERTZ_OK or an error code (1 + k names input k in the point-contact
 * numbering, k != HERTZ_ANGLE). */
int hertz_line_contact(const double in[8], double load, double out[5], hertz_scaled *rho_x,
                       hertz_scaled *rho_y);

#endif
