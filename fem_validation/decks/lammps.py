"""LAMMPS inputs for a scene: the DEM side of the Hertz benchmarks (``pair_style granular``).

:func:`lammps_deck` turns a :class:`~fem_validation.scenes.Scene` of two spheres (or a sphere,
body 1, on a flat body 2: a wall) into a LAMMPS input whose ``fix print`` writes the very CSV
that ``python -m fem_validation grade`` reads: no dump to convert, no reader.

Cases (``units si``, ``atom_style sphere``, no gravity; sphere 1 at the origin):

``normal``
    Sphere 2 (or sphere 1 against the wall) moved by ``fix move`` along the line of centres
    into the overlap of the scene's load (``approach``), and 10% past it; ``force.csv``:
    ``overlap, force`` with the force projected on the line of centres.  Grade with
    ``grade --force-approach``.
``fretting``
    Pressed to the scene's overlap, then moved tangentially at that constant overlap (sphere 2
    moves on the circle around sphere 1's centre, so the overlap does not change by the
    second order of the displacement): a ramp to the displacement at which Cattaneo-Mindlin
    gives Q = ``ratio`` mu P, back to minus it, forward again; ``history.csv``:
    ``displacement, force, normal_force`` from the start of the tangential motion.
``path``
    Pressed to the scene's overlap, pushed sideways as in ``fretting``'s ramp, lifted to
    ``lift`` times the overlap, pressed back; ``history.csv`` as above, the normal force
    varying.
``impact``
    Two free spheres (``fix nve/sphere``), sphere 2 arriving at ``speed`` along the line of
    centres (sphere 1 at rest), or a sphere on the wall at ``speed`` and ``angle_deg`` from the
    wall's normal; ``trajectory.csv``: ``t, overlap, normal_force, tangential_force, v_t,
    omega`` (the wall's case: the sphere's sliding velocity and spin, the tangential force on
    the sphere), one row per step while the run lasts (1.5 of Hertz's contact time).

Forces are projected on the contact normal and plane at each row: the raw x force of a
sphere pushed sideways holds P sin(u / d) of the normal force (4e-4 of Q at a reversal).

Sign conventions of the CSV: ``overlap`` > 0 in contact; ``normal_force`` > 0 pushes the
bodies apart; in ``history.csv`` the ``force`` is the force that drives sphere 2 (the
contact's force on it with the sign reversed), so that it has the sign of the
``displacement``; in ``trajectory.csv`` the ``tangential_force`` is the contact's force on
the moving sphere.

Materials: LAMMPS mixes E* and the shear modulus of Mindlin's stiffness, 8 G* a, from E and
nu of each atom type, and a wall's coefficients are used as the pair's; the deck gives one
equivalent material (:func:`equivalent_material`) that has the scene's E* and G*, so that two
different spheres and a sphere on a wall are stated in the same way.

Examples
--------
>>> import hertz
>>> from fem_validation.scenes import Scene
>>> ball = hertz.Body.sphere(1e-3, E=70e9, nu=0.33)
>>> deck = lammps_deck(Scene("al", ball, ball, 1.0), "normal")
>>> deck.output, deck.columns
('force.csv', ('overlap', 'force'))
>>> "hertz/material" in deck.script
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import hertz

from ..scenes import Scene

__all__ = ["CASES", "DAMPING", "NORMAL", "TANGENTIAL", "LammpsDeck", "equivalent_material",
           "lammps_deck", "write_lammps_deck"]

CASES = ("normal", "fretting", "path", "impact")
#: LAMMPS's normal laws a deck writes (``pair_coeff * * LAW ...``).
NORMAL = ("hertz/material", "hertz", "hooke")
#: LAMMPS's tangential models with a history (``pair_coeff ... tangential MODEL``).
TANGENTIAL = ("mindlin", "mindlin_rescale", "mindlin/force", "mindlin_rescale/force",
              "linear_history")
#: LAMMPS's damping models: ``none`` writes ``viscoelastic`` with a zero coefficient;
#: ``viscoelastic`` takes eta_n0 [1/(s m)], ``tsuji`` and ``coeff_restitution`` a restitution.
DAMPING = ("none", "viscoelastic", "tsuji", "coeff_restitution", "mass_velocity")
#: Steps of each leg of a quasi-static path (ramp, unloading, reloading, lift, press).
STEPS_PER_LEG = 400
#: Steps of an impact before the first touch (rows of zero force before the contact).
LEAD = 10
#: The output files of each case.
OUTPUTS = {"normal": ("force.csv", ("overlap", "force")),
           "fretting": ("history.csv", ("displacement", "force", "normal_force")),
           "path": ("history.csv", ("displacement", "force", "normal_force")),
           "impact": ("trajectory.csv", ("t", "overlap", "normal_force", "v_n",
                                         "tangential_force", "v_t", "omega"))}


@dataclass(frozen=True)
class LammpsDeck:
    """A LAMMPS input and what it writes.

    Attributes
    ----------
    case : str
        One of :data:`CASES`.
    script : str
        The LAMMPS input (``lmp -in in.lammps``, run in the folder it is written to).
    output : str
        The CSV file name the run writes beside the input.
    columns : tuple of str
        The CSV's columns (SI: m, N, s, m/s, rad/s).
    grade : str
        The grade command for the run's output, ``SCENE`` and ``DIR`` standing for the scene
        file and an output folder.
    values : dict
        The numbers the deck was made of: overlap [m], mu, amplitude [m], mass [kg] (the
        reduced mass of an impact), speed [m/s], contact time estimate [s], time step [s]...
    """

    case: str
    script: str
    output: str
    columns: tuple[str, ...]
    grade: str
    values: dict = field(default_factory=dict)


def _sphere(body: hertz.Body, which: str) -> float:
    if not (math.isfinite(body.Rx) and body.Rx == body.Ry and body.Rx > 0):
        raise ValueError(f"a LAMMPS deck needs spheres: {which} has Rx = {body.Rx!r}, Ry = "
                         f"{body.Ry!r} (a convex sphere has Rx = Ry > 0; body2 may be flat, "
                         f"Rx = Ry = inf, a wall)")
    return float(body.Rx)


def _geometry(scene: Scene) -> tuple[float, float | None]:
    """(R1, R2), R2 None for a wall."""
    r1 = _sphere(scene.body1, "body1")
    b2 = scene.body2
    if math.isinf(b2.Rx) and math.isinf(b2.Ry):
        return r1, None
    return r1, _sphere(b2, "body2")


def equivalent_material(scene: Scene) -> tuple[float, float]:
    """(E [Pa], nu) of one material whose pair with itself has the scene's E* and G*.

    LAMMPS's ``hertz/material`` mixes E* = 1 / ((1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j) and,
    for ``tangential mindlin NULL``, 1/G* = 2(2 - nu_i)(1 + nu_i)/E_i + 2(2 - nu_j)(1 +
    nu_j)/E_j (Mindlin's no-slip stiffness 8 G* a); a wall's coefficients are the pair's.  One
    material (E, nu) paired with itself gives both of the scene's when G*/E* = (1 - nu) /
    (2 (2 - nu)), that is nu = (4 r - 1)/(2 r - 1) with r = G*/E*, and E = 2 E* (1 - nu^2).
    Two equal bodies give back their own E and nu; a sphere on a rigid wall its own nu and 2 E.

    Examples
    --------
    >>> import hertz
    >>> ball = hertz.Body.sphere(1e-3, E=70e9, nu=0.33)
    >>> E, nu = equivalent_material(Scene("al", ball, ball, 1.0))
    >>> round(E / 1e9, 9), round(nu, 12)
    (70.0, 0.33)
    """
    inv_e = sum((1 - b.nu ** 2) / b.E for b in (scene.body1, scene.body2))
    inv_g = sum(2 * (2 - b.nu) * (1 + b.nu) / b.E for b in (scene.body1, scene.body2))
    r = (1 / inv_g) / (1 / inv_e)
    nu = (4 * r - 1) / (2 * r - 1)
    if not -1 < nu <= 0.5:
        raise ValueError(f"no one material has the E* and G* of scene {scene.name!r}: its "
                         f"Poisson's ratio would be {nu!r}, outside (-1, 0.5]")
    return 2 * (1 - nu ** 2) / inv_e, nu


def _check(name: str, value, low: float, high: float, what: str) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not (math.isfinite(x) and low < x <= high):
        raise ValueError(f"{name} must be in ({low:g}, {high:g}] ({what}), got {value!r}")
    return x


def _fmt(x: float) -> str:
    return repr(float(x))


def _piecewise(knots: list[tuple[int, float]], dt: float, name: str) -> tuple[str, str]:
    """LAMMPS equal-style expressions of a piecewise-linear function of ``time`` through
    (step, value) knots, and of its slope.  Step n belongs to the leg that ends at or after
    it (the comparisons are made half a step off the knots): ``fix move`` sets a step's
    position and the velocity LAMMPS integrates the tangential displacement with at the
    step's end time, so the displacement accumulated over a leg is the leg's."""
    half = dt / 2
    (n0, y0), (nl, yl) = knots[0], knots[-1]
    value = [f"(time<={_fmt(n0 * dt + half)})*{_fmt(y0)}"]
    slope = []
    for (na, ya), (nb, yb) in zip(knots, knots[1:], strict=False):
        ta, tb = na * dt, nb * dt
        inside = f"(time>{_fmt(ta + half)})*(time<={_fmt(tb + half)})"
        if ya == yb:
            value.append(f"{inside}*{_fmt(ya)}")
            continue
        s = (yb - ya) / (tb - ta)
        value.append(f"{inside}*({_fmt(ya)}+{_fmt(s)}*(time-{_fmt(ta)}))")
        slope.append(f"{inside}*{_fmt(s)}")
    value.append(f"(time>{_fmt(nl * dt + half)})*{_fmt(yl)}")
    return (f"variable {name} equal " + "+".join(value),
            f"variable {name}dot equal " + ("+".join(slope) if slope else "0.0"))


def _pair(tangential: str, e: float, nu: float, mu: float, kt, kn, normal: str,
          damping: str, damp_value: float, x_gamma_t: float, attractive: bool,
          frictionless: bool) -> str:
    damp = 0.0 if damping == "none" else damp_value
    if normal == "hertz/material":
        normal_part = f"hertz/material {_fmt(e)} {_fmt(damp)} {_fmt(nu)}"
    else:
        normal_part = f"{normal} {_fmt(kn)} {_fmt(damp)}"
    if tangential == "linear_history" and kt is None:
        raise ValueError("tangential linear_history needs kt [N/m] (its spring has no NULL)")
    if frictionless:   # no material for mindlin's NULL and no tangential motion: none
        tangential_part = "linear_nohistory 0.0 0.0"
    else:
        kt_text = "NULL" if kt is None else _fmt(kt)
        tangential_part = f"{tangential} {kt_text} {_fmt(x_gamma_t)} {_fmt(mu)}"
    law = "viscoelastic" if damping == "none" else damping
    # limit_damping: the damped normal force never pulls (LAMMPS's default lets it)
    return (f"pair_coeff * * {normal_part} tangential {tangential_part} damping {law}" +
            ("" if damping == "none" or attractive else " limit_damping"))


def lammps_deck(scene: Scene, case: str, *, tangential: str = "mindlin", mu: float = 0.3,
                kt: float | None = None, kn: float | None = None,
                normal: str | None = None, ratio: float = 0.8,
                amplitude: float | None = None,
                lift: float = 0.4, damping: str = "none", damping_value: float = 0.0,
                speed: float = 0.5, angle_deg: float = 0.0, density: float = 2700.0,
                steps: int = STEPS_PER_LEG, attractive: bool = False) -> LammpsDeck:
    """A LAMMPS input of one case for the scene (see the module's text for the cases).

    Parameters
    ----------
    scene : Scene
        Body 1 a sphere; body 2 a sphere or flat (a wall: ``fix wall/gran``).  The scene's
        target load gives the overlap of ``normal``, ``fretting`` and ``path`` (Hertz's
        approach at that load); ``impact`` does not use it.
    case : {'normal', 'fretting', 'path', 'impact'}
    tangential : str
        LAMMPS's tangential model, one of :data:`TANGENTIAL` (default ``mindlin``).
    mu : float
        Coefficient of friction, in (0, 10].
    kt : float, optional
        LAMMPS's tangential coefficient (``mindlin*``: F = kt a xi, Pa; ``linear_history``: N/m);
        default ``NULL``: Mindlin's 8 G* a from the materials.
    kn : float, optional
        The stiffness of a ``hertz`` (F = kn sqrt(R) delta^(3/2), Pa: ``kn = E*`` is the
        forgotten 4/3) or ``hooke`` (F = kn delta, N/m) normal law.  Without ``kt`` the
        contact is frictionless (``tangential linear_nohistory 0 0``: ``normal`` and head-on
        ``impact`` only), LAMMPS's mindlin NULL needing the materials.
    normal : {'hertz/material', 'hertz', 'hooke'}, optional
        LAMMPS's normal law; default ``hertz/material`` (4/3 E*), ``hertz`` where ``kn`` is
        given.
    ratio : float
        Q*/(mu P) of Cattaneo-Mindlin at the end of the tangential ramp, in (0, 1).
    amplitude : float, optional
        The tangential displacement of the ramp [m], instead of ``ratio``'s.
    lift : float
        ``path``: the overlap lifted to, as a fraction of the scene's, in (0, 1).
    damping : str
        One of :data:`DAMPING` (default ``none``: no damping).  The normal force only: the
        tangential damping is off (``x_gamma_t`` 0) in every deck.
    attractive : bool
        Let the damped normal force pull near the end of a contact (LAMMPS's default);
        default False: ``limit_damping``, the force cut off at zero.
    damping_value : float
        The damping law's coefficient (``viscoelastic``: eta_n0 [1/(m s)]; ``tsuji``,
        ``coeff_restitution``: the restitution; ``mass_velocity``: [1/s]).
    speed : float
        ``impact``: the normal approach speed V [m/s], in (0, 1000] (sphere 2 arrives at V,
        sphere 1 at rest; an oblique impact on the wall adds V tan(angle) along x).
    angle_deg : float
        ``impact``: the angle of the velocity from the wall's normal [deg], in [0, 90);
        oblique impacts need a wall.
    density : float
        ``impact``: density of the spheres [kg/m^3].
    steps : int
        Steps per leg of a quasi-static path; an impact takes 5 times as many over Hertz's
        contact time.

    Returns
    -------
    LammpsDeck

    Raises
    ------
    ValueError
        Naming the parameter, the value and what is allowed.
    """
    if case not in CASES:
        raise ValueError(f"case must be one of {', '.join(CASES)}, got {case!r}")
    if tangential not in TANGENTIAL:
        raise ValueError(f"tangential must be one of {', '.join(TANGENTIAL)}, got "
                         f"{tangential!r}")
    if damping not in DAMPING:
        raise ValueError(f"damping must be one of {', '.join(DAMPING)}, got {damping!r}")
    mu = _check("mu", mu, 0.0, 10.0, "a coefficient of friction")
    ratio = _check("ratio", ratio, 0.0, 0.999, "Q*/(mu P) short of sliding")
    lift = _check("lift", lift, 0.0, 0.999, "a fraction of the overlap")
    if amplitude is not None:
        amplitude = _check("amplitude", amplitude, 0.0, 1.0, "a displacement [m]")
    if kt is not None:
        kt = _check("kt", kt, 0.0, 1e30, "a stiffness")
    normal = normal or ("hertz/material" if kn is None else "hertz")
    if normal not in NORMAL:
        raise ValueError(f"normal must be one of {', '.join(NORMAL)}, got {normal!r}")
    if (normal == "hertz/material") != (kn is None):
        raise ValueError(f"kn goes with the normal laws hertz and hooke, not with "
                         f"hertz/material (E and nu from the scene); got normal {normal!r}, "
                         f"kn {kn!r}")
    if kn is not None:
        kn = _check("kn", kn, 0.0, 1e30, "a stiffness coefficient")
    frictionless = kn is not None and kt is None
    if frictionless and (case in ("fretting", "path") or angle_deg):
        raise ValueError(f"a {normal} normal law (kn given) needs kt for the tangential "
                         f"motion of {case}: mindlin's NULL takes the materials of "
                         f"hertz/material")
    damping_value = _check("damping_value", damping_value, -1.0, 1e30, "a coefficient")
    if damping in ("tsuji", "coeff_restitution") and not 0 < damping_value <= 1:
        raise ValueError(f"damping_value of {damping} is a restitution in (0, 1], got "
                         f"{damping_value!r}")
    if not isinstance(steps, int) or not 10 <= steps <= 100_000:
        raise ValueError(f"steps must be an integer in [10, 100000], got {steps!r}")
    r1, r2 = _geometry(scene)
    wall = r2 is None
    e, nu = equivalent_material(scene)
    pair = _pair(tangential, e, nu, mu, kt, kn, normal, damping, damping_value, 0.0,
                 attractive, frictionless)
    reach = r1 if wall else r1 + r2
    box = 4 * max(r1, r2 or 0.0)
    lines = [f"# {case}: {scene.name} (written by fem_validation.decks.lammps)",
             "units si", "atom_style sphere", "dimension 3", "boundary f f f",
             "atom_modify map array", "comm_modify vel yes",
             f"region box block {-box!r} {box!r} {-box!r} {box!r} {-box!r} {box!r} units box",
             "create_box 1 box", "pair_style granular", pair]
    name, columns = OUTPUTS[case]
    values: dict = {"E": e, "nu": nu, "mu": mu, "tangential": tangential,
                    "damping": damping, "damping_value": damping_value}
    P = scene.load
    contact = None
    if case != "impact":
        if not (math.isfinite(P) and P > 0):
            raise ValueError(f"scene {scene.name!r} has no target load (give load or approach "
                             f"in the scene file): the {case} case presses to its overlap")
        contact = scene.hertz()
        values.update(overlap=contact.delta, load=contact.load, a=contact.a)
        start = reach + 0.05 * contact.delta   # the moving sphere starts clear of the contact
    else:   # an impact starts LEAD steps before the first touch
        start = reach + LEAD * _impact_step(scene, r1, r2, speed, angle_deg, density, steps)
    if wall:
        wall_pair = pair.split("pair_coeff * * ", 1)[1]
        lines += [f"create_atoms 1 single 0 0 {_fmt(start)} units box",
                  f"set atom 1 diameter {_fmt(2 * r1)} density {_fmt(density)}",
                  "group s1 id 1",
                  f"fix wall all wall/gran granular {wall_pair} zplane 0.0 NULL"]
        mover = "s1"
        rel = ("0.0", "z[1]")
        force = ("fx[1]", "fz[1]")
    else:
        lines += ["create_atoms 1 single 0 0 0 units box",
                  f"create_atoms 1 single 0 0 {_fmt(start)} units box",
                  f"set atom 1 diameter {_fmt(2 * r1)} density {_fmt(density)}",
                  f"set atom 2 diameter {_fmt(2 * r2)} density {_fmt(density)}",
                  "group s1 id 1", "group s2 id 2"]
        mover = "s2"
        rel = ("x[2]-x[1]", "z[2]-z[1]")
        force = ("fx[2]", "fz[2]")
    lines += ["neighbor " + _fmt(0.2 * min(r1, r2 or r1)) + " bin",
              "neigh_modify every 1 delay 0 check yes"]
    # the contact frame at each row: n from body 2 (or the wall) to the moving sphere
    lines += [f"variable rx equal {rel[0]}", f"variable rz equal {rel[1]}",
              "variable r equal sqrt(v_rx^2+v_rz^2)",
              "variable nx equal v_rx/v_r", "variable nz equal v_rz/v_r",
              f"variable delta equal {_fmt(reach)}-v_r",
              f"variable fn equal {force[0]}*v_nx+{force[1]}*v_nz",
              # the tangent along +x turned with the normal: t = (nz, 0, -nx)
              f"variable ft equal {force[0]}*v_nz-{force[1]}*v_nx"]
    if case == "impact":
        lines += _impact(scene, r1, r2, reach, speed, angle_deg, density, steps, values, mover)
        fmt = "%.17g"
        text = ",".join(f"$({v}:{fmt})" for v in
                        ("time", "v_delta", "v_fn", "v_vn", "v_ft", "v_vt", "v_om"))
        lines += [f'fix out all print 1 "{text}" file {name} screen no title '
                  f'"{",".join(columns)}"',
                  f"run {values['run_steps']}"]
        grade = (f"python -m fem_validation grade --impact DIR/{name} --scene SCENE --mass "
                 f"{values['mass']!r} --speed {values['normal_speed']!r}")
        if damping != "none":
            # LAMMPS's damping tsuji E (this release: alpha = poly(E)) is hertz's
            # lammps_tsuji with the same E
            law = "lammps_tsuji" if damping == "tsuji" else damping
            grade += f" --damping {law}:{damping_value!r}"
            if attractive:
                grade += " --damping-attractive"
        if angle_deg:
            grade += f" --mu {mu!r} --angle-deg {angle_deg!r}"
    else:
        delta0 = contact.delta
        d0 = reach - delta0
        dt = 1e-6
        lines += [f"timestep {_fmt(dt)}"]
        if case == "normal":
            end = 1.1 * delta0
            knots = [(0, start), (steps, reach - end)]
            lines += _radial_move(knots, dt, mover, wall)
            text = "$(v_delta:%.17g),$(v_fn:%.17g)"
            lines += ["fix out all print 1 \"" + text + f"\" file {name} screen no title "
                      f'"{",".join(columns)}"', f"run {steps}"]
            grade = f"python -m fem_validation grade --force-approach DIR/{name} --scene SCENE"
        else:
            k = contact.tangential_stiffness()
            slide = 3 * mu * P / (2 * k)   # Mindlin's displacement at sliding
            amp = slide * (1 - (1 - ratio) ** (2 / 3)) if amplitude is None else amplitude
            values.update(amplitude=amp, stiffness=k, slide=slide)
            press = [(0, start, 0.0), (steps, d0, 0.0)]
            if case == "fretting":
                legs = [(amp, d0), (-amp, d0), (amp, d0)]
                mult = (1, 2, 2)
            else:
                d_lift = reach - lift * delta0
                legs = [(amp, d0), (amp, d_lift), (amp, d0)]
                mult = (1, 1, 1)
                values.update(lift_overlap=lift * delta0)
            knots = press
            for (u, d), m in zip(legs, mult, strict=True):
                knots.append((knots[-1][0] + m * steps, d, u))
            lines += _orbit_move(knots, dt, mover, wall)
            lines += [f"run {steps}"]   # pressing: not printed (no tangential motion yet)
            text = "$(v_u:%.17g),$(-v_ft:%.17g),$(v_fn:%.17g)"
            lines += ["fix out all print 1 \"" + text + f"\" file {name} screen no title "
                      f'"{",".join(columns)}"', f"run {knots[-1][0] - steps}"]
            grade = (f"python -m fem_validation grade --history DIR/{name} --scene SCENE "
                     f"--mu {mu!r}")
        values.update(time_step=dt)
    grade += " --out DIR"
    lines.insert(1, f"# grade: {grade}")
    return LammpsDeck(case, "\n".join(lines) + "\n", name, columns, grade, values)


def _radial_move(knots, dt, mover, wall) -> list[str]:
    """``fix move variable`` of the moving sphere along z: distance of centres d(time)."""
    start = knots[0][1]
    d, ddot = _piecewise(knots, dt, "d")
    return [d, ddot, f"variable dz equal v_d-{_fmt(start)}",
            *([] if wall else ["fix hold s1 move linear 0 0 0 units box"]),
            f"fix move {mover} move variable NULL NULL v_dz NULL NULL v_ddot units box"]


def _orbit_move(knots, dt, mover, wall) -> list[str]:
    """``fix move variable`` on the circle of radius d(time) about sphere 1's centre: angle
    phi = u/d over legs where d is constant, so that the tangential displacement LAMMPS
    accumulates (the integral of the tangential velocity) is u; against a wall, a translation
    along x at the height d(time)."""
    start = knots[0][1]
    d, ddot = _piecewise([(n, dd) for n, dd, _ in knots], dt, "d")
    u, udot = _piecewise([(n, uu) for n, _, uu in knots], dt, "u")
    if wall:
        return [d, ddot, u, udot, f"variable dz equal v_d-{_fmt(start)}",
                f"fix move {mover} move variable v_u NULL v_dz v_udot NULL v_ddot units box"]
    phi = [0.0]
    for (_, da, ua), (_, db, ub) in zip(knots, knots[1:], strict=False):
        if ua != ub and da != db:
            raise ValueError("a leg moves both along the normal and tangentially")
        phi.append(phi[-1] + (ub - ua) / da)
    p, pdot = _piecewise([(n, ph) for (n, _, _), ph in zip(knots, phi, strict=True)], dt, "phi")
    return [d, ddot, p, pdot, u,
            "variable dx equal v_d*sin(v_phi)",
            f"variable dz equal v_d*cos(v_phi)-{_fmt(start)}",
            "variable vx equal v_ddot*sin(v_phi)+v_d*cos(v_phi)*v_phidot",
            "variable vz equal v_ddot*cos(v_phi)-v_d*sin(v_phi)*v_phidot",
            "fix hold s1 move linear 0 0 0 units box",
            f"fix move {mover} move variable v_dx NULL v_dz v_vx NULL v_vz units box"]


def _impact_values(scene, r1, r2, speed, angle_deg, density, steps) -> dict:
    """Mass, speeds, Hertz's contact time and the time step of an impact."""
    speed = _check("speed", speed, 0.0, 1000.0, "an impact speed [m/s]")
    try:
        angle_deg = float(angle_deg)
    except (TypeError, ValueError):
        raise ValueError(f"angle_deg must be a number, got {angle_deg!r}") from None
    if not 0.0 <= angle_deg <= 89.999:  # nan too
        raise ValueError(f"angle_deg must be in [0, 89.999] (degrees from the normal), got "
                         f"{angle_deg!r}")
    if angle_deg and r2 is not None:
        raise ValueError("an oblique impact needs a wall (body2 flat): the two-sphere impact "
                         "is head-on")
    density = _check("density", density, 0.0, 1e6, "a density [kg/m^3]")
    m1 = density * 4 / 3 * math.pi * r1 ** 3
    if r2 is None:
        mass = m1
    else:
        m2 = density * 4 / 3 * math.pi * r2 ** 3
        mass = m1 * m2 / (m1 + m2)
    a = math.radians(angle_deg)
    vn, vt = speed, speed * math.tan(a)   # the grader's convention: V normal, A incidence
    kh = 1.0 / scene.hertz(1.0).delta ** 1.5            # F = kh delta^(3/2)
    delta_max = (5 * mass * vn ** 2 / (4 * kh)) ** 0.4   # from the energy
    t_c = 2.9432 * delta_max / vn                        # Hertz's duration, 4 digits
    dt = t_c / (5 * steps)
    return dict(mass=mass, speed=speed, angle_deg=angle_deg, normal_speed=vn,
                tangential_speed=vt, contact_time=t_c, max_overlap=delta_max, time_step=dt,
                run_steps=int(round(1.5 * t_c / dt)) + 2 * LEAD, density=density)


def _impact_step(scene, r1, r2, speed, angle_deg, density, steps) -> float:
    """How far the bodies close in one step before the touch [m]."""
    v = _impact_values(scene, r1, r2, speed, angle_deg, density, steps)
    return v["normal_speed"] * v["time_step"]


def _impact(scene, r1, r2, reach, speed, angle_deg, density, steps, values, mover):
    v = _impact_values(scene, r1, r2, speed, angle_deg, density, steps)
    values.update(v)
    out = [f"timestep {_fmt(v['time_step'])}", "fix nve all nve/sphere",
           "compute spin all property/atom omegay"]
    if r2 is None:
        out += [f"velocity s1 set {_fmt(v['tangential_speed'])} 0.0 "
                f"{_fmt(-v['normal_speed'])} units box",
                "compute om s1 reduce sum c_spin",
                "variable vn equal vz[1]", "variable vt equal vx[1]", "variable om equal c_om"]
    else:
        out += [f"velocity s2 set 0.0 0.0 {_fmt(-v['normal_speed'])} units box",
                "compute om s2 reduce sum c_spin",
                "variable vn equal (vx[2]-vx[1])*v_nx+(vz[2]-vz[1])*v_nz",
                "variable vt equal (vx[2]-vx[1])*v_nz-(vz[2]-vz[1])*v_nx",
                "variable om equal c_om"]
    return out


def write_lammps_deck(deck: LammpsDeck, out) -> Path:
    """Write ``deck.script`` to ``out/in.lammps`` (the folder is made) and return its path.

    Run it with ``lmp -in in.lammps`` in ``out``; the run writes ``out/<deck.output>``.

    Examples
    --------
    >>> import tempfile, hertz
    >>> from fem_validation.scenes import Scene
    >>> ball = hertz.Body.sphere(1e-3, E=70e9, nu=0.33)
    >>> deck = lammps_deck(Scene("al", ball, ball, 1.0), "fretting", mu=0.5)
    >>> path = write_lammps_deck(deck, tempfile.mkdtemp())
    >>> path.name, deck.output
    ('in.lammps', 'history.csv')
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    path = out / "in.lammps"
    path.write_text(deck.script)
    return path
