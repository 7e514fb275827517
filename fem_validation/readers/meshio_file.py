"""Any mesh file meshio reads (VTU, XDMF, Exodus, MED, ...) with nodal contact fields.

The file holds the mesh (tetrahedra, linear or quadratic, and/or surface
triangles) and point fields.  Found by name (case-insensitive; or given as
``fields``, ``NAME`` or ``NAME:COMPONENT``):

* contact pressure (CPRESS, contact_pressure, pressure, p, ...; a field with
  several components needs its component, e.g. ``CONTACT:3`` for CalculiX's
  CONTACT block, whose fourth component is CPRESS) and/or the nodal normal
  contact force (normal_force, CNORMF, ...);
* the reaction RF (for the total force, where ``force`` is not given);
* the stress S (6 Voigt components xx yy zz xy yz xz, or 9), graded per body:
  the bodies are the mesh's connected parts, body 1 the one on the side the
  contact normal points to.

The contact surface is the surface triangles (given, or the tetrahedra's
boundary faces) that touch a node with positive pressure, grown by two rings of
neighbours, so that the edge of contact lies inside it.  Quadratic faces are
split into four linear triangles through their mid-side nodes.
"""

from __future__ import annotations

import base64
import binascii
import contextlib
import io
import lzma
import re
import zlib
from pathlib import Path

import numpy as np

from ..results.contact import (
    BodyStress,
    ContactFrame,
    ContactResult,
    ResultError,
    stress_from_voigt,
    surface_points,
)
from .common import (
    NORMAL_FORCE_NAMES,
    PRESSURE_NAMES,
    REACTION_NAMES,
    STRESS_NAMES,
    detect_symmetry,
    finish,
    force_from_reaction,
    resolve_frame,
    units_of,
)

#: Faces of a tetrahedron (corner indices) and, for 10-node tetrahedra in meshio's (VTK's)
#: order (corners 0-3, then edges 01, 12, 02, 03, 13, 23), each face's mid-side nodes in
#: the order of its edges (c0 c1, c1 c2, c2 c0).
TET_FACES = ((0, 1, 2), (0, 1, 3), (1, 2, 3), (0, 2, 3))
TET10_FACE_MIDS = ((4, 5, 6), (4, 8, 7), (5, 9, 8), (6, 9, 7))
#: Nodes of each cell type the reader uses.
NODES_PER_CELL = {"triangle": 3, "triangle6": 6, "tetra": 4, "tetra10": 10}


def _mesh_points(mesh, src: str) -> np.ndarray:
    """The mesh's points (n, 3), checked: 2 or 3 finite coordinates each, and every cell's
    node indices in 0..n-1 (a negative index would silently wrap to the last points)."""
    try:
        points = np.asarray(mesh.points, dtype=float)
    except (TypeError, ValueError) as exc:
        raise ResultError(f"{src}: the points are not numbers: {exc}"[:300]) from None
    if points.ndim != 2 or points.shape[1] not in (2, 3):
        raise ResultError(f"{src}: the points must have 2 or 3 coordinates each, got an array "
                          f"of shape {points.shape}")
    bad = ~np.isfinite(points).all(axis=1)
    if bad.any():
        raise ResultError(f"{src}: {int(bad.sum())} point(s) with a non-finite coordinate, "
                          f"first point {int(np.argmax(bad))}: {points[int(np.argmax(bad))]}")
    n = len(points)
    for k, block in enumerate(mesh.cells):
        data = np.asarray(block.data)
        if data.size == 0:
            continue
        width = NODES_PER_CELL.get(block.type)
        if data.dtype.kind not in "iu" or data.ndim != 2 or width not in (None, data.shape[1]):
            raise ResultError(f"{src}: cell block {k} ({block.type}) holds {data.dtype} of "
                              f"shape {data.shape}, not rows of "
                              f"{width or 'its cells'} node indices")
        low, high = int(data.min()), int(data.max())
        if low < 0 or high >= n:
            cell = int(np.argmax(((data < 0) | (data >= n)).any(axis=1)))
            raise ResultError(f"{src}: cell {cell} of block {k} ({block.type}) has node index "
                              f"{low if low < 0 else high}; the mesh has {n} points "
                              f"(indices 0..{n - 1})")
    if points.shape[1] == 2:
        points = np.column_stack([points, np.zeros(n)])
    return points


def _field(point_data: dict, names, role: str, given: str | None, src: str, n_points: int):
    """(name, values) of a point field of one value (or row) per point, or (None, None)."""
    lower = {k.lower(): k for k in point_data}
    component = None
    if given is not None:
        name, _, comp = given.partition(":")
        if name.lower() not in lower:
            raise ResultError(f"{src}: no point field {name!r} for the {role} (point fields: "
                              f"{', '.join(point_data) or 'none'})")
        key = lower[name.lower()]
        if comp:
            try:
                component = int(comp)
            except ValueError:
                raise ResultError(f"{src}: the {role} field's component must be an integer, "
                                  f"got {comp!r}") from None
    else:
        key = next((lower[n] for n in names if n in lower), None)
        if key is None:
            return None, None
    try:
        values = np.asarray(point_data[key], dtype=float)
    except (TypeError, ValueError) as exc:
        raise ResultError(f"{src}: point field {key!r} ({role}) is not numeric: {exc}"[:300]) \
            from None
    if values.ndim == 0 or len(values) != n_points:
        raise ResultError(f"{src}: point field {key!r} ({role}) has shape {values.shape}; the "
                          f"mesh has {n_points} points")
    if component is not None:
        if values.ndim != 2 or not 0 <= component < values.shape[1]:
            raise ResultError(f"{src}: field {key!r} has shape {values.shape}, no component "
                              f"{component}")
        values = values[:, component]
    return key, values


def _scalar(key, values, role, src):
    if values is None:
        return None
    if values.ndim == 2 and values.shape[1] == 1:
        values = values[:, 0]
    if values.ndim != 1:
        raise ResultError(f"{src}: field {key!r} ({role}) has shape {values.shape}: name its "
                          f"component, e.g. {key}:0")
    return values


def _surface_faces(mesh) -> np.ndarray:
    """Linear surface triangles (m, 3): the file's triangles, else the tetrahedra's boundary."""
    tris = []
    for block in mesh.cells:
        if block.type == "triangle":
            tris.append(block.data[:, :3])
        elif block.type == "triangle6":
            d = block.data
            tris += [d[:, [0, 3, 5]], d[:, [3, 1, 4]], d[:, [5, 4, 2]], d[:, [3, 4, 5]]]
    if tris:
        return np.concatenate(tris)
    faces, split = [], []
    for block in mesh.cells:
        if block.type not in ("tetra", "tetra10"):
            continue
        d = block.data
        for k, corners in enumerate(TET_FACES):
            f = d[:, corners]
            faces.append(f)
            split.append(d[:, TET10_FACE_MIDS[k]] if block.type == "tetra10"
                         else np.full((len(d), 3), -1))
    if not faces:
        return np.zeros((0, 3), dtype=np.int64)
    faces, mids = np.concatenate(faces), np.concatenate(split)
    key = np.sort(faces, axis=1)
    _, index, count = np.unique(key, axis=0, return_index=True, return_counts=True)
    boundary = index[count == 1]
    faces, mids = faces[boundary], mids[boundary]
    linear = mids[:, 0] < 0
    out = [faces[linear]]
    f, m = faces[~linear], mids[~linear]
    out += [np.column_stack([f[:, 0], m[:, 0], m[:, 2]]),
            np.column_stack([m[:, 0], f[:, 1], m[:, 1]]),
            np.column_stack([m[:, 2], m[:, 1], f[:, 2]]), m]
    return np.concatenate(out)


def contact_surface(faces: np.ndarray, weight: np.ndarray, rings: int = 2) -> np.ndarray:
    """The faces touching a node with weight > 0, grown by ``rings`` rings of neighbours."""
    nodes = weight > 0
    selected = nodes[faces].any(axis=1)
    for _ in range(rings):
        touched = np.zeros_like(nodes)
        touched[faces[selected].ravel()] = True
        selected = touched[faces].any(axis=1)
    return faces[selected]


def _bodies(mesh, n_points: int):
    """Connected parts of the tetrahedra: (labels per node, -1 off the tetrahedra), corner tets."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    tets = [b.data for b in mesh.cells if b.type in ("tetra", "tetra10")]
    if not tets:
        return None, None
    corners = np.concatenate([t[:, :4] for t in tets])
    alln = np.concatenate([t.ravel() for t in tets])
    rows = np.concatenate([np.repeat(t[:, 0], t.shape[1]) for t in tets])
    graph = coo_matrix((np.ones(len(rows)), (rows, alln)), shape=(n_points, n_points))
    _, labels = connected_components(graph, directed=False)
    used = np.zeros(n_points, dtype=bool)
    used[alln] = True
    labels = np.where(used, labels, -1)
    return labels, corners


#: The most bytes the compressed arrays of a .vtu may inflate to, in all (2 GiB), and per
#: point and cell its pieces declare (4 KiB: 512 float64 values; plus 1 MiB).
MAX_INFLATED = 2 << 30
INFLATED_PER_ITEM = 4096
#: Bytes of inflated output checked at a time.
_INFLATE_STEP = 1 << 20
_VTU_HEADER_TYPES = {"UInt32": 4, "UInt64": 8}


#: An XML attribute, matched only from the start of its name (no quadratic backtracking
#: through a long run of name characters).
_ATTRIBUTE = re.compile(rb'(?<![\w:])([\w:]+)\s*=\s*"([^"]*)"')


def _xml_attributes(tag: bytes) -> dict:
    return {k.decode("latin-1"): v.decode("latin-1")
            for k, v in _ATTRIBUTE.findall(tag)}


def _inflated_size(block: bytes, decompressor, limit: int) -> int | None:
    """The bytes ``block`` inflates to, found ``_INFLATE_STEP`` at a time; None once past
    ``limit`` (nothing more is inflated)."""
    produced = 0
    if hasattr(decompressor, "unconsumed_tail"):  # zlib
        data = block
        while True:
            out = decompressor.decompress(data, _INFLATE_STEP)
            produced += len(out)
            if produced > limit:
                return None
            data = decompressor.unconsumed_tail
            if not data and len(out) < _INFLATE_STEP:
                return produced
    out = decompressor.decompress(block, _INFLATE_STEP)  # lzma
    while True:
        produced += len(out)
        if produced > limit:
            return None
        if decompressor.eof or decompressor.needs_input:
            return produced
        out = decompressor.decompress(b"", _INFLATE_STEP)


def check_vtu_inflation(path, src: str) -> None:
    """Refuse a compressed .vtu whose arrays would inflate past what a result needs, before
    meshio inflates them (it inflates every block whole, trusting nothing but the data).

    The header of each compressed DataArray (vtkZLibDataCompressor or
    vtkLZMADataCompressor; inline base64, appended base64 or appended raw) gives its
    blocks' inflated sizes: their sum over the file must stay within
    :data:`INFLATED_PER_ITEM` bytes per point and cell its pieces declare (plus 1 MiB),
    and within :data:`MAX_INFLATED`; then each block is inflated a step at a time, the
    output dropped, and must not exceed the size its header declares.  A file that is not
    compressed, or whose layout this scan cannot make out, is left to meshio (whose error
    names the file).

    Raises
    ------
    ResultError
        Naming the file and the DataArray.
    """
    import mmap

    try:
        with open(path, "rb") as f:
            mm = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ)
    except (OSError, ValueError):  # empty, or not a regular file: meshio says what it is
        return
    with mm:
        _scan_vtu(mm, src)


def _b64(data: bytes, where: str) -> bytes:
    try:
        return base64.b64decode(data)
    except binascii.Error as exc:
        raise ResultError(f"{where}: not base64 data ({exc}): the file is cut or corrupt") \
            from None


_VTKFILE = re.compile(rb"<VTKFile\b([^>]{0,4096})>")
_APPENDED = re.compile(rb"<AppendedData\b([^>]{0,4096})>")
_PIECE = re.compile(rb"<Piece\b([^>]{0,4096})>")
_DATA_ARRAY = re.compile(rb"<DataArray\b([^>]{0,4096})>")
_CORRUPT = (zlib.error, lzma.LZMAError, EOFError)


def _data_arrays(mm, end: int, src: str):
    """The DataArray start tags before ``end``; one longer than 4096 characters (which the
    scan would pass over unchecked) is refused."""
    at = mm.find(b"<DataArray", 0, end)
    while at >= 0:
        tag = _DATA_ARRAY.match(mm, at, end)
        if tag is not None:
            yield tag
        elif not mm[at + 10:at + 11].isalnum():
            raise ResultError(f"{src}, byte {at}: a DataArray tag longer than 4096 "
                              f"characters: not a mesh file (is it the right file?)")
        at = mm.find(b"<DataArray", at + 10, end)


def _scan_vtu(mm, src: str) -> None:
    """:func:`check_vtu_inflation` on the file's bytes ``mm``."""
    root = _VTKFILE.search(mm, 0, 1 << 16)
    if root is None:
        return
    attrs = _xml_attributes(root.group(1))
    make = {"vtkZLibDataCompressor": zlib.decompressobj,
            "vtkLZMADataCompressor": lzma.LZMADecompressor}.get(attrs.get("compressor", ""))
    size = _VTU_HEADER_TYPES.get(attrs.get("header_type", "UInt32"))
    if make is None or size is None:
        return
    item = np.dtype(f"{'>' if attrs.get('byte_order') == 'BigEndian' else '<'}u{size}")
    appended = _APPENDED.search(mm)
    end = appended.start() if appended else len(mm)
    raw_at = b64_at = None  # where the appended data start, after its "_"
    if appended is not None:
        underscore = mm.find(b"_", appended.end())
        if underscore < 0:
            return
        if _xml_attributes(appended.group(1)).get("encoding") == "raw":
            raw_at = underscore + 1
        else:
            b64_at = underscore + 1

    def integer(text: str) -> int:
        try:
            return max(int(text), 0)
        except ValueError:
            return 0

    points = cells = 0
    for piece in _PIECE.finditer(mm, 0, end):
        a = _xml_attributes(piece.group(1))
        points += integer(a.get("NumberOfPoints", "0"))
        cells += integer(a.get("NumberOfCells", "0"))
    cap = min(MAX_INFLATED, (1 << 20) + INFLATED_PER_ITEM * (points + cells))

    arrays, total = [], 0
    for tag in _data_arrays(mm, end, src):
        a = _xml_attributes(tag.group(1))
        fmt = a.get("format", "ascii")
        if fmt == "binary":
            at, raw = tag.end(), False
            while at < len(mm) and mm[at:at + 1].isspace():
                at += 1
        elif fmt == "appended" and raw_at is not None:
            at, raw = raw_at + integer(a.get("offset", "0")), True
        elif fmt == "appended" and b64_at is not None:
            at, raw = b64_at + integer(a.get("offset", "0")), False
        else:
            continue
        where = f"{src}: DataArray {a.get('Name', '?')!r}"

        def decoded(start: int, n: int, raw=raw, where=where) -> bytes:
            """``n`` bytes from ``start``, as they are (raw) or base64-decoded."""
            if raw:
                return bytes(mm[start:start + n])
            return _b64(bytes(mm[start:start - (-n // 3) * 4]), where)[:n]

        first = decoded(at, size)
        if len(first) < size:
            continue
        blocks = int(np.frombuffer(first, item)[0])
        after = (len(mm) - at) * (1 if raw else 3) // (1 if raw else 4)
        if (3 + blocks) * size > after:
            raise ResultError(f"{where}: its compression header announces {blocks} blocks, "
                              f"more than the {after} bytes after it hold: the file is cut "
                              f"or corrupt")
        head_size = (3 + blocks) * size
        head = np.frombuffer(decoded(at, head_size), item).astype(np.int64)
        if len(head) < 3 + blocks:
            continue
        sizes = [int(head[1])] * blocks
        if blocks and head[2]:
            sizes[-1] = int(head[2])
        total += sum(sizes)
        if total > cap:
            raise ResultError(f"{where}: the compressed arrays declare {total} bytes once "
                              f"inflated (this one {sum(sizes)}); a grid of {points} points "
                              f"and {cells} cells needs at most {cap}: refused before "
                              f"inflating them (a zip bomb, or a corrupt header?)")
        packed = head[3:].tolist()
        start = at + (head_size if raw else -(-head_size // 3) * 4)
        arrays.append((where, start, raw, sizes, packed))

    for where, start, raw, sizes, packed in arrays:
        if raw:
            data, start = mm, start
        else:
            data, start = _b64(bytes(mm[start:start - (-sum(packed) // 3) * 4]), where), 0
        for k, (want, length) in enumerate(zip(sizes, packed, strict=True)):
            try:
                got = _inflated_size(bytes(data[start:start + length]), make(), want)
            except _CORRUPT as exc:
                raise ResultError(f"{where}: compressed block {k} is corrupt ({exc})"[:400]) \
                    from None
            if got is None:
                raise ResultError(f"{where}: compressed block {k} inflates past the {want} "
                                  f"bytes its header declares: refused (a zip bomb, or a "
                                  f"corrupt file)")
            start += length


def read_mesh(path, *, units: str | None = None, symmetry: str | None = None,
              force: float | None = None, frame: ContactFrame | None = None,
              fields: dict | None = None) -> ContactResult:
    """A ContactResult from a mesh file meshio reads (see the module docstring).

    Raises
    ------
    ResultError
        Naming the file and the field: unreadable file, no contact pressure or force
        field, a field with NaN, an empty contact, no total force.
    """
    import meshio

    path = Path(path)
    src = str(path)
    fields = dict(fields or {})
    units = units or "SI"
    if path.suffix.lower() == ".vtu":
        check_vtu_inflation(path, src)
    try:  # meshio prints its complaints and may call sys.exit: keep it quiet, catch both
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            mesh = meshio.read(path)
    except (Exception, SystemExit) as exc:  # meshio raises many types for bad files
        reason = str(exc) if not isinstance(exc, SystemExit) else "not a valid file"
        raise ResultError(f"{src}: meshio cannot read it: {reason}"[:400]) from None
    length, force_unit, pressure_unit = units_of(units, f"{src}: ")
    points = _mesh_points(mesh, src) * length
    pkey, pressure = _field(mesh.point_data, PRESSURE_NAMES, "contact pressure",
                            fields.get("pressure"), src, len(points))
    fkey, normal_force = _field(mesh.point_data, NORMAL_FORCE_NAMES, "nodal contact force",
                                fields.get("normal_force"), src, len(points))
    pressure = _scalar(pkey, pressure, "contact pressure", src)
    normal_force = _scalar(fkey, normal_force, "nodal contact force", src)
    if pressure is None and normal_force is None:
        raise ResultError(f"{src}: no contact pressure field (looked for "
                          f"{', '.join(PRESSURE_NAMES[:4])}, ...) and no nodal contact force "
                          f"field; point fields: {', '.join(mesh.point_data) or 'none'}; name "
                          f"one with --pressure-field NAME[:COMPONENT]")
    weight = pressure if pressure is not None else normal_force
    role = pkey if pressure is not None else fkey
    bad = ~np.isfinite(weight)
    if bad.any():
        raise ResultError(f"{src}: field {role!r} has {int(bad.sum())} non-finite value(s), "
                          f"first at point {int(np.argmax(bad))}")
    if not (weight > 0).any():
        raise ResultError(f"{src}: the contact is empty: field {role!r} has no positive value "
                          f"(largest {weight.max():.6g})")
    faces = _surface_faces(mesh)
    if len(faces):
        faces = contact_surface(faces, weight)
        nodes = np.unique(faces)
    else:
        nodes = np.nonzero(weight > 0)[0]
    index = np.full(len(points), -1)
    index[nodes] = np.arange(len(nodes))
    triangles = index[faces] if len(faces) else None
    surface = surface_points(points[nodes], src)  # an area, at a scale Hertz handles
    p_s = None if pressure is None else pressure[nodes] * pressure_unit
    f_s = None if normal_force is None else normal_force[nodes] * force_unit
    w_s = weight[nodes]
    if not isinstance(frame, ContactFrame):
        sym = symmetry
        if sym is None:
            probe = resolve_frame(frame, surface, w_s, True, src)
            sym = detect_symmetry(probe.to_frame(surface)[:, :2], w_s)
        frame = resolve_frame(frame, surface, w_s, sym != "whole", src)
        symmetry = sym
    if force is None:
        rkey, rf = _field(mesh.point_data, REACTION_NAMES, "reaction", fields.get("reaction"),
                          src, len(points))
        if rf is not None:
            if rf.ndim != 2 or rf.shape[1] < 3:
                raise ResultError(f"{src}: reaction field {rkey!r} must have 3 components, "
                                  f"got shape {rf.shape}")
            force = force_from_reaction(rf[:, :3], frame.normal, f"{src}: field {rkey!r}: ")
    stress = []
    skey, sig = _field(mesh.point_data, STRESS_NAMES, "stress", fields.get("stress"), src,
                       len(points))
    if sig is not None:
        if sig.ndim != 2 or sig.shape[1] not in (6, 9):
            raise ResultError(f"{src}: stress field {skey!r} must have 6 (xx yy zz xy yz xz) "
                              f"or 9 components, got shape {sig.shape}")
        tensors = (stress_from_voigt(sig) if sig.shape[1] == 6 else sig.reshape(-1, 3, 3))
        tensors = tensors * pressure_unit
        labels, corners = _bodies(mesh, len(points))
        if labels is not None:
            parts = [k for k in np.unique(labels) if k >= 0]
            heights = {k: float(np.mean((points[labels == k] - frame.origin) @ frame.normal))
                       for k in parts}
            order = sorted(parts, key=lambda k: -heights[k])[:2]
            for k in order:
                body = 1 if heights[k] > 0 else 2
                if any(st.body == body for st in stress):
                    continue
                own = np.nonzero(labels == k)[0]
                local = np.full(len(points), -1)
                local[own] = np.arange(len(own))
                tets = local[corners[labels[corners[:, 0]] == k]]
                stress.append(BodyStress(body=body, points=points[own], stress=tensors[own],
                                         tetrahedra=tets, source=src))
    return finish(surface, p_s, f_s, force if force is None else float(force) * force_unit,
                  symmetry, frame, triangles=triangles, stress=stress, source=src,
                  details={"reader": f"meshio ({path.suffix})", "units": units,
                           "pressure_field": pkey, "normal_force_field": fkey,
                           "stress_field": skey})
