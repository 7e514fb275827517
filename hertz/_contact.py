"""Bodies, the Hertz point contact and the Hertz line contact (Python face).

The formulas live in C (``hertz/_contact_kernel.c``, which says what it
computes and from which equations); this module checks and shapes the input,
picks the compiled pass, and wraps the results.  One element is computed in
one compiled pass from the radii, angle and moduli to every field.
"""

from __future__ import annotations

import math
import sys
import warnings
from dataclasses import dataclass, field

import numpy as np

from . import _interop, _stress, _tangential, _ufuncs
from ._validate import (
    as_float_array,
    broadcast_shape,
    error_at,
    first_failure,
    index_text,
    int_to_float,
    is_duck_array,
    with_index,
)

__all__ = ["A_OVER_R_LIMIT", "Body", "Contact", "HertzValidityWarning", "LineContact", "contact",
           "line_contact"]

#: The largest a/R at which :func:`contact` and :func:`line_contact` stay silent: a the
#: semi-major axis (half-width), R the smallest |principal radius| of either body
#: (planes excluded). Hertz takes each body for a half-space whose surface is a
#: paraboloid over the contact, which holds for a << R. Finite-element models of real
#: bodies (docs/explanation/curved-bodies.md) are within 0.35% of Hertz's a, b and p0 up
#: to a/R = 0.1 and 1.1% off at 0.2 (a ball in a conforming groove), growing as
#: (a/R)^2: about 3% at this limit (the approach, which grows linearly, about 5%).
#: Beyond it a :class:`HertzValidityWarning` is issued. A Young's modulus in GPa or MPa
#: lands far beyond it: a/R grows as E^(-1/3), 1000 times for GPa typed for Pa, still
#: 10 times with the radii in mm too.
A_OVER_R_LIMIT = 1.0 / 3.0
_INVERSE_LIMIT = 1.0 / A_OVER_R_LIMIT
#: Below this Young's modulus [Pa] the warning suggests E was given in GPa or MPa.
_SMALL_MODULUS = 1e6


class HertzValidityWarning(UserWarning):
    """A contact too large for Hertz's theory, or input in the wrong units.

    Issued once per call of :func:`contact` or :func:`line_contact` (not once per
    element) when the semi-major axis a (the half-width of a line contact) exceeds
    ``A_OVER_R_LIMIT`` = 1/3 of the smallest |principal radius| of either body (planes
    excluded; a concave partner is larger than the ball it holds, so the ball's radius
    counts). The message gives how many contacts of the call are beyond it, the
    largest a/R with its index, and, where a Young's modulus is below 1e6 Pa, that it
    may have been given in GPa or MPa (hertz takes SI units: m, N, Pa). The results
    are still Hertz's exact solution; the real bodies depart from it (about 3% in a,
    b and p0 at the limit, measured by finite elements, and more beyond).

    Dask inputs are not checked (that would compute them).

    Examples
    --------
    Young's modulus typed in GPa (210) instead of Pa (210e9) for a 6 mm bearing ball on
    its race:

    >>> import warnings
    >>> import hertz
    >>> ball = hertz.Body.sphere(6e-3, E=210, nu=0.3)
    >>> race = hertz.Body(Rx=-6.2e-3, Ry=40e-3, E=210, nu=0.3)
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     c = hertz.contact(ball, race, load=1500.0)
    >>> caught[0].category.__name__, f"a = {c.a:.2f} m"
    ('HertzValidityWarning', 'a = 1.84 m')

    To silence it where large contacts are meant:
    ``warnings.simplefilter("ignore", hertz.HertzValidityWarning)``.
    """


# given value: (scalar mode, fused ufunc, load pass ufunc)
_MODES = {"load": (0, _ufuncs.contact_load, _ufuncs.given_load),
          "approach": (1, _ufuncs.contact_approach, _ufuncs.given_approach),
          "p0": (2, _ufuncs.contact_p0, _ufuncs.given_p0)}
_GEOMETRY_NAMES = ("body1.Rx", "body1.Ry", "body2.Rx", "body2.Ry", "angle", "body1.E",
                   "body1.nu", "body2.E", "body2.nu")

# the units of the inputs and fields, for pandas, xarray and pint (hertz._interop)
_GIVEN_UNITS = {"load": _interop.N, "approach": _interop.M, "p0": _interop.PA}
_BODY_UNITS = {"Rx": _interop.M, "Ry": _interop.M, "E": _interop.PA, "nu": _interop.ONE}
#: valid Body fields beside which a bad wrapped field is checked alone (for its labels)
_BODY_STAND_IN = {"Rx": 1.0, "Ry": 1.0, "E": 1.0, "nu": 0.3}
_CONTACT_UNITS = {"a": _interop.M, "b": _interop.M, "load": _interop.N, "p0": _interop.PA,
                  "delta": _interop.M, "stiffness": _interop.N_PER_M}
_GEOMETRY_UNITS = {"ellipticity": _interop.ONE, "alpha": _interop.ONE, "m": _interop.ONE,
                   "K": _interop.ONE, "E": _interop.ONE, "e_star": _interop.PA,
                   "rho_x": _interop.PER_M, "rho_y": _interop.PER_M,
                   "major_axis_angle": _interop.RAD}
_LINE_UNITS = {"half_width": _interop.M, "p0": _interop.PA, "e_star": _interop.PA,
               "rho_sum": _interop.PER_M, "load_per_length": _interop.N_PER_M}

_RADIUS = "a nonzero radius in m (positive convex, negative concave, inf flat)"
_MODULUS = "a positive Young's modulus in Pa (inf for a rigid body)"
#: A rigid body's E = inf enters the kernels as the largest double: 1/E* is then the other
#: body's (1 - nu**2)/E to the last bit (the rigid body's share, below 1e-290 of it for any
#: E up to 1e18 Pa, rounds away); its shear modulus stays inf where the moduli are kept.
_RIGID_E = sys.float_info.max
_POISSON = "a Poisson's ratio in (-1, 0.5]"


def _real(value, name: str):
    """A Python float for a scalar, a private read-only float64 copy of an
    array, or a dask (duck) array unchanged (checked when it is computed)."""
    kind = type(value)
    if kind is float:
        return value
    if kind is int:
        return int_to_float(value, name)
    if is_duck_array(value):
        return value
    arr = as_float_array(value, name)
    if arr.ndim == 0:
        return float(arr)
    arr = np.array(arr, dtype=np.float64, copy=True)
    arr.flags.writeable = False
    return arr


def _require(name: str, value, ok, allowed: str) -> None:
    """Raise the ValueError for the first element of ``value`` where ``ok`` fails."""
    if isinstance(value, float):
        if not ok:
            raise ValueError(f"{name} must be {allowed}, got {value!r}")
    elif isinstance(value, np.ndarray) and not np.all(ok):
        raise error_at(name, value, first_failure(ok), allowed)


def _check_body_fields(Rx, Ry, E, nu) -> None:
    with np.errstate(invalid="ignore"):
        _require("Rx", Rx, (Rx != 0) & (Rx == Rx), _RADIUS)
        _require("Ry", Ry, (Ry != 0) & (Ry == Ry), _RADIUS)
        _require("E", E, E > 0, _MODULUS)
        _require("nu", nu, (nu > -1) & (nu <= 0.5), _POISSON)


def _poisson(E, nu):
    """nu as given, or for a rigid body (every E inf) left out: 0 (it plays no part)."""
    if nu is not None:
        return nu
    if np.all(np.asarray(E, dtype=float) == math.inf):
        return 0.0
    raise TypeError("nu (Poisson's ratio) is required for an elastic body; only a rigid "
                    "body (E = inf) may leave it out")


@dataclass(frozen=True, slots=True, init=False)
class Body:
    """An elastic body near its contact point.

    Each field is kept as a Python float, or as the body's own read-only
    float64 copy of an array (changing the caller's array later changes
    nothing); a dask array is kept as it is and checked when computed.

    A pandas Series or DataFrame, an xarray DataArray or a pint Quantity is
    checked and kept in its kind, around the body's own copy of the values;
    a Quantity is converted to SI (radii in m, E in Pa, nu a plain number),
    and one of another dimension is a TypeError.

    Parameters
    ----------
    Rx, Ry : float or array_like
        Principal radii of curvature of the surface at the contact point [m]:
        positive where the surface is convex, negative where it is concave,
        ``inf`` where it is flat.  Rx lies along the body's own x axis.
    E : float or array_like
        Young's modulus [Pa], positive; ``inf`` for a rigid body (a wall), accepted
        wherever the other body is elastic (the contact's E* is then the other
        body's E / (1 - nu**2)).
    nu : float or array_like
        Poisson's ratio [-], in (-1, 0.5].

    Raises
    ------
    TypeError
        If a field is not real-valued numeric data, or is a numpy masked
        array (pass ``.filled(value)`` or ``.compressed()``: masks are not
        applied).
    ValueError
        If a radius is 0 or NaN, E is not positive (or is NaN), nu is
        outside (-1, 0.5], or a Python int is beyond the double range (the
        message names the field, the value and, for an array, its index).

    Examples
    --------
    >>> import hertz
    >>> ball = hertz.Body.sphere(6e-3, E=210e9, nu=0.3)
    >>> ball.Rx, ball.Ry
    (0.006, 0.006)
    >>> hertz.Body(Rx=-6.2e-3, Ry=40e-3, E=210e9, nu=0.3).Rx  # a concave groove
    -0.0062
    """

    Rx: float | np.ndarray
    Ry: float | np.ndarray
    E: float | np.ndarray
    nu: float | np.ndarray
    _scalar: bool = field(repr=False, compare=False)

    def __init__(self, Rx, Ry, E, nu):
        scalar = type(Rx) is type(Ry) is type(E) is type(nu) is float
        if not scalar and _interop.any_wrapped(Rx, Ry, E, nu):
            # pandas, xarray, pint: checked as numbers, kept in the form given
            _interop.init_fields(self, {"Rx": Rx, "Ry": Ry, "E": E, "nu": nu}, _BODY_UNITS,
                                 _BODY_STAND_IN)
            object.__setattr__(self, "_scalar", False)
            return
        if not scalar:
            Rx, Ry, E, nu = _real(Rx, "Rx"), _real(Ry, "Ry"), _real(E, "E"), _real(nu, "nu")
            scalar = type(Rx) is type(Ry) is type(E) is type(nu) is float
        if not scalar or not (Rx != 0 and Ry != 0 and 0 < E < math.inf and -1 < nu <= 0.5) \
                or Rx != Rx or Ry != Ry:
            _check_body_fields(Rx, Ry, E, nu)
            scalar = scalar and E < math.inf  # a rigid body takes the general path
        setter = object.__setattr__
        setter(self, "Rx", Rx)
        setter(self, "Ry", Ry)
        setter(self, "E", E)
        setter(self, "nu", nu)
        setter(self, "_scalar", scalar)

    @classmethod
    def sphere(cls, R, E, nu=None) -> Body:
        """A sphere (or a spherical cup) near its contact point.

        Parameters
        ----------
        R : float or array_like
            Radius [m]: positive for a ball, negative for a spherical cup
            (the concave seat of a ball joint), nonzero.
        E : float or array_like
            Young's modulus [Pa], positive (``inf``: rigid).
        nu : float or array_like
            Poisson's ratio [-], in (-1, 0.5]; may be left out for a rigid body
            (``E = inf``), whose Poisson's ratio plays no part.

        Returns
        -------
        Body
            ``Body(R, R, E, nu)``.

        Examples
        --------
        >>> import hertz
        >>> hertz.Body.sphere(5e-3, E=210e9, nu=0.3)
        Body(Rx=0.005, Ry=0.005, E=210000000000.0, nu=0.3)
        >>> hertz.Body.sphere([5e-3, -20e-3], E=210e9, nu=0.3).Rx  # a ball and a cup
        array([ 0.005, -0.02 ])
        """
        return cls(R, R, E, _poisson(E, nu))

    @classmethod
    def cylinder(cls, R, E, nu=None) -> Body:
        """A circular cylinder (or a cylindrical groove) near its contact point.

        The cylinder's axis lies along the body's own y axis: it is curved
        along x (``Rx = R``) and straight along y (``Ry = inf``).  Two
        cylinders with parallel axes make a line contact
        (:func:`line_contact`); crossed at an angle, a point contact
        (:func:`contact` with ``angle``).

        Parameters
        ----------
        R : float or array_like
            Radius [m]: positive for a roller, negative for a cylindrical
            groove, nonzero.
        E : float or array_like
            Young's modulus [Pa], positive (``inf``: rigid).
        nu : float or array_like
            Poisson's ratio [-], in (-1, 0.5]; may be left out for a rigid body
            (``E = inf``), whose Poisson's ratio plays no part.

        Returns
        -------
        Body
            ``Body(R, inf, E, nu)``.

        Examples
        --------
        >>> import math
        >>> import hertz
        >>> roller = hertz.Body.cylinder(0.01, E=210e9, nu=0.3)
        >>> roller
        Body(Rx=0.01, Ry=inf, E=210000000000.0, nu=0.3)
        >>> c = hertz.contact(roller, roller, load=100.0, angle=math.pi / 2)  # crossed
        >>> print(f"a = b = {c.a * 1e3:.4f} mm")
        a = b = 0.1866 mm
        """
        return cls(R, math.inf, E, _poisson(E, nu))

    @classmethod
    def plane(cls, E, nu=None) -> Body:
        """A flat surface: an elastic half-space.

        Parameters
        ----------
        E : float or array_like
            Young's modulus [Pa], positive (``inf``: rigid).
        nu : float or array_like
            Poisson's ratio [-], in (-1, 0.5]; may be left out for a rigid body
            (``E = inf``), whose Poisson's ratio plays no part.

        Returns
        -------
        Body
            ``Body(inf, inf, E, nu)``; a plane against a plane has no Hertz
            contact.

        Examples
        --------
        >>> import hertz
        >>> flat = hertz.Body.plane(E=70e9, nu=0.33)
        >>> flat
        Body(Rx=inf, Ry=inf, E=70000000000.0, nu=0.33)
        >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
        >>> print(f"{hertz.contact(ball, flat, load=10.0).p0 / 1e6:.1f} MPa")
        405.1 MPa
        """
        return cls(math.inf, math.inf, E, _poisson(E, nu))

    @property
    def compliance(self):
        """(1 - nu**2)/E [1/Pa], the body's share of 1/E*."""
        return (1.0 - np.square(self.nu)) / self.E


def _read_only(*values) -> None:
    """Make a result's numpy arrays read-only: a frozen result is not changed in place."""
    for x in values:
        if type(x) is np.ndarray:
            x.flags.writeable = False


def _semi_elliptic(p0, r2):
    """Hertz's pressure p0 sqrt(1 - r2) for r2 < 1, 0 outside (and where r2 is NaN: zero load)."""
    p = np.where(r2 < 1.0, p0 * np.sqrt(np.maximum(1.0 - r2, 0.0)), 0.0)
    return float(p) if np.ndim(p) == 0 else p


_GEOMETRY_FIELDS = ("ellipticity", "alpha", "m", "K", "E", "e_star", "rho_x", "rho_y",
                    "major_axis_angle")


class _Deferred:
    """Inputs from which a batch's geometry fields are computed on first access
    (then passed to ``wrap``, if given: the pandas, xarray or pint form)."""

    __slots__ = ("inputs", "shape", "wrap")

    def __init__(self, inputs, shape, wrap=None):
        self.inputs, self.shape, self.wrap = inputs, shape, wrap


def _geometry_field(k: int, doc: str):
    def get(self):
        fields = self._geometry
        if type(fields) is _Deferred:
            deferred, fields = fields, _solve_geometry(fields.inputs, fields.shape)
            if deferred.wrap is not None:
                fields = deferred.wrap(fields)
            object.__setattr__(self, "_geometry", fields)
        return fields[k]

    get.__name__ = _GEOMETRY_FIELDS[k]
    get.__doc__ = doc
    return property(get)


@dataclass(frozen=True, slots=True, eq=False, repr=False)
class Contact:
    """Hertz point contact of two bodies; arrays when any input was an array.

    Made by :func:`contact` (not constructed directly).  The ellipse frame
    has x along the major axis (semi-axis ``a``) and y along the minor axis
    (semi-axis ``b``).  Array fields are the contact's
    own read-only arrays (changing an input array afterwards changes
    nothing).  A zero load is a contact too: a = b = p0 = delta = 0, with
    zero stresses.  The fields that depend on the geometry alone (from
    ``ellipticity`` to ``major_axis_angle``) are computed by a second
    compiled pass the first time one of them is read, so that a batch of
    contacts costs the memory and time of the six load-dependent fields
    only; when one geometry carries many loads they are read-only broadcast
    views.

    Attributes
    ----------
    a, b : float or ndarray
        Semi-major and semi-minor axes of the contact ellipse [m].
    load : float or ndarray
        Normal force P [N].
    p0 : float or ndarray
        Peak (central) pressure [Pa].
    delta : float or ndarray
        Approach of distant points of the two bodies [m].
    stiffness : float or ndarray
        Normal contact stiffness dP/d(delta) = 3 P / (2 delta) [N/m].
    ellipticity : float or ndarray
        a / b >= 1 [-].
    alpha : float or ndarray
        Curvature ratio rho_x / rho_y >= 1 [-].
    m : float or ndarray
        Elliptic parameter 1 - (b/a)**2 (= k**2) [-].
    K, E : float or ndarray
        Complete elliptic integrals K(m), E(m) of the first and second kind [-].
    e_star : float or ndarray
        E* [Pa], 1/E* = (1 - nu1**2)/E1 + (1 - nu2**2)/E2 (E' = 2 E*).
    rho_x, rho_y : float or ndarray
        Principal relative curvatures [1/m], rho_x >= rho_y > 0.
    major_axis_angle : float or ndarray
        Angle from body 1's x axis to the major axis [rad], in (-pi/2, pi/2];
        0 for a circular contact.
    rho_sum : float or ndarray
        rho_x + rho_y [1/m].
    p_mean : float or ndarray
        Mean pressure P / area = 2 p0 / 3 [Pa].
    area : float or ndarray
        Contact area pi a b [m**2].

    See Also
    --------
    contact : the function that makes a Contact.

    Notes
    -----
    Inputs of other libraries give results of the same kind, held in the
    fields themselves (the geometry fields computed when first read, as for
    numpy arrays): pandas Series (or DataFrames) give Series on the same index, named
    after the field (every pandas input must have the same index: hertz
    does not align); xarray DataArrays give DataArrays on the dimensions
    broadcast by name; pint Quantities are converted to SI and give
    Quantities in SI units (``c.a.to("mm")``); dask arrays give dask arrays,
    computed when asked.  The methods (``pressure``, ``stress``,
    ``subsurface``, ``first_yield_load``) follow the same rules; a stress
    tensor has no pandas form and is a numpy array (..., 3, 3) in the
    index's order, and an xarray one has the dimensions ``row`` and
    ``column`` (labels x, y, z) last.  Mixing dask with pandas, pandas with
    xarray, or pint with either is refused.  Errors for pandas and xarray
    inputs add the labels (coordinates) of the index they name; a bad value
    in a dask array raises when its block is computed, naming the
    parameter, the value and its index in the whole (broadcast) array.

    Examples
    --------
    A steel ball of radius 10 mm on a steel plane, 100 N (the closed forms
    are a = (3 P R / (4 E*))**(1/3), p0 = 3 P / (2 pi a**2)):

    >>> import hertz
    >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
    >>> c = hertz.contact(ball, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
    >>> print(f"a = {c.a * 1e6:.2f} um, p0 = {c.p0 / 1e9:.4f} GPa, "
    ...       f"delta = {c.delta * 1e6:.4f} um")
    a = 186.63 um, p0 = 1.3709 GPa, delta = 3.4829 um
    >>> print(f"E* = {c.e_star / 1e9:.3f} GPa, rho_x = {c.rho_x:.1f} 1/m, "
    ...       f"stiffness = {c.stiffness / 1e6:.2f} N/um")
    E* = 115.385 GPa, rho_x = 100.0 1/m, stiffness = 43.07 N/um
    >>> c.ellipticity, c.major_axis_angle  # a circle
    (1.0, 0.0)
    """

    a: float | np.ndarray
    b: float | np.ndarray
    load: float | np.ndarray
    p0: float | np.ndarray
    delta: float | np.ndarray
    stiffness: float | np.ndarray
    #: the nine geometry fields, or the _Deferred inputs to compute them from
    _geometry: tuple | _Deferred = field(repr=False)
    #: Poisson's ratios (nu1, nu2) of the bodies, for the stresses, then their Young's
    #: moduli (E1, E2), for the tangential compliance
    _nu: tuple = field(repr=False)

    #: the fields a plain twin is made of, with their units (hertz._interop)
    _UNITS = {**_CONTACT_UNITS, **_GEOMETRY_UNITS}

    @classmethod
    def _rebuild(cls, fields, nu):
        """A Contact of the values of ``_UNITS``' fields, in order (hertz._interop's twin
        of plain values, on which a method runs as for numpy input)."""
        return cls(*fields[:6], tuple(fields[6:]), nu)

    def __post_init__(self):
        _read_only(self.a, self.b, self.load, self.p0, self.delta, self.stiffness)

    ellipticity = _geometry_field(0, "a / b >= 1 [-].")
    alpha = _geometry_field(1, "Curvature ratio rho_x / rho_y >= 1 [-].")
    m = _geometry_field(2, "Elliptic parameter 1 - (b/a)**2 [-].")
    K = _geometry_field(3, "Complete elliptic integral of the first kind K(m) [-].")
    E = _geometry_field(4, "Complete elliptic integral of the second kind E(m) [-].")
    e_star = _geometry_field(5, "E* [Pa], 1/E* = (1 - nu1**2)/E1 + (1 - nu2**2)/E2.")
    rho_x = _geometry_field(6, "Larger principal relative curvature [1/m].")
    rho_y = _geometry_field(7, "Smaller principal relative curvature [1/m].")
    major_axis_angle = _geometry_field(
        8, "Angle from body 1's x axis to the major axis [rad], in (-pi/2, pi/2].")

    @property
    def rho_sum(self):
        """rho_x + rho_y [1/m]."""
        return self.rho_x + self.rho_y

    @property
    def p_mean(self):
        """Mean pressure 2 p0 / 3 [Pa]."""
        return self.p0 * (2.0 / 3.0)

    @property
    def area(self):
        """Contact area pi a b [m**2]."""
        return math.pi * self.a * self.b

    def __repr__(self):
        names = ("a", "b", "load", "p0", "delta", "stiffness") + _GEOMETRY_FIELDS
        return "Contact(" + ", ".join(f"{k}={getattr(self, k)!r}" for k in names) + ")"

    def pressure(self, x, y):
        """Contact pressure at (x, y) in the ellipse frame [Pa].

        p0 sqrt(1 - (x/a)**2 - (y/b)**2) inside the ellipse, 0 outside (and
        everywhere for a zero load).

        Parameters
        ----------
        x, y : float or array_like
            Position on the surface [m], x along the major axis, y along the
            minor axis; they broadcast against each other and against the
            contact's shape.  Infinite values are allowed (pressure 0).

        Returns
        -------
        float or ndarray
            The pressure [Pa], >= 0.

        Raises
        ------
        ValueError
            If a coordinate is NaN (the message names it, its value and, for
            an array, its index).

        Examples
        --------
        >>> import hertz
        >>> ball = hertz.Body.sphere(0.01, E=200e9, nu=0.3)
        >>> c = hertz.contact(ball, hertz.Body.plane(E=200e9, nu=0.3), load=100.0)
        >>> bool(c.pressure(0.0, 0.0) == c.p0), float(c.pressure(c.a, 0.0))
        (True, 0.0)
        """
        if _interop.any_foreign(self.a, x, y):
            return _interop.call_method(self, "pressure", (("x", x, "m"), ("y", y, "m")), "Pa")
        x, y = _stress.coordinate(x, "x", "any"), _stress.coordinate(y, "y", "any")
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            return _semi_elliptic(self.p0, np.square(x / self.a) + np.square(y / self.b))

    def tangential_stiffness(self, direction=0.0):
        """No-slip tangential stiffness [N/m] for a force along ``direction``.

        Mindlin's no-slip solution for an elliptical contact, each body with its
        own shear modulus G = E / (2 (1 + nu)) and Poisson's ratio:
        1 / (c_x cos^2 t + c_y sin^2 t) with c_x = sum (K - nu B) / (2 pi G a)
        along the major axis and c_y = sum (K - nu D) / (2 pi G a) along the
        minor axis (B, D Fukushima's; a circle gives 8 a / sum (2 - nu)/G).
        The stiffness relates the force to the displacement's component along
        it; :func:`hertz.tangential_compliance` gives the whole 2x2 matrix.
        0 for a contact without load.  Dissimilar bodies: Goodman's coupling
        is neglected (:func:`hertz.dundurs_beta`).

        Parameters
        ----------
        direction : float or array_like
            Angle of the force from the major axis a [rad] (broadcasts).

        Examples
        --------
        >>> import hertz
        >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
        >>> c = hertz.contact(ball, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
        >>> G = 210e9 / 2.6
        >>> print(f"{c.tangential_stiffness() / (8 * c.a / (2 * 1.7 / G)):.15f}")
        1.000000000000000
        """
        if _interop.any_wrapped(self.a, direction):
            return _interop.call_method(self, "tangential_stiffness",
                                        (("direction", direction, "rad"),), "N/m")
        return _tangential.tangential_stiffness(self, direction)

    def tangential(self, force, mu, direction=0.0) -> _tangential.Tangential:
        """Cattaneo-Mindlin partial slip under a tangential force rising from zero.

        Parameters
        ----------
        force : float or array_like
            Tangential force Q [N], 0 <= Q <= mu P; Q = mu P is the onset of
            sliding (stick zone 0, stiffness 0); more raises ValueError.
        mu : float or array_like
            Coefficient of friction [-], > 0.
        direction : float or array_like
            Angle of the force from the major axis a [rad].

        Returns
        -------
        Tangential
            Stick-ellipse semi-axes (a, b) (1 - Q/(mu P))^(1/3) [m], the
            displacement 3 mu P (1 - (1 - Q/(mu P))^(2/3)) / (2 k) [m], the
            tangent stiffness [N/m], the traction [Pa] (Mindlin 1949).

        Raises
        ------
        ValueError
            mu <= 0, force < 0 or > mu P, a contact without normal load.

        Notes
        -----
        Along a principal axis and, in the stick zone, along any direction, the
        stick ellipse is Mindlin's exact construction.  The approximation (of
        the whole literature) is the slip annulus: its traction is taken along
        the force while the slip there is not exactly parallel to it (a
        Poisson effect, measured by Cerruti quadrature at Q/(mu P) = 0.5 and
        nu = 0.3: up to 9 degrees for a circle, 6 and 7 degrees along the axes
        of a b/a = 0.2 ellipse, 10 degrees at 45 degrees to them).
        Dissimilar bodies: Mindlin's uncoupled solution, Goodman's coupling of
        normal and tangential tractions neglected (exact for elastically
        similar bodies; the result's ``dundurs_beta`` gives its size).

        Examples
        --------
        >>> import hertz
        >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
        >>> c = hertz.contact(ball, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
        >>> t = c.tangential(force=26.25, mu=0.3)  # Q / (mu P) = 7/8
        >>> print(f"{t.stick_a / c.a:.3f}, {t.stiffness / t.no_slip_stiffness:.3f}")
        0.500, 0.500
        """
        if _interop.any_wrapped(self.a, force, mu, direction):
            return _interop.call_method(self, "tangential", (("force", force, "N"), ("mu", mu, ""),
                                                             ("direction", direction, "rad")),
                                        _tangential.TANGENTIAL_UNITS, rtype=_tangential.Tangential)
        return _tangential.partial_slip(self, force, mu, direction)

    def fretting(self, amplitude, mu, direction=0.0) -> _tangential.FrettingLoop:
        """The hysteresis loop of a tangential force cycling between -Q* and Q*.

        Mindlin & Deresiewicz (1953) at constant normal load, Masing's rule.

        Parameters
        ----------
        amplitude : float or array_like
            Q* [N], 0 <= Q* <= mu P.
        mu : float or array_like
            Coefficient of friction [-], > 0.
        direction : float or array_like
            Angle of the force from the major axis a [rad].

        Returns
        -------
        FrettingLoop
            ``energy`` per cycle [J] = 36 (mu P)^2 / (5 k) [1 - (1-q)^(5/3)
            - (5q/6)(1 + (1-q)^(2/3))], q = Q*/(mu P); the branches
            (``unloading``, ``reloading``) and the whole ``loop()`` [N, m].

        Examples
        --------
        >>> import hertz
        >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
        >>> c = hertz.contact(ball, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
        >>> loop = c.fretting(amplitude=1e-3, mu=0.3)  # small: W -> 2 Q*^3 / (9 mu P k)
        >>> k = c.tangential_stiffness()
        >>> q = 1e-3 / 30.0  # W / (2 Q*^3 / (9 mu P k)) = 1 + 2q/3 + O(q^2)
        >>> print(f"{loop.energy / (2 * 1e-9 / (9 * 30.0 * k)):.7f} {1 + 2 * q / 3:.7f}")
        1.0000222 1.0000222
        """
        if _interop.any_wrapped(self.a, amplitude, mu, direction):
            return _interop.call_method(self, "fretting", (("amplitude", amplitude, "N"),
                                                           ("mu", mu, ""),
                                                           ("direction", direction, "rad")),
                                        _tangential.FRETTING_UNITS,
                                        rtype=_tangential.FrettingLoop)
        return _tangential.fretting(self, amplitude, mu, direction)

    def stress(self, x, y, z, body=1):
        """Cauchy stress tensor [Pa] at points of body 1 or 2 below the contact.

        Exact closed forms (the ellipsoidal-coordinate potential solution,
        Thomas & Hoersch 1930; Johnson, *Contact Mechanics*, sec. 3.5), with
        the body's own Poisson's ratio; frictionless normal contact.

        Parameters
        ----------
        x, y, z : float or array_like
            Ellipse frame [m]: x along the major axis a, y along the minor
            axis b, z >= 0 the depth into the body.  They broadcast with
            each other and with the contact's shape.
        body : {1, 2}
            Which body.

        Returns
        -------
        ndarray, shape (..., 3, 3)
            The stress tensor, tension positive, rows and columns x, y, z.
            A contact without load has zero stresses.

        Raises
        ------
        ValueError
            If a coordinate is not finite or a depth is negative (the message
            names it, its value and, for an array, its index), ``body`` is
            not 1 or 2, or the ellipse is longer than the kernels' range
            (b/a < 1e-70: a line contact).

        Examples
        --------
        >>> import hertz
        >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
        >>> c = hertz.contact(ball, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
        >>> s = c.stress(0.0, 0.0, 0.0)
        >>> bool(abs(s[2, 2] + c.p0) < 1e-6 * c.p0)  # sigma_zz = -p0 at the centre
        True
        """
        if _interop.any_foreign(self.a, x, y, z):
            return _interop.call_method(self, "stress", (("x", x, "m"), ("y", y, "m"),
                                                         ("z", z, "m")), "Pa", body,
                                        check=_options_check(body), tensor=True)
        return _stress.point_stress(self.a, self.b, self.p0, _stress.poisson_of(self._nu, body),
                                    x, y, z)

    def subsurface(self, body=1) -> _stress.Subsurface:
        """The largest stresses below the contact in body 1 or 2 and where they are.

        Parameters
        ----------
        body : {1, 2}
            Which body (the stresses depend on its Poisson's ratio).

        Returns
        -------
        Subsurface
            tau_max, von_mises (with their depths), the orthogonal shear
            stress tau_orthogonal and the surface tension at the edge, in Pa
            and m.  For a contact without load every field is 0 (the maxima
            shrink to the surface's origin with the load).

        Raises
        ------
        ValueError
            If ``body`` is not 1 or 2, or the ellipse is longer than the
            kernels' range (b/a < 1e-70: a line contact).

        Examples
        --------
        >>> import hertz
        >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
        >>> c = hertz.contact(ball, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
        >>> m = c.subsurface()
        >>> print(f"{m.tau_max / c.p0:.4f} p0 at z = {m.z_tau_max / c.a:.4f} a")
        0.3100 p0 at z = 0.4809 a
        """
        if _interop.any_foreign(self.a):
            return _interop.call_method(self, "subsurface", (), _stress.SUBSURFACE_UNITS, body,
                                        rtype=_stress.Subsurface, check=_options_check(body))
        return _stress.subsurface(self.a, self.b, self.p0, _stress.poisson_of(self._nu, body))

    def first_yield_load(self, yield_strength, body=1, criterion="von_mises"):
        """The load [N] at which body 1 or 2 first yields.

        The stresses scale with p0 at a fixed shape of the ellipse, so the
        body first yields where the largest von Mises stress (or twice the
        largest shear stress, for ``criterion="tresca"``) reaches the yield
        strength, at a peak pressure p0_y.  The load is computed from the
        geometry alone (Hertz's P = (8 pi / 3) lambda (E(m) p0 / (E* rho_sum))**2 p0,
        lambda = a/b), so it does not depend on this contact's own load,
        which may be zero or so large that it overflows.

        Parameters
        ----------
        yield_strength : float or array_like
            Yield strength of the body in tension [Pa], positive and finite.
        body : {1, 2}
            Which body.
        criterion : {"von_mises", "tresca"}
            The yield criterion.

        Returns
        -------
        float or ndarray
            The normal force P_y [N] at which the body first yields; the
            contact's shape broadcast with ``yield_strength``.

        Raises
        ------
        ValueError
            If ``yield_strength`` is not positive and finite (the message
            names the value and, for an array, its index), ``body`` is not 1
            or 2, or ``criterion`` is not one of the two.

        Examples
        --------
        >>> import hertz
        >>> ball = hertz.Body.sphere(6e-3, E=210e9, nu=0.3)
        >>> race = hertz.Body(Rx=-6.2e-3, Ry=40e-3, E=210e9, nu=0.3)
        >>> c = hertz.contact(ball, race, load=1500.0)
        >>> print(f"{c.first_yield_load(1.5e9):.2f} N")
        2969.17 N
        >>> print(f"{c.first_yield_load(1.5e9, criterion='tresca'):.2f} N")
        2237.12 N
        >>> hertz.contact(ball, race, load=0.0).first_yield_load(1.5e9) == c.first_yield_load(1.5e9)
        True
        """
        if _interop.any_foreign(self.a, yield_strength):
            return _interop.call_method(self, "first_yield_load",
                                        (("yield_strength", yield_strength, "Pa"),), "N", body,
                                        criterion, check=_options_check(body, criterion))
        nu = _stress.poisson_of(self._nu, body)
        lam = self.ellipticity
        unit = _stress.subsurface(1.0, 1.0 / lam, 1.0, nu)  # the maxima for a = 1, p0 = 1
        p0_yield = _stress.yield_p0((unit.von_mises, unit.tau_max), yield_strength, criterion)
        return _stress.load_for_p0(p0_yield, lam, self.E, self.e_star, self.rho_sum)


_ufuncs.register_contact_type(Contact)


def _solve_geometry(inputs, shape):
    """The nine geometry fields of a batch, broadcast to its shape."""
    fields = _ufuncs.contact_geometry(*inputs)
    _read_only(*fields)
    return tuple(x if x.shape == shape else np.broadcast_to(x, shape) for x in fields)


@dataclass(frozen=True, slots=True)
class LineContact:
    """Hertz line contact (2D, per unit length of the contact line).

    Made by :func:`line_contact` (not constructed directly).

    Attributes
    ----------
    half_width : float or ndarray
        Semi-width b of the contact strip [m].
    p0 : float or ndarray
        Peak pressure [Pa].
    e_star : float or ndarray
        E* [Pa] as in :class:`Contact`.
    rho_sum : float or ndarray
        Relative curvature across the line [1/m] (1/R, R the effective radius).
    load_per_length : float or ndarray
        Normal force per unit length [N/m].
    p_mean : float or ndarray
        Mean pressure (pi/4) p0 [Pa] (computed on access).

    Notes
    -----
    The approach of a line contact depends on the size of the bodies, not
    only on the contact, and is not given.  Array fields are the contact's
    own read-only arrays.


    pandas, xarray, pint and dask inputs give results of their kind, as for
    :class:`Contact` (load_per_length in N/m).

    Examples
    --------
    >>> import hertz
    >>> roller = hertz.Body.cylinder(5e-3, E=210e9, nu=0.3)
    >>> lc = hertz.line_contact(roller, hertz.Body.plane(E=210e9, nu=0.3), 1e5)
    >>> print(f"b = {lc.half_width * 1e6:.2f} um, p0 = {lc.p0 / 1e9:.4f} GPa, "
    ...       f"p_mean = {lc.p_mean / 1e9:.4f} GPa")
    b = 74.28 um, p0 = 0.8571 GPa, p_mean = 0.6731 GPa
    """

    half_width: float | np.ndarray
    p0: float | np.ndarray
    e_star: float | np.ndarray
    rho_sum: float | np.ndarray
    load_per_length: float | np.ndarray
    #: Poisson's ratios (nu1, nu2) of the bodies, for the stresses
    _nu: tuple = field(repr=False)

    #: the fields a plain twin is made of, with their units (hertz._interop)
    _UNITS = _LINE_UNITS

    @classmethod
    def _rebuild(cls, fields, nu):
        """A LineContact of the values of ``_UNITS``' fields, in order (hertz._interop)."""
        return cls(*fields, nu)

    def __post_init__(self):
        _read_only(self.half_width, self.p0, self.e_star, self.rho_sum, self.load_per_length)

    @property
    def p_mean(self):
        """Mean pressure (pi/4) p0 [Pa]."""
        return self.p0 * (0.25 * math.pi)

    def pressure(self, x):
        """Contact pressure at a distance x across the line [Pa].

        p0 sqrt(1 - (x/b)**2) for |x| < b (b the half-width), 0 outside
        (and everywhere for a zero load).

        Parameters
        ----------
        x : float or array_like
            Distance across the contact line [m]; it broadcasts against the
            contact's shape.  Infinite values are allowed (pressure 0).

        Returns
        -------
        float or ndarray
            The pressure [Pa], >= 0.

        Raises
        ------
        ValueError
            If x is NaN (the message gives the value and, for an array, its
            index).

        Examples
        --------
        >>> import hertz
        >>> roller = hertz.Body.cylinder(5e-3, E=210e9, nu=0.3)
        >>> lc = hertz.line_contact(roller, hertz.Body.plane(E=210e9, nu=0.3), 1e5)
        >>> lc.pressure([0.0, 0.6 * lc.half_width, lc.half_width]) / lc.p0
        array([1. , 0.8, 0. ])
        """
        if _interop.any_foreign(self.half_width, x):
            return _interop.call_method(self, "pressure", (("x", x, "m"),), "Pa")
        x = _stress.coordinate(x, "x", "any")
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            return _semi_elliptic(self.p0, np.square(x / self.half_width))

    def stress(self, x, z, body=1):
        """Cauchy stress tensor [Pa] in body 1 or 2 below the line contact.

        McEwen's closed forms (1949; Johnson, *Contact Mechanics*, sec. 4.2)
        in plane strain, frictionless normal contact, with the body's own
        Poisson's ratio.

        Parameters
        ----------
        x, z : float or array_like
            Position [m]: x across the strip, z >= 0 the depth into the
            body; the contact line runs along y.  They broadcast with each
            other and with the contact's shape.
        body : {1, 2}
            Which body.

        Returns
        -------
        ndarray, shape (..., 3, 3)
            The stress tensor, tension positive, rows and columns x, y, z;
            sigma_yy = nu (sigma_xx + sigma_zz) and the shear stresses with y
            are 0.  A contact without load has zero stresses.

        Raises
        ------
        ValueError
            If a coordinate is not finite or a depth is negative (the message
            names it, its value and, for an array, its index), or ``body``
            is not 1 or 2.

        Examples
        --------
        Below the centre, at the depth of the largest shear stress:

        >>> import hertz
        >>> roller = hertz.Body.cylinder(5e-3, E=210e9, nu=0.3)
        >>> lc = hertz.line_contact(roller, hertz.Body.plane(E=210e9, nu=0.3), 1e5)
        >>> s = lc.stress(0.0, 0.786 * lc.half_width) / lc.p0
        >>> print(f"sxx = {s[0, 0]:.4f}, syy = {s[1, 1]:.4f}, szz = {s[2, 2]:.4f} (p0)")
        sxx = -0.1856, syy = -0.2916, szz = -0.7862 (p0)
        >>> print(f"tau = {(s[0, 0] - s[2, 2]) / 2:.4f} p0")
        tau = 0.3003 p0
        """
        if _interop.any_foreign(self.half_width, x, z):
            return _interop.call_method(self, "stress", (("x", x, "m"), ("z", z, "m")), "Pa",
                                        body, check=_options_check(body), tensor=True)
        return _stress.line_stress(self.half_width, self.p0,
                                   _stress.poisson_of(self._nu, body), x, z)

    def subsurface(self, body=1) -> _stress.LineSubsurface:
        """The largest stresses below the line contact in body 1 or 2 and where they are.

        Parameters
        ----------
        body : {1, 2}
            Which body (the out-of-plane stress depends on its Poisson's
            ratio).

        Returns
        -------
        LineSubsurface
            tau_max and von_mises with their depths, and the largest
            |tau_xz| with its position, in Pa and m.  For a contact without
            load every field is 0.

        Raises
        ------
        ValueError
            If ``body`` is not 1 or 2.

        Examples
        --------
        >>> import hertz
        >>> roller = hertz.Body.cylinder(5e-3, E=210e9, nu=0.3)
        >>> lc = hertz.line_contact(roller, hertz.Body.plane(E=210e9, nu=0.3), 1e5)
        >>> m = lc.subsurface()
        >>> print(f"{m.tau_max / lc.p0:.4f} p0 at z = {m.z_tau_max / lc.half_width:.4f} b")
        0.3003 p0 at z = 0.7862 b
        >>> print(f"von Mises {m.von_mises / lc.p0:.4f} p0 at z = "
        ...       f"{m.z_von_mises / lc.half_width:.4f} b")
        von Mises 0.5575 p0 at z = 0.7043 b
        """
        if _interop.any_foreign(self.half_width):
            return _interop.call_method(self, "subsurface", (), _stress.LINE_SUBSURFACE_UNITS,
                                        body, rtype=_stress.LineSubsurface,
                                        check=_options_check(body))
        return _stress.line_subsurface(self.half_width, self.p0,
                                       _stress.poisson_of(self._nu, body))


def _options_check(body, criterion=None):
    """The check of a method's ``body`` (and yield ``criterion``) that hertz._interop runs
    for pandas, xarray, pint or dask values before any block is computed."""
    def check():
        _stress.poisson_of((0.3, 0.3), body)
        if criterion is not None:
            _stress.yield_p0((1.0, 1.0), 1.0, criterion)

    return check


def _check_body(body, name: str) -> Body:
    if type(body) is not Body and not isinstance(body, Body):
        raise TypeError(f"{name} must be a hertz.Body, got {type(body).__name__}")
    return body


def _check_size(a, body1: Body, body2: Body, axis: str = "a") -> None:
    """Issue one HertzValidityWarning where a (float or array; ``axis`` "b" for the
    half-width of a line contact) exceeds A_OVER_R_LIMIT times the smallest |radius| of
    the two bodies (a plane's, inf, never counts)."""
    if type(a) is float:
        t = a * _INVERSE_LIMIT
        if (-t < body1.Rx < t or -t < body1.Ry < t or -t < body2.Rx < t
                or -t < body2.Ry < t):
            _warn_size(a, body1, body2, axis, (), 0, 1)
        return
    radii = (body1.Rx, body1.Ry, body2.Rx, body2.Ry)
    if all(type(r) is float for r in radii):  # one geometry: one cutoff settles every a
        cut = _cutoff(min(abs(r) for r in radii))
        if not np.size(a) or np.max(a) <= cut:  # (a NaN, never expected, goes on)
            return
        large = a > cut
    else:
        large = _beyond_limit(a, radii)
    where = np.flatnonzero(large)
    if where.size:
        # the largest a/R among the contacts beyond the limit, computed for those only
        shape = np.shape(large)

        def picked(x):
            return np.broadcast_to(x, shape).reshape(-1)[where]

        smallest = np.minimum(np.minimum(np.abs(picked(radii[0])), np.abs(picked(radii[1]))),
                              np.minimum(np.abs(picked(radii[2])), np.abs(picked(radii[3]))))
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            ratio = picked(a) / smallest
        i = int(where[np.argmax(np.where(np.isnan(ratio), -np.inf, ratio))])
        _warn_size(a, body1, body2, axis, shape, i, int(where.size))


#: Elements per block of _beyond_limit: its buffers stay in the cache.
_BLOCK = 16384


def _beyond_limit(a, radii) -> np.ndarray:
    """``a / A_OVER_R_LIMIT > |R|`` for any of the four radii, elementwise (the scalar
    test's operations, so the same bits), in blocks that keep the temporaries in the
    cache: the check costs a small fraction of the contact it guards."""
    shape = np.broadcast_shapes(np.shape(a), *(np.shape(r) for r in radii))
    flat = [np.broadcast_to(x, shape).reshape(-1) if np.shape(x) == shape else None
            for x in (a, *radii)]
    out = np.zeros(shape, dtype=bool)
    if any(f is None for f in flat):  # some input broadcast: the plain form
        with np.errstate(over="ignore", invalid="ignore"):
            t = np.multiply(a, _INVERSE_LIMIT)
            for r in radii:
                out |= np.abs(r) < t
        return out
    a_flat, r_flat = flat[0], flat[1:]
    o = out.reshape(-1)
    n = a_flat.size
    t = np.empty(min(n, _BLOCK))
    m = np.empty_like(t)
    hit = np.empty(t.size, dtype=bool)
    with np.errstate(over="ignore", invalid="ignore"):
        for start in range(0, n, _BLOCK):
            stop = min(n, start + _BLOCK)
            k = stop - start
            np.multiply(a_flat[start:stop], _INVERSE_LIMIT, out=t[:k])
            ob = o[start:stop]
            for r in r_flat:
                np.abs(r[start:stop], out=m[:k])
                np.less(m[:k], t[:k], out=hit[:k])
                ob |= hit[:k]
    return out


def _cutoff(radius: float) -> float:
    """The largest a with fl(a / A_OVER_R_LIMIT) <= radius: ``a > cutoff`` is the scalar
    test, bit for bit, with one comparison per element."""
    cut = radius * A_OVER_R_LIMIT
    while cut * _INVERSE_LIMIT > radius:
        cut = math.nextafter(cut, -math.inf)
    while cut < math.inf and math.nextafter(cut, math.inf) * _INVERSE_LIMIT <= radius:
        cut = math.nextafter(cut, math.inf)
    return cut


def _warn_counted(a, body1: Body, body2: Body, count: int, a_max: float,
                  r_max: float, address: int = 0) -> None:
    """The warning for the ``count`` contacts the kernel found beyond the limit, naming the
    one of the largest a/R, whose a, smallest |R| and the address of its a (0 if unknown)
    it reported: found at that address, or by its a (one comparison over the batch), its
    radii confirming it."""
    shape = np.shape(a)
    flat = np.asarray(a).reshape(-1)
    radii = [np.broadcast_to(r, shape).reshape(-1) for r in
             (body1.Rx, body1.Ry, body2.Rx, body2.Ry)]

    def confirmed(k):
        return flat[k] == a_max and min(abs(float(r[k])) for r in radii) == r_max

    k, rest = divmod(address - flat.ctypes.data, flat.itemsize)
    if address and flat.flags.c_contiguous and rest == 0 and 0 <= k < flat.size \
            and confirmed(k):
        i = int(k)
    else:
        candidates = np.flatnonzero(flat == a_max)
        i = next((int(k) for k in candidates if confirmed(k)),
                 int(candidates[0]) if candidates.size else 0)
    _warn_size(a, body1, body2, "a", shape, i, count)


def _warn_size(a, body1: Body, body2: Body, axis: str, shape, i: int, count: int) -> None:
    """The HertzValidityWarning for ``count`` contacts of ``shape``, naming element i
    (the largest a/R)."""
    def at(x):
        return float(np.broadcast_to(x, shape).reshape(-1)[i])

    a_i = at(a)
    r_i = min(abs(at(r)) for r in (body1.Rx, body1.Ry, body2.Rx, body2.Ry))
    name = "semi-major axis a" if axis == "a" else "half-width b"
    where = index_text(shape, i)
    if not shape:
        head = (f"the {name} = {a_i:.4g} m is {a_i / r_i:.4g} times the smallest radius of "
                f"curvature of the bodies (|R| = {r_i:.4g} m)")
    else:
        head = (f"{count} of {math.prod(shape)} contacts have a {name} above "
                f"{A_OVER_R_LIMIT:.3g} of the smallest radius of curvature |R| of their "
                f"bodies; the largest, {axis}/R = {a_i / r_i:.4g}{where} ({axis} = {a_i:.4g} m, "
                f"|R| = {r_i:.4g} m)")
    moduli = ((f"E{k}", at(b.E)) for k, b in ((1, body1), (2, body2)))
    small = [f"{k} = {value:.4g} Pa" for k, value in moduli if value < _SMALL_MODULUS]
    if small:
        hint = (f"; {' and '.join(small)}{where} "
                f"{'looks like a value' if len(small) == 1 else 'look like values'} in GPa or "
                "MPa: hertz takes SI units (m, N, Pa)")
    else:
        hint = "; if this is not meant, check the units: hertz takes SI units (m, N, Pa)"
    # stacklevel: the first frame outside hertz, so that the warning names the caller
    frame, level = sys._getframe(0), 1
    while frame is not None and frame.f_globals.get("__name__", "").split(".")[0] == "hertz":
        frame, level = frame.f_back, level + 1
    warnings.warn(f"{head}: Hertz's theory holds for {axis} << R (real bodies depart from "
                  f"it by about 3% at {axis}/R = {A_OVER_R_LIMIT:.3g}, more beyond){hint}",
                  HertzValidityWarning, stacklevel=level)


def _finish(values, cls, *extra):
    """The result object; 0-d results become Python floats."""
    if np.ndim(values[0]) == 0:
        return cls(*(float(v) for v in values), *extra)
    return cls(*values, *extra)


def _first_error(status_ufunc, scalar, args, shape, extra=()):
    """The ValueError of the first bad element (C order) with its index."""
    codes = status_ufunc(*args)
    i = first_failure(np.broadcast_to(codes, shape) == 0)
    row = [float(np.broadcast_to(a, shape).reshape(-1)[i]) for a in args]
    try:
        scalar(*extra, *row)
    except ValueError as exc:
        return with_index(exc, shape, i)
    return None  # pragma: no cover - the status pass and the loop agree


def contact(body1: Body, body2: Body, load=None, angle=0.0, *, approach=None,
            p0=None) -> Contact:
    """Hertz point contact of two elastic bodies pressed together.

    Parameters
    ----------
    body1, body2 : Body
        The two bodies; every field may be an array (all broadcast together).
    load : float or array_like, optional
        Normal force P [N], >= 0.  Give exactly one of ``load``, ``approach``
        and ``p0``.
    angle : float or array_like, optional
        Angle from body 1's x axis to body 2's x axis [rad] (default 0: the
        principal planes coincide).
    approach : float or array_like, optional
        Approach delta of distant points of the bodies [m], >= 0 (the
        overlap of a DEM code); the load is then computed.
    p0 : float or array_like, optional
        Peak pressure [Pa], >= 0; the load is then computed.

    Returns
    -------
    Contact
        Semi-axes, pressure, approach, stiffness and the ellipse parameters:
        Python floats for scalar input, else arrays of the broadcast shape.
        Dask arrays in give a Contact of dask arrays, computed (and checked)
        only when asked; pandas, xarray and pint inputs give Series,
        DataArrays and Quantities (see :class:`Contact`).

    Raises
    ------
    TypeError
        If a body is not a :class:`Body`, an argument is not numeric, or not
        exactly one of load, approach and p0 is given.
    ValueError
        For a negative, infinite or NaN load, approach or p0, a non-finite
        angle, shapes that do not broadcast, and bodies without a Hertz point
        contact (line contacts, plane on plane, over-conforming concave
        surfaces, or a curvature ratio beyond the double range), and two rigid
        bodies (both E = inf).  The message
        names the parameter, the value and, for arrays, the index.

    Notes
    -----
    Every field is within a few ulp of an exact evaluation for any input
    whose true results are normal doubles: radii from 1e-308 to 1e308,
    nearly conforming surfaces at any angle, loads from 1e-300 to 1e300.
    Swapping the bodies (and the sign of the angle) gives the same bits.

    Examples
    --------
    A bearing ball on its inner race (the ``hertz`` command's default scene):

    >>> import hertz
    >>> ball = hertz.Body(Rx=6e-3, Ry=6e-3, E=210e9, nu=0.3)
    >>> race = hertz.Body(Rx=-6.2e-3, Ry=40e-3, E=210e9, nu=0.3)
    >>> c = hertz.contact(ball, race, load=1500.0)
    >>> print(f"a = {c.a * 1e3:.4f} mm, b = {c.b * 1e3:.4f} mm, p0 = {c.p0 / 1e9:.3f} GPa")
    a = 1.8387 mm, b = 0.1866 mm, p0 = 2.087 GPa
    >>> round(hertz.contact(ball, race, approach=c.delta).load, 9)
    1500.0
    >>> print(f"{hertz.contact(ball, race, p0=2e9).load:.1f} N gives p0 = 2 GPa")
    1319.7 N gives p0 = 2 GPa
    """
    if approach is None and p0 is None:
        # two bodies of floats and a float load: one C call, the check of Hertz's
        # validity included (NotImplemented for anything else)
        c = _ufuncs.contact_bodies(0, body1, body2, angle, load)
        if c is not NotImplemented:
            return c
        if load is None:
            raise TypeError("give exactly one of load (N), approach (m) and p0 (Pa)")
        name, value = "load", load
    elif (load is None) + (approach is None) + (p0 is None) != 2:
        raise TypeError("give exactly one of load (N), approach (m) and p0 (Pa)")
    else:
        name, value = ("approach", approach) if p0 is None else ("p0", p0)
    mode, fused, given = _MODES[name]
    _check_body(body1, "body1")
    _check_body(body2, "body2")
    kind_v, kind_a = type(value), type(angle)
    if (body1._scalar and body2._scalar and (kind_v is float or kind_v is int)
            and (kind_a is float or kind_a is int)):
        try:
            c = _ufuncs.contact(mode, body1.Rx, body1.Ry, body2.Rx, body2.Ry, angle,
                                body1.E, body1.nu, body2.E, body2.nu, value)
        except OverflowError:  # a Python int beyond the double range: name it
            int_to_float(value, name), int_to_float(angle, "angle")
            raise
        _check_size(c.a, body1, body2)
        return c
    if _interop.any_wrapped(value, angle, body1.Rx, body1.Ry, body1.E, body1.nu, body2.Rx,
                            body2.Ry, body2.E, body2.nu):
        return _wrapped_contact(body1, body2, name, value, angle)  # pandas, xarray, pint
    args = [body1.Rx, body1.Ry, body2.Rx, body2.Ry, _kept_arg(angle, "angle"), body1.E,
            body1.nu, body2.E, body2.nu, _real_arg(value, name)]
    args[5], args[7] = _kernel_moduli(body1.E, body2.E)
    geometry = args[:9]
    if any(is_duck_array(a) for a in args):
        return _dask_contact(fused, args, (body1.nu, body2.nu, body1.E, body2.E))
    geometry_shape = broadcast_shape(**dict(zip(_GEOMETRY_NAMES, geometry, strict=True)))
    shape = broadcast_shape(**dict(zip(_GEOMETRY_NAMES, geometry, strict=True)),
                            **{name: args[9]})
    try:
        if math.prod(geometry_shape) == math.prod(shape):
            if not shape:  # numpy scalars or 0-d arrays: the scalar path
                c = _ufuncs.contact(mode, *(float(x) for x in args))
            else:
                _ufuncs.beyond()  # the kernel counts the contacts beyond Hertz's validity
                c = Contact(*fused(*args), _Deferred(geometry, shape),
                            (body1.nu, body2.nu, body1.E, body2.E))
                count, a_max, r_max, address = _ufuncs.beyond()
                if count:
                    _warn_counted(c.a, body1, body2, count, a_max, r_max, address)
                return c
        else:
            # One geometry carries many loads: solve each geometry once and
            # broadcast its fields (read-only views) over the loads.
            coefficients = _ufuncs.contact_coefficients(*geometry)
            fields = coefficients[:9]
            given_values = given(fields[0], *coefficients[9:], args[9])
            c = Contact(*given_values, tuple(np.broadcast_to(x, shape) for x in fields),
                        (body1.nu, body2.nu, body1.E, body2.E))
    except ValueError as exc:
        err = _first_error(_ufuncs.contact_status, _ufuncs.contact, args, shape, (mode,))
        raise (err or exc) from None
    _check_size(c.a, body1, body2)
    return c


def _kernel_moduli(e1, e2):
    """The Young's moduli the kernels take: a rigid body's inf as ``_RIGID_E``; two rigid
    bodies (E* infinite) are a ValueError naming the index (for dask arrays, a NaN that the
    kernel refuses when computed)."""
    if type(e1) is float and type(e2) is float:
        if e1 < math.inf and e2 < math.inf:
            return e1, e2
        if e1 == e2:
            raise ValueError(_BOTH_RIGID + ", got body1.E = body2.E = inf")
        return min(e1, _RIGID_E), min(e2, _RIGID_E)
    if is_duck_array(e1) or is_duck_array(e2):
        both = (e1 == math.inf) & (e2 == math.inf)
        return (np.where(both, math.nan, np.minimum(e1, _RIGID_E)),
                np.where(both, math.nan, np.minimum(e2, _RIGID_E)))
    r1, r2 = np.isinf(e1), np.isinf(e2)
    if not (r1.any() or r2.any()):
        return e1, e2
    both = r1 & r2
    if both.any():
        shape = np.shape(both)
        raise ValueError(_BOTH_RIGID + f", got body1.E = body2.E = inf"
                         f"{index_text(shape, first_failure(~both))}")
    return np.minimum(e1, _RIGID_E), np.minimum(e2, _RIGID_E)


_BOTH_RIGID = ("body1.E and body2.E must not both be inf: at most one body may be rigid "
               "(E* would be infinite)")


def _kept_arg(value, name):
    """A geometry input a Contact keeps (its geometry fields are computed later): a
    private read-only copy of an array, so that the caller may change theirs."""
    value = _real_arg(value, name)
    if type(value) is np.ndarray:
        value = value.copy()
        value.flags.writeable = False
    return value


def _real_arg(value, name):
    """A float64 array (no copy for float64 input) or a duck array, for one call."""
    if type(value) is float or is_duck_array(value):
        return value
    return as_float_array(value, name)


def line_contact(body1: Body, body2: Body, load_per_length) -> LineContact:
    """Hertz line contact of two bodies with parallel generators (2D, plane strain).

    Parameters
    ----------
    body1, body2 : Body
        Cylinders (``Body.cylinder``, axis along y) or planes, with their axes
        parallel; the contact line runs along y.
    load_per_length : float or array_like
        Normal force per unit length of the line [N/m], >= 0.

    Returns
    -------
    LineContact
        half_width = (4 P' / (pi E* rho))**(1/2), p0 = 2 P' / (pi half_width).

    Raises
    ------
    TypeError
        If a body is not a :class:`Body` or an argument is not numeric.
    ValueError
        For a negative, infinite or NaN load, or bodies that do not make a
        line contact (the message names the value and, for arrays, the index).

    Examples
    --------
    >>> import hertz
    >>> roller = hertz.Body.cylinder(5e-3, E=210e9, nu=0.3)
    >>> lc = hertz.line_contact(roller, hertz.Body.plane(E=210e9, nu=0.3), 1e5)
    >>> print(f"{lc.half_width * 1e6:.2f} um, {lc.p0 / 1e9:.4f} GPa")
    74.28 um, 0.8571 GPa
    """
    _check_body(body1, "body1")
    _check_body(body2, "body2")
    kind = type(load_per_length)
    if body1._scalar and body2._scalar and (kind is float or kind is int):
        if kind is int:
            load_per_length = int_to_float(load_per_length, "load_per_length")
        lc = LineContact(*_ufuncs.line_contact(body1.Rx, body1.Ry, body2.Rx, body2.Ry,
                                               body1.E, body1.nu, body2.E, body2.nu,
                                               load_per_length), (body1.nu, body2.nu))
        _check_size(lc.half_width, body1, body2, "b")
        return lc
    if _interop.any_wrapped(load_per_length, body1.Rx, body1.Ry, body1.E, body1.nu, body2.Rx,
                            body2.Ry, body2.E, body2.nu):
        return _wrapped_line_contact(body1, body2, load_per_length)  # pandas, xarray, pint
    args = [body1.Rx, body1.Ry, body2.Rx, body2.Ry, body1.E, body1.nu, body2.E, body2.nu,
            _real_arg(load_per_length, "load_per_length")]
    args[4], args[6] = _kernel_moduli(body1.E, body2.E)
    if any(is_duck_array(a) for a in args):
        return _dask_line(args, (body1.nu, body2.nu))
    names = [n for n in _GEOMETRY_NAMES if n != "angle"] + ["load_per_length"]
    shape = broadcast_shape(**dict(zip(names, args, strict=True)))
    try:
        lc = _finish(_ufuncs.line(*args), LineContact, (body1.nu, body2.nu))
    except ValueError as exc:
        err = _first_error(_ufuncs.line_status, _ufuncs.line_contact, args, shape)
        raise (err or exc) from None
    _check_size(lc.half_width, body1, body2, "b")
    return lc


# --------------------------------------------------------------------------- other libraries

def _body_items(body, prefix):
    return [(f"{prefix}.{k}", getattr(body, k), u) for k, u in _BODY_UNITS.items()]


def _wrapped_contact(body1, body2, name, value, angle):
    """:func:`contact` for pandas, xarray or pint inputs: unwrap, solve, wrap."""
    items = (_body_items(body1, "body1") + _body_items(body2, "body2")
             + [("angle", angle, _interop.RAD), (name, value, _GIVEN_UNITS[name])])
    plain, recipe = _interop.unwrap(items)
    try:
        result = contact(Body(*plain[0:4]), Body(*plain[4:8]), angle=plain[8],
                         **{name: plain[9]})
    except ValueError as exc:
        raise recipe.labelled(exc) from None
    fields = [recipe.wrap(getattr(result, k), u, k) for k, u in _CONTACT_UNITS.items()]

    def wrap_geometry(values):
        return tuple(recipe.wrap(v, u, k)
                     for v, (k, u) in zip(values, _GEOMETRY_UNITS.items(), strict=True))

    geometry = result._geometry
    if type(geometry) is _Deferred:  # computed (and wrapped) when first read, as for numpy
        geometry = _Deferred(geometry.inputs, geometry.shape, wrap_geometry)
    else:
        geometry = wrap_geometry(getattr(result, k) for k in _GEOMETRY_UNITS)
    return Contact(*fields, geometry, (body1.nu, body2.nu, body1.E, body2.E))


def _wrapped_line_contact(body1, body2, load_per_length):
    """:func:`line_contact` for pandas, xarray or pint inputs."""
    items = (_body_items(body1, "body1") + _body_items(body2, "body2")
             + [("load_per_length", load_per_length, _interop.N_PER_M)])
    plain, recipe = _interop.unwrap(items)
    try:
        result = line_contact(Body(*plain[0:4]), Body(*plain[4:8]), plain[8])
    except ValueError as exc:
        raise recipe.labelled(exc) from None
    return LineContact(*(recipe.wrap(getattr(result, k), u, k) for k, u in _LINE_UNITS.items()),
                       (body1.nu, body2.nu))


def _dask_contact(fused, args, nu):
    """A Contact of dask arrays: the six load fields and the nine geometry fields (all
    of the broadcast shape and chunks), computed when asked."""
    names = _GEOMETRY_NAMES + tuple(k for k, (_, f, _) in _MODES.items() if f is fused)
    fields = _interop.dask_map(fused, args, nout=6, names=names)

    def geometry(*values):
        return _ufuncs.contact_geometry(*values[:9])

    return Contact(*fields, _interop.dask_map(geometry, args, nout=9, names=names), nu)


def _dask_line(args, nu):
    """A LineContact of dask arrays."""
    names = tuple(k for k in _GEOMETRY_NAMES if k != "angle") + ("load_per_length",)
    return LineContact(*_interop.dask_map(_ufuncs.line, args, nout=5, names=names), nu)


# the scalar path reads Body's slots in C and warns through _check_size
_ufuncs.register_validity(Body, _INVERSE_LIMIT, _check_size)
