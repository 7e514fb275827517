"""A 2-D mesh with a contact pressure field (any format meshio reads: .vtu, .xdmf, .msh,
.med, .exo, ...) -> :class:`~fem_validation.results.plane.PlaneResult`.

What is read:

* **cells**: the 2-D ones (triangle, triangle6, quad, quad8, quad9); the points' z (if
  any) must be 0: the model lies in the x-y plane, the load along y (an axisymmetric
  model: x the radius, y the axis, as CalculiX, Abaqus and MOOSE's RZ coordinates have it);
* **pressure**: a point field, named (``fields={"pressure": NAME[:COMPONENT]}``) or the
  first of the names the 3-D readers recognise (``cpress``, ``contact_pressure``,
  ``pressure``, ``p``, ...);
* **the contact line**: the boundary nodes (on edges of one cell only) of the body that
  carries the pressure (the mesh's connected part with the larger pressure sum), within
  1.5 times the pressed extent of the first point of contact along x and 0.2 times it
  along y: the pressed nodes and the nodes just beyond the edge;
* **force**: given (``force``: N/m for plane strain, whole contact; N, full circle,
  axisymmetric; in the file's units), else the integral of the pressure (then the grade's
  pressure-integral check holds by construction);
* **half model** (plane strain): every point at x >= 0.

Stresses are not read from meshio files (the grade reports them as not available).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..results.contact import ResultError
from ..results.plane import MODELS, PlaneResult
from .common import PRESSURE_NAMES, units_of

__all__ = ["read_meshio_plane"]

#: Edges (corner, corner[, mid]) of meshio's 2-D cell types.
_EDGES = {"triangle": ((0, 1), (1, 2), (2, 0)),
          "triangle6": ((0, 1, 3), (1, 2, 4), (2, 0, 5)),
          "quad": ((0, 1), (1, 2), (2, 3), (3, 0)),
          "quad8": ((0, 1, 4), (1, 2, 5), (2, 3, 6), (3, 0, 7)),
          "quad9": ((0, 1, 4), (1, 2, 5), (2, 3, 6), (3, 0, 7))}


def _field(mesh, fields: dict, source: str) -> tuple[np.ndarray, str]:
    data = {k: np.asarray(v) for k, v in mesh.point_data.items()}
    chosen = fields.get("pressure")
    if chosen is not None:
        name, _, comp = str(chosen).partition(":")
        if name not in data:
            raise ResultError(f"{source}: no point field {name!r}; fields: "
                              f"{', '.join(data) or 'none'}")
        values = data[name]
        if values.ndim > 1:
            if not comp.isdigit() or int(comp) >= values.shape[1]:
                raise ResultError(f"{source}: field {name!r} has {values.shape[1]} components:"
                                  f" name one ({name}:0 .. {name}:{values.shape[1] - 1})")
            values = values[:, int(comp)]
        return values.astype(float), name
    lower = {k.lower(): k for k in data}
    for candidate in PRESSURE_NAMES:
        if candidate in lower and data[lower[candidate]].ndim == 1:
            return data[lower[candidate]].astype(float), lower[candidate]
    raise ResultError(f"{source}: no contact pressure among the point fields "
                      f"({', '.join(data) or 'none'}): name it (--pressure-field NAME)")


def read_meshio_plane(path, *, model: str, units: str | None = None,
                      force: float | None = None, fields: dict | None = None) -> PlaneResult:
    """A :class:`PlaneResult` of a 2-D mesh file (see the module's notes).

    Parameters
    ----------
    path : path
    model : {"plane-strain", "axisymmetric"}
        A mesh file does not say.
    units : {"SI", "m", "mm"}, optional
        Default SI.
    force : float, optional
        In the file's units; default the integral of the pressure.
    fields : dict, optional
        ``{"pressure": NAME[:COMPONENT]}``.

    Raises
    ------
    ResultError
        Naming the file: unreadable, no 2-D cells, points out of the x-y plane, no pressure
        field, a non-finite pressure, no pressed node.
    """
    import meshio

    path = Path(path)
    source = str(path)
    if model not in MODELS:
        raise ResultError(f"{source}: model must be one of {', '.join(MODELS)}, got {model!r}")
    length, force_unit, pressure_unit = units_of(units or "SI", f"{source}: ")
    try:
        mesh = meshio.read(path)
    except Exception as exc:  # noqa: BLE001  (meshio raises many kinds)
        raise ResultError(f"{source}: cannot read it with meshio: {exc}") from None
    points = np.asarray(mesh.points, dtype=float)
    if points.ndim != 2 or points.shape[0] == 0:
        raise ResultError(f"{source}: no points")
    if points.shape[1] > 2 and np.abs(points[:, 2]).max() > 1e-9 * np.abs(points).max():
        raise ResultError(f"{source}: a 2-D model lies in z = 0; its points reach z = "
                          f"{np.abs(points[:, 2]).max():g}")
    blocks = [(b.type, np.asarray(b.data)) for b in mesh.cells if b.type in _EDGES]
    if not blocks:
        have = sorted({b.type for b in mesh.cells})
        raise ResultError(f"{source}: no 2-D cells (triangle, quad, triangle6, quad8, quad9); "
                          f"it has {', '.join(have) or 'none'}")
    p, name = _field(mesh, dict(fields or {}), source)
    if p.shape != (points.shape[0],):
        raise ResultError(f"{source}: field {name!r} has {p.size} values for "
                          f"{points.shape[0]} points")
    bad = np.flatnonzero(~np.isfinite(p))
    if bad.size:
        raise ResultError(f"{source}: field {name!r} is not finite at point {bad[0]}: "
                          f"{float(p[bad[0]])!r}")
    xy = points[:, :2] * length
    p = p * pressure_unit
    if not (p > 0).any():
        raise ResultError(f"{source}: field {name!r} is 0 everywhere: no contact")
    # boundary edges and connected parts
    edges, links = [], []
    for kind, cells in blocks:
        for e in _EDGES[kind]:
            edges.append(cells[:, list(e)])
        links.append(np.column_stack([cells[:, 0].repeat(cells.shape[1]), cells.ravel()]))
    corner = np.concatenate([np.sort(e[:, :2], axis=1) for e in edges])
    key, counts = np.unique(corner, axis=0, return_counts=True)
    boundary_pairs = key[counts == 1]
    boundary = np.zeros(len(xy), bool)
    boundary[boundary_pairs.ravel()] = True
    outer = {tuple(pair) for pair in boundary_pairs.tolist()}
    for e in edges:  # mid-side nodes of boundary edges
        if e.shape[1] == 3:
            pair = np.sort(e[:, :2], axis=1).tolist()
            on = np.array([tuple(q) in outer for q in pair], dtype=bool)
            boundary[e[on, 2]] = True
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    link = np.concatenate(links)
    graph = coo_matrix((np.ones(len(link)), (link[:, 0], link[:, 1])),
                       shape=(len(xy), len(xy)))
    _, label = connected_components(graph, directed=False)
    pressed = p > 0
    sums = np.bincount(label[pressed], weights=p[pressed])
    body = int(np.argmax(sums))
    mine = label == body
    on = pressed & mine
    half = bool(xy[:, 0].min() >= -1e-9 * np.abs(xy).max())
    x0 = 0.0 if (model == "axisymmetric" or half) else float(np.sum(p[on] * xy[on, 0])
                                                             / p[on].sum())
    extent = float(np.abs(xy[on, 0] - x0).max()) or float(np.abs(xy).max())
    near = int(np.argmin(np.where(mine & boundary, np.abs(xy[:, 0] - x0), np.inf)))
    y0 = float(xy[near, 1])
    line = mine & boundary & (np.abs(xy[:, 0] - x0) <= 1.5 * extent) & (
        np.abs(xy[:, 1] - y0) <= 0.2 * extent)
    line |= on
    details = {"reader": "meshio_plane", "units": units or "SI", "pressure field": name,
               "cells": sorted({k for k, _ in blocks}),
               "contact line": f"{int(line.sum())} boundary nodes of the pressed body"}
    result = PlaneResult(model, xy[line, 0] - x0, p[line], 1.0, source=source,
                         half_model=half and model == "plane-strain", details=details)
    if force is None:
        value = result.pressure_integral()
        details["force_from"] = "the integral of the pressure (no force given)"
    else:
        if not (isinstance(force, int | float) and math.isfinite(force) and force > 0):
            raise ResultError(f"{source}: the force must be a finite number > 0, got "
                              f"{force!r}")
        value = force * (force_unit / length if model == "plane-strain" else force_unit)
    from dataclasses import replace

    return replace(result, force=float(value), details=details)
