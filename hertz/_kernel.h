/*
 * The contact-ellipse solver (hertz/_kernel.c): lambda(alpha) and m, K(m),
 * E(m) at the root of alpha = B(m) / ((1 - m) D(m)).  Pure C; the numpy
 * binding is hertz/_ufuncs.c.
 */
#ifndef HERTZ_KERNEL_H
#define HERTZ_KERNEL_H

#include <stddef.h>

/* Always inlined, at any optimisation level (the block loops vectorise only
 * with their helpers inlined; GCC's -O2 inlines less than -O3). */
#ifndef HERTZ_INLINE
#if defined(__GNUC__)
#define HERTZ_INLINE static inline __attribute__((always_inline))
#elif defined(_MSC_VER)
#define HERTZ_INLINE static __forceinline
#else
#define HERTZ_INLINE static inline
#endif
#endif

/* A loop of a constant count unrolled completely at any optimisation level
 * (GCC's -O2 keeps small loops whose unrolling grows the code, and then the
 * loop around them does not vectorise). */
#if defined(__GNUC__)
#define HERTZ_PRAGMA(x) _Pragma(#x)
#define HERTZ_UNROLL(n) HERTZ_PRAGMA(GCC unroll n)
#else
#define HERTZ_UNROLL(n)
#endif

/* Code paths.  With GCC or Clang on x86-64 Linux the block functions are
 * compiled three times, for AVX-512 (F, DQ, VL, BW with AVX2 and FMA), for
 * AVX2 with FMA and for the baseline, and hertz_path() picks one for the
 * processor at the first call (__builtin_cpu_supports; no target_clones, whose
 * resolvers Clang 14 gets wrong for arch= levels).  Elementwise operations
 * round the same way at any vector width, and -ffp-contract=off (setup.py)
 * forbids contracting into fused multiply-adds, so all give the same bits.
 * -DHERTZ_PLAIN, MSVC, macOS and aarch64 build the plain path only
 * (tests/test_kernel_builds.py compares them). */
#define HERTZ_PATH_PLAIN 0
#define HERTZ_PATH_AVX2 1
#define HERTZ_PATH_AVX512 2

#if defined(__GNUC__) && defined(__x86_64__) && defined(__linux__) && !defined(HERTZ_PLAIN)
#define HERTZ_X86_PATHS 1
#define HERTZ_TARGET_AVX2 __attribute__((target("avx2,fma")))
#define HERTZ_TARGET_AVX512 \
    __attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,avx2,fma")))
#else
#define HERTZ_X86_PATHS 0
#endif

/* fma() is one instruction of every processor the plain path runs on
 * (aarch64): exact products there use it instead of Dekker's splitting (the
 * same bits either way).  The AVX2 and AVX-512 paths always use it. */
#if (defined(__aarch64__) || defined(_M_ARM64)) && !defined(HERTZ_PLAIN)
#define HERTZ_PLAIN_FMA 1
#else
#define HERTZ_PLAIN_FMA 0
#endif

/* A block function in every version of this build: HERTZ_VERSIONS(RET, NAME,
 * PARAMS, NAMES) defines NAME_avx512, NAME_avx2 (x86-64 Linux) and NAME_plain,
 * each `return NAME_body(NAMES, fused)` with NAME_body always inlined (PARAMS
 * and NAMES are macros of the parameter list and of its names);
 * HERTZ_PICK(NAME) is the version of hertz_path(). */
#if HERTZ_X86_PATHS
#define HERTZ_VERSIONS(RET, NAME, PARAMS, NAMES)                                     \
    HERTZ_TARGET_AVX512 static RET NAME##_avx512(PARAMS)                             \
    {                                                                                \
        return NAME##_body(NAMES, 1);                                                \
    }                                                                                \
    HERTZ_TARGET_AVX2 static RET NAME##_avx2(PARAMS)                                 \
    {                                                                                \
        return NAME##_body(NAMES, 1);                                                \
    }                                                                                \
    static RET NAME##_plain(PARAMS)                                                  \
    {                                                                                \
        return NAME##_body(NAMES, HERTZ_PLAIN_FMA);                                  \
    }
#define HERTZ_PICK(NAME)                                                             \
    (hertz_path() == HERTZ_PATH_AVX512 ? NAME##_avx512                               \
                                       : (hertz_path() == HERTZ_PATH_AVX2 ? NAME##_avx2 \
                                                                          : NAME##_plain))
#else
#define HERTZ_VERSIONS(RET, NAME, PARAMS, NAMES)                                     \
    static RET NAME##_plain(PARAMS)                                                  \
    {                                                                                \
        return NAME##_body(NAMES, HERTZ_PLAIN_FMA);                                  \
    }
#define HERTZ_PICK(NAME) NAME##_plain
#endif

/* The code path in use: HERTZ_PATH_AVX512 or HERTZ_PATH_AVX2 where this build
 * has it and the processor (and its operating system) supports it, else
 * HERTZ_PATH_PLAIN; decided at the first call. */
int hertz_path(void);

/* Use at most path `limit` from now on (HERTZ_PATH_PLAIN, _AVX2 or _AVX512;
 * what the processor lacks is never used); returns hertz_path().  For tests
 * and benchmarks. */
int hertz_set_path(int limit);

/* The paths compiled into this build, as a bit set (1 << HERTZ_PATH_...). */
int hertz_paths_built(void);

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

/* Whether a SIMD path (AVX2 or AVX-512) is used; enable = 0 switches to the
 * plain path, enable = 1 back to the best the processor has, first; enable < 0
 * only asks. */
int hertz_simd(int enable);

#endif
