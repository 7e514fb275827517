/*
 * Hertz point and line contact per element (hertz/_contact_kernel.c): from
 * the radii, the angle and the moduli to a, b, p0, delta and stiffness.
 * Pure C; the numpy binding is hertz/_ufuncs.c.
 */
#ifndef HERTZ_CONTACT_KERNEL_H
#define HERTZ_CONTACT_KERNEL_H

#include <stddef.h>

#include "_kernel.h"

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

/* m * 2^e, so that products and quotients of extreme magnitudes never
 * overflow or underflow before the final result. */
typedef struct {
    double m;
    int e;
} hertz_scaled;

/* What depends on the geometry and the moduli only.  With b the semi-minor
 * axis: b^3 = cb P, delta = cd b^2, p0 = cp b, stiffness = cs b, a = lam b. */
typedef struct {
    double lam, alpha, m, K, E, e_star, rho_x, rho_y, theta;
    hertz_scaled cb, cd, cp, cs;
} hertz_geometry;

/* Point-contact outputs, in this order: the load-dependent ones
 * (HERTZ_NGIVEN of them), then those of the geometry alone. */
enum {
    HERTZ_OUT_A, HERTZ_OUT_B, HERTZ_OUT_LOAD, HERTZ_OUT_P0, HERTZ_OUT_DELTA,
    HERTZ_OUT_STIFFNESS, HERTZ_NGIVEN,
    HERTZ_OUT_LAMBDA = HERTZ_NGIVEN, HERTZ_OUT_ALPHA, HERTZ_OUT_M, HERTZ_OUT_K, HERTZ_OUT_E,
    HERTZ_OUT_ESTAR, HERTZ_OUT_RHOX, HERTZ_OUT_RHOY, HERTZ_OUT_THETA, HERTZ_NOUT
};

/* n <= HERTZ_BLOCK elements, in[k][i] geometry input k of element i.  Returns
 * HERTZ_OK, or an error code with *bad the first bad element (whose rho_x and
 * rho_y are then set where the error concerns them).  With with_theta = 0
 * the major-axis angle is not computed (left 0). */
int hertz_geometry_block(ptrdiff_t n, const double *const in[HERTZ_NGEOMETRY],
                         hertz_geometry *g, ptrdiff_t *bad, int with_theta);

/* The load-dependent outputs for a given load, approach or peak pressure
 * (mode): out = {a, b, load, p0, delta, stiffness}.  HERTZ_OK or
 * HERTZ_BAD_VALUE. */
int hertz_contact_given(const hertz_geometry *g, int mode, double value,
                        double out[HERTZ_NGIVEN]);

/* The geometry's own outputs: lambda, alpha, m, K, E, e_star, rho_x, rho_y,
 * theta. */
void hertz_geometry_fields(const hertz_geometry *g, double out[HERTZ_NOUT - HERTZ_NGIVEN]);

/* Line contact (2-D, plane strain): in = {r1x, r1y, r2x, r2y, E1, nu1, E2,
 * nu2}, the line along y.  out = {half_width, p0, e_star, rho, load}.
 * HERTZ_OK or an error code (1 + k names input k in the point-contact
 * numbering, k != HERTZ_ANGLE). */
int hertz_line_contact(const double in[8], double load, double out[5], double *rho_x,
                       double *rho_y);

#endif
