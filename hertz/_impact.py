"""Normal impact of two elastic bodies: Hertz's exact solution, damping laws, restitution.

Two bodies meet along their common normal at the approach speed V with the reduced mass
M = m1 m2 / (m1 + m2) and interact through Hertz's force F = K delta**(3/2), where delta
is the approach of distant points (a DEM code's overlap) and K the contact's own
coefficient (``hertz.contact`` at any load: delta ~ P**(2/3) for any two bodies, spheres,
ellipsoids at an angle, a ball in a groove). With x = delta / delta_max and
tau = t V / delta_max the equation of motion M delta'' = -F is

    x'' = -(5/4) x**(3/2),  x(0) = 0, x'(0) = 1,

whose energy integral x'**2 = 1 - x**(5/2) gives, in closed form (Hertz 1882; Johnson,
*Contact Mechanics*, sec. 11.4):

* delta_max = (5 M V**2 / (4 K))**(2/5), F_max = K delta_max**(3/2);
* the duration t_c = 2 T1 delta_max / V, T1 = Gamma(7/5) Gamma(1/2) / Gamma(9/10)
  = 1.47164...;
* the history: tau(x) = int_0^x du / sqrt(1 - u**(5/2)) = T1 I(x**(5/2); 2/5, 1/2), I the
  regularised incomplete beta function, inverted with scipy's ``betaincinv`` (to the
  last few ulp; the compression near the peak through the complement I(1 - y; 1/2, 2/5),
  so that the speed V sqrt(1 - x**(5/2)) keeps its digits there; for tau < 1/2 by
  Newton's method on tau's binomial series, which keeps the relative digits of early
  times). No time stepping.

Damped impacts add a normal damping force -c(delta) delta' of one of the laws DEM codes
use (:data:`DAMPING_LAWS`); each reduces to

    x'' = -(5/4) x**(3/2) - gamma x**p x'

with p = 0, 1/4 or 1/2 and one number gamma (:func:`restitution` says which for each law),
integrated in three phases so that the integrand stays smooth: the start in the variable
u = x**(1/4) (x**(3/2), x**(1/4), x**(1/2) are powers of u), the turn in time, the end in
u again, with scipy's DOP853 at a relative tolerance of 1e-13 (the restitution to about
1e-12, tested against a 30-digit Taylor integration in tests/reference_impact.py).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from . import _interop
from ._validate import as_float_array, error_at, first_failure

__all__ = ["DAMPING_LAWS", "Impact", "ImpactHistory", "DampedImpact", "damped_impact",
           "damping_coefficient", "impact", "restitution"]

#: T1 = int_0^1 dx / sqrt(1 - x**(5/2)) = Gamma(7/5) Gamma(1/2) / Gamma(9/10): half the
#: duration of an elastic Hertz impact in units of delta_max / V (50 digits, mpmath).
T1 = 1.4716375921623523  # checked against mpmath in tests/test_impact.py

#: The damping laws :func:`restitution` and :func:`damping_coefficient` take, with the
#: exponent p of the nondimensional damping gamma x**p x' and the coefficient's unit.
#: The force law of each is in the docstring of :func:`restitution`.
DAMPING_LAWS = {
    "velocity": (0.0, "N s/m"),
    "mass_velocity": (0.0, "1/s"),
    "viscoelastic": (0.5, "1/(m s)"),
    "kuwabara_kono": (0.5, "s"),
    "tsuji": (0.25, "1"),
    "coeff_restitution": (0.25, "1"),
    "lammps_tsuji": (0.25, "1"),
    "lammps_tsuji_sqrt2": (0.25, "1"),
}

#: Tsuji et al.'s alpha(e) polynomial as LAMMPS (and Marshall 2009, eq. 53) write it.
_TSUJI_POLY = (1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218)


# ----------------------------------------------------------------------------- input

def _positive(value, name: str, unit: str) -> np.ndarray:
    arr = as_float_array(value, name)
    with np.errstate(invalid="ignore"):
        ok = (arr > 0) & (arr < math.inf)
    if not np.all(ok):
        raise error_at(name, arr, first_failure(ok), f"a positive, finite {unit}")
    return arr


def _out(x):
    """A 0-d result as a Python float; arrays read-only (pandas, xarray, pint and dask
    inputs give numpy results)."""
    if np.ndim(x) == 0:
        return float(x)
    x = np.array(x, dtype=float)  # the result's own copy
    x.flags.writeable = False
    return x


def _reference(body1, body2, angle):
    """The contact at 1 N (no validity warning: only its approach, hence K, is used)."""
    from ._contact import HertzValidityWarning, contact

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", HertzValidityWarning)
        return contact(body1, body2, load=1.0, angle=angle)


# ----------------------------------------------------------------------------- elastic

@dataclass(frozen=True, slots=True)
class ImpactHistory:
    """The state of an elastic impact at given times (made by :meth:`Impact.history`).

    Attributes
    ----------
    time : float or ndarray
        The times t [s] from first touch (broadcast with the impact's shape).
    approach : float or ndarray
        Approach delta of distant points [m] (a DEM code's overlap); before first
        touch (t < 0) and after separation (t > duration) the bodies fly freely and
        delta is minus the gap, V t and -V (t - duration).
    force : float or ndarray
        Normal contact force K delta**(3/2) [N] (0 out of contact).
    speed : float or ndarray
        d delta / dt [m/s]: V at first touch, 0 at the largest approach, -V at
        separation (restitution 1).
    """

    time: float | np.ndarray
    approach: float | np.ndarray
    force: float | np.ndarray
    speed: float | np.ndarray


@dataclass(frozen=True, slots=True, eq=False)
class Impact:
    """Elastic normal impact of two bodies (Hertz); made by :func:`impact`.

    Arrays when any input was an array (the broadcast shape of the bodies' fields,
    ``speed``, ``mass`` and ``angle``); pandas, xarray and pint inputs give fields of
    their kind (Series on the same index, DataArrays, Quantities in SI units), as for
    :class:`hertz.Contact`, and the methods then give numpy arrays.

    Attributes
    ----------
    speed : float or ndarray
        Normal approach speed V at first touch [m/s].
    mass : float or ndarray
        Reduced mass M = m1 m2 / (m1 + m2) [kg].
    stiffness_coefficient : float or ndarray
        K of Hertz's force F = K delta**(3/2) [N/m**1.5] (for two spheres
        (4/3) E* sqrt(R)).
    max_approach : float or ndarray
        Largest approach delta_max = (5 M V**2 / (4 K))**(2/5) [m].
    max_force : float or ndarray
        Largest force K delta_max**(3/2) [N].
    max_pressure : float or ndarray
        Peak pressure p0 of the contact at the largest force [Pa].
    duration : float or ndarray
        Contact time t_c = 2 T1 delta_max / V, T1 = Gamma(7/5) Gamma(1/2) / Gamma(9/10)
        [s].
    restitution : float or ndarray
        Coefficient of restitution: 1 (elastic).
    """

    speed: float | np.ndarray
    mass: float | np.ndarray
    stiffness_coefficient: float | np.ndarray
    max_approach: float | np.ndarray
    max_force: float | np.ndarray
    max_pressure: float | np.ndarray
    duration: float | np.ndarray
    restitution: float | np.ndarray
    #: the contact at the largest approach (for the yield speed and the damping laws)
    _contact: object = field(repr=False)
    #: the Impact of plain numpy values behind pandas, xarray or pint fields (the methods
    #: compute on it), else None
    _plain: object = field(default=None, repr=False)

    def _numeric(self):
        return self if self._plain is None else self._plain

    @property
    def time_to_max(self):
        """Time from first touch to the largest approach, duration / 2 [s]."""
        return self.duration * 0.5

    def history(self, t) -> ImpactHistory:
        """Approach, force and speed at times t [s], from the closed form (no time steps).

        Parameters
        ----------
        t : float or array_like
            Times from first touch [s], finite; broadcast with the impact's shape.

        Returns
        -------
        ImpactHistory
            ``time``, ``approach`` [m], ``force`` [N], ``speed`` [m/s].

        Raises
        ------
        ValueError
            If a time is not finite (the message names the value and its index).

        Examples
        --------
        >>> import hertz
        >>> glass = hertz.Body.sphere(0.01, E=48e9, nu=0.2)
        >>> hit = hertz.impact(glass, glass, speed=20.0, mass=0.5 * 2800 * 4.18879e-6)
        >>> h = hit.history([0.0, hit.time_to_max, hit.duration])
        >>> [round(float(s), 9) for s in h.speed]
        [20.0, 0.0, -20.0]
        >>> bool(h.force[1] == hit.max_force)
        True
        """
        from scipy import special

        t = as_float_array(t, "t")
        ok = np.isfinite(t)
        if not np.all(ok):
            raise error_at("t", t, first_failure(ok), "a finite time in s")
        src = self._numeric()
        V, dmax, fmax, tc = src.speed, src.max_approach, src.max_force, src.duration
        t, V, dmax, fmax, tc = np.broadcast_arrays(t, V, dmax, fmax, tc)
        tau = t * V / dmax
        inside = (t > 0) & (t < tc)
        # distance from the peak in tau, and the compressed half's tau
        d = np.abs(tau - T1)
        half = np.where(tau <= T1, tau, 2.0 * T1 - tau)  # not T1 - d: tau's own digits
        with np.errstate(invalid="ignore", divide="ignore"):
            start = half <= _SERIES_TAU  # early: the series (betaincinv loses digits)
            near_start = ~start & (half <= 0.5 * T1)
            x_early = _early_x(np.where(start & inside, half, 0.0))
            y = np.where(near_start & inside,
                         special.betaincinv(0.4, 0.5, np.clip(half / T1, 0.0, 1.0)),
                         x_early * x_early * np.sqrt(x_early))
            c = np.where(~near_start & ~start & inside,
                         special.betaincinv(0.5, 0.4, np.clip(d / T1, 0.0, 1.0)), 1.0)
            c = np.where(near_start | start, 1.0 - y, c)  # 1 - x**(5/2)
            y = np.where(near_start | start, y, 1.0 - c)  # x**(5/2)
        x = np.where(start, x_early, y ** 0.4)
        sign = np.where(tau <= T1, 1.0, -1.0)
        approach = np.where(inside, dmax * x, np.where(t <= 0, V * t, -V * (t - tc)))
        force = np.where(inside, fmax * x ** 1.5, 0.0)
        speed = np.where(inside, sign * V * np.sqrt(c), np.where(t <= 0, V, -V))
        return ImpactHistory(_out(t), _out(approach), _out(force), _out(speed))

    def yield_speed(self, yield_strength, body=1, criterion="von_mises"):
        """The approach speed [m/s] at which body 1 or 2 first yields during the impact.

        The largest force grows as V**(6/5), so the speed at which it reaches the load of
        first yield P_y (:meth:`hertz.Contact.first_yield_load`) is
        V_y = V (P_y / F_max)**(5/6); it does not depend on this impact's own speed.

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
            V_y [m/s].

        Examples
        --------
        Chung & Ooi's aluminium-oxide sphere (R 5 mm, E 380 GPa, nu 0.23, 4000 kg/m^3) on
        a rigid wall, yield strength 2 GPa:

        >>> import math
        >>> import hertz
        >>> ball = hertz.Body.sphere(5e-3, E=380e9, nu=0.23)
        >>> wall = hertz.Body.plane(E=math.inf, nu=0.23)
        >>> m = 4000 * 4 / 3 * math.pi * 5e-3 ** 3
        >>> hit = hertz.impact(ball, wall, speed=1.0, mass=m)
        >>> print(f"{hit.yield_speed(2e9):.4f} m/s")
        0.0796 m/s
        """
        src = self._numeric()
        p_y = np.asarray(src._contact.first_yield_load(yield_strength, body, criterion),
                         dtype=float)
        return _out(src.speed * (p_y / src.max_force) ** (5.0 / 6.0))

    def plastic_restitution(self, yield_strength, body=1, criterion="von_mises"):
        """Thornton's (1997) restitution of an elastic-perfectly-plastic impact.

        Thornton's model: Hertz's pressure until its peak reaches the limit p_y, then a
        flat-topped pressure p_y over the growing plastic core; elastic unloading. With
        the yield speed V_y (:meth:`yield_speed`, from the contact's own first yield) and
        r = V_y / V:

            e = sqrt(6 sqrt(3) / 5) sqrt(1 - r**2 / 6)
                * (r / (r + 2 sqrt(6/5 - r**2 / 5)))**(1/4)   for V > V_y, else 1.

        Derived for spheres; for other bodies a model (the yield of their own contact in
        the same formula).

        Parameters
        ----------
        yield_strength : float or array_like
            Yield strength in tension [Pa] of the body that yields first.
        body : {1, 2}
            Which body.
        criterion : {"von_mises", "tresca"}
            The yield criterion.

        Returns
        -------
        float or ndarray
            The coefficient of restitution, in (0, 1].

        Examples
        --------
        >>> import math
        >>> import hertz
        >>> ball = hertz.Body.sphere(5e-3, E=70e9, nu=0.33)
        >>> wall = hertz.Body.plane(E=math.inf, nu=0.3)
        >>> hit = hertz.impact(ball, wall, speed=5.0, mass=2700 * 4 / 3 * math.pi * 125e-9)
        >>> print(f"{hit.plastic_restitution(300e6):.4f}")
        0.3195
        """
        r = np.asarray(self.yield_speed(yield_strength, body, criterion)
                       / self._numeric().speed)
        rc = np.minimum(r, 1.0)
        e = (math.sqrt(6.0 * math.sqrt(3.0) / 5.0) * np.sqrt(1.0 - rc * rc / 6.0)
             * (rc / (rc + 2.0 * np.sqrt(1.2 - rc * rc / 5.0))) ** 0.25)
        return _out(np.where(r >= 1.0, 1.0, e))


#: Below this tau (x about 0.49) the history inverts the series of tau(x).
_SERIES_TAU = 0.5
#: c_k / (5 k / 2 + 1), c_k = binomial(2 k, k) / 4**k: tau(x) = sum of these times
#: x**(5 k / 2 + 1) (the binomial series of (1 - x**(5/2))**(-1/2), integrated); 40 terms
#: reach 1e-17 at x = 0.5.
_TAU_SERIES = np.array([math.comb(2 * k, k) / 4.0**k / (2.5 * k + 1.0) for k in range(40)])


def _early_x(tau):
    """x with tau(x) = tau for tau <= _SERIES_TAU, by Newton's method on the series
    (from x = tau, above the root: tau(x) >= x; monotone convergence)."""
    x = np.array(tau, dtype=float)
    for _ in range(6):
        w = x * x * np.sqrt(x)  # x**(5/2)
        total = np.zeros_like(x)
        for c in _TAU_SERIES[::-1]:
            total = total * w + c
        x = x - (x * total - tau) * np.sqrt(1.0 - w)
    return x


def impact(body1, body2, speed, mass, angle=0.0) -> Impact:
    """Elastic normal impact of two bodies: Hertz's exact solution.

    Parameters
    ----------
    body1, body2 : Body
        The two bodies at their first point of contact (any pair :func:`hertz.contact`
        takes; ``E=inf`` for a rigid one).
    speed : float or array_like
        Normal approach speed V [m/s], positive: the relative speed of the two bodies
        along their common normal (two spheres at +-10 m/s meet at 20 m/s).
    mass : float or array_like
        Reduced mass M = m1 m2 / (m1 + m2) [kg], positive (the mass of a ball on a wall).
    angle : float or array_like, optional
        Angle from body 1's x axis to body 2's [rad], as in :func:`hertz.contact`.

    Returns
    -------
    Impact
        ``max_approach``, ``max_force``, ``max_pressure``, ``duration``, ``restitution``
        and the histories (:meth:`Impact.history`); Python floats for scalar input, else
        arrays of the broadcast shape.

    Raises
    ------
    TypeError
        If a body is not a :class:`hertz.Body` or an argument is not numeric.
    ValueError
        If speed or mass is not positive and finite, the bodies have no Hertz point
        contact, or shapes do not broadcast (the message names the parameter, the value
        and its index).

    Examples
    --------
    Chung & Ooi's Test 1: two glass spheres (R 10 mm, E 48 GPa, nu 0.2, 2800 kg/m^3)
    head-on at +-10 m/s:

    >>> import math
    >>> import hertz
    >>> glass = hertz.Body.sphere(0.01, E=48e9, nu=0.2)
    >>> m = 2800 * 4 / 3 * math.pi * 0.01 ** 3
    >>> hit = hertz.impact(glass, glass, speed=20.0, mass=m / 2)
    >>> print(f"{hit.max_approach * 1e6:.2f} um, {hit.max_force / 1e3:.3f} kN, "
    ...       f"{hit.duration * 1e6:.2f} us")
    274.11 um, 10.697 kN, 40.34 us
    """
    from ._contact import _BODY_UNITS, _check_body, contact

    _check_body(body1, "body1")
    _check_body(body2, "body2")
    fields = [getattr(b, k) for b in (body1, body2) for k in _BODY_UNITS]
    if _interop.any_wrapped(speed, mass, angle, *fields):
        return _wrapped_impact(body1, body2, speed, mass, angle)
    V = _positive(speed, "speed", "approach speed in m/s")
    m = _positive(mass, "mass", "reduced mass in kg")
    ref = _reference(body1, body2, angle)
    delta1 = np.asarray(ref.delta)  # the approach at 1 N: K = delta1**(-3/2)
    # delta_max = (5 M V^2 / (4 K))^(2/5) = (5 M V^2 / 4)^(2/5) delta1^(3/5)
    # as a product of powers: no overflow or underflow of M V^2 at extreme speeds and masses
    with np.errstate(over="ignore", under="ignore"):
        dmax = (1.25 * m) ** 0.4 * V ** 0.8 * delta1 ** 0.6
    _representable(dmax, V, m, "a largest approach", "m")
    at_max = contact(body1, body2, approach=_out(dmax), angle=angle)
    _representable(np.asarray(at_max.load, dtype=float), V, m, "a largest force", "N")
    shape = np.shape(at_max.delta)
    K = np.broadcast_to(delta1 ** -1.5, shape)
    V, m = np.broadcast_to(V, shape), np.broadcast_to(m, shape)
    dmax, fmax, p0 = (np.asarray(x, dtype=float) for x in (at_max.delta, at_max.load,
                                                             at_max.p0))
    duration = (2.0 * T1) * dmax / V
    return Impact(_out(V), _out(m), _out(K), _out(dmax), _out(fmax), _out(p0),
                  _out(duration), _out(np.ones(shape)), at_max)


def _representable(x, V, m, what, unit):
    """ValueError naming speed and mass where x is 0 or inf (beyond floating point)."""
    shape = np.broadcast_shapes(np.shape(x), np.shape(V), np.shape(m))
    ok = np.broadcast_to((x > 0) & (x < math.inf), shape).ravel()
    if not np.all(ok):
        k = first_failure(ok)
        V, m, x = (np.broadcast_to(a, shape).ravel()[k] for a in (V, m, x))
        raise ValueError(f"speed {float(V)!r} m/s and mass {float(m)!r} kg give {what} of "
                         f"{float(x)!r} {unit}, beyond floating "
                         f"point: check the units (SI: m/s, kg)")


#: the fields of an Impact with their SI units (pint spelling), for pandas, xarray, pint
_IMPACT_UNITS = {"speed": "m/s", "mass": "kg", "stiffness_coefficient": "N/m**1.5",
                 "max_approach": "m", "max_force": "N", "max_pressure": "Pa", "duration": "s",
                 "restitution": ""}


def _si(value, name: str, unit: str, what: str):
    """A pint Quantity's magnitude in ``unit`` (TypeError naming it for another
    dimension); anything else unchanged."""
    if _interop.library(value) != "pint":
        return value
    from pint import DimensionalityError

    try:
        return value.to(unit).magnitude
    except DimensionalityError:
        raise TypeError(f"{name} must be {what} (a quantity convertible to {unit}), got a "
                        f"quantity in {value.units}") from None


def _wrapped_impact(body1, body2, speed, mass, angle):
    """:func:`impact` for pandas, xarray or pint inputs: fields of their kind, the methods
    computing on the plain twin (numpy results)."""
    from ._contact import _BODY_UNITS, Body

    registry = next((v._REGISTRY for v in (speed, mass) if _interop.library(v) == "pint"),
                    None)
    speed = _si(speed, "speed", "m/s", "a speed")
    mass = _si(mass, "mass", "kg", "a mass")
    items = ([(f"body{i}.{k}", getattr(b, k), u) for i, b in ((1, body1), (2, body2))
              for k, u in _BODY_UNITS.items()]
             + [("speed", speed, ""), ("mass", mass, ""), ("angle", angle, _interop.RAD)])
    plain, recipe = _interop.unwrap(items)
    if recipe.registry is None:
        recipe.registry = registry
    try:
        hit = impact(Body(*plain[0:4]), Body(*plain[4:8]), plain[8], plain[9], plain[10])
    except ValueError as exc:
        raise recipe.labelled(exc) from None
    fields = [recipe.wrap(getattr(hit, k), u, k) for k, u in _IMPACT_UNITS.items()]
    return Impact(*fields, hit._contact, hit)


# ----------------------------------------------------------------------------- damped

@dataclass(frozen=True, slots=True)
class DampedImpact:
    """A normal impact with a damping law (made by :func:`damped_impact`).

    Attributes
    ----------
    restitution : float or ndarray
        Rebound speed over approach speed [-], in [0, 1] (0: the bodies never part).
    duration : float or ndarray
        Contact time [s] (from first touch to the end of the contact: the approach
        back at 0, or the total force back at 0 with ``cutoff``); inf where the bodies
        never part.
    max_approach : float or ndarray
        Largest approach [m] (nan where a creep without the cutoff was abandoned before
        the turn was found).
    gamma : float or ndarray
        The nondimensional damping of the law (see :func:`restitution`).
    """

    restitution: float | np.ndarray
    duration: float | np.ndarray
    max_approach: float | np.ndarray
    gamma: float | np.ndarray


def _check_law(law: str):
    if law not in DAMPING_LAWS:
        raise ValueError(f"law must be one of {', '.join(sorted(DAMPING_LAWS))}, got {law!r}")
    return DAMPING_LAWS[law][0]


def _tsuji_poly(e):
    out = np.zeros_like(e)
    for c in reversed(_TSUJI_POLY):
        out = out * e + c
    return out


def _alpha(law, coefficient):
    """alpha of the Tsuji form c = alpha sqrt(M K) delta**(1/4) for the three laws."""
    if law == "tsuji":
        return coefficient
    e = coefficient
    if law == "coeff_restitution":
        with np.errstate(divide="ignore"):
            L = np.log(e)
        return -math.sqrt(5.0) * L / np.sqrt(math.pi ** 2 + L * L)
    if law == "lammps_tsuji":  # LAMMPS up to the 22 Jul 2025 stable release
        return _tsuji_poly(e)
    return math.sqrt(2.0) * _tsuji_poly(e)  # lammps_tsuji_sqrt2: the development sources


def _scales(body1, body2, speed, mass, angle):
    """V, M, delta_max (elastic), the contact radius factor a b / delta, broadcast."""
    hit = impact(body1, body2, speed, mass, angle)._numeric()
    c = hit._contact
    shape = np.shape(hit.max_approach)
    ra = np.asarray(c.a) * np.asarray(c.b) / np.asarray(c.delta)
    return (np.broadcast_to(hit.speed, shape), np.broadcast_to(hit.mass, shape),
            np.broadcast_to(hit.max_approach, shape), np.broadcast_to(ra, shape), shape)


def _gamma(law, coefficient, V, m, d0, ra):
    """The nondimensional damping gamma of x'' = -(5/4) x^1.5 - gamma x^p x'."""
    if law == "velocity":
        return coefficient * d0 / (m * V)
    if law == "mass_velocity":
        return coefficient * d0 / V
    if law == "viscoelastic":
        return coefficient * np.sqrt(ra) * d0 ** 1.5 / V
    if law == "kuwabara_kono":
        return 1.875 * coefficient * V / d0
    return math.sqrt(1.25) * _alpha(law, coefficient)


def _coefficient(law, gamma, V, m, d0, ra):
    """The inverse of :func:`_gamma`."""
    if law == "velocity":
        return gamma * m * V / d0
    if law == "mass_velocity":
        return gamma * V / d0
    if law == "viscoelastic":
        return gamma * V / (np.sqrt(ra) * d0 ** 1.5)
    if law == "kuwabara_kono":
        return gamma * d0 / (1.875 * V)
    alpha = gamma / math.sqrt(1.25)
    if law == "tsuji":
        return alpha
    if law == "coeff_restitution":
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(alpha < math.sqrt(5.0),
                            np.exp(-alpha * math.pi / np.sqrt(5.0 - alpha * alpha)), np.nan)
    return _invert_tsuji_poly(alpha / math.sqrt(2.0))


def _invert_tsuji_poly(target):
    from scipy import optimize

    out = np.empty(np.shape(target))
    flat = out.reshape(-1)
    for i, a in enumerate(np.asarray(target, dtype=float).reshape(-1)):
        f = lambda e, a=a: float(_tsuji_poly(np.float64(e))) - a  # noqa: E731
        lo, hi = 1e-6, 1.0
        if not (f(lo) >= 0 >= f(hi)):
            flat[i] = math.nan
        else:
            flat[i] = optimize.brentq(f, lo, hi, xtol=1e-15, rtol=1e-15)
    return out


_RTOL, _ATOL = 1e-13, 1e-16
#: The largest nondimensional damping gamma the damped impact is integrated for (beyond
#: it the restitution with the force cut off, (5/4)**2 / gamma**2 for Tsuji's law, is
#: below 1e-12 and the integration loses it).
MAX_GAMMA = 1e6
#: The speed (in units of V) at which the integration leaves the variable u = x**(1/4).
_SWITCH = 0.5
#: Time (in units of delta_max / V) after which a contact that has not ended is taken as
#: one in which the bodies never part.
_STUCK = 1e4
#: A speed (in units of V) below which a contact creeping back toward x = 0 on the way
#: out is taken as one that never ends (restitution 0, duration inf).
_STALL = 1e-9
#: The right-hand-side evaluations after which the way out is taken as such a creep
#: (a stiff one, where the explicit integrator crawls; about half a second).
_MAX_CALLS = 20000


class _StalledError(Exception):
    pass


def _solve(gamma: float, p: float, cutoff: bool):
    """(restitution, duration, largest x) of x'' = -(5/4) x^1.5 - gamma x^p x', x(0) = 0,
    x'(0) = 1, in units of the elastic delta_max and delta_max / V; then where the phases
    changed (u at the switch, the time of the turn's phase, u at the end; nan where
    there was none), for the tests' high-precision reference."""
    from scipy.integrate import solve_ivp

    nan = math.nan
    if gamma == 0.0:
        return 1.0, 2.0 * T1, 1.0, nan, nan, nan
    q = 4.0 * p  # x**p = u**q

    def in_u(u, y):  # y = (v, tau); d/du
        v = y[0]
        u3 = u * u * u
        return (-5.0 * u3 ** 3 / v - 4.0 * gamma * u3 * u ** q, 4.0 * u3 / v)

    def slow(u, y):
        return y[0] - _SWITCH

    slow.terminal, slow.direction = True, -1
    a = solve_ivp(in_u, (0.0, 1.0), (1.0, 0.0), method="DOP853", rtol=_RTOL, atol=_ATOL,
                  events=slow)
    u_s = float(a.t_events[0][0])
    tau_a = float(a.y_events[0][0][1])
    x_s = u_s ** 4

    def in_t(t, y):  # y = (x, v)
        x = max(y[0], 0.0)
        return (y[1], -1.25 * x * math.sqrt(x) - gamma * x ** p * y[1])

    def back(t, y):
        return y[0] - x_s

    back.terminal, back.direction = True, -1

    def turn(t, y):
        return y[1]

    turn.direction = -1

    def zero_force(t, y):
        x = max(y[0], 0.0)
        return 1.25 * x * math.sqrt(x) + gamma * x ** p * y[1]

    zero_force.terminal, zero_force.direction = True, -1
    events = [back, turn] + ([zero_force] if cutoff else [])
    calls = [0]

    def in_t_counted(t, y):
        calls[0] += 1
        if calls[0] > _MAX_CALLS:  # a stiff creep (heavy damping, no cutoff)
            raise _StalledError
        return in_t(t, y)

    try:
        b = solve_ivp(in_t_counted, (0.0, _STUCK), (x_s, _SWITCH), method="DOP853",
                      rtol=_RTOL, atol=_ATOL, events=events)
    except _StalledError:
        return 0.0, math.inf, nan, u_s, nan, nan
    x_max = float(b.y_events[1][0][0]) if len(b.t_events[1]) else x_s
    if b.status != 1:  # no terminal event: the bodies never part
        return 0.0, math.inf, x_max, u_s, nan, nan
    if cutoff and len(b.t_events[2]):
        return (-float(b.y_events[2][0][1]), tau_a + float(b.t_events[2][0]), x_max, u_s,
                float(b.t_events[2][0]), nan)
    tau_b = tau_a + float(b.t_events[0][0])
    v_b = float(b.y_events[0][0][1])

    def ends(u, y):
        return 1.25 * u ** (6.0 - q) + gamma * y[0]

    ends.terminal, ends.direction = True, -1

    def stalls(u, y):  # creeping toward x = 0 (never reached): restitution 0
        return y[0] + _STALL

    stalls.terminal, stalls.direction = True, 1
    calls[0] = 0

    def in_u_counted(u, y):
        calls[0] += 1
        if calls[0] > _MAX_CALLS:  # a stiff creep on the way out (heavy damping, no cutoff)
            raise _StalledError
        return in_u(u, y)

    t_b = float(b.t_events[0][0])
    try:
        c = solve_ivp(in_u_counted, (u_s, 0.0), (v_b, 0.0), method="DOP853", rtol=_RTOL,
                      atol=_ATOL, events=[stalls, ends] if cutoff else [stalls])
    except _StalledError:
        return 0.0, math.inf, x_max, u_s, t_b, nan
    if len(c.t_events[0]):
        return 0.0, math.inf, x_max, u_s, t_b, nan
    if cutoff and len(c.t_events[1]):
        return (-float(c.y_events[1][0][0]), tau_b + float(c.y_events[1][0][1]), x_max, u_s,
                t_b, float(c.t_events[1][0]))
    return -float(c.y[0, -1]), tau_b + float(c.y[1, -1]), x_max, u_s, t_b, 0.0


def _solve_all(gamma, p, cutoff):
    """_solve over an array of gamma, each distinct value once."""
    g = np.asarray(gamma, dtype=float)
    values, inverse = np.unique(g.reshape(-1), return_inverse=True)
    solved = np.array([_solve(float(v), p, cutoff)[:3] for v in values]).reshape(-1, 3)
    return tuple(solved[inverse, k].reshape(g.shape) for k in range(3))


def _law_inputs(body1, body2, speed, mass, law, coefficient, angle, name):
    p = _check_law(law)
    coef = as_float_array(coefficient, name)
    with np.errstate(invalid="ignore"):
        if name == "coefficient" and law in ("coeff_restitution", "lammps_tsuji",
                                                "lammps_tsuji_sqrt2"):
            ok, allowed = (coef > 0) & (coef <= 1), "a LAMMPS restitution in (0, 1]"
        elif name == "coefficient":
            ok, allowed = (coef >= 0) & (coef < math.inf), "a finite damping coefficient >= 0"
        else:
            ok, allowed = (coef > 0) & (coef <= 1), "a coefficient of restitution in (0, 1]"
    if not np.all(ok):
        raise error_at(name, coef, first_failure(ok), allowed)
    V, m, d0, ra, shape = _scales(body1, body2, speed, mass, angle)
    shape = np.broadcast_shapes(shape, coef.shape)
    V, m, d0, ra, coef = (np.broadcast_to(x, shape) for x in (V, m, d0, ra, coef))
    return p, V, m, d0, ra, coef


def damped_impact(body1, body2, speed, mass, law, coefficient, cutoff=True,
                  angle=0.0) -> DampedImpact:
    """A normal impact with one of the damping laws: restitution, duration, largest approach.

    Parameters and laws as :func:`restitution`.

    Returns
    -------
    DampedImpact

    Examples
    --------
    >>> import hertz
    >>> steel = hertz.Body.sphere(0.005, E=210e9, nu=0.3)
    >>> hit = hertz.damped_impact(steel, steel, speed=1.0, mass=2e-3, law="tsuji",
    ...                           coefficient=0.5)
    >>> elastic = hertz.impact(steel, steel, speed=1.0, mass=2e-3)
    >>> print(f"e = {hit.restitution:.6f}, "
    ...       f"delta_max / elastic = {hit.max_approach / elastic.max_approach:.4f}")
    e = 0.539421, delta_max / elastic = 0.7812
    """
    p, V, m, d0, ra, coef = _law_inputs(body1, body2, speed, mass, law, coefficient, angle,
                                        "coefficient")
    gamma = _gamma(law, coef, V, m, d0, ra)
    ok = np.asarray(gamma <= MAX_GAMMA).reshape(-1)
    if not np.all(ok):
        k = first_failure(ok)
        raise ValueError(f"coefficient {float(np.ravel(coef)[k])!r} of law {law!r} gives the "
                         f"nondimensional damping gamma = {float(np.ravel(gamma)[k]):.4g}, "
                         f"above {MAX_GAMMA:g}: a contact so overdamped that its "
                         f"restitution (below 1e-12 cut off, 0 otherwise) is beyond what the "
                         f"integration resolves; check the coefficient's units")
    e, tau, x = _solve_all(gamma, p, bool(cutoff))
    return DampedImpact(_out(e), _out(tau * d0 / V), _out(x * d0), _out(gamma))


def restitution(body1, body2, speed, mass, law, coefficient, cutoff=True, angle=0.0):
    """Coefficient of restitution of a normal Hertz impact with a damping law.

    The total normal force on the bodies is F = K delta**(3/2) + c(delta) delta',
    delta the approach (overlap), delta' its rate (> 0 approaching), K the Hertz
    coefficient (:attr:`Impact.stiffness_coefficient`), M the reduced mass and c:

    ======================= ============================================= ================
    law                     c(delta)                                      coefficient
    ======================= ============================================= ================
    ``velocity``            eta                                           eta [N s/m]
    ``mass_velocity``       eta0 M                                        eta0 [1/s]
    ``viscoelastic``        eta0 M a, a = sqrt(a_x a_y) (sqrt(R delta))   eta0 [1/(m s)]
    ``kuwabara_kono``       (3/2) A K delta**(1/2)                        A [s]
    ``tsuji``               alpha sqrt(M K) delta**(1/4)                  alpha [-]
    ``coeff_restitution``   alpha = -sqrt(5) ln e / sqrt(pi^2 + ln^2 e)   e (LAMMPS's) [-]
    ``lammps_tsuji``        alpha = poly(e) (LAMMPS's Tsuji, stable)      e (LAMMPS's) [-]
    ``lammps_tsuji_sqrt2``  alpha = sqrt(2) poly(e) (LAMMPS development)  e (LAMMPS's) [-]
    ======================= ============================================= ================

    The first three, ``tsuji`` and ``coeff_restitution`` are LAMMPS ``pair_style
    granular``'s ``damping`` options with ``hertz/material`` (``velocity``,
    ``mass_velocity``, ``viscoelastic`` with a = sqrt(R delta) the contact radius, which
    for other bodies is taken as the radius sqrt(a b) of the circle of the same area);
    ``kuwabara_kono`` is Kuwabara & Kono (1987) and Brilliantov et al. (1996),
    F = K (delta**(3/2) + (3/2) A delta**(1/2) delta'); ``tsuji`` is Tsuji et al. (1992);
    LAMMPS's ``damping tsuji`` reads a restitution e and uses alpha = poly(e),
    poly(e) = 1.2728 - 4.2783 e + 11.087 e**2 - 22.348 e**3 + 27.467 e**4 - 18.022 e**5
    + 4.8218 e**6, in the releases up to the 22 Jul 2025 stable one (``lammps_tsuji``;
    measured with that release's ``lmp``), and alpha = sqrt(2) poly(e) in the development
    sources since mid-2026 (``damp *= MY_SQRT2``: ``lammps_tsuji_sqrt2``);
    ``coeff_restitution`` is the damping of EDEM, LIGGGHTS and Lethe (2 sqrt(5/6) beta
    sqrt(S_n M), S_n = 2 E* sqrt(R delta)), whose restitution is close to, not equal to,
    the e it is given.

    With x = delta / delta_max (elastic) and tau = t V / delta_max each law is
    x'' = -(5/4) x**(3/2) - gamma x**p x' with one number gamma: eta delta_max / (M V)
    (``velocity``), eta0 delta_max / V (``mass_velocity``), eta0 sqrt(a b / delta)
    delta_max**(3/2) / V (``viscoelastic``), (15/8) A V / delta_max
    (``kuwabara_kono``), sqrt(5/4) alpha (the three Tsuji forms: their restitution
    does not depend on the speed, the mass or the bodies).

    Parameters
    ----------
    body1, body2 : Body
        The bodies, as for :func:`impact`.
    speed : float or array_like
        Normal approach speed [m/s], positive.
    mass : float or array_like
        Reduced mass [kg], positive.
    law : str
        One of :data:`DAMPING_LAWS` (the table above).
    coefficient : float or array_like
        The law's coefficient (the table above), >= 0 (the LAMMPS restitutions in
        (0, 1]).
    cutoff : bool
        True: the total force is never attractive; the contact ends when it reaches 0
        (LAMMPS with ``limit_damping``, LIGGGHTS ``limitForce on``, any code that clips
        the normal force at 0). False: the damping may pull (LAMMPS's default, LIGGGHTS
        ``limitForce off``); the contact ends when the approach returns to 0.
    angle : float or array_like, optional
        Angle between the bodies' x axes [rad].

    Returns
    -------
    float or ndarray
        The coefficient of restitution (rebound over approach speed), in [0, 1]; 0
        where the bodies never part.

    Raises
    ------
    ValueError
        An unknown law; a coefficient outside its range (naming it and its index); one
        whose nondimensional damping gamma exceeds :data:`MAX_GAMMA` (a restitution
        below 1e-12, beyond the integration's resolution).

    Examples
    --------
    >>> import hertz
    >>> steel = hertz.Body.sphere(0.005, E=210e9, nu=0.3)
    >>> e = hertz.restitution(steel, steel, speed=[0.1, 1.0, 10.0], mass=2e-3,
    ...                       law="tsuji", coefficient=0.5)
    >>> [f"{x:.10f}" for x in e]  # Tsuji's law: independent of the speed
    ['0.5394214314', '0.5394214314', '0.5394214314']
    """
    return damped_impact(body1, body2, speed, mass, law, coefficient, cutoff,
                         angle).restitution


def damping_coefficient(body1, body2, speed, mass, law, restitution, cutoff=True,
                        angle=0.0):
    """The coefficient of a damping law that gives a coefficient of restitution.

    The inverse of :func:`restitution` (the same laws, conventions and parameters),
    solved to about 1e-12 in gamma.

    Parameters
    ----------
    restitution : float or array_like
        The coefficient of restitution wanted, in (0, 1].

    Returns
    -------
    float or ndarray
        The law's coefficient (unit as in :func:`restitution`'s table); for
        ``coeff_restitution`` and ``lammps_tsuji`` the e to give LAMMPS.

    Examples
    --------
    The e to give LAMMPS's ``damping coeff_restitution`` for a true restitution of 0.8
    (the force never attractive):

    >>> import hertz
    >>> glass = hertz.Body.sphere(0.01, E=48e9, nu=0.2)
    >>> e_in = hertz.damping_coefficient(glass, glass, 20.0, 5.86e-3, "coeff_restitution",
    ...                                  0.8)
    >>> print(f"{e_in:.6f}")
    0.791170
    >>> print(f"{hertz.restitution(glass, glass, 20.0, 5.86e-3, 'coeff_restitution', e_in):.10f}")
    0.8000000000
    """
    p, V, m, d0, ra, target = _law_inputs(body1, body2, speed, mass, law, restitution, angle,
                                          "restitution")
    cut = bool(cutoff)
    t = np.asarray(target, dtype=float)
    values, inverse = np.unique(t.reshape(-1), return_inverse=True)
    gammas = np.array([_gamma_for(float(e), p, cut) for e in values])
    gamma = gammas[inverse].reshape(t.shape)
    return _out(_coefficient(law, gamma, V, m, d0, ra))


def _gamma_for(e: float, p: float, cutoff: bool) -> float:
    """gamma with _solve(gamma)'s restitution = e (it falls monotonically with gamma)."""
    from scipy import optimize

    if e == 1.0:
        return 0.0

    def f(g):
        return _solve(g, p, cutoff)[0] - e

    lo, hi = 0.0, 0.5
    while f(hi) > 0:
        lo, hi = hi, hi * 2.0
        if hi > 1e6:
            raise ValueError(f"restitution {e!r} is beyond the reach of this damping law "
                             "(the bodies never part)")
    return optimize.brentq(f, lo, hi, xtol=1e-14, rtol=1e-13)
