"""What every reader shares: units, the contact frame, the symmetry, the total force, and
``read_result``, which picks the reader by the file's extension.

Conventions (every reader follows them):

* ``units``: "SI" (m, N, Pa) or "mm" (mm, N, MPa: a deck's usual system); the
  reader converts to SI before it builds the ContactResult.
* ``force``: the total normal force of the MODEL IN THE FILE (a quarter model's
  own reaction), in the file's units [N]; the reader multiplies it by 4 for a
  quarter model and by 2 for a half model.  Where not given, the reader takes
  it from the file (a CSV's ``# force = ...`` line; a mesh's reaction field RF,
  the sum of its components along the normal on the side that pushes).
* ``symmetry``: "whole", "half", "quarter", or None to detect it: a model that
  holds only x >= 0 and y >= 0 of the contact frame, with its largest pressure
  next to the origin, is a quarter model; only x >= 0 (or y >= 0), a half model.
* ``frame``: a :class:`~fem_validation.results.contact.ContactFrame`, or None to find one
  (:func:`find_frame`), or a dict with some of ``origin``, ``normal``, ``x_axis``
  (SI) given and the rest found.

A CalculiX ``.frd`` is read by ``fem_validation.readers.frd`` where that module
offers ``read_result(path, units=..., symmetry=..., force=..., frame=...,
fields=...)`` (the same keywords as :func:`read_result`).
"""

from __future__ import annotations

import numpy as np

from ..results.contact import (
    MULTIPLICITY,
    ContactFrame,
    ContactResult,
    ResultError,
    surface_points,
    unit_vector,
)

#: Units of a file -> (metres per length unit, newtons per force unit, pascals per
#: pressure unit).
UNITS = {"SI": (1.0, 1.0, 1.0), "m": (1.0, 1.0, 1.0), "mm": (1e-3, 1.0, 1e6)}

#: Field names recognised (lower case; first found wins).
PRESSURE_NAMES = ("cpress", "contact_pressure", "contact pressure", "contactpressure",
                  "contact_pressure_fem", "pressure", "p", "pn", "normal_pressure")
NORMAL_FORCE_NAMES = ("normal_force", "cnormf", "contact_force", "cforce", "fn", "f")
REACTION_NAMES = ("rf", "reaction", "reaction_force", "reactions")
STRESS_NAMES = ("s", "stress", "sigma", "stress_fem", "cauchy_stress")


def units_of(units: str, where: str = "") -> tuple[float, float, float]:
    """(length, force, pressure) factors to SI of ``units``; ValueError naming it."""
    if units not in UNITS:
        raise ResultError(f"{where}units must be one of {', '.join(UNITS)}, got {units!r}")
    return UNITS[units]


def find_frame(points: np.ndarray, weight: np.ndarray, symmetric: bool,
               normal=None, x_axis=None, origin=None, source: str = "") -> ContactFrame:
    """A contact frame for surface points (n, 3) [m] weighted by pressure or force.

    normal: given, else the direction in which the pressed nodes (weight > 0)
    spread least (the smallest principal axis of their positions), turned to
    point along +z (or +y, +x where it has no z): decks put body 1 above.  x_axis:
    given, else the model's x axis projected on the contact plane (y where x is
    along the normal).  origin: given, else in the plane the symmetry planes'
    intersection (the model's origin projected) for a symmetric model, the
    weight's centroid for a whole one; along the normal, the pressed node
    nearest that point.
    """
    pts = np.asarray(points, dtype=float)
    w = np.clip(np.asarray(weight, dtype=float), 0.0, None)
    pressed = pts[w > 0]
    if normal is None:
        if len(pressed) < 3:
            raise ResultError(f"{source + ': ' if source else ''}cannot find the contact "
                              f"normal from {len(pressed)} pressed node(s): give the frame")
        centred = pressed - pressed.mean(axis=0)
        _, _, vt = np.linalg.svd(centred, full_matrices=False)
        n = vt[-1]
        axis = np.round(n)
        if np.abs(axis).sum() == 1 and np.abs(n - axis).max() < 1e-9:
            n = axis  # a plane of coordinates: keep the axis exact
        k = 2 if abs(n[2]) > 1e-6 else 1 if abs(n[1]) > 1e-6 else 0
        normal = n if n[k] > 0 else -n
        normal = normal / np.linalg.norm(normal)
    else:
        normal = unit_vector(normal, "frame.normal", source)  # as given: huge, tiny or 0
    if x_axis is not None:
        x_axis = unit_vector(x_axis, "frame.x_axis", source)
    if x_axis is None:
        for axis in np.eye(3):
            v = axis - (axis @ normal) * normal
            if np.linalg.norm(v) > 0.5:
                x_axis = v / np.linalg.norm(v)
                if abs(axis @ normal) < 1e-12:
                    x_axis = axis
                break
    if origin is None:
        if symmetric:
            centre = np.zeros(3)
        else:
            centre = (w[:, None] * pts).sum(axis=0) / w.sum()
        near = pressed[np.argmin(np.linalg.norm(
            (pressed - centre) - np.outer((pressed - centre) @ normal, normal), axis=1))]
        origin = centre + ((near - centre) @ normal) * normal
    return ContactFrame(origin=origin, normal=normal, x_axis=x_axis, source=source)


def detect_symmetry(xy: np.ndarray, weight: np.ndarray) -> str:
    """"quarter", "half" or "whole" from in-plane coordinates (n, 2) about the model's origin.

    Symmetric where every node lies on one side of a coordinate plane through the
    origin (to 1e-6 of the extent) and the largest weight sits within 10% of the
    extent of that plane: a whole model that merely lies off the origin has no
    pressure there.
    """
    scale = np.abs(xy).max()
    top = xy[int(np.argmax(weight))]
    tol = 1e-6 * scale
    pos = [bool(xy[:, k].min() >= -tol) and abs(top[k]) <= 0.1 * scale for k in (0, 1)]
    return "quarter" if all(pos) else "half" if any(pos) else "whole"


def force_from_reaction(rf: np.ndarray, normal: np.ndarray, where: str = "") -> float:
    """The normal force of a model from its nodal reactions (k, 3): the sum of their
    components along the normal on the side that pushes and on the side that holds,
    which must agree (within 5%) and are averaged."""
    fn = np.asarray(rf, dtype=float) @ normal
    push, hold = fn[fn > 0].sum(), -fn[fn < 0].sum()
    if not (push > 0 and hold > 0) or abs(push - hold) > 0.05 * max(push, hold):
        raise ResultError(f"{where}the reaction field does not give one normal force: "
                          f"{push:.6g} along the normal, {hold:.6g} against it; give --force")
    return 0.5 * (push + hold)


def resolve_frame(frame, points, weight, symmetric: bool, source: str = "") -> ContactFrame:
    """``frame`` as a ContactFrame: itself, found (None) or completed (a dict of parts)."""
    if isinstance(frame, ContactFrame):
        return frame
    return find_frame(points, weight, symmetric, source=source, **(frame or {}))


def finish(points, pressure, normal_force, force, symmetry, frame, triangles=None,
           stress=(), source="", details=None, weight=None) -> ContactResult:
    """Detect what is not given and build the ContactResult (SI inputs; ``force`` of the
    model in the file)."""
    pts = surface_points(points, source)  # finite, an area, a scale Hertz and qhull handle
    if weight is None:
        weight = pressure if pressure is not None else normal_force
    if weight is None:
        raise ResultError(f"{source}: no contact pressure and no nodal contact force in the "
                          f"file: name the field (--pressure-field)")
    weight = np.asarray(weight, dtype=float)
    if not np.isfinite(weight).all():
        bad = int(np.argmax(~np.isfinite(weight)))
        field = "pressure" if pressure is not None else "normal_force"
        raise ResultError(f"{source}: field {field!r} has {int((~np.isfinite(weight)).sum())} "
                          f"non-finite value(s), first at node index {bad}")
    if not (weight > 0).any():
        raise ResultError(f"{source}: the contact is empty: no node carries a positive "
                          f"contact pressure or force")
    if symmetry is not None and symmetry not in MULTIPLICITY:
        raise ResultError(f"{source}: symmetry must be one of {', '.join(MULTIPLICITY)}, "
                          f"got {symmetry!r}")
    probe = resolve_frame(frame, pts, weight, True, source)
    detected = detect_symmetry(probe.to_frame(pts)[:, :2], weight)
    if symmetry is None:
        symmetry = detected
    elif MULTIPLICITY[detected] > MULTIPLICITY[symmetry]:
        # Pressed on one side of a plane through its peak: no whole contact looks so.
        raise ResultError(f"{source}: symmetry {symmetry!r} was given, but the file holds a "
                          f"{detected} model (every node on one side of the symmetry "
                          f"plane(s), the largest pressure on it): give --symmetry {detected}")
    frame = resolve_frame(frame, pts, weight, symmetry != "whole", source)
    if force is None:
        raise ResultError(f"{source}: no total force: the file has no reaction field (RF) "
                          f"and no force line; give --force N (the model's own reaction)")
    return ContactResult(points=pts, force=float(force) * MULTIPLICITY[symmetry],
                         pressure=pressure, normal_force=normal_force, symmetry=symmetry,
                         frame=frame, triangles=triangles, stress=tuple(stress), source=source,
                         details=dict(details or {}))




def __getattr__(name: str):
    """``read_result``, which moved to :mod:`fem_validation.readers` (the one dispatch):
    kept here one release, with a DeprecationWarning."""
    if name == "read_result":
        import warnings

        from . import read_result

        warnings.warn("fem_validation.readers.read_result is deprecated: use "
                      "fem_validation.readers.read_result", DeprecationWarning, stacklevel=2)
        return read_result
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
