"""Tangential loading of a Hertz point contact: Cattaneo-Mindlin partial slip and
Mindlin-Deresiewicz histories (pure numpy, vectorised over contacts).

Frame and model
---------------
The ellipse frame of :class:`hertz.Contact`: x along the major semi-axis a, y along
the minor semi-axis b, ``direction`` the angle of the tangential force from x [rad].
Each body has its own shear modulus G = E / (2 (1 + nu)) and Poisson's ratio nu.
The tangential tractions are Mindlin's (1949) uncoupled solution: the normal
pressure is Hertz's whatever the tangential force, which is exact for elastically
similar bodies (Dundurs' beta = 0) and neglects Goodman's coupling otherwise
(:func:`dundurs_beta` gives its size).

Sources: Cattaneo (1938); Mindlin, J. Appl. Mech. 16 (1949) 259; Mindlin &
Deresiewicz, J. Appl. Mech. 20 (1953) 327; Deresiewicz, J. Appl. Mech. 24 (1957) 623
(the elliptical contact); Johnson, Contact Mechanics (1985), ch. 7.

Formulas (derived here; checked against a quadrature of Cerruti's point-force
solution, tests/reference_tangential.py, at 50 digits and at 20 in the tests)
------------------------------------------------------------------------------
With m, K(m), E(m) of the contact and Fukushima's B = (E - (1-m) K)/m and
D = (K - E)/m: the no-slip traction Q/(2 pi a b) (1 - x^2/a^2 - y^2/b^2)^(-1/2)
along a principal axis displaces the whole ellipse uniformly with no transverse
part, by Q times the compliance

    c_x = sum_bodies (K - nu B) / (2 pi G a),   c_y = sum_bodies (K - nu D) / (2 pi G a)

(a circle: c = sum (2 - nu) / (8 G a), Mindlin's classic result).
B and D are computed without cancellation from Hertz's own relation
alpha = B / ((1 - m) D) and K = B + D: D = K / (1 + alpha (b/a)^2),
B = alpha (b/a)^2 D.  A force Q at ``direction`` t gives the relative displacement
Q (c_x cos t, c_y sin t) in the frame; along the force, Q / k_t with
1/k_t = c_x cos^2 t + c_y sin^2 t.

Partial slip (Cattaneo 1938, Mindlin 1949), q = Q/(mu P),
s = (1 - q)^(1/3): the stick zone is the ellipse similar to the contact ellipse with
semi-axes s a, s b; the traction along the force is mu p0 [sqrt(1 - r^2) -
s sqrt(1 - r^2/s^2)] (r^2 = x^2/a^2 + y^2/b^2, the second term in the stick zone
only); the displacement along the force is 3 mu P (1 - s^2) / (2 k_t) and the
tangent stiffness dQ/d(delta) = s k_t.  In the stick zone this is exact for any
direction (both axis problems give a rigid displacement there).  What is
approximate, as in all of the literature, is the slip annulus: its traction is
taken parallel to the force while the slip computed from it is not exactly
parallel.  It is a Poisson effect (none at nu = 0) and larger off the axes;
measured by Cerruti quadrature (benchmarks/tangential_slip.py) at Q/(mu P) = 0.5 on
the mid-annulus ring, largest (mean) angle between slip and force: nu = 0.3, circle
9.0 (6.0) degrees; b/a = 0.2 along a 5.9 (3.3), along b 7.4 (4.0), at 45 degrees
10.1 (7.1); nu = 0.5 about twice that (b/a = 0.2 at 45 degrees: 19.3 (13.3)).

The no-slip stiffness and the partial-slip state are one pass of a compiled kernel
(hertz/_tangential_kernel.c: the formulas above, with its own vectorised cos 2t, sin 2t
(within 2 ulp) and cube root (within 1 ulp)) over the contacts.  dask arrays:
``tangential_stiffness`` and ``tangential`` stay lazy (a bad value is reported, with
its index, when the block holding it is computed); the other functions compute their
inputs once to check them.

Masing's rule (constant P; Mindlin & Deresiewicz 1953): a branch from a reversal
point (Q_r, delta_r) is delta = delta_r + 2 f((Q - Q_r)/2) with f the (odd) virgin
curve; a branch that reaches the point where the previous branch started closes
that small loop and continues the branch before it (memory), and one that reaches
the largest force so far continues on the virgin curve.  The energy of a cycle
Q* -> -Q* -> Q* is, with q = Q*/(mu P) and s = (1 - q)^(1/3),

    W = (36 (mu P)^2 / (5 k)) [1 - (1-q)^(5/3) - (5q/6)(1 + (1-q)^(2/3))]
      = (6 (mu P)^2 / (5 k)) q^3 (1 + 3s + s^2) / (1 + s + s^2)^3

(the second form, derived here from 1 - 5 s^2 + 5 s^3 - s^5 = (1 - s)^3 (1 + 3s + s^2),
keeps full precision as q -> 0, where W -> 2 Q*^3 / (9 mu P k)).  The forms
1 - (1-q)^(2/3) = q (1+s) / (1+s+s^2) and its inverse are used for the same reason.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from . import _interop, _ufuncs
from ._stress import point_stress, poisson_of
from ._validate import (
    as_float_array,
    broadcast_shape,
    error_at,
    first_failure,
    index_text,
    with_index,
)

__all__ = ["FrettingLoop", "Tangential", "TangentialSpring", "dundurs_beta",
           "proportional_loading", "tangential_compliance", "tangential_history"]

_MU = "a positive, finite coefficient of friction"
_DIRECTION = "a finite angle in rad"

# the units of the results' fields, for pandas, xarray and pint (hertz._interop); None: a
# flag, wrapped in a container, never a unit
_M, _N, _N_PER_M, _ONE = _interop.M, _interop.N, _interop.N_PER_M, _interop.ONE
TANGENTIAL_UNITS = {"force": _N, "mu": _ONE, "direction": _interop.RAD, "stick_a": _M,
                    "stick_b": _M, "slip_area": "m**2", "displacement": _M,
                    "displacement_transverse": _M, "stiffness": _N_PER_M,
                    "no_slip_stiffness": _N_PER_M, "sliding": None, "dundurs_beta": _ONE,
                    "_a": _M, "_b": _M, "_p0": _interop.PA}
FRETTING_UNITS = {"amplitude": _N, "displacement_amplitude": _M, "energy": "J",
                  "stiffness": _N_PER_M, "mu": _ONE, "load": _N, "_reach": _M}


# ----------------------------------------------------------------------- input checks
def _checked(value, name, ok_fn, allowed):
    arr = as_float_array(value, name)
    with np.errstate(invalid="ignore"):
        ok = ok_fn(arr)
    if not np.all(ok):
        raise error_at(name, arr, first_failure(np.broadcast_to(ok, arr.shape)), allowed)
    return arr


def _mu(mu):
    return _checked(mu, "mu", lambda v: (v > 0) & (v < math.inf), _MU)


def _direction(direction):
    return _checked(direction, "direction", np.isfinite, _DIRECTION)


def _out(x):
    """A Python float for a 0-d result, else the array."""
    return float(x) if np.ndim(x) == 0 else x


def _moduli(contact):
    """(nu1, nu2, E1, E2) of the contact's bodies, as hertz.contact keeps them."""
    moduli = contact._nu
    if len(moduli) != 4:  # a Contact built by a path that does not keep the moduli
        raise TypeError("this Contact does not carry its bodies' Young's moduli, which the "
                        "tangential compliance needs; build it with hertz.contact")
    return moduli


def _require_load(contact, what):
    load = np.asarray(contact.load, dtype=np.float64)
    ok = load > 0
    if not np.all(ok):
        i = first_failure(np.broadcast_to(ok, load.shape))
        raise error_at("contact.load", load, i,
                       f"positive for {what} (a contact without normal load carries no "
                       "tangential force)")
    return load


# ----------------------------------------------------------------------- compliance
def _is_lazy(*values):
    return any(_interop.is_dask(v) for v in values)


def _stiffness_inputs(contact, direction):
    """The inputs of the compiled no-slip stiffness (hertz/_tangential_kernel.c)."""
    nu1, nu2, e1, e2 = _moduli(contact)
    return (contact.K, contact.alpha, contact.ellipticity, contact.a, nu1, nu2, e1, e2,
            direction)


def _stiffness(contact, direction):
    """No-slip stiffness along ``direction`` [N/m] (0 at zero load), numpy or dask; the
    formula (module docstring) lives in hertz/_tangential_kernel.c."""
    args = _stiffness_inputs(contact, direction)
    if _is_lazy(*args):
        return _interop.dask_map(_ufuncs.tangential_stiffness, args)
    direction = as_float_array(direction, "direction")
    try:
        return _ufuncs.tangential_stiffness(*args[:-1], direction)
    except ValueError:
        _direction(direction)  # the error again, with the index
        raise


def _along(contact, direction):
    """Compliance along the force [m/N] (inf at zero load)."""
    with np.errstate(divide="ignore"):
        return 1.0 / _stiffness(contact, direction)


def tangential_compliance(contact):
    """No-slip tangential compliance matrix of a contact in its ellipse frame [m/N].

    The relative tangential displacement of distant points of the two bodies
    (body 1 relative to body 2) is ``C @ Q`` for a tangential force Q [N] small
    enough that nothing slips (or at the first instant of loading).  C is
    diagonal in the ellipse frame: a force along a principal axis moves the
    contact area rigidly along that axis with no transverse part.

    Parameters
    ----------
    contact : Contact
        A Hertz point contact (:func:`hertz.contact`).

    Returns
    -------
    ndarray, shape (..., 2, 2)
        ``[[c_x, 0], [0, c_y]]`` with c_x = sum (K - nu B) / (2 pi G a) along the
        major axis and c_y = sum (K - nu D) / (2 pi G a) along the minor axis,
        summed over the two bodies (G = E / (2 (1 + nu))).  Infinite for a
        contact with zero load (a = 0).

    Notes
    -----
    Mindlin's uncoupled solution: exact for elastically similar bodies, the
    normal-tangential coupling of dissimilar ones neglected (see
    :func:`dundurs_beta`).  For a circle c_x = c_y = sum (2 - nu) / (8 G a).

    Examples
    --------
    >>> import hertz
    >>> steel = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
    >>> c = hertz.contact(steel, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
    >>> C = hertz.tangential_compliance(c)
    >>> G = 210e9 / 2.6
    >>> print(f"{C[0, 0] * 8 * G * c.a / (2 * 1.7):.15f}")
    1.000000000000000
    """
    cx = _along(contact, 0.0)
    cy = _along(contact, math.pi / 2)
    cx, cy = np.asarray(cx), np.asarray(cy)
    out = np.zeros(np.broadcast_shapes(cx.shape, cy.shape) + (2, 2))
    out[..., 0, 0] = cx
    out[..., 1, 1] = cy
    return out


def tangential_stiffness(contact, direction=0.0):
    """No-slip tangential stiffness [N/m] along ``direction`` (the force's angle from
    the major axis [rad]): 1 / (c_x cos^2 t + c_y sin^2 t); 0 at zero load."""
    return _out(_stiffness(contact, direction))


def dundurs_beta(contact):
    """Dundurs' second parameter beta [-] of the two bodies' materials.

    beta = [(1 - 2 nu1)/G1 - (1 - 2 nu2)/G2] / (2 [(1 - nu1)/G1 + (1 - nu2)/G2]),
    in [-1/2, 1/2]; 0 for elastically similar bodies.  It measures the coupling of
    normal and tangential tractions (Goodman, J. Appl. Mech. 29 (1962) 515) that
    Mindlin's solution, and so this module, neglects (Dundurs 1969; Johnson,
    Contact Mechanics, ch. 5 and 7).

    Examples
    --------
    >>> import hertz
    >>> steel = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
    >>> glass = hertz.Body.plane(E=70e9, nu=0.22)
    >>> print(f"{hertz.dundurs_beta(hertz.contact(steel, glass, load=10.0)):.4f}")
    -0.2031
    """
    nu1, nu2, e1, e2 = _moduli(contact)
    g1, g2 = 2.0 * (1.0 + nu1) / e1, 2.0 * (1.0 + nu2) / e2  # 1/G
    return _out((g1 * (1.0 - 2.0 * nu1) - g2 * (1.0 - 2.0 * nu2))
                / (2.0 * (g1 * (1.0 - nu1) + g2 * (1.0 - nu2))))


# ----------------------------------------------------------------------- virgin curve
def _virgin(q, s=None):
    """1 - (1 - q)^(2/3) for 0 <= q <= 1, without cancellation as q -> 0 (s: the cube
    root of 1 - q if known)."""
    if s is None:
        s = np.cbrt(1.0 - q)
    return q * (1.0 + s) / (1.0 + s + s * s)


def _virgin_inverse(r):
    """The q in [0, 1] with 1 - (1 - q)^(2/3) = r, for 0 <= r <= 1 (q = 1 beyond)."""
    t = np.sqrt(np.maximum(1.0 - r, 0.0))
    return np.minimum(r * (1.0 + t + t * t) / (1.0 + t), 1.0)


def _loop_energy(limit, q, along):
    """W [J] of a cycle of amplitude q = Q*/(mu P), limit = mu P [N], along = 1/k [m/N]:
    (6/5) limit^2 along q^3 (1 + 3s + s^2) / (1 + s + s^2)^3 (module docstring).

    The powers are taken on the mantissas of limit, along and q (in [1/2, 1)) and the
    exponents added apart, so nothing overflows or underflows before the result itself
    does (limit^2 alone overflows beyond mu P = 1.3e154, q^3 underflows below 5e-109);
    where no intermediate product leaves the range of a double these are the bits of
    the unscaled product (scaling by powers of 2 is exact).  Elementwise products only
    (no ``**``, which numpy computes for arrays differently from Python for floats), so
    one contact and an array of them get the same bits."""
    s = np.cbrt(1.0 - q)
    u = 1.0 + s + s * s
    g = 1.2 * (1.0 + 3.0 * s + s * s) / (u * u * u)
    m_limit, e_limit = np.frexp(limit)
    m_along, e_along = np.frexp(along)
    m_q, e_q = np.frexp(q)
    mantissa = g * (m_limit * m_limit) * m_along * (m_q * m_q * m_q)
    exponent = 2 * e_limit.astype(np.int64) + e_along + 3 * e_q.astype(np.int64)
    # beyond the int range of ldexp the result is 0 or inf either way
    exponent = np.clip(exponent, -4000, 4000).astype(np.int32)
    with np.errstate(over="ignore", under="ignore"):
        return np.ldexp(mantissa, exponent)


# mu P at most this [N]: 3 mu P / 2, the scale of every displacement, stays a double
_LIMIT_MAX = 1e308


def _limit(mu, load):
    """mu P [N], checked: at most _LIMIT_MAX (beyond, a product overflows to inf and the
    displacements at zero force are inf * 0 = NaN)."""
    with np.errstate(over="ignore"):
        limit = mu * load
    ok = limit <= _LIMIT_MAX
    if not np.all(ok):
        shape = np.shape(limit)
        i = first_failure(np.broadcast_to(ok, shape))
        m, p = (float(np.broadcast_to(v, shape).reshape(-1)[i]) for v in (mu, load))
        raise ValueError(f"mu * load must be at most {_LIMIT_MAX!r} N (3 mu P / 2, the "
                         f"displacement scale's factor, must be a double), got mu = {m!r} "
                         f"and load = {p!r} N{index_text(shape, i)}")
    return limit


def _force_ratio(force, mu, load, shape_name="force"):
    """q = force / (mu P), checked: mu P <= _LIMIT_MAX and 0 <= force <= mu P (one pass
    when all is well)."""
    force = as_float_array(force, shape_name)
    limit = _limit(mu, load)
    with np.errstate(invalid="ignore"):
        ok = (force >= 0) & (force <= limit)  # false for NaN; mu P is finite
    if not ok.all():
        _checked(force, shape_name, lambda v: (v >= 0) & (v < math.inf),
                 "a non-negative, finite tangential force in N")
        shape = ok.shape
        i = first_failure(ok)
        f = float(np.broadcast_to(force, shape).reshape(-1)[i])
        lim = float(np.broadcast_to(limit, shape).reshape(-1)[i])
        raise ValueError(f"{shape_name} must be at most mu * load = {lim!r} N (the limit of "
                         f"friction; beyond it the contact slides as a whole), got {f!r}"
                         f"{index_text(shape, i)}")
    return force / limit


# ----------------------------------------------------------------------- monotonic
@dataclass(frozen=True, slots=True)
class Tangential:
    """Cattaneo-Mindlin partial slip of a Hertz contact under a tangential force.

    The force rises monotonically from 0 at constant normal load P.  Lengths in
    m, forces in N, the ellipse frame of the contact (x along the major axis).

    Attributes
    ----------
    force : float or ndarray
        Tangential force Q [N], 0 <= Q <= mu P.
    mu : float or ndarray
        Coefficient of friction [-].
    direction : float or ndarray
        Angle of the force from the major axis [rad].
    stick_a, stick_b : float or ndarray
        Semi-axes of the stick ellipse [m]: (a, b) (1 - Q/(mu P))^(1/3).  Zero at
        Q = mu P, where the whole contact slides.
    slip_area : float or ndarray
        Area of the slip annulus between the stick and contact ellipses [m**2].
    displacement : float or ndarray
        Relative tangential displacement of distant points along the force [m]:
        3 mu P (1 - (1 - Q/(mu P))^(2/3)) / (2 k), k the no-slip stiffness along
        the force.  At Q = mu P it is the displacement at which sliding starts.
    displacement_transverse : float or ndarray
        Its component perpendicular to the force (positive 90 degrees
        counter-clockwise from it) [m]; 0 along a principal axis, else towards
        the major axis, the more compliant one.
    stiffness : float or ndarray
        Tangent stiffness dQ/d(displacement) [N/m] = k (1 - Q/(mu P))^(1/3); 0 at
        Q = mu P.
    no_slip_stiffness : float or ndarray
        k [N/m], the stiffness at Q = 0.
    sliding : bool or ndarray
        Whether Q = mu P (the contact is at the limit of friction and slides).
    dundurs_beta : float or ndarray
        The size of the normal-tangential coupling neglected (:func:`dundurs_beta`).
    """

    force: float | np.ndarray
    mu: float | np.ndarray
    direction: float | np.ndarray
    stick_a: float | np.ndarray
    stick_b: float | np.ndarray
    slip_area: float | np.ndarray
    displacement: float | np.ndarray
    displacement_transverse: float | np.ndarray
    stiffness: float | np.ndarray
    no_slip_stiffness: float | np.ndarray
    sliding: bool | np.ndarray
    dundurs_beta: float | np.ndarray
    # the contact's semi-axes [m] and peak pressure [Pa], for the traction and stresses
    # (private: the Contact has them; hidden from the repr)
    _a: float | np.ndarray = field(repr=False)
    _b: float | np.ndarray = field(repr=False)
    _p0: float | np.ndarray = field(repr=False)
    # (nu1, nu2) of the bodies; None in a result rebuilt around pandas/xarray/pint/dask
    # fields, which carries no stress field
    _nu: tuple | None = field(default=None, repr=False)

    def traction(self, x, y):
        """Shear traction along the force at (x, y) in the ellipse frame [Pa].

        mu p0 sqrt(1 - r^2) - mu p0 s sqrt(1 - r^2/s^2), r^2 = (x/a)^2 + (y/b)^2,
        s = stick_a / a, the second term in the stick ellipse only; 0 outside
        the contact.  The traction vector is this times the force's unit vector.
        """
        if _interop.any_wrapped(self._a, x, y):  # pandas, xarray, pint
            return _interop.call_result_method(self, "traction", (("x", x, "m"), ("y", y, "m")),
                                               "Pa", TANGENTIAL_UNITS)
        x = as_float_array(x, "x")
        y = as_float_array(y, "y")
        with np.errstate(divide="ignore", invalid="ignore"):
            r2 = np.square(x / self._a) + np.square(y / self._b)
            s = self.stick_a / self._a
            full = np.sqrt(np.maximum(1.0 - r2, 0.0))
            stick = np.where(r2 < s * s, s * np.sqrt(np.maximum(1.0 - r2 / (s * s), 0.0)), 0.0)
            return _out(self.mu * self._p0 * (full - stick))

    # The traction on each body.  Q is the force that pushes body 1 along ``direction``
    # relative to body 2 (``tangential_compliance``: distant points of body 1 move by
    # C @ Q relative to body 2's).  A surface traction moves a half-space's surface
    # along itself relative to its distant points (Cerruti), so the stuck interface
    # carries Q that way only if body 2's surface is dragged along ``direction`` and
    # body 1's held back: the traction on body 2 is along ``direction``, on body 1
    # along direction + pi.
    def _poisson(self, body, what):
        if self._nu is None:
            raise TypeError(f"Tangential.{what} needs numpy fields: this result was built "
                            "around pandas, xarray, pint or dask values; call "
                            "Contact.tangential on a contact of plain numpy values")
        return poisson_of(self._nu, body)

    def _stick_ratio(self):
        """c = stick_a / a = (1 - Q/(mu P))^(1/3) in [0, 1] (0 when sliding)."""
        return np.clip(np.asarray(self.stick_a, dtype=np.float64) / self._a, 0.0, 1.0)

    def stress(self, x, y, z, body=1):
        """Cauchy stress tensor [Pa] in body 1 or 2 under the normal and tangential load.

        The frictionless Hertz field (:meth:`hertz.Contact.stress`) plus the field of the
        Cattaneo-Mindlin traction (:meth:`traction`): mu p over the contact ellipse minus
        c mu p0 sqrt(1 - r^2/c^2) over the stick ellipse, c = stick_a / a (Mindlin 1949),
        integrated through Cerruti's solution (``hertz._friction.partial_slip_stress``),
        with the body's own Poisson's ratio.  At Q = mu P (c = 0) it is the field of
        the sliding traction mu p.

        The force Q pushes body 1 along ``direction`` relative to body 2 (the sense of
        :func:`hertz.tangential_compliance` and of ``displacement``), so the traction
        that body 1 exerts on body 2 is along ``direction`` and the one on body 1 the
        opposite: on the surface inside the contact sigma_xz = -t cos(direction) in
        body 2 and +t cos(direction) in body 1 (t = :meth:`traction`; z points into
        the body, whose outward normal is -z).  Mindlin's uncoupled solution: the
        pressure is Hertz's (exact for elastically similar bodies, see
        ``dundurs_beta``).

        Parameters
        ----------
        x, y, z : float or array_like
            Ellipse frame [m]: x along the major axis a, y along the minor axis b,
            z >= 0 the depth into the body.  They broadcast with each other and with
            the result's shape.
        body : {1, 2}
            Which body.

        Returns
        -------
        ndarray, shape (..., 3, 3)
            The stress tensor [Pa], tension positive, rows and columns x, y, z.

        Raises
        ------
        ValueError
            A coordinate not finite, a negative depth, ``body`` not 1 or 2.
        TypeError
            A result built around pandas, xarray, pint or dask values.

        Examples
        --------
        >>> import hertz
        >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
        >>> c = hertz.contact(ball, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
        >>> t = c.tangential(force=15.0, mu=0.3)  # Q / (mu P) = 1/2, along x
        >>> x = 0.9 * c.a  # in the slip annulus, on the surface
        >>> s1, s2 = t.stress(x, 0.0, 0.0, body=1), t.stress(x, 0.0, 0.0, body=2)
        >>> print(f"{s1[0, 2] / t.traction(x, 0.0):.12f} {s2[0, 2] / t.traction(x, 0.0):.12f}")
        1.000000000000 -1.000000000000
        """
        # (scipy's import, for the sliding maxima, waits until a stress is asked for)
        from ._friction import partial_slip_stress

        nu = self._poisson(body, "stress")
        normal = point_stress(self._a, self._b, self._p0, nu, x, y, z)
        friction = partial_slip_stress(self._a, self._b, self._p0, self.mu, nu, x, y, z,
                                       self._stick_ratio(), self.direction)
        # body 1 carries the reversed traction: the field is linear in it (exactly the
        # field of direction + pi, without cos/sin(pi)'s rounding)
        return normal - friction if body == 1 else normal + friction

    def maxima(self, body=1):
        """The largest stresses in body 1 or 2 under the normal and tangential load.

        :func:`hertz._friction.sliding_maxima` with the stick ratio c = stick_a / a of
        this state and the body's Poisson's ratio: the frictionless Hertz field plus
        that of the Cattaneo-Mindlin traction, on body 2 along ``direction`` and on
        body 1 along direction + pi (see :meth:`stress`).

        Parameters
        ----------
        body : {1, 2}
            Which body.

        Returns
        -------
        SlidingMaxima
            The largest von Mises and principal shear stress [Pa] and where they are,
            and the largest surface tension [Pa] and where it is (positions [m] in the
            ellipse frame, z the depth).  The maxima of the two bodies differ by their
            Poisson's ratios; their positions are mirrored through the z axis.  For a
            result holding an array of contacts (any shape), each field is an array of
            that shape, element by element the result of the same contact alone
            (bit for bit: the contacts are searched one after the other).

        Raises
        ------
        ValueError
            ``body`` not 1 or 2; a field of the state outside its range (with the index
            of the contact), checked for all contacts before any search.
        TypeError
            A result built around pandas, xarray, pint or dask values.

        Notes
        -----
        A search over grids below and on the surface, refined by Nelder-Mead, per
        contact: the cost is that of one contact times their number (no vectorisation
        across contacts).  Per contact and body, CPU time on an AMD EPYC core (shared),
        b/a = 0.48: along a principal axis (the search stays in the plane of symmetry)
        0.6 s sliding and 1.1 s in partial slip at Q = mu P / 2; in another direction
        (the whole half-space; 0.5 rad) 5.6 s and 15 s.  A result of dask arrays is
        computed first.

        Examples
        --------
        >>> import hertz
        >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
        >>> c = hertz.contact(ball, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
        >>> m = c.tangential(force=30.0, mu=0.3).maxima(body=2)  # sliding, mu = 0.3
        >>> print(f"{m.von_mises / c.p0:.3f} p0 at z = {m.z_von_mises / c.a:.3f} a")
        0.660 p0 at z = 0.428 a
        """
        from ._friction import SlidingMaxima, check_maxima_inputs, sliding_maxima

        nu = self._poisson(body, "maxima")
        turn = math.pi if body == 1 else 0.0  # body 1 carries the reversed traction
        shape = np.shape(self.stick_a)
        if not shape:
            return sliding_maxima(self._a, self._b, self._p0, self.mu, nu,
                                  float(self.direction) + turn, float(self._stick_ratio()))
        # every contact checked first (with its index): none fails after hours of search
        fields = check_maxima_inputs(self._a, self._b, self._p0, self.mu, nu, self.direction,
                                     self._stick_ratio(), shape)
        names = [f.name for f in dataclasses.fields(SlidingMaxima)]
        out = np.empty((len(names),) + shape)
        for flat, index in enumerate(np.ndindex(shape)):
            a, b, p0, mu, nu_i, direction, ratio = (float(f[index]) for f in fields)
            try:
                found = sliding_maxima(a, b, p0, mu, nu_i, direction + turn, ratio)
            except ValueError as exc:  # pragma: no cover - the checks above come first
                raise with_index(exc, shape, flat) from None
            out[(slice(None),) + index] = [getattr(found, k) for k in names]
        return SlidingMaxima(*out)

def _broadcast(x, shape):
    """x as a Python float (0-d) or a read-only view of ``shape`` (no copy)."""
    if not shape:
        return _out(x)
    return x if np.shape(x) == shape else np.broadcast_to(x, shape)


def partial_slip(contact, force, mu, direction=0.0) -> Tangential:
    """The :class:`Tangential` state of ``contact`` under ``force`` [N] (see
    :meth:`hertz.Contact.tangential`): one pass of the compiled kernel
    (hertz/_tangential_kernel.c) over the contacts, lazily for dask arrays."""
    nu1, nu2, e1, e2 = _moduli(contact)
    given = (force, mu, direction)
    if not _is_lazy(*given):
        force, mu, direction = (as_float_array(v, name) for v, name in
                                zip(given, ("force", "mu", "direction"), strict=True))
    a, b = contact.a, contact.b
    args = (contact.K, contact.alpha, contact.ellipticity, a, b, contact.load, nu1, nu2, e1,
            e2, force, mu, direction)
    shape = broadcast_shape(contact=a, force=force, mu=mu, direction=direction)
    if _is_lazy(*args):
        out = _interop.dask_map(_ufuncs.partial_slip, args, nout=8)
    else:
        try:
            out = _ufuncs.partial_slip(*args)
        except ValueError:  # the checks again, in their order, for the index
            mu = _mu(mu)
            _direction(direction)
            _force_ratio(force, mu, _require_load(contact, "a tangential force"))
            raise
        _limit(mu, contact.load)
    stick_a, stick_b, slip_area, disp, transverse, tangent, no_slip, sliding = out
    sliding = sliding != 0.0
    fields = (force, mu, direction, stick_a, stick_b, slip_area, disp, transverse, tangent,
              no_slip, sliding, dundurs_beta(contact), a, b, contact.p0)
    fields = [_broadcast(x, shape) for x in fields]
    if not shape:
        fields[10] = bool(fields[10])
    return Tangential(*fields, (nu1, nu2))


# ----------------------------------------------------------------------- fretting
@dataclass(frozen=True, slots=True)
class FrettingLoop:
    """The steady hysteresis loop of a tangential force cycling between -Q* and Q*
    at constant normal load (Mindlin & Deresiewicz 1953, Masing's rule).

    Attributes
    ----------
    amplitude : float or ndarray
        Q* [N], 0 <= Q* <= mu P.
    displacement_amplitude : float or ndarray
        delta* [m], the displacement along the force at Q = Q*.
    energy : float or ndarray
        Energy dissipated per cycle [J], the loop's area.
    stiffness : float or ndarray
        No-slip stiffness k along the force [N/m].
    mu, load : float or ndarray
        Coefficient of friction [-] and normal force P [N].
    """

    amplitude: float | np.ndarray
    displacement_amplitude: float | np.ndarray
    energy: float | np.ndarray
    stiffness: float | np.ndarray
    mu: float | np.ndarray
    load: float | np.ndarray
    # 3 mu P / (2 k), the displacement where sliding starts (private; hidden from the repr)
    _reach: float | np.ndarray = field(repr=False)

    def _f(self, x):
        """The virgin curve Q -> displacement [m] for 0 <= x <= mu P."""
        return self._reach * _virgin(x / (self.mu * self.load))

    def unloading(self, force):
        """Displacement [m] on the branch from Q* down to -Q*:
        delta* - 2 f((Q* - Q)/2), for -Q* <= force <= Q* [N]."""
        if _interop.any_wrapped(self._reach, force):  # pandas, xarray, pint
            return _interop.call_result_method(self, "unloading", (("force", force, "N"),), "m",
                                               FRETTING_UNITS)
        force = as_float_array(force, "force")
        return _out(self.displacement_amplitude - 2.0 * self._f((self.amplitude - force) / 2.0))

    def reloading(self, force):
        """Displacement [m] on the branch from -Q* up to Q*: -delta* + 2 f((Q* + Q)/2)."""
        if _interop.any_wrapped(self._reach, force):  # pandas, xarray, pint
            return _interop.call_result_method(self, "reloading", (("force", force, "N"),), "m",
                                               FRETTING_UNITS)
        force = as_float_array(force, "force")
        return _out(-self.displacement_amplitude + 2.0 * self._f((self.amplitude + force) / 2.0))

    def _wrapped_loop(self, points):
        """:meth:`loop` of a result whose fields are pandas, xarray or pint: the loop of
        the plain twin, its point axis in front, wrapped (``Recipe.wrap_points``)."""
        plain, recipe = _interop.unwrap([(k, getattr(self, k), u)
                                         for k, u in FRETTING_UNITS.items()])
        twin = type(self)(**dict(zip(FRETTING_UNITS, plain, strict=True)))
        force, displacement = type(self).loop(twin, points)
        return (recipe.wrap_points(force, _N, "force"),
                recipe.wrap_points(displacement, _M, "displacement"))

    def loop(self, points=101):
        """The closed loop: (force, displacement) [N, m], each of shape (2 points - 1, ...),
        down the unloading branch from Q* to -Q* and back up the reloading branch.

        For a result of pandas Series, each is a DataFrame with a row per point of the
        loop (index ``point``) and a column per contact (the Series' index); of xarray
        DataArrays, a DataArray with the dimension ``point`` in front of the contacts';
        of pint Quantities, Quantities in N and m; of pandas DataFrames (which have no
        third axis), numpy arrays of shape (2 points - 1, rows, columns).
        """
        if _interop.any_wrapped(self._reach):  # pandas, xarray, pint
            return self._wrapped_loop(points)
        t = np.linspace(1.0, -1.0, int(points))
        t = t.reshape((-1,) + (1,) * np.ndim(self.amplitude))
        down = t * self.amplitude
        up = -down[1:]
        return (np.concatenate([down, up]),
                np.concatenate([self.unloading(down), self.reloading(up)]))


def fretting(contact, amplitude, mu, direction=0.0) -> FrettingLoop:
    """The :class:`FrettingLoop` of ``contact`` (see :meth:`hertz.Contact.fretting`)."""
    mu = _mu(mu)
    direction = _direction(direction)
    load = _require_load(contact, "a tangential force")
    q = _force_ratio(amplitude, mu, load, "amplitude")
    along = _along(contact, direction)
    limit = _limit(mu, load)
    amplitude = np.asarray(amplitude, dtype=np.float64)
    shape = np.broadcast_shapes(np.shape(q), np.shape(along))
    reach = 1.5 * limit * along
    fields = (amplitude, reach * _virgin(q), _loop_energy(limit, q, along),
              1.0 / along, mu, load, reach)
    return FrettingLoop(*(_broadcast(x, shape) for x in fields))


# ----------------------------------------------------------------------- histories
def tangential_history(contact, forces, mu, direction=0.0):
    """Relative tangential displacement [m] along a history of tangential forces.

    Mindlin & Deresiewicz (1953) at constant normal load: Masing's rule with the
    memory of every reversal point (module docstring of ``hertz._tangential``).

    Parameters
    ----------
    contact : Contact
    forces : array_like, shape (n, ...)
        The force along ``direction`` [N] at n instants, starting from the
        unloaded state (Q = 0, displacement 0); negative is the opposite way.
        |Q| <= mu P throughout.  The trailing axes broadcast with the contact's
        shape.  n = 0 (no instants) gives an empty result, as numpy's cumulative
        functions do.
    mu : float or array_like
        Coefficient of friction [-], > 0.
    direction : float or array_like
        Angle of the force's line from the major axis [rad].

    Returns
    -------
    ndarray, shape (n, ...)
        The displacement along the force's line at each instant [m] (shape (0, ...)
        for n = 0).

    Examples
    --------
    >>> import hertz
    >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
    >>> c = hertz.contact(ball, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
    >>> d = hertz.tangential_history(c, [20.0, -10.0, 5.0, -10.0, 20.0], mu=0.3)
    >>> bool(d[4] == hertz.tangential_history(c, [20.0], mu=0.3)[0])  # memory
    True
    >>> bool(d[1] == d[3])  # the small loop -10 -> 5 -> -10 closes
    True
    """
    mu = _mu(mu)
    direction = _direction(direction)
    load = _require_load(contact, "a tangential force")
    forces = as_float_array(forces, "forces")
    if forces.ndim == 0:
        raise ValueError("forces must be an array of shape (n, ...) of tangential forces in N")
    n, trail = forces.shape[0], forces.shape[1:]  # n = 0: an empty result of shape (0, ...)
    limit = _limit(mu, load)
    along = _along(contact, direction)
    contacts = np.broadcast_shapes(np.shape(limit), np.shape(along))
    try:
        shape = np.broadcast_shapes(trail, contacts)
    except ValueError:
        raise ValueError(f"forces must have the shape (n, ...), its trailing axes {trail} "
                         f"broadcasting with the contacts' shape {contacts}, got the shape "
                         f"{forces.shape}") from None
    # the trailing axes aligned with the contacts' (the axis of instants never meets one)
    forces = np.broadcast_to(forces.reshape((n,) + (1,) * (len(shape) - len(trail)) + trail),
                             (n,) + shape)
    _force_ratio(np.abs(forces), mu, load, "forces")  # |Q| <= mu P
    flat = forces.reshape(n, math.prod(shape))
    lim = np.broadcast_to(limit, shape).reshape(-1)
    reach = np.broadcast_to(1.5 * limit * along, shape).reshape(-1)  # 3 mu P / (2 k)
    out = np.empty_like(flat)
    engine = _Masing(lim.size, lambda x: reach * _virgin(np.minimum(x / lim, 1.0)))
    for i in range(n):
        out[i] = engine.step(flat[i])
    return out.reshape((n,) + shape)


class _Masing:
    """Masing's rule with reversal memory, vectorised over N elements, driven by the
    variable x with the odd skeleton y = sign(x) f(|x|):

    * a reversal of the direction of x pushes the last point (x, y);
    * the branch from the top reversal (x_r, y_r) is y_r + 2 f((x - x_r)/2) (odd f);
    * passing the reversal before the top one closes a loop: pop two;
    * with one reversal left, reaching |x| >= |x_1| rejoins the skeleton: pop it
      (only while ``virgin``; the spring clears it when a contact slides).
    """

    def __init__(self, n, f):
        self.f = f
        self.x = np.zeros(n)
        self.y = np.zeros(n)
        self.sense = np.zeros(n)  # direction of the last move, 0 before the first
        self.depth = np.zeros(n, dtype=np.intp)
        self.virgin = np.ones(n, dtype=bool)  # on or inside the skeleton (never slid)
        self.stack_x = np.zeros((n, 4))
        self.stack_y = np.zeros((n, 4))
        self.rows = np.arange(n)

    def _odd(self, x):
        return np.sign(x) * self.f(np.abs(x))

    def step(self, x):
        # differences of two values near the largest double overflow to +-inf: their sign
        # and comparisons stay right, and the halves below are taken apart
        with np.errstate(over="ignore"):
            return self._step(x)

    @staticmethod
    def _half_difference(x, xr):
        """(x - xr) / 2, also where x - xr overflows (then x/2 - xr/2; elsewhere these are
        the same bits but for subnormal halves)."""
        d = x - xr
        return np.where(np.isfinite(d), d / 2.0, x / 2.0 - xr / 2.0)

    def _step(self, x):
        move = np.sign(x - self.x)
        reverse = (move != 0) & (self.sense != 0) & (move != self.sense)
        if reverse.any():
            if self.depth.max() + 1 >= self.stack_x.shape[1]:
                grow = self.stack_x.shape[1]
                self.stack_x = np.pad(self.stack_x, ((0, 0), (0, grow)))
                self.stack_y = np.pad(self.stack_y, ((0, 0), (0, grow)))
            r = self.rows[reverse]
            self.stack_x[r, self.depth[r]] = self.x[r]
            self.stack_y[r, self.depth[r]] = self.y[r]
            self.depth[r] += 1
        self.sense = np.where(move != 0, move, self.sense)
        while True:  # loops closed by this step
            d = self.depth
            top = np.maximum(d - 1, 0)
            below = np.maximum(d - 2, 0)
            xr1 = self.stack_x[self.rows, top]
            xr0 = self.stack_x[self.rows, below]
            close = (d >= 2) & ((x - xr0) * self.sense >= 0) & ((xr0 - xr1) * self.sense > 0)
            skeleton = (d == 1) & self.virgin & (np.abs(x) >= np.abs(xr1)) & (x * xr1 <= 0)
            if not (close.any() or skeleton.any()):
                break
            self.depth = d - 2 * close - skeleton
        d = self.depth
        top = np.maximum(d - 1, 0)
        xr = self.stack_x[self.rows, top]
        yr = self.stack_y[self.rows, top]
        branch = yr + 2.0 * self._odd(self._half_difference(x, xr))
        y = np.where(d == 0, self._odd(x), branch)
        self.x = np.array(x, dtype=np.float64, copy=True)
        self.y = y
        return y


def proportional_loading(contact, force, mu, direction=0.0):
    """Displacement [m] when the tangential and normal forces rise together from zero.

    Mindlin & Deresiewicz (1953), the oblique force of fixed direction: if Q/P
    stays fixed below mu, the traction is (Q/P) times the pressure everywhere,
    nothing slips, and the displacement is
    3 Q / (2 k) with k the no-slip stiffness at the final load (k grows as
    P^(1/3)): half again the displacement of the same Q applied at full load
    before slip.  It applies to any monotonic loading with dQ/dP = Q/P < mu
    constant; Q/P >= mu slides from the start (ValueError).  Two further classic
    cases need no function: raising P at fixed Q changes nothing tangential (the
    displacement stays); lowering P at fixed Q gives the Cattaneo-Mindlin state
    of the current P and Q (:meth:`hertz.Contact.tangential` of the contact at the
    new load), as long as Q < mu P.

    Parameters
    ----------
    contact : Contact
        The contact at the final normal load P.
    force : float or array_like
        The final tangential force Q [N], 0 <= Q < mu P.
    mu : float or array_like
        Coefficient of friction [-].
    direction : float or array_like
        Angle of the force from the major axis [rad].

    Examples
    --------
    >>> import hertz
    >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
    >>> c = hertz.contact(ball, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
    >>> d = hertz.proportional_loading(c, 10.0, mu=0.3)
    >>> print(f"{d * c.tangential_stiffness() / 10.0:.3f}")
    1.500
    """
    mu = _mu(mu)
    direction = _direction(direction)
    load = _require_load(contact, "a tangential force")
    q = _force_ratio(force, mu, load)
    if np.any(q >= 1.0):
        i = first_failure(np.broadcast_to(q < 1.0, np.shape(q)))
        raise ValueError("force / load must stay below mu for loading without slip (it "
                         f"slides from the start){'' if not np.ndim(q) else f' at index {i}'}")
    along = _along(contact, direction)
    return _out(1.5 * np.asarray(force, dtype=np.float64) * along)


def _batch_shape(shape, size):
    """The batch's shape: ``shape`` (the inputs') broadcast with (size,) if size is given."""
    if size is None:
        return shape
    if isinstance(size, bool) or not isinstance(size, (int, np.integer)) or size < 0:
        raise ValueError(f"size must be a non-negative int (the number of contacts), got "
                         f"{size!r}")
    try:
        return np.broadcast_shapes(shape, (int(size),))
    except ValueError:
        raise ValueError(f"size = {size!r} contacts does not broadcast with the contacts' "
                         f"shape {shape}") from None


def _selection(where, shape, n):
    """Flat indices of the contacts ``where`` selects: a boolean mask of the batch's shape
    (or broadcasting to it) or integer indices into the flattened batch."""
    arr = np.asarray(where)
    if arr.dtype == bool:
        try:
            return np.flatnonzero(np.broadcast_to(arr, shape))
        except ValueError:
            raise ValueError(f"where must be a boolean mask of the contacts' shape {shape} "
                             f"or integer indices, got a mask of shape {arr.shape}") from None
    if arr.dtype.kind not in "iu":
        raise ValueError(f"where must be a boolean mask of the contacts' shape {shape} or "
                         f"integer indices into the {n} contacts, got {arr.dtype} values")
    flat = arr.reshape(-1).astype(np.intp)
    bad = (flat < -n) | (flat >= n)
    if bad.any():
        raise ValueError(f"where must hold indices from {-n} to {n - 1} (the {n} contacts, "
                         f"flattened), got {int(flat[bad][0])}")
    return np.where(flat < 0, flat + n, flat)


class _MasingSpring:
    """Masing's rule with reversal memory and sliding at +-mu P (the law of
    :class:`TangentialSpring`), vectorised over N contacts at a constant cost per step.

    The same rule and the same floating-point operations, element by element, as
    :class:`_Masing` (which :func:`tangential_history` uses) with the sliding rules of
    the spring; only the bookkeeping differs, for speed: the top two reversal points of
    each contact are held in dense arrays, so a step reads the stack only for the rows
    that reverse or close a loop; a contact that slides with no memory skips the
    skeleton; and the contacts are advanced in blocks of ``BLOCK``, so that the
    temporaries of a step stay in the processor's cache.  Memory: ``depth`` reversal
    points per contact (x and y each), the turning points that no later branch has
    wiped out; the stack's width is the largest depth over the contacts, doubled when
    a reversal needs more.
    """

    BLOCK = 16384

    def __init__(self, n, limit, reach):
        self.limit = limit
        self.reach = reach
        self.x = np.zeros(n)  # the coordinate: the displacement since the last slide
        self.y = np.zeros(n)  # the force
        self.sense = np.zeros(n)  # direction of the last move, 0 before the first
        self.depth = np.zeros(n, dtype=np.intp)
        self.virgin = np.ones(n, dtype=bool)  # never slid since the last reset
        self.stack_x = np.zeros((n, 2))
        self.stack_y = np.zeros((n, 2))
        self.top_x = np.zeros(n)  # stack_x[depth - 1] where depth >= 1
        self.top_y = np.zeros(n)
        self.below_x = np.zeros(n)  # stack_x[depth - 2] where depth >= 2

    def reset(self, rows):
        for name in ("x", "y", "sense", "depth"):
            getattr(self, name)[rows] = 0
        self.virgin[rows] = True

    def advance(self, x):
        """Move every contact to the coordinate ``x``; return the forces and whether
        each contact slides as a whole."""
        n = x.size
        force = np.empty(n)
        sliding = np.empty(n, dtype=bool)
        for start in range(0, n, self.BLOCK):
            s = slice(start, start + self.BLOCK)
            self._block(start, s, x[s], force[s], sliding[s])
        return force, sliding

    def _block(self, start, s, x, force, sliding_out):
        x_old, y_old, sense, depth = self.x[s], self.y[s], self.sense[s], self.depth[s]
        virgin, top_x, top_y, below_x = self.virgin[s], self.top_x[s], self.top_y[s], \
            self.below_x[s]
        limit = self.limit[s]
        # the direction of the move only where it changes the sense: at a reversal
        # (moved the other way) or at the first move (an overflowed difference times a
        # sense 0 is NaN: not > 0, so it changes the sense too)
        dx = x - x_old
        along = dx * sense
        change = (dx != 0) & ~(along > 0)
        reverse = along < 0
        if reverse.any():  # push the last point
            r = np.flatnonzero(reverse)
            d = depth[r]
            if d.max() + 1 >= self.stack_x.shape[1]:
                grow = self.stack_x.shape[1]
                self.stack_x = np.pad(self.stack_x, ((0, 0), (0, grow)))
                self.stack_y = np.pad(self.stack_y, ((0, 0), (0, grow)))
            self.stack_x[r + start, d] = x_old[r]
            self.stack_y[r + start, d] = y_old[r]
            depth[r] = d + 1
            below_x[r] = top_x[r]
            top_x[r] = x_old[r]
            top_y[r] = y_old[r]
        if change.any():
            r = np.flatnonzero(change)
            sense[r] = np.sign(dx[r])
        # loops closed by this step: only where two reversals are remembered, or one
        # while still on the skeleton (rows that change are looked at again)
        rows = np.flatnonzero((depth >= 2) | ((depth == 1) & virgin))
        while rows.size:
            xs, sn, dr = x[rows], sense[rows], depth[rows]
            xr1, xr0 = top_x[rows], below_x[rows]
            close = (dr >= 2) & ((xs - xr0) * sn >= 0) & ((xr0 - xr1) * sn > 0)
            skeleton = ((dr == 1) & virgin[rows] & (np.abs(xs) >= np.abs(xr1))
                        & (xs * xr1 <= 0))
            change = close | skeleton
            rows = rows[change]
            if rows.size:
                d = dr[change] - 2 * close[change] - skeleton[change]
                depth[rows] = d
                g = rows + start
                top_x[rows] = self.stack_x[g, np.maximum(d - 1, 0)]
                top_y[rows] = self.stack_y[g, np.maximum(d - 1, 0)]
                below_x[rows] = self.stack_x[g, np.maximum(d - 2, 0)]
        # a contact that slid as a whole and remembers no reversal keeps sliding: its
        # force is sense * mu P whatever the skeleton gives, so the skeleton is evaluated
        # on the others only (on a gathered subset when fewer than half remain); where
        # it reaches the limit of friction the contact slides, its memory lost
        sliding = (depth == 0) & ~virgin
        reach = self.reach[s]
        if sliding.any():
            np.multiply(sense, limit, out=force)
            rows = np.flatnonzero(~sliding)
            if 8 * rows.size < 7 * x.size:  # gathers pay off from 1 in 8 sliding
                y, over = self._branch(x[rows], depth[rows], top_x[rows], top_y[rows],
                                       limit[rows], reach[rows])
                force[rows] = y
                over = rows[over]
            else:
                y, over = self._branch(x, depth, top_x, top_y, limit, reach)
                np.copyto(force, y, where=~sliding)
                over = over[~sliding[over]]
        else:
            y, over = self._branch(x, depth, top_x, top_y, limit, reach)
            force[...] = y
        if over.size:
            depth[over] = 0
            virgin[over] = False
            sliding[over] = True
        y_old[...] = force  # the point a later reversal starts from
        # sliding as a whole with no memory: the coordinate starts again at 0
        # (x * 0 + 0 is +0 for any x, x * 1 + 0 is x: x is never -0, as it starts at +0)
        np.multiply(x, ~sliding, out=x_old)
        x_old += 0.0
        sliding_out[...] = sliding

    @staticmethod
    def _branch(x, d, top_x, top_y, limit, reach):
        """The force on the skeleton (depth 0) or on the branch from the top reversal,
        and the rows where it reached +-mu P (set to it)."""
        # on the skeleton (depth 0) the argument is x, on a branch (x - xr) / 2; numpy
        # selects on a mixed mask only (where costs most on random masks)
        free = d == 0
        every, some = free.all(), free.any()
        if every:
            z = x
        else:
            diff = x - top_x
            half = diff / 2.0
            finite = np.isfinite(diff)
            if not finite.all():  # (x - xr) overflowed: x/2 - xr/2 (as _Masing's)
                half = np.where(finite, half, x / 2.0 - top_x / 2.0)
            z = np.where(free, x, half) if some else half
        # sign(z) mu P f(|z| / reach), the skeleton as _Masing's f with the same bits
        # (_virgin_inverse's operations in place, 1 + t once); copysign(v, z) is
        # sign(z) * v here (v >= 0, and v = 0 at z = +-0)
        r = np.abs(z)
        r /= reach
        t = np.subtract(1.0, r)
        np.maximum(t, 0.0, out=t)
        np.sqrt(t, out=t)
        u = t + 1.0
        v = t * t
        v += u
        v *= r
        v /= u
        np.minimum(v, 1.0, out=v)
        v *= limit
        oz = np.copysign(v, z, out=v)
        if every:
            y = oz
        else:
            y = oz * 2.0
            y += top_y
            if some:
                y = np.where(free, oz, y)
        # the force reaches the limit of friction: +-mu P (the rows returned)
        over = np.flatnonzero(np.abs(y) >= limit)
        if over.size:
            y[over] = np.sign(y[over]) * limit[over]
        return y, over


class TangentialSpring:
    """Tangential contact laws in the shape a DEM code uses: displacement increments in,
    tangential forces out (Mindlin & Deresiewicz at constant normal load), for one
    contact or N at a time.

    Each contact of the batch carries its own state: the force, the displacement and
    the reversal points remembered (Masing's rule, as :func:`tangential_history`).
    Where the force reaches mu P the contact slides: the force stays at +-mu P, the
    memory is cleared, and a reversal starts a Masing branch from the sliding point
    (it reaches the opposite limit after 2 delta_s more, delta_s = 3 mu P / (2 k)).
    A DEM code keeps one spring for all its contacts: :meth:`step` advances every
    contact, :meth:`reset` empties the slots of contacts that leave (a slot reset is
    a fresh contact: no force, no memory).

    Parameters
    ----------
    contact : Contact
        The contacts (any shape); the normal load is held constant.
    mu : float or array_like
        Coefficient of friction [-].
    direction : float or array_like
        Angle of the line of the tangential motion from the major axis [rad]
        (the law is one-dimensional along it).
    size : int, optional
        Number of contacts, when the contact, mu and direction are the same for all
        (the batch's shape is theirs broadcast with (size,)).

    Attributes
    ----------
    force : float or ndarray
        Tangential force along the line [N].
    displacement : float or ndarray
        Accumulated relative displacement along the line [m], slip included.
    sliding : bool or ndarray of bool
        Whether the contact slid in the last step.
    memory : int or ndarray of int
        Reversal points each contact remembers (those no later branch has wiped out).

    Notes
    -----
    Memory per contact: the force, the displacement, the state of the Masing branch
    (5 numbers) and 2 doubles per remembered reversal point.  A branch that passes an
    earlier turning point closes that loop and drops both of its points, and sliding
    drops all, so ``memory`` counts only nested loops still open (the bound: one pair
    per open loop; a path must nest loops of shrinking amplitude to add one); the stack
    is as wide as the largest ``memory`` over the batch.  Cost per step: a fixed number
    of numpy passes (about 50) over blocks of contacts that stay in cache, contacts
    sliding as a whole skipping most of them, plus passes over only the contacts that
    reverse or close a loop in that step; nothing grows with the length of the history.
    benchmarks/dem_laws.py measures it at N = 1e6 against one scipy ellipk + ellipe
    pass per contact: 1.5x on a fretting path (a reversal every 100 steps), 5x on a
    random walk (a reversal every other step).  Contact i of a batch gives the bits of a
    spring of that contact alone.

    Examples
    --------
    >>> import hertz
    >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
    >>> c = hertz.contact(ball, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
    >>> spring = hertz.TangentialSpring(c, mu=0.3)
    >>> f1 = spring.step(1e-9)  # small against 3 mu P / (2 k) = 1.3e-6 m: no slip
    >>> bool(abs(f1 - c.tangential_stiffness() * 1e-9) < 1e-3 * f1)
    True
    >>> float(spring.step(1e-3))  # far: sliding at mu P
    30.0

    Three contacts at once; the second leaves and its slot starts again empty:

    >>> springs = hertz.TangentialSpring(c, mu=0.3, size=3)
    >>> f = springs.step([1e-9, 1e-3, -1e-3])
    >>> [round(float(v), 6) for v in f[1:]]
    [30.0, -30.0]
    >>> springs.reset([1])
    >>> [float(v) for v in springs.force[1:]]
    [0.0, -30.0]
    """

    def __init__(self, contact, mu, direction=0.0, size=None):
        mu = _mu(mu)
        direction = _direction(direction)
        load = _require_load(contact, "a tangential spring")
        along = _along(contact, direction)
        limit = _limit(mu, load)
        self._shape = _batch_shape(np.broadcast_shapes(np.shape(limit), np.shape(along)),
                                   size)
        self._limit = np.broadcast_to(limit, self._shape).reshape(-1).copy()
        reach = np.broadcast_to(1.5 * limit * along, self._shape).reshape(-1).copy()
        self._reach = reach  # delta_s = 3 mu P / (2 k)
        n = self._limit.size
        self._engine = _MasingSpring(n, self._limit, reach)
        self._displacement = np.zeros(n)
        self._force = np.zeros(n)
        self._sliding = np.zeros(n, dtype=bool)

    def _view(self, x):
        return _out(x.reshape(self._shape)) if self._shape else x.item()

    @property
    def shape(self):
        """The batch's shape (() for one contact)."""
        return self._shape

    @property
    def force(self):
        return self._view(self._force)

    @property
    def displacement(self):
        return self._view(self._displacement)

    @property
    def sliding(self):
        return self._view(self._sliding)

    @property
    def memory(self):
        return self._view(self._engine.depth.copy())

    def reset(self, where=None):
        """Return contacts to the unloaded state (no force, no displacement, no memory):
        a contact that leaves, its slot ready for the next one.

        Parameters
        ----------
        where : array_like of bool or int, optional
            A boolean mask of the batch's shape, or integer indices into the flattened
            batch; all contacts if omitted.
        """
        n = self._limit.size
        rows = np.arange(n) if where is None else _selection(where, self._shape, n)
        self._engine.reset(rows)
        self._displacement[rows] = 0.0
        self._force[rows] = 0.0
        self._sliding[rows] = False

    def step(self, increment):
        """Apply a displacement increment [m] (broadcast to the contacts); return the
        new tangential force [N], never beyond +-mu P.

        Raises
        ------
        ValueError
            An increment not finite, or one that takes the accumulated displacement
            beyond the range of a double (magnitude 1.8e308 m); the state is unchanged.
        """
        inc = as_float_array(increment, "increment")
        try:
            inc = np.broadcast_to(inc, self._shape).reshape(-1)
        except ValueError:
            raise ValueError(f"increment must broadcast to the contacts' shape {self._shape}, "
                             f"got the shape {inc.shape}") from None
        engine = self._engine
        with np.errstate(over="ignore"):
            displacement = self._displacement + inc
            # the engine's own coordinate: the displacement since the contact last slid
            # as a whole (the force depends on nothing before), so that it stays within
            # a few 3 mu P / (2 k) and a small step after a long slide is not rounded away
            x = engine.x + inc
        if not (np.isfinite(displacement).all() and np.isfinite(x).all()):
            # checked before any change: the state stays as it was
            if not np.isfinite(inc).all():
                raise error_at("increment", inc.reshape(self._shape),
                               first_failure(np.isfinite(inc)),
                               "a finite displacement increment in m")
            i = first_failure(np.isfinite(displacement) & np.isfinite(x))
            raise ValueError(
                f"increment must keep the accumulated displacement within the range of a "
                f"double (magnitude at most 1.7976931348623157e308 m), got "
                f"{float(inc[i])!r} m on {float(self._displacement[i])!r} m"
                f"{index_text(self._shape, i)}")
        self._displacement = displacement
        # differences of two values near the largest double overflow to +-inf: their sign
        # and comparisons stay right, and the halves are taken apart (inf times a sense
        # of 0 is NaN, read as a first move)
        with np.errstate(over="ignore", invalid="ignore"):
            force, slid = engine.advance(x)
        self._force = force
        self._sliding = slid
        return self.force
