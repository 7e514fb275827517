"""A CSV of the contact surface: x, y (and z), the nodal pressure p, and the total force.

The file::

    # force = 4065.5      the total normal force of the model in the file [N]
    # symmetry = quarter  optional: whole, half, quarter (else detected)
    # units = mm          optional: SI (default) or mm (mm, N, MPa)
    x,y,p
    0.0,0.0,3893.1
    ...

Columns (a header row, any order, case-insensitive, a trailing "[unit]" ignored):
``x``, ``y``, optionally ``z``; ``p`` (or ``pressure``, ``cpress``) and/or ``f``
(or ``normal_force``: the nodal normal contact force); optionally ``active``
(1/0).  x, y are taken as coordinates in the contact plane unless a frame is
given.  Options of :func:`read_csv` override the ``#`` lines.
"""

from __future__ import annotations

import csv
import math
import re
from pathlib import Path

import numpy as np

from ..result import ContactFrame, ContactResult, ResultError
from .common import NORMAL_FORCE_NAMES, PRESSURE_NAMES, finish, units_of

_META = re.compile(r"^\s*#\s*(\w+)\s*[=:]\s*(.*?)\s*$")


def _number(text: str, where: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise ResultError(f"{where}: {text!r} is not a number") from None


def _parse(path: Path):
    """(meta {key: (text, line)}, header [names], rows [(line, cells)]) of a CSV."""
    src = str(path)
    meta, header, rows = {}, None, []
    try:
        with open(path, newline="", encoding="utf-8") as f:
            for lineno, line in enumerate(f, 1):
                m = _META.match(line)
                if m:
                    meta[m.group(1).lower()] = (m.group(2), lineno)
                    continue
                if not line.strip() or line.lstrip().startswith("#"):
                    continue
                cells = next(csv.reader([line]))
                if header is None:
                    header = [re.sub(r"\[.*?\]|\(.*?\)", "", c).strip().lower() for c in cells]
                    continue
                if len(cells) != len(header):
                    raise ResultError(f"{src}, line {lineno}: {len(cells)} values, the header "
                                      f"has {len(header)} columns")
                rows.append((lineno, cells))
    except OSError as exc:
        raise ResultError(f"{src}: cannot read: {exc.strerror}") from None
    except UnicodeDecodeError:
        raise ResultError(f"{src}: not a text (UTF-8) CSV file") from None
    if header is None or not rows:
        raise ResultError(f"{src}: no header row and data rows")
    return meta, header, rows


def read_csv(path, *, units: str | None = None, symmetry: str | None = None,
             force: float | None = None, frame: ContactFrame | None = None,
             fields: dict | None = None) -> ContactResult:
    """A ContactResult from a CSV of the contact surface (see the module docstring).

    Raises
    ------
    ResultError
        Naming the file, the row and the column: no pressure column, a value that
        is not a number, NaN, an empty contact, no force.
    """
    path = Path(path)
    src = str(path)
    meta, header, rows = _parse(path)
    fields = dict(fields or {})

    def column(names, role):
        chosen = fields.get(role)
        if chosen is not None:
            if chosen.lower() not in header:
                raise ResultError(f"{src}: no column {chosen!r} for the {role} "
                                  f"(columns: {', '.join(header)})")
            return header.index(chosen.lower())
        return next((header.index(n) for n in names if n in header), None)

    ix, iy, iz = (column((c,), c) for c in ("x", "y", "z"))
    if ix is None or iy is None:
        raise ResultError(f"{src}: needs columns x and y (columns: {', '.join(header)})")
    ip = column(PRESSURE_NAMES, "pressure")
    jf = column(NORMAL_FORCE_NAMES, "normal_force")
    ia = column(("active", "status"), "active")
    if ip is None and jf is None:
        raise ResultError(f"{src}: no contact pressure column (p, pressure, cpress) and no "
                          f"nodal force column (f, normal_force); columns: {', '.join(header)}")
    table = np.empty((len(rows), len(header)))
    for k, (lineno, cells) in enumerate(rows):
        for j, cell in enumerate(cells):
            if j in (ix, iy, iz, ip, jf, ia):
                table[k, j] = _number(cell.strip(), f"{src}, line {lineno}, column "
                                                    f"{header[j]!r}")
    for j, role in ((ix, "x"), (iy, "y"), (iz, "z"), (ip, "pressure"), (jf, "normal_force")):
        if j is None:
            continue
        bad = ~np.isfinite(table[:, j])
        if bad.any():
            lineno = rows[int(np.argmax(bad))][0]
            raise ResultError(f"{src}: column {header[j]!r} ({role}) has {int(bad.sum())} "
                              f"non-finite value(s), first on line {lineno}")

    def meta_value(key, given):
        if given is not None:
            return given
        return meta[key][0] if key in meta else None

    units = meta_value("units", units) or "SI"
    length, force_unit, pressure_unit = units_of(units, f"{src}: ")
    symmetry = meta_value("symmetry", symmetry)
    if force is None and "force" in meta:
        text, lineno = meta["force"]
        force = _number(text.split()[0] if text else text, f"{src}, line {lineno}, force")
    if force is not None and not (math.isfinite(float(force)) and float(force) > 0):
        raise ResultError(f"{src}: the force must be a finite number > 0, got {force!r}")
    z = table[:, iz] if iz is not None else np.zeros(len(rows))
    points = np.column_stack([table[:, ix], table[:, iy], z]) * length
    pressure = table[:, ip] * pressure_unit if ip is not None else None
    normal_force = table[:, jf] * force_unit if jf is not None else None
    result = finish(points, pressure, normal_force,
                    None if force is None else float(force) * force_unit, symmetry, frame,
                    source=src, details={"reader": "csv", "units": units})
    if ia is not None:
        from dataclasses import replace

        result = replace(result, active=table[:, ia] != 0)
    return result


def read_force_approach(path, units: str | None = None) -> tuple[np.ndarray, np.ndarray, str]:
    """A force against approach curve from a CSV: (approach [m], force [N], units).

    Columns: ``approach`` (or ``overlap``, ``delta``) and ``force`` (or ``f``,
    ``fn``); ``# units = mm`` (or ``units``) scales the approach from mm.

    Raises
    ------
    ResultError
        Naming the file, the line and the column.
    """
    path = Path(path)
    src = str(path)
    meta, header, rows = _parse(path)
    ia = next((header.index(n) for n in ("approach", "overlap", "delta") if n in header), None)
    jf = next((header.index(n) for n in ("force", "f", "fn", "normal_force") if n in header),
              None)
    if ia is None or jf is None:
        raise ResultError(f"{src}: needs an approach column (approach, overlap, delta) and a "
                          f"force column (force, f, fn); columns: {', '.join(header)}")
    values = np.empty((len(rows), 2))
    for k, (lineno, cells) in enumerate(rows):
        for col, j in enumerate((ia, jf)):
            values[k, col] = _number(cells[j].strip(), f"{src}, line {lineno}, column "
                                                       f"{header[j]!r}")
    units = units or (meta["units"][0] if "units" in meta else "SI")
    length, force_unit, _ = units_of(units, f"{src}: ")
    return values[:, 0] * length, values[:, 1] * force_unit, units
