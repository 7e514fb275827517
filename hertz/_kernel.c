/*
 * hertz._kernel -- the contact-ellipse solver.
 *
 * Problem (Hokada, Iizuka & Takada, arXiv 2508.06967, eq. (alpha_lambda_relation)):
 * given the curvature ratio alpha = rho_x / rho_y >= 1, find the elliptic
 * parameter m = 1 - 1/lambda^2 (p = 1 - m = 1/lambda^2) with
 *
 *     alpha = B(m) / (p D(m)),                                          (1)
 *
 * where B = (E - pK)/m and D = (K - E)/m are Fukushima's associate complete
 * elliptic integrals (K = B + D, E = B + pD).  Eq. (1) is the seed's
 * F(nu) = (alpha + 1)(1 - nu)K - [1 + alpha(1 - nu)]E = 0 divided by its
 * trivial root: F = m (alpha p D - B).
 *
 * The seed's Bailey (Halley) step, eq. (recurrence),
 *
 *     x_{n+1} = x_n - f / (f' - f f'' / (2 f')),                        (2)
 *
 * is applied to f(x) = ln(B / (p D)) - ln(alpha) in the variable x = ln p
 * instead of F(nu).  Deflating the root m = 0, taking logarithms and using
 * x instead of nu keep every quantity well scaled from alpha = 1 + 2^-52
 * (m ~ 3e-16) to alpha ~ 1e19 (p ~ 1e-21): f' lies in [-1, -3/4], so the
 * step never divides by a vanishing derivative (the seed's F' ~ (alpha-1)pi/4
 * and its 0/0 in F'' near alpha = 1 are gone).
 *
 * Start: a piecewise polynomial in alpha (generated, see
 * tools/generate_coefficients.py; the piece is read from the bits of alpha,
 * no logarithm) accurate to 6e-8 in x, so that one step of (2) leaves an
 * error far below the double rounding.  B and D are evaluated
 * once, at the start, by our own routine (two Landen steps and a short
 * Maclaurin series for m <= 0.95, the logarithmic series in p above), which has
 * no cancellation anywhere; K and E at the root are then obtained from a
 * second-order Taylor update of D instead of a second evaluation.
 *
 * For alpha >= 2^START_BINADES (1.8e19) the root satisfies
 * lambda^2 = alpha (L - 1), L = ln(4 lambda), to a relative O(1/alpha) and is
 * solved directly.  alpha < 1 uses lambda(alpha) = 1/lambda(1/alpha); 1/alpha
 * only picks the start, the residual of (2) uses alpha itself.
 *
 * Pure C: the numpy binding is in _ufuncs.c, the contact formulas built on
 * this solver in _contact_kernel.c.
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "_coefficients.h"
#include "_kernel.h"

/* The block functions (associate_integrals, solve_block) are compiled once per
 * code path of this build (HERTZ_VERSIONS in _kernel.h: AVX-512, AVX2 and
 * plain on x86-64 Linux, plain elsewhere) and the path is chosen at run time
 * (hertz_path); the vectorised stages then take four or eight elements at a
 * time.  Elementwise operations round the same way at any vector width (and
 * -ffp-contract=off forbids fused multiply-adds), so all give the same bits. */

/* The processor's best path (-1: not asked yet) and the limit set by
 * hertz_set_path; both plain ints, written with the same value by any thread
 * that races on the first call. */
static int best_path = -1;
static int path_limit = HERTZ_PATH_AVX512;

static int
detect_path(void)
{
#if HERTZ_X86_PATHS
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) {
        return HERTZ_PATH_PLAIN;
    }
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq")
        && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw")) {
        return HERTZ_PATH_AVX512;
    }
    return HERTZ_PATH_AVX2;
#else
    return HERTZ_PATH_PLAIN;
#endif
}

int
hertz_path(void)
{
    if (best_path < 0) {
        best_path = detect_path();
    }
    return best_path < path_limit ? best_path : path_limit;
}

int
hertz_set_path(int limit)
{
    path_limit = limit < HERTZ_PATH_PLAIN ? HERTZ_PATH_PLAIN
                                          : (limit > HERTZ_PATH_AVX512 ? HERTZ_PATH_AVX512 : limit);
    return hertz_path();
}

int
hertz_paths_built(void)
{
    return HERTZ_X86_PATHS ? (1 << HERTZ_PATH_PLAIN) | (1 << HERTZ_PATH_AVX2)
                                 | (1 << HERTZ_PATH_AVX512)
                           : 1 << HERTZ_PATH_PLAIN;
}

int
hertz_simd(int enable)
{
    if (enable >= 0) {
        hertz_set_path(enable ? HERTZ_PATH_AVX512 : HERTZ_PATH_PLAIN);
    }
    return hertz_path() != HERTZ_PATH_PLAIN;
}

#if START_DEGREE != 5
#error "the start is evaluated as a degree-5 polynomial"
#endif

HERTZ_INLINE double
horner(const double *c, int degree, double x)
{
    double r = c[degree];
    HERTZ_UNROLL(8)
    for (int i = degree - 1; i >= 0; --i) {
        r = r * x + c[i];
    }
    return r;
}

/* B(m), D(m) and V(m) = (B - pD)/m = 2p dD/dm for 0 < m < 1, p = 1 - m, at
 * n <= BLOCK points.  m and p are passed separately so that each can carry
 * full relative precision (m near 0, p near 0). */
#define BLOCK 64
#if BLOCK != HERTZ_BLOCK
#error "BLOCK and HERTZ_BLOCK must agree"
#endif

#define ASSOC_PARAMETERS                                                          \
    ptrdiff_t n, const double *restrict m, const double *restrict p, double *restrict B, \
        double *restrict D, double *restrict V
#define ASSOC_NAMES n, m, p, B, D, V

HERTZ_INLINE int
associate_integrals_body(ASSOC_PARAMETERS, const int fused)
{
    (void)fused;
    double l1[BLOCK];
    /* DLMF 19.12.1-2 rearranged, L = ln(4/sqrt(p)):
     *   mD = Q_D (L - 1) + P_D,  mB = Q_B L + P_B  (valid for p < P_LOG_MAX).
     * Evaluated for every element (the loop vectorises); the Landen branch
     * below overwrites the elements with m <= M_LANDEN_MAX. */
    for (ptrdiff_t i = 0; i < n; ++i) {
        l1[i] = LN4_MINUS_1 - 0.5 * log(p[i]);
    }
    for (ptrdiff_t i = 0; i < n; ++i) {
        double x = p[i];
        double md = horner(BD_LOG_QD, LOG_DEGREE, x) * l1[i] + horner(BD_LOG_PD, LOG_DEGREE, x);
        double mb = horner(BD_LOG_QB, LOG_DEGREE, x) * (l1[i] + 1.0)
                    + horner(BD_LOG_PB, LOG_DEGREE, x);
        double im = 1.0 / m[i];
        D[i] = md * im;
        B[i] = mb * im;
        V[i] = (mb - x * md) * im * im;
    }
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        if (m[i] > M_LANDEN_MAX) {
            continue;
        }
        /* Descending Landen transformation, k' = sqrt(p), k1 = (1 - k')/(1 + k'):
         *   D(m) = (B1 + (1 + k1) D1)/(1 + k'),  B(m) = (B1 + (1 - k1) D1)/(1 + k'),
         *   (D - B)/m = 2 D1 / (1 + k')^3,
         * with B1, D1 at m1 = k1^2 and p1 = 4k'/(1 + k')^2.  Every term is
         * positive: no cancellation.  Two steps take m <= 0.95 to m2 < 0.017. */
        double kp = sqrt(p[i]);
        double s1 = 1.0 + kp;
        double k1 = m[i] / (s1 * s1);
        double s2 = 1.0 + 2.0 * sqrt(kp) / s1;
        double k2 = k1 * k1 / (s2 * s2);
        double m2 = k2 * k2;
        double b2 = horner(BD_SMALL_B, SMALL_DEGREE, m2);
        double d2 = horner(BD_SMALL_D, SMALL_DEGREE, m2);
        double d1 = (b2 + (1.0 + k2) * d2) / s2;
        double b1 = (b2 + (1.0 - k2) * d2) / s2;
        double is1 = 1.0 / s1;
        D[i] = (b1 + (1.0 + k1) * d1) * is1;
        B[i] = (b1 + (1.0 - k1) * d1) * is1;
        V[i] = D[i] - 2.0 * d1 * is1 * is1 * is1;
    }
    return 0;
}
HERTZ_VERSIONS(int, associate_integrals, ASSOC_PARAMETERS, ASSOC_NAMES)

/* alpha = 1, alpha = inf, and alpha' = max(alpha, 1/alpha) >= 2^START_BINADES,
 * where lambda^2 = alpha' (L - 1), L = ln 4 + ln lambda (relative error
 * O(1/alpha') < 1e-19); K = L and E = 1 to the same order, m rounds to 1. */
static void
solve_closed_form(double alpha, int flip, double *lam, double *m, double *K, double *E)
{
    if (alpha == 1.0) {
        *lam = 1.0;
        *m = 0.0;
        *K = *E = PI_2;
        return;
    }
    *m = 1.0;
    *E = 1.0;
    if (isinf(alpha)) {
        *lam = INFINITY;
        *K = INFINITY;
        return;
    }
    double t = flip ? -log(alpha) : log(alpha);
    double L = LN4 + 0.5 * (t + log(0.5 * t));
    for (int i = 0; i < 3; ++i) {
        double f = L - LN4 - 0.5 * (t + log(L - 1.0));
        L -= f / (1.0 - 0.5 / (L - 1.0));
    }
    *lam = flip ? sqrt(alpha) / sqrt(L - 1.0) : sqrt(alpha) * sqrt(L - 1.0);
    *K = L;
}

/* Solve n <= BLOCK elements.  Returns -1, or the index of the first alpha
 * that is not a positive number (outputs are then incomplete).  The block is
 * processed one stage at a time, so that the processor overlaps independent
 * elements (and the compiler vectorises the branch-free stages) instead of
 * waiting on the dependency chain of one. */
#define SOLVE_PARAMETERS                                                         \
    const double *alpha, ptrdiff_t n, int iterations, double *lam, double *mo, double *ko, \
        double *eo
#define SOLVE_NAMES alpha, n, iterations, lam, mo, ko, eo

HERTZ_INLINE ptrdiff_t
solve_block_body(SOLVE_PARAMETERS, const int fused)
{
    (void)fused;
    double m[BLOCK], p[BLOCK], B[BLOCK], D[BLOCK], V[BLOCK], dm[BLOCK], inv_m[BLOCK];
    unsigned char done[BLOCK];

    /* iterations = 0 and lambda alone: the start is the answer (faster path). */
    int start_only = iterations == 0 && !mo && !ko && !eo;

    /* Stage 1: checks, closed-form cases, start. */
    for (ptrdiff_t i = 0; i < n; ++i) {
        double a = alpha[i];
        if (!(a > 0.0)) {
            return i;
        }
        int flip = a < 1.0;
        double ap = flip ? 1.0 / a : a; /* alpha' = max(alpha, 1/alpha) */
        uint64_t bits;
        memcpy(&bits, &ap, sizeof bits);
        int e = (int)(bits >> 52) - 1023; /* ap = 2^e f, f in [1, 2) */
        if (e >= START_BINADES || a == 1.0) {
            double mi, K, E;
            solve_closed_form(a, flip, &lam[i], &mi, &K, &E);
            if (mo) mo[i] = mi;
            if (ko) ko[i] = K;
            if (eo) eo[i] = E;
            done[i] = 1;
            m[i] = p[i] = 0.5; /* placeholders, never output */
            dm[i] = 0.0;
            continue;
        }
        done[i] = 0;
        /* h = lambda^2/alpha' = 1 + (alpha' - 1) r(alpha'), then
         * p = 1/(alpha' h) and m = (alpha' h - 1) p = eps (1 + alpha' r) p with
         * eps = alpha' - 1 formed exactly from alpha, so that m keeps its
         * relative accuracy as alpha -> 1. */
        int k = (int)((bits >> 50) & 3);
        uint64_t fbits = (bits & 0x000FFFFFFFFFFFFFull) | 0x3FF0000000000000ull;
        double f;
        memcpy(&f, &fbits, sizeof f);
        const double *c = START_R[START_SPLIT * e + k];
        double z = 8.0 * f - (9.0 + 2.0 * k), z2 = z * z;
        /* degree 5 by Estrin's scheme: a shorter dependency chain than Horner */
        double r = (c[0] + c[1] * z) + z2 * ((c[2] + c[3] * z) + z2 * (c[4] + c[5] * z));
        double eps = flip ? (1.0 - a) * ap : a - 1.0;
        double h = 1.0 + eps * r;
        if (start_only) {
            lam[i] = flip ? sqrt(a / h) : sqrt(ap * h);
            continue;
        }
        p[i] = 1.0 / (ap * h);
        m[i] = eps * (1.0 + ap * r) * p[i];
    }
    if (start_only) {
        return -1;
    }

    for (int it = 0; it < iterations; ++it) {
        /* Stage 2: B, D, V at the current point. */
        associate_integrals_body(n, m, p, B, D, V, fused);
        /* Stage 3: one Bailey step, eq. (2), on f(x) = ln(B/(p D alpha')). */
        for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
            double a = alpha[i], mi = m[i], pi = p[i], b = B[i], d = D[i], v = V[i];
            int flip = a < 1.0;
            /* w = B/(p D alpha') - 1, for small m from R - 1 = m V/(p D).
             * All candidates are computed and then selected, so that the
             * loop has no branches and vectorises. */
            double pd = pi * d;
            double den = flip ? pd : a * pd;
            double num_small = flip ? mi * v * a - (1.0 - a) * pd : mi * v - (a - 1.0) * pd;
            double num_large = (flip ? b * a : b) - den;
            double num = mi <= M_LANDEN_MAX ? num_small : num_large;
            double w = num / den;
            /* |w| < 1e-7 from the start (6e-8 in x): three terms of log1p. */
            double phi = w * (1.0 - w * (0.5 - w * (1.0 / 3.0)));
            /* f' = s and f'' = s2 in x = ln p, from dB/dm = (D - B)/(2m) and
             * dD/dm = V/(2p); they only scale the small step. */
            double rbdm = 1.0 / (b * d * mi);
            double s1 = 0.5 * (v * (b + pd) - pd * d) * rbdm * mi; /* f' + 1 */
            double s = s1 - 1.0;
            double s2 = 0.5 * (b * b * s1 + s * pd * d + 2.0 * pi * s1 * b * d) * rbdm;
            double step = 2.0 * s * phi / (2.0 * s * s - phi * s2);
            /* p (1 - exp(-step)), |step| < 1e-7 */
            double dmi = pi * step * (1.0 - 0.5 * step * (1.0 - step * (1.0 / 3.0)));
            double h = done[i] ? 0.0 : dmi;
            dm[i] = h;
            inv_m[i] = rbdm * b * d;
            m[i] = mi + h;
            p[i] = pi - h;
        }
    }

    if (iterations == 0 && (ko || eo)) {
        associate_integrals_body(n, m, p, B, D, V, fused);
    }

    /* Stage 4: outputs (elements solved in stage 1 keep their values). */
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        double mi = m[i], pi = p[i];
        double kp = sqrt(pi);
        double near_one = 1.0 + mi / (kp * (1.0 + kp)); /* keeps lambda - 1 accurate */
        double far = sqrt(1.0 / pi);
        double l = alpha[i] < 1.0 ? kp : (mi < 0.5 ? near_one : far);
        lam[i] = done[i] ? lam[i] : l;
    }
    if (mo) {
        for (ptrdiff_t i = 0; i < n; ++i) {
            mo[i] = done[i] ? mo[i] : m[i];
        }
    }
    if (!ko && !eo) {
        return -1;
    }
    /* K, E at the root come from D, Taylor-updated to second order about the
     * last evaluation point (dD/dm = V/(2p)), and eq. (1): B = alpha' p D, so
     * K = D (1 + alpha' p), E = p D (1 + alpha').  Without a step (iterations
     * = 0) they are those of the start. */
    double K[BLOCK], E[BLOCK];
    if (iterations == 0) {
        for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
            K[i] = B[i] + D[i];
            E[i] = B[i] + p[i] * D[i];
        }
    }
    else {
        for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
            double a = alpha[i], pi = p[i], h = dm[i], d = D[i], v = V[i];
            double p0 = pi + h, ip0 = 1.0 / p0;
            double d1 = 0.5 * v * ip0;
            double d2 = 0.5 * (1.5 * p0 * d - 2.0 * p0 * v + (m[i] - h) * v) * ip0 * ip0
                        * inv_m[i];
            double droot = d + h * (d1 + 0.5 * h * d2);
            double ia = 1.0 / a;
            int flip = a < 1.0;
            K[i] = flip ? droot * (1.0 + pi * ia) : droot * (1.0 + a * pi);
            E[i] = flip ? pi * droot * (1.0 + a) * ia : pi * droot * (1.0 + a);
        }
    }
    for (ptrdiff_t i = 0; i < n; ++i) {
        if (ko) ko[i] = done[i] ? ko[i] : K[i];
        if (eo) eo[i] = done[i] ? eo[i] : E[i];
    }
    return -1;
}
HERTZ_VERSIONS(ptrdiff_t, solve_block, SOLVE_PARAMETERS, SOLVE_NAMES)

static ptrdiff_t
solve_block(SOLVE_PARAMETERS)
{
    return HERTZ_PICK(solve_block)(SOLVE_NAMES);
}

#if HERTZ_X86_PATHS
#include <immintrin.h>
#define HAVE_AVX2_START 1

/* The start-only path (iterations = 0, lambda alone) four elements at a time
 * with AVX2 gathers from START_R: the arithmetic of stage 1 of solve_block in
 * the same order (no FMA is enabled here, and -ffp-contract=off), so the
 * results are the same bits.  A group of four with an element outside
 * 1 <= alpha < 2^64 (alpha < 1, closed forms, bad input) goes through
 * solve_block instead.  Returns -1 or the index of the first bad alpha. */
__attribute__((target("avx2"))) static ptrdiff_t
start_only_avx2(const double *alpha, ptrdiff_t n, double *lam)
{
    const __m256d one = _mm256_set1_pd(1.0), top = _mm256_set1_pd(0x1p64);
    const __m256d two = _mm256_set1_pd(2.0), eight = _mm256_set1_pd(8.0);
    const __m256d nine = _mm256_set1_pd(9.0), two52 = _mm256_set1_pd(0x1p52);
    const __m256i mantissa = _mm256_set1_epi64x(0x000FFFFFFFFFFFFFll);
    const __m256i exponent_one = _mm256_set1_epi64x(0x3FF0000000000000ll);
    const __m256i bias = _mm256_set1_epi64x(4 * 1023), three = _mm256_set1_epi64x(3);
    const __m256i two52_bits = _mm256_set1_epi64x(0x4330000000000000ll);
    const double *table = &START_R[0][0];
    ptrdiff_t i = 0;
    for (; i + 4 <= n; i += 4) {
        __m256d a = _mm256_loadu_pd(alpha + i);
        __m256d plain = _mm256_and_pd(_mm256_cmp_pd(a, one, _CMP_GE_OQ),
                                      _mm256_cmp_pd(a, top, _CMP_LT_OQ));
        if (_mm256_movemask_pd(plain) != 0xF) {
            ptrdiff_t r = solve_block(alpha + i, 4, 0, lam + i, NULL, NULL, NULL);
            if (r >= 0) {
                return i + r;
            }
            continue;
        }
        __m256i bits = _mm256_castpd_si256(a);
        __m256i row = _mm256_sub_epi64(_mm256_srli_epi64(bits, 50), bias); /* 4 e + k */
        /* k = row & 3 as a double, exactly: (2^52 + k) - 2^52 */
        __m256d k = _mm256_sub_pd(
            _mm256_castsi256_pd(_mm256_or_si256(_mm256_and_si256(row, three), two52_bits)),
            two52);
        __m256d f = _mm256_castsi256_pd(
            _mm256_or_si256(_mm256_and_si256(bits, mantissa), exponent_one));
        __m256d z = _mm256_sub_pd(_mm256_mul_pd(eight, f),
                                  _mm256_add_pd(nine, _mm256_mul_pd(two, k)));
        __m256d z2 = _mm256_mul_pd(z, z);
        __m256i at = _mm256_add_epi64(_mm256_slli_epi64(row, 2), _mm256_slli_epi64(row, 1));
        __m256d c0 = _mm256_i64gather_pd(table, at, 8);
        __m256d c1 = _mm256_i64gather_pd(table + 1, at, 8);
        __m256d c2 = _mm256_i64gather_pd(table + 2, at, 8);
        __m256d c3 = _mm256_i64gather_pd(table + 3, at, 8);
        __m256d c4 = _mm256_i64gather_pd(table + 4, at, 8);
        __m256d c5 = _mm256_i64gather_pd(table + 5, at, 8);
        __m256d r = _mm256_add_pd(
            _mm256_add_pd(c0, _mm256_mul_pd(c1, z)),
            _mm256_mul_pd(z2, _mm256_add_pd(_mm256_add_pd(c2, _mm256_mul_pd(c3, z)),
                                            _mm256_mul_pd(z2, _mm256_add_pd(
                                                                  c4, _mm256_mul_pd(c5, z))))));
        __m256d h = _mm256_add_pd(one, _mm256_mul_pd(_mm256_sub_pd(a, one), r));
        _mm256_storeu_pd(lam + i, _mm256_sqrt_pd(_mm256_mul_pd(a, h)));
    }
    if (i < n) {
        ptrdiff_t r = solve_block(alpha + i, n - i, 0, lam + i, NULL, NULL, NULL);
        if (r >= 0) {
            return i + r;
        }
    }
    return -1;
}

#else
#define HAVE_AVX2_START 0
#endif

/* ------------------------------------------------------------- entry points */

ptrdiff_t
hertz_ellipse_block(const double *alpha, ptrdiff_t n, int iterations,
                    double *lam, double *m, double *K, double *E)
{
    return solve_block(alpha, n, iterations, lam, m, K, E);
}

ptrdiff_t
hertz_ellipse_solve(const double *alpha, ptrdiff_t n, int iterations,
                    double *lam, double *m, double *K, double *E)
{
#if HAVE_AVX2_START
    if (iterations == 0 && !m && !K && !E && hertz_path() != HERTZ_PATH_PLAIN) {
        return start_only_avx2(alpha, n, lam);
    }
#endif
    for (ptrdiff_t i = 0; i < n; i += BLOCK) {
        ptrdiff_t len = n - i < BLOCK ? n - i : BLOCK;
        ptrdiff_t r = solve_block(alpha + i, len, iterations, lam + i, m ? m + i : NULL,
                                  K ? K + i : NULL, E ? E + i : NULL);
        if (r >= 0) {
            return i + r;
        }
    }
    return -1;
}

void
hertz_associate_integrals(ptrdiff_t n, const double *m, const double *p,
                          double *B, double *D, double *V)
{
    for (ptrdiff_t i = 0; i < n; i += BLOCK) {
        ptrdiff_t len = n - i < BLOCK ? n - i : BLOCK;
        HERTZ_PICK(associate_integrals)(len, m + i, p + i, B + i, D + i, V + i);
    }
}
