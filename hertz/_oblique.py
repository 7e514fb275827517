"""Oblique impact of two elastic bodies with friction: Hertz's normal impact and
Mindlin-Deresiewicz partial slip coupled to the rigid-body motion (Maw, Barber & Fawcett).

The model
---------
Two bodies meet at the normal approach speed V_n = V cos(theta) (theta the incidence
from the common normal) with the tangential velocity V sin(theta) of the centres along
a principal axis of the contact ellipse.  The normal impact is Hertz's
(:func:`hertz.impact`: elastic, restitution 1); the tangential force Q does not change
the pressure (Mindlin's uncoupled solution, exact for elastically similar bodies; see
:func:`hertz.dundurs_beta`).  The tangential traction follows Mindlin and Deresiewicz
under the varying normal force, by the exact one-dimensional memory of
:func:`hertz.load_path` (``hertz._load_path``: springs enter the contact free of force
as it grows, leave it as it shrinks, and stick or slide at +-mu p).

Rigid-body motion, x along the initial tangential velocity of body 1 relative to body 2,
each spin positive in the sense that friction from a forward slip drives it (a ball on a
floor: topspin):

    v_t = (v1x - v2x) - R1 w1 - R2 w2        (velocity of the contact point, slip + strain)
    m1 dv1x/dt = -Q,  m2 dv2x/dt = +Q,  I1 dw1/dt = R1 Q,  I2 dw2/dt = R2 Q,

so that dv_t/dt = -Q / m_t with 1/m_t = 1/m1 + 1/m2 + R1^2/I1 + R2^2/I2 (R the arm from
the mass centre to the contact point; a half-space: m2 = inf).  The relative tangential
displacement of distant points (the load path's displacement) has d delta_t/dt = v_t.

Normalisation (Maw, Barber & Fawcett 1976, 1981; Thornton, Cummins & Cleary 2013)
----------------------------------------------------------------------------------
With c = 3 P / (2 k_t delta_n) (k_t the no-slip tangential stiffness, delta_n the
normal approach: c is the same at every load, and (2 - nu) / (2 (1 - nu)) for a sphere
on a half-space of the same material), the whole contact slides once delta_t reaches
mu c delta_n.  With x = delta_n / delta_max, w = (d delta_n/dt) / V_n, tau = t V_n /
delta_max, u = v_t / (mu c V_n), y = delta_t / (mu c delta_max) and f = Q / (mu P_max):

    dw/dtau = -(5/4) x^(3/2),  dy/dtau = u,  du/dtau = -(5/2) chi f,
    chi = (m*/m_t) / (2 c)   (m* = m1 m2 / (m1 + m2); a sphere on a half-space of its own
                              material: chi = (1 - nu)/(2 - nu) (1 + m R^2 / I), Maw's),

and y, f are exactly the load path's scaled displacement and force (f = x^(3/2) when the
whole contact slides).  The outcome psi2 = u after against psi1 = u before depends on chi
alone, for any pair of bodies (ellipses too: c and chi carry the geometry).

Closed forms (derived here)
---------------------------
The whole contact slides forwards while u >= w (the slip rate u - w of the edge: the
sliding displacement is x in these units).  Sliding throughout, f = x^(3/2) and u =
psi1 - 2 chi (1 - w); u >= w for all w in [-1, 1] exactly when

    psi1 >= max(1, 4 chi - 1)      (gross slip throughout; psi2 = psi1 - 4 chi),

that is tan(theta) >= mu c max(1, 4 chi - 1); for a sphere on a half-space of its own
material (chi > 1/2), tan(theta) >= mu [2 (1 + m R^2/I) - (2 - nu) / (2 (1 - nu))].
Coulomb's rigid-body impulse (ratio mu) gives the same rebound while it lasts; its own
limit, v_t after = 0, is tan(theta) = 2 mu (1 + m R^2/I): between the two, the contact
point's velocity reverses (psi2 in [-1, 0)) while the surfaces still slide forwards, as
the tangential strain relaxes.  For chi = 1/2 and psi1 <= 1, u = psi1 w solves the
equations with nothing slipping (every spring at psi1 (x - s^2), within its limit):
psi2 = -psi1 exactly, the tangential velocity reversed.

Integration and its error
-------------------------
The normal motion is Hertz's closed form (:meth:`hertz.Impact.history`; no steps).  The
tangential equations are stepped in time on n steps of equal length over the impact:
the velocity by product integration, int r p dtau with r = f / p linear in the step and
the exact zeroth and first moments of p = x^(3/2) from the normal motion
(int p dtau = (4/5) (w_k - w_k+1), int p (tau - tau_k) dtau = (4/5) (Delta x -
h w_k+1)); the
displacement by the trapezoidal rule; the force at the end of the step from the spring
bed (exact when delta_t is linear in x within a step); one implicit scalar equation per
step, solved by Newton's method in the bed's bracket.  Gross slip throughout is exact
(r = 1: the impulse telescopes to (8/5) exactly).  An impact that starts in gross slip
(1 < psi1 < 4 chi - 1) is taken in closed form up to the instant it stops, w = (psi1 -
2 chi) / (1 - 2 chi), where the steps start (so that no step straddles that kink).
Partial slip converges as the square of the step, and the result is Richardson's
extrapolation from n/2 and n steps, with the estimate |psi2(n) - psi2(n/2)| / 3 reported
as ``error`` (measured in tools/oblique_curves.py --convergence).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ._validate import as_float_array, error_at, first_failure

__all__ = ["ObliqueHistory", "ObliqueImpact", "oblique_impact"]


@dataclass(frozen=True, slots=True)
class ObliqueHistory:
    """The state during an oblique impact at the integration's nodes (made by
    :func:`oblique_impact` with ``history=True``): one-dimensional arrays, one entry per
    node (``steps + 1`` over the partial slip; before it, an initial gross slip in closed
    form on about ``steps`` times its share of the duration).

    Attributes
    ----------
    time : ndarray
        Time from first touch [s].
    approach : ndarray
        Normal approach of distant points [m] (Hertz, closed form).
    normal_force : ndarray
        P [N].
    tangential_force : ndarray
        Q [N] on body 2 along x (on body 1 it is -Q), |Q| <= mu P.
    displacement : ndarray
        Relative tangential displacement of distant points, body 1 relative to body 2
        along x [m].
    tangential_velocity : ndarray
        v_t of the contact point [m/s].
    spin : ndarray
        Spin of body 1 [rad/s] (positive: topspin, see :func:`oblique_impact`).
    sliding : ndarray of bool
        Whether the whole contact slid in the step ending at the node.
    """

    time: np.ndarray
    approach: np.ndarray
    normal_force: np.ndarray
    tangential_force: np.ndarray
    displacement: np.ndarray
    tangential_velocity: np.ndarray
    spin: np.ndarray
    sliding: np.ndarray


@dataclass(frozen=True, slots=True, eq=False)
class ObliqueImpact:
    """An oblique elastic impact with friction (made by :func:`oblique_impact`).

    Floats for scalar input, else arrays of the broadcast shape of ``speed``,
    ``incidence``, ``mu`` and ``spin``.  Velocities are of body 1 relative to body 2,
    x along the initial tangential velocity of the centres.

    Attributes
    ----------
    incidence : float or ndarray
        Angle of the centres' relative velocity from the common normal before [rad].
    tangential_restitution : float or ndarray
        v_t after / v_t before of the contact point [-]: negative where it reverses.
        Where v_t before is 0 (no incidence, no spin) nothing tangential happens and this
        is the limit of small incidences.
    rebound_angle : float or ndarray
        Angle of the contact point's relative velocity from the normal after [rad]
        (Maw's local angle of reflection; negative: backwards).
    centre_rebound_angle : float or ndarray
        Angle of the centres' relative velocity from the normal after [rad].
    spin, spin2 : float or ndarray
        Spin of body 1 and body 2 after [rad/s] (0 change where the inertia or mass is
        infinite).
    tangential_velocity : float or ndarray
        v_t of the contact point after [m/s].
    impulse_ratio : float or ndarray
        Tangential over normal impulse [-]; mu under gross slip.
    gross_slip : bool or ndarray of bool
        Whether the whole contact slides throughout (closed form, psi1 >= max(1,
        4 chi - 1)).
    gross_slip_angle : float or ndarray
        The contact point's incidence above which the whole contact slides throughout,
        atan(mu c max(1, 4 chi - 1)) [rad] (the incidence itself without initial spin).
    normalised_incidence, normalised_rebound : float or ndarray
        Maw's psi1 and psi2: v_t / (mu c V_n) before and after [-].
    chi : float
        Maw's chi = (m*/m_t) / (2 c) [-].
    compliance_ratio : float
        c = 3 P / (2 k_t delta_n) [-]: the tangential displacement at which the contact
        slides, over mu times the normal approach; (2 - nu) / (2 (1 - nu)) for a sphere
        on a half-space of its own material.
    error : float or ndarray
        Estimated error of ``normalised_rebound`` (Richardson) [-]; 0 under gross slip.
    normal : Impact
        The normal impact (:func:`hertz.impact`): duration, largest force and approach.
    history : ObliqueHistory or None
        The time history (``history=True``, one impact only).
    """

    incidence: float | np.ndarray
    tangential_restitution: float | np.ndarray
    rebound_angle: float | np.ndarray
    centre_rebound_angle: float | np.ndarray
    spin: float | np.ndarray
    spin2: float | np.ndarray
    tangential_velocity: float | np.ndarray
    impulse_ratio: float | np.ndarray
    gross_slip: bool | np.ndarray
    gross_slip_angle: float | np.ndarray
    normalised_incidence: float | np.ndarray
    normalised_rebound: float | np.ndarray
    chi: float
    compliance_ratio: float
    error: float | np.ndarray
    normal: object = field(repr=False)
    history: ObliqueHistory | None = field(default=None, repr=False)


# ------------------------------------------------------------------- normalised solver

def _gross_end(psi1, chi):
    """w (normalised normal speed) at which an impact that starts in gross slip stops
    sliding as a whole, u = w with u = psi1 - 2 chi (1 - w); None if it never does (or
    never slides: psi1 < 1)."""
    if chi > 0.5 and 1.0 < psi1 < 4.0 * chi - 1.0:
        return (psi1 - 2.0 * chi) / (1.0 - 2.0 * chi)
    return None


def _states(hit, t):
    """(tau, x, w) at the times t of the normal impact ``hit`` (closed form)."""
    from ._impact import T1

    h = hit.history(t)
    dmax, V = hit.max_approach, hit.speed
    x = np.asarray(h.approach, dtype=float) / dmax
    w = np.asarray(h.speed, dtype=float) / V
    tau = t * (V / dmax)
    x[t <= 0.0] = 0.0
    w[t <= 0.0] = 1.0
    end = tau >= 2.0 * T1
    x[end], w[end] = 0.0, -1.0
    return tau, x, w


def _nodes(hit, steps, w_start=None):
    """(tau, x, w) at steps + 1 equally spaced times over the normal impact ``hit`` (a
    scalar :class:`hertz.Impact`), from its closed-form history: from first touch, or from
    the time at which the normalised normal speed is ``w_start`` (the end of an initial
    gross slip), tau = T1 (1 -+ I(w^2; 1/2, 2/5)) in compression (restitution)."""
    from scipy import special

    from ._impact import T1

    t0 = 0.0
    if w_start is not None:
        tau0 = T1 * (1.0 - math.copysign(special.betainc(0.5, 0.4, w_start * w_start),
                                         w_start))
        t0 = tau0 * hit.max_approach / hit.speed
    t = np.linspace(t0, hit.duration, steps + 1)
    t[-1] = hit.duration
    return _states(hit, t)


def _step_root(bed, prep, a1, c, hb):
    """The increment dy with dy - c + hb f(dy) = 0 (f the bed's force, nondecreasing)."""
    lo, hi = bed._bracket(prep, a1)
    top = a1 * a1 * a1
    up, down = c - hb * top, c + hb * top
    if up >= hi:  # slides forwards as a whole
        return up
    if down <= lo:
        return down
    y = min(max(c, lo), hi)
    low, high = lo, hi
    for _ in range(200):
        f, slope = bed._force(prep, a1, y)
        g = y - c + hb * f
        if abs(g) <= 2e-16 * (abs(y) + abs(c) + hb * abs(f)):
            break
        if g > 0.0:
            high = y
        else:
            low = y
        nxt = y - g / (1.0 + hb * slope)
        if not low < nxt < high:
            nxt = 0.5 * (low + high)
        if nxt == y:
            break
        y = nxt
    return y


def _normalised(psi1, chi, nodes, keep=False):
    """psi2, whether the whole contact slid at every step, and (if ``keep``) the node
    values (u, y, f, sliding) of one integration on ``nodes``.  Nodes that start after
    first touch start in gross slip (the closed form up to there: u = psi1 - 2 chi (1 -
    w), y = (psi1 - 2 chi) tau + 2 chi x, every spring at its limit)."""
    from ._load_path import _SpringBed

    tau, x, w = nodes
    n = tau.size - 1
    bed = _SpringBed()
    u, y, r = float(psi1), 0.0, None
    if tau[0] > 0.0:  # the end of an initial gross slip
        u = psi1 - 2.0 * chi * (1.0 - w[0])
        y = (psi1 - 2.0 * chi) * tau[0] + 2.0 * chi * x[0]
        bed.move(math.sqrt(x[0]), 4.0)  # beyond 2 alpha^2: every spring at its limit
        r = 1.0
    gross = True
    if keep:
        us, ys, fs, sl = [u], [y], [0.0 if r is None else x[0] ** 1.5], [r is not None]
    for k in range(n):
        h = tau[k + 1] - tau[k]
        slope = (x[k + 1] - x[k]) / h
        w0 = 0.8 * (w[k] - slope)  # int p (tau_k+1 - tau) / h, int p (tau - tau_k) / h
        w1 = 0.8 * (slope - w[k + 1])
        if k == n - 1:  # the contact closes: r held over the last step (weight O(h^5/2))
            u_new = u - 2.5 * chi * r * (w0 + w1)
            y += 0.5 * h * (u + u_new)
            u, f, sliding = u_new, 0.0, gross
            bed.move(0.0, 0.0)
        else:
            a1 = math.sqrt(x[k + 1])
            p1 = a1 * a1 * a1
            if r is None:  # first step: r constant (p = 0 at the start)
                a, b = u, 2.5 * chi * (w0 + w1) / p1
            else:
                a, b = u - 2.5 * chi * r * w0, 2.5 * chi * w1 / p1
            prep = bed._prepare(a1)
            dy = _step_root(bed, prep, a1, 0.5 * h * (u + a), 0.5 * h * b)
            f, front = bed.move(a1, dy)
            sliding = front == 0.0 or abs(f) >= p1
            gross = gross and sliding and f > 0.0
            r = f / p1
            u = a - b * f
            y += dy
        if keep:
            us.append(u)
            ys.append(y)
            fs.append(f)
            sl.append(bool(sliding))
    if keep:
        return u, gross, (np.array(us), np.array(ys), np.array(fs), np.array(sl))
    return u, gross, None


def _gross_limit(chi):
    """psi1 above which the whole contact slides throughout: max(1, 4 chi - 1)."""
    return max(1.0, 4.0 * chi - 1.0)


# ------------------------------------------------------------------------------ input

def _array(value, name, ok, allowed):
    arr = as_float_array(value, name)
    with np.errstate(invalid="ignore"):
        good = ok(arr)
    if not np.all(good):
        raise error_at(name, arr, first_failure(good), allowed)
    return arr


def _scalar(value, name, ok, allowed):
    arr = _array(value, name, ok, allowed)
    if arr.ndim != 0:
        raise ValueError(f"{name} must be a single number (one pair of bodies per call), got "
                         f"an array of shape {arr.shape}")
    return float(arr)


def _arm(body, arm, name, which):
    if arm is not None:
        return _scalar(arm, name, lambda a: (a >= 0) & (a < math.inf),
                       "a non-negative, finite distance in m")
    rx, ry = np.asarray(body.Rx), np.asarray(body.Ry)
    if rx.ndim or ry.ndim:
        raise ValueError(f"body{which} must hold single numbers (one pair of bodies per "
                         "call), got arrays")
    if float(rx) == float(ry) and 0.0 < float(rx) < math.inf:
        return float(rx)
    raise ValueError(f"{name} must be given for body{which}, which is not a ball (Rx "
                     f"{float(rx)!r} m, Ry {float(ry)!r} m): the distance from its mass "
                     "centre to the contact point [m]")


def oblique_impact(body1, body2, speed, incidence, mass, mu, *, mass2=math.inf,
                   inertia=None, inertia2=None, arm=None, arm2=None, spin=0.0, angle=0.0,
                   direction=0.0, steps=400, history=False) -> ObliqueImpact:
    """Oblique elastic impact with friction: Hertz normally, Mindlin-Deresiewicz partial
    slip tangentially, coupled to the bodies' translation and rotation.

    Body 1 (mass ``mass``) meets body 2 (``mass2``; a fixed wall or half-space by
    default) at the relative speed ``speed`` of the centres, ``incidence`` from the
    common normal, the tangential motion along a principal axis of the contact ellipse
    (``direction``).  The bodies rotate freely about the axis normal to the plane of
    motion; the normal impact is elastic (restitution 1).  The model, the normalisation
    of Maw, Barber & Fawcett and the closed forms are in the docstring of
    ``hertz._oblique`` and in the explanation page on oblique impacts.

    Parameters
    ----------
    body1, body2 : Body
        The bodies at the contact point (one pair, as :func:`hertz.contact` takes them).
    speed : float or array_like
        Relative speed of the centres before the impact [m/s], positive.
    incidence : float or array_like
        Its angle from the common normal [rad], in [0, pi/2) (``math.radians(deg)``).
    mass : float
        Mass of body 1 [kg], positive and finite.
    mu : float or array_like
        Coefficient of friction [-], positive and finite.
    mass2 : float, optional
        Mass of body 2 [kg], positive; ``inf`` (default): fixed.
    inertia, inertia2 : float, optional
        Moments of inertia about the mass centres, about the axis normal to the plane
        of motion [kg m^2], positive (``inf``: no rotation).  Default: a solid ball,
        (2/5) m R^2 with R the arm.
    arm, arm2 : float, optional
        Distance from each mass centre to the contact point [m] (the normal through the
        contact point passes through the mass centres).  Default: the radius of a ball;
        required for body 1 if it is not a ball, and for body 2 if it moves (finite
        ``mass2``) and is not a ball.
    spin : float or array_like, optional
        Spin of body 1 before the impact [rad/s], positive in the sense friction from a
        forward slip drives it (topspin of a ball on a floor).
    angle : float, optional
        Angle between the bodies' principal planes [rad], as :func:`hertz.contact`.
    direction : {0.0, math.pi / 2}, optional
        The tangential motion along the contact ellipse's major (0) or minor (pi/2)
        axis [rad].
    steps : int, optional
        Time steps over the impact (even, >= 20); the result is extrapolated from
        ``steps / 2`` and ``steps``.  400 gives psi2 to about 1e-6 (``error``).
    history : bool, optional
        Also return the time history (one impact only: scalar speed, incidence, mu,
        spin).

    Returns
    -------
    ObliqueImpact
        Tangential restitution, rebound angles, spins after, impulse ratio, whether the
        contact slid throughout, Maw's normalised angles, the normal impact.

    Raises
    ------
    TypeError
        A body that is not a :class:`hertz.Body`, an argument that is not a number.
    ValueError
        An argument outside its range (the message names it, the value and the index);
        bodies holding arrays; a missing ``arm``; ``history`` for several impacts.

    Examples
    --------
    Chung & Ooi's alumina sphere (R 2.5 mm, E 380 GPa, nu 0.23, 4000 kg/m^3, mu 0.092)
    on an alumina half-space at 3.9 m/s:

    >>> import math
    >>> import hertz
    >>> ball = hertz.Body.sphere(2.5e-3, E=380e9, nu=0.23)
    >>> block = hertz.Body.plane(E=380e9, nu=0.23)
    >>> m = 4000 * 4 / 3 * math.pi * 2.5e-3 ** 3
    >>> hit = hertz.oblique_impact(ball, block, 3.9, math.radians(45.0), m, 0.092)
    >>> bool(hit.gross_slip), round(hit.impulse_ratio, 12)
    (True, 0.092)
    >>> print(f"{math.degrees(hit.gross_slip_angle):.3f} deg")
    28.292 deg
    >>> low = hertz.oblique_impact(ball, block, 3.9, math.radians(15.0), m, 0.092)
    >>> print(f"{low.tangential_restitution:.3f}")  # the contact point's velocity reverses
    -0.426
    """
    from ._contact import Body, HertzValidityWarning, contact
    from ._impact import impact
    from ._load_path import _direction
    from ._tangential import tangential_stiffness

    for name, body in (("body1", body1), ("body2", body2)):
        if not isinstance(body, Body):
            raise TypeError(f"{name} must be a hertz.Body, got {type(body).__name__}")
    finite_pos = (lambda a: (a > 0) & (a < math.inf)), "a positive, finite"
    speed = _array(speed, "speed", finite_pos[0], "a positive, finite speed in m/s")
    incidence = _array(incidence, "incidence", lambda a: (a >= 0) & (a < math.pi / 2),
                       "an angle in rad in [0, pi/2) from the common normal (pi/2 grazes: "
                       "no impact)")
    mu = _array(mu, "mu", finite_pos[0], "a positive, finite coefficient of friction")
    spin0 = _array(spin, "spin", np.isfinite, "a finite spin in rad/s")
    m1 = _scalar(mass, "mass", finite_pos[0], "a positive, finite mass in kg")
    m2 = _scalar(mass2, "mass2", lambda a: a > 0, "a positive mass in kg (inf: fixed)")
    if not (isinstance(steps, (int, np.integer)) and not isinstance(steps, bool)
            and steps >= 20 and steps % 2 == 0):
        raise ValueError(f"steps must be an even integer >= 20, got {steps!r}")
    direction = _direction(direction)
    r1 = _arm(body1, arm, "arm", 1)
    moving2 = m2 < math.inf
    r2 = _arm(body2, arm2, "arm2", 2) if moving2 or arm2 is not None else 0.0
    ok_inertia = (lambda a: a > 0), "a positive moment of inertia in kg m^2 (inf: no spin)"
    i1 = 0.4 * m1 * r1 * r1 if inertia is None else _scalar(inertia, "inertia", *ok_inertia)
    if inertia2 is not None:
        i2 = _scalar(inertia2, "inertia2", *ok_inertia)
    else:
        i2 = 0.4 * m2 * r2 * r2 if moving2 else math.inf

    def turning(r, i):  # R^2 / I, the rotation's share of 1 / m_t (none at R = 0, I = inf)
        return r * r / i if r > 0.0 and i < math.inf else 0.0

    # masses: reduced m*, tangential m_t
    m_red = m1 if not moving2 else m1 * m2 / (m1 + m2)
    inv_mt = 1.0 / m_red + turning(r1, i1) + turning(r2, i2)
    m_t = 1.0 / inv_mt

    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", HertzValidityWarning)
        ref = contact(body1, body2, load=1.0, angle=angle)
    if np.ndim(ref.delta) != 0:
        raise ValueError("body1 and body2 must hold single numbers (one pair of bodies per "
                         "call; broadcast speed, incidence, mu or spin instead)")
    kt = float(tangential_stiffness(ref, direction))
    c = 1.5 / (kt * float(ref.delta))  # 3 P / (2 k_t delta_n) at P = 1 N
    chi = (m_red / m_t) / (2.0 * c)

    speed, incidence, mu, spin0 = np.broadcast_arrays(speed, incidence, mu, spin0)
    shape = speed.shape
    if history and shape != ():
        raise ValueError(f"history=True takes one impact (scalar speed, incidence, mu and "
                         f"spin), got the shape {shape}")
    vn = speed * np.cos(incidence)
    vx = speed * np.sin(incidence)
    normal = impact(body1, body2, speed=vn, mass=m_red, angle=angle)
    vt0 = vx - r1 * spin0
    sign = np.where(vt0 < 0.0, -1.0, 1.0)
    psi1 = np.abs(vt0) / (mu * c * vn)

    one = normal if shape == () else impact(body1, body2, speed=float(vn.flat[0]),
                                            mass=m_red, angle=angle)
    plain = _nodes(one, steps)
    limit = _gross_limit(chi)
    psi2 = np.empty(shape)
    err = np.empty(shape)
    ratio0 = None  # the small-incidence limit of psi2 / psi1, where psi1 = 0
    kept = None
    flat1, flat2, flate = psi1.reshape(-1), psi2.reshape(-1), err.reshape(-1)
    cache = {}
    for i, p in enumerate(flat1):
        p = float(p)
        if p not in cache:
            if p == 0.0 and ratio0 is None:
                tiny = 1e-9
                a2 = _normalised(tiny, chi, plain)[0]
                b2 = _normalised(tiny, chi, tuple(a[::2] for a in plain))[0]
                ratio0 = (4.0 * a2 - b2) / 3.0 / tiny
            if p == 0.0:
                cache[p] = (0.0, 0.0)
            else:
                end = _gross_end(p, chi)
                fine = plain if end is None else _nodes(one, steps, end)
                a2, _, kept = _normalised(p, chi, fine, keep=history)
                b2 = _normalised(p, chi, tuple(a[::2] for a in fine))[0]
                if history:
                    kept = _with_start(one, kept, fine, p, chi, steps)
                cache[p] = ((4.0 * a2 - b2) / 3.0, abs(a2 - b2) / 3.0)
        flat2[i], flate[i] = cache[p]

    vtf = sign * psi2 * mu * c * vn
    with np.errstate(invalid="ignore", divide="ignore"):
        et = np.where(psi1 > 0.0, psi2 / np.where(psi1 > 0.0, psi1, 1.0),
                      ratio0 if ratio0 is not None else 0.0)
    impulse_t = m_t * (vt0 - vtf)  # on body 2 along x (on body 1: -)
    spin1 = spin0 + turning(r1, i1) / r1 * impulse_t if r1 > 0.0 else spin0 + 0.0 * vtf
    spin2 = (turning(r2, i2) / r2 if r2 > 0.0 else 0.0) * impulse_t
    vxf = vx - impulse_t / m_red
    impulse_n = 2.0 * m_red * vn
    hist = None
    if history:
        hist = _history(normal, kept, mu=float(mu), c=c, vn=float(vn), sign=float(sign),
                        m_t=m_t, lever=turning(r1, i1) / r1 if r1 > 0.0 else 0.0,
                        spin0=float(spin0))

    def out(a):
        a = np.asarray(a)
        if a.ndim == 0:
            return a.item()
        a = a.copy()
        a.flags.writeable = False
        return a

    return ObliqueImpact(
        incidence=out(incidence), normal=normal, tangential_restitution=out(et),
        rebound_angle=out(np.arctan2(vtf, vn)), centre_rebound_angle=out(np.arctan2(vxf, vn)),
        spin=out(spin1), spin2=out(spin2), tangential_velocity=out(vtf),
        impulse_ratio=out(impulse_t / impulse_n), gross_slip=out(psi1 >= limit),
        gross_slip_angle=out(np.arctan(mu * c * limit) * np.ones(shape)),
        normalised_incidence=out(psi1), normalised_rebound=out(psi2), chi=chi,
        compliance_ratio=c, error=out(err), history=hist)


def _with_start(hit, kept, nodes, psi1, chi, steps):
    """The node values (tau, x, u, y, f, sliding) of an integration, with the initial
    gross slip before its first node in closed form (on about ``steps`` times its share
    of the duration)."""
    tau, x, w = nodes
    u, y, f, sliding = kept
    if tau[0] > 0.0:
        count = max(2, int(math.ceil(steps * tau[0] / tau[-1])))  # the share of the impact
        t = np.linspace(0.0, tau[0] * hit.max_approach / hit.speed, count + 1)[:-1]
        t0, x0, w0 = _states(hit, t)
        p0 = x0 ** 1.5
        tau, x = np.concatenate([t0, tau]), np.concatenate([x0, x])
        u = np.concatenate([psi1 - 2.0 * chi * (1.0 - w0), u])
        y = np.concatenate([(psi1 - 2.0 * chi) * t0 + 2.0 * chi * x0, y])
        f = np.concatenate([p0, f])
        sliding = np.concatenate([t0 > 0.0, sliding])
    return tau, x, u, y, f, sliding


def _history(normal, kept, *, mu, c, vn, sign, m_t, lever, spin0):
    dmax, pmax = normal.max_approach, normal.max_force
    if kept is None:  # psi1 = 0: nothing tangential happens
        tau, x, _ = _nodes(normal, 20)
        n = tau.size
        kept = (tau, x, np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n, dtype=bool))
    tau, x, u, y, f, sliding = kept
    scale = mu * c * vn  # v_t per unit of psi
    vt = sign * u * scale
    impulse = m_t * scale * sign * (u[0] - u)  # tangential impulse so far, on body 2
    spin = spin0 + lever * impulse  # lever = R1 / I1
    time = tau * dmax / vn
    if abs(time[-1] - normal.duration) <= 1e-12 * normal.duration:
        time[-1] = normal.duration  # the end of the contact to the last bit (tau's rounding)
    arrays = [time, x * dmax, pmax * x ** 1.5, sign * mu * pmax * f,
              sign * y * mu * c * dmax, vt, spin, sliding]
    for a in arrays:
        a.flags.writeable = False
    return ObliqueHistory(*arrays)
