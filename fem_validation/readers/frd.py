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

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

#: Nodes per element for each .frd element type.
ELEMENT_NODES = {1: 8, 2: 6, 3: 4, 4: 20, 5: 15, 6: 10, 7: 3, 8: 6, 9: 4, 10: 8, 11: 2, 12: 3}


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
    """

    name: str
    components: tuple
    step: int
    time: float
    nodes: np.ndarray
    values: np.ndarray

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


class _Cursor:
    """Lines and binary records of the file's bytes, with the line number for errors."""

    def __init__(self, data: bytes, path: str):
        self.data, self.pos, self.line, self.path = data, 0, 0, path

    def readline(self) -> str | None:
        if self.pos >= len(self.data):
            return None
        end = self.data.find(b"\n", self.pos)
        end = len(self.data) if end < 0 else end
        text = self.data[self.pos:end].decode("latin-1").rstrip("\r")
        self.pos, self.line = end + 1, self.line + 1
        return text

    def take(self, dtype: np.dtype, count: int) -> np.ndarray:
        size = dtype.itemsize * count
        if self.pos + size > len(self.data):
            self.fail(f"binary block ends early ({count} records of {dtype.itemsize} bytes "
                      f"expected, {len(self.data) - self.pos} bytes left)")
        out = np.frombuffer(self.data, dtype=dtype, count=count, offset=self.pos)
        self.pos += size
        return out

    def fail(self, message: str):
        raise FrdFormatError(f"{self.path}: line {self.line}: {message}")


def _int(text: str, cur: _Cursor, what: str) -> int:
    try:
        return int(text)
    except ValueError:
        cur.fail(f"expected an integer for {what}, got {text!r}")


def _floats(text: str, start: int, count: int, cur: _Cursor) -> list[float]:
    try:
        return [float(text[start + 12 * k:start + 12 * k + 12]) for k in range(count)]
    except ValueError:
        cur.fail(f"expected {count} numbers 12 characters wide from column {start + 1}: "
                 f"{text!r}")


def _read_nodes(cur: _Cursor, key: str):
    tokens = key.split()
    n, fmt = _int(tokens[1], cur, "the number of nodes"), _int(tokens[-1], cur, "the format")
    if fmt in (2, 3):
        real = "<f4" if fmt == 2 else "<f8"
        rec = cur.take(np.dtype([("id", "<i4"), ("xyz", real, (3,))]), n)
        return rec["id"].astype(np.int64), rec["xyz"].astype(np.float64)
    width = 5 if fmt == 0 else 10
    ids, xyz = [], []
    while True:
        line = cur.readline()
        if line is None:
            cur.fail("the node block has no end (-3)")
        if line.startswith(" -3"):
            break
        if not line.startswith(" -1"):
            cur.fail(f"expected a node record (-1), got {line!r}")
        ids.append(_int(line[3:3 + width], cur, "a node number"))
        xyz.append(_floats(line, 3 + width, 3, cur))
    if len(ids) != n:
        cur.fail(f"the node block announces {n} nodes and holds {len(ids)}")
    return np.array(ids, dtype=np.int64), np.array(xyz, dtype=np.float64).reshape(-1, 3)


def _read_elements(cur: _Cursor, key: str):
    tokens = key.split()
    n, fmt = _int(tokens[1], cur, "the number of elements"), _int(tokens[-1], cur, "the format")
    ids, types, mats, conns = [], [], [], []
    if fmt in (2, 3):
        for _ in range(n):
            head = cur.take(np.dtype("<i4"), 4)
            etype = int(head[1])
            if etype not in ELEMENT_NODES:
                cur.fail(f"element {int(head[0])} has unknown type {etype}")
            conns.append(cur.take(np.dtype("<i4"), ELEMENT_NODES[etype]).astype(np.int64))
            ids.append(int(head[0]))
            types.append(etype)
            mats.append(int(head[3]))
    else:
        width = 5 if fmt == 0 else 10
        while True:
            line = cur.readline()
            if line is None:
                cur.fail("the element block has no end (-3)")
            if line.startswith(" -3"):
                break
            if not line.startswith(" -1"):
                cur.fail(f"expected an element record (-1), got {line!r}")
            head = line[3:].split()
            if len(head) < 4:
                cur.fail(f"an element record needs number, type, group, material: {line!r}")
            etype = _int(head[1], cur, "an element type")
            if etype not in ELEMENT_NODES:
                cur.fail(f"element {head[0]} has unknown type {etype}")
            need, nodes = ELEMENT_NODES[etype], []
            while len(nodes) < need:
                more = cur.readline()
                if more is None or not more.startswith(" -2"):
                    cur.fail(f"element {head[0]}: expected its nodes (-2), got {more!r}")
                body = more[3:]
                nodes += [_int(body[k:k + width], cur, "a node number")
                          for k in range(0, len(body.rstrip()), width)]
            ids.append(_int(head[0], cur, "an element number"))
            types.append(etype)
            mats.append(_int(head[3], cur, "a material number"))
            conns.append(np.array(nodes[:need], dtype=np.int64))
    if len(ids) != n:
        cur.fail(f"the element block announces {n} elements and holds {len(ids)}")
    width = max((len(c) for c in conns), default=0)
    conn = np.full((len(conns), width), -1, dtype=np.int64)
    for i, c in enumerate(conns):
        conn[i, :len(c)] = c
    return (np.array(ids, dtype=np.int64), np.array(types, dtype=np.int64),
            np.array(mats, dtype=np.int64), conn)


def _read_result(cur: _Cursor, key: str) -> FrdResult:
    # fixed columns of the 100C line: value 13-24, nodes 25-36, step 59-63, format 74-75
    try:
        time = float(key[12:24])
        n = int(key[24:36])
        step = int(key[58:63])
        fmt = int(key[73:75])
    except ValueError:
        cur.fail(f"unreadable result-set header: {key!r}")
    head = cur.readline()
    if head is None or not head.startswith(" -4"):
        cur.fail(f"expected the result set's name (-4), got {head!r}")
    name = head[5:13].strip() or head.split()[1]
    components = []
    while True:
        pos = cur.pos
        line = cur.readline()
        if line is None:
            cur.fail(f"result set {name} has no values")
        if not line.startswith(" -5"):
            cur.pos, cur.line = pos, cur.line - 1
            break
        flags = line[13:].split()
        computed = len(flags) >= 5 and flags[4].startswith("1")
        if not computed:
            components.append(line[5:13].strip())
    nc = len(components)
    if fmt in (2, 3):
        real = "<f4" if fmt == 2 else "<f8"
        rec = cur.take(np.dtype([("id", "<i4"), ("v", real, (nc,))]), n)
        return FrdResult(name, tuple(components), step, time, rec["id"].astype(np.int64),
                         rec["v"].astype(np.float64).reshape(n, nc))
    width = 5 if fmt == 0 else 10
    start = 3 + width
    ids = np.empty(n, dtype=np.int64)
    values = np.empty((n, nc))
    count = 0
    row: list[float] = []
    while True:
        line = cur.readline()
        if line is None:
            cur.fail(f"result set {name} has no end (-3)")
        if line.startswith(" -3"):
            break
        if line.startswith(" -1"):
            if count >= n:
                cur.fail(f"result set {name} holds more than the {n} nodes it announces")
            ids[count] = _int(line[3:3 + width], cur, "a node number")
            row = _floats(line, start, min(nc, 6), cur)
        elif line.startswith(" -2"):
            row += _floats(line, start, min(nc - len(row), 6), cur)
        else:
            cur.fail(f"expected a value record (-1 or -2), got {line!r}")
        if len(row) == nc:
            values[count] = row
            count += 1
            row = []
    if count != n:
        cur.fail(f"result set {name} announces {n} nodes and holds {count}")
    return FrdResult(name, tuple(components), step, time, ids, values)


def read_frd(path) -> FrdFile:
    """Read a CalculiX .frd file (ASCII or binary).

    Parameters
    ----------
    path : path-like

    Returns
    -------
    FrdFile

    Raises
    ------
    FrdFormatError
        If the file is not a .frd file (naming the file, the line and what was expected).
    OSError
        If it cannot be read.
    """
    path = Path(path)
    cur = _Cursor(path.read_bytes(), str(path))
    nodes = coords = None
    elements = types = mats = conn = None
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
            nodes, coords = _read_nodes(cur, line)
        elif key == "3C":
            elements, types, mats, conn = _read_elements(cur, line)
        elif key == "100C":
            results.append(_read_result(cur, line))
        elif line.strip():
            cur.fail(f"unexpected line {line[:40]!r} (not a .frd block key)")
    if nodes is None:
        raise FrdFormatError(f"{path}: no node block (2C): not a CalculiX .frd file")
    if elements is None:
        elements = types = mats = np.zeros(0, dtype=np.int64)
        conn = np.zeros((0, 0), dtype=np.int64)
    return FrdFile(str(path), nodes, coords, elements, types, mats, conn, tuple(results),
                   tuple(headers))


def read_result(path, *, units: str = "SI", symmetry: str | None = None,
                force: float | None = None, frame=None, fields: dict | None = None):
    """A CalculiX .frd as a :class:`~fem_validation.result.ContactResult` (the interface of
    :func:`fem_validation.readers.common.read_result`).

    See :func:`fem_validation.readers.calculix.read_calculix`; ``fields`` may name
    the pressure component (``{"pressure": "CPRESS"}``).  Where the deck's
    problem.json lies beside the file, its units must agree with ``units``.
    """
    from ..result import ResultError
    from .calculix import read_calculix

    fields = dict(fields or {})
    unknown = set(fields) - {"pressure"}
    if unknown:
        raise ResultError(f"{path}: a .frd takes only the field 'pressure' (a component "
                          f"name such as CPRESS), got {', '.join(sorted(unknown))}")
    return read_calculix(path, units=units, symmetry=symmetry, force=force, frame=frame,
                         pressure_name=fields.get("pressure", "CPRESS"))
