"""Published methods for the contact-ellipse ratio, for comparison with ours.

Each function maps the curvature ratio alpha = rho_x/rho_y (array_like,
alpha >= 1 unless stated) to lambda = a/b, vectorised with numpy, and names
its source and equations.  They are baselines for
``benchmarks/speed_vs_error.py``; use :func:`hertz.ellipticity` for work.
Elliptic integrals take the parameter m = k**2 (scipy.special's convention).
"""

from __future__ import annotations

import numpy as np
from scipy import special

__all__ = [
    "OBA_COEFFICIENTS",
    "OBA_COEFFICIENTS_PRINTED",
    "oba_2014_start",
    "seed_hokada_2025",
]

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
        lambda for each alpha; K and E are evaluated iterations + 1 times.

    Examples
    --------
    >>> from hertz import methods
    >>> float(methods.seed_hokada_2025(10.0).round(12))
    4.499447303155
    """
    a = np.asarray(alpha, dtype=np.float64)
    flip = corrected & (a < 1)
    a = np.where(flip, 1 / a, a)
    coeffs = OBA_COEFFICIENTS if corrected else OBA_COEFFICIENTS_PRINTED
    nu = 1 - 1 / oba_2014_start(a, coeffs) ** 2
    for _ in range(iterations):
        f, f1, f2 = _seed_f(nu, a)
        with np.errstate(divide="ignore", invalid="ignore"):
            nu = nu - f / (f1 - f * f2 / (2 * f1))
    with np.errstate(divide="ignore", invalid="ignore"):
        lam = 1 / np.sqrt(1 - nu)
    return np.where(flip, 1 / lam, lam)
