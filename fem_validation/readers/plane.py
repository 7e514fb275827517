"""The one dispatch of 2-D results (plane strain, axisymmetric), by the file's suffix:
``.frd`` (CalculiX, :mod:`.calculix_plane`), ``.csv`` (:mod:`.csv_plane`), anything else
through meshio (:mod:`.meshio_plane`)."""

from __future__ import annotations

from pathlib import Path

from ..results.contact import ResultError
from ..results.plane import PlaneResult

__all__ = ["read_plane_result"]


def read_plane_result(path, *, model: str | None = None, units: str | None = None,
                      force: float | None = None, fields: dict | None = None,
                      radii: tuple[float, float] | None = None,
                      body1: str | None = None) -> PlaneResult:
    """A :class:`~fem_validation.results.plane.PlaneResult` from a file, by its suffix.

    Parameters
    ----------
    path : path
    model : {"plane-strain", "axisymmetric"}, optional
        Default: the file's (a .frd's deck, a CSV's ``# model`` line); a meshio file needs
        it.
    units : {"SI", "m", "mm"}, optional
        Default: mm for a .frd, else the file's or SI.
    force : float, optional
        The whole contact's force in the file's units (plane strain per unit length,
        axisymmetric the full circle); default the file's (a .frd's reactions, a CSV's
        ``# force`` line) or the integral of the pressure.
    fields : dict, optional
        Field or column names: ``{"pressure": ..., "x": ..., "active": ...}``.
    radii : (float, float), optional
        The scene's radii in the plane (which body is which in a .frd of one material).
    body1 : str, optional
        A .frd's body 1: an element set or material of its deck.

    Raises
    ------
    ResultError
        Naming the file.
    """
    path = Path(path)
    if not path.is_file():
        raise ResultError(f"{path}: " + ("not a regular file (a folder, a device or a pipe)"
                                         if path.exists() else "no such file"))
    suffix = path.suffix.lower()
    fields = dict(fields or {})
    if suffix == ".frd":
        from .calculix_plane import read_calculix_plane

        return read_calculix_plane(path, model=model, units=units, radii=radii, force=force,
                                   body1=body1)
    if suffix == ".csv":
        from .csv_plane import read_csv_plane

        return read_csv_plane(path, model=model, units=units, force=force, fields=fields)
    if model is None:
        raise ResultError(f"{path}: a mesh file does not say its model: give --model "
                          f"plane-strain or axisymmetric")
    from .meshio_plane import read_meshio_plane

    return read_meshio_plane(path, model=model, units=units, force=force, fields=fields)
