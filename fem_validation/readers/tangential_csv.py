"""A frictional contact result from two CSV files: the contact surface and the path.

The surface at one state of the path (the snapshot)::

    # mu = 0.3              coefficient of friction
    # direction_deg = 0     the load's angle from the x axis [deg] (default 0)
    # normal_force = 42.2   the normal force of the MODEL IN THE FILE [N] (a quarter
    #                       model's own reaction); default: the scene's load
    # snapshot = 20         path index of this state (default: the first reversal)
    # symmetry = quarter    optional: whole, half, quarter (else detected)
    # units = mm            optional: SI or mm (mm, N, MPa); default: the columns'
    #                       units (x [mm], p [MPa]), else SI
    x,y,z,p,qx,qy,stick
    0.0,0.0,0.0,1855.9,310.2,0.0,1
    ...

Columns (a header row, any order, case-insensitive; a unit in a column's name as
:mod:`fem_validation.readers.csv_file` reads it, which also reads spreadsheets' CSVs):
``x``, ``y``, optionally ``z``; the contact pressure ``p`` (or ``pressure``,
``cpress``); the tangential traction ``qx``, ``qy`` (or
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

from ..results.contact import MULTIPLICITY, ContactFrame, ResultError
from ..results.tangential import TangentialResult, check_path
from .common import PRESSURE_NAMES, finish, units_of
from .csv_file import Table, read_table

SHEAR_NAMES = {"x": ("qx", "shear_x", "cshear1", "tx"), "y": ("qy", "shear_y", "cshear2", "ty"),
               "z": ("qz", "shear_z", "tz")}
DISPLACEMENT_NAMES = ("displacement", "delta", "u", "slip")
FORCE_NAMES = ("force", "q", "tangential_force")


def read_history(path, units: str | None = None) -> tuple[np.ndarray, np.ndarray, str]:
    """The path of a frictional result: (displacement [m], force of the model in the file
    [N], units), from a CSV (see the module docstring), checked as a path
    (:func:`fem_validation.results.tangential.check_path`).

    Raises
    ------
    ResultError
        Naming this file, the line and the column.
    """
    src = str(path)

    def choose(t: Table):
        return {"displacement": t.find(DISPLACEMENT_NAMES, "displacement", "length"),
                "force": t.find(FORCE_NAMES, "tangential force", "force")}

    t = read_table(path, choose)
    units = t.resolve_units(units)
    length, force_unit, _ = units_of(units, f"{src}: ")
    displacement, force = check_path(t["displacement"] * length, t["force"] * force_unit, src,
                                     lines=t.lines)
    return displacement, force, units


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

    def choose(t: Table):
        cols = {"x": t.find(("x",), "x", "length"), "y": t.find(("y",), "y", "length"),
                "pressure": t.find(PRESSURE_NAMES, "contact pressure", "pressure"),
                "qx": t.find(SHEAR_NAMES["x"], "shear x", "pressure"),
                "qy": t.find(SHEAR_NAMES["y"], "shear y", "pressure")}
        for role, names, kind in (("z", ("z",), "length"), ("qz", SHEAR_NAMES["z"], "pressure"),
                                  ("stick", ("stick",), "number")):
            col = t.find(names, role, kind, required=False)
            if col is not None:
                cols[role] = col
        return cols

    t = read_table(surface, choose)
    given_units = units
    units = t.resolve_units(units)
    length, force_unit, pressure_unit = units_of(units, f"{src}: ")
    n = len(t.lines)
    z = t["z"] if "z" in t else np.zeros(n)
    points = np.column_stack([t["x"], t["y"], z]) * length
    pressure = t["pressure"] * pressure_unit
    shear3 = np.column_stack([t["qx"], t["qy"], t["qz"] if "qz" in t else np.zeros(n)])
    shear3 = shear3 * pressure_unit

    mu = t.meta_number("mu", mu)
    if mu is None:
        raise ResultError(f"{src}: no coefficient of friction: give --mu or a '# mu = ...' line")
    direction_deg = t.meta_number("direction_deg", direction_deg, unit="deg")
    direction_deg = 0.0 if direction_deg is None else direction_deg
    if not math.isfinite(direction_deg):
        raise ResultError(f"{src}: the direction must be a finite angle in degrees, got "
                          f"{direction_deg!r}")
    snapshot = t.meta_number("snapshot", snapshot, integer=True)
    if symmetry is None and "symmetry" in t.meta:
        symmetry = t.meta["symmetry"][0]
    normal_force = t.meta_number("normal_force", normal_force, unit="N")
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
    for key, value, ok, allowed in (
            ("snapshot", snapshot, snapshot is None or 1 <= snapshot < len(force),
             f"an index 1..{len(force) - 1} into the path of {len(force)} points in {history}"),
            ("mu", mu, mu > 0, "a number > 0")):
        if not ok:
            line = f", line {t.meta[key][1]}" if key in t.meta else ""
            raise ResultError(f"{src}{line}: {key} = {value!r}: it must be {allowed}")
    shear = np.column_stack([shear3 @ base.frame.x_axis, shear3 @ base.frame.y_axis])
    return TangentialResult(
        points=points, pressure=pressure, shear=shear, normal_force=whole_p, mu=mu,
        direction=math.radians(direction_deg), displacement=displacement,
        force=force * MULTIPLICITY[base.symmetry], snapshot=snapshot, symmetry=base.symmetry,
        frame=base.frame, stick=(t["stick"] != 0) if "stick" in t else None,
        source=src, details={**base.details, "history": str(history),
                             "history_units": history_units,
                             "normal_force_from": ("file" if normal_force is not None
                                                   else "scene")})
