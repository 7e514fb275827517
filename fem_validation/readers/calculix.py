"""A CalculiX result (.frd, with its .inp) -> :class:`~fem_validation.result.ContactResult`.

What is read, and from where:

* **the contact surface**: the slave surface of the deck's ``*CONTACT PAIR``
  (the first data line: slave, master) and its ``*SURFACE, TYPE=ELEMENT``
  faces (or ``TYPE=NODE`` nodes), from the .inp beside the .frd (same name) or
  the one given; the faces' nodes in the .frd's element connectivity (4- and
  10-node tetrahedra).  Without a deck: the nodes that carry any contact output
  (then the edge of contact is only what the pressed nodes show);
* **pressure**: ``CPRESS`` of the last ``CONTACT`` set, at those nodes
  (CalculiX gives contact output at slave nodes only);
* **force**: body 1's total reaction ``F3`` (the moved face's), times 4 for a
  quarter model, 2 for a half; body 2's (the clamped face's) is the
  independent ``reaction``.  Bodies are told apart by the elements' material
  numbers: material 1 is body 1 (the decks of :mod:`fem_validation.decks`
  define MATERIAL1 first);
* **stresses**: the nodal ``STRESS`` set (SXX, SYY, SZZ, SXY, SYZ, SZX),
  per body, with the corner tetrahedra for interpolation;
* **symmetry**: detected from the node coordinates (all x >= 0 and y >= 0:
  quarter; one of them: half) unless given;
* **units**, **approach** and the contact **frame**: from problem.json beside
  the deck where :mod:`fem_validation.decks` wrote one (the approach is the
  prescribed one plus the Boussinesq settlement the finite bodies do not show,
  at the force reached); otherwise ``units`` as given (default mm, N, MPa), no
  approach, the standard frame (origin 0, normal +z into body 1).
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np

from ..result import BodyStress, ContactFrame, ContactResult, ResultError, stress_from_voigt
from .frd import FrdFile, read_frd

#: Length and stress factors to SI for the unit systems of decks.
UNIT_FACTORS = {"mm": (1e-3, 1e6), "SI": (1.0, 1.0), "m": (1.0, 1.0)}
#: Faces of tetrahedra in CalculiX's numbering (S1..S4): corners, then (10-node) mid-sides.
_TET_FACES = {1: (0, 1, 2, 4, 5, 6), 2: (0, 3, 1, 7, 8, 4), 3: (1, 3, 2, 8, 9, 5),
              4: (2, 3, 0, 9, 7, 6)}
#: A 6-node triangle (corners 0-2, mid-sides 3: 01, 4: 12, 5: 20) as 4 linear triangles.
_SPLIT6 = ((0, 3, 5), (3, 1, 4), (5, 4, 2), (3, 4, 5))
SYMMETRY_TOL = 1e-9


def _keyword_blocks(text: str):
    """(keyword line, data lines) of an .inp, comments dropped, upper-case keywords."""
    blocks, current = [], None
    for raw in text.splitlines():
        line = raw.strip()
        if not line or line.startswith("**"):
            continue
        if line.startswith("*"):
            current = (line.upper(), [])
            blocks.append(current)
        elif current is not None:
            current[1].append(line)
    return blocks


def _param(keyword: str, name: str) -> str | None:
    m = re.search(rf",\s*{name}\s*=\s*([^,]+)", keyword)
    return m.group(1).strip() if m else None


def slave_surface(inp_path) -> tuple[str, list[tuple[int, int]], list[int]]:
    """The slave surface of the deck's first contact pair: (name, element faces, nodes).

    Raises
    ------
    ResultError
        If the deck has no ``*CONTACT PAIR`` or the slave surface is not defined.
    """
    inp_path = Path(inp_path)
    blocks = _keyword_blocks(inp_path.read_text(errors="replace"))
    pair = next((b for b in blocks if b[0].startswith("*CONTACT PAIR")), None)
    if pair is None or not pair[1]:
        raise ResultError(f"{inp_path}: no *CONTACT PAIR with a data line (slave, master)")
    name = pair[1][0].split(",")[0].strip().upper()
    faces, nodes, found = [], [], False
    for key, data in blocks:
        if key.startswith("*SURFACE,") and (_param(key, "NAME") or "").upper() == name:
            found = True
            kind = (_param(key, "TYPE") or "ELEMENT").upper()
            for line in data:
                parts = [p.strip() for p in line.split(",") if p.strip()]
                if kind == "NODE":
                    nodes += [int(p) for p in parts[:1] if p.isdigit()]
                elif len(parts) >= 2 and parts[0].isdigit():
                    face = parts[1].upper()
                    if not re.fullmatch(r"S[1-4]", face):
                        raise ResultError(f"{inp_path}: surface {name}: face {parts[1]!r} of "
                                          f"element {parts[0]} (tetrahedra have S1..S4)")
                    faces.append((int(parts[0]), int(face[1])))
                else:
                    raise ResultError(f"{inp_path}: surface {name}: cannot read {line!r} "
                                      f"(expected: element number, S1..S4)")
    if not found:
        raise ResultError(f"{inp_path}: the slave surface {name} of *CONTACT PAIR is not "
                          f"defined by a *SURFACE")
    return name, faces, nodes


def _surface(frd: FrdFile, faces, nodes, source: str):
    """Slave node numbers and triangles (as indices into them) from element faces."""
    if nodes and not faces:
        return np.unique(np.asarray(nodes, dtype=np.int64)), None
    order = np.argsort(frd.elements)
    ids = np.array([f[0] for f in faces], dtype=np.int64)
    pos = order[np.clip(np.searchsorted(frd.elements, ids, sorter=order), 0, len(order) - 1)]
    if np.any(frd.elements[pos] != ids):
        bad = ids[frd.elements[pos] != ids][0]
        raise ResultError(f"{source}: slave face on element {bad}, which the .frd does not "
                          f"hold: the deck does not match the result")
    types = frd.element_types[pos]
    if not np.all(np.isin(types, (3, 6))):
        raise ResultError(f"{source}: the slave surface lies on elements of .frd type "
                          f"{sorted(set(types.tolist()) - {3, 6})}; this reader knows "
                          f"tetrahedra (types 3 and 6)")
    six = np.array([_TET_FACES[f[1]] for f in faces])
    quadratic = np.all(types == 6)
    local = six if quadratic else six[:, :3]
    conn = frd.connectivity[pos[:, None], local]
    surface, inverse = np.unique(conn, return_inverse=True)
    inverse = inverse.reshape(conn.shape)
    tri = inverse[:, list(_SPLIT6)].reshape(-1, 3) if quadratic else inverse
    return surface, tri


def _symmetry(xyz: np.ndarray) -> str:
    scale = np.abs(xyz).max()
    tol = SYMMETRY_TOL * scale
    x_half, y_half = xyz[:, 0].min() >= -tol, xyz[:, 1].min() >= -tol
    return "quarter" if x_half and y_half else "half" if x_half or y_half else "whole"


def read_calculix(path, inp=None, units: str | None = None, symmetry: str | None = None,
                  problem=None, stress: bool = True, tetrahedra: bool = False,
                  force: float | None = None, frame: ContactFrame | None = None,
                  pressure_name: str = "CPRESS") -> ContactResult:
    """Read a CalculiX .frd (ASCII or binary) into a contact result in SI.

    Parameters
    ----------
    path : path-like
        The .frd file.
    inp : path-like, optional
        The deck (default: the .inp beside the .frd with the same name, if any).
    units : {"mm", "SI"}, optional
        The deck's units (mm, N, MPa or m, N, Pa); default: problem.json's, else mm.
    symmetry : {"whole", "half", "quarter"}, optional
        Default: from the coordinates.
    problem : path-like, optional
        problem.json of :mod:`fem_validation.decks` (default: beside the .frd).
    stress : bool
        Read the nodal stresses of both bodies (the von Mises maxima on the axis).
    force : float, optional
        The total normal force of the model in the file [N]: replaces body 1's
        reaction (times the multiplicity) as the result's force.
    frame : ContactFrame, optional
        The contact frame [m]; default problem.json's, else the standard frame.
    pressure_name : str
        The contact pressure's component name (default CPRESS).
    tetrahedra : bool
        Also hand the grader each body's corner tetrahedra, for the stress-field
        RMS.  Off by default: the grader samples that field at depths below the
        plane z = 0, and near the surface of a curved body (a true ball, a
        paraboloid-faced block) those points lie outside it.

    Returns
    -------
    ContactResult

    Raises
    ------
    ResultError
        Naming the file and what is missing or contradictory (no contact
        pressure, no reaction forces, a deck that does not match, ...).
    """
    path = Path(path)
    source = str(path)
    try:
        frd = read_frd(path)
    except OSError as exc:
        raise ResultError(f"{source}: cannot read: {exc.strerror}") from None
    except ValueError as exc:
        raise ResultError(str(exc)) from None
    problem_path = Path(problem) if problem is not None else path.parent / "problem.json"
    info = json.loads(problem_path.read_text()) if problem_path.is_file() else None
    if info:
        own = {"mm": "mm", "m": "SI"}.get(info["units"]["length"], info["units"]["length"])
        if units is not None and UNIT_FACTORS.get(units) != UNIT_FACTORS.get(own):
            raise ResultError(f"{source}: units {units!r} contradict {problem_path}, which "
                              f"says the deck is in {own} ({info['units']['length']}, "
                              f"{info['units']['stress']}): give units {own!r}")
        units = own
    if units is None:
        units = "mm"
    if units not in UNIT_FACTORS:
        raise ResultError(f"{source}: units must be one of mm, SI, got {units!r}")
    to_m, to_pa = UNIT_FACTORS[units]
    if not any(pressure_name in r.components for r in frd.results):
        raise ResultError(f"{source}: no contact pressure ({pressure_name}) in the file: the "
                          f"deck needs *CONTACT FILE (or *CONTACT OUTPUT) with CSTR; it has "
                          f"{', '.join(frd.component_names) or 'no results'}")
    cnodes, cpress = frd.field(pressure_name)
    inp_path = Path(inp) if inp is not None else path.with_suffix(".inp")
    if inp_path.is_file():
        name, faces, nodes = slave_surface(inp_path)
        surface, tri = _surface(frd, faces, nodes, f"{inp_path}")
        how = f"slave surface {name} of {inp_path.name}"
    else:
        contact = frd.result("CONTACT") if any(r.name == "CONTACT" for r in frd.results) \
            else None
        rows = np.any(contact.values != 0, axis=1) if contact is not None else cpress != 0
        surface, tri = (contact.nodes if contact is not None else cnodes)[rows], None
        how = "nodes with contact output (no deck found)"
    lookup = {n: i for i, n in enumerate(cnodes.tolist())}
    missing = [n for n in surface.tolist() if n not in lookup]
    if missing:
        raise ResultError(f"{source}: slave node {missing[0]} has no contact output: the deck "
                          f"does not match the result")
    pressure = cpress[[lookup[n] for n in surface.tolist()]] * to_pa
    xyz_all = frd.coordinates * to_m
    points = xyz_all[frd.node_index(surface)]
    sym = symmetry or _symmetry(xyz_all)

    # reactions per body from the elements' materials
    mats = sorted(set(frd.element_materials.tolist()))
    if len(mats) != 2:
        raise ResultError(f"{source}: expected two bodies (two material numbers on the "
                          f"elements), found {len(mats)}: {mats}")
    body_nodes = [np.unique(frd.connectivity[frd.element_materials == m]) for m in mats]
    body_nodes = [n[n > 0] for n in body_nodes]
    try:
        rnodes, rz = frd.field("F3")
    except KeyError:
        raise ResultError(f"{source}: no reaction forces (FORC F3): the deck needs "
                          f"*NODE FILE with RF") from None
    mult = {"whole": 1, "half": 2, "quarter": 4}.get(sym)
    if mult is None:
        raise ResultError(f"{source}: symmetry must be whole, half or quarter, got {sym!r}")
    reactions = [mult * abs(float(rz[np.isin(rnodes, n)].sum())) for n in body_nodes]
    reaction = reactions[1]
    force = reactions[0] if force is None else mult * float(force)

    details = {"solver": "CalculiX", "file": source, "units": units, "contact_surface": how,
               "nodes": len(frd.nodes), "elements": len(frd.elements),
               "version": next((h.split(None, 1)[1].strip() for h in frd.headers
                                if h.startswith("VERSION")), "")}
    given_frame = frame
    frame = ContactFrame(source=source)
    approach = None
    if info:
        fr = info.get("frame", {})
        frame = ContactFrame(origin=np.asarray(fr.get("origin", [0, 0, 0]), float) * to_m,
                             normal=fr.get("normal_into_body1", [0, 0, 1]),
                             x_axis=fr.get("body1_x_axis", [1, 0, 0]), source=source)
        approach = _approach(info, force, to_m, to_pa)
        details |= {"geometry": info["model"]["geometry"], "level": info["model"]["level"],
                    "penalty_factor": info["contact"]["penalty_factor"],
                    "slave": info["contact"]["slave"],
                    "approach_note": "prescribed approach plus the Boussinesq settlement of "
                                     "half-spaces at the far faces' depths, at the force"}
    if given_frame is not None:
        frame = given_frame
    bodies = []
    if stress and any(r.name == "STRESS" for r in frd.results):
        st = frd.result("STRESS")
        sig = stress_from_voigt(st.values[:, [st.components.index(c) for c in
                                              ("SXX", "SYY", "SZZ", "SXY", "SYZ", "SZX")]],
                                "xx yy zz xy yz xz") * to_pa
        rows = frd.node_index(st.nodes)
        for body, (m, nodes) in enumerate(zip(mats, body_nodes, strict=True), start=1):
            keep = np.isin(st.nodes, nodes)
            where = rows[keep]
            local = np.full(len(frd.nodes), -1, dtype=np.int64)
            local[where] = np.arange(keep.sum())
            conn = frd.connectivity[frd.element_materials == m][:, :4]
            tets = local[frd.node_index(conn.ravel())].reshape(-1, 4)
            tets = tets[np.all(tets >= 0, axis=1)]
            bodies.append(BodyStress(body, xyz_all[where], sig[keep],
                                     tetrahedra=tets if tetrahedra else None, source=source))
    return ContactResult(points=points, force=force, pressure=pressure, symmetry=sym,
                         frame=frame, triangles=tri, approach=approach, reaction=reaction,
                         stress=tuple(bodies), source=source, details=details)


def _approach(info: dict, force: float, to_m: float, to_pa: float) -> float | None:
    """The prescribed approach plus the far faces' Boussinesq settlement at ``force`` [m]."""
    from ..solve import boussinesq_settlement

    loads, model = info.get("loads", {}), info.get("model", {})
    depths = model.get("far_face_depths")
    if "approach" not in loads or not depths:
        return None
    total = loads["approach"] * to_m
    for body, depth in zip(("body1", "body2"), depths, strict=True):
        m = info["materials"][body]
        total += boussinesq_settlement(force, m["E"] * to_pa, m["nu"], depth * to_m)
    return total
