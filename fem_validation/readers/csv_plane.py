"""A CSV of a 2-D contact line: x (or r) and the nodal pressure p.

The file::

    # model = axisymmetric   plane-strain or axisymmetric (or --model)
    # force = 2605.8         plane strain: per unit length [N/m, or N/mm in mm units] of
                             the whole contact; axisymmetric: the full circle [N]; without
                             it (and without --force), the integral of p
    # symmetry = half        plane strain: the file holds x >= 0 of a symmetric model
                             (default: detected, every x >= 0)
    # units = mm             SI or mm (mm, N, MPa); default: the columns' units, else SI
    r,p
    0.0,4064.2
    ...

Columns (any order, case-insensitive): ``x`` or ``r``; ``p`` (or ``pressure``,
``cpress``, ...); optionally ``active`` (1/0).  Other names are chosen with ``fields``
(``grade --columns x=r_mm,p=p_mpa``).  The file is read by
:func:`fem_validation.readers.csv_file.read_table` (BOM, ``;`` separators, comment lines,
units in the column names: all as for the 3-D CSV).  Every malformed file gets one
:class:`~fem_validation.results.contact.ResultError` naming the file and the line.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..results.contact import ResultError
from ..results.plane import MODELS, PlaneResult
from .common import PRESSURE_NAMES, units_of
from .csv_file import read_table

__all__ = ["read_csv_plane"]


def read_csv_plane(path, *, model: str | None = None, units: str | None = None,
                   force: float | None = None, half_model: bool | None = None,
                   fields: dict | None = None) -> PlaneResult:
    """A :class:`PlaneResult` of a CSV of x (or r), p (see the module's notes).

    Parameters
    ----------
    path : path
    model : {"plane-strain", "axisymmetric"}, optional
        Default: the file's ``# model`` line.
    units : {"SI", "m", "mm"}, optional
    force : float, optional
        In the file's units (N/m or N/mm per length; N for the full circle).
    half_model : bool, optional
        Plane strain: the file holds x >= 0 of a symmetric model (default: the
        ``# symmetry`` line, else every x >= 0).
    fields : dict, optional
        ``{"x": NAME, "pressure": NAME, "active": NAME}``.

    Raises
    ------
    ResultError
        Naming the file and line: no model, an unknown model, no x or p column, a force
        that is not a finite number > 0, what :func:`read_table` refuses.
    """
    path = Path(path)
    src = str(path)
    fields = dict(fields or {})

    def choose(t):
        x = t.find(("x", "r", "radius"), "x", "length", chosen=fields.get("x"))
        cols = {"x": x, "pressure": t.find(PRESSURE_NAMES, "pressure", "pressure",
                                           chosen=fields.get("pressure"))}
        active = t.find(("active", "status"), "active", "number", False, fields.get("active"))
        if active is not None:
            cols["active"] = active
        return cols

    t = read_table(path, choose)
    if model is None:
        if "model" not in t.meta:
            raise ResultError(f"{src}: the model is not known: give a '# model = "
                              f"plane-strain' (or axisymmetric) line or --model")
        text, line = t.meta["model"]
        model = text.strip().lower()
        if model not in MODELS:
            raise ResultError(f"{src}, line {line}: model must be one of {', '.join(MODELS)}, "
                              f"got {text!r}")
    elif model not in MODELS:
        raise ResultError(f"{src}: model must be one of {', '.join(MODELS)}, got {model!r}")
    units = t.resolve_units(units)
    length, force_unit, pressure_unit = units_of(units, f"{src}: ")
    x = t["x"] * length
    p = t["pressure"] * pressure_unit
    if half_model is None and "symmetry" in t.meta:
        text, line = t.meta["symmetry"]
        if text.strip().lower() not in ("half", "whole"):
            raise ResultError(f"{src}, line {line}: symmetry of a 2-D line is half or whole, "
                              f"got {text!r}")
        half_model = text.strip().lower() == "half"
    if half_model is None:
        half_model = bool(x.min() >= 0)
    value = t.meta_number("force", force)
    details = {"reader": "csv_plane", "units": units}
    per = force_unit / length if model == "plane-strain" else force_unit
    result = PlaneResult(model, x, p, 1.0, source=src,
                         half_model=half_model and model == "plane-strain",
                         active=(t["active"] != 0) if "active" in t else None,
                         details=details)
    if value is None:
        value_si = result.pressure_integral()
        details["force_from"] = "the integral of the pressure (no force given)"
    else:
        try:
            ok = math.isfinite(float(value)) and float(value) > 0
        except (TypeError, ValueError):
            ok = False
        if not ok:
            raise ResultError(f"{src}: the force must be a finite number > 0, got {value!r}")
        value_si = float(value) * per
    from dataclasses import replace

    return replace(result, force=float(value_si), details=details)
