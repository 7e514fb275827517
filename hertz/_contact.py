"""Bodies, the Hertz point contact and the Hertz line contact.

Formulas (Hokada, Iizuka & Takada, sec. 2; Johnson, *Contact Mechanics*,
1985, ch. 4), with lambda = a/b, m = 1 - 1/lambda**2, K = K(m), E = E(m),
rho_+ = rho_x + rho_y and q = P / (pi lambda E*):

    b = (3 E q / rho_+)**(1/3),      a = lambda b,
    p0 = 3 P / (2 pi a b),           delta = (K/2) (9 rho_+ q**2 / E)**(1/3).

p0 and delta are evaluated in forms that are exact at P = 0 (no 0/0).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._ellipse import solve_ellipse
from ._geometry import relative_curvature
from ._validate import as_float_array, broadcast_shape, index_text, require

__all__ = ["Body", "Contact", "LineContact", "contact", "line_contact"]


def _scalar_or_array(arr: np.ndarray):
    return float(arr) if arr.ndim == 0 else arr


def _semi_elliptic(p0, r2):
    """Hertz's pressure p0 sqrt(1 - r2) for r2 < 1, 0 outside (and where r2 is NaN: zero load)."""
    return _scalar_or_array(np.asarray(np.where(r2 < 1.0, p0 * np.sqrt(np.maximum(1.0 - r2, 0.0)),
                                                0.0)))


def _radius(value, name: str) -> np.ndarray:
    arr = as_float_array(value, name)
    require(name, arr, (arr != 0) & ~np.isnan(arr),
            "a nonzero radius in m (positive convex, negative concave, inf flat)")
    return arr


@dataclass(frozen=True)
class Body:
    """An elastic body near its contact point.

    Parameters
    ----------
    Rx, Ry : float or array_like
        Principal radii of curvature of the surface at the contact point [m]:
        positive where the surface is convex, negative where it is concave,
        ``inf`` where it is flat.  Rx lies along the body's own x axis.
    E : float or array_like
        Young's modulus [Pa], positive and finite.
    nu : float or array_like
        Poisson's ratio [-], in (-1, 0.5].

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

    def __post_init__(self):
        e = as_float_array(self.E, "E")
        require("E", e, (e > 0) & np.isfinite(e), "a positive, finite Young's modulus in Pa")
        nu = as_float_array(self.nu, "nu")
        require("nu", nu, (nu > -1) & (nu <= 0.5), "a Poisson's ratio in (-1, 0.5]")
        for name, value in (("Rx", _radius(self.Rx, "Rx")), ("Ry", _radius(self.Ry, "Ry")),
                            ("E", e), ("nu", nu)):
            object.__setattr__(self, name, _scalar_or_array(value))

    @classmethod
    def sphere(cls, R, E, nu) -> Body:
        """A sphere of radius ``R`` [m] (negative: a spherical cup)."""
        return cls(R, R, E, nu)

    @classmethod
    def cylinder(cls, R, E, nu) -> Body:
        """A cylinder of radius ``R`` [m] with its axis along the body's y axis."""
        return cls(R, np.inf, E, nu)

    @classmethod
    def plane(cls, E, nu) -> Body:
        """A flat surface (an elastic half-space)."""
        return cls(np.inf, np.inf, E, nu)

    @property
    def compliance(self):
        """(1 - nu**2)/E [1/Pa], the body's share of 1/E*."""
        return (1.0 - np.square(self.nu)) / self.E


@dataclass(frozen=True)
class Contact:
    """Hertz point contact of two bodies; arrays when any input was an array.

    The ellipse frame has x along the major axis (semi-axis ``a``) and y
    along the minor axis (semi-axis ``b``).

    Attributes
    ----------
    a, b : float or ndarray
        Semi-major and semi-minor axes of the contact ellipse [m].
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
    rho_sum : float or ndarray
        rho_x + rho_y [1/m].
    major_axis_angle : float or ndarray
        Angle from body 1's x axis to the major axis [rad], in (-pi/2, pi/2];
        0 for a circular contact.
    load : float or ndarray
        Normal force P [N].
    p0 : float or ndarray
        Peak (central) pressure [Pa].
    p_mean : float or ndarray
        Mean pressure P / area = 2 p0 / 3 [Pa].
    area : float or ndarray
        Contact area pi a b [m**2].
    delta : float or ndarray
        Approach of distant points of the two bodies [m].
    stiffness : float or ndarray
        Normal contact stiffness dP/d(delta) = 3 P / (2 delta) [N/m].
    """

    a: float | np.ndarray
    b: float | np.ndarray
    ellipticity: float | np.ndarray
    alpha: float | np.ndarray
    m: float | np.ndarray
    K: float | np.ndarray
    E: float | np.ndarray
    e_star: float | np.ndarray
    rho_x: float | np.ndarray
    rho_y: float | np.ndarray
    rho_sum: float | np.ndarray
    major_axis_angle: float | np.ndarray
    load: float | np.ndarray
    p0: float | np.ndarray
    p_mean: float | np.ndarray
    area: float | np.ndarray
    delta: float | np.ndarray
    stiffness: float | np.ndarray

    def pressure(self, x, y):
        """Contact pressure at (x, y) in the ellipse frame [Pa].

        p0 sqrt(1 - (x/a)**2 - (y/b)**2) inside the ellipse, 0 outside; x, y
        [m] broadcast against each other and against the contact's shape.

        Examples
        --------
        >>> import hertz
        >>> ball = hertz.Body.sphere(0.01, E=200e9, nu=0.3)
        >>> c = hertz.contact(ball, hertz.Body.plane(E=200e9, nu=0.3), load=100.0)
        >>> bool(c.pressure(0.0, 0.0) == c.p0), float(c.pressure(c.a, 0.0))
        (True, 0.0)
        """
        x = as_float_array(x, "x")
        y = as_float_array(y, "y")
        with np.errstate(divide="ignore", invalid="ignore"):
            return _semi_elliptic(self.p0, np.square(x / self.a) + np.square(y / self.b))


@dataclass(frozen=True)
class LineContact:
    """Hertz line contact (2D, per unit length of the contact line).

    Attributes
    ----------
    half_width : float or ndarray
        Semi-width b of the contact strip [m].
    p0 : float or ndarray
        Peak pressure [Pa].
    p_mean : float or ndarray
        Mean pressure (pi/4) p0 [Pa].
    load_per_length : float or ndarray
        Normal force per unit length [N/m].
    e_star : float or ndarray
        E* [Pa] as in :class:`Contact`.
    rho_sum : float or ndarray
        Relative curvature across the line [1/m] (1/R, R the effective radius).

    Notes
    -----
    The approach of a line contact depends on the size of the bodies, not
    only on the contact, and is not given.
    """

    half_width: float | np.ndarray
    p0: float | np.ndarray
    p_mean: float | np.ndarray
    load_per_length: float | np.ndarray
    e_star: float | np.ndarray
    rho_sum: float | np.ndarray

    def pressure(self, x):
        """Pressure p0 sqrt(1 - (x/b)**2) at distance x [m] across the line [Pa]."""
        x = as_float_array(x, "x")
        with np.errstate(divide="ignore", invalid="ignore"):
            return _semi_elliptic(self.p0, np.square(x / self.half_width))


def _check_body(body, name: str) -> Body:
    if not isinstance(body, Body):
        raise TypeError(f"{name} must be a hertz.Body, got {type(body).__name__}")
    return body


def _nonnegative(value, name: str, unit: str) -> np.ndarray:
    arr = as_float_array(value, name)
    require(name, arr, (arr >= 0) & np.isfinite(arr), f"a finite value >= 0 in {unit}")
    return arr


def _curvatures_and_moduli(body1, body2, angle, **extra):
    """Relative curvatures and E*, each on the broadcast shape of its own inputs only
    (one geometry with a million loads is solved once), and the full result shape."""
    body1 = _check_body(body1, "body1")
    body2 = _check_body(body2, "body2")
    ang = as_float_array(angle, "angle")
    require("angle", ang, np.isfinite(ang), "a finite angle in rad")
    geometry = {"body1.Rx": body1.Rx, "body1.Ry": body1.Ry, "body2.Rx": body2.Rx,
                "body2.Ry": body2.Ry, "angle": ang}
    moduli = {"body1.E": body1.E, "body1.nu": body1.nu, "body2.E": body2.E, "body2.nu": body2.nu}
    shape = broadcast_shape(**geometry, **moduli, **extra)
    curv = relative_curvature(*(np.asarray(v, dtype=np.float64) for v in geometry.values()))
    e1, nu1, e2, nu2 = (np.asarray(v, dtype=np.float64) for v in moduli.values())
    e_star = 1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)
    return curv, e_star, shape


def _no_contact(rho_x: np.ndarray, rho_y: np.ndarray) -> ValueError | None:
    """The error for the first pair of bodies that has no Hertz point contact."""
    bad = ~((rho_x > 0) & (rho_y > 0))
    if not bad.any():
        return None
    i = int(np.argmax(bad.reshape(-1)))
    where = index_text(rho_x.shape, i)
    rx, ry = float(rho_x.reshape(-1)[i]), float(rho_y.reshape(-1)[i])
    if rx > 0 and ry == 0:
        return ValueError(
            f"the bodies make a line contact{where} (relative curvature {rx:g} 1/m across, 0 "
            "along the line: parallel cylinders or a cylinder on a plane); use "
            "hertz.line_contact(body1, body2, load_per_length)")
    if rx == 0 and ry == 0:
        return ValueError(f"no Hertz point contact{where}: the relative curvature is zero in every "
                          "direction (plane on plane, or surfaces that fit each other exactly)")
    return ValueError(
        f"no Hertz point contact{where}: principal relative curvatures {rx:g} and {ry:g} 1/m "
        "must both be positive; a concave surface that conforms more closely than the convex "
        "one touches it away from a single point")


def contact(body1: Body, body2: Body, load=None, angle=0.0, *, approach=None) -> Contact:
    """Hertz point contact of two elastic bodies pressed together.

    Parameters
    ----------
    body1, body2 : Body
        The two bodies; every field may be an array (all broadcast together).
    load : float or array_like, optional
        Normal force P [N], >= 0.  Give exactly one of ``load`` and ``approach``.
    angle : float or array_like, optional
        Angle from body 1's x axis to body 2's x axis [rad] (default 0: the
        principal planes coincide).
    approach : float or array_like, optional
        Approach delta of distant points of the bodies [m], >= 0 (the
        overlap of a DEM code); the load is then computed.

    Returns
    -------
    Contact
        Semi-axes, pressure, approach, stiffness and the ellipse parameters.

    Raises
    ------
    TypeError
        If a body is not a :class:`Body` or an argument is not numeric.
    ValueError
        For a negative, infinite or NaN load or approach, a non-finite angle,
        shapes that do not broadcast, and bodies without a Hertz point contact
        (line contacts, plane on plane, over-conforming concave surfaces).

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
    """
    if (load is None) == (approach is None):
        raise TypeError("give exactly one of load (N) and approach (m)")
    if load is not None:
        given = {"load": _nonnegative(load, "load", "N")}
    else:
        given = {"approach": _nonnegative(approach, "approach", "m")}
    curv, e_star, shape = _curvatures_and_moduli(body1, body2, angle, **given)
    (value,) = given.values()
    err = _no_contact(curv.rho_x, curv.rho_y)
    if err is not None:
        raise err
    rho_sum = curv.rho_x + curv.rho_y
    sol = solve_ellipse(curv.rho_x / curv.rho_y)
    lam, K, E = sol.ellipticity, sol.K, sol.E
    # P = C delta**1.5, from delta = (K/2) (9 rho_+ q**2 / E)**(1/3), q = P/(pi lam E*).
    c_load = np.pi * lam * e_star * np.sqrt((2.0 / K) ** 3 * E / (9.0 * rho_sum))
    if load is not None:
        P = value
        q = P / (np.pi * lam * e_star)
        delta = 0.5 * K * np.cbrt(9.0 * rho_sum * q * q / E)
    else:
        delta = value
        P = c_load * delta * np.sqrt(delta)
        q = P / (np.pi * lam * e_star)
    b = np.cbrt(3.0 * E * q / rho_sum)
    a = lam * b
    p0 = 1.5 * e_star * np.cbrt(q * rho_sum * rho_sum / (9.0 * E * E))
    fields = dict(
        a=a, b=b, ellipticity=lam, alpha=curv.rho_x / curv.rho_y, m=sol.m, K=K, E=E,
        e_star=e_star, rho_x=curv.rho_x, rho_y=curv.rho_y, rho_sum=rho_sum,
        major_axis_angle=curv.major_axis_angle, load=P, p0=p0, p_mean=p0 * (2.0 / 3.0),
        area=np.pi * a * b, delta=delta, stiffness=1.5 * c_load * np.sqrt(delta))
    return Contact(**{k: _scalar_or_array(np.broadcast_to(v, shape)) for k, v in fields.items()})


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

    Examples
    --------
    >>> import hertz
    >>> roller = hertz.Body.cylinder(5e-3, E=210e9, nu=0.3)
    >>> lc = hertz.line_contact(roller, hertz.Body.plane(E=210e9, nu=0.3), 1e5)
    >>> print(f"{lc.half_width * 1e6:.2f} um, {lc.p0 / 1e9:.4f} GPa")
    74.28 um, 0.8571 GPa
    """
    load = _nonnegative(load_per_length, "load_per_length", "N/m")
    curv, e_star, shape = _curvatures_and_moduli(body1, body2, 0.0, load_per_length=load)
    line = (curv.rho_x > 0) & (curv.rho_y == 0)
    if not line.all():
        i = int(np.argmin(line.reshape(-1)))
        rx, ry = float(curv.rho_x.reshape(-1)[i]), float(curv.rho_y.reshape(-1)[i])
        raise ValueError(
            f"not a line contact{index_text(line.shape, i)}: the principal relative curvatures "
            f"are {rx:g} and {ry:g} 1/m; a line contact needs one of them 0 and the other "
            "positive (use hertz.contact for a point contact)")
    rho = curv.rho_x
    half_width = np.sqrt(4.0 * load / (np.pi * e_star * rho))
    p0 = np.sqrt(load * e_star * rho / np.pi)
    fields = dict(half_width=half_width, p0=p0, p_mean=0.25 * np.pi * p0,
                  load_per_length=load, e_star=e_star, rho_sum=rho)
    return LineContact(**{k: _scalar_or_array(np.broadcast_to(v, shape))
                          for k, v in fields.items()})
