"""Write and run the hand-built 2-D CalculiX runs of tests/data/calculix_plane/.

Two decks as an analyst writes them, independent of ``fem_validation.decks`` (so that the
grader is tested on files it did not write): a steel cylinder (R = 10 mm) on a steel block
in plane strain (CPE4, half model, x >= 0) and a steel sphere (R = 10 mm) on a steel block,
axisymmetric (CAX4, x the radius, y the axis).  The same gmsh mesh serves both: a quarter
disc (body 1, centre (0, R), the diametric cut y = R on top) on a rectangle (body 2,
20 x 20 mm, bottom clamped), all quadrangles, graded to 0.02 mm at the contact point.
Units mm, N, MPa; displacement control (the cut moves down by ``--approach``); the force is
the reaction of the cut.  Frictionless penalty surface-to-surface contact, slope
10 E*/h at the contact (h the element size there).

Usage (a few seconds of ccx on one core each; writes DIR/plane_strain.{inp,frd},
DIR/axisymmetric.{inp,frd} and the convention check DIR/cax_rod.{inp,frd,dat}; the
committed files are the output of the defaults)::

    python tools/make_plane_runs.py --out tests/data/calculix_plane
"""

from __future__ import annotations

import argparse
import os
import subprocess
from pathlib import Path

R = 10.0          # mm, the cylinder's or sphere's radius
WIDTH = 20.0      # mm, the block's half-width (plane strain) or radius (axisymmetric)
DEPTH = 20.0      # mm, the block's depth
H_CONTACT = 0.04  # mm, gmsh's size at the contact point (halved by the subdivision)
H_FAR = 3.0       # mm (halved likewise)
E, NU = 210000.0, 0.3  # MPa
#: The imposed displacement of the cut [mm] per model: about 0.5 mm of half-width or
#: contact radius (b/R = a/R = 0.05).
APPROACH = {"plane_strain": 0.030, "axisymmetric": 0.030}


def mesh():
    """Nodes {number: (x, y)} and the quadrangles of body 1 and body 2 (node numbers,
    counter-clockwise)."""
    import gmsh

    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add("plane")
    occ = gmsh.model.occ
    disc = occ.addDisk(0, R, 0, R, R)
    box = occ.addRectangle(0, 0, 0, R, R)  # the lower-right quarter of the disc
    quarter, _ = occ.intersect([(2, disc)], [(2, box)])
    block = occ.addRectangle(0, -DEPTH, 0, WIDTH, DEPTH)
    occ.synchronize()
    origin = [tag for dim, tag in gmsh.model.getEntities(0)
              if max(abs(c) for c in gmsh.model.getValue(0, tag, [])) < 1e-9]
    field = gmsh.model.mesh.field
    dist = field.add("Distance")
    field.setNumbers(dist, "PointsList", origin)
    thr = field.add("Threshold")
    field.setNumber(thr, "InField", dist)
    field.setNumber(thr, "SizeMin", H_CONTACT)
    field.setNumber(thr, "SizeMax", H_FAR)
    field.setNumber(thr, "DistMin", 0.8)
    field.setNumber(thr, "DistMax", 12.0)
    field.setAsBackgroundMesh(thr)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.RecombineAll", 1)
    gmsh.option.setNumber("Mesh.SubdivisionAlgorithm", 1)  # all quadrangles
    gmsh.option.setNumber("Mesh.Algorithm", 8)
    gmsh.model.mesh.generate(2)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    nodes = {int(t): (coords[3 * i], coords[3 * i + 1]) for i, t in enumerate(tags)}
    bodies = []
    for surf in (quarter[0][1], block):
        types, _, conn = gmsh.model.mesh.getElements(2, surf)
        quads = [list(map(int, conn[i][k:k + 4])) for i, t in enumerate(types) if t == 3
                 for k in range(0, len(conn[i]), 4)]
        bodies.append(quads)
    gmsh.finalize()
    return nodes, bodies


def _ccw(nodes, quad):
    (x1, y1), (x2, y2), (x3, y3) = (nodes[n] for n in quad[:3])
    return quad if (x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1) > 0 else quad[::-1]


def _faces(nodes, quads, on):
    """(element, face) of the quadrangle edges with both nodes where on(x, y)."""
    out = []
    for eid, q in quads:
        for f in range(4):
            a, b = q[f], q[(f + 1) % 4]
            if on(*nodes[a]) and on(*nodes[b]):
                out.append((eid, f + 1))
    return out


def write_deck(path: Path, model: str, approach: float):
    """The .inp of ``model`` ("plane_strain" or "axisymmetric")."""
    nodes, (cyl, blk) = mesh()
    kind = {"plane_strain": "CPE4", "axisymmetric": "CAX4"}[model]
    eid = 0
    body = []
    for quads in (cyl, blk):
        rows = []
        for q in quads:
            eid += 1
            rows.append((eid, _ccw(nodes, q)))
        body.append(rows)
    tol = 1e-7
    # the contact lines: the cylinder's arc within 3 mm of the axis, the block's top
    arc = _faces(nodes, body[0], lambda x, y: abs(x * x + (y - R) ** 2 - R * R) < 1e-4 * R * R
                 and x < 3.0 and y < R - 1.0)
    top = _faces(nodes, body[1], lambda x, y: abs(y) < tol and x < 4.0)
    used = {n for rows in body for _, q in rows for n in q}
    lines = ["** hand-built 2-D Hertz run (tools/make_plane_runs.py): " + model,
             "*NODE, NSET=NALL"]
    lines += [f"{n}, {nodes[n][0]:.10g}, {nodes[n][1]:.10g}" for n in sorted(used)]
    for name, rows in (("CYL", body[0]), ("BLOCK", body[1])):
        lines.append(f"*ELEMENT, TYPE={kind}, ELSET={name}")
        lines += [f"{e}, " + ", ".join(map(str, q)) for e, q in rows]
    axis = sorted(n for n in used if abs(nodes[n][0]) < tol)
    cut = sorted(n for n in used if abs(nodes[n][1] - R) < tol)
    bottom = sorted(n for n in used if abs(nodes[n][1] + DEPTH) < tol)
    for name, ids in (("AXIS", axis), ("CUT", cut), ("BOTTOM", bottom)):
        lines.append(f"*NSET, NSET={name}")
        lines += [", ".join(map(str, ids[i:i + 12])) for i in range(0, len(ids), 12)]
    for name, faces in (("SARC", arc), ("STOP", top)):
        lines.append(f"*SURFACE, NAME={name}, TYPE=ELEMENT")
        lines += [f"{e}, S{f}" for e, f in faces]
    e_star = E / (2 * (1 - NU * NU))
    slope = 10 * e_star / (H_CONTACT / 2)  # the elements at the contact: H_CONTACT / 2
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E:g}, {NU:g}",
              "*SOLID SECTION, ELSET=CYL, MATERIAL=STEEL", "1.",
              "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL", "1.",
              "*SURFACE INTERACTION, NAME=SI", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
              f"{slope:.6g}",
              "*CONTACT PAIR, INTERACTION=SI, TYPE=SURFACE TO SURFACE", "SARC, STOP",
              "*BOUNDARY", "AXIS, 1, 1", "BOTTOM, 1, 2", "CUT, 1, 1",
              "*STEP, NLGEOM=NO, INC=100", "*STATIC, DIRECT", "1.0, 1.0",
              "*BOUNDARY", f"CUT, 2, 2, {-approach:.10g}",
              # FREQUENCY=2: ccx appends a zero-size increment to an axisymmetric step
              # here; its last increment is written whatever the frequency
              "*NODE FILE, FREQUENCY=2", "RF", "*EL FILE, FREQUENCY=2", "S",
              "*CONTACT FILE, FREQUENCY=2", "CDIS, CSTR",
              "*END STEP", ""]
    path.write_text("\n".join(lines))


#: The convention check: a CAX4 cylinder of radius 1 and height 1 (2 x 2 elements), E 1000,
#: nu 0, stretched by 1e-3: a uniform axial stress of 1, so the full circle's force is pi,
#: a radian's 1/2, the 2-degree sector's pi/180.  ccx 2.20 writes F2 summing to pi in the
#: .frd (the full circle) and pi/180 for the *NODE PRINT totals of the .dat.
CAX_ROD = """** a CAX4 rod: uniform axial stress 1 (tools/make_plane_runs.py)
*NODE, NSET=NALL
1, 0, 0
2, 0.5, 0
3, 1, 0
4, 0, 0.5
5, 0.5, 0.5
6, 1, 0.5
7, 0, 1
8, 0.5, 1
9, 1, 1
*ELEMENT, TYPE=CAX4, ELSET=E
1, 1, 2, 5, 4
2, 2, 3, 6, 5
3, 4, 5, 8, 7
4, 5, 6, 9, 8
*NSET, NSET=BOT
1, 2, 3
*NSET, NSET=TOP
7, 8, 9
*MATERIAL, NAME=M
*ELASTIC
1000., 0.
*SOLID SECTION, ELSET=E, MATERIAL=M
*BOUNDARY
BOT, 2, 2
1, 1, 1
*STEP
*STATIC
*BOUNDARY
TOP, 2, 2, 0.001
*NODE FILE
RF
*EL FILE
S
*NODE PRINT, NSET=TOP, TOTALS=ONLY
RF
*END STEP
"""


def _ccx(out: Path, job: str, keep=(".inp", ".frd")):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    subprocess.run(["ccx", "-i", job], cwd=out, env=env, check=True, stdout=subprocess.DEVNULL)
    for f in out.glob(f"{job}.*"):
        if f.suffix not in keep:
            f.unlink()
    (out / "spooles.out").unlink(missing_ok=True)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="tests/data/calculix_plane")
    parser.add_argument("--models", nargs="+", default=list(APPROACH))
    parser.add_argument("--no-run", action="store_true", help="write the decks only")
    args = parser.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for model in args.models:
        write_deck(out / f"{model}.inp", model, APPROACH[model])
        if not args.no_run:
            _ccx(out, model)
    (out / "cax_rod.inp").write_text(CAX_ROD)
    if not args.no_run:
        _ccx(out, "cax_rod", keep=(".inp", ".frd", ".dat"))


if __name__ == "__main__":
    main()
