"""CalculiX and Abaqus input decks (.inp) from a :class:`DeckModel`.

Both dialects share the model data (``*NODE``, ``*ELEMENT, TYPE=C3D10``,
``*NSET``, element-face ``*SURFACE``, ``*MATERIAL``, ``*SOLID SECTION``,
``*SURFACE INTERACTION`` with a linear pressure-overclosure penalty,
``*CONTACT PAIR, TYPE=SURFACE TO SURFACE``, the symmetry and fixed
``*BOUNDARY``); they differ in the step: CalculiX takes
``*STATIC, SOLVER=ITERATIVE CHOLESKY`` and the ``*NODE FILE`` / ``*EL FILE`` /
``*CONTACT FILE`` requests of the ASCII .frd, Abaqus ``*OUTPUT, FIELD`` with
``*NODE OUTPUT`` / ``*ELEMENT OUTPUT`` / ``*CONTACT OUTPUT`` for its .odb.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .model import DeckModel, in_range

#: Length, force and stress factors from SI to each unit system.
UNITS = {"SI": {"length": 1.0, "force": 1.0, "stress": 1.0,
                "names": {"length": "m", "force": "N", "stress": "Pa"}},
         "mm": {"length": 1e3, "force": 1.0, "stress": 1e-6,
                "names": {"length": "mm", "force": "N", "stress": "MPa"}}}


#: Increments of the frictional ramp; unloading takes twice as many, reloading one more.
#: ccx 2.20 needed about 100 s of CPU per increment at level 0 (unsymmetric SPOOLES,
#: 4-8 Newton iterations each): 2 gives a loop of 11 path points in about 20 minutes.
DEFAULT_FRICTION_INCREMENTS = 2
#: Stick slope of the penalty friction over the normal penalty slope.
STICK_SLOPE_FACTOR = 1.0
#: The most increments of the ramp a deck takes: the reloading's 2N + 1 fixed increments
#: must fit the tangential steps' ``*STEP, INC=`` (:data:`FRICTION_STEP_INC`), and at about
#: 100 s of ccx CPU an increment at level 0, N = 100 is already a loop of 5N + 1 = 501
#: increments (half a day).  (1e9 wrote increments of 5e-10 that ccx stops after 1000 of.)
MAX_FRICTION_INCREMENTS = 100
#: ``*STEP, INC=`` of the tangential steps: the most increments ccx takes in one step.
FRICTION_STEP_INC = 1000
#: The coefficients of friction a deck takes, [low, high]: measured ones of solids lie
#: between about 0.001 (lubricated or superlubric pairs) and a few (clean metals in vacuum).
FRICTION_MU_RANGE = (1e-3, 10.0)
#: The least Q*/(mu P) at the end of the ramp (the most is 1, excluded: gross sliding):
#: the slip annulus is then about a ratio/3 wide, under 1/3000 of a, far below any element
#: (h0 >= 0.05 a at the deck levels), so that the loop has no area to grade.
MIN_FRICTION_RATIO = 1e-3


@dataclass(frozen=True)
class FrictionPath:
    """The tangential steps of a frictional deck (SI).

    After the normal step, body 1's moved face goes along x to ``peak`` in
    ``increments`` increments (the ramp), to -``peak`` in 2 ``increments``
    (unloading) and back to ``peak`` and one increment beyond in
    2 ``increments`` + 1 (reloading: the loop closes whatever force the
    reloading reaches at ``peak``), with the result written at every increment.

    Attributes
    ----------
    mu : float
        Coefficient of friction [-].
    ratio : float
        Q/(mu P) that Cattaneo-Mindlin gives at ``peak`` [-].
    peak : float
        Imposed tangential displacement at the end of the ramp [m]: Mindlin's
        displacement at Q = ratio mu P less the Cerruti settlement
        Q (3 - 2 nu)/(8 pi G H) of each clamped block of depth H.
    increments : int
        Increments of the ramp.
    stick_slope : float
        CalculiX's stick slope lambda [Pa/m]: the tangential penalty, shear
        stress per unit of elastic slip.
    """

    mu: float
    ratio: float
    peak: float
    increments: int
    stick_slope: float


def check_mu(mu) -> float:
    """``mu`` if it is a coefficient of friction in :data:`FRICTION_MU_RANGE`.

    Raises
    ------
    ValueError
        Naming the parameter, the range and the value.
    """
    low, high = FRICTION_MU_RANGE
    if not in_range(mu, low, high):
        raise ValueError(f"mu must be a finite number in [{low:g}, {high:g}] (a coefficient "
                         f"of friction of solids), got {mu!r}")
    return mu


def check_ratio(ratio) -> float:
    """``ratio`` (Q*/(mu P) at the end of the ramp) if it is in [:data:`MIN_FRICTION_RATIO`, 1).

    Raises
    ------
    ValueError
        Naming the parameter, the range and the value.
    """
    if not in_range(ratio, MIN_FRICTION_RATIO, 1.0, open_high=True):
        raise ValueError(f"friction ratio must be in (0, 1), at least {MIN_FRICTION_RATIO:g} "
                         f"(Q*/(mu P) at the end of the ramp: 1 is gross sliding, below "
                         f"{MIN_FRICTION_RATIO:g} the slip annulus is far below an element), "
                         f"got {ratio!r}")
    return ratio


def check_increments(increments) -> int:
    """``increments`` (of the ramp) if it is an integer in [1, :data:`MAX_FRICTION_INCREMENTS`].

    Raises
    ------
    ValueError
        Naming the parameter, the range and the value.
    """
    if not in_range(increments, 1, MAX_FRICTION_INCREMENTS, kind=int):
        raise ValueError(f"friction increments must be an integer from 1 to "
                         f"{MAX_FRICTION_INCREMENTS} (the ramp's; the loop takes 5N + 1 "
                         f"increments of ccx, each about 100 s of CPU at level 0), got "
                         f"{increments!r}")
    return increments


def check_friction(mu, ratio=0.8, increments=DEFAULT_FRICTION_INCREMENTS) -> None:
    """:func:`check_mu`, :func:`check_ratio` and :func:`check_increments` (before meshing)."""
    check_mu(mu)
    check_ratio(ratio)
    check_increments(increments)


def friction_path(model: DeckModel, mu: float, ratio: float = 0.8,
                  increments: int = DEFAULT_FRICTION_INCREMENTS,
                  stick_slope_factor: float = STICK_SLOPE_FACTOR) -> FrictionPath:
    """The tangential path of a frictional deck on a half model loaded along x.

    Parameters
    ----------
    model : DeckModel
        A half model of paraboloid-faced blocks (:func:`~.model.half_model`).
    mu : float
        Coefficient of friction, in :data:`FRICTION_MU_RANGE` ([0.001, 10]).
    ratio : float
        Q*/(mu P) at the end of the ramp, in [:data:`MIN_FRICTION_RATIO`, 1)
        ([0.001, 1)).
    increments : int
        Ramp increments, from 1 to :data:`MAX_FRICTION_INCREMENTS` (100).
    stick_slope_factor : float
        Stick slope over the normal penalty slope, > 0.  Default 1: the
        tangential penalty equals the normal one (10 E*/h0), as in
        :mod:`fem_validation.solvers.friction`; it adds an elastic slip q/lambda, about
        1% of h0 at q = mu p0 / 10 E* scale, far below Mindlin's displacement.

    Raises
    ------
    ValueError
        Naming the parameter and the value.
    """
    from ..halfspace import cerruti_settlement
    from ..solvers.friction import hertz_direction

    check_friction(mu, ratio, increments)
    if isinstance(stick_slope_factor, bool) or not (
            isinstance(stick_slope_factor, int | float) and math.isfinite(stick_slope_factor)
            and stick_slope_factor > 0):
        raise ValueError(f"stick_slope_factor must be a finite number > 0, got "
                         f"{stick_slope_factor!r}")
    if model.symmetry == "quarter" or model.geometry != "paraboloid-blocks":
        raise ValueError(f"a frictional deck needs the half or whole model of paraboloid-faced "
                         f"blocks (a load along x breaks the symmetry in x = 0), got a "
                         f"{model.symmetry} model of {model.geometry}")
    scene = model.scene
    c = model.contact
    force = ratio * mu * c.load
    t = c.tangential(force, mu, hertz_direction(scene, "x"))
    depth = model.info["block_depth"]
    missed = sum(cerruti_settlement(force, b.E, b.nu, depth) for b in (scene.body1, scene.body2))
    peak = float(t.displacement) - missed
    slope = stick_slope_factor * model.penalty
    if not (math.isfinite(peak) and peak > 0 and math.isfinite(slope) and slope > 0):
        raise ValueError(f"scene {scene.name!r}: the tangential path is degenerate (peak "
                         f"displacement {peak!r} m, stick slope {slope!r} Pa/m): check the "
                         f"friction options and the scene")
    return FrictionPath(float(mu), float(ratio), peak, increments, slope)


#: The longest scene name written into a deck's comments and title [characters].
MAX_NAME_CHARS = 80


def one_line(text, limit: int | None = MAX_NAME_CHARS) -> str:
    """``text`` made safe for a comment or title line of a deck.

    Every character outside printable ASCII (a line break, a tab, a control
    character, anything else: .inp files are ASCII) becomes "?", leading
    blanks and "*" go (a line starting with "*" is a keyword), and the result is
    cut to ``limit`` characters.  A scene name holding a line break and
    ``*INCLUDE, INPUT=...`` thus stays inside its comment.

    Examples
    --------
    >>> one_line("ball\\n*INCLUDE, INPUT=/etc/passwd")
    'ball?*INCLUDE, INPUT=/etc/passwd'
    >>> one_line("*STEP")
    'STEP'
    """
    out = "".join(ch if " " <= ch <= "~" else "?" for ch in str(text)).lstrip(" *")
    if limit is not None and len(out) > limit:
        out = out[:limit - 3] + "..."
    return out or "?"


def _lines(ids, per_line: int = 16) -> str:
    ids = list(ids)
    return "\n".join(", ".join(str(i) for i in ids[k:k + per_line])
                     for k in range(0, len(ids), per_line))


def _g(x: float) -> str:
    return f"{x:.12g}"


def deck_header(model: DeckModel, units: str, dialect: str, command: str | None) -> list[str]:
    """Comment lines stating the problem and the Hertz values expected."""
    u = UNITS[units]
    lu, fu, su = (u["names"][k] for k in ("length", "force", "stress"))
    ul, us = u["length"], u["stress"]
    c = model.contact
    s = model.scene
    out = [f"** hertz benchmark deck ({dialect}): {one_line(s.name)}",
           f"** units: {lu}, {fu}, {su}; geometry: {model.geometry}, "
           f"{model.symmetry} model, mesh level {model.level}",
           f"** body 1: Rx = {s.body1.Rx * ul:g}, Ry = {s.body1.Ry * ul:g} {lu}, "
           f"E = {s.body1.E * us:g} {su}, nu = {s.body1.nu:g}",
           f"** body 2: Rx = {s.body2.Rx * ul:g}, Ry = {s.body2.Ry * ul:g} {lu}, "
           f"E = {s.body2.E * us:g} {su}, nu = {s.body2.nu:g}, "
           f"angle {math.degrees(s.angle):g} deg",
           f"** Hertz at the target load P = {c.load:.6g} {fu} (whole model): "
           f"a = {c.a * ul:.6g}, b = {c.b * ul:.6g} {lu}, p0 = {c.p0 * us:.6g} {su}, "
           f"approach {c.delta * ul:.6g} {lu}",
           f"** prescribed approach of MOVED: {model.approach * ul:.6g} {lu} (Hertz's less the "
           f"Boussinesq settlement the clamped finite bodies do not show)",
           f"** penalty: linear pressure-overclosure slope {model.penalty * us / ul:.6g} "
           f"{su}/{lu} = {model.info['penalty_factor']:g} E*/h0, h0 = {model.h0 * ul:.4g} {lu}",
           f"** slave surface {model.slave}, master {model.master}; "
           f"the total force is the reaction of MOVED"
           + (f" times {model.multiplicity} ({model.symmetry} model)"
              if model.multiplicity > 1 else "")]
    if command:
        out.append(f"** written by: {one_line(command, None)}")
    return out


def write_inp(model: DeckModel, path, units: str = "mm", dialect: str = "calculix",
              command: str | None = None, friction: FrictionPath | None = None) -> None:
    """Write the deck.

    Parameters
    ----------
    model : DeckModel
    path : path-like
        The .inp file.
    units : {"mm", "SI"}
        mm, N, MPa or m, N, Pa.
    dialect : {"calculix", "abaqus"}
    command : str, optional
        The command line, recorded in a comment (made one line of printable
        ASCII by :func:`one_line`, as the scene's name is).
    friction : FrictionPath, optional
        Coulomb friction (``*FRICTION``) and the tangential steps after the
        normal one (CalculiX only).
    """
    if friction is not None and dialect != "calculix":
        raise ValueError(f"friction decks are written for CalculiX only, got dialect "
                         f"{dialect!r}")
    if units not in UNITS:
        raise ValueError(f"units must be one of {sorted(UNITS)}, got {units!r}")
    if dialect not in ("calculix", "abaqus"):
        raise ValueError(f"dialect must be 'calculix' or 'abaqus', got {dialect!r}")
    ul, us = UNITS[units]["length"], UNITS[units]["stress"]
    out = deck_header(model, units, dialect, command)
    out += ["*HEADING", f"hertz benchmark {one_line(model.scene.name)}",
            "*NODE, NSET=NALL"]
    xyz = model.nodes * ul
    out += [f"{i + 1}, {_g(x)}, {_g(y)}, {_g(z)}" for i, (x, y, z) in enumerate(xyz)]
    for body in (1, 2):
        idx = np.nonzero(model.body == body)[0]
        out.append(f"*ELEMENT, TYPE=C3D10, ELSET=BODY{body}")
        conn = model.elements[idx] + 1
        out += [f"{e + 1}, " + ", ".join(map(str, row)) for e, row in zip(idx, conn,
                                                                          strict=True)]
    for name, nodes in model.node_sets.items():
        out += [f"*NSET, NSET={name}", _lines(nodes + 1)]
    for name, (elem, face) in model.surfaces.items():
        out.append(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
        out += [f"{e + 1}, S{f}" for e, f in zip(elem, face, strict=True)]
    for body, b in ((1, model.scene.body1), (2, model.scene.body2)):
        out += [f"*MATERIAL, NAME=MATERIAL{body}", "*ELASTIC", f"{_g(b.E * us)}, {_g(b.nu)}",
                f"*SOLID SECTION, ELSET=BODY{body}, MATERIAL=MATERIAL{body}"]
    out += ["*SURFACE INTERACTION, NAME=HERTZ",
            "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
            f"{_g(model.penalty * us / ul)}"]
    if friction is not None:
        out += ["*FRICTION", f"{_g(friction.mu)}, {_g(friction.stick_slope * us / ul)}"]
    out += ["*CONTACT PAIR, INTERACTION=HERTZ, TYPE=SURFACE TO SURFACE",
            f"{model.slave}, {model.master}",
            "** fixed face, the moved face's lateral motion, symmetry planes",
            "*BOUNDARY", "FIXED, 1, 3, 0.",
            "MOVED, 1, 2, 0." if friction is None else "MOVED, 2, 2, 0."]
    if model.symmetry == "quarter":
        out += ["SYMX, 1, 1, 0.", "SYMY, 2, 2, 0."]
    elif model.symmetry == "half":
        out += ["SYMY, 2, 2, 0."]
    if friction is not None:
        out += _friction_steps(model, friction, ul)
    elif dialect == "calculix":
        out += ["*STEP, INC=100", "*STATIC, SOLVER=ITERATIVE CHOLESKY", "1., 1., 1e-5, 1.",
                "*BOUNDARY", f"MOVED, 3, 3, {_g(-model.approach * ul)}",
                "*NODE FILE", "U, RF", "*EL FILE", "S", "*CONTACT FILE", "CDIS, CSTR",
                "*NODE PRINT, NSET=MOVED, TOTALS=ONLY", "RF", "*END STEP"]
    else:
        out += ["*STEP, NLGEOM=NO, INC=100", "*STATIC", "1., 1., 1e-5, 1.",
                "*BOUNDARY", f"MOVED, 3, 3, {_g(-model.approach * ul)}",
                "*OUTPUT, FIELD", "*NODE OUTPUT", "U, RF", "*ELEMENT OUTPUT",
                "S", "*CONTACT OUTPUT", "CSTRESS, CDISP",
                "*NODE PRINT, NSET=MOVED, TOTALS=YES", "RF", "*END STEP"]
    with open(path, "w", encoding="ascii") as f:
        f.write("\n".join(out) + "\n")


def _friction_steps(model: DeckModel, friction: FrictionPath, ul: float) -> list[str]:
    """The normal step, then the ramp, unloading and reloading along x in fixed increments."""
    n = friction.increments
    peak = _g(friction.peak * ul)
    out = [f"** Coulomb friction mu = {friction.mu:g}, stick slope {friction.stick_slope:.6g} "
           f"Pa/m; path of MOVED along x: 0 -> {peak} ({n} increments) -> -{peak} ({2 * n}) "
           f"-> {peak} ({2 * n}); Cattaneo-Mindlin gives Q = {friction.ratio:g} mu P at "
           f"{peak} (Mindlin's displacement less the clamped blocks' Cerruti settlement)"]
    output = ["*NODE FILE", "U, RF", "*CONTACT FILE", "CDIS, CSTR",
              "*NODE PRINT, NSET=MOVED, TOTALS=ONLY", "RF"]
    out += ["*STEP, INC=100", "*STATIC", "1., 1., 1e-5, 1.", "*BOUNDARY",
            "MOVED, 1, 1, 0.", f"MOVED, 3, 3, {_g(-model.approach * ul)}", *output,
            "*END STEP"]
    # the reloading goes one increment past the peak, so that the loop closes whatever
    # the force reached there (Masing's memory: the path then continues on the ramp's curve)
    beyond = _g(friction.peak * (1 + 1 / n) * ul)
    if not 2 * n + 1 <= FRICTION_STEP_INC:
        raise ValueError(f"friction increments must be at most {(FRICTION_STEP_INC - 1) // 2} "
                         f"(the reloading's 2N + 1 must fit *STEP, INC={FRICTION_STEP_INC}), "
                         f"got {n!r}")
    for target, count in ((peak, n), (f"-{peak}", 2 * n), (beyond, 2 * n + 1)):
        out += [f"*STEP, INC={FRICTION_STEP_INC}", "*STATIC, DIRECT", f"{_g(1 / count)}, 1.",
                "*BOUNDARY",
                f"MOVED, 1, 1, {target}", *output, "*END STEP"]
    return out
