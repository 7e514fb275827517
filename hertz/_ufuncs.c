/*
 * hertz._ufuncs -- the numpy binding of the scalar C kernels (_kernel.c: the
 * ellipse solver; _contact_kernel.c: the contact formulas; _stress_kernel.c:
 * the stresses below the contact; _tangential_kernel.c: the no-slip
 * tangential stiffness and the Cattaneo-Mindlin partial slip).
 *
 * Every elementwise function is a numpy ufunc with one float64 loop
 * registered through the ArrayMethod API (numpy >= 2.0), so that a loop can
 * stop with a ValueError that numpy raises (and dask raises at compute
 * time), and a promoter that casts any real input (integers, float16/32/64,
 * long double, Python numbers) to float64 and rejects bool, complex and the
 * rest with a TypeError.  Broadcasting, out=, and __array_ufunc__ dispatch
 * come from numpy.  The loops copy strided operands through blocks of
 * HERTZ_BLOCK elements, the unit the kernels work in.
 *
 * The scalar entry points (contact, line_contact) take Python floats and
 * return tuples: a one-contact call then costs a few hundred ns.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <structmember.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#define NPY_NO_DEPRECATED_API NPY_2_0_API_VERSION
#define NPY_TARGET_VERSION NPY_2_0_API_VERSION
#include <numpy/arrayobject.h>
#include <numpy/dtype_api.h>
#include <numpy/ufuncobject.h>

#include "_contact_kernel.h"
#include "_kernel.h"
#include "_load_path_kernel.h"
#include "_stress_kernel.h"
#include "_tangential_kernel.h"

#define MAXARGS 32

/* ------------------------------------------------------------------ errors */

static const char *const geometry_names[HERTZ_NGEOMETRY] = {
    "body1.Rx", "body1.Ry", "body2.Rx", "body2.Ry", "angle", "body1.E", "body1.nu",
    "body2.E", "body2.nu"};
static const char *const value_names[] = {"load", "approach", "p0", "load_per_length"};
static const char *const value_units[] = {"N", "m", "Pa", "N/m"};

/* repr() of a float, as a new C string (PyMem_Free it), or NULL. */
static char *
repr(double x)
{
    return PyOS_double_to_string(x, 'r', 0, Py_DTSF_ADD_DOT_0, NULL);
}

static char *
short_text(double x)
{
    return PyOS_double_to_string(x, 'g', 6, 0, NULL);
}

/* m 2^e to 6 significant digits, also beyond the double range (a curvature
 * of 2e+323 1/m); PyMem-allocated. */
static char *
scaled_text(hertz_scaled x)
{
    int e = x.e > 4000.0 ? 4000 : (x.e < -4000.0 ? -4000 : (int)x.e);
    double v = ldexp(x.m, e);
    if (x.m == 0.0 || !isfinite(x.m) || (isfinite(v) && fabs(v) >= DBL_MIN)) {
        return short_text(v);
    }
    double l = log10(fabs(x.m)) + e * log10(2.0), p = floor(l);
    char *digits = short_text(copysign(pow(10.0, l - p), x.m));
    if (!digits) {
        return NULL;
    }
    if (strncmp(digits + (x.m < 0.0), "10", 2) == 0) { /* 9.9999996 rounded up */
        PyMem_Free(digits);
        digits = short_text(copysign(1.0, x.m));
        p += 1.0;
        if (!digits) {
            return NULL;
        }
    }
    char *text = PyMem_Malloc(strlen(digits) + 16);
    if (text) {
        sprintf(text, "%se%+d", digits, (int)p);
    }
    PyMem_Free(digits);
    return text;
}

/* Set the ValueError of error code `code` for one element: `in` holds its
 * geometry inputs (point-contact numbering), `value` its load, approach or
 * p0 (`what` indexes value_names), rho_x and rho_y its relative curvatures.
 * Must hold the GIL. */
static void
set_error(int code, const double *in, double value, int what, hertz_scaled rho_x,
          hertz_scaled rho_y)
{
    char *v = NULL, *w = NULL;
    if (code >= 1 && code <= HERTZ_NGEOMETRY) {
        int k = code - 1;
        const char *name = geometry_names[k];
        v = repr(in[k]);
        if (k == HERTZ_ANGLE) {
            PyErr_Format(PyExc_ValueError, "angle must be a finite angle in rad, got %s", v);
        }
        else if (k == HERTZ_E1 || k == HERTZ_E2) {
            PyErr_Format(PyExc_ValueError,
                         "%s must be a positive, finite Young's modulus in Pa, got %s", name, v);
        }
        else if (k == HERTZ_NU1 || k == HERTZ_NU2) {
            PyErr_Format(PyExc_ValueError, "%s must be a Poisson's ratio in (-1, 0.5], got %s",
                         name, v);
        }
        else {
            PyErr_Format(PyExc_ValueError,
                         "%s must be a nonzero radius in m (positive convex, negative concave, "
                         "inf flat), got %s", name, v);
        }
    }
    else if (code == HERTZ_BAD_VALUE) {
        v = repr(value);
        PyErr_Format(PyExc_ValueError, "%s must be a finite value >= 0 in %s, got %s",
                     value_names[what], value_units[what], v);
    }
    else if (code == HERTZ_LINE) {
        v = scaled_text(rho_x);
        PyErr_Format(PyExc_ValueError,
                     "the bodies make a line contact (relative curvature %s 1/m across, 0 "
                     "along the line: parallel cylinders or a cylinder on a plane); use "
                     "hertz.line_contact(body1, body2, load_per_length)", v);
    }
    else if (code == HERTZ_FLAT) {
        PyErr_SetString(PyExc_ValueError,
                        "no Hertz point contact: the relative curvature is zero in every "
                        "direction (plane on plane, or surfaces that fit each other exactly)");
    }
    else if (code == HERTZ_CONFORM) {
        v = scaled_text(rho_x);
        w = scaled_text(rho_y);
        PyErr_Format(PyExc_ValueError,
                     "no Hertz point contact: principal relative curvatures %s and %s 1/m "
                     "must both be positive; a concave surface that conforms more closely "
                     "than the convex one touches it away from a single point", v, w);
    }
    else if (code == HERTZ_LIMIT) {
        v = scaled_text(rho_x);
        w = scaled_text(rho_y);
        PyErr_Format(PyExc_ValueError,
                     "the bodies are within rounding of a line contact: the principal "
                     "relative curvatures %s and %s 1/m have a ratio rho_x / rho_y beyond "
                     "what a double resolves (about 1e307); treat it as a line contact "
                     "(hertz.line_contact)", v, w);
    }
    else if (code == HERTZ_NOT_LINE) {
        v = scaled_text(rho_x);
        w = scaled_text(rho_y);
        PyErr_Format(PyExc_ValueError,
                     "not a line contact: the principal relative curvatures are %s and %s "
                     "1/m; a line contact needs one of them 0 and the other positive (use "
                     "hertz.contact for a point contact)", v, w);
    }
    else {
        PyErr_Format(PyExc_SystemError, "hertz: unknown error code %d", code);
    }
    PyMem_Free(v);
    PyMem_Free(w);
}

static void
set_error_nogil(int code, const double *in, double value, int what, hertz_scaled rho_x,
                hertz_scaled rho_y)
{
    PyGILState_STATE state = PyGILState_Ensure();
    set_error(code, in, value, what, rho_x, rho_y);
    PyGILState_Release(state);
}

/* ------------------------------------------------------ block kernels */

/* A block function computes n <= HERTZ_BLOCK elements from contiguous
 * inputs into contiguous outputs.  It returns 0, or sets the Python error
 * (taking the GIL) and returns -1. */
typedef int (*block_fn)(ptrdiff_t n, const double *const *in, double *const *out, int variant);

static int
ellipticity_block(ptrdiff_t n, const double *const *in, double *const *out, int iterations)
{
    ptrdiff_t bad = hertz_ellipse_solve(in[0], n, iterations, out[0], NULL, NULL, NULL);
    if (bad >= 0) {
        PyGILState_STATE state = PyGILState_Ensure();
        char *v = repr(in[0][bad]);
        PyErr_Format(PyExc_ValueError,
                     "alpha must be a positive number (rho_x / rho_y > 0), got %s", v);
        PyMem_Free(v);
        PyGILState_Release(state);
        return -1;
    }
    return 0;
}

static int
ellipse_block(ptrdiff_t n, const double *const *in, double *const *out, int iterations)
{
    ptrdiff_t bad = hertz_ellipse_solve(in[0], n, iterations, out[0], out[1], out[2], out[3]);
    if (bad >= 0) {
        PyGILState_STATE state = PyGILState_Ensure();
        char *v = repr(in[0][bad]);
        PyErr_Format(PyExc_ValueError,
                     "alpha must be a positive number (rho_x / rho_y > 0), got %s", v);
        PyMem_Free(v);
        PyGILState_Release(state);
        return -1;
    }
    return 0;
}

static int
geometry_error(int code, ptrdiff_t bad, const double *const *in, double value, int what,
               hertz_scaled rho_x, hertz_scaled rho_y)
{
    double row[HERTZ_NGEOMETRY];
    for (int k = 0; k < HERTZ_NGEOMETRY; ++k) {
        row[k] = in[k][bad];
    }
    set_error_nogil(code, row, value, what, rho_x, rho_y);
    return -1;
}

/* inputs: 9 geometry + value; outputs: a, b, load, p0, delta, stiffness. */
static int
contact_block(ptrdiff_t n, const double *const *in, double *const *out, int mode)
{
    ptrdiff_t bad = 0;
    hertz_scaled rho_x = {0.0, 0.0}, rho_y = {0.0, 0.0};
    int code = hertz_contact_block(n, in, mode, out, &bad, &rho_x, &rho_y);
    if (code != HERTZ_OK) {
        return geometry_error(code, bad, in, in[HERTZ_NGEOMETRY][bad], mode, rho_x, rho_y);
    }
    return 0;
}

/* The fields of the geometry alone: inputs 9 geometry; outputs lambda,
 * alpha, m, K, E, e_star, rho_x, rho_y, theta, and with `coefficients` the
 * load-pass coefficients cb, cd, cp, cs as (m, e) pairs. */
#define GEOMETRY_NOUT (HERTZ_NFIELDS + HERTZ_NCOEFFICIENTS - 1)

static int
geometry_block(ptrdiff_t n, const double *const *in, double *const *out, int coefficients)
{
    double fields[HERTZ_NFIELDS * HERTZ_BLOCK], cbuf[HERTZ_NCOEFFICIENTS][HERTZ_BLOCK];
    double *c[HERTZ_NCOEFFICIENTS];
    for (int k = 0; k < HERTZ_NCOEFFICIENTS; ++k) {
        c[k] = coefficients && k > 0 ? out[HERTZ_NFIELDS + k - 1] : cbuf[k];
    }
    ptrdiff_t bad = 0;
    hertz_scaled rho_x = {0.0, 0.0}, rho_y = {0.0, 0.0};
    int code = hertz_geometry_block(n, in, c, fields, &bad, &rho_x, &rho_y);
    if (code != HERTZ_OK) {
        return geometry_error(code, bad, in, 0.0, 0, rho_x, rho_y);
    }
    for (int k = 0; k < HERTZ_NFIELDS; ++k) {
        memcpy(out[k], fields + k * n, (size_t)n * sizeof(double));
    }
    return 0;
}

/* The load pass: inputs the coefficients (lambda first) and the value;
 * outputs a, b, load, p0, delta, stiffness. */
static int
given_block(ptrdiff_t n, const double *const *in, double *const *out, int mode)
{
    ptrdiff_t bad = 0;
    if (hertz_given_block(n, mode, in, in[HERTZ_NCOEFFICIENTS], out, &bad) != HERTZ_OK) {
        hertz_scaled zero = {0.0, 0.0};
        set_error_nogil(HERTZ_BAD_VALUE, NULL, in[HERTZ_NCOEFFICIENTS][bad], mode, zero, zero);
        return -1;
    }
    return 0;
}

/* One contact, the same code as an array of them: returns the error code;
 * out = the HERTZ_NOUT fields. */
static int
contact_one(const double in[HERTZ_NGEOMETRY + 1], int mode, int with_fields,
            double out[HERTZ_NOUT], hertz_scaled *rho_x, hertz_scaled *rho_y)
{
    const double *ptr[HERTZ_NGEOMETRY + 1];
    for (int k = 0; k <= HERTZ_NGEOMETRY; ++k) {
        ptr[k] = in + k;
    }
    double *given[HERTZ_NGIVEN];
    for (int k = 0; k < HERTZ_NGIVEN; ++k) {
        given[k] = out + k;
    }
    ptrdiff_t bad = 0;
    int code = hertz_contact_block(1, ptr, mode, given, &bad, rho_x, rho_y);
    if (code == HERTZ_OK && with_fields) {
        double cbuf[HERTZ_NCOEFFICIENTS], *c[HERTZ_NCOEFFICIENTS];
        for (int k = 0; k < HERTZ_NCOEFFICIENTS; ++k) {
            c[k] = cbuf + k;
        }
        code = hertz_geometry_block(1, ptr, c, out + HERTZ_NGIVEN, &bad, rho_x, rho_y);
    }
    return code;
}

/* Error code of each element (0 where it is fine), for locating the first
 * bad element of an array after a loop has raised. inputs: 9 geometry +
 * value; output: the code. */
static int
contact_status_block(ptrdiff_t n, const double *const *in, double *const *out, int mode)
{
    for (ptrdiff_t i = 0; i < n; ++i) {
        double row[HERTZ_NGEOMETRY + 1], fields[HERTZ_NOUT];
        hertz_scaled rho_x, rho_y;
        for (int k = 0; k <= HERTZ_NGEOMETRY; ++k) {
            row[k] = in[k][i];
        }
        out[0][i] = contact_one(row, mode, 0, fields, &rho_x, &rho_y);
    }
    return 0;
}

/* inputs: r1x, r1y, r2x, r2y, E1, nu1, E2, nu2, load per length; outputs:
 * half_width, p0, e_star, rho, load per length. */
static int
line_block(ptrdiff_t n, const double *const *in, double *const *out, int status_only)
{
    for (ptrdiff_t i = 0; i < n; ++i) {
        double row[8], res[5];
        hertz_scaled rho_x, rho_y;
        for (int k = 0; k < 8; ++k) {
            row[k] = in[k][i];
        }
        int code = hertz_line_contact(row, in[8][i], res, &rho_x, &rho_y);
        if (status_only) {
            out[0][i] = code;
            continue;
        }
        if (code != HERTZ_OK) {
            double geo[HERTZ_NGEOMETRY] = {row[0], row[1], row[2], row[3], 0.0,
                                           row[4], row[5], row[6], row[7]};
            set_error_nogil(code, geo, in[8][i], 3, rho_x, rho_y);
            return -1;
        }
        for (int k = 0; k < 5; ++k) {
            out[k][i] = res[k];
        }
    }
    return 0;
}

/* The stress kernels: one element at a time; a nonzero code stops the loop
 * with a ValueError naming the argument. */
static int
stress_error(int code, const char *fn, const double *args, int nargs)
{
    static const char *const what[] = {
        "", "the semi-axes must be finite with a >= b > 0 and b/a >= 1e-70 (below that the "
        "contact is a line contact: use hertz.line_contact)",
        "nu must be a Poisson's ratio in (-1, 0.5]", "the point must have finite coordinates",
        "z must be a depth >= 0"};
    PyGILState_STATE state = PyGILState_Ensure();
    char text[512];
    int used = snprintf(text, sizeof text, "%s: %s, got (", fn,
                        code >= 1 && code <= 4 ? what[code] : "invalid input");
    for (int k = 0; k < nargs && used < (int)sizeof text; ++k) {
        used += snprintf(text + used, sizeof text - (size_t)used, "%s%.17g", k ? ", " : "",
                         args[k]);
    }
    PyErr_Format(PyExc_ValueError, "%s)", text);
    PyGILState_Release(state);
    return -1;
}

/* The four stress kernels behind one signature: args in, res out. */
static int
point_stress_one(const double *x, double *res)
{
    return hertz_point_stress(x[0], x[1], x[2], x[3], x[4], x[5], res);
}

static int
subsurface_one(const double *x, double *res)
{
    return hertz_subsurface(x[0], x[1], x[2], res);
}

static int
line_stress_one(const double *x, double *res)
{
    return hertz_line_stress(x[0], x[1], x[2], x[3], res);
}

static int
line_subsurface_one(const double *x, double *res)
{
    return hertz_line_subsurface(x[0], x[1], res);
}

static const struct {
    int (*fn)(const double *, double *);
    int nin, nout;
    const char *what;
} stress_kernels[] = {
    {point_stress_one, 6, 6, "stress (a, b, nu, x, y, z)"},
    {subsurface_one, 3, 10, "subsurface (a, b, nu)"},
    {line_stress_one, 4, 4, "line stress (b, nu, x, z)"},
    {line_subsurface_one, 2, 7, "line subsurface (b, nu)"},
};

/* variant: the index in stress_kernels. */
static int
stress_block(ptrdiff_t n, const double *const *in, double *const *out, int variant)
{
    int nin = stress_kernels[variant].nin, nout = stress_kernels[variant].nout;
    for (ptrdiff_t i = 0; i < n; ++i) {
        double args[6], res[12]; /* hertz_subsurface writes 12 (two reserved) */
        for (int k = 0; k < nin; ++k) {
            args[k] = in[k][i];
        }
        int code = stress_kernels[variant].fn(args, res);
        if (code) {
            return stress_error(code, stress_kernels[variant].what, args, nin);
        }
        for (int k = 0; k < nout; ++k) {
            out[k][i] = res[k];
        }
    }
    return 0;
}

/* The tangential kernels.  The error names the input and its value, in the
 * words of hertz/_tangential.py (which, for numpy input, checks the arrays
 * again for the index; dask blocks get it from hertz._interop.dask_map). */
static int
tangential_error(int code, const double *const *in, ptrdiff_t i, int stiffness_only)
{
    PyGILState_STATE state = PyGILState_Ensure();
    int direction = stiffness_only ? HERTZ_T_STIFFNESS_NIN - 1 : HERTZ_T_DIRECTION;
    char *v = NULL, *w = NULL;
    switch (code) {
    case HERTZ_T_BAD_MU:
        v = repr(in[HERTZ_T_MU][i]);
        PyErr_Format(PyExc_ValueError,
                     "mu must be a positive, finite coefficient of friction, got %s", v);
        break;
    case HERTZ_T_BAD_DIRECTION:
        v = repr(in[direction][i]);
        PyErr_Format(PyExc_ValueError, "direction must be a finite angle in rad, got %s", v);
        break;
    case HERTZ_T_BAD_LOAD:
        v = repr(in[HERTZ_T_LOAD][i]);
        PyErr_Format(PyExc_ValueError,
                     "contact.load must be positive for a tangential force (a contact without "
                     "normal load carries no tangential force), got %s", v);
        break;
    case HERTZ_T_BAD_FORCE:
        v = repr(in[HERTZ_T_FORCE][i]);
        PyErr_Format(PyExc_ValueError,
                     "force must be a non-negative, finite tangential force in N, got %s", v);
        break;
    case HERTZ_T_ABOVE_LIMIT:
        v = repr(in[HERTZ_T_MU][i] * in[HERTZ_T_LOAD][i]);
        w = repr(in[HERTZ_T_FORCE][i]);
        PyErr_Format(PyExc_ValueError,
                     "force must be at most mu * load = %s N (the limit of friction; beyond "
                     "it the contact slides as a whole), got %s", v, w);
        break;
    default:
        PyErr_Format(PyExc_SystemError, "hertz: unknown tangential error code %d", code);
    }
    PyMem_Free(v);
    PyMem_Free(w);
    PyGILState_Release(state);
    return -1;
}

/* inputs: K, alpha, lambda, a, nu1, nu2, E1, E2, direction; output: k. */
static int
tangential_stiffness_block(ptrdiff_t n, const double *const *in, double *const *out,
                           int variant)
{
    (void)variant;
    ptrdiff_t bad = 0;
    int code = hertz_tangential_stiffness_block(n, in, out[0], &bad);
    return code == HERTZ_T_OK ? 0 : tangential_error(code, in, bad, 1);
}

/* inputs: the HERTZ_T_NIN of _tangential_kernel.h; outputs: its HERTZ_T_NOUT. */
static int
partial_slip_block(ptrdiff_t n, const double *const *in, double *const *out, int variant)
{
    (void)variant;
    ptrdiff_t bad = 0;
    int code = hertz_partial_slip_block(n, in, out, &bad);
    return code == HERTZ_T_OK ? 0 : tangential_error(code, in, bad, 0);
}

/* ------------------------------------------------------ the ufunc loops */

/* Hertz's validity check (hertz.A_OVER_R_LIMIT): a contact whose semi-major axis a
 * exceeds the limit times the smallest |radius| of the two bodies, tested as Python
 * tests it (|R| < a * inverse_limit for any radius, so the same bits).  The batch loops
 * of the contact count such contacts in `beyond_count`, per thread (numpy runs a ufunc
 * in the calling thread, which reads the count right after the call): the check costs a
 * pass over each block while it is in the cache instead of a pass over the arrays. */
#if defined(_MSC_VER)
#define HERTZ_THREAD_LOCAL __declspec(thread)
#else
#define HERTZ_THREAD_LOCAL _Thread_local
#endif
static HERTZ_THREAD_LOCAL Py_ssize_t beyond_count = 0;
/* Among them, the largest a / min|R| and its a and min|R| (for the warning's message) */
static HERTZ_THREAD_LOCAL double beyond_ratio = -1.0, beyond_a = 0.0, beyond_r = 0.0;
/* and where its a is, when the loop wrote the output array itself (else 0): the
 * caller finds the element without a pass over the batch */
static HERTZ_THREAD_LOCAL uintptr_t beyond_at = 0;
static double inverse_limit = 0.0; /* 0 until hertz._contact registers it: no check */
static PyObject *warn_size = NULL; /* hertz._contact._check_size */

/* min |R| of element i of a block (radii: never NaN) */
static inline double
smallest_radius(const double *const in[], ptrdiff_t i)
{
    double r0 = fabs(in[0][i]), r1 = fabs(in[1][i]), r2 = fabs(in[2][i]), r3 = fabs(in[3][i]);
    double r01 = r0 < r1 ? r0 : r1, r23 = r2 < r3 ? r2 : r3;
    return r01 < r23 ? r01 : r23;
}

static void
count_beyond(ptrdiff_t n, const double *const in[], const double *a, int in_place)
{
    const double inv = inverse_limit;
    /* A candidate for the largest a / min|R| of the call: beyond, and a at least
     * that ratio so far times min|R| (less 2^-50: a non-candidate's a / min|R|,
     * rounded, is below the ratio so far).  The ratios, divisions, only in a
     * block that holds candidates, which are few once a large one is known. */
    const double bar = beyond_ratio * (1.0 - 0x1p-50);
    Py_ssize_t count = 0, candidates = 0;
    for (ptrdiff_t i = 0; i < n; ++i) { /* vectorised */
        double r = smallest_radius(in, i);
        int beyond = r < a[i] * inv;
        count += beyond;
        candidates += beyond & (a[i] >= bar * r);
    }
    beyond_count += count;
    if (candidates == 0) {
        return;
    }
    for (ptrdiff_t i = 0; i < n; ++i) { /* the first of the largest */
        double r = smallest_radius(in, i);
        if (r < a[i] * inv && a[i] >= bar * r) {
            double ratio = a[i] / r;
            if (ratio > beyond_ratio) {
                beyond_ratio = ratio;
                beyond_a = a[i];
                beyond_r = r;
                beyond_at = in_place ? (uintptr_t)(a + i) : 0;
            }
        }
    }
}

/* Run `fn` over a strided ufunc call in blocks: contiguous operands are used
 * in place, the others copied through block buffers.  check: count the contacts
 * beyond Hertz's validity (inputs 0-3 the radii, output HERTZ_OUT_A the semi-axis a). */
static int
drive(char *const data[], npy_intp const dims[], npy_intp const steps[], int nin, int nout,
      block_fn fn, int variant, int any_length, int check)
{
    double buf[MAXARGS][HERTZ_BLOCK];
    const double *in[MAXARGS];
    double *out[MAXARGS];
    npy_intp total = dims[0];
    int contiguous = 1;
    for (int k = 0; k < nin + nout; ++k) {
        contiguous &= steps[k] == sizeof(double);
    }
    if (any_length && contiguous) { /* the solver blocks the work itself */
        for (int k = 0; k < nin; ++k) {
            in[k] = (const double *)data[k];
        }
        for (int k = 0; k < nout; ++k) {
            out[k] = (double *)data[nin + k];
        }
        return fn((ptrdiff_t)total, in, out, variant);
    }
    /* A broadcast input (step 0) is copied into its buffer once. */
    for (int k = 0; k < nin; ++k) {
        if (steps[k] == 0) {
            double v = *(const double *)data[k];
            for (ptrdiff_t i = 0; i < HERTZ_BLOCK; ++i) {
                buf[k][i] = v;
            }
        }
    }
    for (npy_intp start = 0; start < total; start += HERTZ_BLOCK) {
        ptrdiff_t n = total - start < HERTZ_BLOCK ? (ptrdiff_t)(total - start) : HERTZ_BLOCK;
        for (int k = 0; k < nin; ++k) {
            char *p = data[k] + start * steps[k];
            if (steps[k] == sizeof(double)) {
                in[k] = (const double *)p;
            }
            else if (steps[k] == 0) {
                in[k] = buf[k];
            }
            else {
                for (ptrdiff_t i = 0; i < n; ++i) {
                    buf[k][i] = *(const double *)(p + i * steps[k]);
                }
                in[k] = buf[k];
            }
        }
        for (int k = 0; k < nout; ++k) {
            int j = nin + k;
            out[k] = steps[j] == sizeof(double) ? (double *)(data[j] + start * steps[j])
                                                : buf[j];
        }
        if (fn(n, in, out, variant) < 0) {
            return -1;
        }
        if (check && inverse_limit > 0.0) {
            count_beyond(n, in, out[HERTZ_OUT_A],
                         steps[nin + HERTZ_OUT_A] == sizeof(double));
        }
        for (int k = 0; k < nout; ++k) {
            int j = nin + k;
            if (steps[j] != sizeof(double)) {
                char *p = data[j] + start * steps[j];
                for (ptrdiff_t i = 0; i < n; ++i) {
                    *(double *)(p + i * steps[j]) = buf[j][i];
                }
            }
        }
    }
    return 0;
}

/* ANY: the block function takes any length (the ellipse solver does). */
#define LOOP_ANY(NAME, NIN, NOUT, FN, VARIANT, ANY, CHECK)                                   \
    static int NAME(PyArrayMethod_Context *context, char *const data[],                    \
                    npy_intp const dims[], npy_intp const steps[], NpyAuxData *aux)        \
    {                                                                                      \
        (void)context;                                                                     \
        (void)aux;                                                                         \
        return drive(data, dims, steps, NIN, NOUT, FN, VARIANT, ANY, CHECK);               \
    }
#define LOOP(NAME, NIN, NOUT, FN, VARIANT) LOOP_ANY(NAME, NIN, NOUT, FN, VARIANT, 0, 0)

LOOP_ANY(ellipticity0_loop, 1, 1, ellipticity_block, 0, 1, 0)
LOOP_ANY(ellipticity1_loop, 1, 1, ellipticity_block, 1, 1, 0)
LOOP_ANY(ellipticity2_loop, 1, 1, ellipticity_block, 2, 1, 0)
LOOP_ANY(ellipticity3_loop, 1, 1, ellipticity_block, 3, 1, 0)
LOOP_ANY(ellipse0_loop, 1, 4, ellipse_block, 0, 1, 0)
LOOP_ANY(ellipse1_loop, 1, 4, ellipse_block, 1, 1, 0)
LOOP_ANY(contact_load_loop, 10, HERTZ_NGIVEN, contact_block, HERTZ_GIVEN_LOAD, 0, 1)
LOOP_ANY(contact_approach_loop, 10, HERTZ_NGIVEN, contact_block, HERTZ_GIVEN_APPROACH, 0, 1)
LOOP_ANY(contact_p0_loop, 10, HERTZ_NGIVEN, contact_block, HERTZ_GIVEN_P0, 0, 1)
LOOP(geometry_loop, 9, HERTZ_NFIELDS, geometry_block, 0)
LOOP(coefficients_loop, 9, GEOMETRY_NOUT, geometry_block, 1)
LOOP(given_load_loop, 10, 6, given_block, HERTZ_GIVEN_LOAD)
LOOP(given_approach_loop, 10, 6, given_block, HERTZ_GIVEN_APPROACH)
LOOP(given_p0_loop, 10, 6, given_block, HERTZ_GIVEN_P0)
LOOP(contact_status_loop, 10, 1, contact_status_block, HERTZ_GIVEN_LOAD)
LOOP(line_loop, 9, 5, line_block, 0)
LOOP(line_status_loop, 9, 1, line_block, 1)
LOOP(point_stress_loop, 6, 6, stress_block, 0)
LOOP(subsurface_loop, 3, 10, stress_block, 1)
LOOP(line_stress_loop, 4, 4, stress_block, 2)
LOOP(line_subsurface_loop, 2, 7, stress_block, 3)
LOOP(tangential_stiffness_loop, HERTZ_T_STIFFNESS_NIN, 1, tangential_stiffness_block, 0)
LOOP(partial_slip_loop, HERTZ_T_NIN, HERTZ_T_NOUT, partial_slip_block, 0)

/* Any real dtype (and Python int/float) is cast to float64; bool, complex,
 * strings, datetimes and objects are refused. */
static int
real_to_double(PyObject *ufunc, PyArray_DTypeMeta *const op_dtypes[],
               PyArray_DTypeMeta *const signature[], PyArray_DTypeMeta *new_op_dtypes[])
{
    PyUFuncObject *uf = (PyUFuncObject *)ufunc;
    (void)signature;
    for (int i = 0; i < uf->nargs; ++i) {
        PyArray_DTypeMeta *d = op_dtypes[i];
        if (i < uf->nin && d != NULL) {
            int type_num = d->singleton ? d->singleton->type_num : -1;
            int real = d == &PyArray_PyFloatDType || d == &PyArray_PyLongDType
                       || (type_num >= 0 && type_num != NPY_BOOL
                           && (PyTypeNum_ISINTEGER(type_num) || PyTypeNum_ISFLOAT(type_num)));
            if (!real) {
                PyErr_Format(PyExc_TypeError,
                             "hertz.%s: argument %d must be real numbers (integer or floating "
                             "point), got %S", uf->name, i, (PyObject *)d);
                return -1;
            }
        }
        Py_INCREF(&PyArray_DoubleDType);
        new_op_dtypes[i] = &PyArray_DoubleDType;
    }
    return 0;
}

static int
add_ufunc(PyObject *module, const char *name, const char *doc, int nin, int nout,
          PyArrayMethod_StridedLoop *loop)
{
    PyObject *ufunc = PyUFunc_FromFuncAndData(NULL, NULL, NULL, 0, nin, nout, PyUFunc_None,
                                              name, doc, 0);
    if (ufunc == NULL) {
        return -1;
    }
    PyArray_DTypeMeta *dtypes[MAXARGS];
    for (int i = 0; i < nin + nout; ++i) {
        dtypes[i] = &PyArray_DoubleDType;
    }
    PyType_Slot slots[] = {{NPY_METH_strided_loop, (void *)loop}, {0, NULL}};
    PyArrayMethod_Spec spec = {name, nin, nout, NPY_NO_CASTING,
                               NPY_METH_NO_FLOATINGPOINT_ERRORS, dtypes, slots};
    PyObject *any = NULL, *promoter = NULL;
    int ok = PyUFunc_AddLoopFromSpec(ufunc, &spec) == 0;
    if (ok) {
        any = PyTuple_New(nin + nout);
        ok = any != NULL;
        for (int i = 0; ok && i < nin + nout; ++i) {
            PyTuple_SET_ITEM(any, i, Py_NewRef(Py_None));
        }
    }
    if (ok) {
        promoter = PyCapsule_New((void *)&real_to_double, "numpy._ufunc_promoter", NULL);
        ok = promoter != NULL && PyUFunc_AddPromoter(ufunc, any, promoter) == 0;
    }
    Py_XDECREF(any);
    Py_XDECREF(promoter);
    if (ok && PyModule_AddObject(module, name, ufunc) == 0) {
        return 0;
    }
    Py_DECREF(ufunc);
    return -1;
}

/* ------------------------------------------------------ scalar entry points */

static PyObject *
tuple_of(const double *x, int n)
{
    PyObject *t = PyTuple_New(n);
    if (t == NULL) {
        return NULL;
    }
    for (int k = 0; k < n; ++k) {
        PyObject *f = PyFloat_FromDouble(x[k]);
        if (f == NULL) {
            Py_DECREF(t);
            return NULL;
        }
        PyTuple_SET_ITEM(t, k, f);
    }
    return t;
}

static int
floats(PyObject *const *args, Py_ssize_t nargs, Py_ssize_t want, double *x, const char *fn)
{
    if (nargs != want) {
        PyErr_Format(PyExc_TypeError, "%s takes %zd arguments (%zd given)", fn, want, nargs);
        return -1;
    }
    for (Py_ssize_t k = 0; k < want; ++k) {
        x[k] = PyFloat_AsDouble(args[k]);
        if (x[k] == -1.0 && PyErr_Occurred()) {
            return -1;
        }
    }
    return 0;
}

/* The result class (hertz.Contact, a slotted frozen dataclass) and the
 * offsets of its slots a, b, load, p0, delta, stiffness, _geometry and _nu,
 * so that a scalar call builds its result without running Python code. */
#define CONTACT_SLOTS (HERTZ_NGIVEN + 2)
static PyTypeObject *contact_type = NULL;
static Py_ssize_t contact_offsets[CONTACT_SLOTS];

PyDoc_STRVAR(register_doc,
"register_contact_type(cls)\n\n"
"Let contact() return instances of cls, a class with slots a, b, load, p0,\n"
"delta, stiffness, _geometry and _nu.  Private: hertz._contact calls it once.");

static PyObject *
register_contact_type(PyObject *self, PyObject *cls)
{
    (void)self;
    static const char *const names[CONTACT_SLOTS] = {"a", "b", "load", "p0", "delta",
                                                    "stiffness", "_geometry", "_nu"};
    if (!PyType_Check(cls)) {
        PyErr_SetString(PyExc_TypeError, "register_contact_type: a class is required");
        return NULL;
    }
    for (int k = 0; k < CONTACT_SLOTS; ++k) {
        PyObject *d = PyDict_GetItemString(((PyTypeObject *)cls)->tp_dict, names[k]);
        if (d == NULL || !PyObject_TypeCheck(d, &PyMemberDescr_Type)
            || ((PyMemberDescrObject *)d)->d_member->type != T_OBJECT_EX) {
            PyErr_Format(PyExc_TypeError, "register_contact_type: no slot %s", names[k]);
            return NULL;
        }
        contact_offsets[k] = ((PyMemberDescrObject *)d)->d_member->offset;
    }
    Py_XSETREF(contact_type, (PyTypeObject *)Py_NewRef(cls));
    Py_RETURN_NONE;
}

/* An instance of the registered class from the HERTZ_NOUT fields and the
 * bodies' elastic constants (nu1, nu2, E1, E2): the stresses read the Poisson's
 * ratios, the tangential compliance needs each body's own modulus too. */
static PyObject *
new_contact(const double *fields, const double moduli[4])
{
    PyObject *geometry = tuple_of(fields + HERTZ_NGIVEN, HERTZ_NOUT - HERTZ_NGIVEN);
    PyObject *poisson = tuple_of(moduli, 4);
    PyObject *obj = geometry && poisson ? contact_type->tp_alloc(contact_type, 0) : NULL;
    if (obj == NULL) {
        Py_XDECREF(geometry);
        Py_XDECREF(poisson);
        return NULL;
    }
    *(PyObject **)((char *)obj + contact_offsets[HERTZ_NGIVEN + 1]) = poisson;
    for (int k = 0; k < HERTZ_NGIVEN; ++k) {
        PyObject *f = PyFloat_FromDouble(fields[k]);
        if (f == NULL) {
            Py_DECREF(geometry);
            Py_DECREF(obj);
            return NULL;
        }
        *(PyObject **)((char *)obj + contact_offsets[k]) = f;
    }
    *(PyObject **)((char *)obj + contact_offsets[HERTZ_NGIVEN]) = geometry;
    return obj;
}

PyDoc_STRVAR(contact_scalar_doc,
"contact(mode, r1x, r1y, r2x, r2y, angle, E1, nu1, E2, nu2, value) -> Contact\n\n"
"One point contact from Python floats; mode 0, 1, 2: value is the load,\n"
"approach or p0.  Returns an instance of the registered class (or, before\n"
"one is registered, the tuple (a, b, load, p0, delta, stiffness, lambda,\n"
"alpha, m, K, E, e_star, rho_x, rho_y, theta)).\n"
"Private: use hertz.contact.");

static PyObject *
contact_scalar(PyObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    (void)self;
    double x[11];
    if (floats(args, nargs, 11, x, "contact") < 0) {
        return NULL;
    }
    int mode = (int)x[0];
    if (!(mode >= 0 && mode < HERTZ_NMODES && x[0] == mode)) {
        PyErr_SetString(PyExc_ValueError, "contact: mode must be 0, 1 or 2");
        return NULL;
    }
    double fields[HERTZ_NOUT];
    hertz_scaled rho_x = {0.0, 0.0}, rho_y = {0.0, 0.0};
    int code = contact_one(x + 1, mode, 1, fields, &rho_x, &rho_y);
    if (code != HERTZ_OK) {
        set_error(code, x + 1, x[10], mode, rho_x, rho_y);
        return NULL;
    }
    double moduli[4] = {x[1 + HERTZ_NU1], x[1 + HERTZ_NU2], x[1 + HERTZ_E1], x[1 + HERTZ_E2]};
    return contact_type ? new_contact(fields, moduli) : tuple_of(fields, HERTZ_NOUT);
}

/* hertz.Body (a slotted frozen dataclass) and the offsets of its slots Rx, Ry, E, nu
 * and _scalar, for contact_bodies. */
static PyTypeObject *body_type = NULL;
static Py_ssize_t body_offsets[5];

static int
slot_offsets(PyObject *cls, const char *const names[], int count, Py_ssize_t offsets[],
             const char *who)
{
    for (int k = 0; k < count; ++k) {
        PyObject *d = PyDict_GetItemString(((PyTypeObject *)cls)->tp_dict, names[k]);
        if (d == NULL || !PyObject_TypeCheck(d, &PyMemberDescr_Type)
            || ((PyMemberDescrObject *)d)->d_member->type != T_OBJECT_EX) {
            PyErr_Format(PyExc_TypeError, "%s: no slot %s", who, names[k]);
            return -1;
        }
        offsets[k] = ((PyMemberDescrObject *)d)->d_member->offset;
    }
    return 0;
}

PyDoc_STRVAR(register_validity_doc,
"register_validity(body_cls, inverse_limit, check_size)\n\n"
"The body class (slots Rx, Ry, E, nu, _scalar) that contact_bodies reads, the\n"
"validity test |R| < a * inverse_limit, and the function called as\n"
"check_size(a, body1, body2) where a contact fails it (it warns).  Private:\n"
"hertz._contact calls it once.");

static PyObject *
register_validity(PyObject *self, PyObject *args)
{
    (void)self;
    static const char *const names[5] = {"Rx", "Ry", "E", "nu", "_scalar"};
    PyObject *cls, *check;
    double inv;
    if (!PyArg_ParseTuple(args, "O!dO", &PyType_Type, &cls, &inv, &check)) {
        return NULL;
    }
    if (!(inv > 0.0) || !PyCallable_Check(check)) {
        PyErr_SetString(PyExc_ValueError, "register_validity: inverse_limit > 0 and a "
                                          "callable are required");
        return NULL;
    }
    if (slot_offsets(cls, names, 5, body_offsets, "register_validity") < 0) {
        return NULL;
    }
    Py_XSETREF(body_type, (PyTypeObject *)Py_NewRef(cls));
    Py_XSETREF(warn_size, Py_NewRef(check));
    inverse_limit = inv;
    Py_RETURN_NONE;
}

PyDoc_STRVAR(beyond_doc,
"beyond() -> (count, a, r, address)\n\n"
"How many contacts the batch loops of this thread found beyond Hertz's validity\n"
"since the last call, and the a and smallest |R| of the one with the largest a/R\n"
"(0.0, 0.0 when none) and the address of its a where the loop wrote the output\n"
"array itself (0 where it wrote a buffer, or none); resets them.  Private:\n"
"hertz.contact calls it.");

static PyObject *
beyond(PyObject *self, PyObject *unused)
{
    (void)self;
    (void)unused;
    PyObject *out = Py_BuildValue("(nddK)", beyond_count, beyond_a, beyond_r,
                                  (unsigned long long)beyond_at);
    beyond_count = 0;
    beyond_ratio = -1.0;
    beyond_a = beyond_r = 0.0;
    beyond_at = 0;
    return out;
}

PyDoc_STRVAR(contact_bodies_doc,
"contact_bodies(mode, body1, body2, angle, value) -> Contact or NotImplemented\n\n"
"hertz.contact's scalar path in one call: two registered bodies of Python floats,\n"
"a float angle and value (mode 0, 1, 2: the load, approach or p0); the validity\n"
"check made and check_size called where it fails.  NotImplemented for any other\n"
"input (the caller takes its general path).  Private: use hertz.contact.");

static PyObject *
contact_bodies(PyObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    (void)self;
    if (nargs != 5 || body_type == NULL || contact_type == NULL
        || Py_TYPE(args[1]) != body_type || Py_TYPE(args[2]) != body_type
        || !PyFloat_CheckExact(args[3]) || !PyFloat_CheckExact(args[4])
        || !PyLong_CheckExact(args[0])) {
        Py_RETURN_NOTIMPLEMENTED;
    }
    double x[HERTZ_NGEOMETRY + 1];
    static const int where[2][4] = {{HERTZ_R1X, HERTZ_R1Y, HERTZ_E1, HERTZ_NU1},
                                    {HERTZ_R2X, HERTZ_R2Y, HERTZ_E2, HERTZ_NU2}};
    for (int j = 0; j < 2; ++j) {
        char *body = (char *)args[1 + j];
        if (*(PyObject **)(body + body_offsets[4]) != Py_True) {
            Py_RETURN_NOTIMPLEMENTED; /* array fields: the general path */
        }
        for (int k = 0; k < 4; ++k) {
            PyObject *f = *(PyObject **)(body + body_offsets[k]);
            if (f == NULL || !PyFloat_CheckExact(f)) {
                Py_RETURN_NOTIMPLEMENTED;
            }
            x[where[j][k]] = PyFloat_AS_DOUBLE(f);
        }
    }
    x[HERTZ_ANGLE] = PyFloat_AS_DOUBLE(args[3]);
    x[HERTZ_NGEOMETRY] = PyFloat_AS_DOUBLE(args[4]);
    long mode = PyLong_AsLong(args[0]);
    if (!(mode >= 0 && mode < HERTZ_NMODES)) {
        PyErr_SetString(PyExc_ValueError, "contact_bodies: mode must be 0, 1 or 2");
        return NULL;
    }
    double fields[HERTZ_NOUT];
    hertz_scaled rho_x = {0.0, 0.0}, rho_y = {0.0, 0.0};
    int code = contact_one(x, (int)mode, 1, fields, &rho_x, &rho_y);
    if (code != HERTZ_OK) {
        set_error(code, x, x[HERTZ_NGEOMETRY], (int)mode, rho_x, rho_y);
        return NULL;
    }
    double moduli[4] = {x[HERTZ_NU1], x[HERTZ_NU2], x[HERTZ_E1], x[HERTZ_E2]};
    PyObject *c = new_contact(fields, moduli);
    double t = fields[HERTZ_OUT_A] * inverse_limit;
    if (c != NULL && inverse_limit > 0.0
        && (fabs(x[HERTZ_R1X]) < t || fabs(x[HERTZ_R1Y]) < t || fabs(x[HERTZ_R2X]) < t
            || fabs(x[HERTZ_R2Y]) < t)) {
        PyObject *a = PyFloat_FromDouble(fields[HERTZ_OUT_A]);
        PyObject *r = a ? PyObject_CallFunctionObjArgs(warn_size, a, args[1], args[2], NULL)
                        : NULL;
        Py_XDECREF(a);
        if (r == NULL) {
            Py_DECREF(c);
            return NULL;
        }
        Py_DECREF(r);
    }
    return c;
}

PyDoc_STRVAR(line_scalar_doc,
"line_contact(r1x, r1y, r2x, r2y, E1, nu1, E2, nu2, load_per_length) -> tuple\n\n"
"One line contact from Python floats: (half_width, p0, e_star, rho, load).\n"
"Private: use hertz.line_contact.");

static PyObject *
line_scalar(PyObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    (void)self;
    double x[9], res[5];
    hertz_scaled rho_x, rho_y;
    if (floats(args, nargs, 9, x, "line_contact") < 0) {
        return NULL;
    }
    int code = hertz_line_contact(x, x[8], res, &rho_x, &rho_y);
    if (code != HERTZ_OK) {
        double geo[HERTZ_NGEOMETRY] = {x[0], x[1], x[2], x[3], 0.0, x[4], x[5], x[6], x[7]};
        set_error(code, geo, x[8], 3, rho_x, rho_y);
        return NULL;
    }
    return tuple_of(res, 5);
}

PyDoc_STRVAR(simd_doc,
"simd(enable=None) -> bool\n\n"
"Whether a SIMD code path (AVX2 or AVX-512) is used (they give the same bits\n"
"as the plain code); with enable, switch to the plain path or back to the\n"
"best the CPU has first.  Private: for tests and benchmarks.");

static PyObject *
simd(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *enable = Py_None;
    if (!PyArg_ParseTuple(args, "|O", &enable)) {
        return NULL;
    }
    int on = -1;
    if (enable != Py_None) {
        on = PyObject_IsTrue(enable);
        if (on < 0) {
            return NULL;
        }
    }
    return PyBool_FromLong(hertz_simd(on));
}

PyDoc_STRVAR(assoc_doc,
"associate_integrals(m, p) -> (B, D, V)\n\n"
"B(m), D(m) and V(m) = (B - pD)/m for 0 < m < 1 with p = 1 - m given\n"
"separately (so that either can carry full relative precision); float64\n"
"arrays of one length.  Private: for the accuracy tests of the kernel.");

static PyObject *
associate_integrals(PyObject *self, PyObject *args)
{
    (void)self;
    PyObject *mo, *po;
    if (!PyArg_ParseTuple(args, "OO", &mo, &po)) {
        return NULL;
    }
    PyArrayObject *m = (PyArrayObject *)PyArray_FROMANY(mo, NPY_DOUBLE, 1, 1,
                                                        NPY_ARRAY_CARRAY_RO);
    PyArrayObject *p = (PyArrayObject *)PyArray_FROMANY(po, NPY_DOUBLE, 1, 1,
                                                        NPY_ARRAY_CARRAY_RO);
    PyObject *result = NULL;
    if (m && p && PyArray_SIZE(m) != PyArray_SIZE(p)) {
        PyErr_SetString(PyExc_ValueError, "m and p must have the same length");
    }
    else if (m && p) {
        npy_intp n = PyArray_SIZE(m);
        PyObject *B = PyArray_SimpleNew(1, &n, NPY_DOUBLE);
        PyObject *D = PyArray_SimpleNew(1, &n, NPY_DOUBLE);
        PyObject *V = PyArray_SimpleNew(1, &n, NPY_DOUBLE);
        if (B && D && V) {
            hertz_associate_integrals(n, PyArray_DATA(m), PyArray_DATA(p),
                                      PyArray_DATA((PyArrayObject *)B),
                                      PyArray_DATA((PyArrayObject *)D),
                                      PyArray_DATA((PyArrayObject *)V));
            result = PyTuple_Pack(3, B, D, V);
        }
        Py_XDECREF(B);
        Py_XDECREF(D);
        Py_XDECREF(V);
    }
    Py_XDECREF(m);
    Py_XDECREF(p);
    return result;
}

/* ------------------------------------------------------- LoadPathSpring */

/* The data of load_path_step's argument `name`: a 1-d ndarray of `typenum`,
 * C-contiguous and aligned (writeable where `write`), of length n, or of
 * length 1 where `stride` is given (*stride: 1 for length n, 0 for 1). */
static void *
lp_array(PyObject *obj, const char *name, int typenum, npy_intp n, int write,
         ptrdiff_t *stride)
{
    if (!PyArray_Check(obj)) {
        PyErr_Format(PyExc_TypeError, "load_path_step: %s must be a numpy array, got %.100s",
                     name, Py_TYPE(obj)->tp_name);
        return NULL;
    }
    PyArrayObject *a = (PyArrayObject *)obj;
    if (!PyArray_EquivTypenums(PyArray_TYPE(a), typenum) || !PyArray_ISNOTSWAPPED(a)) {
        PyErr_Format(PyExc_TypeError, "load_path_step: %s must be of dtype %s (native)", name,
                     typenum == NPY_DOUBLE ? "float64" : typenum == NPY_BOOL ? "bool" : "intp");
        return NULL;
    }
    int flags = NPY_ARRAY_C_CONTIGUOUS | NPY_ARRAY_ALIGNED | (write ? NPY_ARRAY_WRITEABLE : 0);
    if (!PyArray_CHKFLAGS(a, flags)) {
        PyErr_Format(PyExc_ValueError, "load_path_step: %s must be C-contiguous and aligned%s",
                     name, write ? " and writeable" : "");
        return NULL;
    }
    npy_intp length = PyArray_NDIM(a) == 1 ? PyArray_DIM(a, 0) : -1;
    if (length != n && !(stride != NULL && length == 1)) {
        PyErr_Format(PyExc_ValueError, "load_path_step: %s must be 1-d of length %zd%s", name,
                     (Py_ssize_t)n, stride != NULL ? " or 1" : "");
        return NULL;
    }
    if (stride != NULL) {
        *stride = length == n ? 1 : 0;
    }
    return PyArray_DATA(a);
}

PyDoc_STRVAR(load_path_step_doc,
"load_path_step(count, alpha, delta, top, pieces, alpha1, load, increment, mu,\n"
"               per_reach, force, normal_force, displacement, sliding, front)\n"
"    -> (status, value)\n\n"
"One step of hertz.LoadPathSpring for n contacts (hertz/_load_path_kernel.c).\n"
"The stacks (count intp, delta float64 of length n, top of shape (n, 4), pieces\n"
"of shape (n, width, 4)) and the outputs (float64, sliding bool, length n) are\n"
"updated in place; alpha holds the sizes before the step (not written: alpha1 =\n"
"numpy.cbrt(load) holds them after it); mu, per_reach (1 / reach) of length n or 1.  status 0:\n"
"done, value the largest count; otherwise nothing was written and value is the\n"
"first contact where status fails: 1 the load (negative, not finite), 2 the\n"
"increment (not finite), 3 displacement + increment (not finite).  A count\n"
"outside [0, width - 2] is a RuntimeError (the other contacts made their step).\n"
"Private.");

static PyObject *
load_path_step(PyObject *self, PyObject *const *args, Py_ssize_t nargs)
{
    (void)self;
    static const char *const names[] = {
        "count", "alpha", "delta", "top", "pieces", "alpha1", "load", "increment", "mu",
        "per_reach", "force", "normal_force", "displacement", "sliding", "front"};
    enum { NARGS = sizeof names / sizeof names[0] };
    if (nargs != NARGS) {
        PyErr_Format(PyExc_TypeError, "load_path_step takes %d arguments, got %zd", NARGS,
                     nargs);
        return NULL;
    }
    if (!PyArray_Check(args[0]) || PyArray_NDIM((PyArrayObject *)args[0]) != 1) {
        PyErr_SetString(PyExc_TypeError, "load_path_step: count must be a 1-d numpy array");
        return NULL;
    }
    npy_intp n = PyArray_DIM((PyArrayObject *)args[0], 0);
    void *data[NARGS];
    ptrdiff_t strides[2], width = 0;
    for (int k = 0; k < NARGS; ++k) {
        if (k == 3 || k == 4) { /* top (n, 4), pieces (n, width, 4) */
            PyArrayObject *a = (PyArrayObject *)args[k];
            int ndim = k == 3 ? 2 : 3;
            if (!PyArray_Check(args[k]) || PyArray_NDIM(a) != ndim || PyArray_DIM(a, 0) != n
                || PyArray_DIM(a, ndim - 1) != HERTZ_PIECE || (k == 4 && PyArray_DIM(a, 1) < 2)
                || PyArray_TYPE(a) != NPY_DOUBLE || !PyArray_ISNOTSWAPPED(a)
                || !PyArray_CHKFLAGS(a, NPY_ARRAY_CARRAY)) {
                PyErr_Format(PyExc_ValueError, "load_path_step: %s must be a writeable, "
                             "aligned, C-contiguous float64 array of shape (%zd, %s%d)",
                             names[k], (Py_ssize_t)n, k == 3 ? "" : "width >= 2, ",
                             HERTZ_PIECE);
                return NULL;
            }
            width = k == 4 ? PyArray_DIM(a, 1) : width;
            data[k] = PyArray_DATA(a);
            continue;
        }
        int typenum = k == 0 ? NPY_INTP : k == 13 ? NPY_BOOL : NPY_DOUBLE;
        int write = k == 0 || k == 2 || k >= 10;
        ptrdiff_t *stride = k == 8 || k == 9 ? &strides[k - 8] : NULL;
        data[k] = lp_array(args[k], names[k], typenum, n, write, stride);
        if (data[k] == NULL) {
            return NULL;
        }
    }
    hertz_spring_stacks stacks = {n, width, data[0], data[1], data[2], data[3], data[4]};
    hertz_load_path_input in = {data[6], data[5], data[7], data[8], data[9], strides[0],
                                strides[1]};
    hertz_load_path_output out = {data[10], data[11], data[12], data[14], data[13]};
    ptrdiff_t value = 0;
    int status;
    Py_BEGIN_ALLOW_THREADS
    status = hertz_load_path_check(n, in.load, in.increment, out.displacement, &value);
    if (status == HERTZ_LP_OK) {
        value = hertz_load_path_step(&stacks, &in, &out);
    }
    Py_END_ALLOW_THREADS
    if (value < 0) {
        PyErr_Format(PyExc_RuntimeError, "load_path_step: contact %zd holds a count outside "
                     "[0, width - 2 = %zd]: no room for a step (it was left as it was)",
                     (Py_ssize_t)(-1 - value), (Py_ssize_t)(width - 2));
        return NULL;
    }
    return Py_BuildValue("(in)", status, (Py_ssize_t)value);
}

/* ------------------------------------------------------------ build info */

#if defined(HERTZ_BUILD_INFO)
#include "hertz_build_info.h" /* written by setup.py into the build's temporary folder */
#endif
#ifndef HERTZ_BUILD_COMMAND
#define HERTZ_BUILD_COMMAND ""
#endif
#ifndef HERTZ_BUILD_FLAGS
#define HERTZ_BUILD_FLAGS ""
#endif

#define HERTZ_STRINGIFY_(x) #x
#define HERTZ_STRINGIFY(x) HERTZ_STRINGIFY_(x)
#if defined(__clang__)
#define HERTZ_COMPILER                                                              \
    "Clang " HERTZ_STRINGIFY(__clang_major__) "." HERTZ_STRINGIFY(__clang_minor__) "." \
        HERTZ_STRINGIFY(__clang_patchlevel__)
#elif defined(__GNUC__)
#define HERTZ_COMPILER "GCC " __VERSION__
#elif defined(_MSC_VER)
#define HERTZ_COMPILER "MSVC " HERTZ_STRINGIFY(_MSC_FULL_VER)
#else
#define HERTZ_COMPILER "unknown"
#endif

static const char *const path_names[] = {"plain", "avx2", "avx512"};

PyDoc_STRVAR(build_info_doc,
"build_info() -> dict\n\n"
"How this module was built and which code path runs: compiler (name and\n"
"version), command (the compile command with its flags, CFLAGS included),\n"
"flags (those setup.py added), paths (the code paths compiled in), path\n"
"(the one in use on this processor), fma (whether exact products use fused\n"
"multiply-adds on it: the same bits either way), plain (built with\n"
"HERTZ_PLAIN), fast_math (__FAST_MATH__: must be False), optimized\n"
"(__OPTIMIZE__).  Private: hertz.show_config() prints it.");

static PyObject *
build_info(PyObject *self, PyObject *args)
{
    (void)self;
    (void)args;
    int built = hertz_paths_built(), path = hertz_path();
    PyObject *paths = PyTuple_New(0);
    for (int k = HERTZ_PATH_AVX512; paths && k >= HERTZ_PATH_PLAIN; --k) {
        if (built & (1 << k)) {
            PyObject *name = PyUnicode_FromString(path_names[k]);
            if (!name || _PyTuple_Resize(&paths, PyTuple_GET_SIZE(paths) + 1) < 0) {
                Py_XDECREF(name);
                Py_XDECREF(paths);
                return NULL;
            }
            PyTuple_SET_ITEM(paths, PyTuple_GET_SIZE(paths) - 1, name);
        }
    }
    if (!paths) {
        return NULL;
    }
#if defined(HERTZ_PLAIN)
    int plain = 1;
#else
    int plain = 0;
#endif
#if defined(__FAST_MATH__)
    int fast_math = 1;
#else
    int fast_math = 0;
#endif
#if defined(__OPTIMIZE__)
    int optimized = 1;
#else
    int optimized = 0;
#endif
    return Py_BuildValue("{s:s,s:s,s:s,s:N,s:s,s:N,s:N,s:N,s:N}", "compiler", HERTZ_COMPILER,
                         "command", HERTZ_BUILD_COMMAND, "flags", HERTZ_BUILD_FLAGS, "paths",
                         paths, "path", path_names[path], "fma",
                         PyBool_FromLong(path != HERTZ_PATH_PLAIN || HERTZ_PLAIN_FMA), "plain",
                         PyBool_FromLong(plain), "fast_math", PyBool_FromLong(fast_math),
                         "optimized", PyBool_FromLong(optimized));
}

PyDoc_STRVAR(path_doc,
"path(limit=None) -> str\n\n"
"The code path in use ('plain', 'avx2' or 'avx512'); with limit, use at most\n"
"that one from now on first ('avx512' for the best the processor has).  All\n"
"paths give the same bits.  Private: for tests and benchmarks.");

static PyObject *
path(PyObject *self, PyObject *args)
{
    (void)self;
    const char *limit = NULL;
    if (!PyArg_ParseTuple(args, "|z", &limit)) {
        return NULL;
    }
    if (limit) {
        int k = HERTZ_PATH_PLAIN;
        while (k <= HERTZ_PATH_AVX512 && strcmp(limit, path_names[k]) != 0) {
            ++k;
        }
        if (k > HERTZ_PATH_AVX512) {
            PyErr_Format(PyExc_ValueError, "no code path %R: 'plain', 'avx2' or 'avx512'",
                         PyTuple_GET_ITEM(args, 0));
            return NULL;
        }
        hertz_set_path(k);
    }
    return PyUnicode_FromString(path_names[hertz_path()]);
}

static PyMethodDef methods[] = {
    {"contact", (PyCFunction)(void (*)(void))contact_scalar, METH_FASTCALL, contact_scalar_doc},
    {"line_contact", (PyCFunction)(void (*)(void))line_scalar, METH_FASTCALL, line_scalar_doc},
    {"register_contact_type", register_contact_type, METH_O, register_doc},
    {"register_validity", register_validity, METH_VARARGS, register_validity_doc},
    {"contact_bodies", (PyCFunction)(void (*)(void))contact_bodies, METH_FASTCALL,
     contact_bodies_doc},
    {"beyond", beyond, METH_NOARGS, beyond_doc},
    {"simd", simd, METH_VARARGS, simd_doc},
    {"path", path, METH_VARARGS, path_doc},
    {"build_info", build_info, METH_NOARGS, build_info_doc},
    {"associate_integrals", associate_integrals, METH_VARARGS, assoc_doc},
    {"load_path_step", (PyCFunction)(void (*)(void))load_path_step, METH_FASTCALL,
     load_path_step_doc},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module_def = {
    PyModuleDef_HEAD_INIT, "_ufuncs",
    "Compiled core of hertz: numpy ufuncs over the C kernels (private).", -1, methods,
};

PyMODINIT_FUNC
PyInit__ufuncs(void)
{
    import_array();
    import_umath();
    PyObject *module = PyModule_Create(&module_def);
    if (module == NULL) {
        return NULL;
    }
    struct {
        const char *name;
        int nin, nout;
        PyArrayMethod_StridedLoop *loop;
        const char *doc;
    } table[] = {
        {"ellipticity0", 1, 1, ellipticity0_loop, "lambda(alpha), the start only (private)"},
        {"ellipticity1", 1, 1, ellipticity1_loop, "lambda(alpha), one Bailey step (private)"},
        {"ellipticity2", 1, 1, ellipticity2_loop, "lambda(alpha), two Bailey steps (private)"},
        {"ellipticity3", 1, 1, ellipticity3_loop, "lambda(alpha), three Bailey steps (private)"},
        {"ellipse0", 1, 4, ellipse0_loop, "alpha -> lambda, m, K, E; the start (private)"},
        {"ellipse1", 1, 4, ellipse1_loop, "alpha -> lambda, m, K, E (private)"},
        {"contact_load", 10, HERTZ_NGIVEN, contact_load_loop,
         "geometry, moduli, load -> a, b, load, p0, delta, stiffness (private)"},
        {"contact_approach", 10, HERTZ_NGIVEN, contact_approach_loop,
         "geometry, moduli, approach -> a, b, load, p0, delta, stiffness (private)"},
        {"contact_p0", 10, HERTZ_NGIVEN, contact_p0_loop,
         "geometry, moduli, peak pressure -> a, b, load, p0, delta, stiffness (private)"},
        {"contact_geometry", 9, HERTZ_NFIELDS, geometry_loop,
         "geometry and moduli -> lambda, alpha, m, K, E, e_star, rho_x, rho_y, theta "
         "(private)"},
        {"contact_coefficients", 9, GEOMETRY_NOUT, coefficients_loop,
         "geometry and moduli -> the contact_geometry fields and the load-pass "
         "coefficients (private)"},
        {"given_load", 10, 6, given_load_loop,
         "coefficients and load -> a, b, load, p0, delta, stiffness (private)"},
        {"given_approach", 10, 6, given_approach_loop,
         "coefficients and approach -> a, b, load, p0, delta, stiffness (private)"},
        {"given_p0", 10, 6, given_p0_loop,
         "coefficients and p0 -> a, b, load, p0, delta, stiffness (private)"},
        {"contact_status", 10, 1, contact_status_loop,
         "the error code of each contact, 0 if none (private)"},
        {"line", 9, 5, line_loop,
         "radii, moduli, load per length -> half_width, p0, e_star, rho, load (private)"},
        {"line_status", 9, 1, line_status_loop,
         "the error code of each line contact, 0 if none (private)"},
        {"point_stress", 6, 6, point_stress_loop,
         "a, b, nu, x, y, z -> sxx, syy, szz, syz, sxz, sxy per p0 (private)"},
        {"subsurface", 3, 10, subsurface_loop,
         "a, b, nu -> the maxima below a point contact per p0 (private)"},
        {"line_stress", 4, 4, line_stress_loop,
         "b, nu, x, z -> sxx, szz, sxz, syy per p0, line contact (private)"},
        {"line_subsurface", 2, 7, line_subsurface_loop,
         "b, nu -> the maxima below a line contact per p0 (private)"},
        {"tangential_stiffness", HERTZ_T_STIFFNESS_NIN, 1, tangential_stiffness_loop,
         "K, alpha, lambda, a, nu1, nu2, E1, E2, direction -> the no-slip tangential "
         "stiffness (private)"},
        {"partial_slip", HERTZ_T_NIN, HERTZ_T_NOUT, partial_slip_loop,
         "K, alpha, lambda, a, b, load, nu1, nu2, E1, E2, force, mu, direction -> stick_a, "
         "stick_b, slip_area, displacement, displacement_transverse, stiffness, "
         "no_slip_stiffness, sliding (private)"},
    };
    for (size_t i = 0; i < sizeof table / sizeof table[0]; ++i) {
        if (add_ufunc(module, table[i].name, table[i].doc, table[i].nin, table[i].nout,
                      table[i].loop) < 0) {
            Py_DECREF(module);
            return NULL;
        }
    }
    return module;
}
