"""A CSV of the contact surface: x, y (and z), the nodal pressure p, and the total force.

The file::

    # force = 4065.5      the total normal force of the model in the file [N]; without
                          it (and without --force), the integral of p over the surface
    # symmetry = quarter  optional: whole, half, quarter (else detected)
    # units = mm          optional: SI or mm (mm, N, MPa); default: the columns'
                          units (x [mm], p [MPa]), else SI
    x,y,p
    0.0,0.0,3893.1
    ...

Columns (a header row, any order, case-insensitive): ``x``, ``y``, optionally ``z``;
``p`` (or ``pressure``, ``cpress``) and/or ``f`` (or ``normal_force``: the nodal normal
contact force); optionally ``active`` (1/0).  x, y are taken as coordinates in the
contact plane unless a frame is given.  Options of :func:`read_csv` override the ``#``
lines.  Columns of other names are chosen by the ``fields`` option (``grade --columns
x=x_m,y=y_m,p=p_pa``, read by :func:`parse_columns`); a unit at the end of a name
(``x_m``, ``p_pa``) sets the units as it does anywhere (below).  A file that gives no force
(a boundary-element code's pressure on a grid, say) is graded at the integral of its
pressure over the surface (the nodal pressure times the lumped area of a triangulation in
the contact plane, as the grader integrates it): the grade's ``pressure_integral`` check is
then met by construction, and ``details["force_from"]`` says so.

Every CSV reader of :mod:`fem_validation.readers` reads its file through
:func:`read_table`, which accepts what spreadsheets write:

* a UTF-8 byte-order mark (Excel's "CSV UTF-8"), CRLF or CR line ends, quoted cells;
* commas, semicolons or tabs between cells (the header row's most frequent one); with
  semicolons or tabs, a decimal comma (``0,25``);
* rows of empty cells (a spreadsheet's blank row) and ``# key = value`` lines padded with
  empty cells (``# force = 25,,``); comment lines starting with ``#``, ``%`` (MATLAB,
  Octave) or ``//``;
* a unit in a column's name: ``x [mm]``, ``p (MPa)``, ``x/mm``, ``pressure_MPa``.  Length
  columns in m (SI) or mm, pressure columns in Pa (SI) or MPa (= N/mm^2, mm), force
  columns in N; where neither the ``units`` option nor a ``# units`` line says, the
  columns' units choose the system (SI where no column names one).  A unit that
  contradicts the units given, or that neither system reads (``um``, ``kPa``, ``kN``),
  is refused with a message naming the column.

A file is streamed: only the columns a reader uses are kept, as float64 (8 bytes a value);
at most :data:`MAX_ROWS` data rows and :data:`MAX_LINE_CHARS` characters a line, so the
peak memory of reading a table is below about ``8 * columns_used * MAX_ROWS`` bytes twice
over (about 0.2 GB for seven columns) whatever the file holds.  Every malformed file gets
one :class:`~fem_validation.results.contact.ResultError` naming the file and the line.
"""

from __future__ import annotations

import csv
import math
import re
from array import array
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..results.contact import ContactFrame, ContactResult, ResultError
from .common import NORMAL_FORCE_NAMES, PRESSURE_NAMES, finish, units_of

#: The most data rows a table may hold: a contact surface of two million nodes is far
#: beyond what a grader needs or a finite-element contact surface has.
MAX_ROWS = 2_000_000
#: The most lines of any kind (comments and blank lines too) read before giving up.
MAX_LINES = 2 * MAX_ROWS
#: The longest line [characters]: a row of numbers takes well under a kilobyte.
MAX_LINE_CHARS = 65_536

_META = re.compile(r"^\s*#\s*(\w+)\s*[=:]\s*(.*?)\s*$")
#: "x [mm]", "p (MPa)", "f {N}": the unit is the last bracketed group.
_BRACKETED = re.compile(r"^(?P<name>.*?)\s*[\[({]\s*(?P<unit>[^\[\](){}]*?)\s*[\])}]\s*$")
#: The units recognised at the end of a name ("pressure_MPa", "x_mm", "x/mm", "x mm"):
#: only these, so that "normal_force" or "shear_x" keep their names.
_UNIT_WORDS = ("mm", "m", "um", "µm", "cm", "pa", "kpa", "mpa", "gpa", "n", "kn")
_SUFFIXED = re.compile(r"^(?P<name>.*?[^\s_/])(?:\s*/\s*|[\s_]+)(?P<unit>"
                       + "|".join(re.escape(u) for u in _UNIT_WORDS) + r")$", re.IGNORECASE)

#: The unit system each unit belongs to, by the kind of quantity; "both" for N.
_UNIT_SYSTEMS = {
    "length": {"m": "SI", "metre": "SI", "meter": "SI", "mm": "mm", "millimetre": "mm",
               "millimeter": "mm"},
    "pressure": {"pa": "SI", "n/m2": "SI", "n/m^2": "SI", "n/m²": "SI", "mpa": "mm",
                 "n/mm2": "mm", "n/mm^2": "mm", "n/mm²": "mm"},
    "force": {"n": "both", "newton": "both"},
    "number": {"-": "both", "1": "both", "": "both"},
}
#: The unit of each kind of column in each system, for the messages.
_SYSTEM_UNITS = {"SI": {"length": "m", "force": "N", "pressure": "Pa"},
                 "mm": {"length": "mm", "force": "N", "pressure": "MPa"}}


def _system(units: str) -> str:
    return "mm" if units == "mm" else "SI"


def _number(text: str, where: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise ResultError(f"{where}: {text[:40]!r} is not a number") from None


def split_unit(label: str) -> tuple[str, str | None]:
    """(name, unit) of a column label, both lower case: ``"p [MPa]"`` -> ``("p", "mpa")``;
    the unit is None where the label names none."""
    text = label.strip()
    for pattern in (_BRACKETED, _SUFFIXED):
        m = pattern.match(text)
        if m and m.group("name").strip():
            return m.group("name").strip().lower(), m.group("unit").strip().lower()
    return text.lower(), None


@dataclass
class Column:
    """A column a reader uses: its index, its role (for messages) and its kind of
    quantity ("length", "pressure", "force" or "number")."""

    index: int
    role: str
    kind: str


def _same_meta(a: str, b: str) -> bool:
    """Two ``# key`` values that say the same: the same words, or the same number."""
    if " ".join(a.lower().split()) == " ".join(b.lower().split()):
        return True
    try:
        return float(a) == float(b)
    except ValueError:
        return False


class _Meta(dict):
    """``{key: (text, line)}`` of a file's ``# key = value`` lines, the first of each key.

    A key given twice with values that differ is kept as a contradiction: reading it
    (``meta[key]``) raises a ResultError naming both lines; a key no reader asks for (a
    ``# note:`` line, say) may repeat freely.
    """

    def __init__(self, src: str):
        super().__init__()
        self.src = src
        self.conflicts: dict = {}

    def add(self, key: str, text: str, line: int) -> None:
        if not dict.__contains__(self, key):
            dict.__setitem__(self, key, (text, line))
            return
        first, first_line = dict.__getitem__(self, key)
        if key not in self.conflicts and not _same_meta(first, text):
            self.conflicts[key] = (first_line, first, line, text)

    def __getitem__(self, key: str):
        if key in self.conflicts:
            first_line, first, line, text = self.conflicts[key]
            raise ResultError(f"{self.src}, lines {first_line} and {line}: two '# {key}' lines "
                              f"contradict each other ({first!r}, then {text!r}): keep one")
        return dict.__getitem__(self, key)


@dataclass
class Table:
    """The columns a reader asked for, as numbers, with where each row came from.

    Attributes
    ----------
    src : str
        The file.
    meta : dict
        ``{key: (text, line)}`` of the ``# key = value`` lines (lower-case keys).
    labels : list of str
        The header's cells as written.
    names : list of str
        The header's column names, lower case, without their units.
    units : list of str or None
        The unit each column names (lower case), or None.
    header_line : int
        The header's line.
    columns : dict
        ``{role: Column}`` of the columns read.
    values : ndarray, shape (rows, len(columns))
        The numbers, in the file's units, every one finite.
    lines : ndarray of int, shape (rows,)
        The line of each row.
    """

    src: str
    meta: dict
    labels: list
    names: list
    units: list
    header_line: int
    columns: dict = field(default_factory=dict)
    values: np.ndarray | None = None
    lines: np.ndarray | None = None

    def __getitem__(self, role: str) -> np.ndarray:
        return self.values[:, list(self.columns).index(role)]

    def __contains__(self, role: str) -> bool:
        return role in self.columns

    def where(self, row: int) -> str:
        """``"file, line L"`` of a data row."""
        return f"{self.src}, line {int(self.lines[row])}"

    def find(self, names, role: str, kind: str, required: bool = True,
             chosen: str | None = None) -> Column | None:
        """The first column named one of ``names`` (or exactly ``chosen``), as a Column.

        Raises
        ------
        ResultError
            None is found and ``required``, or the name is in the header twice.
        """
        lower_labels = [label.strip().lower() for label in self.labels]
        if chosen is not None:
            key = chosen.strip().lower()
            hits = [j for j, (n, lab) in enumerate(zip(self.names, lower_labels, strict=True))
                    if key in (n, lab)]
            if not hits:
                raise ResultError(f"{self.src}, line {self.header_line}: no column {chosen!r} "
                                  f"for the {role} (columns: {', '.join(self.labels)})")
        else:
            name = next((n for n in names if n in self.names), None)
            if name is None:
                if required:
                    raise ResultError(f"{self.src}, line {self.header_line}: no {role} column "
                                      f"({', '.join(names)}); columns: {', '.join(self.labels)}")
                return None
            hits = [j for j, n in enumerate(self.names) if n == name]
        if len(hits) > 1:
            raise ResultError(f"{self.src}, line {self.header_line}: the {role} column "
                              f"{self.labels[hits[0]]!r} is in the header {len(hits)} times "
                              f"(columns {', '.join(str(j + 1) for j in hits)})")
        return Column(hits[0], role, kind)

    def resolve_units(self, given: str | None) -> str:
        """The unit system of the table's numbers: ``given`` (the ``units`` option), else
        the ``# units`` line, else the one the columns' units name, else SI; checked
        against every unit the columns used name.

        Raises
        ------
        ResultError
            A column's unit contradicts the system, belongs to neither system, is not a
            unit of its kind of quantity, or the columns name units of both systems.
        """
        if given is not None:
            units, said = given, f"--units says {given}"
            units_of(units, f"{self.src}: ")
        elif "units" in self.meta:
            units, line = self.meta["units"]
            units_of(units, f"{self.src}, line {line}: ")
            said = f"the '# units' line (line {line}) says {units}"
        else:
            units, said = None, ""
        named = {}
        for col in self.columns.values():
            unit = self.units[col.index]
            if unit is None:
                continue
            label = self.labels[col.index].strip()
            systems = _UNIT_SYSTEMS[col.kind]
            if unit not in systems:
                expected = ("no unit" if col.kind == "number" else " or ".join(
                    f"{s[col.kind]} ({name})" for name, s in _SYSTEM_UNITS.items()))
                raise ResultError(f"{self.src}, line {self.header_line}: column {label!r} "
                                  f"names the unit {unit!r}; the {col.role} is read in "
                                  f"{expected}: convert the column or rename it")
            if systems[unit] != "both":
                named[label] = systems[unit]
        if units is None:
            found = sorted(set(named.values()))
            if len(found) > 1:
                by = {s: next(lab for lab, v in named.items() if v == s) for s in found}
                raise ResultError(f"{self.src}, line {self.header_line}: the columns name units "
                                  f"of two systems: {by['SI']!r} (SI: m, N, Pa) and "
                                  f"{by['mm']!r} (mm, N, MPa); use one, or say --units")
            return found[0] if found else "SI"
        for label, system in named.items():
            if system != _system(units):
                raise ResultError(f"{self.src}, line {self.header_line}: column {label!r} is "
                                  f"in {system} units but {said} "
                                  f"({', '.join(_SYSTEM_UNITS[_system(units)].values())}): "
                                  f"correct one of them")
        return units

    def meta_number(self, key: str, given=None, unit: str | None = None,
                    integer: bool = False):
        """The number of the ``# key = value`` line (``given`` where not None), finite;
        after it at most ``unit`` (``"N"``); an integer where ``integer``.

        Raises
        ------
        ResultError
            Naming the file and the line: not a number, not finite, another unit, not an
            integer.
        """
        if given is not None:
            return given
        if key not in self.meta:
            return None
        text, line = self.meta[key]
        where = f"{self.src}, line {line}, {key}"
        parts = text.split()
        value = _number(parts[0] if parts else text, where)
        rest = " ".join(parts[1:]).strip("[]() ")
        if rest and (unit is None or rest.lower() != unit.lower()):
            raise ResultError(f"{where}: {text!r}: expected a number"
                              + (f" in {unit}" if unit else "")
                              + f", not {rest!r} after it")
        if not math.isfinite(value):
            raise ResultError(f"{where}: {text!r}: must be a finite number")
        if integer:
            if value != int(value):
                raise ResultError(f"{where}: must be an integer, got {text!r}")
            return int(value)
        return value


#: The separator of a table whose header holds no comma, semicolon or tab but two or more
#: names apart: runs of spaces (numpy.savetxt's default, Fortran and C printf output).
WHITESPACE = " "


def _delimiter(line: str) -> str:
    """The header row's separator: the most frequent of comma, semicolon and tab, else
    whitespace where the row holds two or more names."""
    counts = {d: line.count(d) for d in (",", ";", "\t")}
    if not any(counts.values()) and len(line.split()) >= 2:
        return WHITESPACE
    return max(counts, key=lambda d: (counts[d], d == ","))


def _cells(line: str, delimiter: str, where) -> list[str]:
    if delimiter == WHITESPACE:
        return line.split()
    if '"' not in line:
        return line.split(delimiter)
    try:
        return next(csv.reader([line], delimiter=delimiter, strict=True))
    except (csv.Error, StopIteration) as exc:
        raise ResultError(f"{where()}: not a CSV row ({exc})") from None


def _not_utf8(path: Path, lineno: int) -> str:
    """The message for a file that is not UTF-8, naming the first bad line (the text
    reader decodes ahead of the line it returns, so its own count may fall short)."""
    with open(path, "rb") as f:
        for k in range(1, lineno + 1 + (1 << 20)):
            raw = f.readline(4 * MAX_LINE_CHARS + 1)
            if not raw:
                break
            try:
                raw.decode("utf-8-sig" if k == 1 else "utf-8")
            except UnicodeDecodeError as exc:
                return f"{path}, line {k}: not UTF-8 text (byte {raw[exc.start]:#04x})"
    return f"{path}, line {lineno + 1}: not UTF-8 text"


def read_table(path, choose) -> Table:
    """Stream a CSV file: its ``#`` lines, its header and the columns ``choose`` picks.

    Parameters
    ----------
    path : path
        The file (see the module docstring for what it may hold).
    choose : callable
        ``choose(table)`` -> ``{role: Column}``, called once the header is read (the
        Table then has no values yet); it raises a ResultError where the header lacks a
        column.

    Returns
    -------
    Table

    Raises
    ------
    ResultError
        Naming the file and the line: unreadable, not UTF-8, a line over
        :data:`MAX_LINE_CHARS` characters, more than :data:`MAX_ROWS` rows, a row with
        another number of cells than the header, a cell that is not a number, a
        non-finite number, no header or no data row.
    """
    path = Path(path)
    src = str(path)
    meta = _Meta(src)
    table: Table | None = None
    delimiter, picked = ",", ()
    numbers, lines = array("d"), array("q")
    lineno = 0
    try:
        # utf-8-sig drops a byte-order mark; newline=None reads CRLF and CR line ends too.
        with open(path, encoding="utf-8-sig", newline=None) as f:
            while True:
                raw = f.readline(MAX_LINE_CHARS + 1)
                if not raw:
                    break
                lineno += 1
                if len(raw) > MAX_LINE_CHARS:
                    raise ResultError(f"{src}, line {lineno}: longer than {MAX_LINE_CHARS} "
                                      "characters: not a table of numbers (is it the right "
                                      "file?)")
                if lineno > MAX_LINES:
                    raise ResultError(f"{src}: more than {MAX_LINES} lines: a table of at most "
                                      f"{MAX_ROWS} rows is read")
                line = raw.rstrip("\r\n")
                m = _META.match(line) or _META.match(line.lstrip().lstrip('"'))
                if m:
                    meta.add(m.group(1).lower(), m.group(2).rstrip(",;\t ").strip('"'), lineno)
                    continue
                stripped = line.strip()
                if (not stripped.strip(",;\t\" ") or stripped.startswith(("#", "%", "//"))
                        or stripped.startswith('"#')):
                    continue  # a blank line, a spreadsheet's empty row, a comment
                if table is None:
                    delimiter = _delimiter(line)
                    labels = [c.strip() for c in _cells(
                        line, delimiter, lambda n=lineno: f"{src}, line {n}")]
                    names, units = zip(*(split_unit(c) for c in labels), strict=True)
                    table = Table(src, meta, labels, list(names), list(units), lineno)
                    table.columns = dict(choose(table))
                    picked = [c.index for c in table.columns.values()]
                    continue
                cells = _cells(line, delimiter, lambda n=lineno: f"{src}, line {n}")
                if len(cells) != len(table.labels):
                    raise ResultError(f"{src}, line {lineno}: {len(cells)} values, the header "
                                      f"(line {table.header_line}) has {len(table.labels)} "
                                      f"columns")
                if len(lines) >= MAX_ROWS:
                    raise ResultError(f"{src}, line {lineno}: more than {MAX_ROWS} data rows: "
                                      "more than a contact result is read with")
                for j in picked:
                    text = cells[j].strip()
                    try:
                        numbers.append(float(text))
                    except ValueError:
                        if delimiter != "," and text.count(",") == 1 and "." not in text:
                            text = text.replace(",", ".")  # a decimal comma
                        numbers.append(_number(text, f"{src}, line {lineno}, column "
                                                     f"{table.names[j]!r}"))
                lines.append(lineno)
    except OSError as exc:
        raise ResultError(f"{src}: cannot read: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise ResultError(_not_utf8(path, lineno)) from None
    if table is None or not lines:
        raise ResultError(f"{src}: no header row and data rows"
                          + (f" (the header is line {table.header_line})" if table else ""))
    table.meta = meta
    table.lines = np.frombuffer(lines, dtype=np.int64)
    table.values = np.frombuffer(numbers, dtype=float).reshape(len(lines), len(picked))
    for c, col in enumerate(table.columns.values()):
        bad = ~np.isfinite(table.values[:, c])
        if bad.any():
            raise ResultError(f"{src}: column {table.names[col.index]!r} ({col.role}) has "
                              f"{int(bad.sum())} non-finite value(s), first on line "
                              f"{int(table.lines[int(np.argmax(bad))])}")
    return table


#: The roles a column may be given for with ``--columns ROLE=NAME`` (and their short
#: names): the keys of ``fields`` that :func:`read_csv` takes.
COLUMN_ROLES = {"x": "x", "y": "y", "z": "z", "p": "pressure", "pressure": "pressure",
                "f": "normal_force", "normal_force": "normal_force", "active": "active"}


def parse_columns(text: str) -> dict:
    """``"x=x_m,y=y_m,p=p_pa"`` (``grade --columns``) as the ``fields`` of :func:`read_csv`.

    Roles: x, y, z, p (or pressure), f (or normal_force), active; each at most once; a
    column's name as the header writes it (case-insensitive; with its unit, ``x_m`` or
    ``x [mm]``).

    Raises
    ------
    ValueError
        Naming the item: not ROLE=NAME, an unknown role, a role given twice.

    Examples
    --------
    >>> parse_columns("x=x_m, y=y_m, p=p_pa")
    {'x': 'x_m', 'y': 'y_m', 'pressure': 'p_pa'}
    """
    out = {}
    for item in str(text).split(","):
        if not item.strip():
            continue
        role, sep, name = item.partition("=")
        role, name = role.strip().lower(), name.strip()
        if not sep or not name:
            raise ValueError(f"--columns {text!r}: expected ROLE=NAME items separated by "
                             f"commas, got {item.strip()!r}")
        if role not in COLUMN_ROLES:
            raise ValueError(f"--columns {text!r}: unknown role {role!r}; roles: "
                             f"{', '.join(COLUMN_ROLES)}")
        key = COLUMN_ROLES[role]
        if key in out:
            raise ValueError(f"--columns {text!r}: the {key} column is given twice")
        out[key] = name
    if not out:
        raise ValueError(f"--columns {text!r}: expected ROLE=NAME items (x=x_m,y=y_m,p=p_pa)")
    return out


def pressure_force(points: np.ndarray, pressure: np.ndarray, frame, source: str) -> float:
    """The integral of the nodal pressure over a surface [N]: each node's pressure [Pa]
    times its lumped area in the contact plane (a Delaunay triangulation of the points
    [m] there, :func:`fem_validation.fe.surface.surface_triangles`), as the grader
    integrates it.

    Raises
    ------
    ResultError
        The integral is not a finite number > 0 (no positive pressure).
    """
    from ..fe.surface import lumped_area, surface_triangles
    from .common import resolve_frame

    probe = resolve_frame(frame, points, pressure, True, source)
    xy = probe.to_frame(points)[:, :2]
    try:
        area = lumped_area(xy, surface_triangles(xy))
    except Exception as exc:  # qhull: points on a line, too few points
        raise ResultError(f"{source}: no force given and the pressure cannot be integrated "
                          f"over the points ({type(exc).__name__}): give --force N") from None
    force = float(pressure @ area)
    if not (math.isfinite(force) and force > 0):
        raise ResultError(f"{source}: no force given and the integral of the pressure over "
                          f"the surface is {force!r} N: give --force N")
    return force


def _optional(pairs):
    return {role: col for role, col in pairs if col is not None}


def read_csv(path, *, units: str | None = None, symmetry: str | None = None,
             force: float | None = None, frame: ContactFrame | None = None,
             fields: dict | None = None) -> ContactResult:
    """A ContactResult from a CSV of the contact surface (see the module docstring).

    Raises
    ------
    ResultError
        Naming the file, the row and the column: no pressure column, a value that
        is not a number, NaN, an empty contact, no force, a column's unit that
        contradicts ``units``.
    """
    path = Path(path)
    src = str(path)
    fields = dict(fields or {})

    def choose(t: Table):
        cols = {"x": t.find(("x",), "x", "length", chosen=fields.get("x")),
                "y": t.find(("y",), "y", "length", chosen=fields.get("y"))}
        cols.update(_optional([
            ("z", t.find(("z",), "z", "length", False, fields.get("z"))),
            ("pressure", t.find(PRESSURE_NAMES, "pressure", "pressure", False,
                                fields.get("pressure"))),
            ("normal_force", t.find(NORMAL_FORCE_NAMES, "normal_force", "force", False,
                                    fields.get("normal_force"))),
            ("active", t.find(("active", "status"), "active", "number", False,
                              fields.get("active")))]))
        if "pressure" not in cols and "normal_force" not in cols:
            raise ResultError(f"{src}, line {t.header_line}: no contact pressure column (p, "
                              f"pressure, cpress) and no nodal force column (f, normal_force); "
                              f"columns: {', '.join(t.labels)}")
        return cols

    t = read_table(path, choose)
    units = t.resolve_units(units)
    length, force_unit, pressure_unit = units_of(units, f"{src}: ")
    if symmetry is None and "symmetry" in t.meta:
        symmetry = t.meta["symmetry"][0]
    force = t.meta_number("force", force, unit="N")
    try:
        ok = math.isfinite(float(force)) and float(force) > 0 if force is not None else True
    except (TypeError, ValueError):
        ok = False
    if not ok:
        raise ResultError(f"{src}: the force must be a finite number > 0, got {force!r}")
    z = t["z"] if "z" in t else np.zeros(len(t.lines))
    points = np.column_stack([t["x"], t["y"], z]) * length
    pressure = t["pressure"] * pressure_unit if "pressure" in t else None
    normal_force = t["normal_force"] * force_unit if "normal_force" in t else None
    details = {"reader": "csv", "units": units}
    if force is None and normal_force is not None and np.isfinite(normal_force).all():
        force = float(normal_force.sum()) / force_unit
        details["force_from"] = "the sum of the nodal forces (no force given)"
    elif force is None and pressure is not None and (pressure > 0).any():
        from ..results.contact import surface_points

        force = pressure_force(surface_points(points, src), pressure, frame, src) / force_unit
        details["force_from"] = ("the integral of the pressure over the surface (no force "
                                 "given)")
        details["by_construction"] = ["pressure_integral_rel_err"]
    result = finish(points, pressure, normal_force,
                    None if force is None else float(force) * force_unit, symmetry, frame,
                    source=src, details=details)
    if "active" in t:
        from dataclasses import replace

        result = replace(result, active=t["active"] != 0)
    return result


def read_force_approach(path, units: str | None = None) -> tuple[np.ndarray, np.ndarray, str]:
    """A force against approach curve from a CSV: (approach [m], force [N], units).

    Columns: ``approach`` (or ``overlap``, ``delta``) and ``force`` (or ``f``,
    ``fn``); ``# units = mm`` (or ``units``, or ``approach [mm]``) reads the approach in mm.

    Raises
    ------
    ResultError
        Naming the file, the line and the column.
    """
    src = str(path)

    def choose(t: Table):
        a = t.find(("approach", "overlap", "delta"), "approach", "length", False)
        f = t.find(("force", "f", "fn", "normal_force"), "force", "force", False)
        if a is None or f is None:
            raise ResultError(f"{src}, line {t.header_line}: needs an approach column "
                              f"(approach, overlap, delta) and a force column (force, f, fn); "
                              f"columns: {', '.join(t.labels)}")
        return {"approach": a, "force": f}

    t = read_table(path, choose)
    units = t.resolve_units(units)
    length, force_unit, _ = units_of(units, f"{src}: ")
    return t["approach"] * length, t["force"] * force_unit, units
