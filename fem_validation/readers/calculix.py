"""A CalculiX result (.frd, with its .inp) -> a
:class:`~fem_validation.results.contact.ContactResult`.

What is read, and from where:

* **the contact surface**: the slave surface of the deck's ``*CONTACT PAIR``
  (the first data line: slave, master) and its ``*SURFACE, TYPE=ELEMENT``
  faces (or ``TYPE=NODE`` nodes), from the .inp beside the .frd (same name) or
  the one given; the faces' nodes in the .frd's element connectivity (4- and
  10-node tetrahedra, 8- and 20-node hexahedra: their corners).  Without a deck,
  or where the slave surface is given by node-set names: the nodes that carry any
  contact output, on the faces of the mesh's boundary that they cover (the
  facing surface, found from the geometry: :func:`facing_triangles`);
* **pressure**: ``CPRESS`` of the last ``CONTACT`` set, at those nodes
  (CalculiX gives contact output at slave nodes only);
* **force**: body 1's total reaction along the contact normal (``F1..F3`` on
  it; ``F3`` in the standard frame), times 4 for a quarter model, 2 for a half;
  body 2's is the independent ``reaction``;
* **the two bodies** (:func:`bodies`), whichever the files name: ``body1`` given
  (``grade --body1 NAME``): the elements of the deck's element set NAME, or of the
  material NAME (the deck's ``*SOLID SECTION``s, or the .frd's own ``MAT`` header
  lines), are body 1, every other element body 2; else two material numbers on
  the elements: material 1 is body 1 (the decks of :mod:`fem_validation.decks`
  define MATERIAL1 first); else (one material for both, as analysts often write)
  the connected components of the mesh (elements sharing nodes), which must be
  two: body 1 the one on the side the contact normal points to;
* **stresses**: the nodal ``STRESS`` set (SXX, SYY, SZZ, SXY, SYZ, SZX),
  per body, with the corner tetrahedra for interpolation;
* **symmetry**: detected from the node coordinates (all x >= 0 and y >= 0:
  quarter; one of them: half) unless given;
* **units**, **approach** and the contact **frame**: from problem.json beside
  the deck where :mod:`fem_validation.decks` wrote one (read and checked by
  :func:`read_problem`; the approach is the prescribed one plus the Boussinesq
  settlement the finite bodies do not show, at the force reached); otherwise
  ``units`` as given (default mm, N, MPa), no approach, the standard frame
  (origin 0, normal +z into body 1).  Parts of the frame given (``grade
  --origin``, ``--normal``, ``--x-axis``) replace problem.json's; without
  problem.json the parts not given are found from the slave nodes' pressure, as
  the other readers find them (:func:`contact_frame`), but for a quarter or half
  model, whose normal is z (the line of its symmetry planes).
"""

from __future__ import annotations

import json
import math
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..limits import read_small_text
from ..results.contact import (
    BodyStress,
    ContactFrame,
    ContactResult,
    ResultError,
    stress_from_voigt,
    unit_vector,
)
from .common import resolve_frame
from .frd import FrdFile, FrdResult, read_frd

#: Length and stress factors to SI for the unit systems of decks.
UNIT_FACTORS = {"mm": (1e-3, 1e6), "SI": (1.0, 1.0), "m": (1.0, 1.0)}
#: Faces of tetrahedra in CalculiX's numbering (S1..S4): corners, then (10-node) mid-sides.
_TET_FACES = {1: (0, 1, 2, 4, 5, 6), 2: (0, 3, 1, 7, 8, 4), 3: (1, 3, 2, 8, 9, 5),
              4: (2, 3, 0, 9, 7, 6)}
#: A 6-node triangle (corners 0-2, mid-sides 3: 01, 4: 12, 5: 20) as 4 linear triangles.
_SPLIT6 = ((0, 3, 5), (3, 1, 4), (5, 4, 2), (3, 4, 5))
#: Faces of hexahedra in CalculiX's numbering (S1..S6), their corners.
_HEX_FACES = {1: (0, 1, 2, 3), 2: (4, 7, 6, 5), 3: (0, 4, 5, 1), 4: (1, 5, 6, 2),
              5: (2, 6, 7, 3), 6: (3, 7, 4, 0)}
#: .frd element types whose faces the readers know: tetrahedra (3, 6), hexahedra (1, 4).
_TETS, _HEXES = (3, 6), (1, 4)
SYMMETRY_TOL = 1e-9


#: The longest line of a deck read [characters] (CalculiX reads 132).
MAX_INP_LINE = 1024


#: The largest node or element number a deck may give: what the .frd's int64 arrays hold.
MAX_ID = (1 << 63) - 1


class _Line(str):
    """A data line of a deck, stripped, with its line ``number`` in the file."""

    number: int

    def __new__(cls, text: str, number: int):
        line = super().__new__(cls, text)
        line.number = number
        return line


def deck_id(text: str, where: str, what: str) -> int:
    """``text`` as a node or element number: 1 to :data:`MAX_ID`.

    Raises
    ------
    ResultError
        Naming ``where`` (file and line) and ``what`` is numbered, where ``text`` is no
        integer or out of that range (an int64 would overflow).
    """
    try:
        value = int(text)
    except ValueError:
        raise ResultError(f"{where}: expected a {what} number, got {text!r}") from None
    if not 1 <= value <= MAX_ID:
        shown = text if len(text) <= 30 else f"{text[:12]}...({len(text)} digits)"
        raise ResultError(f"{where}: {what} number {shown} is out of range (1 to {MAX_ID})")
    return value


def _keyword_blocks(inp_path, keep: tuple[str, ...]):
    """(keyword line, data lines) of the keywords of an .inp starting with one of ``keep``,
    comments dropped, upper-case keywords; read line by line, other keywords' data (the
    nodes and elements) skipped.  Each data line is a str with its line ``number``.

    Raises
    ------
    ResultError
        A line longer than :data:`MAX_INP_LINE` (not a deck), naming the file and line.
    """
    blocks, current = [], None
    with open(inp_path, "rb") as f:
        for number, raw in enumerate(iter(lambda: f.readline(MAX_INP_LINE + 1), b""), 1):
            if len(raw) > MAX_INP_LINE and not raw.endswith(b"\n"):
                raise ResultError(f"{inp_path}: line {number}: longer than {MAX_INP_LINE} "
                                  f"characters: not a CalculiX deck")
            line = raw.decode("utf-8", errors="replace").strip()
            if not line or line.startswith("**"):
                continue
            if line.startswith("*"):
                current = (line.upper(), []) if line.upper().startswith(keep) else None
                if current is not None:
                    blocks.append(current)
            elif current is not None:
                current[1].append(_Line(line, number))
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
    try:
        blocks = _keyword_blocks(inp_path, ("*CONTACT PAIR", "*SURFACE,"))
    except OSError as exc:
        raise ResultError(f"{inp_path}: cannot read: {exc.strerror or exc}") from None
    pair = next((b for b in blocks if b[0].startswith("*CONTACT PAIR")), None)
    if pair is None or not pair[1]:
        raise ResultError(f"{inp_path}: no *CONTACT PAIR with a data line (slave, master)")
    name = pair[1][0].split(",")[0].strip().upper()
    faces, nodes, found = [], [], False
    sets: dict = {}

    def named(set_name: str, kind: str, where: str) -> np.ndarray:
        if kind not in sets:
            sets[kind] = named_sets(inp_path, kind)
        key = set_name.upper()
        if key not in sets[kind]:
            what = "node" if kind == "NSET" else "element"
            raise ResultError(f"{where}: expected a {what} number, got {set_name[:40]!r}, "
                              f"which is no {what} set of the deck either")
        return sets[kind][key]

    for key, data in blocks:
        if key.startswith("*SURFACE,") and (_param(key, "NAME") or "").upper() == name:
            found = True
            kind = (_param(key, "TYPE") or "ELEMENT").upper()
            for line in data:
                parts = [p.strip() for p in line.split(",") if p.strip()]
                where = f"{inp_path}: line {line.number}: surface {name}"
                if not parts:
                    continue
                if kind == "NODE":
                    for q in parts[:1] if parts[0].isdecimal() else parts:
                        if q.isdecimal():
                            nodes.append(deck_id(q, where, "node"))
                        else:  # a node set's name
                            nodes.extend(named(q, "NSET", where).tolist())
                elif len(parts) >= 2:
                    face = parts[1].upper()
                    if not re.fullmatch(r"S[1-6]", face):
                        raise ResultError(f"{where}: face {parts[1]!r} of element "
                                          f"{parts[0][:30]} (tetrahedra have S1..S4, "
                                          f"hexahedra S1..S6)")
                    elements = ([deck_id(parts[0], where, "element")] if parts[0].isdecimal()
                                else named(parts[0], "ELSET", where).tolist())
                    faces.extend((e, int(face[1])) for e in elements)
                else:
                    raise ResultError(f"{where}: cannot read {line!r} "
                                      f"(expected: element number, S1..S6)")
    if not found:
        raise ResultError(f"{inp_path}: the slave surface {name} of *CONTACT PAIR is not "
                          f"defined by a *SURFACE")
    if not faces and not nodes:
        raise ResultError(f"{inp_path}: the slave surface {name} of *CONTACT PAIR has no "
                          f"faces or nodes (its *SURFACE has no data lines)")
    return name, faces, nodes


def _surface(frd: FrdFile, faces, nodes, source: str):
    """Slave node numbers and triangles (as indices into them) from element faces."""
    if nodes and not faces:
        return np.unique(np.asarray(nodes, dtype=np.int64)), None
    if not len(frd.elements):
        raise ResultError(f"{frd.path}: holds no elements (no 3C block), so the slave faces "
                          f"of {source} cannot be found")
    order = np.argsort(frd.elements)
    ids = np.array([f[0] for f in faces], dtype=np.int64)
    pos = order[np.clip(np.searchsorted(frd.elements, ids, sorter=order), 0, len(order) - 1)]
    if np.any(frd.elements[pos] != ids):
        bad = ids[frd.elements[pos] != ids][0]
        raise ResultError(f"{source}: slave face on element {bad}, which the .frd does not "
                          f"hold: the deck does not match the result")
    types = frd.element_types[pos]
    if np.all(np.isin(types, _HEXES)):
        return _hex_surface(frd, pos, faces, source)
    if not np.all(np.isin(types, _TETS)):
        raise ResultError(f"{source}: the slave surface lies on elements of .frd type "
                          f"{sorted(set(types.tolist()) - {3, 6})}; this reader knows "
                          f"tetrahedra (types 3 and 6) and hexahedra (1 and 4), one kind "
                          f"on a surface")
    if any(f[1] > 4 for f in faces):
        bad = next(f for f in faces if f[1] > 4)
        raise ResultError(f"{source}: face S{bad[1]} of element {bad[0]}, a tetrahedron "
                          f"(S1..S4)")
    six = np.array([_TET_FACES[f[1]] for f in faces])
    quadratic = np.all(types == 6)
    local = six if quadratic else six[:, :3]
    conn = frd.connectivity[pos[:, None], local]
    surface, inverse = np.unique(conn, return_inverse=True)
    inverse = inverse.reshape(conn.shape)
    tri = inverse[:, list(_SPLIT6)].reshape(-1, 3) if quadratic else inverse
    return surface, tri


def _hex_surface(frd: FrdFile, pos: np.ndarray, faces, source: str):
    """Slave nodes and triangles of hexahedron faces: each face's four corners, as two
    triangles (a 20-node face's mid-side nodes are left out)."""
    quads = np.array([_HEX_FACES[f[1]] for f in faces])
    conn = frd.connectivity[pos[:, None], quads]
    if (conn <= 0).any():
        raise ResultError(f"{source}: a slave face's element has fewer nodes than a "
                          f"hexahedron in the .frd")
    surface, inverse = np.unique(conn, return_inverse=True)
    inverse = inverse.reshape(conn.shape)
    return surface, inverse[:, [0, 1, 2, 0, 2, 3]].reshape(-1, 3)


#: The faces of each element kind the readers know (0-based local nodes): 4-node
#: tetrahedra and hexahedra by their corners, 10-node tetrahedra with their mid-side nodes.
_ELEMENT_FACES = {3: [f[:3] for f in _TET_FACES.values()], 6: list(_TET_FACES.values()),
                  1: list(_HEX_FACES.values()), 4: list(_HEX_FACES.values())}
#: Each kind of face (by its number of nodes) as triangles of its local nodes.
_FACE_TRIANGLES = {3: ((0, 1, 2),), 4: ((0, 1, 2), (0, 2, 3)), 6: _SPLIT6}


def facing_triangles(frd: FrdFile, nodes: np.ndarray) -> np.ndarray | None:
    """The faces of the mesh's boundary whose nodes are all among ``nodes`` (node
    numbers: the surface that carries contact output), as triangles of indices into
    ``nodes``; None where no such face is found (the grader then triangulates the nodes
    in the contact plane).

    A face on the boundary belongs to one element only; a face whose nodes all carry
    contact output lies on the contact surface (CalculiX reports the slave's nodes, so
    the faces are the slave body's).  10-node tetrahedra's faces are split in four at
    their mid-side nodes, hexahedra's in two (a 20-node face by its corners).
    """
    nodes = np.unique(np.asarray(nodes, dtype=np.int64))
    if not len(frd.elements) or len(nodes) < 3:
        return None
    out = []
    for etype, local in _ELEMENT_FACES.items():
        rows = np.nonzero(frd.element_types == etype)[0]
        if not len(rows):
            continue
        faces = frd.connectivity[rows[:, None, None], np.array(local)[None]]
        faces = faces.reshape(-1, len(local[0]))
        faces = faces[np.isin(faces, nodes).all(axis=1)]
        if not len(faces):
            continue
        corners = np.sort(faces[:, :len(local[0]) if etype != 6 else 3], axis=1)
        _, first, count = np.unique(corners, axis=0, return_index=True, return_counts=True)
        faces = faces[first[count == 1]]  # on the boundary: one element only
        out.append(faces[:, list(_FACE_TRIANGLES[faces.shape[1]])].reshape(-1, 3))
    if not out:
        return None
    return np.searchsorted(nodes, np.vstack(out))


@dataclass(frozen=True)
class DeckSets:
    """What a deck says of its elements' grouping: element sets and materials.

    Attributes
    ----------
    elsets : dict
        ``{NAME: element numbers}`` (upper-case names): ``*ELEMENT, ELSET=`` and
        ``*ELSET`` (numbers, other sets' names, ``GENERATE``).
    sections : dict
        ``{ELSET: MATERIAL}`` of the ``*SOLID SECTION`` s (upper case).
    """

    elsets: dict
    sections: dict


def named_sets(inp_path, kind: str = "ELSET") -> dict:
    """``{NAME: numbers}`` (upper-case names) of a deck's element sets (``kind`` "ELSET":
    ``*ELEMENT, ELSET=`` and ``*ELSET``) or node sets ("NSET": ``*NODE, NSET=`` and
    ``*NSET``): numbers, other sets' names, ``GENERATE``.

    Raises
    ------
    ResultError
        Naming the file and line: a data line that is not numbers (or set names), a
        ``GENERATE`` line that is not start, end[, step]; a set that names an undefined
        set or itself.
    """
    inp_path = Path(inp_path)
    what = "element" if kind == "ELSET" else "node"
    define = "*ELEMENT" if kind == "ELSET" else "*NODE"
    try:
        blocks = _keyword_blocks(inp_path, (define, f"*{kind}"))
    except OSError as exc:
        raise ResultError(f"{inp_path}: cannot read: {exc.strerror or exc}") from None
    sets: dict[str, list] = {}
    for key, data in blocks:
        word = key.split(",")[0].strip()
        name = (_param(key, kind) or "").upper()
        if word == define and name:
            numbers, continued = sets.setdefault(name, []), False
            for line in data:
                if not continued:
                    head = line.split(",")[0].strip()
                    numbers.append(deck_id(head, f"{inp_path}: line {line.number}", what))
                continued = what == "element" and line.rstrip().endswith(",")
        elif word == f"*{kind}" and name:
            numbers = sets.setdefault(name, [])
            generate = re.search(r",\s*GENERATE\b", key) is not None
            for line in data:
                where = f"{inp_path}: line {line.number}: *{kind} {name}"
                parts = [q.strip() for q in line.split(",") if q.strip()]
                if generate:
                    if not 2 <= len(parts) <= 3 or not all(q.isdecimal() for q in parts):
                        raise ResultError(f"{where}: GENERATE takes start, end[, step], got "
                                          f"{line[:60]!r}")
                    a, b, step = (*map(int, parts), 1)[:3]
                    if step < 1 or b < a or (b - a) // step > 100_000_000:
                        raise ResultError(f"{where}: GENERATE {a}, {b}, {step}: expected "
                                          f"start <= end and a step >= 1")
                    numbers.extend(range(a, b + 1, step))
                    continue
                for q in parts:
                    if q.isdecimal():
                        numbers.append(deck_id(q, where, what))
                    else:
                        numbers.append(q.upper())  # another set's name, resolved below
    resolved: dict[str, np.ndarray] = {}

    def resolve(name, seen=()):
        if name in resolved:
            return resolved[name]
        if name in seen:
            raise ResultError(f"{inp_path}: *{kind} {name} contains itself")
        out = []
        for item in sets.get(name, []):
            if isinstance(item, str):
                if item not in sets:
                    raise ResultError(f"{inp_path}: *{kind} {name} names the set {item}, "
                                      f"which the deck does not define")
                out.extend(resolve(item, (*seen, name)).tolist())
            else:
                out.append(item)
        resolved[name] = np.unique(np.asarray(out, dtype=np.int64))
        return resolved[name]

    for name in sets:
        resolve(name)
    return resolved


def deck_sets(inp_path) -> DeckSets:
    """The element sets and the sections' materials of a deck (:class:`DeckSets`).

    Raises
    ------
    ResultError
        As :func:`named_sets`.
    """
    inp_path = Path(inp_path)
    elsets = named_sets(inp_path, "ELSET")
    try:
        blocks = _keyword_blocks(inp_path, ("*SOLID SECTION",))
    except OSError as exc:
        raise ResultError(f"{inp_path}: cannot read: {exc.strerror or exc}") from None
    sections = {}
    for key, _ in blocks:
        name = (_param(key, "ELSET") or "").upper()
        material = (_param(key, "MATERIAL") or "").upper()
        if name and material:
            sections[name] = material
    return DeckSets(elsets, sections)


def frd_materials(frd: FrdFile) -> dict[str, int]:
    """``{NAME: number}`` of the materials the .frd's header names (``MAT    1STEEL``)."""
    out = {}
    for h in frd.headers:
        m = re.match(r"MAT\s*(\d+)\s*(\S.*)$", h)
        if m:
            out[m.group(2).strip().upper()] = int(m.group(1))
    return out


def bodies(frd: FrdFile, inp_path, body1: str | None, source: str):
    """The two bodies of a CalculiX result: (element masks of body 1 and body 2 over
    ``frd.elements``, how they were told apart, whether the order is known).

    ``body1`` names an element set of the deck or a material (of the deck's sections or
    the .frd's header): its elements are body 1, all others body 2.  Otherwise two
    material numbers (material 1 body 1); otherwise the mesh's connected components
    (elements sharing nodes), which must be two; their order is then not known (False):
    the caller puts body 1 on the side the contact normal points to.

    Raises
    ------
    ResultError
        ``body1`` names no set or material of the files (the names they hold are
        listed), or takes every element or none; not two bodies.
    """
    mats = frd.element_materials
    if body1 is not None:
        key = str(body1).strip().upper()
        sets = deck_sets(inp_path) if inp_path is not None and Path(inp_path).is_file() \
            else DeckSets({}, {})
        numbers = materials = None
        if key in sets.elsets:
            numbers, how = sets.elsets[key], f"element set {key}"
        else:
            in_frd = frd_materials(frd)
            chosen = [e for e, m in sets.sections.items() if m == key]
            if chosen:
                numbers = np.unique(np.concatenate([sets.elsets.get(e, np.zeros(0, np.int64))
                                                    for e in chosen]))
                how = f"material {key} (sections of {', '.join(chosen)})"
            elif key in in_frd:
                materials, how = in_frd[key], f"material {key} (number {in_frd[key]})"
            else:
                known = sorted(set(sets.elsets) | set(sets.sections.values()) | set(in_frd))
                raise ResultError(f"{source}: body1 {body1!r} names no element set or "
                                  f"material of the files; they name: "
                                  f"{', '.join(known) or 'none (no deck beside the .frd)'}")
        one = np.isin(frd.elements, numbers) if materials is None else mats == materials
        if one.all() or not one.any():
            raise ResultError(f"{source}: body1 {body1!r} ({how}) holds "
                              f"{'every' if one.any() else 'no'} element of the .frd: name "
                              f"the set or material of one body only")
        return (one, ~one), how + " is body 1, the rest body 2", True
    found = sorted(set(mats.tolist()))
    if len(found) == 2:
        return (mats == found[0], mats == found[1]), \
            f"material numbers {found[0]} (body 1) and {found[1]} (body 2)", True
    if len(found) > 2:
        raise ResultError(f"{source}: expected two bodies, found {len(found)} material "
                          f"numbers on the elements ({found}): name body 1's element set or "
                          f"material (grade --body1 NAME)")
    labels = _components(frd)
    count = int(labels.max()) + 1 if len(labels) else 0
    if count != 2:
        raise ResultError(f"{source}: expected two bodies: one material on the elements and "
                          f"{count} connected parts of the mesh (elements sharing nodes): "
                          f"name body 1's element set or material (grade --body1 NAME)")
    return (labels == 0, labels == 1), "the mesh's two connected parts (one material)", False


def _components(frd: FrdFile) -> np.ndarray:
    """The connected part of each element (0, 1, ...): elements sharing a node are one."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    conn = frd.connectivity
    if not len(conn):
        return np.zeros(0, dtype=np.int64)
    n = len(frd.nodes)
    rows = np.repeat(np.arange(len(conn)), conn.shape[1])
    flat = conn.ravel()
    keep = flat > 0
    cols = frd.node_index(flat[keep])
    graph = coo_matrix((np.ones(int(keep.sum())), (rows[keep], len(conn) + cols)),
                       shape=(len(conn) + n, len(conn) + n))
    _, labels = connected_components(graph, directed=False)
    element_labels = labels[:len(conn)]
    _, dense = np.unique(element_labels, return_inverse=True)
    return dense


def _symmetry(xyz: np.ndarray) -> str:
    scale = np.abs(xyz).max()
    tol = SYMMETRY_TOL * scale
    x_half, y_half = xyz[:, 0].min() >= -tol, xyz[:, 1].min() >= -tol
    return "quarter" if x_half and y_half else "half" if x_half or y_half else "whole"


class _NotJson:
    """NaN, Infinity or -Infinity where problem.json holds them (Python's json takes them)."""

    def __init__(self, text: str):
        self.text = text


def _json_type(value) -> str:
    return {dict: "an object", list: "a list", str: "a string", bool: "true or false",
            type(None): "null"}.get(type(value), "a number")


def _first_not_json(value, key: str = "") -> tuple[str, str] | None:
    """(key, constant) of the first NaN or Infinity in a parsed problem.json, or None."""
    if isinstance(value, _NotJson):
        return key, value.text
    items = value.items() if isinstance(value, dict) else \
        enumerate(value) if isinstance(value, list) else ()
    for k, v in items:
        found = _first_not_json(v, f"{key}.{k}" if key else str(k))
        if found:
            return found
    return None


@dataclass(frozen=True)
class Problem:
    """What the CalculiX readers take from a deck's problem.json, checked.

    Attributes
    ----------
    path : str
    units : {"mm", "SI"}
        The deck's units: mm, N, MPa or m, N, Pa (``units.length``).
    names : dict
        ``units`` as the file writes them (``{"length": "mm", "stress": "MPa"}``).
    frame : dict
        Those of ``origin`` (in the deck's length unit), ``normal`` and ``x_axis`` that
        ``frame`` (``origin``, ``normal_into_body1``, ``body1_x_axis``) gives.
    approach : float or None
        ``loads.approach``, the prescribed approach [deck's length unit].
    far_face_depths : tuple of float or None
        ``model.far_face_depths``: depth of body 1's and body 2's far face [length unit].
    materials : tuple of (E, nu) or None
        ``materials.body1`` and ``body2``: E [deck's stress unit], nu.
    slave : {"CONTACT1", "CONTACT2"} or None
        ``contact.slave``.
    details : dict
        ``geometry``, ``level``, ``penalty_factor``, ``slave``, ``stick_slope``: those given.
    """

    path: str
    units: str
    names: dict
    frame: dict = field(default_factory=dict)
    approach: float | None = None
    far_face_depths: tuple | None = None
    materials: tuple | None = None
    slave: str | None = None
    details: dict = field(default_factory=dict)

    def need_materials(self, why: str) -> tuple:
        """:attr:`materials`, or a ResultError naming the key and ``why`` it is needed."""
        if self.materials is None:
            raise ResultError(f"problem.json {self.path!r}: no key 'materials' (body1 and "
                              f"body2, each with E and nu), which {why} needs")
        return self.materials


def read_problem(path) -> Problem:
    """Read and check problem.json of :mod:`fem_validation.decks` (capped at 1 MiB).

    Only ``units.length`` is required; every other key the readers use is checked where
    given: ``units.stress`` (MPa with mm, Pa with m), ``units.force`` (N), ``frame.origin``,
    ``frame.normal_into_body1``, ``frame.body1_x_axis`` (3 finite numbers; the axis
    orthogonal to the normal), ``loads.approach`` (finite), ``model.far_face_depths`` (2
    positive numbers), ``materials.body1`` / ``body2`` (``E`` > 0, -1 < ``nu`` < 0.5),
    ``model.geometry`` (text), ``model.level`` (an integer >= 0),
    ``contact.penalty_factor`` and ``friction.stick_slope`` (positive),
    ``contact.slave`` (CONTACT1 or CONTACT2).

    Raises
    ------
    ResultError
        One line naming the file and the key (or the line, for text that is not JSON):
        not JSON, NaN or Infinity anywhere, not an object, a required key missing, a key
        of the wrong type or out of range.
    """
    where = f"problem.json {str(path)!r}"
    text = read_small_text(path, "problem.json")
    try:
        info = json.loads(text, parse_constant=_NotJson)
    except json.JSONDecodeError as exc:
        raise ResultError(f"{where}, line {exc.lineno}: not JSON ({exc.msg})") from None
    except RecursionError:
        raise ResultError(f"{where}: nested too deeply to be a problem.json") from None
    except ValueError:  # an integer of more digits than Python converts (4300)
        digits = re.search(r"\d{1000,}", text)
        line = text[:digits.start()].count("\n") + 1 if digits else 1
        raise ResultError(f"{where}, line {line}: a number of "
                          f"{len(digits.group()) if digits else 'too many'} digits: not a "
                          f"number a problem.json holds") from None
    if not isinstance(info, dict):
        raise ResultError(f"{where}: must hold a JSON object ({{...}}), got "
                          f"{_json_type(info)}")
    bad = _first_not_json(info)
    if bad:
        raise ResultError(f"{where}: key {bad[0]!r} is {bad[1]}, which is not JSON (every "
                          f"number must be finite)")

    def get(key: str, kind, required: bool = False):
        node, parts = info, key.split(".")
        for i, part in enumerate(parts):
            if not isinstance(node, dict):
                raise ResultError(f"{where}: key {'.'.join(parts[:i])!r} must be an object, "
                                  f"got {_json_type(node)}")
            if part not in node:
                if required:
                    raise ResultError(f"{where}: no key {key!r}")
                return None
            node = node[part]
        return kind(node, key)

    def fail(key, value, allowed):
        shown = repr(value)
        if len(shown) > 80:  # a 400-digit integer, a long list
            shown = f"{shown[:40]}... ({len(shown)} characters)"
        raise ResultError(f"{where}: key {key!r} must be {allowed}, got {shown}")

    def number(value, key, low=-math.inf, allowed="a finite number"):
        if isinstance(value, bool) or not isinstance(value, int | float):
            fail(key, value, allowed)
        try:
            out = float(value)
        except OverflowError:  # an integer beyond the largest float
            fail(key, value, allowed)
        if not low < out < math.inf:
            fail(key, value, allowed)
        return out

    def positive(value, key):
        return number(value, key, 0.0, "a positive number")

    def vector(value, key):
        if not (isinstance(value, list) and len(value) == 3):
            fail(key, value, "a list of 3 finite numbers")
        out = [number(v, key, allowed="a list of 3 finite numbers") for v in value]
        return out

    def direction(value, key):
        out = vector(value, key)
        if not any(out):
            fail(key, value, "a nonzero vector")
        largest = max(abs(v) for v in out)  # 1e308s, 5e-324s: the direction they give
        return out if 1e-150 < largest < 1e150 else [v / largest for v in out]

    def text_(value, key):
        if not isinstance(value, str):
            fail(key, value, "a string")
        return value

    def one_of(*allowed):
        def check(value, key):
            if value not in allowed:
                fail(key, value, "one of " + ", ".join(map(repr, allowed)))
            return value
        return check

    def level(value, key):
        if isinstance(value, bool) or not isinstance(value, int) or value < 0:
            fail(key, value, "an integer 0 or more")
        return value

    def depths(value, key):
        # each a normal float in metres too: 5e-324 mm is 0 m, and no depth
        least = sys.float_info.min / UNIT_FACTORS[units][0]
        allowed = (f"a list of 2 positive numbers (body 1's, body 2's), each at least "
                   f"{least:.3g} {length}")
        if not (isinstance(value, list) and len(value) == 2):
            fail(key, value, allowed)
        out = tuple(number(v, key, allowed=allowed) for v in value)
        if not all(d >= least for d in out):
            fail(key, value, allowed)
        return out

    def material(value, key):
        if not isinstance(value, dict) or not {"E", "nu"} <= set(value):
            fail(key, value, "an object with E and nu")
        nu = number(value["nu"], f"{key}.nu")
        if not -1.0 < nu < 0.5:
            fail(f"{key}.nu", value["nu"], "between -1 and 0.5")
        return positive(value["E"], f"{key}.E"), nu

    length = get("units.length", one_of("mm", "m", "SI"), required=True)
    units = "mm" if length == "mm" else "SI"
    names = {"length": length}
    stress = get("units.stress", one_of("MPa", "Pa"))
    if stress is not None:
        want = "MPa" if units == "mm" else "Pa"
        if stress != want:
            fail("units.stress", stress, f"{want!r} (the stress unit of a deck in {length})")
        names["stress"] = stress
    if get("units.force", one_of("N")) is not None:
        names["force"] = "N"
    frame = {}
    for key, part, kind in (("frame.origin", "origin", vector),
                            ("frame.normal_into_body1", "normal", direction),
                            ("frame.body1_x_axis", "x_axis", direction)):
        value = get(key, kind)
        if value is not None:
            frame[part] = value
    if "normal" in frame and "x_axis" in frame:
        n, x = np.array(frame["normal"]), np.array(frame["x_axis"])
        if abs(n @ x) > 1e-6 * np.linalg.norm(n) * np.linalg.norm(x):
            fail("frame.body1_x_axis", frame["x_axis"], "orthogonal to "
                 f"frame.normal_into_body1 {frame['normal']}")
    materials = None
    if get("materials", lambda v, k: v) is not None:
        materials = tuple(get(f"materials.{b}", material, required=True)
                          for b in ("body1", "body2"))
    details = {}
    for key, name, kind in (("model.geometry", "geometry", text_),
                            ("model.level", "level", level),
                            ("contact.penalty_factor", "penalty_factor", positive),
                            ("contact.slave", "slave", one_of("CONTACT1", "CONTACT2")),
                            ("friction.stick_slope", "stick_slope", positive)):
        value = get(key, kind)
        if value is not None:
            details[name] = value
    return Problem(str(path), units, names, frame, get("loads.approach", number),
                   get("model.far_face_depths", depths), materials, details.get("slave"),
                   details)


def problem_beside(path, problem) -> Problem | None:
    """problem.json read: ``problem`` where given, else the one beside ``path`` if any."""
    if problem is not None:
        return read_problem(problem)
    beside = Path(path).parent / "problem.json"
    return read_problem(beside) if beside.is_file() else None


def deck_units(units: str | None, info: Problem | None, source: str) -> str:
    """The deck's units: problem.json's (``units`` must agree with them), else ``units``,
    else mm."""
    if info is not None:
        if units is not None and UNIT_FACTORS.get(units) != UNIT_FACTORS[info.units]:
            said = ", ".join(info.names.values())
            raise ResultError(f"{source}: units {units!r} contradict {info.path}, which "
                              f"says the deck is in {info.units} ({said}): give units "
                              f"{info.units!r}")
        units = info.units
    units = units or "mm"
    if units not in UNIT_FACTORS:
        raise ResultError(f"{source}: units must be one of mm, SI, got {units!r}")
    return units


def contact_frame(frame, info: Problem | None, to_m: float, points, weight,
                  symmetric: bool, source: str) -> ContactFrame:
    """The contact frame of a CalculiX result [m].

    ``frame`` where it is a ContactFrame.  Otherwise (None or a dict of some of
    ``origin`` [m], ``normal``, ``x_axis``, as the other readers take it): the parts
    given; the rest problem.json's (its x axis only where it is orthogonal to the
    normal); without problem.json, the standard frame where ``frame`` is None, else the
    parts not given found from the surface ``points`` [m] and their ``weight``
    (:func:`fem_validation.readers.common.resolve_frame`).
    """
    if isinstance(frame, ContactFrame):
        return frame
    if frame is not None and not isinstance(frame, dict):
        raise ResultError(f"{source}: frame must be a ContactFrame or a dict of origin, "
                          f"normal, x_axis, got {type(frame).__name__}")
    parts = {k: v for k, v in (frame or {}).items() if v is not None}
    unknown = set(parts) - {"origin", "normal", "x_axis"}
    if unknown:
        raise ResultError(f"{source}: frame takes origin, normal, x_axis, got "
                          f"{', '.join(sorted(unknown))}")
    if info is not None:
        own = {"origin": np.asarray(info.frame.get("origin", [0.0, 0.0, 0.0])) * to_m,
               "normal": info.frame.get("normal", [0.0, 0.0, 1.0]),
               "x_axis": info.frame.get("x_axis", [1.0, 0.0, 0.0])}
        parts.setdefault("origin", own["origin"])
        normal = unit_vector(parts.setdefault("normal", own["normal"]), "frame.normal", source)
        x_axis = unit_vector(own["x_axis"], "frame.x_axis", source)
        if "x_axis" not in parts and abs(normal @ x_axis) <= 1e-6:
            parts["x_axis"] = x_axis
    elif frame is None:
        return ContactFrame(source=source)
    if len(parts) < 3 and not (np.asarray(weight) > 0).any():
        raise ResultError(f"{source}: no slave node carries a positive contact pressure, so "
                          f"the contact frame cannot be found: give origin, normal and x axis")
    return resolve_frame(parts, points, weight, symmetric, source)


def components(result: FrdResult, names, source: str) -> np.ndarray:
    """The columns ``names`` of a result set, shape (n, len(names)).

    Raises
    ------
    ResultError
        Naming the file, the set and its line where a component is missing.
    """
    missing = [c for c in names if c not in result.components]
    if missing:
        raise ResultError(f"{source}: line {result.line}: result set {result.name} has no "
                          f"component {missing[0]!r} (it has "
                          f"{', '.join(result.components) or 'none'}); the reader needs "
                          f"{', '.join(names)}")
    return result.values[:, [result.components.index(c) for c in names]]


def read_calculix(path, inp=None, units: str | None = None, symmetry: str | None = None,
                  problem=None, stress: bool = True, tetrahedra: bool = False,
                  force: float | None = None, frame: ContactFrame | dict | None = None,
                  pressure_name: str = "CPRESS", body1: str | None = None) -> ContactResult:
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
        problem.json of :mod:`fem_validation.decks` (default: beside the .frd, if
        any), read by :func:`read_problem`.
    stress : bool
        Read the nodal stresses of both bodies (the von Mises maxima on the axis).
    force : float, optional
        The total normal force of the model in the file [N]: replaces body 1's
        reaction (times the multiplicity) as the result's force.
    frame : ContactFrame or dict, optional
        The contact frame [m]; or a dict of some of ``origin`` [m], ``normal``,
        ``x_axis``, the rest problem.json's, else found from the slave nodes' pressure
        (:func:`contact_frame`).  Default problem.json's, else the standard frame.
    pressure_name : str
        The contact pressure's component name (default CPRESS).
    body1 : str, optional
        An element set of the deck, or a material (the deck's or the .frd's), whose
        elements are body 1 (:func:`bodies`); default: the two material numbers, else
        the mesh's two connected parts.
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
        pressure, no reaction forces, a deck that does not match, a malformed .frd
        or problem.json, ...).
    """
    path = Path(path)
    source = str(path)
    try:
        frd = read_frd(path)
    except OSError as exc:
        raise ResultError(f"{source}: cannot read: {exc.strerror}") from None
    except ValueError as exc:
        raise ResultError(str(exc)) from None
    info = problem_beside(path, problem)
    units = deck_units(units, info, source)
    to_m, to_pa = UNIT_FACTORS[units]
    if not len(frd.nodes):
        raise ResultError(f"{source}: the node block holds no nodes")
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
        if tri is None:  # a surface of nodes: the boundary faces they cover
            tri = facing_triangles(frd, surface)
            how += "" if tri is None else ", on the mesh's boundary faces its nodes cover"
    else:
        contact = frd.result("CONTACT") if any(r.name == "CONTACT" for r in frd.results) \
            else None
        rows = np.any(contact.values != 0, axis=1) if contact is not None else cpress != 0
        surface = np.unique((contact.nodes if contact is not None else cnodes)[rows])
        tri = facing_triangles(frd, surface)
        how = ("nodes with contact output (no deck found)" + (
            ", on the mesh's boundary faces they cover" if tri is not None else ""))
    lookup = {n: i for i, n in enumerate(cnodes.tolist())}
    missing = [n for n in surface.tolist() if n not in lookup]
    if missing:
        raise ResultError(f"{source}: slave node {missing[0]} has no contact output: the deck "
                          f"does not match the result")
    pressure = cpress[[lookup[n] for n in surface.tolist()]] * to_pa
    xyz_all = frd.coordinates * to_m
    points = xyz_all[frd.node_index(surface)]
    sym = symmetry or _symmetry(xyz_all)

    # the two bodies: named, by material, or the mesh's connected parts
    masks, bodies_how, ordered = bodies(frd, inp_path if inp_path.is_file() else None,
                                        body1, source)
    body_nodes = [np.unique(frd.connectivity[m]) for m in masks]
    body_nodes = [n[n > 0] for n in body_nodes]
    try:
        rnodes, rz = frd.field("F3")
    except KeyError:
        raise ResultError(f"{source}: no reaction forces (FORC F3): the deck needs "
                          f"*NODE FILE with RF") from None
    mult = {"whole": 1, "half": 2, "quarter": 4}.get(sym)
    if mult is None:
        raise ResultError(f"{source}: symmetry must be one of whole, half, quarter, got "
                          f"{sym!r}")
    if sym in ("quarter", "half") and info is None and isinstance(frame, dict) \
            and frame.get("normal") is None:
        # a quarter model (x >= 0, y >= 0): the normal is the symmetry planes' line, z (a
        # half model's, in its plane: z, as a deck's); found from a curved surface cut by
        # the planes it would lean a little towards them
        frame = {**frame, "normal": [0.0, 0.0, 1.0]}
    frame = contact_frame(frame, info, to_m, points, pressure, sym != "whole", source)
    if not ordered:
        # body 1 lies on the side the normal points to: its nodes' centroid is the higher
        height = [float(np.mean(xyz_all[frd.node_index(n)] @ frame.normal)) for n in body_nodes]
        if height[1] > height[0]:
            masks, body_nodes = masks[::-1], body_nodes[::-1]
        bodies_how += ": body 1 on the side the contact normal points to"
    forc = next((r for r in reversed(frd.results) if "F3" in r.components), None)
    if forc is not None and {"F1", "F2"} <= set(forc.components):
        rnodes = forc.nodes
        along = components(forc, ("F1", "F2", "F3"), source) @ np.asarray(frame.normal)
    else:
        along = rz * float(np.asarray(frame.normal)[2])
    reactions = [mult * abs(float(along[np.isin(rnodes, n)].sum())) for n in body_nodes]
    reaction = reactions[1]
    if force is not None:
        force = mult * float(force)
    elif reactions[0] <= 1e-6 * reactions[1]:
        # body 1 loaded by a force (*CLOAD), not a displacement: no reaction on it, and
        # body 2's clamped face carries the force; no independent check is left
        force, reaction = reactions[1], None
        bodies_how += "; body 1 carries no reaction (loaded by a force): the force is body 2's"
    else:
        force = reactions[0]

    details = {"solver": "CalculiX", "file": source, "units": units, "contact_surface": how,
               "bodies": bodies_how,
               "nodes": len(frd.nodes), "elements": len(frd.elements),
               "version": next((h.split(None, 1)[1].strip() for h in frd.headers
                                if h.startswith("VERSION")), "")}
    approach = None
    if info is not None:
        approach = _approach(info, force, to_m, to_pa)
        details |= {k: v for k, v in info.details.items() if k != "stick_slope"}
        details["approach_note"] = ("prescribed approach plus the Boussinesq settlement of "
                                    "half-spaces at the far faces' depths, at the force")
    stresses = []
    if stress and any(r.name == "STRESS" for r in frd.results):
        st = frd.result("STRESS")
        sig = stress_from_voigt(components(st, ("SXX", "SYY", "SZZ", "SXY", "SYZ", "SZX"),
                                           source), "xx yy zz xy yz xz") * to_pa
        rows = frd.node_index(st.nodes)
        tetra = np.isin(frd.element_types, (3, 6))  # corner tetrahedra of tetrahedra only
        for body, (mask, nodes) in enumerate(zip(masks, body_nodes, strict=True), start=1):
            keep = np.isin(st.nodes, nodes)
            where = rows[keep]
            local = np.full(len(frd.nodes), -1, dtype=np.int64)
            local[where] = np.arange(keep.sum())
            conn = frd.connectivity[mask & tetra][:, :4]
            tets = local[frd.node_index(conn.ravel())].reshape(-1, 4)
            tets = tets[np.all(tets >= 0, axis=1)]
            stresses.append(BodyStress(body, xyz_all[where], sig[keep],
                                       tetrahedra=tets if tetrahedra else None,
                                       source=source))
    return ContactResult(points=points, force=force, pressure=pressure, symmetry=sym,
                         frame=frame, triangles=tri, approach=approach, reaction=reaction,
                         stress=tuple(stresses), source=source, details=details)


def _approach(info: Problem, force: float, to_m: float, to_pa: float) -> float | None:
    """The prescribed approach plus the far faces' Boussinesq settlement at ``force`` [m]."""
    from ..halfspace import boussinesq_settlement

    if info.approach is None or info.far_face_depths is None:
        return None
    total = info.approach * to_m
    materials = info.need_materials("the settlement of the far faces (loads.approach, "
                                    "model.far_face_depths)")
    try:
        for (E, nu), depth in zip(materials, info.far_face_depths, strict=True):
            total += boussinesq_settlement(force, E * to_pa, nu, depth * to_m)
    except (ArithmeticError, ValueError):  # E times depth underflows to 0
        total = math.nan
    if not math.isfinite(total):
        raise ResultError(f"problem.json {info.path!r}: keys 'loads.approach', "
                          f"'model.far_face_depths' and 'materials' give an approach of "
                          f"{total} m at the force {force:.6g} N, not a finite number: "
                          f"check their values")
    return total


def read_result(path, *, units: str = "SI", symmetry: str | None = None,
                force: float | None = None, frame=None, fields: dict | None = None):
    """A CalculiX .frd as a :class:`~fem_validation.results.contact.ContactResult` (the interface of
    :func:`fem_validation.readers.read_result`).

    See :func:`fem_validation.readers.calculix.read_calculix`; ``fields`` may name
    the pressure component (``{"pressure": "CPRESS"}``) and body 1's element set or
    material (``{"body1": "BALL"}``).  Where the deck's problem.json lies beside the
    file, its units must agree with ``units``.
    """
    fields = dict(fields or {})
    unknown = set(fields) - {"pressure", "body1"}
    if unknown:
        raise ResultError(f"{path}: a .frd takes only the field 'pressure' (a component "
                          f"name such as CPRESS) and 'body1' (an element set or material "
                          f"of body 1), got {', '.join(sorted(unknown))}")
    return read_calculix(path, units=units, symmetry=symmetry, force=force, frame=frame,
                         pressure_name=fields.get("pressure", "CPRESS"),
                         body1=fields.get("body1"))
