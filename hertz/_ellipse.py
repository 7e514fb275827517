"""The contact-ellipse ratio lambda(alpha) and the elliptic integrals at the root.

Conventions (used everywhere in hertz): the elliptic integrals take the
*parameter* m = k**2 (scipy's convention, the seed's nu), and

    m = 1 - (b / a)**2,   lambda = a / b = (1 - m)**(-1/2)

for an ellipse of semi-axes a >= b.  The numerical work is done by the
compiled ufuncs of ``hertz._ufuncs`` (see the comment at the top of
``hertz/_kernel.c`` for the algorithm and the seed's equations it implements).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from . import _interop, _ufuncs
from ._validate import as_float_array, first_failure, is_duck_array, with_index

#: Bailey steps taken by default; one reaches full double precision.
DEFAULT_ITERATIONS = 1
#: Largest number of Bailey steps accepted (more change nothing).
MAX_ITERATIONS = 3

_ELLIPTICITY = (_ufuncs.ellipticity0, _ufuncs.ellipticity1, _ufuncs.ellipticity2,
                _ufuncs.ellipticity3)
_ELLIPSE = (_ufuncs.ellipse0, _ufuncs.ellipse1)


class EllipseSolution(NamedTuple):
    """Arrays (same shape as alpha) returned by :func:`solve_ellipse`."""

    ellipticity: np.ndarray
    m: np.ndarray
    K: np.ndarray
    E: np.ndarray


def _check_iterations(iterations, most=MAX_ITERATIONS) -> int:
    if isinstance(iterations, bool) or not isinstance(iterations, (int, np.integer)):
        raise TypeError(f"iterations must be an integer, got {iterations!r}")
    if not 0 <= iterations <= most:
        raise ValueError(f"iterations must be in 0 .. {most}, got {iterations}")
    return int(iterations)


def _indexed(ufunc, arr: np.ndarray, exc: ValueError) -> ValueError:
    """The loop's error, re-made for the first bad element in C order, with its index."""
    i = first_failure(arr > 0)
    try:
        ufunc(float(arr.reshape(-1)[i]))
    except ValueError as one:
        return with_index(one, arr.shape, i)
    return exc  # pragma: no cover - the scan and the loop agree on what is bad


def solve_ellipse(alpha, iterations: int = DEFAULT_ITERATIONS) -> EllipseSolution:
    """lambda(alpha) and m, K(m), E(m) at the root, float64 arrays of alpha's shape.

    ``iterations`` is 0 (the start) or 1 (one Bailey step, full precision).
    """
    ufunc = _ELLIPSE[_check_iterations(iterations, most=1)]
    arr = as_float_array(alpha, "alpha")
    try:
        return EllipseSolution(*ufunc(arr))
    except ValueError as exc:
        raise _indexed(ufunc, arr, exc) from None


def ellipticity(alpha, *, iterations=DEFAULT_ITERATIONS, out=None):
    """Axis ratio of the Hertz contact ellipse for a curvature ratio.

    Solves ``alpha = (lambda**2 E(m) - K(m)) / (K(m) - E(m))`` with
    ``m = 1 - 1/lambda**2`` (Harris; eq. (alpha_lambda_relation) of Hokada,
    Iizuka & Takada) for ``lambda = l_y / l_x``, the ratio of the contact
    semi-axis along y to the one along x, given ``alpha = rho_x / rho_y``,
    the ratio of the relative curvatures along x and y.

    Elementwise like a numpy ufunc: any real dtype in, float64 out,
    broadcasting, ``out=``; a dask array in gives a dask array out, computed
    only when asked, and a pandas Series, an xarray DataArray or a
    dimensionless pint Quantity gives one of its kind.

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
    out : ndarray, optional
        Where to put the result, as for a ufunc.

    Returns
    -------
    float or ndarray
        lambda >= 1 for alpha >= 1 (and lambda < 1 for alpha < 1), dimensionless.
        A Python float for scalar input, else a float64 array of alpha's shape
        (or ``out``).

    Raises
    ------
    TypeError
        If alpha is not real-valued numeric data.
    ValueError
        If any alpha is zero, negative or NaN (the message gives the value
        and, for an array, its index).

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
    if iterations == 1 and type(iterations) is int:
        ufunc = _ufuncs.ellipticity1
    else:
        ufunc = _ELLIPTICITY[_check_iterations(iterations)]
    if out is None and type(alpha) is float:
        return float(ufunc(alpha))
    if is_duck_array(alpha):
        if out is None:  # block by block; an error names the index in the whole array
            return _interop.dask_map(ufunc, [alpha], names=["alpha"])
        # dtype given, so that dask need not try the ufunc on uninitialised
        # memory to learn the result type (a ValueError there would hide it)
        return ufunc(alpha, out=out, dtype=np.float64)
    if _interop.any_wrapped(alpha):
        plain, recipe = _interop.unwrap([("alpha", alpha, _interop.ONE)])  # pandas, xarray, pint
        try:
            lam = ellipticity(plain[0], iterations=iterations, out=out)
        except ValueError as exc:
            raise recipe.labelled(exc) from None
        return recipe.wrap(lam, _interop.ONE, "ellipticity")
    arr = as_float_array(alpha, "alpha")
    try:
        lam = ufunc(arr) if out is None else ufunc(arr, out=out)
    except ValueError as exc:
        raise _indexed(ufunc, arr, exc) from None
    return float(lam) if out is None and lam.ndim == 0 else lam
