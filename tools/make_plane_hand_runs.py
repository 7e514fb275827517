"""Hand-built CalculiX 2-D Hertz runs, written as an analyst would (gmsh + numpy), not by
fem_validation's deck writer nor tools/make_plane_runs.py.

    python tools/make_plane_hand_runs.py plane DIR  # roller.inp: CPE4, node-to-surface
    python tools/make_plane_hand_runs.py axi DIR    # sphere.inp: CAX4, surface-to-surface
    cd DIR && OMP_NUM_THREADS=1 ccx -i roller      # (or sphere); about 4 s each
    gzip -9 roller.frd     # the committed runs: the same meshes, other node numbers

plane: a WHOLE half-disc roller (R 10 mm, centre (0, 10)) on a block 20 x 10 mm; quads
(gmsh's Frontal-Delaunay for quads, subdivided), 0.03 mm at the contact; one *MATERIAL
for both bodies; the block's elements first; node numbers shuffled; the roller's contact
line a node set (TYPE=NODE surface); 0.02 mm imposed on the roller's cut, the block's base
held.  axi: a quarter-disc sphere (R 10 mm) on a block 10 x 10 mm, CAX4 0.0175 mm at the
contact, element-face surfaces, surface-to-surface contact (ccx 2.20 diverged with
node-to-surface here).  Units mm, N, MPa; steel (210 GPa, 0.3).
"""

import sys

import gmsh
import numpy as np

KIND, OUT = sys.argv[1], sys.argv[2]
R, W, D = 10.0, 10.0, 10.0
H_MIN, H_MAX = (0.06, 2.5) if KIND == "plane" else (0.035, 2.5)
NAME = "roller" if KIND == "plane" else "sphere"

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
occ = gmsh.model.occ
xmin = -W if KIND == "plane" else 0.0
block = occ.addRectangle(xmin, -D, 0, W - xmin, D)
disc = occ.addDisk(0, R, 0, R, R)
cuts = [occ.addRectangle(-R, R, 0, 2 * R, R)] if KIND == "plane" else [
    occ.addRectangle(-R, 0, 0, R, 2 * R), occ.addRectangle(0, R, 0, R, R)]
occ.synchronize()
body, _ = occ.cut([(2, disc)], [(2, c) for c in cuts])
origin = occ.addPoint(0, 0, 0)
occ.synchronize()
roller = body[0][1]
field = gmsh.model.mesh.field
dist = field.add("Distance")
field.setNumbers(dist, "PointsList", [origin])
thr = field.add("Threshold")
field.setNumber(thr, "InField", dist)
field.setNumber(thr, "SizeMin", H_MIN)
field.setNumber(thr, "SizeMax", H_MAX)
field.setNumber(thr, "DistMin", 0.45)
field.setNumber(thr, "DistMax", 5.0)
field.setAsBackgroundMesh(thr)
gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
gmsh.option.setNumber("Mesh.RecombineAll", 1)
gmsh.option.setNumber("Mesh.Algorithm", 8)
gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 1)
gmsh.option.setNumber("Mesh.SubdivisionAlgorithm", 1)  # all quadrangles
gmsh.model.mesh.generate(2)
tags, xyz, _ = gmsh.model.mesh.getNodes()
coords = dict(zip(tags.astype(int).tolist(), xyz.reshape(-1, 3)[:, :2], strict=True))
elements = {}
for name, tag in (("BLOCK", block), ("ROLLER", roller)):
    types, _, enodes = gmsh.model.mesh.getElements(2, tag)
    assert len(types) == 1 and types[0] == 3, types  # 4-node quadrangles
    elements[name] = enodes[0].astype(int).reshape(-1, 4)
gmsh.finalize()

# node numbers shuffled, elements from 5001, the block first
old = np.array(sorted(coords))
new = np.random.default_rng(7).permutation(len(old)) + 101
number = dict(zip(old.tolist(), new.tolist(), strict=True))
xy = {number[o]: coords[o] for o in old.tolist()}
etype = "CPE4" if KIND == "plane" else "CAX4"
lines = ["** hand-built Hertz model (gmsh + numpy), not fem_validation's deck", "*HEADING",
         f"hand {KIND}", "*NODE, NSET=NALL"]
lines += [f"{number[o]}, {coords[o][0]:.9f}, {coords[o][1]:.9f}" for o in old.tolist()]
conn, eid = {}, 5001
for name in ("BLOCK", "ROLLER"):
    lines.append(f"*ELEMENT, TYPE={etype}, ELSET={name}")
    for row in elements[name]:
        c = np.array([coords[int(v)] for v in row])
        area = 0.5 * np.sum(c[:, 0] * np.roll(c[:, 1], -1) - np.roll(c[:, 0], -1) * c[:, 1])
        assert area > 0  # counterclockwise
        conn[eid] = (name, [number[int(v)] for v in row])
        lines.append(f"{eid}, " + ", ".join(map(str, conn[eid][1])))
        eid += 1


def on_arc(n):
    x, y = xy[n]
    return abs(np.hypot(x, y - R) - R) < 1e-6 and y < 2.0 and abs(x) < 3


def on_top(n):
    x, y = xy[n]
    return abs(y) < 1e-7 and abs(x) < 3.0


def faces(body, test):
    return [(e, k + 1) for e, (name, ns) in conn.items() if name == body
            for k in range(4) if test(ns[k]) and test(ns[(k + 1) % 4])]


def nset(name, ns):
    lines.append(f"*NSET, NSET={name}")
    lines.extend(", ".join(map(str, ns[i:i + 10])) + "," for i in range(0, len(ns), 10))


nodes = new.tolist()
nset("TOP", [n for n in nodes if abs(xy[n][1] - R) < 1e-7])
nset("BOTTOM", [n for n in nodes if abs(xy[n][1] + D) < 1e-7])
if KIND == "plane":
    nset("SLAVEN", sorted({n for name, ns in conn.values() if name == "ROLLER" for n in ns
                           if on_arc(n)}))
    lines += ["*SURFACE, NAME=SROLL, TYPE=NODE", "SLAVEN"]
else:
    nset("AXIS", [n for n in nodes if abs(xy[n][0]) < 1e-7])
    lines.append("*SURFACE, NAME=SROLL, TYPE=ELEMENT")
    lines += [f"{e}, S{k}" for e, k in faces("ROLLER", on_arc)]
lines.append("*SURFACE, NAME=MBLOCK, TYPE=ELEMENT")
lines += [f"{e}, S{k}" for e, k in faces("BLOCK", on_top)]
pair = "NODE TO SURFACE" if KIND == "plane" else "SURFACE TO SURFACE"
lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", "210000., 0.3",
          "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL", "1.",
          "*SOLID SECTION, ELSET=ROLLER, MATERIAL=STEEL", "1.",
          "*SURFACE INTERACTION, NAME=SI", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
          "1.0e7", f"*CONTACT PAIR, INTERACTION=SI, TYPE={pair}", "SROLL, MBLOCK",
          "*BOUNDARY", "BOTTOM, 1, 2", "TOP, 1, 1"]
lines += ["AXIS, 1, 1"] if KIND == "axi" else []
lines += ["*STEP, NLGEOM=NO, INC=200", "*STATIC", "0.1, 1.0, 1e-5, 0.25",
          "*BOUNDARY", "TOP, 2, 2, -0.02",
          "*NODE FILE, FREQUENCY=1000", "U, RF, NT" if KIND == "plane" else "RF",
          "*EL FILE, FREQUENCY=1000", "S", "*CONTACT FILE, FREQUENCY=1000", "CDIS, CSTR",
          "*END STEP"]
with open(f"{OUT}/{NAME}.inp", "w") as f:
    f.write("\n".join(lines) + "\n")
print(f"{OUT}/{NAME}.inp: {len(old)} nodes, {eid - 5001} {etype} elements")
