"""A DEM code's impact trajectory from a CSV file: time, overlap, normal force (and, for an
oblique impact, tangential force, tangential velocity and spin).

The file (one row per output step, from before the contact to after it)::

    # units = SI          optional: SI (m, N) or mm (mm, N; velocities in mm/s)
    t,overlap,normal_force
    0.0,-2.0e-6,0.0
    1.0e-7,0.0,0.0
    2.0e-7,2.0e-6,3.1
    ...

Columns (a header row, any order, case-insensitive; a unit after a name is allowed:
``t [s]``, ``t_s``, ``overlap_m``, ``overlap [mm]``, ``normal_force_N``):

=====================  ====================================================  ==========
role                   names                                                 unit
=====================  ====================================================  ==========
time                   ``t``, ``time``                                       s
overlap                ``overlap``, ``approach``, ``delta``                  m (mm)
normal force           ``normal_force``, ``fn``, ``f_n``, ``force``          N
normal velocity        ``v_n``, ``vn``, ``normal_velocity`` (optional)       m/s (mm/s)
tangential force       ``tangential_force``, ``ft``, ``f_t`` (oblique)       N
tangential velocity    ``v_t``, ``vt``, ``tangential_velocity`` (oblique)    m/s (mm/s)
spin                   ``omega``, ``spin``, ``angular_velocity`` (oblique)   rad/s
=====================  ====================================================  ==========

The file is read by :func:`fem_validation.readers.csv_file.read_table` (streamed; a
byte-order mark, ``#`` comment lines, ``;`` or tab separators and decimal commas are
read; at most :data:`~fem_validation.readers.csv_file.MAX_ROWS` rows) after a size check
(:data:`MAX_BYTES`), and validated once as an
:class:`~fem_validation.results.impact.ImpactTrajectory`.
"""

from __future__ import annotations

import os
import stat

from ..results.contact import ResultError
from ..results.impact import ImpactTrajectory
from .common import units_of
from .csv_file import Column, read_table, split_unit

__all__ = ["COLUMNS", "MAX_BYTES", "read_impact"]

#: The largest trajectory file read [bytes] (256 MiB: two million rows of seven columns).
MAX_BYTES = 256 << 20

#: role -> (names, kind of quantity, required)
COLUMNS = {
    "t": (("t", "time", "t_s", "time_s"), "time", True),
    "overlap": (("overlap", "approach", "delta"), "length", True),
    "normal_force": (("normal_force", "fn", "f_n", "force", "normal_force_n"), "force", True),
    "v_n": (("v_n", "vn", "normal_velocity", "v_n_m/s"), "velocity", False),
    "tangential_force": (("tangential_force", "ft", "f_t", "tangential_force_n"), "force",
                         False),
    "v_t": (("v_t", "vt", "tangential_velocity", "v_t_m/s"), "velocity", False),
    "omega": (("omega", "spin", "angular_velocity", "omega_rad/s"), "spin", False),
}
#: Units a column of each kind that the CSV reader does not know may name, and the system.
_OWN_UNITS = {"time": {"s": "both"}, "velocity": {"m/s": "SI", "mm/s": "mm"},
              "spin": {"rad/s": "both", "1/s": "both"}}


def read_impact(path, units: str | None = None) -> ImpactTrajectory:
    """An :class:`~fem_validation.results.impact.ImpactTrajectory` from a CSV file (see
    the module docstring), in SI.

    Parameters
    ----------
    path : str or os.PathLike
    units : {"SI", "m", "mm"}, optional
        The file's units (default: its ``# units`` line, else the columns' units, else SI).

    Raises
    ------
    ResultError
        Naming the file, the line and the column: a missing column, a column given twice,
        a cell that is not a finite number, time not increasing, a file over
        :data:`MAX_BYTES` or not text.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "impact.csv"
    >>> _ = f.write_text("t [s];overlap [mm];Fn\\n0;-0,001;0\\n1e-6;0,002;4\\n2e-6;-0,001;0\\n")
    >>> r = read_impact(f)
    >>> r.overlap.tolist(), r.details["units"]
    ([-1e-06, 2e-06, -1e-06], 'mm')
    """
    src = str(path)
    try:
        st = os.stat(path)
    except OSError:
        st = None  # missing or unreadable: read_table says which, naming the file
    if st is not None and not stat.S_ISREG(st.st_mode):
        raise ResultError(f"{src}: not a regular file (a folder, a device or a pipe): give "
                          f"the trajectory file itself")
    size = st.st_size if st is not None else 0
    if size > MAX_BYTES:
        raise ResultError(f"{src}: {size} bytes, more than the {MAX_BYTES} bytes an impact "
                          f"trajectory is read from (write fewer rows: every step of the "
                          f"contact and a few before and after it are enough)")
    own = {}

    def choose(t):
        lowered = [label.strip().lower() for label in t.labels]
        found = {}
        for role, (names, kind, required) in COLUMNS.items():
            hits = [j for j, lab in enumerate(lowered) if lab in names]
            if not hits:
                hits = [j for j, name in enumerate(t.names) if name in names]
            if len(hits) > 1:
                raise ResultError(f"{src}, line {t.header_line}: the {role} column is in the "
                                  f"header {len(hits)} times ("
                                  f"{', '.join(repr(t.labels[j]) for j in hits)})")
            if not hits:
                if required:
                    raise ResultError(f"{src}, line {t.header_line}: no {role} column (one "
                                      f"of {', '.join(names[:3])}); columns: "
                                      f"{', '.join(t.labels)}")
                continue
            j = hits[0]
            if kind in _OWN_UNITS:
                unit = None if lowered[j] in names else split_unit(t.labels[j])[1]
                if unit is not None and unit not in _OWN_UNITS[kind]:
                    raise ResultError(f"{src}, line {t.header_line}: column "
                                      f"{t.labels[j].strip()!r} names the unit {unit!r}; "
                                      f"the {role} is read in "
                                      f"{' or '.join(_OWN_UNITS[kind])}")
                own[role] = (t.labels[j].strip(), unit)
                t.units[j] = None  # checked here, not by the table's unit systems
                kind = "number"
            elif lowered[j] in names:
                t.units[j] = None  # "v_n", "f_n": the name, not a unit
            found[role] = Column(j, role, kind)
        return found

    t = read_table(path, choose)
    units = t.resolve_units(units)
    length, force, _ = units_of(units, f"{src}: ")
    system = "mm" if units == "mm" else "SI"
    for role, (label, unit) in own.items():
        said = _OWN_UNITS[COLUMNS[role][1]].get(unit, "both") if unit else "both"
        if said not in ("both", system):
            raise ResultError(f"{src}, line {t.header_line}: column {label!r} is in {said} "
                              f"units but the file is read in {system} units: correct one "
                              f"of them")
    scale = {"t": 1.0, "overlap": length, "normal_force": force, "v_n": length,
             "tangential_force": force, "v_t": length, "omega": 1.0}
    values = {role: t[role] * scale[role] for role in t.columns}
    return ImpactTrajectory(**values, source=src, lines=t.lines,
                            details={"units": units, "reader": "impact CSV",
                                     "columns": {role: t.labels[c.index].strip()
                                                 for role, c in t.columns.items()}})

