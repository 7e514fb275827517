"""Published methods for the contact-ellipse ratio, for comparison with ours.

Each function maps the curvature ratio alpha = rho_x/rho_y (array_like,
alpha >= 1 unless stated) to lambda = a/b, vectorised with numpy, and names
its source and equations.  They are baselines for
``benchmarks/speed_vs_error.py``; use :func:`hertz.ellipticity` for work.
Elliptic integrals take the parameter m = k**2 (scipy.special's convention).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from scipy import interpolate, optimize, special

from ._ellipse import ellipticity

__all__ = [
    "ANTOINE_U",
    "ANTOINE_V",
    "OBA_COEFFICIENTS",
    "OBA_COEFFICIENTS_PRINTED",
    "IterativeResult",
    "TableLookup",
    "antoine_2006",
    "bracketing_reference",
    "dyson_evans_snidle_1992",
    "greenwood_1985",
    "hamrock_1994",
    "hamrock_1994_integrals",
    "hamrock_anderson_1973",
    "hamrock_brewe_1983",
    "hamrock_brewe_1983_integrals",
    "oba_2014_start",
    "seed_hokada_2025",
    "seed_hokada_2025_nu",
]


class IterativeResult(NamedTuple):
    """lambda and the number of iterations each element took (iterative methods)."""

    ellipticity: np.ndarray
    iterations: np.ndarray


def _alpha(alpha) -> np.ndarray:
    return np.asarray(alpha, dtype=np.float64)


def hamrock_brewe_1983(alpha):
    """Hamrock & Brewe's closed form, lambda = 1.0339 alpha**0.636.

    B. J. Hamrock and D. Brewe, "Simplified solution for stresses and
    deformations", J. Lubr. Technol. 105 (1983) 171-177.  Errors in lambda:
    1.3% for 2 <= alpha <= 20, 6.3% at 100, 23% at 1000; lambda(1) = 1.0339.
    """
    return 1.0339 * _alpha(alpha) ** 0.636


def hamrock_brewe_1983_integrals(alpha):
    """Hamrock & Brewe's (1983) K and E approximations.

    K ~ 1.5277 + 0.6023 ln(alpha), E ~ 1.0003 + 0.5968/alpha.
    """
    a = _alpha(alpha)
    return 1.5277 + 0.6023 * np.log(a), 1.0003 + 0.5968 / a


def hamrock_1994(alpha):
    """Hamrock's textbook closed form, lambda = alpha**(2/pi).

    B. J. Hamrock, *Fundamentals of Fluid Film Lubrication*, McGraw-Hill,
    1994, ch. 17.  Errors in lambda: -3.7% for alpha = 5 .. 10, +20% at 1000.
    """
    return _alpha(alpha) ** (2 / np.pi)


def hamrock_1994_integrals(alpha):
    """Hamrock's (1994) K ~ pi/2 + q ln(alpha) and E ~ 1 + q/alpha, q = pi/2 - 1."""
    a = _alpha(alpha)
    q = np.pi / 2 - 1
    return np.pi / 2 + q * np.log(a), 1 + q / a


def greenwood_1985(alpha):
    """Greenwood's approximation lambda = alpha**(2/3).

    J. A. Greenwood, "Formulas for moderately elliptical Hertzian contacts",
    J. Tribol. 107 (1985) 501-504.  Errors: 3.2% at alpha = 10, 18% at 100.
    """
    return _alpha(alpha) ** (2 / 3)


#: Antoine et al. (2006) numerator and denominator coefficients u1..u4, v1..v4.
ANTOINE_U = (0.40227436, 3.7491752e-2, 7.4855761e-4, 2.1667028e-6)
ANTOINE_V = (0.42678878, 4.2605401e-2, 9.0786922e-4, 2.7868927e-6)


def antoine_2006(alpha):
    """Antoine, Visa, Sauvey & Abba's fit lambda = alpha**p(q), q = (log10 alpha)**2.

    J.-F. Antoine, C. Visa, C. Sauvey, G. Abba, "Approximate analytical model
    for Hertzian elliptical contact problems", J. Tribol. 128 (2006) 660-664:
    p = (2/3)(1 + sum u_i q**i)/(1 + sum v_i q**i), i = 1..4.  Error in lambda
    5.9e-6 on 1 <= alpha <= 1e4.
    """
    a = _alpha(alpha)
    q = np.log10(a) ** 2
    num = 1 + q * (ANTOINE_U[0] + q * (ANTOINE_U[1] + q * (ANTOINE_U[2] + q * ANTOINE_U[3])))
    den = 1 + q * (ANTOINE_V[0] + q * (ANTOINE_V[1] + q * (ANTOINE_V[2] + q * ANTOINE_V[3])))
    return a ** (2 / 3 * num / den)


def _iterate(update, x0, rtol, maxiter):
    """Vectorised fixed-point/Newton driver: update only the unconverged elements."""
    shape = np.shape(x0)
    x = np.array(x0, dtype=np.float64).reshape(-1)
    count = np.zeros(x.shape, dtype=np.int64)
    active = np.ones(x.shape, dtype=bool)
    for _ in range(maxiter):
        if not active.any():
            break
        idx = np.nonzero(active)
        new = update(x[idx], idx)
        count[idx] += 1
        with np.errstate(invalid="ignore"):
            done = ~(np.abs(new - x[idx]) > rtol * np.abs(new))  # NaN stops too
        x[idx] = new
        active[idx] = ~done
    return x.reshape(shape), count.reshape(shape)


def hamrock_anderson_1973(alpha, rtol=1e-13, maxiter=500):
    """Hamrock & Anderson's fixed-point iteration, run to a tolerance.

    B. J. Hamrock and W. J. Anderson, "Arched-outer-race ball-bearing
    considering centrifugal forces", J. Lubr. Technol. 95 (1973) 265-276:
    lambda_{n+1} = sqrt((2K - E(1 + R))/(E(1 - R))), R = (alpha - 1)/(alpha + 1),
    K, E at m = 1 - 1/lambda_n**2 (the seed's eq. (lambda_rho-); K from
    scipy's ellipkm1(1/lambda_n**2) to keep its precision), from
    lambda_0 = alpha**(2/3), until |lambda_{n+1} - lambda_n| <= rtol lambda_{n+1}.
    Converges linearly (about 70 iterations at alpha = 2), slower near 1.

    Returns
    -------
    IterativeResult
        lambda and the iterations taken per element.
    """
    a = _alpha(alpha)
    r = (a - 1) / (a + 1)

    r = r.reshape(-1)

    def update(lam, idx):
        p = 1 / lam**2  # 1 - m, so that K keeps its precision as m -> 1
        K, E = special.ellipkm1(p), special.ellipe(1 - p)
        return np.sqrt((2 * K - E * (1 + r[idx])) / (E * (1 - r[idx])))

    return IterativeResult(*_iterate(update, a ** (2 / 3), rtol, maxiter))


def dyson_evans_snidle_1992(alpha, rtol=1e-14, maxiter=50):
    """Newton's method on k'**2 = 1 - m, started from k'**2 = alpha**(-4/3).

    A. Dyson, H. P. Evans, R. W. Snidle, "A simple, accurate method for
    calculation of stresses and deformations in elliptical Hertzian contacts",
    Proc. IMechE C 206 (1992) 139-141: Newton on the seed's F written in
    p = k'**2, F(p) = (alpha + 1) p K - (1 + alpha p) E, dF/dp = -F'(nu),
    K = ellipkm1(p).  4-7 iterations to 2e-14.
    """
    a = _alpha(alpha)
    flat = a.reshape(-1)

    def update(p, idx):
        ai = flat[idx]
        K, E = special.ellipkm1(p), special.ellipe(1 - p)
        f = (ai + 1) * p * K - (1 + ai * p) * E
        dfdp = ((1 + 2 * ai) * K - 3 * ai * E) / 2
        with np.errstate(divide="ignore", invalid="ignore"):  # dF/dp -> 0 as alpha -> 1
            return p - f / dfdp

    p, count = _iterate(update, a ** (-4 / 3), rtol, maxiter)
    return IterativeResult(1 / np.sqrt(p), count)


def bracketing_reference(alpha, xtol=1e-15):
    """A bracketing solve per element (scipy.optimize.toms748) of the same equation.

    Solves ln((lambda**2 E - K)/(K - E)) = ln(alpha) for u = ln(lambda) in
    [t/2, min(t, t/2 + ln(t + 2))], t = ln(alpha) > 0, with scipy's
    ellipkm1(1 - m) and ellipe(m).  One Python-level solve per element: the slow, simple
    reference a user could write.  Where rounding defeats the bracket (K - E
    vanishes in double precision as alpha -> 1) the result is NaN.
    """
    a = _alpha(alpha)
    out = np.empty(a.shape)
    for i, ai in np.ndenumerate(a):
        if ai == 1:
            out[i] = 1.0
            continue
        t = np.log(ai)

        def f(u, t=t):
            p = np.exp(-2 * u)  # 1 - m = 1/lambda**2
            K, E = special.ellipkm1(p), special.ellipe(1 - p)
            return np.log((E / p - K) / (K - E)) - t

        lo, hi = t / 2, min(t, t / 2 + np.log(t + 2))
        try:
            with np.errstate(divide="ignore", invalid="ignore"):
                u = optimize.toms748(f, lo, hi, xtol=xtol, rtol=4 * np.finfo(float).eps)
        except ValueError:  # K - E or the bracket's signs lost to rounding near alpha = 1
            u = np.nan
        out[i] = np.exp(u)
    return out


class TableLookup:
    """lambda(alpha) interpolated in a precomputed table on a uniform grid in ln(alpha).

    The table holds lambda at ``size`` nodes uniform in t = ln(alpha) on
    [0, ln(alpha_max)], computed with :func:`hertz.ellipticity`.  ``kind`` is
    ``"linear"`` (piecewise linear) or ``"cubic"`` (the not-a-knot cubic
    spline of scipy.interpolate.CubicSpline).  The grid is uniform, so the
    interval is found by one multiplication instead of a search.  Outside
    [1, alpha_max] the result is NaN.

    Examples
    --------
    >>> from hertz import methods
    >>> table = methods.TableLookup(1000, "cubic")
    >>> float(table(10.0).round(9)), table.nbytes  # lambda(10) = 4.499447303
    (4.499447301, 31968)
    """

    def __init__(self, size: int, kind: str = "linear", alpha_max: float = 1e15):
        if kind not in ("linear", "cubic"):
            raise ValueError(f"kind must be 'linear' or 'cubic', got {kind!r}")
        if size < 4:
            raise ValueError(f"size must be at least 4, got {size}")
        self.size, self.kind, self.alpha_max = int(size), kind, float(alpha_max)
        t = np.linspace(0.0, np.log(alpha_max), self.size)
        lam = ellipticity(np.exp(t))
        self.step = t[1]
        if kind == "linear":
            # lambda = c[0][i] + c[1][i] (t - t_i) on interval i
            self.coefficients = np.stack([lam[:-1], np.diff(lam) / self.step])
        else:
            # the spline's power-basis coefficients, constant term first
            self.coefficients = interpolate.CubicSpline(t, lam).c[::-1].copy()

    @property
    def nbytes(self) -> int:
        """Memory of the table's coefficients."""
        return self.coefficients.nbytes

    def __call__(self, alpha):
        a = _alpha(alpha)
        with np.errstate(divide="ignore", invalid="ignore"):
            u = np.log(a.reshape(-1)) / self.step
        outside = ~((u >= 0) & (u <= self.size - 1))
        u[outside] = 0.0
        i = np.minimum(u.astype(np.intp), self.size - 2)
        dt = (u - i) * self.step
        c = self.coefficients
        y = np.take(c[-1], i)
        for row in c[-2::-1]:
            y *= dt
            y += np.take(row, i)
        y[outside] = np.nan
        return y.reshape(a.shape)


#: Oba (2014) trial-function coefficients c1..c4 as printed in the seed
#: (Hokada, Iizuka & Takada, eq. (Oba_fitting)); c3 has the wrong sign.
OBA_COEFFICIENTS_PRINTED = (0.666947681, 0.082186314, 0.109262836, 0.028024325)
#: The same with c3 = -0.109262836, which makes the start accurate to 6e-3.
OBA_COEFFICIENTS = (0.666947681, 0.082186314, -0.109262836, 0.028024325)


def oba_2014_start(alpha, coefficients=OBA_COEFFICIENTS):
    """Oba's trial function for lambda (M. Oba, Trans. JSME 80, CM0105, 2014).

    ln(lambda0) = L (c1 + c2 L**(1/2) + c3 L**(3/4) + c4 L), L = ln(alpha),
    seed eq. (Oba_fitting).  Defined for alpha >= 1 only (NaN below).

    Parameters
    ----------
    alpha : array_like
        Curvature ratio(s), >= 1.
    coefficients : tuple of 4 floats, optional
        c1..c4; :data:`OBA_COEFFICIENTS` (sign of c3 corrected, default) or
        :data:`OBA_COEFFICIENTS_PRINTED`.

    Returns
    -------
    ndarray
        The start lambda0.

    Examples
    --------
    >>> from hertz import methods
    >>> float(methods.oba_2014_start(10.0).round(3))  # lambda(10) = 4.499
    4.487
    """
    c1, c2, c3, c4 = coefficients
    with np.errstate(invalid="ignore"):
        L = np.log(np.asarray(alpha, dtype=np.float64))
        return np.exp(L * (c1 + c2 * np.sqrt(L) + c3 * L**0.75 + c4 * L))


def _seed_f(nu, alpha):
    """F, F', F'' of the seed, eqs. (F) and (F', F''), with K, E at parameter nu."""
    K, E = special.ellipk(nu), special.ellipe(nu)
    with np.errstate(divide="ignore", invalid="ignore"):
        f = (alpha + 1) * (1 - nu) * K - (1 + alpha * (1 - nu)) * E
        f1 = (-(1 + 2 * alpha) * K + 3 * alpha * E) / 2
        f2 = -((1 - nu) * (alpha - 1) * K + (1 - alpha * (1 - 3 * nu)) * E) / (4 * nu * (1 - nu))
    return f, f1, f2


def seed_hokada_2025_nu(alpha, iterations=2, corrected=True):
    """The seed's iterate nu_n (= m, the elliptic parameter) after ``iterations`` steps.

    See :func:`seed_hokada_2025`; for alpha < 1 (``corrected=True``) nu is
    the parameter of the problem solved, 1/alpha, which is that of the same
    ellipse.
    """
    a = np.asarray(alpha, dtype=np.float64)
    a = np.where(corrected & (a < 1), 1 / a, a)
    coeffs = OBA_COEFFICIENTS if corrected else OBA_COEFFICIENTS_PRINTED
    nu = 1 - 1 / oba_2014_start(a, coeffs) ** 2
    for _ in range(iterations):
        f, f1, f2 = _seed_f(nu, a)
        with np.errstate(divide="ignore", invalid="ignore"):
            nu = nu - f / (f1 - f * f2 / (2 * f1))
    return nu


def seed_hokada_2025(alpha, iterations=2, corrected=True):
    """The seed's method: Bailey iteration on F(nu) from Oba's start.

    S. Hokada, S. Iizuka, S. Takada, "Proposal for fast computational method
    for Hertzian contact theory" (arXiv 2508.06967, 2025): nu0 = 1 - 1/lambda0**2
    from :func:`oba_2014_start`, then ``iterations`` Bailey steps, eq.
    (recurrence), nu_{n+1} = nu_n - F/(F' - F F''/(2F')), with
    F(nu) = (alpha + 1)(1 - nu) K(nu) - [1 + alpha(1 - nu)] E(nu) and F', F''
    as printed; lambda = (1 - nu)**(-1/2).

    Parameters
    ----------
    alpha : array_like
        Curvature ratio(s).  As printed the method needs alpha >= 1; with
        ``corrected=True`` alpha < 1 uses lambda(alpha) = 1/lambda(1/alpha).
    iterations : int, optional
        Number of Bailey steps (the seed recommends 2).
    corrected : bool, optional
        True (default): c3 = -0.109262836 and the alpha < 1 symmetry.  False:
        exactly as printed (c3 = +0.109262836), which gives NaN above
        alpha ~ 100.

    Returns
    -------
    ndarray
        lambda for each alpha; K and E are evaluated ``iterations`` times.

    Examples
    --------
    >>> from hertz import methods
    >>> float(methods.seed_hokada_2025(10.0).round(12))
    4.499447303155
    """
    a = np.asarray(alpha, dtype=np.float64)
    nu = seed_hokada_2025_nu(a, iterations, corrected)
    with np.errstate(divide="ignore", invalid="ignore"):
        lam = 1 / np.sqrt(1 - nu)
    return np.where(corrected & (a < 1), 1 / lam, lam)
