"""A frictional contact result from two CSV files: the contact surface and the path.

The surface at one state of the path (the snapshot)::

    # mu = 0.3              coefficient of friction
    # direction_deg = 0     the load's angle from the x axis [deg] (default 0)
    # normal_force = 42.2   the normal force of the MODEL IN THE FILE [N] (a quarter
    #                       model's own reaction); default: the scene's load
    # snapshot = 20         path index of this state (default: the first reversal)
    # symmetry = quarter    optional: whole, half, quarter (else detected)
    # units = mm            optional: SI (default) or mm (mm, N, MPa)
    x,y,z,p,qx,qy,stick
    0.0,0.0,0.0,1855.9,310.2,0.0,1
    ...

Columns (a header row, any order, case-insensitive, a trailing "[unit]"
ignored): ``x``, ``y``, optionally ``z``; the contact pressure ``p`` (or
``pressure``, ``cpress``); the tangential traction ``qx``, ``qy`` (or
``shear_x``, ``shear_y``; ``cshear1``, ``cshear2``), optionally ``qz``: the
traction that body 1 exerts on body 2, in the file's axes (projected on the
contact plane of the frame); optionally ``stick`` (1 stuck, 0 slipping or open;
information only).

The path, one row per state from the unloaded one::

    # units = mm
    displacement,force
    0.0,0.0
    ...

Columns ``displacement`` (or ``delta``, ``u``, ``slip``): the relative tangential
displacement of body 1's remote points with respect to body 2's along the load
[m or mm], starting at 0 and rising first; ``force`` (or ``q``,
``tangential_force``): the tangential force along the load of the MODEL IN THE
FILE [N] (multiplied by 4 for a quarter model, 2 for a half, as the normal
force).  Options of :func:`read_tangential` override the ``#`` lines.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..result import MULTIPLICITY, ContactFrame, ResultError
from ..tangential_result import TangentialResult
from .common import PRESSURE_NAMES, finish, units_of
from .table import _number, _parse

SHEAR_NAMES = {"x": ("qx", "shear_x", "cshear1", "tx"), "y": ("qy", "shear_y", "cshear2", "ty"),
               "z": ("qz", "shear_z", "tz")}
DISPLACEMENT_NAMES = ("displacement", "delta", "u", "slip")
FORCE_NAMES = ("force", "q", "tangential_force")


def _columns(header, src, names, role, required=True):
    index = next((header.index(n) for n in names if n in header), None)
    if index is None and required:
        raise ResultError(f"{src}: no {role} column ({', '.join(names)}); columns: "
                          f"{', '.join(header)}")
    return index


def _table(rows, header, cols, src) -> np.ndarray:
    """The numbers of the columns ``cols`` {role: index}, checked finite, (k, len(cols))."""
    out = np.empty((len(rows), len(cols)))
    for k, (lineno, cells) in enumerate(rows):
        for c, j in enumerate(cols.values()):
            out[k, c] = _number(cells[j].strip(), f"{src}, line {lineno}, column "
                                                  f"{header[j]!r}")
    for c, (role, j) in enumerate(cols.items()):
        bad = ~np.isfinite(out[:, c])
        if bad.any():
            lineno = rows[int(np.argmax(bad))][0]
            raise ResultError(f"{src}: column {header[j]!r} ({role}) has {int(bad.sum())} "
                              f"non-finite value(s), first on line {lineno}")
    return out


def read_history(path, units: str | None = None) -> tuple[np.ndarray, np.ndarray, str]:
    """The path of a frictional result: (displacement [m], force of the model in the file
    [N], units), from a CSV (see the module docstring).

    Raises
    ------
    ResultError
        Naming the file, the line and the column.
    """
    path = Path(path)
    src = str(path)
    meta, header, rows = _parse(path)
    cols = {"displacement": _columns(header, src, DISPLACEMENT_NAMES, "displacement"),
            "force": _columns(header, src, FORCE_NAMES, "tangential force")}
    values = _table(rows, header, cols, src)
    units = units or (meta["units"][0] if "units" in meta else "SI")
    length, force_unit, _ = units_of(units, f"{src}: ")
    return values[:, 0] * length, values[:, 1] * force_unit, units


def read_tangential(surface, history, *, units: str | None = None, symmetry: str | None = None,
                    normal_force: float | None = None, mu: float | None = None,
                    direction_deg: float | None = None, snapshot: int | None = None,
                    frame: ContactFrame | dict | None = None,
                    default_normal_force: float | None = None) -> TangentialResult:
    """A TangentialResult from a surface CSV and a path CSV (see the module docstring).

    Parameters
    ----------
    surface, history : path
        The two files.
    units : {"SI", "m", "mm"}, optional
        Both files' units; default each file's own ``# units`` line, else SI.
    symmetry : {"whole", "half", "quarter"}, optional
        Detected where not given (as :func:`fem_validation.readers.common.finish`).
    normal_force : float, optional
        The normal force of the model in the file [its force unit]; default the
        ``# normal_force`` line.
    mu : float, optional
        Default the ``# mu`` line; one of them is needed.
    direction_deg : float, optional
        The load's angle from the frame's x axis [deg]; default the
        ``# direction_deg`` line, else 0.
    snapshot : int, optional
        The path index of the surface's state; default the ``# snapshot`` line,
        else the first reversal.
    frame : ContactFrame or dict, optional
        In SI; found where not given.
    default_normal_force : float, optional
        The WHOLE contact's normal force [N] where neither ``normal_force`` nor the
        file gives one (the scene's load).

    Raises
    ------
    ResultError
        Naming the file, the line, the column or the field.
    """
    surface, history = Path(surface), Path(history)
    for p in (surface, history):
        if not p.is_file():
            raise ResultError(f"{p}: no such file")
    src = str(surface)
    meta, header, rows = _parse(surface)

    def meta_number(key, given, kind=float):
        if given is not None:
            return given
        if key not in meta:
            return None
        text, lineno = meta[key]
        value = _number(text.split()[0] if text else text, f"{src}, line {lineno}, {key}")
        if kind is int:
            if value != int(value):
                raise ResultError(f"{src}, line {lineno}: {key} must be an integer, got {text!r}")
            return int(value)
        return value

    given_units = units
    units = units or (meta["units"][0] if "units" in meta else "SI")
    length, force_unit, pressure_unit = units_of(units, f"{src}: ")
    cols = {"x": _columns(header, src, ("x",), "x"), "y": _columns(header, src, ("y",), "y"),
            "pressure": _columns(header, src, PRESSURE_NAMES, "contact pressure"),
            "qx": _columns(header, src, SHEAR_NAMES["x"], "shear x"),
            "qy": _columns(header, src, SHEAR_NAMES["y"], "shear y")}
    for role, names in (("z", ("z",)), ("qz", SHEAR_NAMES["z"]), ("stick", ("stick",))):
        j = _columns(header, src, names, role, required=False)
        if j is not None:
            cols[role] = j
    table = dict(zip(cols, _table(rows, header, cols, src).T, strict=True))
    z = table.get("z", np.zeros(len(rows)))
    points = np.column_stack([table["x"], table["y"], z]) * length
    pressure = table["pressure"] * pressure_unit
    shear3 = np.column_stack([table["qx"], table["qy"], table.get("qz", np.zeros(len(rows)))])
    shear3 = shear3 * pressure_unit

    mu = meta_number("mu", mu)
    if mu is None:
        raise ResultError(f"{src}: no coefficient of friction: give --mu or a '# mu = ...' line")
    direction_deg = meta_number("direction_deg", direction_deg)
    direction_deg = 0.0 if direction_deg is None else direction_deg
    if not math.isfinite(direction_deg):
        raise ResultError(f"{src}: the direction must be a finite angle in degrees, got "
                          f"{direction_deg!r}")
    snapshot = meta_number("snapshot", snapshot, int)
    symmetry = symmetry if symmetry is not None else (meta["symmetry"][0] if "symmetry" in meta
                                                      else None)
    normal_force = meta_number("normal_force", normal_force)
    if normal_force is not None and not (math.isfinite(normal_force) and normal_force > 0):
        raise ResultError(f"{src}: the normal force must be a finite number > 0, got "
                          f"{normal_force!r}")
    # The frame and the symmetry as for a normal contact result (the same detection).
    base = finish(points, pressure, None,
                  (normal_force * force_unit if normal_force is not None else 1.0),
                  symmetry, frame, source=src,
                  details={"reader": "tangential csv", "units": units})
    if normal_force is not None:
        whole_p = base.force
    elif default_normal_force is not None:
        whole_p = float(default_normal_force)
    else:
        raise ResultError(f"{src}: no normal force: give --normal-force N (the model's own), "
                          f"a '# normal_force = ...' line or a scene with a load")
    displacement, force, history_units = read_history(history, given_units)
    shear = np.column_stack([shear3 @ base.frame.x_axis, shear3 @ base.frame.y_axis])
    return TangentialResult(
        points=points, pressure=pressure, shear=shear, normal_force=whole_p, mu=mu,
        direction=math.radians(direction_deg), displacement=displacement,
        force=force * MULTIPLICITY[base.symmetry], snapshot=snapshot, symmetry=base.symmetry,
        frame=base.frame, stick=(table["stick"] != 0) if "stick" in table else None,
        source=src, details={**base.details, "history": str(history),
                             "history_units": history_units,
                             "normal_force_from": ("file" if normal_force is not None
                                                   else "scene")})
