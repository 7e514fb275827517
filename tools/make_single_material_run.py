"""Write a CalculiX deck of a steel ball on a steel block as an analyst writes one by hand,
and (with ``--run``) run ccx on it: the fixture of tests/test_analyst_files.py.

    python tools/make_single_material_run.py [--out tests/data/calculix/single_material]
        [--size 0.09] [--run]

The deck is NOT written by :mod:`fem_validation.decks`: it is built here from gmsh's
OpenCASCADE geometry with its own conventions, as someone outside the project would:

* one ``*MATERIAL, NAME=STEEL`` for both bodies (E = 210000 MPa, nu = 0.3), two
  ``*SOLID SECTION`` s naming it, element sets ``BALL`` and ``BLOCK``; the ball's elements
  come first in the file;
* units mm, N, MPa; C3D10 (gmsh's second-order tetrahedra, mid-side nodes on the sphere);
* a quarter model (x >= 0, y >= 0) of a ball of radius 10 mm (its lower hemisphere's
  quarter) on a block 6 mm wide and 6 mm deep; the ball's equator moved down 0.02 mm;
  the block's bottom clamped; symmetry planes x = 0 and y = 0;
* ``*CONTACT PAIR`` (surface to surface, the ball's face the slave) with a linear
  pressure-overclosure penalty of 1.5e7 MPa/mm, ``*NODE FILE`` U, RF; ``*EL FILE`` S;
  ``*CONTACT FILE`` CDIS, CSTR.

The force is the reaction ccx finds (about 1 kN); Hertz's a is then about 0.4 mm and the
contact zone is meshed at ``--size`` mm.  ccx 2.20 ran it here in about 30 s of CPU.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np

R = 10.0  # ball radius [mm]
L = 6.0  # block half-width and depth [mm] (quarter model: 0..L)
APPROACH = 0.02  # the equator's prescribed displacement [mm]
E, NU = 210000.0, 0.3  # MPa
PENALTY = 1.5e7  # MPa/mm: 10 E*/h (h = 0.08 mm), as the decks of fem_validation take
#: gmsh's 10-node tetrahedron -> C3D10 (gmsh's nodes 8 and 9 are edges 3-4 and 2-4).
GMSH_TO_C3D10 = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]
#: C3D10 faces S1..S4 by their corner nodes (0-based).
FACES = ((0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0))


def mesh(size: float):
    """(nodes (n, 3), ball tets, block tets, ball contact faces, block contact faces)."""
    import gmsh

    gmsh.initialize(["-noenv"])
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        occ = gmsh.model.occ
        sphere = occ.addSphere(0, 0, R, R)
        box = occ.addBox(0, 0, 0, R, R, R)
        ball, _ = occ.intersect([(3, sphere)], [(3, box)])
        block = occ.addBox(0, 0, -L, L, L, L)
        occ.synchronize()
        # the contact region fine, growing away from it
        field = gmsh.model.mesh.field
        ball_field = field.add("Ball")
        field.setNumber(ball_field, "Radius", 0.8)
        field.setNumber(ball_field, "Thickness", 4.0)
        field.setNumber(ball_field, "VIn", size)
        field.setNumber(ball_field, "VOut", 2.0)
        field.setAsBackgroundMesh(ball_field)
        for key in ("Mesh.MeshSizeExtendFromBoundary", "Mesh.MeshSizeFromPoints",
                    "Mesh.MeshSizeFromCurvature"):
            gmsh.option.setNumber(key, 0)
        gmsh.option.setNumber("Mesh.ElementOrder", 2)
        gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
        gmsh.model.mesh.generate(3)
        tags, xyz, _ = gmsh.model.mesh.getNodes()
        index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
        index[tags.astype(np.int64)] = np.arange(len(tags))
        nodes = xyz.reshape(-1, 3)

        def tets(volume_tag):
            types, _, conn = gmsh.model.mesh.getElements(3, volume_tag)
            (k,) = [i for i, t in enumerate(types) if t == 11]  # 10-node tetrahedron
            return index[conn[k].astype(np.int64)].reshape(-1, 10)[:, GMSH_TO_C3D10]

        ball_tets, block_tets = tets(ball[0][1]), tets(block)
        # the contact faces: the sphere's surface and the block's top
        sphere_surf = [s for _, s in gmsh.model.getBoundary(ball, oriented=False)
                       if gmsh.model.getType(2, s) == "Sphere"]
        top_surf = [s for _, s in gmsh.model.getBoundary([(3, block)], oriented=False)
                    if abs(occ.getCenterOfMass(2, s)[2]) < 1e-9]
        corners = []
        for surfs in (sphere_surf, top_surf):
            tri = []
            for s in surfs:
                types, _, conn = gmsh.model.mesh.getElements(2, s)
                (k,) = [i for i, t in enumerate(types) if t == 9]  # 6-node triangle
                tri.append(index[conn[k].astype(np.int64)].reshape(-1, 6)[:, :3])
            corners.append(np.vstack(tri))
    finally:
        gmsh.finalize()
    return nodes, ball_tets, block_tets, corners


def faces_on(tets: np.ndarray, offset: int, triangles: np.ndarray, nodes, reach: float):
    """(element number, face number) of the tetrahedra's faces on ``triangles`` whose
    centroid lies within ``reach`` mm of the z axis."""
    want = {tuple(sorted(t)) for t in triangles.tolist()
            if np.hypot(*nodes[t, :2].mean(axis=0)) <= reach}
    out = []
    for e, tet in enumerate(tets):
        for f, local in enumerate(FACES, start=1):
            if tuple(sorted(tet[list(local)].tolist())) in want:
                out.append((e + 1 + offset, f))
    return out


def _lines(numbers, per=16) -> list[str]:
    numbers = list(numbers)
    return [", ".join(str(n) for n in numbers[i:i + per]) for i in range(0, len(numbers), per)]


def write_deck(path: Path, size: float) -> None:
    nodes, ball, block, (sphere_tri, top_tri) = mesh(size)
    # keep only the nodes the tetrahedra use (gmsh also numbers geometry points)
    used = np.unique(np.concatenate([ball.ravel(), block.ravel()]))
    renumber = np.full(len(nodes), -1, dtype=np.int64)
    renumber[used] = np.arange(len(used))
    nodes = nodes[used]
    ball, block = renumber[ball], renumber[block]
    sphere_tri, top_tri = renumber[sphere_tri], renumber[top_tri]
    x, y, z = nodes.T
    tol = 1e-7
    sets = {"SYMX": np.nonzero(np.abs(x) < tol)[0], "SYMY": np.nonzero(np.abs(y) < tol)[0],
            "BOTTOM": np.nonzero(np.abs(z + L) < tol)[0],
            "EQUATOR": np.nonzero(np.abs(z - R) < tol)[0]}
    slave = faces_on(ball, 0, sphere_tri, nodes, 2.5)
    master = faces_on(block, len(ball), top_tri, nodes, 3.5)
    out = ["** steel ball (R 10 mm) on a steel block, quarter model, mm N MPa",
           "** written by tools/make_single_material_run.py (gmsh OpenCASCADE, C3D10)",
           "*HEADING", "ball on block, one material", "*NODE, NSET=NALL"]
    out += [f"{i + 1}, {p[0]:.9g}, {p[1]:.9g}, {p[2]:.9g}" for i, p in enumerate(nodes)]
    for name, tets, offset in (("BALL", ball, 0), ("BLOCK", block, len(ball))):
        out.append(f"*ELEMENT, TYPE=C3D10, ELSET={name}")
        out += [f"{e + 1 + offset}, " + ", ".join(str(n + 1) for n in tet)
                for e, tet in enumerate(tets)]
    for name, idx in sets.items():
        out += [f"*NSET, NSET={name}", *_lines(idx + 1)]
    for name, faces in (("BALLFACE", slave), ("BLOCKFACE", master)):
        out += [f"*SURFACE, NAME={name}, TYPE=ELEMENT", *(f"{e}, S{f}" for e, f in faces)]
    out += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E:g}, {NU:g}",
            "*SOLID SECTION, ELSET=BALL, MATERIAL=STEEL",
            "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL",
            "*SURFACE INTERACTION, NAME=SI1",
            "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{PENALTY:g}",
            "*CONTACT PAIR, INTERACTION=SI1, TYPE=SURFACE TO SURFACE",
            "BALLFACE, BLOCKFACE",
            "*BOUNDARY", "SYMX, 1, 1", "SYMY, 2, 2", "BOTTOM, 1, 3",
            "*STEP", "*STATIC", "1., 1.", "*BOUNDARY", f"EQUATOR, 3, 3, {-APPROACH:g}",
            "*NODE FILE", "U, RF", "*EL FILE", "S", "*CONTACT FILE", "CDIS, CSTR",
            "*END STEP"]
    path.write_text("\n".join(out) + "\n")
    print(f"wrote {path}: {len(nodes)} nodes, {len(ball) + len(block)} C3D10, "
          f"{len(slave)} slave faces, {len(master)} master faces")


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", type=Path,
                   default=Path(__file__).parent.parent / "tests/data/calculix/single_material")
    p.add_argument("--size", type=float, default=0.08, help="element size at the contact [mm]")
    p.add_argument("--run", action="store_true", help="run ccx on the deck")
    args = p.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    deck = args.out / "ball_block.inp"
    write_deck(deck, args.size)
    if args.run:
        ccx = shutil.which("ccx")
        if ccx is None:
            print("ccx is not installed", file=sys.stderr)
            return 1
        subprocess.run([ccx, "-i", "ball_block"], cwd=args.out, check=True,
                       stdout=subprocess.DEVNULL)
        for junk in ("ball_block.dat", "ball_block.cvg", "ball_block.sta", "spooles.out"):
            (args.out / junk).unlink(missing_ok=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
