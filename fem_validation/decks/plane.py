"""2-D benchmark decks: plane strain (parallel cylinders, a cylinder on a block) and
axisymmetric (spheres, a sphere on a block), for CalculiX or Abaqus (.inp).

``python -m fem_validation deck --scene FILE --format calculix --model plane-strain --out DIR``
writes DIR/hertz.inp.  The model, in the x-y plane, load along y (an axisymmetric model: x
the radius, y the axis, as both codes require):

* body 1 above the first point of contact (the origin), body 2 below; a body of finite
  radius R is the quarter disc x in [0, R] next to the contact, cut along its diameter (the
  Abaqus Benchmarks' "Hertz contact problem": two cylinders, displacement imposed on a
  diametric cut); a flat body is a block 2 R wide and deep (R the other body's radius);
* plane strain: a half model (x >= 0, the plane x = 0 of symmetry), thickness 1 (the force
  of the run per unit of the length unit); axisymmetric: the axis at x = 0;
* 4-node quadrilaterals (CPE4 / CAX4) from gmsh, all quadrangles, of size
  h = b / (10 * 2**level) within 1.5 b of the first point of contact (b the half-width or
  contact radius of Hertz at the target), growing to R / 8;
* frictionless surface-to-surface penalty contact, slope PENALTY_FACTOR E*/h, slave on
  body 1 near the contact, master body 2;
* body 1's cut (or far face) moved along -y by an estimate of the approach reaching the
  target, body 2's clamped.  A line contact's approach depends on the bodies' sizes:
  the estimate is Johnson's for discs and blocks (*Contact Mechanics*, eq. 5.36), good to
  some percent; the grade evaluates Hertz at the force the run reached (its reaction), so
  the target need not be met.

The grade reads the run back from DIR/hertz.frd and this deck beside it
(:mod:`fem_validation.readers.calculix_plane`).
"""

from __future__ import annotations

import math
from pathlib import Path

from ..results.plane import PlaneScene
from .inp import UNITS, one_line
from .model import PENALTY_FACTOR

__all__ = ["MAX_PLANE_LEVEL", "write_plane_deck"]

#: The finest mesh level (level 5: h = b / 320).
MAX_PLANE_LEVEL = 5
#: The largest half-width (contact radius) over the smallest radius a deck takes: beyond,
#: the quarter discs' refined zone reaches their cut (and Hertz's theory is far from its
#: range; Code_Aster's SSNV104 runs a/R = 0.2).
MAX_WIDTH_OVER_R = 0.25


def _check(scene: PlaneScene, level: int) -> None:
    if not (isinstance(level, int) and 0 <= level <= MAX_PLANE_LEVEL):
        raise ValueError(f"level must be an integer from 0 to {MAX_PLANE_LEVEL}, got {level!r}")
    for i, b in ((1, scene.body1), (2, scene.body2)):
        if b.Rx < 0:
            raise ValueError(f"body{i}: a concave body (Rx = {b.Rx:g} m) is not written as a "
                             f"2-D deck (a disc or a block only)")
    if not (math.isfinite(scene.load) and scene.load > 0):
        target = ("load_per_length [N/m]" if scene.model == "plane-strain"
                  else "load [N] or approach [m]")
        raise ValueError(f"scene {scene.name!r}: a deck needs a target ({target} > 0), got "
                         f"{scene.load!r}")
    width = _width(scene)
    ratio = width / scene.smallest_radius
    if ratio > MAX_WIDTH_OVER_R:
        w = "b" if scene.model == "plane-strain" else "a"
        raise ValueError(f"scene {scene.name!r}: Hertz's {w}/R = {ratio:.3g} at the target "
                         f"is above {MAX_WIDTH_OVER_R} (the refined zone would reach the "
                         f"bodies' cut): lower the load")


def _quiet_hertz(scene: PlaneScene):
    """Hertz at the target, its validity warning silenced (the deck checks b/R itself)."""
    import warnings

    import hertz

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hertz.HertzValidityWarning)
        return scene.hertz(scene.load)


def _width(scene: PlaneScene) -> float:
    c = _quiet_hertz(scene)
    return float(c.half_width if scene.model == "plane-strain" else c.a)


def _approach(scene: PlaneScene, size: float) -> float:
    """An estimate of the approach reaching the target [m] (see the module's notes)."""
    c = _quiet_hertz(scene)
    if scene.model == "axisymmetric":
        return float(c.delta)
    b = float(c.half_width)
    total = 0.0
    for body in (scene.body1, scene.body2):
        length = body.Rx if math.isfinite(body.Rx) else size
        total += scene.load * (1 - body.nu ** 2) / (math.pi * body.E) * (
            2 * math.log(4 * length / b) - 1)
    return total


def _mesh(scene: PlaneScene, h: float, size: float, width: float):
    """(nodes {tag: (x, y)}, quads of body 1, quads of body 2) in metres."""
    import gmsh

    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("hertz2d")
        occ = gmsh.model.occ
        surfaces = []
        for sign, body in ((1, scene.body1), (-1, scene.body2)):
            if math.isfinite(body.Rx):
                r = body.Rx
                disc = occ.addDisk(0, sign * r, 0, r, r)
                box = occ.addRectangle(0, 0 if sign > 0 else -r, 0, r, r)
                part, _ = occ.intersect([(2, disc)], [(2, box)])
                surfaces.append(part[0][1])
            else:
                surfaces.append(occ.addRectangle(0, 0 if sign > 0 else -size, 0, size, size))
        occ.synchronize()
        origin = [tag for _, tag in gmsh.model.getEntities(0)
                  if max(abs(v) for v in gmsh.model.getValue(0, tag, [])) < 1e-12 * size]
        field = gmsh.model.mesh.field
        dist = field.add("Distance")
        field.setNumbers(dist, "PointsList", origin)
        thr = field.add("Threshold")
        field.setNumber(thr, "InField", dist)
        field.setNumber(thr, "SizeMin", 2 * h)  # the subdivision halves every size
        field.setNumber(thr, "SizeMax", 2 * size / 8)
        field.setNumber(thr, "DistMin", 1.5 * width)  # the contact at size h throughout
        field.setNumber(thr, "DistMax", 0.6 * size)
        field.setAsBackgroundMesh(thr)
        for key, value in (("Mesh.MeshSizeExtendFromBoundary", 0),
                           ("Mesh.MeshSizeFromPoints", 0), ("Mesh.RecombineAll", 1),
                           ("Mesh.SubdivisionAlgorithm", 1), ("Mesh.Algorithm", 8)):
            gmsh.option.setNumber(key, value)
        gmsh.model.mesh.generate(2)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        nodes = {int(t): (coords[3 * i], coords[3 * i + 1]) for i, t in enumerate(tags)}
        quads = []
        for surf in surfaces:
            types, _, conn = gmsh.model.mesh.getElements(2, surf)
            quads.append([list(map(int, conn[i][k:k + 4])) for i, t in enumerate(types)
                          if t == 3 for k in range(0, len(conn[i]), 4)])
    finally:
        gmsh.finalize()
    return nodes, quads


def write_plane_deck(scene: PlaneScene, out, dialect: str = "calculix", units: str = "mm",
                     level: int = 1, penalty_factor: float = PENALTY_FACTOR,
                     command: str | None = None) -> tuple[Path, dict]:
    """Write DIR/hertz.inp of a 2-D scene; (its path, a summary dict).

    Parameters
    ----------
    scene : PlaneScene
        With its target (``load``: N/m plane strain, N axisymmetric).
    out : path
        The folder (it exists).
    dialect : {"calculix", "abaqus"}
    units : {"mm", "SI"}
    level : int
        0 to MAX_PLANE_LEVEL: h = b / (10 * 2**level) at the contact.
    penalty_factor : float
        Penalty slope over E*/h.
    command : str, optional
        Recorded in a comment.

    Raises
    ------
    ValueError
        A concave body, no target, a contact too large (b/R or a/R above
        MAX_WIDTH_OVER_R), a level out of range, an unknown dialect or units.
    """
    if dialect not in ("calculix", "abaqus"):
        raise ValueError(f"dialect must be calculix or abaqus, got {dialect!r}")
    if units not in UNITS:
        raise ValueError(f"units must be one of {sorted(UNITS)}, got {units!r}")
    _check(scene, level)
    ul, us = UNITS[units]["length"], UNITS[units]["stress"]
    lu, su = UNITS[units]["names"]["length"], UNITS[units]["names"]["stress"]
    width = _width(scene)
    finite = [b.Rx for b in (scene.body1, scene.body2) if math.isfinite(b.Rx)]
    size = 2 * max(finite)
    h = width / (10 * 2 ** level)
    nodes, (q1, q2) = _mesh(scene, h, size, width)
    kind = "CPE4" if scene.model == "plane-strain" else "CAX4"
    e_star = float(_quiet_hertz(scene).e_star)
    slope = penalty_factor * e_star / h
    approach = _approach(scene, size)
    tol = 1e-9 * size

    def ccw(q):
        (x1, y1), (x2, y2), (x3, y3) = (nodes[n] for n in q[:3])
        return q if (x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1) > 0 else q[::-1]

    rows, eid = [], 0
    for quads in (q1, q2):
        body = []
        for q in quads:
            eid += 1
            body.append((eid, ccw(q)))
        rows.append(body)

    def faces(body, on):
        return [(e, f + 1) for e, q in body for f in range(4)
                if on(*nodes[q[f]]) and on(*nodes[q[(f + 1) % 4]])]

    reach = min(8 * width, 0.5 * min(finite))

    def surface(body_index, b):
        sign = 1 if body_index == 0 else -1
        if math.isfinite(b.Rx):
            r = b.Rx
            return faces(rows[body_index], lambda x, y: abs(x * x + (y - sign * r) ** 2 - r * r)
                         < 1e-6 * r * r and x <= reach and sign * y < 0.5 * r)
        return faces(rows[body_index], lambda x, y: abs(y) < tol and x <= reach)

    used = sorted({n for body in rows for _, q in body for n in q})
    lines = [f"** hertz 2-D benchmark deck ({dialect}, {scene.model}): {one_line(scene.name)}",
             f"** units: {lu}, N, {su}; {kind} elements, h = {h * ul:.4g} {lu} at the contact "
             f"(level {level})",
             f"** Hertz at the target {scene.load:.6g} "
             f"{'N/m' if scene.model == 'plane-strain' else 'N'}: "
             f"{'b' if scene.model == 'plane-strain' else 'a'} = {width * ul:.6g} {lu}",
             f"** prescribed approach of MOVED: {approach * ul:.6g} {lu} (an estimate: the "
             f"grade takes the force reached, the reaction"
             + (", per unit thickness, of a half model: times 2)" if scene.model ==
                "plane-strain" else ", of the full circle)"),
             f"** penalty slope {slope * us / ul:.6g} {su}/{lu} = {penalty_factor:g} E*/h"]
    if command:
        lines.append(f"** written by: {one_line(command, None)}")
    lines += ["*HEADING", f"hertz 2-D benchmark {one_line(scene.name)}", "*NODE, NSET=NALL"]
    lines += [f"{n}, {nodes[n][0] * ul:.12g}, {nodes[n][1] * ul:.12g}" for n in used]
    for i, body in enumerate(rows, 1):
        lines.append(f"*ELEMENT, TYPE={kind}, ELSET=BODY{i}")
        lines += [f"{e}, " + ", ".join(map(str, q)) for e, q in body]

    def nset(name, ids):
        out_ = [f"*NSET, NSET={name}"]
        out_ += [", ".join(map(str, ids[k:k + 16])) for k in range(0, len(ids), 16)]
        return out_

    top = max(y for _, y in nodes.values())
    bottom = min(y for _, y in nodes.values())
    lines += nset("AXIS", [n for n in used if abs(nodes[n][0]) < tol])
    lines += nset("MOVED", [n for n in used if abs(nodes[n][1] - top) < tol])
    lines += nset("FIXED", [n for n in used if abs(nodes[n][1] - bottom) < tol])
    for name, fs in (("SLAVE", surface(0, scene.body1)), ("MASTER", surface(1, scene.body2))):
        lines.append(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
        lines += [f"{e}, S{f}" for e, f in fs]
    for i, b in ((1, scene.body1), (2, scene.body2)):
        lines += [f"*MATERIAL, NAME=MATERIAL{i}", "*ELASTIC", f"{b.E * us:.12g}, {b.nu:.12g}",
                  f"*SOLID SECTION, ELSET=BODY{i}, MATERIAL=MATERIAL{i}", "1."]
    lines += ["*SURFACE INTERACTION, NAME=HERTZ",
              "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{slope * us / ul:.12g}",
              "*CONTACT PAIR, INTERACTION=HERTZ, TYPE=SURFACE TO SURFACE", "SLAVE, MASTER",
              "** the axis (symmetry plane) held in x; the cuts held along y only (free to "
              "** expand: SSNV104's conditions)",
              "*BOUNDARY", "AXIS, 1, 1, 0.", "FIXED, 2, 2, 0."]
    move = f"MOVED, 2, 2, {-approach * ul:.12g}"
    if dialect == "calculix":
        lines += ["*STEP, INC=100", "*STATIC", "1., 1., 1e-5, 1.", "*BOUNDARY", move,
                  "*NODE FILE", "RF", "*EL FILE", "S", "*CONTACT FILE", "CDIS, CSTR",
                  "*END STEP"]
    else:
        lines += ["*STEP, NLGEOM=NO, INC=100", "*STATIC", "1., 1., 1e-5, 1.", "*BOUNDARY",
                  move, "*OUTPUT, FIELD", "*NODE OUTPUT", "U, RF", "*ELEMENT OUTPUT", "S",
                  "*CONTACT OUTPUT", "CSTRESS, CDISP", "*END STEP"]
    path = Path(out) / "hertz.inp"
    with open(path, "w", encoding="ascii") as f:
        f.write("\n".join(lines) + "\n")
    return path, {"nodes": len(used), "elements": eid, "h": h, "width": width,
                  "approach": approach, "kind": kind}


def plane_deck(scene_path, model: str, dialect: str, out, units: str = "mm", level: int = 1,
               penalty_factor: float = PENALTY_FACTOR, command: str | None = None) -> str:
    """``deck --model plane-strain|axisymmetric``: read the scene, write DIR/hertz.inp; the
    line to print.  ``out`` must exist (the command checks it)."""
    if dialect not in ("calculix", "abaqus"):
        raise ValueError(f"--model {model} writes a CalculiX or Abaqus deck (--format "
                         f"calculix or abaqus), not {dialect}")
    from ..results.plane import plane_scene_from_toml

    scene = plane_scene_from_toml(scene_path, model)
    path, info = write_plane_deck(scene, out, dialect, units, level, penalty_factor, command)
    unit = UNITS[units]["names"]["length"]
    w = "b" if model == "plane-strain" else "a"
    return (f"{scene.name}: {model}, {info['kind']}, {info['nodes']} nodes, "
            f"{info['elements']} elements; Hertz {w} = "
            f"{info['width'] * UNITS[units]['length']:.5g} {unit} at {scene.load:.5g} "
            f"{'N/m' if model == 'plane-strain' else 'N'}; wrote {path}")
