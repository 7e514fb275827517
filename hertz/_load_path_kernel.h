/*
 * One step of hertz.LoadPathSpring for N contacts (hertz/_load_path_kernel.c):
 * Mindlin-Deresiewicz with a varying normal force, each contact's memory a
 * stack of pieces of the one-dimensional spring bed.  Pure C; the numpy
 * binding is hertz/_ufuncs.c (load_path_step), the Python side
 * hertz/_load_path.py (_SpringStacks, LoadPathSpring).
 */
#ifndef HERTZ_LOAD_PATH_KERNEL_H
#define HERTZ_LOAD_PATH_KERNEL_H

#include <stddef.h>

/* The contacts' memory.  Contact i holds count[i] pieces, each (E, D, B, F):
 * its inner edge, the coefficients of u = (delta - D) + B x^2 and the force
 * below it.  The top piece (the last, the only one most steps change) is at
 * top + i * HERTZ_PIECE, the ones below it, j < count[i] - 1, at
 * pieces + (i * width + j) * HERTZ_PIECE.  alpha[i] is the contact's scaled
 * size before the step (the caller keeps the new sizes, alpha1, as the next
 * step's), delta[i] its scaled displacement.  A contact whose count is not
 * in [0, width - 2] (no room for the 2 pieces a step may push) is left as it
 * is and reported: the kernel never writes beyond the arrays. */
#define HERTZ_PIECE 4
typedef struct {
    ptrdiff_t n, width;
    ptrdiff_t *count;
    const double *alpha;
    double *delta, *top, *pieces;
} hertz_spring_stacks;

/* Per contact: the normal force P [N], alpha1 = cbrt(P) (numpy's cbrt,
 * computed by the caller), the displacement increment [m]; mu and per_reach,
 * the reciprocal of the reach 3 mu / (2 k) at P = 1 N [1/m] (a product in the
 * step where a division would bound it), each an array of n (stride 1) or one value
 * (stride 0). */
typedef struct {
    const double *load, *alpha1, *increment, *mu, *per_reach;
    ptrdiff_t mu_stride, per_reach_stride;
} hertz_load_path_input;

/* The outputs, per contact (the LoadPathSpring's state, updated in place:
 * displacement += increment): the force [N], the normal force, sliding (0 or
 * 1), and the scaled size of the stick ellipse (0 where sliding). */
typedef struct {
    double *force, *normal_force, *displacement, *front;
    unsigned char *sliding;
} hertz_load_path_output;

/* Which input fails first, in the order LoadPathSpring.step checks them. */
enum {
    HERTZ_LP_OK, HERTZ_LP_BAD_LOAD, HERTZ_LP_BAD_INCREMENT, HERTZ_LP_BAD_DISPLACEMENT
};

/* The checks alone, nothing written: HERTZ_LP_OK, or the code of the first
 * check that fails with *bad the first contact where it does (a normal force
 * negative, infinite or NaN; an increment not finite; displacement +
 * increment not finite). */
int hertz_load_path_check(ptrdiff_t n, const double *load, const double *increment,
                          const double *displacement, ptrdiff_t *bad);

/* One step of every contact (inputs checked): returns the largest count after
 * it, or -1 - i where contact i is the first whose count left no room (the
 * caller's bug; the other contacts have made their step). */
ptrdiff_t hertz_load_path_step(const hertz_spring_stacks *stacks,
                               const hertz_load_path_input *in,
                               const hertz_load_path_output *out);

#endif
