"""Independent references for hertz.load_path (Mindlin-Deresiewicz along (P, Q) paths); does
not import hertz.

Two kinds:

1. mpmath at 50 digits, the closed forms of Mindlin & Deresiewicz (1953) written in terms of
   Cattaneo distributions (tractions t0 sqrt(1 - r^2/c^2) on ellipses similar to the contact
   ellipse, each displacing its own ellipse rigidly).  The contact ellipse comes from
   tests/reference.py (Harris's relation solved in mpmath); the no-slip compliance along a
   principal axis from its closed form in K(m), E(m), c_x = sum (K - nu (E - (1-m) K)/m) /
   (2 pi G a), c_y = sum (K - nu (K - E)/m) / (2 pi G a), m = 1 - b^2/a^2 (checked against a
   quadrature of Cerruti's solution in tests/test_tangential.py).  A Cattaneo distribution
   of size c and peak t0 along x has force (2 pi/3) t0 c^2 b/a and displaces its ellipse by
   t0 c pi (b/a) / (k/a), k = 1/c_x the no-slip stiffness of the contact of size a (k ~ a):
   the sliding traction (c = a, t0 = mu p0) then gives 3 mu P / (2 k).
   ``superposition_force`` integrates a superposition of such distributions over the
   ellipse by mpmath.quad, for the force balance of the closed forms.

2. A brute-force spring bed on a uniform grid of sizes (numpy, no piecewise algebra): the
   same one-dimensional memory as hertz/_load_path.py, sampled at N + 1 nodes and
   integrated by the trapezoid rule, for the convergence in the size parameter.
"""

import mpmath as mp
import numpy as np
from reference import contact_ref

DPS = 50


# ----------------------------------------------------------------------- mpmath closed forms
def geometry(body1, body2, load):
    """(a, b, p0) [m, m, Pa] of the Hertz contact; bodies as (Rx, Ry, E, nu)."""
    c = contact_ref(body1, body2, load)
    return c.a, c.b, c.p0


def compliance(a, b, bodies, axis):
    """No-slip compliance [m/N] along ``axis`` ('x' major, 'y' minor); bodies as (G, nu)."""
    with mp.workdps(DPS + 20):
        a, b = mp.mpf(a), mp.mpf(b)
        m = 1 - (b / a) ** 2
        K, E = mp.ellipk(m), mp.ellipe(m)
        if m == 0:
            B = D = mp.pi / 4
        else:
            B, D = (E - (1 - m) * K) / m, (K - E) / m
        part = B if axis == "x" else D
        return sum((K - mp.mpf(nu) * part) / (2 * mp.pi * mp.mpf(G) * a) for G, nu in bodies)


class Scene:
    """A contact family (fixed bodies, any load) in mpmath."""

    def __init__(self, body1, body2, mu, axis):
        self.body1, self.body2, self.axis = body1, body2, axis
        self.mu = mp.mpf(mu)
        self.bodies = [(mp.mpf(E) / (2 * (1 + mp.mpf(nu))), mp.mpf(nu))
                       for E, nu in ((body1[2], body1[3]), (body2[2], body2[3]))]

    def contact(self, load):
        return geometry(self.body1, self.body2, load)

    def stiffness(self, load):
        a, b, _ = self.contact(load)
        return 1 / compliance(a, b, self.bodies, self.axis)

    def cattaneo(self, load, force):
        """(delta, stick_a): Cattaneo-Mindlin at (P, Q), Q rising from 0 at constant P."""
        with mp.workdps(DPS + 20):
            P, shear = mp.mpf(load), mp.mpf(force)
            a = self.contact(load)[0]
            s = mp.cbrt(1 - shear / (self.mu * P))
            return 3 * self.mu * P / (2 * self.stiffness(load)) * (1 - s * s), a * s

    def proportional(self, load, force):
        """Q/P fixed from zero: 3 Q / (2 k(P)), nothing slips."""
        with mp.workdps(DPS + 20):
            return 3 * mp.mpf(force) / (2 * self.stiffness(load))

    def normal_up_then_tangential(self, p0, q0, p1, dq):
        """(delta, stick_a): Q0 at P0, P raised to P1 at fixed Q0, then Q raised by dQ."""
        with mp.workdps(DPS + 20):
            p0, q0, p1, dq = (mp.mpf(v) for v in (p0, q0, p1, dq))
            if dq <= self.mu * (p1 - p0):  # the slip annulus stays in the new ring
                d0 = self.cattaneo(p0, q0)[0]
                d1, stick = self.cattaneo(p1, dq)
                return d0 + d1, stick
            return self.cattaneo(p1, q0 + dq)  # the virgin state at P1

    def normal_down(self, p0, q, p1):
        """(delta, stick_a): Q at P0, then P lowered to P1 at fixed Q: Cattaneo at (P1, Q)."""
        return self.cattaneo(p1, q)

    def superposition_force(self, load, parts):
        """Tangential force [N] of the traction sum_j w_j mu p0 (c_j/a) sqrt(1 - r^2/c_j^2)
        (sizes c_j as fractions of a, signed weights w_j) at normal force ``load``, by
        mpmath.quad over the ellipse (area element 2 pi (b/a) rho d rho)."""
        with mp.workdps(DPS + 20):
            a, b, p0 = self.contact(load)
            pts = sorted({mp.mpf(0), mp.mpf(1)} | {mp.mpf(c) for c, _ in parts})

            def traction(r):  # r = rho / a
                return sum(w * self.mu * p0 * c * mp.sqrt(1 - (r / c) ** 2)
                           for c, w in parts if r < c)
            return mp.quad(lambda r: traction(r) * 2 * mp.pi * (b / a) * r * a * a, pts)


# ----------------------------------------------------------------------- grid spring bed
def grid_path(alpha, target, nodes):
    """The scaled spring bed on a uniform grid: alpha_k = (P_k/P_ref)^(1/3) and targets
    Q_k/(mu P_ref); returns the scaled displacements (units of 3 mu P_ref / (2 k_ref)).
    Nodes x_i = i h on [0, max alpha]; a spring is in contact when x_i < alpha; force
    (3/2) x trapezoid sum of u over the contact (the last panel cut at alpha with u
    interpolated linearly to 0 at the edge); in a step the displacement changes in
    proportion to a^2 (as in hertz/_load_path.py) and each spring ends at
    clip(u + d, -L, L) (entering ones at clip(d (a1^2 - x^2)/(a1^2 - a0^2), -L, L))."""
    from scipy.optimize import brentq

    x = np.linspace(0.0, max(alpha), nodes + 1)
    u = np.zeros_like(x)
    a_old = 0.0
    delta, out = 0.0, []
    for a1, q1 in zip(alpha, target, strict=True):
        inside = x < a1
        entering = inside & (x >= a_old)
        old = inside & ~entering
        limit = np.where(inside, a1 * a1 - x * x, 0.0)
        d2 = a1 * a1 - a_old * a_old

        def state(d, old=old, entering=entering, limit=limit, d2=d2, a1=a1, u=u):
            trial = np.where(old, u + d, 0.0)
            if d2 > 0:
                trial = np.where(entering, d * (a1 * a1 - x * x) / d2, trial)
            return np.clip(trial, -limit, limit)

        def force(d, state=state, a1=a1, inside=inside):
            v = state(d)
            xi, vi = x[inside], v[inside]
            xs = np.append(xi, a1)
            vs = np.append(vi, 0.0)
            return 1.5 * np.sum(0.5 * (vs[1:] + vs[:-1]) * np.diff(xs))

        span = 4.0 * (a1 * a1 + np.abs(u).max() + 1.0)
        lo, hi = -span, span
        f_lo, f_hi = force(lo), force(hi)
        if not f_lo < q1 < f_hi:
            raise ValueError("the grid bed takes paths that do not slide as a whole")
        d = brentq(lambda t, q1=q1: force(t) - q1, lo, hi, xtol=1e-300, rtol=8.9e-16)
        u = np.where(inside, state(d), 0.0)
        a_old = a1
        delta += d
        out.append(delta)
    return np.array(out)


def scaled(loads, forces, mu):
    """(alpha, target) of a path, as the grid bed takes them."""
    loads = np.asarray(loads, dtype=float)
    p_ref = loads.max()
    return np.cbrt(loads / p_ref), np.asarray(forces, dtype=float) / (mu * p_ref)


__all__ = ["DPS", "Scene", "compliance", "geometry", "grid_path", "scaled"]


def superposition_displacement(scene, load, parts, x0, y0, dps=20):
    """Relative displacement [m] along the axis at (x0, y0) under the traction of
    ``Scene.superposition_force``, by the quadrature of Cerruti's solution of
    tests/reference_tangential.py (at ``dps`` digits): an independent check that the
    stick zone moves rigidly and by the closed form's amount."""
    import reference_tangential as rt

    saved = rt.DPS
    rt.DPS = dps
    try:
        with mp.workdps(dps + 5):
            a, b, p0 = scene.contact(load)
            total = mp.mpf(0)
            for c, w in parts:
                ca, cb = a * mp.mpf(c), b * mp.mpf(c)
                unit = rt.displacement_hertz_traction(ca, cb, scene.bodies, x0, y0,
                                                      scene.axis)[0]
                total += w * scene.mu * p0 * mp.mpf(c) * unit
            return total
    finally:
        rt.DPS = saved
