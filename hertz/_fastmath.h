/*
 * hertz._ufuncs, shared by the contact and tangential kernels: bit-level
 * helpers of binary64 and the reduction of an angle to the quarter period with
 * the sine series on it, in branch-free code the compiler vectorises.
 *
 *   as_double, as_bits   the bits of a double and back;
 *   split_normal         x = m 2^e, 1 <= m < 2, for a normal x > 0;
 *   reduce_half_pi       x = k pi/2 + r, |r| <= pi/4, for |x| <= 1e5
 *                        (Cody-Waite, pi/2 in three parts, the first two of 33
 *                        significant bits, so k P1 and k P2 are exact for
 *                        |k| < 2^20);
 *   sin_reduced          sin r by its Taylor series to r^17 (truncation below
 *                        1e-17 relative for |r| <= pi/4).
 *
 * Built, as every C file of hertz/, without contraction into fused multiply-adds
 * (setup.py), so every vector width gives the same bits.
 */
#ifndef HERTZ_FASTMATH_H
#define HERTZ_FASTMATH_H

#include <stdint.h>
#include <string.h>

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

#define ROUND 0x1.8p52 /* (x + ROUND) - ROUND rounds x to an integer, |x| < 2^51 */

HERTZ_INLINE double
as_double(uint64_t bits)
{
    double d;
    memcpy(&d, &bits, sizeof d);
    return d;
}

HERTZ_INLINE uint64_t
as_bits(double d)
{
    uint64_t bits;
    memcpy(&bits, &d, sizeof bits);
    return bits;
}

/* x = m 2^e with m in [1, 2), for a normal x > 0 (bits only). */
HERTZ_INLINE double
split_normal(double x, double *e)
{
    uint64_t bits = as_bits(x);
    *e = as_double((bits >> 52) | 0x4330000000000000ull) - (0x1p52 + 1023.0);
    return as_double((bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull);
}

/* r = x - k pi/2 with k = round(x 2/pi); returns r and sets *k. */
HERTZ_INLINE double
reduce_half_pi(double x, double *k)
{
    const double P1 = 0x1.921fb54400000p+0, P2 = 0x1.0b4611a600000p-34,
                 P3 = 0x1.3198a2e037073p-69, TWO_OVER_PI = 0x1.45f306dc9c883p-1;
    double n = (x * TWO_OVER_PI + ROUND) - ROUND;
    *k = n;
    return ((x - n * P1) - n * P2) - n * P3;
}

/* sin r for |r| <= pi/4, z = r^2. */
HERTZ_INLINE double
sin_reduced(double r, double z)
{
    double sp = 1.0 / 355687428096000.0;  /* 1/17! */
    sp = -1.0 / 1307674368000.0 + z * sp; /* -1/15! */
    sp = 1.0 / 6227020800.0 + z * sp;     /* 1/13! */
    sp = -1.0 / 39916800.0 + z * sp;      /* -1/11! */
    sp = 1.0 / 362880.0 + z * sp;         /* 1/9! */
    sp = -1.0 / 5040.0 + z * sp;          /* -1/7! */
    sp = 1.0 / 120.0 + z * sp;            /* 1/5! */
    sp = -1.0 / 6.0 + z * sp;             /* -1/3! */
    return r + r * z * sp;
}

#endif
