"""Grade a DEM code's impact of two bodies against the exact Hertz impact.

What is measured from the trajectory (:class:`~fem_validation.results.impact.ImpactTrajectory`)
and what it is compared with (:class:`ImpactReference`, from :func:`impact_reference`):

* **max overlap** and **max force**: the largest sampled values.  A sampled maximum lies
  below the true one by at most ``|f''| dt^2 / 8`` (the peak falls at most half a step
  from a sample); at Hertz's peak the overlap's curvature is the deceleration
  ``F_max / M`` and the force's is ``1.5 F_max / delta_max`` times it, so the sampling
  bounds are ``b_delta = F_max dt^2 / (8 M delta_max)`` and ``b_F = 1.5 b_delta``
  (relative).
* **duration**: the contact is where the force is positive (with ``attractive``, a
  damping that may pull: where the overlap is positive or the force nonzero, so that it
  lasts until the overlap returns to 0); its start and end are placed within the step
  where the force turns on (off), where the overlap crosses 0 (interpolated between the
  rows around the crossing where the record writes the gap, else extrapolated from the
  two rows in contact next to it: the overlap is linear in time there, the force being
  small), or, where the force turns off before the overlap does (a damped force cut off
  at 0, not ``attractive``), where the force extrapolates to 0; without an overlap that
  says, where ``F^(2/3)`` (linear in time at the ends of a Hertz contact) extrapolates to
  0.  The error is at most ``dt`` and, for Hertz, far smaller.
* **restitution**: ``-v_out / v_in`` of the normal velocity just before and just after
  the contact (after: from the first row of free flight, no force on it and the next; a
  force that pulls after a contact measured as not ``attractive`` is noted): from the
  ``v_n`` column where the file has one (exact: free flight); else
  from the overlap's slope over the two rows before the contact (after it) where the file
  writes the gap there (exact: free flight), else over the first (last) two rows in
  contact, whose error is bounded by the force there, ``|dv| <= F dt_2 / M`` over the two
  steps ``dt_2`` (stated in the grade).  The approach speed found is checked against
  ``--speed`` too.
* **F(delta)**: RMS over the rows in contact of ``F - F_Hertz(delta)``, over ``F_max``
  (elastic only: pointwise, no sampling error).
* **F(t)**: RMS over the rows in and next to the contact of ``F(t) - F_ref(t - t0)``, over
  ``F_max``, the start ``t0`` fitted within a step of the one found; the allowance adds
  what a duration error at its tolerance makes of the curve.
* **oblique** (with ``tangential_force``, ``v_t``, ``omega``; body 1 a sphere of radius
  R on a fixed plane): the contact point's tangential restitution ``(v_t - R omega)``
  after over before, its rebound angle ``atan((v_t - R omega) / v_n)`` after the impact
  [deg] and the spin after it, from the rows next to the contact (free flight: exact),
  against ``hertz.oblique_impact`` (Maw, Barber & Fawcett's Mindlin-Deresiewicz
  impact).

Each tolerance is :data:`FLOOR` (the DEM integrator's own error, which the output
sampling does not show) plus the sampling bound of the metric; ``tolerances`` replaces
any of them.  A linear spring tuned to the same peak force has an overlap 0.8 times
Hertz's and a duration 0.85 times: it fails.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..results.contact import ResultError
from ..results.impact import ImpactTrajectory
from .contact import Check, GradeMethods, nan_to_none

__all__ = ["CURVE_FLOOR", "FLOOR", "LAMMPS_LAWS", "METRICS", "ImpactGrade",
           "ImpactReference", "grade_impact", "hertz_closed_form", "hertz_law",
           "impact_reference", "measure"]

#: The part of every tolerance that the output sampling does not explain: a DEM
#: integrator's own error at its time step (velocity Verlet at t_c / 50 errs by about
#: 2e-4 on the peak), relative (restitution: absolute).
FLOOR = 1e-3
#: The same for the RMS of the F(delta) and F(t) curves, over F_max.
CURVE_FLOOR = 2e-3
#: The fewest rows in contact a trajectory must hold to be graded.
MIN_CONTACT_ROWS = 5


#: ``--damping`` names for LAMMPS's ``pair_style granular`` keywords whose VALUE is not the
#: coefficient of a :mod:`hertz` law as such: name -> (LAMMPS's keyword and version, the
#: hertz law it is graded against, how VALUE becomes that law's coefficient).  LAMMPS's
#: ``damping tsuji E`` is F_damp = alpha sqrt(m_eff F_n / delta) delta' = alpha sqrt(m_eff K)
#: delta^(1/4) delta' (F_n = K delta^1.5 the elastic force); alpha = poly(E) in the
#: releases up to the 22 Jul 2025 stable one, sqrt(2) poly(E) in the development sources
#: since mid-2026 (``damp *= MY_SQRT2``, "effective mass convention").
LAMMPS_LAWS = {
    "lammps_tsuji": ("damping tsuji E, LAMMPS up to 22 Jul 2025 (stable): alpha = poly(E)",
                     "lammps_tsuji", "E"),
    "lammps_tsuji_sqrt2": ("damping tsuji E, LAMMPS development since mid-2026: alpha = "
                           "sqrt(2) poly(E)", "lammps_tsuji_sqrt2", "E"),
}

#: metric -> (short name, what it measures)
METRICS = {
    "max_overlap_rel_err": ("max overlap", "largest sampled overlap against Hertz's "
                                           "delta_max (relative)"),
    "max_force_rel_err": ("max force", "largest sampled normal force against Hertz's F_max "
                                       "(relative)"),
    "duration_rel_err": ("duration", "contact duration (start and end from the force "
                                     "record) against Hertz's t_c (relative)"),
    "restitution_err": ("restitution", "-v_out / v_in minus the reference's restitution "
                                       "(absolute)"),
    "impact_speed_rel_err": ("impact speed", "the record's approach speed against --speed "
                                             "(relative)"),
    "force_overlap_rms": ("F(delta) RMS", "RMS of F - F_Hertz(delta) over the rows in "
                                          "contact, over F_max"),
    "force_time_rms": ("F(t) RMS", "RMS of F(t) - F_ref(t - t0) over the rows in and next "
                                   "to the contact, over F_max"),
    "tangential_restitution_err": ("tangential e", "the contact point's v_t - R omega "
                                                   "after over before, minus the "
                                                   "reference's (absolute)"),
    "rebound_angle_err_deg": ("rebound angle [deg]", "rebound angle of the contact point "
                                                     "minus the reference's [deg]"),
    "spin_rel_err": ("spin", "body 1's spin after the impact against the reference's, "
                             "over the contact point's speed before / R"),
}


@dataclass(frozen=True)
class ImpactReference:
    """The exact impact a trajectory is graded against.

    Attributes
    ----------
    max_approach : float
        Largest overlap delta_max [m] (NaN where the reference has none).
    max_force : float
        Largest normal force F_max [N] (NaN where none).
    duration : float
        Contact duration t_c [s] (NaN where none).
    restitution : float
        Normal coefficient of restitution (1 for an elastic impact).
    source : str
        Where the numbers come from (``"hertz.impact"``, ``"closed form"``, ...).
    force_of_time : callable or None
        tau [s] since the contact's start (array) -> the normal force [N], 0 outside
        [0, duration]; None where the reference has no history.
    force_of_overlap : callable or None
        delta [m] (array) -> the elastic force F(delta) [N]; None for a damped contact.
    stiffness : float
        K of the elastic force K delta^1.5 [N/m^1.5] (the overlap's curvature at its
        peak, K delta_max^1.5 / M, where the reference has no F_max).
    oblique : dict or None
        ``tangential_restitution``, ``rebound_angle_deg`` (the contact point's) and
        ``spin`` [rad/s] after the impact, and ``v_t_before`` [m/s], where the reference
        has them.
    attractive : bool
        The reference's force may pull (a damping not cut off at 0): its contact ends
        when the overlap returns to 0, and :func:`grade_impact` measures the record's so
        (False: it ends where the force reaches 0).
    """

    max_approach: float
    max_force: float
    duration: float
    restitution: float
    source: str
    force_of_time: Callable | None = None
    force_of_overlap: Callable | None = None
    oblique: dict | None = None
    stiffness: float = math.nan
    attractive: bool = False

    def replace(self, **changes) -> ImpactReference:
        """A copy with ``changes``."""
        return dataclasses.replace(self, **changes)


def _stiffness(scene) -> float:
    """K of F = K delta^1.5 for the scene's bodies [N/m^1.5], from hertz.contact."""
    import hertz

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hertz.HertzValidityWarning)
        c = hertz.contact(scene.body1, scene.body2, load=1.0, angle=scene.angle)
    return 1.0 / float(c.delta) ** 1.5


def hertz_closed_form(stiffness: float, mass: float, speed: float) -> ImpactReference:
    """The elastic Hertz impact of F = K delta^1.5 in closed form.

    Parameters
    ----------
    stiffness : float
        K [N/m^1.5] (for two spheres ``(4/3) E* sqrt(R*)``).
    mass : float
        Reduced mass M [kg].
    speed : float
        Normal approach speed V [m/s].

    Returns
    -------
    ImpactReference
        ``delta_max = (5 M V^2 / (4 K))^(2/5)``, ``F_max = K delta_max^1.5``,
        ``t_c = 2 (delta_max / V) Gamma(7/5) Gamma(1/2) / Gamma(9/10)``, restitution 1;
        the history delta(tau) by the inverse incomplete beta function (the energy
        equation integrated exactly: ``tau = (t_c / 2) I_s(2/5, 1/2)``,
        ``delta = delta_max s^(2/5)``).

    Examples
    --------
    >>> r = hertz_closed_form(2.357022603955158e9, 0.005864306286700947, 20.0)
    >>> print(f"{r.max_approach * 1e6:.2f} um, {r.max_force / 1e3:.3f} kN, "
    ...       f"{r.duration * 1e6:.2f} us")
    274.11 um, 10.697 kN, 40.34 us
    """
    for name, value in (("stiffness", stiffness), ("mass", mass), ("speed", speed)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    k, m, v = float(stiffness), float(mass), float(speed)
    dmax = (5.0 * m * v * v / (4.0 * k)) ** 0.4
    fmax = k * dmax ** 1.5
    tc = 2.0 * dmax / v * math.gamma(1.4) * math.gamma(0.5) / math.gamma(0.9)

    def force_of_time(tau):
        from scipy.special import betaincinv

        tau = np.asarray(tau, dtype=float)
        u = np.clip(np.minimum(tau, tc - tau) / (0.5 * tc), 0.0, 1.0)
        s = betaincinv(0.4, 0.5, u)
        f = fmax * s ** 0.6
        return np.where((tau > 0) & (tau < tc), f, 0.0)

    def force_of_overlap(delta):
        d = np.clip(np.asarray(delta, dtype=float), 0.0, None)
        return k * d ** 1.5

    return ImpactReference(dmax, fmax, tc, 1.0, "closed form (hertz.contact's K)",
                           force_of_time, force_of_overlap, stiffness=k)


def _damping(damping):
    if damping is None:
        return None
    if isinstance(damping, str):
        law, sep, value = damping.partition(":")
        try:
            coefficient = float(value)
        except ValueError:
            coefficient = math.nan
        if not sep or not law.strip() or not math.isfinite(coefficient):
            raise ValueError(f"damping must be LAW:VALUE (a law's name and a finite number), "
                             f"got {damping!r}")
        return law.strip(), coefficient
    law, coefficient = damping
    return str(law), float(coefficient)


def hertz_law(law: str, value: float) -> tuple[str, float, str]:
    """The :mod:`hertz` damping law and coefficient a ``--damping LAW:VALUE`` is graded
    against.

    Parameters
    ----------
    law : str
        A law of ``hertz.DAMPING_LAWS`` (its coefficient as such), or one of
        :data:`LAMMPS_LAWS` (LAMMPS's ``damping tsuji`` restitution, by release).
    value : float
        The law's coefficient, or for a :data:`LAMMPS_LAWS` name the restitution E given
        to LAMMPS, in (0, 1].

    Returns
    -------
    (str, float, str)
        The hertz law, its coefficient and a description for the report.

    Raises
    ------
    ValueError
        A LAMMPS restitution outside (0, 1]; a law neither hertz nor LAMMPS_LAWS knows
        (naming those that are known).

    Examples
    --------
    LAMMPS's ``damping tsuji 0.8`` (22 Jul 2025) is hertz's ``lammps_tsuji`` with e = 0.8
    (Tsuji's law with alpha = poly(0.8)):

    >>> hertz_law("lammps_tsuji", 0.8)[:2]
    ('lammps_tsuji', 0.8)
    >>> hertz_law("viscoelastic", 3e4)[:2]
    ('viscoelastic', 30000.0)
    """
    if law not in LAMMPS_LAWS:
        import hertz

        known = getattr(hertz, "DAMPING_LAWS", None)
        if known is not None and law not in known:
            raise ValueError(f"damping: unknown law {law!r}; known: "
                             f"{', '.join(sorted({*known, *LAMMPS_LAWS}))}")
        return law, float(value), f"{law!r}, {value:g}"
    what, target, _ = LAMMPS_LAWS[law]
    if not (math.isfinite(value) and 0 < value <= 1):
        raise ValueError(f"damping: {law}'s VALUE is the restitution given to LAMMPS "
                         f"(damping tsuji E), in (0, 1], got {value!r}")
    return target, float(value), f"{target!r}, {value:g} ({law}: {what})"


def impact_reference(scene, mass: float, speed: float, *, damping=None, mu=None,
                     angle_deg: float = 0.0, cutoff: bool = True) -> ImpactReference:
    """The exact impact of the scene's bodies, from :mod:`hertz`.

    Parameters
    ----------
    scene : Scene
        The two bodies (``body1``, ``body2``, ``angle``).
    mass : float
        Reduced mass [kg].
    speed : float
        Normal approach speed [m/s].
    damping : str or (str, float), optional
        ``"LAW:VALUE"``: a damped contact, graded against ``hertz.damped_impact`` of that
        law and coefficient (:func:`hertz_law`: a law of ``hertz.DAMPING_LAWS``, or a
        LAMMPS ``damping tsuji`` restitution of :data:`LAMMPS_LAWS`); None: elastic.
    mu : float, optional
        Friction coefficient of an oblique impact.
    angle_deg : float
        Incidence of an oblique impact from the normal [deg] (0: head-on).
    cutoff : bool
        With ``damping``: True, the total force is cut off at 0 (LAMMPS's
        ``limit_damping``, most DEM codes) and the contact ends where it reaches 0;
        False, the damping may pull (LAMMPS's default) and the contact ends when the
        overlap returns to 0 (the reference's ``attractive``).

    Returns
    -------
    ImpactReference
        Elastic: ``hertz.impact`` where this hertz has it, else :func:`hertz_closed_form`
        with the stiffness of ``hertz.contact``.

    Raises
    ------
    ValueError
        A mass or speed that is not a finite number > 0; a damping this hertz cannot
        evaluate (naming the law).
    """
    import hertz

    for name, value in (("mass", mass), ("speed", speed)):
        if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    law = _damping(damping)
    elastic = _elastic(scene, mass, speed)
    radii = [abs(float(r)) for b in (scene.body1, scene.body2) for r in (b.Rx, b.Ry)
             if math.isfinite(float(r)) and float(r) != 0.0]
    if not (math.isfinite(elastic.max_approach) and elastic.max_approach > 0.0
            and elastic.max_approach < min(radii, default=math.inf)):
        raise ValueError(f"mass {mass!r} kg and speed {speed!r} m/s give Hertz's largest "
                         f"overlap {elastic.max_approach:.4g} m, not a small positive "
                         f"fraction of the bodies' radius {min(radii, default=math.inf):g} m:"
                         f" not a Hertz impact (check the units: kg, m/s)")
    if law is not None:
        ref = _damped(scene, mass, speed, law, cutoff, elastic)
    else:
        ref = elastic
    if mu is not None or angle_deg:
        ref = _with_oblique(ref, scene, mass, speed, mu, angle_deg, hertz)
    return ref


def _elastic(scene, mass, speed) -> ImpactReference:
    import hertz

    closed = hertz_closed_form(_stiffness(scene), mass, speed)
    impact = getattr(hertz, "impact", None)
    if impact is None:
        return closed
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hertz.HertzValidityWarning)
        imp = impact(scene.body1, scene.body2, speed=speed, mass=mass, angle=scene.angle)
    force_of_time = closed.force_of_time
    history = getattr(imp, "history", None)
    if history is not None:
        def force_of_time(tau, _h=history, _tc=float(imp.duration)):
            tau = np.asarray(tau, dtype=float)
            inside = (tau > 0) & (tau < _tc)
            out = np.zeros_like(tau)
            if inside.any():
                h = _h(tau[inside])
                out[inside] = np.asarray(h[1] if isinstance(h, tuple) else h.force, dtype=float)
            return out
    return ImpactReference(float(imp.max_approach), float(imp.max_force), float(imp.duration),
                           float(getattr(imp, "restitution", 1.0)), "hertz.impact",
                           force_of_time, closed.force_of_overlap, stiffness=closed.stiffness)


def _damped(scene, mass, speed, law, cutoff, elastic) -> ImpactReference:
    """hertz.damped_impact (restitution, duration, delta_max) where this hertz has it, else
    hertz.restitution (the restitution alone)."""
    import hertz

    name, coefficient, described = hertz_law(*law)
    damped = getattr(hertz, "damped_impact", None)
    restitution = getattr(hertz, "restitution", None)
    if damped is None and restitution is None:
        raise ValueError("damping: this hertz has no damped impact (hertz.damped_impact, "
                         "hertz.restitution); grade the elastic impact (no --damping) or "
                         "update hertz")
    args = (scene.body1, scene.body2, speed, mass, name, coefficient)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hertz.HertzValidityWarning)
        r = (damped(*args, cutoff=cutoff, angle=scene.angle) if damped is not None
             else restitution(*args, cutoff=cutoff, angle=scene.angle))
    nan = math.nan
    e = float(getattr(r, "restitution", r))
    if not math.isfinite(float(getattr(r, "duration", 0.0))):
        raise ValueError(f"damping: {described} never lets the bodies part (restitution "
                         f"{e:g}, no end of contact): no impact to grade; check the "
                         f"coefficient {coefficient!r}")
    what = "hertz.damped_impact" if damped is not None else "hertz.restitution"
    return ImpactReference(float(getattr(r, "max_approach", nan)),
                           float(getattr(r, "max_force", nan)),
                           float(getattr(r, "duration", nan)), e,
                           f"{what}({described}, cutoff={cutoff})",
                           stiffness=elastic.stiffness, attractive=not cutoff)


def _oblique_function(hertz):
    """hertz.oblique_impact, or the module that will export it (hertz._oblique), or None."""
    found = getattr(hertz, "oblique_impact", None)
    if found is None:
        try:
            from hertz._oblique import oblique_impact as found
        except ImportError:
            found = None
    return found


def _with_oblique(ref, scene, mass, speed, mu, angle_deg, hertz) -> ImpactReference:
    oblique = _oblique_function(hertz)
    if oblique is None or mu is None:
        return ref.replace(oblique={})
    b2 = scene.body2
    if math.isfinite(b2.Rx) or math.isfinite(b2.Ry):
        # two moving bodies need both masses; --mass is the reduced one
        return ref.replace(oblique={"note": "an oblique impact is graded against a fixed "
                                            "plane (body 2 flat) only"})
    return ref.replace(oblique=_oblique_reference(oblique, scene, mass, speed, mu, angle_deg))


def _oblique_reference(oblique, scene, mass, speed, mu, angle_deg) -> dict:
    """hertz.oblique_impact of body 1 (mass ``mass``, a solid ball) on the fixed plane at
    normal speed ``speed`` and incidence ``angle_deg``: the contact point's tangential
    restitution and rebound angle, the spin after."""
    theta = math.radians(abs(angle_deg))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        r = oblique(scene.body1, scene.body2, speed / math.cos(theta), theta, mass, mu,
                    angle=scene.angle)
    return {"tangential_restitution": float(r.tangential_restitution),
            "rebound_angle_deg": math.degrees(float(r.rebound_angle)),
            "centre_rebound_angle_deg": math.degrees(float(r.centre_rebound_angle)),
            "spin": float(r.spin), "tangential_velocity": float(r.tangential_velocity),
            "v_t_before": speed * math.tan(theta), "gross_slip": bool(r.gross_slip),
            "gross_slip_angle_deg": math.degrees(float(r.gross_slip_angle)),
            "error": float(getattr(r, "error", 0.0))}


@dataclass(frozen=True)
class Measured:
    """What the trajectory says (see the module docstring for how each is found)."""

    i0: int
    i1: int
    dt: float
    t_start: float
    t_end: float
    duration: float
    max_overlap: float
    max_force: float
    v_in: float
    v_out: float
    v_in_bound: float
    v_out_bound: float
    restitution: float
    restitution_method: str
    start_method: str = ""
    end_method: str = ""
    notes: tuple = ()


def _secant(t, y, a, b):
    return (y[b] - y[a]) / (t[b] - t[a])


def _zero(t, y, a, b) -> float:
    """Where the line through rows a and b of y(t) crosses 0."""
    return t[a] - y[a] * (t[b] - t[a]) / (y[b] - y[a])


def _start(t, d, f, i0) -> tuple[float, str]:
    """The contact's start, within the step before the first row in contact: where the
    overlap crosses 0 (interpolated between the rows around it where the record writes
    the gap, else extrapolated from the first two rows in contact), else where F^(2/3)
    (linear in time for Hertz) extrapolates to 0."""
    if d[i0 - 1] < 0 < d[i0]:
        ts, how = _zero(t, d, i0 - 1, i0), "the overlap's zero, interpolated"
    elif 0 < d[i0] < d[i0 + 1]:
        ts, how = _zero(t, d, i0, i0 + 1), "the overlap's zero, extrapolated"
    else:
        g = np.abs(f) ** (2.0 / 3.0)
        if g[i0 + 1] > g[i0]:
            ts, how = _zero(t, g, i0, i0 + 1), "F^(2/3) extrapolated to 0"
        else:
            ts, how = 0.5 * (t[i0 - 1] + t[i0]), "the middle of the step"
    return float(min(max(ts, t[i0 - 1]), t[i0])), how


def _end(t, d, f, i1) -> tuple[float, str]:
    """The contact's end, within the step after the last row in contact: where the
    overlap returns to 0, as :func:`_start`; where the force turned off before the overlap
    did (a damped force cut off at 0), where the force extrapolates to 0."""
    if d[i1 + 1] > 0:
        if f[i1 - 1] > f[i1] > 0:
            te, how = _zero(t, f, i1 - 1, i1), "the force's zero (cut off), extrapolated"
        else:
            te, how = 0.5 * (t[i1] + t[i1 + 1]), "the middle of the step"
    elif d[i1 + 1] < 0 < d[i1]:
        te, how = _zero(t, d, i1, i1 + 1), "the overlap's zero, interpolated"
    elif d[i1 - 1] > d[i1] > 0:
        te, how = _zero(t, d, i1 - 1, i1), "the overlap's zero, extrapolated"
    else:
        te, how = 0.5 * (t[i1] + t[i1 + 1]), "the middle of the step"
    return float(max(min(te, t[i1 + 1]), t[i1])), how


def measure(r: ImpactTrajectory, mass: float, attractive: bool = False) -> Measured:
    """The contact's start and end, peaks and velocities in and out of a trajectory.

    The contact is the first run of rows with a positive normal force; ``attractive`` (the
    damping may pull at the end of the contact): the first run of rows with a positive
    overlap or a nonzero force, so that it ends when the overlap returns to 0, not where
    the force first reaches 0 (nor at a row whose force is written as 0 near its change
    of sign).

    Raises
    ------
    ResultError
        No row in contact, fewer than :data:`MIN_CONTACT_ROWS`, a record that starts or
        ends in contact, an overlap that does not grow into the contact.
    """
    t, d, f = r.t, r.overlap, r.normal_force
    src = f"{r.source}: " if r.source else ""
    on = ((f != 0) | (d > 0)) if attractive else (f > 0)
    if not (f > 0).any():
        raise ResultError(f"{src}no row has a positive normal force: the record holds no "
                          f"contact (is the force column the contact's normal force?)")
    i0 = int(np.argmax(on))
    off = np.nonzero(~on[i0:])[0]
    i1 = (i0 + int(off[0]) - 1) if len(off) else len(t) - 1
    notes = []
    if i0 == 0:
        raise ResultError(f"{r.where(0)}: the record starts in contact (force "
                          f"{f[0]:.6g} N): write rows from before the impact")
    if i1 == len(t) - 1:
        raise ResultError(f"{r.where(i1)}: the record ends in contact (force {f[i1]:.6g} N): "
                          f"write rows until after the bodies part")
    if i1 - i0 + 1 < MIN_CONTACT_ROWS:
        dip = ""
        if d[i1 + 1] > 0 and on[i1 + 1:].any():  # the force dips to 0 inside the contact
            k = i1 + 1
            at = f"line {int(r.lines[k])}" if r.lines is not None else f"row {k}"
            dip = (f"; the force is {f[k]:.6g} N at {at} with the overlap "
                   f"still {d[k]:.6g} m, and positive again later: a contact is the rows "
                   f"of positive force (a noisy or attractive force? --damping-attractive)")
        raise ResultError(f"{r.where(i0)}: only {i1 - i0 + 1} row(s) in contact; an impact is "
                          f"graded from {MIN_CONTACT_ROWS} or more (write every step of the "
                          f"contact, or at least 20 rows of it){dip}")
    if on[i1 + 1:].any():
        k = i1 + 1 + int(np.argmax(on[i1 + 1:]))
        notes.append(f"a second contact starts at {r.where(k)}; only the first is graded")
    dt = float(np.diff(t[i0 - 1:i1 + 2]).max())
    ts, start_how = _start(t, d, f, i0)
    te, end_how = _end(t, d, f, i1)
    # the first row after the contact from which the bodies fly freely (no force on it
    # and the next): where the force pulls after the contact, the rebound is measured there
    zero = f == 0
    free = np.nonzero(zero[i1 + 1:] & np.append(zero[i1 + 2:], True))[0]
    after = i1 + 1 + int(free[0]) if len(free) else i1 + 1
    if after > i1 + 1 or (f[i1 + 1] < 0 and not attractive):
        notes.append(f"the force is negative (attractive) after the contact, from "
                     f"{r.where(i1 + 1)}: the rebound is measured from {r.where(after)}; "
                     f"--damping-attractive grades such a contact as one")
    if r.v_n is not None:
        v_in, v_out = float(r.v_n[i0 - 1]), float(r.v_n[after])
        b_in = b_out = 0.0
        method = "the v_n column, the rows next to the contact (free flight)"
        if v_in == 0:
            raise ResultError(f"{r.where(i0 - 1)}: v_n is 0 just before the contact: the "
                              f"restitution -v_n(after) / v_n(before) is not defined")
    else:
        parts = []
        if i0 >= 2 and d[i0 - 1] != d[i0 - 2]:
            v_in, b_in = _secant(t, d, i0 - 2, i0 - 1), 0.0
            parts.append("in: the gap over the two rows before the contact")
        else:
            v_in = _secant(t, d, i0, i0 + 1)
            b_in = float(f[i0 + 1]) / mass * (t[i0 + 1] - t[i0 - 1])
            parts.append("in: the overlap over the first two rows in contact")
        if after + 1 < len(t) and d[after] != d[after + 1]:
            v_out, b_out = _secant(t, d, after, after + 1), 0.0
            parts.append("out: the gap over the two rows after it")
        else:
            v_out = _secant(t, d, i1 - 1, i1)
            b_out = float(abs(f[i1 - 1])) / mass * (t[i1 + 1] - t[i1 - 1])
            parts.append("out: the overlap over the last two rows in contact")
        method = "d overlap / dt (" + "; ".join(parts) + ")"
        if not v_in > 0:
            raise ResultError(f"{r.where(i0)}: the overlap does not grow into the contact "
                              f"(slope {v_in:.6g} m/s): is the overlap column the overlap "
                              f"(positive in contact)?")
    e = -v_out / v_in
    return Measured(i0, i1, dt, float(ts), float(te), float(te - ts),
                    float(d[i0:i1 + 1].max()), float(f[i0:i1 + 1].max()), float(v_in),
                    float(v_out), float(b_in), float(b_out), float(e), method, start_how,
                    end_how, tuple(notes))


@dataclass(frozen=True)
class ImpactGrade(GradeMethods):
    """A DEM impact graded against the exact impact.

    Attributes
    ----------
    scene, source : str
        What was graded.
    mass, speed : float
        Reduced mass [kg] and normal approach speed [m/s] graded at.
    metrics : dict
        Every metric of :data:`METRICS` (NaN where not available).
    checks : tuple of Check
        One per metric, with its tolerance and status.
    passed : bool
        Every checked metric within its tolerance.
    reference : dict
        The reference's delta_max [m], F_max [N], t_c [s], restitution, source (and the
        oblique quantities).
    measured : dict
        The trajectory's: start, end, duration [s], dt [s], peaks, v_in, v_out [m/s],
        restitution and how it was found (and the oblique quantities).
    tolerance_basis : dict
        metric -> how its tolerance was derived (the sampling bound and the floor).
    curves : dict
        Arrays for the figure: t [s], overlap [m], force [N], the reference's F(t) and
        F(delta) at the rows (NaN where none).
    details : dict
        The trajectory's details and the options graded with.
    notes : tuple of str
    hint : str
        "" (the contact grades' unit hint has no counterpart here).
    """

    scene: str
    source: str
    mass: float
    speed: float
    metrics: dict
    checks: tuple
    passed: bool
    reference: dict
    measured: dict
    tolerance_basis: dict
    curves: dict = field(repr=False, default_factory=dict)
    details: dict = field(default_factory=dict)
    notes: tuple = ()
    hint: str = ""

    def to_dict(self) -> dict:
        """grade.json: the metrics at the top level, passed, checks (with their meaning
        and the basis of their tolerance), reference, measured, details, notes."""
        checks = [{**c.to_dict(), "meaning": METRICS[c.name][1],
                   "tolerance_basis": self.tolerance_basis.get(c.name, "")}
                  for c in self.checks]
        return nan_to_none({
            "kind": "impact", "scene": self.scene, "source": self.source, "mass": self.mass,
            "speed": self.speed, **self.metrics, "passed": self.passed, "checks": checks,
            "reference": self.reference, "measured": self.measured, "details": self.details,
            "notes": list(self.notes)})


def _trapezoid(y, x) -> float:
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(x)))


def _rms(x) -> float:
    x = np.asarray(x, dtype=float)
    return float(np.sqrt(np.mean(x * x))) if x.size else math.nan


def grade_impact(r: ImpactTrajectory, ref: ImpactReference, *, mass: float, speed: float,
                 radius: float | None = None, scene: str = "",
                 tolerances: Mapping[str, float] | None = None,
                 details: Mapping | None = None, attractive: bool | None = None
                 ) -> ImpactGrade:
    """Grade a trajectory against a reference (see the module docstring).

    Parameters
    ----------
    r : ImpactTrajectory
    ref : ImpactReference
        From :func:`impact_reference` (or :func:`hertz_closed_form`).
    mass : float
        Reduced mass [kg] (the overlap's deceleration at the peak is F / M).
    speed : float
        Normal approach speed [m/s].
    radius : float, optional
        Body 1's radius [m] (the rebound angle of the contact point of an oblique impact).
    scene : str
        The scene's name, for the report.
    tolerances : dict, optional
        metric -> tolerance, replacing the derived ones.
    details : dict, optional
        Plain values the report should quote.
    attractive : bool, optional
        The contact force may pull (a damping not cut off at 0): the contact lasts until
        the overlap returns to 0 (interpolated), the rebound speed is the one there (the
        free flight after it); False: the contact ends where the force reaches 0.
        Default: the reference's own (``ref.attractive``, from ``impact_reference(...,
        cutoff=False)``), so that the contact is measured as the reference's is.

    Returns
    -------
    ImpactGrade

    Raises
    ------
    ResultError
        A trajectory that cannot be graded (:func:`measure`).
    ValueError
        A mass, speed or tolerance that is not a finite number > 0; an unknown metric.

    Examples
    --------
    >>> import numpy as np
    >>> from fem_validation.results.impact import ImpactTrajectory
    >>> ref = hertz_closed_form(2.357022603955158e9, 0.005864306286700947, 20.0)
    >>> t = np.linspace(-2e-6, ref.duration + 2e-6, 401)
    >>> f = ref.force_of_time(t)
    >>> d = np.where(f > 0, (f / 2.357022603955158e9) ** (2 / 3), 0.0)
    >>> g = grade_impact(ImpactTrajectory(t, d, f), ref, mass=0.005864306286700947,
    ...                  speed=20.0)
    >>> g.passed, round(g.metrics["duration_rel_err"], 4)
    (True, 0.0)
    """
    for name, value in (("mass", mass), ("speed", speed)):
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    for name, value in (tolerances or {}).items():
        if name not in METRICS:
            raise ValueError(f"tolerances: unknown metric {name!r}; known: "
                             f"{', '.join(sorted(METRICS))}")
        if not (isinstance(value, int | float) and math.isfinite(value) and value > 0):
            raise ValueError(f"tolerances: {name} must be a finite number > 0, got {value!r}")
    if attractive is None:
        attractive = bool(ref.attractive)
    m = measure(r, mass, bool(attractive))
    notes = list(m.notes)
    if bool(attractive) != bool(ref.attractive) and (ref.attractive
                                                     or bool((r.normal_force < 0).any())):
        notes.append(f"the contact is measured as one whose force "
                     f"{'may pull' if attractive else 'is cut off at 0'}, the reference's "
                     f"force {'may pull' if ref.attractive else 'is cut off at 0'}: the "
                     f"duration and restitution compare different contacts")
    values, tol, basis = {}, {}, {}
    dmax, fmax, tc = ref.max_approach, ref.max_force, ref.duration
    dt = m.dt

    f_peak = fmax if math.isfinite(fmax) else ref.stiffness * dmax ** 1.5
    if math.isfinite(dmax) and math.isfinite(f_peak):
        b_d = (f_peak / mass) * (dt / dmax) * dt / 8.0  # no underflow of 8 M delta
        values["max_overlap_rel_err"] = m.max_overlap / dmax - 1.0
        tol["max_overlap_rel_err"] = FLOOR + b_d
        basis["max_overlap_rel_err"] = (f"{FLOOR:g} + F dt^2 / (8 M delta_max), F the force "
                                        f"at delta_max, = {FLOOR:g} + {b_d:.3g} (dt {dt:.4g} "
                                        f"s)")
    if math.isfinite(dmax) and math.isfinite(fmax):
        values["max_force_rel_err"] = m.max_force / fmax - 1.0
        tol["max_force_rel_err"] = FLOOR + 1.5 * b_d
        basis["max_force_rel_err"] = f"{FLOOR:g} + 1.5 x the overlap's bound = " \
                                     f"{FLOOR:g} + {1.5 * b_d:.3g}"
    if math.isfinite(tc):
        values["duration_rel_err"] = m.duration / tc - 1.0
        tol["duration_rel_err"] = FLOOR + dt / tc
        basis["duration_rel_err"] = f"{FLOOR:g} + dt / t_c = {FLOOR:g} + {dt / tc:.3g}"
    b_e = (m.v_out_bound + abs(m.restitution) * m.v_in_bound) / abs(m.v_in)
    values["restitution_err"] = m.restitution - ref.restitution
    tol["restitution_err"] = FLOOR + b_e
    basis["restitution_err"] = (f"{FLOOR:g} + the velocities' bound {b_e:.3g} "
                                f"(from {m.restitution_method})")
    values["impact_speed_rel_err"] = abs(m.v_in) / speed - 1.0
    tol["impact_speed_rel_err"] = FLOOR + m.v_in_bound / speed
    basis["impact_speed_rel_err"] = f"{FLOOR:g} + {m.v_in_bound / speed:.3g}"

    i0, i1 = m.i0, m.i1
    rows = slice(i0, i1 + 1)
    near = slice(i0 - 1, i1 + 2)
    ref_fd = np.full(r.rows, math.nan)
    ref_ft = np.full(r.rows, math.nan)
    scale = fmax if math.isfinite(fmax) else m.max_force
    if ref.force_of_overlap is not None:
        ref_fd[rows] = ref.force_of_overlap(r.overlap[rows])
        values["force_overlap_rms"] = _rms(r.normal_force[rows] - ref_fd[rows]) / scale
        tol["force_overlap_rms"] = CURVE_FLOOR
        basis["force_overlap_rms"] = (f"{CURVE_FLOOR:g} (pointwise at the record's "
                                      f"overlaps: no sampling error)")
    if ref.force_of_time is not None and math.isfinite(tc):
        t_near, f_near = r.t[near], r.normal_force[near]

        def misfit(shift):
            return _rms(f_near - ref.force_of_time(t_near - shift))

        from scipy.optimize import minimize_scalar

        best = minimize_scalar(misfit, bounds=(m.t_start - dt, m.t_start + dt),
                               method="bounded", options={"xatol": 1e-6 * dt})
        t0 = float(best.x) if misfit(best.x) < misfit(m.t_start) else m.t_start
        ref_ft[near] = ref.force_of_time(t_near - t0)
        values["force_time_rms"] = misfit(t0) / scale
        # what a duration error at its tolerance makes of the curve: d F(t (1 + eps)) / d eps
        tau = np.linspace(0.0, tc, 401)
        slope = np.gradient(ref.force_of_time(tau), tau)
        allowance = tol.get("duration_rel_err", FLOOR) * _rms((tau - 0.5 * tc) * slope) / scale
        tol["force_time_rms"] = CURVE_FLOOR + allowance
        basis["force_time_rms"] = (f"{CURVE_FLOOR:g} + the RMS a duration error at its "
                                   f"tolerance makes, {allowance:.3g} (start fitted within "
                                   f"one step)")
    oblique_measured = {}
    if r.oblique:
        oblique_measured = _oblique(r, m, radius, ref, values, tol, basis, notes)
    for name, value in (tolerances or {}).items():
        tol[name] = float(value)
        basis[name] = "given"
    checks = []
    oblique_names = ("tangential_restitution_err", "rebound_angle_err_deg", "spin_rel_err")
    for name in METRICS:
        if name in oblique_names and not r.oblique:
            continue  # a head-on impact: no oblique check at all
        if name in values and math.isfinite(values[name]) and name in tol:
            ok = abs(values[name]) <= tol[name]
            checks.append(Check(name, float(values[name]), tol[name], "pass" if ok else "fail"))
        else:
            checks.append(Check(name, math.nan, None, "not available"))
    passed = all(c.passed is not False for c in checks) and any(c.passed for c in checks)
    reference = {"max_approach": dmax, "max_force": fmax, "duration": tc,
                 "restitution": ref.restitution, "source": ref.source,
                 **({"oblique": ref.oblique} if ref.oblique is not None else {})}
    measured = {"t_start": m.t_start, "t_end": m.t_end, "duration": m.duration, "dt": dt,
                "rows_in_contact": i1 - i0 + 1, "max_overlap": m.max_overlap,
                "max_force": m.max_force, "v_in": m.v_in, "v_out": m.v_out,
                "restitution": m.restitution, "restitution_method": m.restitution_method,
                "start_method": m.start_method, "end_method": m.end_method,
                "attractive": bool(attractive), **oblique_measured}
    curves = {"t": r.t, "overlap": r.overlap, "force": r.normal_force,
              "reference_force_time": ref_ft, "reference_force_overlap": ref_fd,
              "t_start": m.t_start, "t_end": m.t_end}
    return ImpactGrade(scene, r.source, float(mass), float(speed),
                       {n: values.get(n, math.nan) for n in METRICS}, tuple(checks), passed,
                       reference, measured, basis, curves,
                       {**r.details, **dict(details or {})}, tuple(notes),
                       _unit_hint(m, dmax, fmax))


def _unit_hint(m: Measured, dmax: float, fmax: float) -> str:
    """Where the record's peaks are about 1000 times off the reference's: the likely unit
    mistake; "" otherwise."""
    hints = []
    for what, ratio, big, small in (
            ("overlap", m.max_overlap / dmax, "is the file in mm? (--units mm, or a "
             "'# units = mm' line)", "is the file in m but read as mm?"),
            ("force", m.max_force / fmax, "is the force in mN?", "is the force in kN?")):
        if not math.isfinite(ratio) or ratio <= 0:
            continue
        decades = math.log10(ratio) / 3
        if abs(decades - round(decades)) < 0.1 and round(decades) != 0:
            hints.append(f"the largest {what} is about 1e{3 * round(decades):+d} times the "
                         f"reference's: {big if decades > 0 else small}")
    return "; ".join(hints)


def _oblique(r, m, radius, ref, values, tol, basis, notes) -> dict:
    """The oblique metrics where the reference has them (the contact point's tangential
    restitution and rebound angle, the spin after); what the trajectory says in any case.
    A record whose tangential axis points against the incoming motion (v_t < 0 before)
    is read with v_t and omega both reversed."""
    i0, i1 = m.i0, m.i1
    sign = -1.0 if r.v_t[i0 - 1] < 0 else 1.0
    vt0, vt1 = sign * float(r.v_t[i0 - 1]), sign * float(r.v_t[i1 + 1])
    w0, w1 = sign * float(r.omega[i0 - 1]), sign * float(r.omega[i1 + 1])
    v_n_after = abs(m.v_out)
    out = {"v_t_before": vt0, "v_t_after": vt1, "omega_before": w0, "omega_after": w1}
    rows = slice(i0 - 1, i1 + 2)
    normal_impulse = _trapezoid(r.normal_force[rows], r.t[rows])
    tangential_impulse = sign * _trapezoid(r.tangential_force[rows], r.t[rows])
    if normal_impulse > 0:  # information: mu in gross slip
        out["impulse_ratio"] = abs(tangential_impulse) / normal_impulse
    if tangential_impulse * (vt1 - vt0) < 0:  # the column is information only: say so
        notes.append(f"oblique: the tangential_force column's impulse "
                     f"({tangential_impulse:.4g} N s) has the opposite sign of body 1's "
                     f"change of v_t ({vt1 - vt0:+.4g} m/s): it is not the force on body 1 "
                     f"along v_t (the other body's, or the other sign); it is not graded")
    if radius is None:
        notes.append("oblique: body 1 is not a sphere; the contact point's velocity (v_t - R "
                     "omega) is not known, the oblique checks are not made")
        return out
    cp0, cp1 = vt0 - radius * w0, vt1 - radius * w1
    out.update({"contact_point_v_t_before": cp0, "contact_point_v_t_after": cp1,
                "rebound_angle_deg": math.degrees(math.atan2(cp1, v_n_after))})
    if cp0 != 0:
        out["tangential_restitution"] = cp1 / cp0
    o = ref.oblique or {}
    if "tangential_restitution" not in o:
        notes.append("oblique: " + o.get("note", "the reference has no oblique impact "
                                               "(hertz.oblique_impact missing or no --mu)")
                     + ": the tangential restitution, rebound angle and spin are reported, "
                       "not graded")
        return out
    if not o.get("gross_slip", True):
        notes.append(f"oblique: partial slip (incidence below "
                     f"{o.get('gross_slip_angle_deg', math.nan):.2f} deg): the reference is "
                     f"Mindlin-Deresiewicz's; a DEM tangential spring approximates it")
    err = o.get("error", 0.0)
    if "tangential_restitution" in out:
        values["tangential_restitution_err"] = (out["tangential_restitution"]
                                                - o["tangential_restitution"])
        tol["tangential_restitution_err"] = 2 * FLOOR + err
        basis["tangential_restitution_err"] = (f"{2 * FLOOR:g} + the reference's own error "
                                               f"{err:.2g} (free-flight rows: no sampling "
                                               f"error)")
    values["rebound_angle_err_deg"] = out["rebound_angle_deg"] - o["rebound_angle_deg"]
    tol["rebound_angle_err_deg"] = 0.1
    basis["rebound_angle_err_deg"] = "0.1 deg (free-flight rows: no sampling error)"
    scale = abs(cp0) / radius
    if scale > 0:
        values["spin_rel_err"] = (w1 - o["spin"]) / scale
        tol["spin_rel_err"] = 2 * FLOOR + err
        basis["spin_rel_err"] = (f"{2 * FLOOR:g} of the contact point's speed before / R "
                                 f"(free-flight rows)")
    return out
