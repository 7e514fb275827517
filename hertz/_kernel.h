/*
 * The contact-ellipse solver (hertz/_kernel.c): lambda(alpha) and m, K(m),
 * E(m) at the root of alpha = B(m) / ((1 - m) D(m)).  Pure C; the numpy
 * binding is hertz/_ufuncs.c.
 */
#ifndef HERTZ_KERNEL_H
#define HERTZ_KERNEL_H

#include <stddef.h>

/* With GCC or Clang on x86-64 Linux, block functions are also compiled for
 * AVX-512 (x86-64-v4) and AVX2 and the best one is chosen at load time;
 * elementwise operations round the same way at any vector width (and
 * -ffp-contract=off forbids contracting into fused multiply-adds), so all
 * give the same bits.  -DHERTZ_PLAIN builds
 * the plain version only (tests/test_kernel_builds.py compares them). */
#if defined(__GNUC__) && defined(__x86_64__) && defined(__linux__) && !defined(HERTZ_PLAIN)
#if (defined(__clang__) && __clang_major__ >= 14) || (!defined(__clang__) && __GNUC__ >= 11)
#define HERTZ_MULTIVERSION __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
/* For code that calls fma(): clones whose processors all have it. */
#define HERTZ_FMA_MULTIVERSION \
    __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#define HERTZ_FMA_CLONES 1
#else /* older compilers (manylinux2014's GCC 10) know no x86-64-vN level */
#define HERTZ_MULTIVERSION __attribute__((target_clones("avx2", "default")))
#define HERTZ_FMA_MULTIVERSION
#define HERTZ_FMA_CLONES 0
#endif
#else
#define HERTZ_MULTIVERSION
#define HERTZ_FMA_MULTIVERSION
#define HERTZ_FMA_CLONES 0
#endif

/* Largest n accepted by hertz_ellipse_block. */
#define HERTZ_BLOCK 64

/* Solve n <= HERTZ_BLOCK contiguous alphas.  m, K, E may be NULL.  Returns -1,
 * or the index of the first alpha that is not a positive number (the outputs
 * are then incomplete). */
ptrdiff_t hertz_ellipse_block(const double *alpha, ptrdiff_t n, int iterations,
                              double *lam, double *m, double *K, double *E);

/* The same for any n. */
ptrdiff_t hertz_ellipse_solve(const double *alpha, ptrdiff_t n, int iterations,
                              double *lam, double *m, double *K, double *E);

/* Fukushima's B(m), D(m) and V(m) = (B - pD)/m for 0 < m < 1, p = 1 - m given
 * separately so that either can carry full relative precision. */
void hertz_associate_integrals(ptrdiff_t n, const double *m, const double *p,
                               double *B, double *D, double *V);

/* lambda, K, E for n contiguous alphas from the piecewise-polynomial table
 * (hertz/_ellipse_table.c) where 1 <= alpha < 2^64, from the solver
 * elsewhere.  Returns -1, or the index of the first alpha that is not a
 * positive number. */
ptrdiff_t hertz_ellipse_table(const double *alpha, ptrdiff_t n, double *lam, double *K,
                              double *E);

/* 1 where fma() is a single instruction of this processor (x86-64-v3 and up
 * with GCC 11+ or Clang 14+ on Linux, aarch64), 0 elsewhere and in a
 * HERTZ_PLAIN build: exact products then use fma() instead of Dekker's
 * splitting (the same bits either way). */
int hertz_fma_available(void);

/* Whether the AVX2 start-only path is used; enable = 0 or 1 switches it off
 * or on (on only where the CPU has AVX2) first, enable < 0 only asks. */
int hertz_simd(int enable);

#endif
