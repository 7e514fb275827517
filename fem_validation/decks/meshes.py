"""The deck model as a mesh with named groups (msh, med, exodus, xdmf) and problem.json.

For codes whose input is a script of their own (Code_Aster, MOOSE, FEniCS,
Elmer): the quadratic tetrahedra of both bodies, the boundary faces of every
named set as 6-node triangles, and the node sets, under these names:

* BODY1, BODY2: the two bodies (volume groups);
* CONTACT1, CONTACT2: the contact faces of body 1 and body 2 (slave and master
  of the CalculiX deck, see problem.json);
* MOVED: the face moved by the prescribed approach (body 1's top, or the ball's
  equator), FIXED: body 2's clamped face;
* SYMX, SYMY: the symmetry planes x = 0 and y = 0 (quarter models).

How each format carries the names:

* msh (gmsh 2.2, read by gmsh, Code_Aster, MOOSE and meshio alike): physical
  groups (volumes and surfaces) with these names;
* med: cell families named after the groups (``cell_tags``), node families for
  the node sets (``point_tags``, one group per family);
* exodus: one element block per group, named (``eb_names``, ids as in
  problem.json's ``group_ids``), and named node sets for every node set;
* xdmf: the volumes only (``cell_data["group"]``: 1 body 1, 2 body 2) and one
  0/1 point field per node set named after it (SLAVE and MASTER are the
  contact faces' nodes).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ..errors import FEMValidationError
from .inp import UNITS
from .model import TET_FACES, DeckModel, face_nodes

#: meshio's 6-node triangle from a C3D10 face: vertices, then mid-sides (same order).
FACE_GROUPS = ("CONTACT1", "CONTACT2", "MOVED", "FIXED", "SYMX", "SYMY")
FORMATS = {"msh": "mesh.msh", "med": "mesh.med", "exodus": "mesh.exo", "xdmf": "mesh.xdmf"}
#: meshio's tetra10 order from C3D10 (they agree: vertices, then 01 12 20 03 13 23).
TETRA10_FROM_C3D10 = list(range(10))


def _boundary_faces(model: DeckModel):
    """All boundary faces of both bodies: (element, face number 1..4)."""
    conn = model.elements[:, :4]
    faces = np.concatenate([conn[:, list(f)] for f in TET_FACES])
    elem = np.tile(np.arange(len(conn)), 4)
    number = np.repeat(np.arange(1, 5), len(conn))
    _, inv, count = np.unique(np.sort(faces, axis=1), axis=0, return_inverse=True,
                              return_counts=True)
    outer = count[inv.ravel()] == 1
    return elem[outer], number[outer]


def face_groups(model: DeckModel) -> dict[str, np.ndarray]:
    """6-node triangles (k, 6) of each named face group."""
    groups = {}
    for name in ("CONTACT1", "CONTACT2"):
        el, fc = model.surfaces[name]
        groups[name] = face_nodes(model.elements[el], fc)
    el, fc = _boundary_faces(model)
    tri = face_nodes(model.elements[el], fc)
    for name in ("MOVED", "FIXED", "SYMX", "SYMY"):
        if name in model.node_sets:
            inside = np.zeros(len(model.nodes), dtype=bool)
            inside[model.node_sets[name]] = True
            groups[name] = tri[np.all(inside[tri], axis=1)]
    return groups


def write_mesh(model: DeckModel, out: Path, fmt: str, units: str = "mm") -> Path:
    """Write the mesh with named groups in one of :data:`FORMATS`; returns the path."""
    import meshio

    if fmt not in FORMATS:
        raise ValueError(f"format must be one of {sorted(FORMATS)}, got {fmt!r}")
    needs = {"med": "h5py", "exodus": "netCDF4"}.get(fmt)
    if needs:
        try:
            __import__(needs)
        except ImportError:
            raise ValueError(f"--format {fmt} needs the {needs} package (pip install {needs}, "
                             f"or the fem extra)") from None
    path = Path(out) / FORMATS[fmt]
    points = model.nodes * UNITS[units]["length"]
    faces = face_groups(model)
    names = ["BODY1", "BODY2", *faces]
    ids = {name: i + 1 for i, name in enumerate(names)}
    cells, group = [], []
    for body in (1, 2):
        cells.append(("tetra10", model.elements[model.body == body][:, TETRA10_FROM_C3D10]))
        group.append(np.full(int(np.sum(model.body == body)), ids[f"BODY{body}"]))
    for name, tri in faces.items():
        cells.append(("triangle6", tri))
        group.append(np.full(len(tri), ids[name]))
    if fmt == "msh":
        dims = {name: 3 if name.startswith("BODY") else 2 for name in names}
        mesh = meshio.Mesh(points, cells,
                           cell_data={"gmsh:physical": group, "gmsh:geometrical": group},
                           field_data={n: np.array([ids[n], dims[n]]) for n in names})
        meshio.write(path, mesh, file_format="gmsh22", binary=False)
    elif fmt == "med":
        # MED families: negative numbers for cells, positive for nodes; one group each
        # MED holds one section per cell type: merge the blocks, keep the groups as families
        merged, tags = [], []
        for kind in ("tetra10", "triangle6"):
            pick = [k for k, (t, _) in enumerate(cells) if t == kind]
            merged.append((kind, np.vstack([cells[k][1] for k in pick])))
            tags.append(-np.concatenate([group[k] for k in pick]))
        mesh = meshio.Mesh(points, merged, cell_data={"cell_tags": tags})
        mesh.cell_tags = {-ids[n]: [n] for n in names}
        sets = list(model.node_sets)
        tags = np.zeros(len(points), dtype=np.int64)
        # a node in several sets gets the family of the last set that holds it (med allows
        # one family per node: the mesh's face groups carry the full sets)
        for k, name in enumerate(sets):
            tags[model.node_sets[name]] = k + 1
        mesh.point_data["point_tags"] = tags
        mesh.point_tags = {k + 1: [name] for k, name in enumerate(sets)}
        meshio.write(path, mesh, file_format="med")
    elif fmt == "exodus":
        mesh = meshio.Mesh(points, cells, cell_data={"group": group},
                           point_sets={n: np.asarray(v) for n, v in model.node_sets.items()})
        meshio.write(path, mesh, file_format="exodus")
        _name_exodus_blocks(path, names)
    else:
        # meshio writes several cell types to XDMF as a mixed topology that it cannot read
        # back with 10-node tetrahedra: the volumes only, the sets as named 0/1 node fields
        cells = [("tetra10", np.vstack([cells[0][1], cells[1][1]]))]
        group = [np.concatenate(group[:2])]
        point_data = {}
        for name, nodes in model.node_sets.items():
            mask = np.zeros(len(points), dtype=np.int32)
            mask[nodes] = 1
            point_data[name] = mask
        mesh = meshio.Mesh(points, cells, cell_data={"group": group}, point_data=point_data)
        meshio.write(path, mesh, file_format="xdmf", data_format="XML")
    return path


def _name_exodus_blocks(path: Path, names: list[str]) -> None:
    """Give the Exodus element blocks their group names (meshio leaves them unnamed)."""
    import netCDF4

    with netCDF4.Dataset(path, "a") as nc:
        width = len(nc.dimensions["len_string"])
        var = nc.createVariable("eb_names", "S1", ("num_el_blk", "len_string"))
        var[:] = netCDF4.stringtochar(np.array(names, dtype=f"S{width}"))
        nc.variables["eb_prop1"][:] = np.arange(1, len(names) + 1)


def _length(value, ul: float):
    """A length (or a list of them) in the file's unit; other values as they are."""
    if isinstance(value, list):
        return [_length(v, ul) for v in value]
    return value * ul if isinstance(value, float) else value


def problem(model: DeckModel, units: str = "mm", files: dict | None = None,
            command: str | None = None, friction=None) -> dict:
    """What problem.json holds: the scene, the model, loads, contact, Hertz's values
    (and, for a frictional deck, the tangential path under "friction")."""
    u = UNITS[units]
    ul, uf, us = u["length"], u["force"], u["stress"]
    s, c = model.scene, model.contact

    def body(b):
        return {"Rx": b.Rx * ul if math.isfinite(b.Rx) else "inf",
                "Ry": b.Ry * ul if math.isfinite(b.Ry) else "inf",
                "E": b.E * us, "nu": b.nu}

    expected = {"load": c.load * uf, "a": c.a * ul, "b": c.b * ul, "p0": c.p0 * us,
                "approach": c.delta * ul, "ellipticity": c.ellipticity,
                "major_axis_angle_deg": math.degrees(c.major_axis_angle)}
    for i in (1, 2):
        sub = c.subsurface(i)
        expected[f"von_mises_max_body{i}"] = sub.von_mises * us
        expected[f"von_mises_depth_body{i}"] = sub.z_von_mises * ul
    groups = {"BODY1": "volume: body 1 (elements of the first body of the scene)",
              "BODY2": "volume: body 2",
              "CONTACT1": "faces: body 1's contact surface", "CONTACT2": "faces: body 2's",
              "MOVED": f"faces and nodes: {model.info['moved']}, moved by the approach",
              "FIXED": "faces and nodes: body 2's clamped face (u = 0)",
              "SLAVE": "nodes of the slave contact surface", "MASTER": "nodes of the master"}
    if model.symmetry == "quarter":
        groups |= {"SYMX": "faces and nodes on x = 0 (u_x = 0)",
                   "SYMY": "faces and nodes on y = 0 (u_y = 0)"}
    elif model.symmetry == "half":
        groups |= {"SYMY": "faces and nodes on y = 0 (u_y = 0)"}
    group_ids = {name: i + 1 for i, name in
                 enumerate(["BODY1", "BODY2", *face_groups(model)])}
    return {
        "scene": {"name": s.name, "body1": body(s.body1), "body2": body(s.body2),
                  "angle_deg": math.degrees(s.angle), "load": s.load * uf},
        "units": dict(u["names"]),
        "model": {"geometry": model.geometry,
                  "symmetry": model.symmetry,
                  "force_multiplier": model.multiplicity,
                  "level": model.level, "element": "10-node tetrahedron (C3D10 node order)",
                  "nodes": len(model.nodes), "elements": len(model.elements),
                  "element_size_at_contact": model.h0 * ul,
                  **{k: _length(v, ul) for k, v in model.info.items()
                     if k != "penalty_factor"}},
        "frame": {"origin": [0.0, 0.0, 0.0], "normal_into_body1": [0.0, 0.0, 1.0],
                  "body1_x_axis": [1.0, 0.0, 0.0]},
        "materials": {"body1": {"E": s.body1.E * us, "nu": s.body1.nu},
                      "body2": {"E": s.body2.E * us, "nu": s.body2.nu}},
        "loads": {"MOVED": {"u_z": -model.approach * ul, "u_x": 0.0, "u_y": 0.0},
                  "FIXED": {"u_x": 0.0, "u_y": 0.0, "u_z": 0.0},
                  **({"SYMX": {"u_x": 0.0}, "SYMY": {"u_y": 0.0}} if model.quarter else
                     {"SYMY": {"u_y": 0.0}} if model.symmetry == "half" else {}),
                  "approach": model.approach * ul,
                  "approach_note": "Hertz's approach at the target load less the Boussinesq "
                                   "settlement of half-spaces at the depth of the moved and "
                                   "the fixed face, which the finite bodies do not show"},
        "contact": {"slave": model.slave, "master": model.master,
                    "formulation": "frictionless, surface to surface, penalty",
                    "penalty": model.penalty * us / ul,
                    "penalty_unit": f"{u['names']['stress']}/{u['names']['length']}",
                    "penalty_factor": model.info["penalty_factor"],
                    "penalty_note": "linear pressure-overclosure slope = penalty_factor E*/h0"},
        "groups": groups, "group_ids": group_ids,
        "expected": expected,
        "expected_note": "Hertz at the scene's target load, whole model; a run reaches "
                         "another force: grade at the force reached",
        "files": files or {},
        "command": command,
        **({} if friction is None else {"friction": {
            "mu": friction.mu, "ratio": friction.ratio, "direction": "x",
            "peak_displacement": friction.peak * ul, "ramp_increments": friction.increments,
            "stick_slope": friction.stick_slope * us / ul,
            "stick_slope_note": "CalculiX *FRICTION lambda: shear stress per unit elastic "
                                "slip, here the normal penalty slope",
            "steps": ["normal approach", "ramp 0 -> peak", "unloading peak -> -peak",
                      "reloading -peak -> peak (1 + 1/ramp_increments)"],
            "peak_note": "Mindlin's displacement at Q = ratio mu P (the scene's target load) "
                         "less the Cerruti settlement Q (3 - 2 nu)/(8 pi G H) of each "
                         "clamped block of depth H"}}),
    }


def write_problem(model: DeckModel, out: Path, units: str = "mm", files: dict | None = None,
                  command: str | None = None, friction=None) -> Path:
    """Write DIR/problem.json (:func:`problem`), strict JSON; returns the path.

    Raises
    ------
    FEMValidationError
        A number is not finite (JSON has no Infinity or NaN): the model's checks let
        it through, a defect.
    """
    path = Path(out) / "problem.json"
    try:
        text = json.dumps(problem(model, units, files, command, friction), indent=1,
                          allow_nan=False)
    except ValueError:
        raise FEMValidationError(f"{path}: a value is not a finite number, which JSON cannot "
                                 f"hold (a defect of fem_validation: please report)") from None
    path.write_text(text + "\n")
    return path
