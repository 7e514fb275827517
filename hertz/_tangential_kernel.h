/*
 * Tangential loading of a Hertz point contact per element
 * (hertz/_tangential_kernel.c): the no-slip tangential stiffness and the
 * Cattaneo-Mindlin partial-slip state.  Pure C; the numpy binding is
 * hertz/_ufuncs.c, the Python side hertz/_tangential.py.
 */
#ifndef HERTZ_TANGENTIAL_KERNEL_H
#define HERTZ_TANGENTIAL_KERNEL_H

#include <stddef.h>

/* Inputs of both kernels, in this order (the stiffness kernel takes the first
 * four geometry inputs, the moduli and the direction: K, alpha, lambda, a,
 * nu1, nu2, E1, E2, direction). */
enum {
    HERTZ_T_K, HERTZ_T_ALPHA, HERTZ_T_LAMBDA, HERTZ_T_A, HERTZ_T_B, HERTZ_T_LOAD,
    HERTZ_T_NU1, HERTZ_T_NU2, HERTZ_T_E1, HERTZ_T_E2, HERTZ_T_FORCE, HERTZ_T_MU,
    HERTZ_T_DIRECTION, HERTZ_T_NIN
};
#define HERTZ_T_STIFFNESS_NIN 9

/* Partial-slip outputs, in this order (sliding is 1.0 or 0.0). */
enum {
    HERTZ_T_STICK_A, HERTZ_T_STICK_B, HERTZ_T_SLIP_AREA, HERTZ_T_DISPLACEMENT,
    HERTZ_T_TRANSVERSE, HERTZ_T_TANGENT, HERTZ_T_NO_SLIP, HERTZ_T_SLIDING, HERTZ_T_NOUT
};

/* Error codes: the first input that fails, in the order hertz/_tangential.py
 * checks them. */
enum {
    HERTZ_T_OK, HERTZ_T_BAD_MU, HERTZ_T_BAD_DIRECTION, HERTZ_T_BAD_LOAD, HERTZ_T_BAD_FORCE,
    HERTZ_T_ABOVE_LIMIT
};

/* n elements, in[k][i] input k of element i, contiguous.  They return
 * HERTZ_T_OK, or an error code with *bad the element (outputs then partly
 * written). */
int hertz_tangential_stiffness_block(ptrdiff_t n, const double *const *in, double *out,
                                     ptrdiff_t *bad);
int hertz_partial_slip_block(ptrdiff_t n, const double *const *in, double *const *out,
                             ptrdiff_t *bad);

#endif
