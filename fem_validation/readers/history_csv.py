"""A DEM code's tangential force-displacement history from a CSV file (no surface file).

The file::

    # mu = 0.3              coefficient of friction (or --mu)
    # normal_force = 12.5   P [N] where there is no normal_force column (or
    #                       --normal-force; default: the scene's load)
    # units = mm            optional: SI or mm (mm, N); default the columns' units, else SI
    displacement,force,normal_force
    0.0,0.0,12.5
    1e-9,0.0184,12.5
    ...

Columns (a header row, any order, case-insensitive, read by
:func:`fem_validation.readers.csv_file.read_table` as every CSV of this package: a
byte-order mark, comments, semicolons and decimal commas, units in the names, the caps
on rows and line lengths, non-finite numbers refused naming the line):

* ``displacement`` (or ``delta``, ``u``, ``slip``): the relative tangential displacement
  [m or mm] of the moved body, projected on the contact plane, from 0, rising first;
* ``force`` (or ``q``, ``tangential_force``) [N]: the tangential force that drives it
  (the displacement's sign on the ramp), projected on the contact plane;
* optionally ``normal_force`` (or ``fn``, ``normal_load``, ``p_n``) [N] at each row.

The same names as :mod:`fem_validation.readers.tangential_csv`'s path file, which this
reader extends with the normal force and the ``# mu`` line.
"""

from __future__ import annotations

import math

from ..results.contact import ResultError
from ..results.tangential_history import TangentialHistory
from .common import units_of
from .csv_file import Table, read_table
from .tangential_csv import DISPLACEMENT_NAMES, FORCE_NAMES

__all__ = ["NORMAL_FORCE_NAMES", "read_dem_history"]

#: Names of the normal force column.
NORMAL_FORCE_NAMES = ("normal_force", "fn", "normal_load", "p_n")


def read_dem_history(path, *, units: str | None = None, mu: float | None = None,
                     normal_force: float | None = None,
                     default_normal_force: float | None = None) -> TangentialHistory:
    """A :class:`~fem_validation.results.tangential_history.TangentialHistory` from a CSV.

    Parameters
    ----------
    path : path
        The file (module docstring).
    units : {"SI", "m", "mm"}, optional
        Default the ``# units`` line, else the columns' units, else SI.
    mu : float, optional
        Default the ``# mu`` line; one of them is needed.
    normal_force : float, optional
        P [N] for every row; overrides the ``# normal_force`` line; refused with a
        ``normal_force`` column (which one would hold?).
    default_normal_force : float, optional
        P [N] where neither the column, the option nor the line gives one (the scene's
        load).

    Returns
    -------
    TangentialHistory
        ``details`` say the units and where P and mu came from.

    Raises
    ------
    ResultError
        Naming the file, the line and the column.
    """
    src = str(path)

    def choose(t: Table):
        cols = {"displacement": t.find(DISPLACEMENT_NAMES, "displacement", "length"),
                "force": t.find(FORCE_NAMES, "tangential force", "force")}
        col = t.find(NORMAL_FORCE_NAMES, "normal force", "force", required=False)
        if col is not None:
            cols["normal_force"] = col
        return cols

    t = read_table(path, choose)
    units = t.resolve_units(units)
    length, force_unit, _ = units_of(units, f"{src}: ")
    mu_from = "option" if mu is not None else "file"
    mu = t.meta_number("mu", mu)
    if mu is None:
        raise ResultError(f"{src}: no coefficient of friction: give --mu or a '# mu = ...' "
                          f"line")
    if not (math.isfinite(mu) and mu > 0):
        raise ResultError(f"{src}: mu = {mu!r}: it must be a finite number > 0")
    if "normal_force" in t:
        if normal_force is not None:
            raise ResultError(f"{src}: the file has a normal_force column: --normal-force "
                              f"does not apply (drop one of them)")
        p, p_from = t["normal_force"] * force_unit, "column"
    else:
        given = t.meta_number("normal_force", normal_force, unit="N")
        if given is not None:
            p_from = "option" if normal_force is not None else "file"
        elif default_normal_force is not None:
            given, p_from = float(default_normal_force), "scene"
        else:
            raise ResultError(f"{src}: no normal force: a normal_force column, --normal-force "
                              f"N, a '# normal_force = ...' line or a scene with a load")
        if not (math.isfinite(given) and given > 0):
            raise ResultError(f"{src}: the normal force must be a finite number > 0, got "
                              f"{given!r}")
        p = given * (force_unit if p_from == "file" else 1.0)
    return TangentialHistory(
        displacement=t["displacement"] * length, force=t["force"] * force_unit,
        normal_force=p, mu=mu, source=src, lines=t.lines,
        details={"reader": "dem history csv", "units": units, "normal_force_from": p_from,
                 "mu_from": mu_from})
