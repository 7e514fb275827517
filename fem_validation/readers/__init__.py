"""Other codes' files -> results.

:func:`read_result` is the one dispatch, by the file's suffix: ``.csv``
(:mod:`.csv_file`), ``.frd`` (CalculiX, :mod:`.calculix` over the parser :mod:`.frd`),
anything meshio reads (:mod:`.meshio_file`).  The tangential readers:
:mod:`.tangential_csv`, :mod:`.calculix_friction`.  What the readers share (units, the
contact frame, the symmetry): :mod:`.common`.
"""

from __future__ import annotations

from pathlib import Path

from ..results.contact import ContactFrame, ContactResult, ResultError
from .common import units_of


def read_result(path, *, units: str | None = None, symmetry: str | None = None,
                force: float | None = None, frame: ContactFrame | dict | None = None,
                fields: dict | None = None) -> ContactResult:
    """A ContactResult from a file, by its extension: ``.csv`` (:mod:`.csv_file`), ``.frd``
    (CalculiX, :mod:`.calculix`), anything else through meshio (:mod:`.meshio_file`).

    Parameters
    ----------
    path : path
    units : {"SI", "m", "mm"}, optional
        Default: a CSV's ``# units`` line, else the units its columns name
        (``x [mm]``), else SI.
    symmetry : {"whole", "half", "quarter"}, optional
        Detected where not given.
    force : float, optional
        The total normal force of the model in the file [its force unit].
    frame : ContactFrame or dict, optional
        In SI; found where not given; a dict of some of origin, normal, x_axis: the
        rest found.
    fields : dict, optional
        Field names: ``{"pressure": NAME[:COMPONENT], "normal_force": ...,
        "reaction": ..., "stress": ...}``; recognised where not given.

    Raises
    ------
    ResultError
        Naming the file and the field.
    """
    path = Path(path)
    if not path.is_file():
        raise ResultError(f"{path}: " + ("not a regular file (a folder, a device or a pipe)"
                                         if path.exists() else "no such file"))
    if units is not None:
        units_of(units, f"{path}: ")
    kwargs = {"units": units, "symmetry": symmetry, "force": force, "frame": frame,
              "fields": dict(fields or {})}
    suffix = path.suffix.lower()
    if suffix == ".csv":
        from .csv_file import read_csv

        return read_csv(path, **kwargs)
    if suffix == ".frd":
        from .calculix import read_result as read_frd

        return read_frd(path, **kwargs)
    from .meshio_file import read_mesh

    return read_mesh(path, **kwargs)
