"""The contact-ellipse ratio lambda(alpha) and the elliptic integrals at the root.

Conventions (used everywhere in hertz): the elliptic integrals take the
*parameter* m = k**2 (scipy's convention, the seed's nu), and

    m = 1 - (b / a)**2,   lambda = a / b = (1 - m)**(-1/2)

for an ellipse of semi-axes a >= b.  The numerical work is done by the
compiled kernel ``hertz._kernel`` (see the comment at the top of
``hertz/_kernel.c`` for the algorithm and the seed's equations it implements).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import _kernel
from ._validate import as_float_array, error_at

#: Bailey steps taken by default; one reaches full double precision.
DEFAULT_ITERATIONS = 1
#: Largest number of Bailey steps accepted (more change nothing).
MAX_ITERATIONS = 3


class EllipseSolution(NamedTuple):
    """Arrays (same shape as alpha) returned by :func:`solve_ellipse`."""

    ellipticity: np.ndarray
    m: np.ndarray
    K: np.ndarray
    E: np.ndarray


def _check_iterations(iterations) -> int:
    if isinstance(iterations, bool) or not isinstance(iterations, (int, np.integer)):
        raise TypeError(f"iterations must be an integer, got {iterations!r}")
    if not 0 <= iterations <= MAX_ITERATIONS:
        raise ValueError(f"iterations must be in 0 .. {MAX_ITERATIONS}, got {iterations}")
    return int(iterations)


def solve_ellipse(alpha: np.ndarray, iterations: int = DEFAULT_ITERATIONS,
                  with_integrals: bool = True) -> EllipseSolution:
    """lambda(alpha) and m, K(m), E(m) at the root for a clean float64 array.

    ``alpha`` must already be a float64 ndarray (any shape).  With
    ``with_integrals=False`` the m, K, E fields are None.
    """
    flat = np.ascontiguousarray(alpha, dtype=np.float64).reshape(-1)
    lam = np.empty_like(flat)
    extra = [np.empty_like(flat) for _ in range(3)] if with_integrals else [None] * 3
    bad = _kernel.solve(flat, lam, *extra, iterations)
    if bad >= 0:
        raise error_at("alpha", np.asarray(alpha), bad, "a positive number (rho_x / rho_y > 0)")
    shape = np.shape(alpha)
    return EllipseSolution(lam.reshape(shape),
                           *(None if x is None else x.reshape(shape) for x in extra))


def ellipticity(alpha, *, iterations=DEFAULT_ITERATIONS):
    """Axis ratio of the Hertz contact ellipse for a curvature ratio.

    Solves ``alpha = (lambda**2 E(m) - K(m)) / (K(m) - E(m))`` with
    ``m = 1 - 1/lambda**2`` (Harris; eq. (alpha_lambda_relation) of Hokada,
    Iizuka & Takada) for ``lambda = l_y / l_x``, the ratio of the contact
    semi-axis along y to the one along x, given ``alpha = rho_x / rho_y``,
    the ratio of the relative curvatures along x and y.

    Parameters
    ----------
    alpha : array_like
        Curvature ratio(s) rho_x / rho_y, any positive value including
        ``inf``.  Values below 1 are allowed: lambda(alpha) = 1/lambda(1/alpha).
    iterations : int, optional
        Bailey steps after the start (0 .. 3).  The default, 1, gives lambda
        to a few units in the last place (measured maximum relative error
        4e-16 on 1 <= alpha <= 1e15); 0 returns the start, about six times
        faster and accurate to 3e-8.

    Returns
    -------
    float or ndarray
        lambda >= 1 for alpha >= 1 (and lambda < 1 for alpha < 1), dimensionless.
        A Python float for scalar input, else a float64 array of alpha's shape.

    Raises
    ------
    TypeError
        If alpha is not real-valued numeric data.
    ValueError
        If any alpha is zero, negative or NaN (the message gives the value
        and its index).

    See Also
    --------
    contact : semi-axes, pressure and approach of a point contact.

    Notes
    -----
    ``alpha = 1`` gives exactly 1 and ``alpha = inf`` gives ``inf``.  For
    alpha > 1.8e19 the root satisfies lambda**2 = alpha (ln(4 lambda) - 1) to
    relative order 1/alpha and is computed from that equation.

    Examples
    --------
    >>> import hertz
    >>> hertz.ellipticity(1.0)
    1.0
    >>> round(hertz.ellipticity(10.0), 12)
    4.499447303155
    >>> hertz.ellipticity([0.1, 1.0, 10.0]).round(6)
    array([0.22225 , 1.      , 4.499447])
    """
    iterations = _check_iterations(iterations)
    arr = as_float_array(alpha, "alpha")
    lam = solve_ellipse(arr, iterations, with_integrals=False).ellipticity
    return float(lam) if lam.ndim == 0 else lam
