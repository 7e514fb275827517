/*
 * The contact ellipse from a table (hertz/_ellipse_table.c): lambda(alpha),
 * K and E at the root of alpha = B(m) / ((1 - m) D(m)) (hertz/_kernel.c,
 * eq. (1)) for the contact kernel, without an iteration.
 *
 * For 1 <= alpha < 2^TABLE_BINADES the three functions are piecewise
 * polynomials (hertz/_ellipse_table.h, written by
 * tools/generate_ellipse_table.py from 50-digit mpmath roots): the piece is
 * read from the bits of alpha (its binade and the next TABLE_SPLIT_BITS bits),
 * the local variable z in [-1, 1) is exact, and each function is
 *
 *     c0_hi + (c0_lo + z (c1 + z (c2 + ... + z c_d))),
 *
 * within 1.0 x 2^-53 relative of the truth (the generator's check; the tests
 * compare with tests/reference.py).  This costs a fraction of one evaluation of
 * K and E, which is why hertz.contact uses it; hertz.ellipticity keeps the
 * seed's Bailey iteration (hertz/_kernel.c), whose own accuracy is 3.7e-16.
 *
 * alpha = 1 gives lambda = 1 and K = E = pi/2 exactly; lambda is never below
 * 1.  alpha >= 2^TABLE_BINADES (and anything not in [1, inf)) goes to the
 * solver, whose closed form covers alpha >= 2^64.
 */
#include <stdint.h>
#include <string.h>

#include "_coefficients.h"
#include "_ellipse_table.h"
#include "_kernel.h"

#if TABLE_DEGREE != 8 || TABLE_STRIDE != 10
#error "the table is evaluated as a degree-8 polynomial, 30 doubles a piece"
#endif

#define TABLE_TOP 0x1p64 /* 2^TABLE_BINADES */
#define Z_SCALE ((double)(2 << TABLE_SPLIT_BITS))
#if TABLE_BINADES != 64
#error "TABLE_TOP is 2^TABLE_BINADES"
#endif

/* Horner in z on a stored row, then the two-part leading coefficient. */
HERTZ_INLINE double
table_poly(const double *c, double z)
{
    double r = c[9];
    r = r * z + c[8];
    r = r * z + c[7];
    r = r * z + c[6];
    r = r * z + c[5];
    r = r * z + c[4];
    r = r * z + c[3];
    r = r * z + c[2];
    return c[0] + (c[1] + z * r);
}

/* The row of alpha (in [1, 2^TABLE_BINADES)) in the table and its z. */
HERTZ_INLINE void
table_setup(double a, const double **row, double *z)
{
    uint64_t bits;
    memcpy(&bits, &a, sizeof bits);
    /* piece e 2^S + k: the exponent and the top S bits of the mantissa */
    uint64_t piece = (bits >> (52 - TABLE_SPLIT_BITS)) - ((uint64_t)1023 << TABLE_SPLIT_BITS);
    uint64_t fbits = (bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull;
    double f;
    memcpy(&f, &fbits, sizeof f);
    double k = (double)(piece & ((1u << TABLE_SPLIT_BITS) - 1));
    *z = Z_SCALE * f - (Z_SCALE + 2.0 * k + 1.0);
    *row = &ELLIPSE_TABLE[piece][0][0];
}

/* lambda, K, E of one alpha in [1, 2^TABLE_BINADES). */
HERTZ_INLINE void
table_one(double a, double *lam, double *K, double *E)
{
    const double *row;
    double z;
    table_setup(a, &row, &z);
    double l = table_poly(row, z);
    *lam = a == 1.0 ? 1.0 : (l > 1.0 ? l : 1.0);
    *K = a == 1.0 ? PI_2 : table_poly(row + TABLE_STRIDE, z);
    *E = a == 1.0 ? PI_2 : table_poly(row + 2 * TABLE_STRIDE, z);
}

/* Where the compiler has GNU C's vector types (GCC and Clang, any processor):
 * table_one for two elements at once, the same operations lane by lane.  The
 * plain path's loop of table_one stays scalar (no compiler vectorises its
 * gathers to advantage: GCC's emulated ones compute an address per load);
 * here the two rows are read by scalar loads into the two lanes and the
 * arithmetic, half of the work, is done on pairs. */
#if defined(__GNUC__) || defined(__clang__)
#define HAVE_PAIR_TABLE 1
typedef double hertz_v2d __attribute__((vector_size(16)));

/* table_poly of rows a and b (lanes 0 and 1) at z. */
HERTZ_INLINE hertz_v2d
table_poly_pair(const double *a, const double *b, hertz_v2d z)
{
#define C(j) ((hertz_v2d){a[j], b[j]})
    hertz_v2d r = C(9);
    r = r * z + C(8);
    r = r * z + C(7);
    r = r * z + C(6);
    r = r * z + C(5);
    r = r * z + C(4);
    r = r * z + C(3);
    r = r * z + C(2);
    return C(0) + (C(1) + z * r);
#undef C
}

/* The elements of alpha[0..n) within the table, two at a time where both of a
 * pair are; returns whether any is outside. */
static int
table_pairs(ptrdiff_t n, const double *alpha, double *lam, double *K, double *E)
{
    int outside = 0;
    ptrdiff_t i = 0;
    for (; i + 2 <= n; i += 2) {
        double a0 = alpha[i], a1 = alpha[i + 1];
        int ok0 = a0 >= 1.0 && a0 < TABLE_TOP, ok1 = a1 >= 1.0 && a1 < TABLE_TOP;
        if (!(ok0 && ok1)) {
            outside |= !(ok0 && ok1);
            if (ok0) {
                table_one(a0, lam + i, K + i, E + i);
            }
            if (ok1) {
                table_one(a1, lam + i + 1, K + i + 1, E + i + 1);
            }
            continue;
        }
        const double *r0, *r1;
        double z0, z1;
        table_setup(a0, &r0, &z0);
        table_setup(a1, &r1, &z1);
        hertz_v2d z = {z0, z1};
        hertz_v2d l = table_poly_pair(r0, r1, z);
        hertz_v2d kk = table_poly_pair(r0 + TABLE_STRIDE, r1 + TABLE_STRIDE, z);
        hertz_v2d ee = table_poly_pair(r0 + 2 * TABLE_STRIDE, r1 + 2 * TABLE_STRIDE, z);
        lam[i] = a0 == 1.0 ? 1.0 : (l[0] > 1.0 ? l[0] : 1.0);
        lam[i + 1] = a1 == 1.0 ? 1.0 : (l[1] > 1.0 ? l[1] : 1.0);
        K[i] = a0 == 1.0 ? PI_2 : kk[0];
        K[i + 1] = a1 == 1.0 ? PI_2 : kk[1];
        E[i] = a0 == 1.0 ? PI_2 : ee[0];
        E[i + 1] = a1 == 1.0 ? PI_2 : ee[1];
    }
    for (; i < n; ++i) {
        int ok = alpha[i] >= 1.0 && alpha[i] < TABLE_TOP;
        outside |= !ok;
        if (ok) {
            table_one(alpha[i], lam + i, K + i, E + i);
        }
    }
    return outside;
}
#else
#define HAVE_PAIR_TABLE 0
#endif

#if HERTZ_X86_PATHS
#include <immintrin.h>
#define HAVE_AVX2_TABLE 1

/* Coefficients j and j + 1 of the rows of four elements as two vectors (lane
 * k from row k): two 128-bit loads per pair of rows and two unpacks.  This
 * replaces two gathers, which are slow on AMD Zen (about as slow as the
 * scalar loads they stand for, and they block the pipes). */
__attribute__((target("avx2"))) static inline void
pair_avx2(const double *const row[4], int j, __m256d *cj, __m256d *cj1)
{
    __m256d a = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(row[0] + j)),
                                     _mm_loadu_pd(row[2] + j), 1);
    __m256d b = _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(row[1] + j)),
                                     _mm_loadu_pd(row[3] + j), 1);
    *cj = _mm256_unpacklo_pd(a, b);
    *cj1 = _mm256_unpackhi_pd(a, b);
}

/* table_poly of four rows (row[k] + offset) at once. */
__attribute__((target("avx2"))) static inline __m256d
poly_avx2(const double *const rows[4], int offset, __m256d z)
{
    const double *const row[4] = {rows[0] + offset, rows[1] + offset, rows[2] + offset,
                                  rows[3] + offset};
    __m256d c[TABLE_STRIDE];
    for (int j = 0; j < TABLE_STRIDE; j += 2) {
        pair_avx2(row, j, &c[j], &c[j + 1]);
    }
    __m256d r = c[9];
    for (int j = 8; j >= 2; --j) {
        r = _mm256_add_pd(_mm256_mul_pd(r, z), c[j]);
    }
    return _mm256_add_pd(c[0], _mm256_add_pd(c[1], _mm256_mul_pd(z, r)));
}

/* table_one four at a time, the same operations in the same order (no FMA),
 * so the same bits.  Elements outside [1, 2^64) are left to the caller. */
__attribute__((target("avx2"))) static int
table_avx2(ptrdiff_t n, const double *alpha, double *lam, double *K, double *E)
{
    int outside = 0;
    const __m256d one = _mm256_set1_pd(1.0), top = _mm256_set1_pd(TABLE_TOP);
    const __m256d pi_2 = _mm256_set1_pd(PI_2), scale = _mm256_set1_pd(Z_SCALE);
    const __m256d two = _mm256_set1_pd(2.0), two52 = _mm256_set1_pd(0x1p52);
    const __m256i mantissa = _mm256_set1_epi64x(0x000FFFFFFFFFFFFFll);
    const __m256i exponent_one = _mm256_set1_epi64x(0x3FF0000000000000ll);
    const __m256i bias = _mm256_set1_epi64x((long long)1023 << TABLE_SPLIT_BITS);
    const __m256i low = _mm256_set1_epi64x((1 << TABLE_SPLIT_BITS) - 1);
    const __m256i two52_bits = _mm256_set1_epi64x(0x4330000000000000ll);
    const double *table = &ELLIPSE_TABLE[0][0][0];
    ptrdiff_t i = 0;
    for (; i + 4 <= n; i += 4) {
        __m256d a = _mm256_loadu_pd(alpha + i);
        __m256d ok = _mm256_and_pd(_mm256_cmp_pd(a, one, _CMP_GE_OQ),
                                   _mm256_cmp_pd(a, top, _CMP_LT_OQ));
        outside |= _mm256_movemask_pd(ok) != 0xF;
        a = _mm256_blendv_pd(one, a, ok);
        __m256i bits = _mm256_castpd_si256(a);
        __m256i piece = _mm256_sub_epi64(_mm256_srli_epi64(bits, 52 - TABLE_SPLIT_BITS), bias);
        __m256d k = _mm256_sub_pd(
            _mm256_castsi256_pd(_mm256_or_si256(_mm256_and_si256(piece, low), two52_bits)),
            two52);
        __m256d f = _mm256_castsi256_pd(
            _mm256_or_si256(_mm256_and_si256(bits, mantissa), exponent_one));
        __m256d z = _mm256_sub_pd(_mm256_mul_pd(scale, f),
                                  _mm256_add_pd(_mm256_add_pd(scale, _mm256_mul_pd(two, k)),
                                                one));
        __m256i at = _mm256_sub_epi64(_mm256_slli_epi64(piece, 5), _mm256_slli_epi64(piece, 1));
        long long offset[4];
        _mm256_storeu_si256((__m256i *)offset, at);
        const double *const rows[4] = {table + offset[0], table + offset[1], table + offset[2],
                                       table + offset[3]};
        __m256d l = poly_avx2(rows, 0, z);
        __m256d kk = poly_avx2(rows, TABLE_STRIDE, z);
        __m256d ee = poly_avx2(rows, 2 * TABLE_STRIDE, z);
        __m256d is_one = _mm256_cmp_pd(a, one, _CMP_EQ_OQ);
        l = _mm256_blendv_pd(one, l, _mm256_cmp_pd(l, one, _CMP_GT_OQ));
        _mm256_storeu_pd(lam + i, _mm256_blendv_pd(l, one, is_one));
        _mm256_storeu_pd(K + i, _mm256_blendv_pd(kk, pi_2, is_one));
        _mm256_storeu_pd(E + i, _mm256_blendv_pd(ee, pi_2, is_one));
    }
    for (; i < n; ++i) {
        int ok = alpha[i] >= 1.0 && alpha[i] < TABLE_TOP;
        outside |= !ok;
        table_one(ok ? alpha[i] : 1.0, lam + i, K + i, E + i);
    }
    return outside;
}
__attribute__((target("avx512f"))) static inline __m512d
poly_avx512(const double *row, __m512i at, __m512d z)
{
    __m512d r = _mm512_i64gather_pd(at, row + 9, 8);
    for (int j = 8; j >= 2; --j) {
        r = _mm512_add_pd(_mm512_mul_pd(r, z), _mm512_i64gather_pd(at, row + j, 8));
    }
    __m512d c1 = _mm512_i64gather_pd(at, row + 1, 8);
    __m512d c0 = _mm512_i64gather_pd(at, row, 8);
    return _mm512_add_pd(c0, _mm512_add_pd(c1, _mm512_mul_pd(z, r)));
}

/* table_avx2 eight at a time (AVX-512F), the same operations. */
__attribute__((target("avx512f"))) static int
table_avx512(ptrdiff_t n, const double *alpha, double *lam, double *K, double *E)
{
    int outside = 0;
    const __m512d one = _mm512_set1_pd(1.0), top = _mm512_set1_pd(TABLE_TOP);
    const __m512d pi_2 = _mm512_set1_pd(PI_2), scale = _mm512_set1_pd(Z_SCALE);
    const __m512d two = _mm512_set1_pd(2.0), two52 = _mm512_set1_pd(0x1p52);
    const __m512i mantissa = _mm512_set1_epi64(0x000FFFFFFFFFFFFFll);
    const __m512i exponent_one = _mm512_set1_epi64(0x3FF0000000000000ll);
    const __m512i bias = _mm512_set1_epi64((long long)1023 << TABLE_SPLIT_BITS);
    const __m512i low = _mm512_set1_epi64((1 << TABLE_SPLIT_BITS) - 1);
    const __m512i two52_bits = _mm512_set1_epi64(0x4330000000000000ll);
    const double *table = &ELLIPSE_TABLE[0][0][0];
    ptrdiff_t i = 0;
    for (; i + 8 <= n; i += 8) {
        __m512d a = _mm512_loadu_pd(alpha + i);
        __mmask8 ok = _mm512_cmp_pd_mask(a, one, _CMP_GE_OQ)
                      & _mm512_cmp_pd_mask(a, top, _CMP_LT_OQ);
        outside |= ok != 0xFF;
        a = _mm512_mask_blend_pd(ok, one, a);
        __m512i bits = _mm512_castpd_si512(a);
        __m512i piece = _mm512_sub_epi64(_mm512_srli_epi64(bits, 52 - TABLE_SPLIT_BITS), bias);
        __m512d k = _mm512_sub_pd(
            _mm512_castsi512_pd(_mm512_or_si512(_mm512_and_si512(piece, low), two52_bits)),
            two52);
        __m512d f = _mm512_castsi512_pd(
            _mm512_or_si512(_mm512_and_si512(bits, mantissa), exponent_one));
        __m512d z = _mm512_sub_pd(_mm512_mul_pd(scale, f),
                                  _mm512_add_pd(_mm512_add_pd(scale, _mm512_mul_pd(two, k)),
                                                one));
        __m512i at = _mm512_sub_epi64(_mm512_slli_epi64(piece, 5), _mm512_slli_epi64(piece, 1));
        __m512d l = poly_avx512(table, at, z);
        __m512d kk = poly_avx512(table + TABLE_STRIDE, at, z);
        __m512d ee = poly_avx512(table + 2 * TABLE_STRIDE, at, z);
        __mmask8 is_one = _mm512_cmp_pd_mask(a, one, _CMP_EQ_OQ);
        l = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(l, one, _CMP_GT_OQ), one, l);
        _mm512_storeu_pd(lam + i, _mm512_mask_blend_pd(is_one, l, one));
        _mm512_storeu_pd(K + i, _mm512_mask_blend_pd(is_one, kk, pi_2));
        _mm512_storeu_pd(E + i, _mm512_mask_blend_pd(is_one, ee, pi_2));
    }
    return table_avx2(n - i, alpha + i, lam + i, K + i, E + i) | outside;
}

#ifndef TABLE_AVX512
#define TABLE_AVX512 table_avx512
#endif
#else
#define HAVE_AVX2_TABLE 0
#endif

ptrdiff_t
hertz_ellipse_table(const double *alpha, ptrdiff_t n, double *lam, double *K, double *E)
{
    int outside = 0;
#if HAVE_AVX2_TABLE
    int path = hertz_path();
    if (path == HERTZ_PATH_AVX512) {
        outside = TABLE_AVX512(n, alpha, lam, K, E);
    }
    else if (path == HERTZ_PATH_AVX2) {
        outside = table_avx2(n, alpha, lam, K, E);
    }
    else
#endif
    {
#if HAVE_PAIR_TABLE
        outside = table_pairs(n, alpha, lam, K, E);
#else
        for (ptrdiff_t i = 0; i < n; ++i) {
            int ok = alpha[i] >= 1.0 && alpha[i] < TABLE_TOP;
            outside |= !ok;
            if (ok) {
                table_one(alpha[i], lam + i, K + i, E + i);
            }
        }
#endif
    }
    if (!outside) {
        return -1;
    }
    for (ptrdiff_t i = 0; i < n; ++i) {
        if (!(alpha[i] >= 1.0 && alpha[i] < TABLE_TOP)) {
            double m;
            ptrdiff_t bad = hertz_ellipse_block(alpha + i, 1, 1, lam + i, &m, K + i, E + i);
            if (bad >= 0) {
                return i;
            }
        }
    }
    return -1;
}
