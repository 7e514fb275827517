"""Read CalculiX result files (.frd), ASCII and binary, into numpy arrays.

The .frd format (CalculiX GraphiX's "results format") is a sequence of
blocks, each opened by a fixed-column key line:

* ``    1C`` / ``    1U...`` / ``    1P...``: headers (kept as text);
* ``    2C``: the nodes: number and x, y, z;
* ``    3C``: the elements: number, type (1 he8, 2 pe6, 3 te4, 4 he20, 5 pe15,
  6 te10, 7 tr3, 8 tr6, 9 qu4, 10 qu8, 11 be2, 12 be3), group, material and
  the node numbers;
* ``  100C``: one nodal result set: a ``-4`` line with its name (DISP,
  STRESS, FORC, CONTACT, ...), ``-5`` lines naming the components (D1, D2,
  D3; SXX ... SZX; COPEN, CSLIP1, CSLIP2, CPRESS, CSHEAR1, CSHEAR2), then one
  record per node;
* ``9999``: the end.

The last field of each ``2C``, ``3C`` and ``100C`` key line says how its
records are written: 0 or 1 ASCII (node numbers 5 or 10 wide, values 12
wide, ``-1`` records, ``-2`` continuations, ``-3`` to close), 2 binary
with 4-byte integers and 4-byte floats, 3 binary with 8-byte floats (little
endian).  CalculiX writes ASCII for ``*NODE FILE`` / ``*EL FILE`` /
``*CONTACT FILE`` and binary for ``*NODE OUTPUT`` / ``*ELEMENT OUTPUT`` /
``*CONTACT OUTPUT`` (floats for results, doubles for coordinates).  A
component flagged as computed (the ``ALL`` magnitude of a vector) has no
values in the records and is not returned.
"""

from __future__ import annotations

from array import array
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..limits import check_count, file_size

#: What :func:`fem_validation.limits.file_size` says of a device or a pipe.
UNBOUNDED = 1 << 62

#: Nodes per element for each .frd element type.
ELEMENT_NODES = {1: 8, 2: 6, 3: 4, 4: 20, 5: 15, 6: 10, 7: 3, 8: 6, 9: 4, 10: 8, 11: 2, 12: 3}
_SIZES = np.array([ELEMENT_NODES.get(t, 0) for t in range(13)])


class FrdFormatError(ValueError):
    """The file is not a .frd file this reader understands; the message names file and line."""


@dataclass(frozen=True)
class FrdResult:
    """One nodal result set of a .frd file.

    Attributes
    ----------
    name : str
        Its name: DISP, STRESS, FORC (reaction forces), CONTACT, ERROR, ...
    components : tuple of str
        The names of the stored components (D1, D2, D3; SXX, SYY, SZZ, SXY,
        SYZ, SZX; COPEN, CSLIP1, CSLIP2, CPRESS, CSHEAR1, CSHEAR2; ...).
    step : int
        The step number of the set (CalculiX counts increments here).
    time : float
        The step time (the analysis' time value) of the set.
    nodes : ndarray of int
        Node numbers.
    values : ndarray, shape (len(nodes), len(components))
        The values, in the deck's units.
    line : int
        The line of its key (``100C``) in the file, for messages (0: not known).
    """

    name: str
    components: tuple
    step: int
    time: float
    nodes: np.ndarray
    values: np.ndarray
    line: int = 0

    def component(self, name: str) -> np.ndarray:
        """The values of one component, in the order of :attr:`nodes`."""
        try:
            return self.values[:, self.components.index(name)]
        except ValueError:
            raise KeyError(f"result set {self.name} has no component {name!r}; it has "
                           f"{', '.join(self.components)}") from None


@dataclass(frozen=True)
class FrdFile:
    """The contents of a .frd file.

    Attributes
    ----------
    path : str
    nodes : ndarray of int
        Node numbers.
    coordinates : ndarray, shape (n, 3)
        Their coordinates, in the deck's length unit.
    elements : ndarray of int
        Element numbers.
    element_types : ndarray of int
        Their .frd types (6 for a 10-node tetrahedron, see :data:`ELEMENT_NODES`).
    element_materials : ndarray of int
        Their material numbers (1-based, in the order of the deck's materials).
    connectivity : ndarray of int, shape (m, k)
        Node numbers of each element, padded with -1 where types differ in size.
    results : tuple of FrdResult
        The nodal result sets in file order.
    headers : tuple of str
        The ``1U`` header lines (user, date, version, materials ...).
    """

    path: str
    nodes: np.ndarray
    coordinates: np.ndarray
    elements: np.ndarray
    element_types: np.ndarray
    element_materials: np.ndarray
    connectivity: np.ndarray
    results: tuple = field(default_factory=tuple)
    headers: tuple = field(default_factory=tuple)

    def result(self, name: str, step: int | None = None) -> FrdResult:
        """The result set ``name`` of ``step`` (default: the last one in the file)."""
        found = [r for r in self.results if r.name == name and (step is None or r.step == step)]
        if not found:
            have = sorted({r.name for r in self.results})
            raise KeyError(f"{self.path}: no result set {name!r}"
                           + (f" in step {step}" if step is not None else "")
                           + f"; the file has {', '.join(have) or 'none'}")
        return found[-1]

    def field(self, component: str, step: int | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(node numbers, values) of a component found by name in any result set.

        ``field("CPRESS")`` gives the contact pressure, ``field("D3")`` the
        z displacement; the last set holding the component (of ``step``) wins.
        """
        found = [r for r in self.results if component in r.components
                 and (step is None or r.step == step)]
        if not found:
            raise KeyError(f"{self.path}: no component {component!r}"
                           + (f" in step {step}" if step is not None else "")
                           + f"; the file has {', '.join(self.component_names) or 'none'}")
        r = found[-1]
        return r.nodes, r.component(component)

    @property
    def component_names(self) -> list[str]:
        """Every component name in the file, once each, in file order."""
        names = []
        for r in self.results:
            names += [c for c in r.components if c not in names]
        return names

    def node_index(self, numbers: np.ndarray) -> np.ndarray:
        """Row of each node number in :attr:`coordinates` (KeyError for an unknown number)."""
        order = np.argsort(self.nodes)
        pos = np.searchsorted(self.nodes, numbers, sorter=order)
        pos = np.clip(pos, 0, len(order) - 1)
        rows = order[pos]
        bad = self.nodes[rows] != numbers
        if np.any(bad):
            raise KeyError(f"{self.path}: node {int(np.asarray(numbers)[bad][0])} is not in "
                           f"the node block")
        return rows


#: The longest text line read [characters]: a .frd line is about 90; more is not a .frd.
MAX_LINE = 1024
#: The largest piece of a binary block read at once [bytes].
CHUNK = 1 << 24


class _Cursor:
    """Lines and binary records of an open .frd, read as they come, with the line number.

    Nothing is read whole: a text line is read at most :data:`MAX_LINE` characters far, a
    binary block only after its announced size was checked against what is left of the
    file (:func:`fem_validation.limits.check_count`), and then in pieces of
    :data:`CHUNK` bytes, so that a pipe announcing more than it holds costs no more memory
    than what it sends.  No seeking, so that a pipe reads as a file does.
    """

    def __init__(self, f, size: int, path: str):
        self.f, self.size, self.path = f, size, path
        self.pos = self.line = 0

    def readline(self) -> str | None:
        raw = self.f.readline(MAX_LINE + 1)
        if not raw:
            return None
        self.pos += len(raw)
        self.line += 1
        if len(raw) > MAX_LINE and not raw.endswith(b"\n"):
            self.fail(f"a line longer than {MAX_LINE} characters: not a .frd text line")
        return raw.decode("latin-1").rstrip("\r\n")


    def left(self) -> int:
        """The bytes left in the file (unbounded for a device or a pipe)."""
        return max(self.size - self.pos, 0)

    def count(self, n: int, bytes_each: int, what: str, line: int) -> int:
        """``n`` checked against the rest of the file before anything is allocated."""
        try:
            return check_count(n, bytes_each, self.left(), f"{self.path}: line {line}", what)
        except ValueError as exc:
            raise FrdFormatError(str(exc)) from None

    def take(self, dtype: np.dtype, count: int, what: str, line: int) -> np.ndarray:
        if count < 0:
            self.count(count, dtype.itemsize, what, line)
        size, left = dtype.itemsize * count, self.left()
        got = 0
        if size <= left:
            # a file's size bounds the block: one buffer; a pipe's does not: grown as it sends
            data = bytearray(size if self.size < UNBOUNDED else min(size, CHUNK))
            while got < size:
                if got == len(data):
                    data.extend(bytes(min(size - got, len(data))))
                n = self.f.readinto(memoryview(data)[got:got + CHUNK])
                if not n:
                    break
                got += n
        self.pos += got
        if got < size:
            self.fail(f"binary block ends early ({count} {what} of {dtype.itemsize} bytes "
                      f"expected, {got if size <= left else left} bytes left)", line)
        return np.frombuffer(data, dtype=dtype, count=count)

    def fail(self, message: str, line: int | None = None):
        raise FrdFormatError(f"{self.path}: line {self.line if line is None else line}: "
                             f"{message}")


def _int(text: str, cur: _Cursor, what: str) -> int:
    try:
        value = int(text)
    except ValueError:
        cur.fail(f"expected an integer for {what}, got {text!r}")
    if not -(1 << 63) <= value < 1 << 63:
        cur.fail(f"{what} is {text.strip()}, beyond a 64-bit integer")
    return value


def _floats(text: str, start: int, count: int, cur: _Cursor) -> list[float]:
    try:
        return [float(text[start + 12 * k:start + 12 * k + 12]) for k in range(count)]
    except ValueError:
        cur.fail(f"expected {count} numbers 12 characters wide from column {start + 1}: "
                 f"{text!r}")


def _fewest(width: int) -> int:
    """The fewest bytes of an ASCII record: " -1", a number ``width`` wide, the line end.

    A bound below what a whole record takes: an announced count is refused at once where
    even this does not fit, a file cut inside its block reads to its end and says so.  The
    arrays for the count are then allocated empty; their pages are touched, and take
    memory, only as records are read.
    """
    return 3 + width + 1


def _header(key: str, cur: _Cursor, what: str) -> tuple[int, int]:
    """(count, format) of a ``2C`` or ``3C`` key line (the second and the last field)."""
    tokens = key.split()
    if len(tokens) < 3:
        cur.fail(f"the {what} block's key line needs the number of {what} and the format "
                 f"(0 to 3): {key!r}")
    fmt = _int(tokens[-1], cur, "the format")
    if fmt not in (0, 1, 2, 3):
        cur.fail(f"the {what} block's format is {fmt}; a .frd has 0 or 1 (ASCII), 2 or 3 "
                 f"(binary)")
    return _int(tokens[1], cur, f"the number of {what}"), fmt


def _first_repeat(ids: np.ndarray) -> int | None:
    """The smallest number that ``ids`` holds twice, or None."""
    if len(ids) < 2:
        return None
    s = np.sort(ids)
    same = s[1:] == s[:-1]
    return int(s[1:][same][0]) if same.any() else None


def _check_unique(ids: np.ndarray, cur: _Cursor, line: int, what: str):
    dup = _first_repeat(ids)
    if dup is not None:
        first, second = np.flatnonzero(ids == dup)[:2] + 1
        cur.fail(f"{what} {dup} appears twice (records {first} and {second} of the block)",
                 line)


def _read_nodes(cur: _Cursor, key: str):
    line0 = cur.line
    n, fmt = _header(key, cur, "nodes")
    if fmt in (2, 3):
        real = "<f4" if fmt == 2 else "<f8"
        rec = cur.take(np.dtype([("id", "<i4"), ("xyz", real, (3,))]), n, "node records",
                       line0)
        ids, xyz = rec["id"].astype(np.int64), rec["xyz"].astype(np.float64)
    else:
        width = 5 if fmt == 0 else 10
        cur.count(n, _fewest(width), "nodes", line0)
        ids, xyz = np.empty(n, dtype=np.int64), np.empty((n, 3))
        count = 0
        while True:
            line = cur.readline()
            if line is None:
                cur.fail("the node block has no end (-3)")
            if line.startswith(" -3"):
                break
            if not line.startswith(" -1"):
                cur.fail(f"expected a node record (-1), got {line!r}")
            if count >= n:
                cur.fail(f"the node block holds more than the {n} nodes it announces")
            ids[count] = _int(line[3:3 + width], cur, "a node number")
            xyz[count] = _floats(line, 3 + width, 3, cur)
            count += 1
        if count != n:
            cur.fail(f"the node block announces {n} nodes and holds {count}")
    bad = ~np.isfinite(xyz).all(axis=1)
    if bad.any():
        k = int(np.argmax(bad))
        cur.fail(f"node {ids[k]} (record {k + 1} of the block) has a non-finite coordinate "
                 f"{xyz[k].tolist()}", line0)
    _check_unique(ids, cur, line0, "node")
    return ids, xyz, line0


def _read_elements(cur: _Cursor, key: str):
    line0 = cur.line
    n, fmt = _header(key, cur, "elements")
    flat = array("q")  # every element's node numbers, one after the other
    if fmt in (2, 3):
        cur.count(n, 4 * (4 + min(ELEMENT_NODES.values())), "elements", line0)
        ids, types, mats = (np.empty(n, dtype=np.int64) for _ in range(3))
        for i in range(n):
            head = cur.take(np.dtype("<i4"), 4, "element header integers", line0)
            etype = int(head[1])
            if etype not in ELEMENT_NODES:
                cur.fail(f"element {int(head[0])} (record {i + 1} of the block) has unknown "
                         f"type {etype}", line0)
            flat.extend(cur.take(np.dtype("<i4"), ELEMENT_NODES[etype], "element nodes",
                                 line0).tolist())
            ids[i], types[i], mats[i] = head[0], etype, head[3]
        count = n
    else:
        width = 5 if fmt == 0 else 10
        cur.count(n, 2 * _fewest(width), "elements", line0)  # a -1 and a -2 line each
        ids, types, mats = (np.empty(n, dtype=np.int64) for _ in range(3))
        count = 0
        while True:
            line = cur.readline()
            if line is None:
                cur.fail("the element block has no end (-3)")
            if line.startswith(" -3"):
                break
            if not line.startswith(" -1"):
                cur.fail(f"expected an element record (-1), got {line!r}")
            if count >= n:
                cur.fail(f"the element block holds more than the {n} elements it announces")
            head = line[3:].split()
            if len(head) < 4:
                cur.fail(f"an element record needs number, type, group, material: {line!r}")
            etype = _int(head[1], cur, "an element type")
            if etype not in ELEMENT_NODES:
                cur.fail(f"element {head[0]} has unknown type {etype}")
            ids[count] = _int(head[0], cur, "an element number")
            types[count] = etype
            mats[count] = _int(head[3], cur, "a material number")
            need, nodes = ELEMENT_NODES[etype], []
            while len(nodes) < need:
                more = cur.readline()
                if more is None or not more.startswith(" -2"):
                    cur.fail(f"element {head[0]}: expected its nodes (-2), got {more!r}")
                body = more[3:].rstrip()
                nodes += [_int(body[k:k + width], cur, "a node number")
                          for k in range(0, len(body), width)]
            if len(nodes) != need:
                cur.fail(f"element {head[0]} of type {etype} has {need} nodes; its -2 lines "
                         f"hold {len(nodes)}")
            flat.extend(nodes)
            count += 1
        if count != n:
            cur.fail(f"the element block announces {n} elements and holds {count}")
    _check_unique(ids, cur, line0, "element")
    sizes = _SIZES[types]
    width = int(sizes.max()) if count else 0
    conn = np.full((count, width), -1, dtype=np.int64)
    conn[np.arange(width) < sizes[:, None]] = np.frombuffer(flat, dtype=np.int64)
    return ids, types, mats, conn, line0


def _read_result(cur: _Cursor, key: str) -> FrdResult:
    line0 = cur.line
    # fixed columns of the 100C line: value 13-24, nodes 25-36, step 59-63, format 74-75
    try:
        time = float(key[12:24])
        n = int(key[24:36])
        step = int(key[58:63])
        fmt = int(key[73:75])
    except ValueError:
        cur.fail(f"unreadable result-set header: {key!r}")
    if fmt not in (0, 1, 2, 3):
        cur.fail(f"the result set's format is {fmt}; a .frd has 0 or 1 (ASCII), 2 or 3 "
                 f"(binary)")
    head = cur.readline()
    if head is None or not head.startswith(" -4"):
        cur.fail(f"expected the result set's name (-4), got {head!r}")
    # the -4 line: name (columns 6-13), number of components, a type; then one -5 line each
    name, fields = head[5:13].strip(), head[13:].split()
    if not name or not fields:
        cur.fail(f"the result set's -4 line needs its name and its number of components: "
                 f"{head!r}")
    listed = _int(fields[0], cur, f"the number of components of result set {name}")
    cur.count(listed, _fewest(0), f"components of result set {name}", cur.line)
    components = []
    for k in range(listed):
        line = cur.readline()
        if line is None or not line.startswith(" -5"):
            cur.fail(f"result set {name}: expected component line (-5) {k + 1} of {listed}, "
                     f"got {line!r}")
        flags = line[13:].split()
        computed = len(flags) >= 5 and flags[4].startswith("1")
        if not computed:
            components.append(line[5:13].strip())
    nc = len(components)
    dup = next((c for i, c in enumerate(components) if c in components[:i]), None)
    if dup is not None:
        cur.fail(f"result set {name} names its component {dup!r} twice", line0)
    where = f"result set {name}"
    if fmt in (2, 3):
        real = "<f4" if fmt == 2 else "<f8"
        rec = cur.take(np.dtype([("id", "<i4"), ("v", real, (nc,))]), n,
                       f"node records of {where}", line0)
        ids, values = rec["id"].astype(np.int64), rec["v"].astype(np.float64).reshape(n, nc)
    else:
        width = 5 if fmt == 0 else 10
        start = 3 + width
        cur.count(n, _fewest(width), f"nodes in {where}", line0)
        ids = np.empty(n, dtype=np.int64)
        values = np.empty((n, nc))
        count = 0
        row: list[float] | None = None  # the values of the record being read
        while True:
            line = cur.readline()
            if line is None:
                cur.fail(f"{where} has no end (-3)")
            if line.startswith(" -3"):
                break
            if line.startswith(" -1") and row is None:
                if count >= n:
                    cur.fail(f"{where} holds more than the {n} nodes it announces")
                ids[count] = _int(line[3:3 + width], cur, "a node number")
                row = _floats(line, start, min(nc, 6), cur)
            elif line.startswith(" -2") and row is not None:
                row += _floats(line, start, min(nc - len(row), 6), cur)
            elif line.startswith((" -1", " -2")):
                cur.fail(f"{where} has {nc} components: node {ids[count]} needs "
                         f"{max((nc - 1) // 6, 0)} continuation line(s) (-2) after its -1 "
                         f"line, got {line!r}" if row is not None else
                         "a continuation line (-2) with no node record (-1) before it")
            else:
                cur.fail(f"expected a value record (-1 or -2), got {line!r}")
            if len(row) == nc:
                values[count] = row
                count += 1
                row = None
        if row is not None:
            cur.fail(f"{where}: node {ids[count]} has {len(row)} of its {nc} values")
        if count != n:
            cur.fail(f"{where} announces {n} nodes and holds {count}")
    _check_unique(ids, cur, line0, f"{where}: node")
    return FrdResult(name, tuple(components), step, time, ids, values, line0)


def _check_known(numbers: np.ndarray, nodes: np.ndarray, order: np.ndarray, cur: _Cursor,
                 line: int, what: str):
    """Every node number of ``numbers`` is in the node block."""
    if not numbers.size:
        return
    if not nodes.size:
        cur.fail(f"{what} refers to node {int(numbers.flat[0])}, and the file has no nodes",
                 line)
    pos = order[np.clip(np.searchsorted(nodes, numbers, sorter=order), 0, len(order) - 1)]
    bad = nodes[pos] != numbers
    if bad.any():
        cur.fail(f"{what} refers to node {int(numbers[bad].flat[0])}, which is not in the node "
                 f"block", line)


def read_frd(path) -> FrdFile:
    """Read a CalculiX .frd file (ASCII or binary), streaming it.

    Memory: the arrays returned (8 bytes a number: 32 bytes a node of the node block,
    8 (1 + k) bytes a node of each result set of k components), one line, and a binary
    block's raw records while they are converted; never the whole file.  Measured on
    synthetic files of 10^6 nodes with a DISP and a STRESS set (120 MB of arrays): a peak
    140 MB above the interpreter's from ASCII (186 MB of file), 158 MB from binary.

    Parameters
    ----------
    path : path-like

    Returns
    -------
    FrdFile

    Raises
    ------
    FrdFormatError
        If the file is not a .frd file this reader understands (naming the file, the line
        and what was expected): a block cut short, a count the rest of the file cannot
        hold, a node or element number given twice, an element or a result for a node
        that is not in the node block, a non-finite coordinate, a second node block.
    OSError
        If it cannot be read.
    """
    path = Path(path)
    source = str(path)
    with open(path, "rb") as f:
        cur = _Cursor(f, file_size(path), source)
        nodes = coords = None
        elements = types = mats = conn = None
        node_line = element_line = 0
        results, headers = [], []
        while True:
            line = cur.readline()
            if line is None:
                break
            key = line[:6].strip()
            if key == "9999":
                break
            if key == "1C" or line[4:6] in ("1U", "1P"):
                if line[4:6] == "1U":
                    headers.append(line[6:].rstrip())
            elif key == "2C":
                if nodes is not None:
                    cur.fail(f"a second node block (2C); the first is at line {node_line}")
                nodes, coords, node_line = _read_nodes(cur, line)
            elif key == "3C":
                if elements is not None:
                    cur.fail(f"a second element block (3C); the first is at line "
                             f"{element_line}")
                elements, types, mats, conn, element_line = _read_elements(cur, line)
            elif key == "100C":
                results.append(_read_result(cur, line))
            elif line.strip():
                cur.fail(f"unexpected line {line[:40]!r} (not a .frd block key)")
    if nodes is None:
        raise FrdFormatError(f"{path}: no node block (2C): not a CalculiX .frd file")
    order = np.argsort(nodes)
    if elements is None:
        elements = types = mats = np.zeros(0, dtype=np.int64)
        conn = np.zeros((0, 0), dtype=np.int64)
    else:
        _check_known(conn[np.arange(conn.shape[1]) < _SIZES[types][:, None]], nodes, order, cur,
                     element_line, "the element block")
    for r in results:
        _check_known(r.nodes, nodes, order, cur, r.line, f"result set {r.name}")
    return FrdFile(source, nodes, coords, elements, types, mats, conn, tuple(results),
                   tuple(headers))


