/*
 * hertz/_load_path_kernel.c -- one step of hertz.LoadPathSpring for N
 * contacts: Mindlin-Deresiewicz under a varying normal force, driven by
 * displacement (Mindlin & Deresiewicz 1953), on the exact one-dimensional
 * memory of hertz/_load_path.py's module docstring (Jaeger's superposition
 * principle, J. Tribol. 120 (1998) 677; the spring bed of Popov and Hess's
 * method of dimensionality reduction, scaled by the contact at P_ref = 1 N).
 *
 * Each contact holds its bed as a stack of pieces ordered by x, piece j on
 * [E_j, E_j+1] (the top one up to the contact's size alpha) carrying
 * u = (delta - D_j) + B_j x^2; F_j = int (-D + B x^2) over the pieces below j,
 * so that the force is read from the top piece, which is kept apart from the
 * others (a dense array, read and written in order: the pieces below are
 * touched only where pieces are pushed or popped).  A step moves every spring in
 * contact by d_delta at once through delta; what changes piece by piece is
 * at the top (the springs that slide in a step are an outer interval [c, a],
 * and those that enter or leave are at the edge):
 *
 * - leaving (alpha falls): pop the pieces that start at or beyond the new size;
 * - sliding (the outer old spring beyond its limit +-(alpha^2 - x^2) by more
 *   than the rounding of u, 8 eps (|delta| + alpha^2)): pop the pieces whose
 *   inner edge slides, cut the piece that holds the front c (the root of
 *   s u(c) = alpha^2 - c^2), push one piece on the limit from c;
 * - entering (alpha rises): push one piece from the old size,
 *   u = d_delta (a1^2 - x^2) / (a1^2 - a0^2), or on the limit where
 *   |d_delta| > a1^2 - a0^2;
 * - a piece pushed equal to the top one is merged with it;
 * - a contact sliding as a whole keeps one piece and starts delta from 0; a
 *   delta beyond 4 alpha^2 is re-based into the pieces (D -= delta,
 *   F += delta E), so that delta - D keeps its digits.
 *
 * Then LoadPathSpring's own step: the increment scaled by 3 mu / (2 k) at 1 N
 * and clipped to +-4 max(alpha0, alpha1)^2 (beyond, every spring slides), the
 * force mu Q / (mu P_ref), |Q| >= mu P rounded onto the limit of friction,
 * the stick ellipse.
 *
 * This is the numpy code it replaced, one contact at a time, every operation
 * in its order (tests/reference_spring_stacks.py keeps that code; the tests
 * assert the same bits): numpy's elementwise double arithmetic, sqrt,
 * minimum, maximum and clip are IEEE operations, and the build forbids
 * contraction into fused multiply-adds (setup.py), so every build gives the
 * numpy code's bits.  cbrt is numpy's, computed by the caller (numpy's
 * differs from libm's on processors where numpy uses SVML).  Plain scalar C,
 * one contact at a time: the work of a contact is a few operations on its own
 * stack, its branches following the contact's own history (branch-free
 * variants, computing every case and choosing after, measured slower).  The
 * top pieces are a dense array and the pieces below them are prefetched; the
 * input checks, a pass of their own before anything is written, are a sum the
 * compiler vectorises.  benchmarks/dem_laws.py measures the step.
 */
#include <float.h>
#include <math.h>
#include <stddef.h>

#include "_load_path_kernel.h"

#define EPS 2.220446049250313080847e-16 /* 2^-52, numpy's finfo(float).eps */

/* The pieces below the top of the contact PREFETCH ahead are asked for early
 * (the one under the top, where pops read and pushes write): a contact's
 * stack is a stride of width pieces from its neighbour's, which the
 * processor's own prefetchers do not foresee. */
#define PREFETCH 16
#if defined(__GNUC__) || defined(__clang__)
#define PREFETCH_PIECE(address) __builtin_prefetch((address), 1, 3)
#elif defined(_MSC_VER) && (defined(_M_X64) || defined(_M_IX86))
#include <xmmintrin.h>
#define PREFETCH_PIECE(address) _mm_prefetch((const char *)(address), _MM_HINT_T0)
#else
#define PREFETCH_PIECE(address) ((void)(address))
#endif

typedef struct {
    double e, d, b, f;
} piece_t;

static inline piece_t
get(const double *x)
{
    piece_t p = {x[0], x[1], x[2], x[3]};
    return p;
}

static inline void
put(double *x, piece_t p)
{
    x[0] = p.e;
    x[1] = p.d;
    x[2] = p.b;
    x[3] = p.f;
}

/* numpy's maximum, minimum and clip for numbers that are not NaN */
static inline double
max2(double a, double b)
{
    return a > b ? a : b;
}

static inline double
min2(double a, double b)
{
    return a < b ? a : b;
}

static inline double
clip(double x, double lo, double hi)
{
    return min2(max2(x, lo), hi);
}

/* int_x0^x1 (c0 + c2 x^2) dx */
static inline double
piece_integral(double x0, double x1, double c0, double c2)
{
    double w = x1 - x0;
    return w * (c0 + c2 * (x1 * x1 + x1 * x0 + x0 * x0) * (1.0 / 3.0));
}

/* A contact's stack: *count pieces, the top one in *top, the others in
 * below[j * HERTZ_PIECE], j < *count - 1. */

/* Push the piece [edge, ...) with (D, B), merged with the top piece where that
 * has the same coefficients. */
static inline void
push(double *below, piece_t *top, ptrdiff_t *count, double edge, double d, double b)
{
    ptrdiff_t n = *count;
    double f = 0.0;
    if (n > 0) {
        if (top->d == d && top->b == b) {
            return;
        }
        f = top->f + piece_integral(top->e, edge, -top->d, top->b);
        put(below + (n - 1) * HERTZ_PIECE, *top);
    }
    top->e = edge;
    top->d = d;
    top->b = b;
    top->f = f;
    *count = n + 1;
}

/* The outer old springs slide to the limit s (alpha^2 - x^2), s = +-1: pop
 * the pieces whose inner edge slides, cut the piece that holds the front c,
 * push the piece on the limit from c; *front = c where anything slid. */
static inline void
slide(double *below, piece_t *top, ptrdiff_t *count, double s, double d1, double a1,
      double end, double tol, double *front)
{
    ptrdiff_t n = *count, k = n - 1;
    double tiny = 4.0 * EPS * a1;
    piece_t pk = *top; /* piece k */
    for (;;) {         /* the innermost piece whose inner edge does not slide (none: -1) */
        double e = pk.e;
        double u = (d1 - pk.d) + pk.b * (e * e);
        double lim = (a1 - e) * (a1 + e) + tol;
        if (!(s * u > lim)) {
            break;
        }
        if (k == 0) {
            k = -1;
            break;
        }
        --k;
        pk = get(below + k * HERTZ_PIECE);
    }
    double c = 0.0, e0 = 0.0; /* c = 0: everything slides */
    if (k >= 0) {
        e0 = pk.e;
        double e1 = end; /* where piece k ends */
        if (k + 1 < n) {
            e1 = min2(k + 1 == n - 1 ? top->e : below[(k + 1) * HERTZ_PIECE], end);
        }
        /* the front in piece k: s (d1 - dk + bk c^2) = a1^2 - c^2 */
        c = sqrt((a1 * a1 - s * (d1 - pk.d)) / (1.0 + s * pk.b));
        c = isfinite(c) ? clip(c, e0, e1) : e1;
        if (c - e0 <= tiny) { /* a sliver that sticks: slides too */
            c = e0;
        }
    }
    if (!(end - c > tiny)) { /* a sliver that slides: nothing slid */
        return;
    }
    /* the pieces kept: up to piece k if a stretch of it sticks, else below it */
    ptrdiff_t keep = c == 0.0 ? 0 : c > e0 ? k + 1 : k;
    if (keep > 0) {
        *top = keep == k + 1 ? pk : get(below + (keep - 1) * HERTZ_PIECE);
    }
    *count = keep;
    push(below, top, count, c, d1 - s * (a1 * a1), -s);
    *front = c;
}

int
hertz_load_path_check(ptrdiff_t n, const double *load, const double *increment,
                      const double *displacement, ptrdiff_t *bad)
{
    /* The common case, a pass that the compiler vectorises: per contact
     * (P - |P| + 0 P) + (0 d + 0 (x + d)) is +-0 where all three are fine, NaN
     * where one is not finite, < 0 where P < 0 (every term is <= 0 or NaN, so
     * that a sum never comes back to 0); summed in 4 independent sums. */
    double sum[4] = {0.0, 0.0, 0.0, 0.0};
    ptrdiff_t i = 0;
    for (; i + 4 <= n; i += 4) {
        for (int k = 0; k < 4; ++k) {
            double p = load[i + k], d = increment[i + k], x = displacement[i + k] + d;
            sum[k] += ((p - fabs(p)) + p * 0.0) + (d * 0.0 + x * 0.0);
        }
    }
    for (; i < n; ++i) {
        double p = load[i], d = increment[i], x = displacement[i] + d;
        sum[0] += ((p - fabs(p)) + p * 0.0) + (d * 0.0 + x * 0.0);
    }
    if ((sum[0] == 0.0) & (sum[1] == 0.0) & (sum[2] == 0.0) & (sum[3] == 0.0)) {
        return HERTZ_LP_OK;
    }
    ptrdiff_t first[3] = {-1, -1, -1};
    for (ptrdiff_t i = 0; i < n && first[0] < 0; ++i) {
        double p = load[i], d = increment[i];
        if (!(p >= 0.0 && p <= DBL_MAX)) {
            first[0] = i;
        }
        if (first[1] < 0 && !(fabs(d) <= DBL_MAX)) {
            first[1] = i;
        }
        if (first[2] < 0 && !(fabs(displacement[i] + d) <= DBL_MAX)) {
            first[2] = i;
        }
    }
    for (int k = 0; k < 3; ++k) {
        if (first[k] >= 0) {
            *bad = first[k];
            return HERTZ_LP_BAD_LOAD + k;
        }
    }
    return HERTZ_LP_OK; /* not reached */
}

/* One step of contacts [0, n) (see hertz_load_path_step); the strides of mu
 * and per_reach are arguments so that a caller passing constants gets a loop of
 * its own (one value for all: read once). */
static inline ptrdiff_t
step_contacts(ptrdiff_t n_contacts, ptrdiff_t width, ptrdiff_t *restrict count,
              const double *restrict alpha, double *restrict delta_of,
              double *restrict tops, double *restrict pieces,
              const double *restrict alpha1, const double *restrict load_of,
              const double *restrict increment, const double *restrict mu_of,
              const double *restrict per_reach, ptrdiff_t mu_stride,
              ptrdiff_t per_reach_stride,
              double *restrict force_of, double *restrict normal_force,
              double *restrict displacement, double *restrict front_of,
              unsigned char *restrict sliding_of)
{
    ptrdiff_t most = 0, bad = -1;
    for (ptrdiff_t i = 0; i < n_contacts; ++i) {
        if (i + PREFETCH < n_contacts) {
            ptrdiff_t j = i + PREFETCH, m = count[j];
            PREFETCH_PIECE(pieces + (j * width + (m > 1 ? m - 2 : 0)) * HERTZ_PIECE);
        }
        ptrdiff_t n = count[i];
        if ((size_t)n > (size_t)(width - 2)) { /* no room: left as it is */
            bad = bad < 0 ? i : bad;
            continue;
        }
        double *below = pieces + i * width * HERTZ_PIECE;
        piece_t top = get(tops + i * HERTZ_PIECE);
        double a0 = alpha[i], delta = delta_of[i];
        double a1 = alpha1[i], load = load_of[i], inc = increment[i];
        /* the scaled increment, limited to +-4 alpha^2 (alpha the larger size) */
        double bound = max2(a1, a0);
        bound = 4.0 * bound * bound;
        double dd = clip(inc * per_reach[i * per_reach_stride], -bound, bound);
        int gone = a1 == 0.0;
        if (gone) { /* out of contact: nothing carries or remembers a force */
            n = 0;
            a0 = 0.0;
            delta = 0.0;
        }
        double d1 = delta + dd;
        double a2 = a1 * a1;
        double front = a1;
        /* springs leaving: pop the pieces at or beyond the new size (a top piece
         * starts below the old size, so none where the size does not fall) */
        while (n > 0 && top.e >= a1) {
            if (--n > 0) {
                top = get(below + (n - 1) * HERTZ_PIECE);
            }
        }
        double end = min2(a0, a1); /* where the old springs end now */
        if (n > 0) {               /* springs sliding: an outer interval of the old ones */
            double u = (d1 - top.d) + top.b * (end * end);
            /* beyond the limit (>= 0) by more than the rounding of u */
            double tol = 8.0 * EPS * (fabs(d1) + a1 * a1);
            double limit = (a1 - end) * (a1 + end) + tol;
            if (fabs(u) > limit) {
                slide(below, &top, &n, u > limit ? 1.0 : -1.0, d1, a1, end, tol, &front);
            }
        }
        if (a1 > a0) { /* springs entering: one piece from the old size */
            double d = (a1 - a0) * (a1 + a0);
            double ratio = dd / d;
            int on_limit = fabs(ratio) > 1.0;
            double coef = on_limit ? (ratio > 0.0 ? 1.0 : -1.0) : ratio;
            push(below, &top, &n, a0, d1 - coef * a2, -coef);
            if (on_limit && front == a1) {
                front = a0;
            }
        }
        delta = d1;
        if (n == 1 && front == 0.0) { /* sliding as a whole: delta from 0 again */
            top.d -= delta;
            delta = 0.0;
        }
        if (fabs(delta) > 4.0 * a2) { /* re-based into the pieces */
            for (ptrdiff_t j = 0; j < n - 1; ++j) {
                double *piece = below + j * HERTZ_PIECE;
                piece[1] -= delta;
                piece[3] += delta * piece[0];
            }
            if (n > 0) {
                top.d -= delta;
                top.f += delta * top.e;
            }
            delta = 0.0;
        }
        count[i] = n;
        delta_of[i] = delta;
        put(tops + i * HERTZ_PIECE, top);
        most = n > most ? n : most;
        /* Q / (mu P_ref) = (3/2) int_0^alpha u dx, from the top piece */
        double q = 0.0;
        if (n > 0) {
            q = top.f + delta * top.e + piece_integral(top.e, a1, delta - top.d, top.b);
            q = 1.5 * q;
        }
        if (gone) {
            front = 0.0;
        }
        /* a force that rounds onto or past the limit of friction is the limit */
        double mu = mu_of[i * mu_stride];
        double limit = mu * load, force = mu * q;
        int sliding = (a1 > 0.0) & ((front == 0.0) | (fabs(force) >= limit));
        force_of[i] = sliding ? copysign(limit, q) : force;
        front_of[i] = sliding ? 0.0 : front;
        sliding_of[i] = (unsigned char)sliding;
        normal_force[i] = load;
        displacement[i] = displacement[i] + inc;
    }
    return bad < 0 ? most : -1 - bad;
}

ptrdiff_t
hertz_load_path_step(const hertz_spring_stacks *stacks, const hertz_load_path_input *in,
                     const hertz_load_path_output *out)
{
#define STEP(MU, REACH)                                                                     \
    step_contacts(stacks->n, stacks->width, stacks->count, stacks->alpha, stacks->delta,    \
                  stacks->top, stacks->pieces, in->alpha1, in->load, in->increment, in->mu, \
                  in->per_reach, MU, REACH, out->force, out->normal_force, out->displacement,   \
                  out->front, out->sliding)
    if (in->mu_stride == 0 && in->per_reach_stride == 0) { /* one body and mu for all */
        return STEP(0, 0);
    }
    if (in->mu_stride == 1 && in->per_reach_stride == 1) {
        return STEP(1, 1);
    }
    return STEP(in->mu_stride, in->per_reach_stride);
#undef STEP
}
