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

import numpy as np

from .model import DeckModel

#: Length, force and stress factors from SI to each unit system.
UNITS = {"SI": {"length": 1.0, "force": 1.0, "stress": 1.0,
                "names": {"length": "m", "force": "N", "stress": "Pa"}},
         "mm": {"length": 1e3, "force": 1.0, "stress": 1e-6,
                "names": {"length": "mm", "force": "N", "stress": "MPa"}}}


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
    out = [f"** hertz benchmark deck ({dialect}): {s.name}",
           f"** units: {lu}, {fu}, {su}; geometry: {model.geometry}, "
           f"{'quarter' if model.quarter else 'whole'} model, mesh level {model.level}",
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
           + (" times 4 (quarter model)" if model.quarter else "")]
    if command:
        out.append(f"** written by: {command}")
    return out


def write_inp(model: DeckModel, path, units: str = "mm", dialect: str = "calculix",
              command: str | None = None) -> None:
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
        The command line, recorded in a comment.
    """
    if units not in UNITS:
        raise ValueError(f"units must be one of {sorted(UNITS)}, got {units!r}")
    if dialect not in ("calculix", "abaqus"):
        raise ValueError(f"dialect must be 'calculix' or 'abaqus', got {dialect!r}")
    ul, us = UNITS[units]["length"], UNITS[units]["stress"]
    out = deck_header(model, units, dialect, command)
    out += ["*HEADING", f"hertz benchmark {model.scene.name}",
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
            f"{_g(model.penalty * us / ul)}",
            "*CONTACT PAIR, INTERACTION=HERTZ, TYPE=SURFACE TO SURFACE",
            f"{model.slave}, {model.master}",
            "** fixed face, the moved face's lateral motion, symmetry planes",
            "*BOUNDARY", "FIXED, 1, 3, 0.", "MOVED, 1, 2, 0."]
    if model.quarter:
        out += ["SYMX, 1, 1, 0.", "SYMY, 2, 2, 0."]
    if dialect == "calculix":
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
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
