"""A CalculiX 2-D result (.frd of CPE*, CPS*, CAX* elements, with its .inp) ->
:class:`~fem_validation.results.plane.PlaneResult`.

CalculiX expands 2-D elements into one layer of 3-D ones to solve and, by default, writes
the .frd on the 2-D mesh (tr3, tr6, qu4, qu8; z = 0).  What is read:

* **the model**: the ``*ELEMENT, TYPE=`` of the deck beside the .frd (same name): CPE*
  plane strain, CAX* axisymmetric, CPS* plane stress (graded as plane strain with
  nu = 0: the in-plane Hertz solution of thin discs, 1/E* = 1/E1 + 1/E2); given
  (``model``) it must agree.  Without the deck it must be given;
* **the contact line**: the nodes of the slave surface of the deck's ``*CONTACT PAIR``
  (element faces S1..S4 of the 2-D elements), else the nodes with any contact output;
  pressure ``CPRESS`` of the last ``CONTACT`` set there.  The load must act along y (the
  contact line along x; CalculiX's axisymmetric models have their axis along y anyway);
* **the bodies**: :func:`fem_validation.readers.calculix.bodies` (materials, element sets,
  else the mesh's two connected parts).  Where their order is not known, the body of the
  slave surface is the one whose radius (fitted to its undeformed contact line) is
  closer to the scene's (``radii``: body 1's, body 2's);
* **force**: the sum of ``F2`` (the FORC set: reactions at the constrained nodes) over body
  1's nodes away from the contact (CalculiX's FORC also holds the contact forces at the
  slave nodes: the contact line's nodes and those within twice its pressed width are left
  out); body 2's is the independent ``reaction``.  Plane strain: divided by the
  section's thickness (``*SOLID SECTION`` data line, default 1) and doubled for a half
  model (every node at x >= 0): the force per unit length of the whole contact.
  Axisymmetric: **CalculiX 2.20's .frd holds the reactions of the full circle** (verified:
  a CAX4 cylinder of radius 1 under a uniform axial stress of 1 gives F2 summing to pi,
  tests/data/calculix_plane/cax_rod; the ``*NODE PRINT ... TOTALS`` of the .dat give the
  expanded 2-degree sector, pi / 180);
* **stresses**: the nodal ``STRESS`` set (with SZZ, the out-of-plane or hoop stress) at the
  nodes on the axis below the first point of contact (x = its x), per body; where no node
  column lies on the axis (an unstructured whole model), interpolated onto it (linear, on
  the Delaunay triangles of the nodes near it);
* **units**: ``units`` (default mm, N, MPa, as the 3-D reader).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from ..results.contact import ResultError
from ..results.plane import MODELS, AxisStress, PlaneResult
from .calculix import MAX_INP_LINE, UNIT_FACTORS, bodies, slave_surface
from .frd import read_frd

__all__ = ["element_model", "read_calculix_plane"]

#: .frd element types of 2-D elements: tr3, tr6, qu4, qu8.
PLANE_TYPES = (7, 8, 9, 10)
#: Each face (edge) S1.. of the 2-D elements: its nodes (corners, then the mid-side).
_EDGES = {7: ((0, 1), (1, 2), (2, 0)), 8: ((0, 1, 3), (1, 2, 4), (2, 0, 5)),
          9: ((0, 1), (1, 2), (2, 3), (3, 0)), 10: ((0, 1, 4), (1, 2, 5), (2, 3, 6), (3, 0, 7))}
#: The deck's element type prefixes and their model.
_PREFIXES = (("CPE", "plane-strain"), ("CPS", "plane-stress"), ("CAX", "axisymmetric"))


def element_model(inp_path) -> tuple[str | None, float]:
    """(model, thickness) of a deck: ``"plane-strain"``, ``"plane-stress"``,
    ``"axisymmetric"`` from its ``*ELEMENT, TYPE=`` lines (None: no 2-D element), and the
    first ``*SOLID SECTION``'s thickness (1 where not given).

    Raises
    ------
    ResultError
        The deck mixes 2-D kinds or 2-D and 3-D elements (naming the types), or a section
        thickness that is not a positive number (naming the line).
    """
    kinds, others, thickness = set(), set(), None
    section = False
    with open(inp_path, "rb") as f:
        for number, raw in enumerate(iter(lambda: f.readline(MAX_INP_LINE + 1), b""), 1):
            if len(raw) > MAX_INP_LINE and not raw.endswith(b"\n"):
                raise ResultError(f"{inp_path}: line {number}: longer than {MAX_INP_LINE} "
                                  f"characters: not a CalculiX deck")
            line = raw.decode("utf-8", errors="replace").strip()
            if not line or line.startswith("**"):
                continue
            upper = line.upper()
            if upper.startswith("*"):
                section = upper.startswith("*SOLID SECTION") and thickness is None
                if upper.startswith("*ELEMENT"):
                    m = re.search(r",\s*TYPE\s*=\s*([A-Z0-9]+)", upper)
                    if m:
                        kind = next((k for p, k in _PREFIXES if m.group(1).startswith(p)), None)
                        (kinds.add(kind) if kind else others.add(m.group(1)))
                continue
            if section:
                section = False
                first = line.split(",")[0].strip()
                try:
                    thickness = float(first) if first else 1.0
                except ValueError:
                    raise ResultError(f"{inp_path}: line {number}: the section's thickness "
                                      f"must be a number, got {first[:40]!r}") from None
                if not (math.isfinite(thickness) and thickness > 0):
                    raise ResultError(f"{inp_path}: line {number}: the section's thickness "
                                      f"must be > 0, got {first[:40]!r}")
    if len(kinds) > 1 or (kinds and others):
        raise ResultError(f"{inp_path}: mixes element kinds "
                          f"({', '.join(sorted(kinds | others))}): a 2-D grade takes one of "
                          f"plane strain (CPE), plane stress (CPS) or axisymmetric (CAX)")
    return (next(iter(kinds)) if kinds else None), (thickness or 1.0)


def _slave_nodes(frd, inp, contact, source: str) -> tuple[np.ndarray, str]:
    """Node numbers of the contact line and how they were found."""
    if inp is not None:
        name, faces, nodes = slave_surface(inp)
        if faces:
            index = {int(e): k for k, e in enumerate(frd.elements)}
            out = []
            for element, face in faces:
                k = index.get(element)
                if k is None:
                    raise ResultError(f"{inp}: surface {name}: element {element} is not in "
                                      f"the .frd {source}")
                edges = _EDGES.get(int(frd.element_types[k]))
                if edges is None or face > len(edges):
                    raise ResultError(f"{inp}: surface {name}: face S{face} of element "
                                      f"{element}, not a face of a 2-D element")
                out.extend(int(frd.connectivity[k, j]) for j in edges[face - 1])
            return np.unique(out), f"slave surface {name} of *CONTACT PAIR"
        return np.unique(nodes), f"slave surface {name} (nodes)"
    some = np.any(contact.values != 0, axis=1)
    if not some.any():
        raise ResultError(f"{source}: no node carries contact output (every CONTACT value is "
                          f"0): is the contact closed?")
    return np.unique(contact.nodes[some]), "the nodes with contact output (no deck)"


def _finite(values, nodes, block: str, component: str, source: str) -> None:
    """Refuse a NaN or infinity in a result the grade uses, naming the first node."""
    bad = ~np.isfinite(np.asarray(values, dtype=float))
    if bad.any():
        raise ResultError(f"{source}: {block} {component} is not a finite number at node "
                          f"{int(np.asarray(nodes)[bad][0])} ({int(bad.sum())} node(s))")


def _axis_interpolated(xy, vm, x0: float, y0: float, width: float):
    """The von Mises stress along the axis x = x0 of one body, linearly interpolated
    (Delaunay of its nodes within 0.3 contact half-widths of the axis and 4 deep) at steps
    of the mesh's spacing there; None where too few nodes."""
    band = (np.abs(xy[:, 0] - x0) <= 0.3 * width) & (np.abs(xy[:, 1] - y0) <= 4 * width)
    if band.sum() < 8 or np.ptp(xy[band, 0]) <= 0:
        return None
    from scipy.interpolate import LinearNDInterpolator

    pts = xy[band]
    depth = np.abs(pts[:, 1] - y0)
    spacing = math.sqrt(np.ptp(pts[:, 0]) * max(float(depth.max()), 1e-300) / band.sum())
    z = np.arange(0.0, float(depth.max()), spacing)
    sign = 1.0 if float(np.mean(pts[:, 1] - y0)) > 0 else -1.0
    values = LinearNDInterpolator(pts, vm[band])(np.full_like(z, x0), y0 + sign * z)
    ok = np.isfinite(values)
    return AxisStress(z[ok], values[ok]) if ok.sum() >= 5 else None


def read_calculix_plane(path, *, model: str | None = None, inp=None, units: str | None = None,
                        radii: tuple[float, float] | None = None, force: float | None = None,
                        body1: str | None = None) -> PlaneResult:
    """A :class:`PlaneResult` of a CalculiX 2-D run (see the module's notes).

    Parameters
    ----------
    path : path
        The .frd.
    model : {"plane-strain", "axisymmetric"}, optional
        Default: from the deck's element types.
    inp : path, optional
        The deck (default: the .inp beside the .frd, where there is one).
    units : {"mm", "SI", "m"}, optional
        Of the deck (default mm: mm, N, MPa).
    radii : (float, float), optional
        The scene's radii in the model's plane [m] (body 1, body 2; inf flat, negative
        concave): which body is which where the files do not say.
    force : float, optional
        The whole contact's force in the deck's units, instead of the reactions: per unit
        length (N/mm in mm units) in plane strain, the full circle in an axisymmetric model.
    body1 : str, optional
        Body 1's element set or material (:func:`fem_validation.readers.calculix.bodies`).

    Raises
    ------
    ResultError
        Naming the file: not a 2-D model, no contact pressure, a model that disagrees with
        the elements, the load not along y, no reactions.
    """
    path = Path(path)
    source = str(path)
    if model is not None and model not in MODELS:
        raise ResultError(f"{source}: model must be one of {', '.join(MODELS)}, got {model!r}")
    if inp is None and path.with_suffix(".inp").is_file():
        inp = path.with_suffix(".inp")
    to_m, to_pa = UNIT_FACTORS.get(units or "mm", (None, None))
    if to_m is None:
        raise ResultError(f"{source}: units must be one of {', '.join(UNIT_FACTORS)}, got "
                          f"{units!r}")
    try:
        frd = read_frd(path)
    except ValueError as exc:
        raise ResultError(str(exc)) from None
    types = set(np.unique(frd.element_types).tolist())
    if not types or not types <= set(PLANE_TYPES):
        raise ResultError(f"{source}: not a 2-D model: element types {sorted(types)} of the "
                          f".frd (2-D: 7 tr3, 8 tr6, 9 qu4, 10 qu8); grade a 3-D model "
                          f"without --model")
    if np.abs(frd.coordinates[:, 2]).max() > 1e-9 * np.abs(frd.coordinates).max():
        raise ResultError(f"{source}: a 2-D model lies in z = 0; this one has z up to "
                          f"{np.abs(frd.coordinates[:, 2]).max():g} (written with "
                          f"OUTPUT=3D? write the .frd in 2-D)")
    kind, thickness = element_model(inp) if inp is not None else (None, 1.0)
    plane_stress = kind == "plane-stress"
    found = "plane-strain" if plane_stress else kind
    if model is None:
        if found is None:
            raise ResultError(f"{source}: the model is not known (no deck beside the .frd "
                              f"names CPE/CPS/CAX elements): give --model plane-strain or "
                              f"axisymmetric")
        model = found
    elif found is not None and found != model:
        raise ResultError(f"{source}: --model {model}, but the deck {inp} has "
                          f"{'CPS (plane stress)' if plane_stress else kind} elements")
    try:
        contact = frd.result("CONTACT")
        pressure_all = contact.component("CPRESS")
    except KeyError as exc:
        raise ResultError(f"{source}: no contact pressure: {exc.args[0]} (request it with "
                          f"*CONTACT FILE, CSTR)") from None
    _finite(pressure_all, contact.nodes, "CONTACT", "CPRESS", source)
    slaves, how = _slave_nodes(frd, inp, contact, source)
    p_of = dict(zip(contact.nodes.tolist(), pressure_all.tolist(), strict=True))
    pos = frd.node_index(slaves)
    xy = frd.coordinates[pos, :2] * to_m
    p = np.array([p_of.get(int(n), 0.0) for n in slaves]) * to_pa
    if not (p > 0).any():
        raise ResultError(f"{source}: no pressure on the contact line ({how}): every CPRESS "
                          f"is 0")
    scale = float(np.abs(frd.coordinates[:, :2]).max()) * to_m
    tol = 1e-9 * scale
    half = bool(frd.coordinates[:, 0].min() * to_m >= -tol)
    if model == "axisymmetric":
        x0 = 0.0
    elif half:
        x0 = 0.0
    else:
        x0 = float(np.sum(p * xy[:, 0]) / p.sum())
        # a whole model: the axis through the node column nearest the pressure's centroid
        # (where the stresses on the axis are), if one is within 2% of the contact's width
        near_x = float(xy[np.argmin(np.abs(xy[:, 0] - x0)), 0])
        if abs(near_x - x0) <= 0.01 * float(np.ptp(xy[p > 0, 0])):
            x0 = near_x
    on = p > 0
    spread = np.ptp(xy[on], axis=0) if on.sum() > 1 else np.zeros(2)
    if spread[1] > spread[0]:
        raise ResultError(f"{source}: the pressed nodes spread more along y than along x: the "
                          f"load must act along y (the contact line along x)")
    near = int(np.argmin(np.abs(xy[:, 0] - x0)))
    y0 = float(xy[near, 1])
    # the bodies and their order
    masks, told, ordered = bodies(frd, inp, body1, source)
    node_body = {}
    for b, mask in enumerate(masks, 1):
        for n in np.unique(frd.connectivity[mask]):
            if n >= 0:
                node_body[int(n)] = b
    slave_body = {node_body.get(int(n)) for n in slaves} - {None}
    if len(slave_body) != 1:
        raise ResultError(f"{source}: the contact line's nodes ({how}) lie on "
                          f"{len(slave_body)} bodies; expected one")
    slave_body = slave_body.pop()
    centre = {b: float(frd.coordinates[np.isin(frd.nodes, [n for n, k in node_body.items()
                                                             if k == b]), 1].mean()) * to_m
              for b in (1, 2)}
    side = 1.0 if centre[slave_body] > y0 else -1.0
    if not ordered and radii is not None:
        r = np.abs(xy[:, 0] - x0)
        sel = r > 0
        curvature = (2 * side * np.sum((xy[sel, 1] - y0) * r[sel] ** 2) / np.sum(r[sel] ** 4)
                     if sel.any() else 0.0)
        k1, k2 = (1 / radii[0], 1 / radii[1])
        # the slave's body is body 1 where its contact line's curvature is closer to body
        # 1's (the connected parts come in the mesh's order, which says nothing)
        want = 1 if abs(curvature - k1) <= abs(curvature - k2) else 2
        if want != slave_body:
            slave_body = want
            masks = masks[::-1]
            node_body = {n: 3 - b for n, b in node_body.items()}
            centre = {1: centre[2], 2: centre[1]}
        told += "; body 1 the one whose contact line's radius is closer to the scene's"
    # the force: the reactions (F2) of each body's constrained nodes
    try:
        forc = frd.result("FORC")
        f2 = forc.component("F2")
    except KeyError as exc:
        raise ResultError(f"{source}: no reaction forces: {exc.args[0]} (request them with "
                          f"*NODE FILE, RF)") from None
    # CalculiX's FORC holds the contact forces at the slave nodes too: the nodes of the
    # contact line and those within twice its pressed width of it are left out
    _finite(f2, forc.nodes, "FORC", "F2", source)
    sums = {1: 0.0, 2: 0.0}
    reach = 2.0 * max(float(np.ptp(xy[p > 0, 0])), tol)
    fxy = frd.coordinates[frd.node_index(forc.nodes), :2] * to_m
    away = np.hypot(fxy[:, 0] - x0, fxy[:, 1] - y0) > reach
    away &= ~np.isin(forc.nodes, slaves)
    for n, f, keep in zip(forc.nodes.tolist(), f2.tolist(), away.tolist(), strict=True):
        b = node_body.get(int(n))
        if b is not None and keep:
            sums[b] += f
    factor = 1.0
    if model == "plane-strain":
        factor = (2.0 if half else 1.0) / (thickness * to_m)
    reaction = abs(sums[2]) * factor
    if force is not None:
        if isinstance(force, bool) or not (isinstance(force, int | float)
                                           and math.isfinite(force) and force > 0):
            raise ResultError(f"{source}: the force must be a finite number > 0, got "
                              f"{force!r}")
        force = float(force) * (1.0 / to_m if model == "plane-strain" else 1.0)
    else:
        force = abs(sums[1]) * factor
    if not force > 0:
        raise ResultError(f"{source}: body 1 has no reaction along y (FORC F2 sums to 0): "
                          f"the force of a displacement-controlled run is its support's "
                          f"reaction")
    # the stresses on the axis
    axis, details_axis = {}, None
    try:
        stress = frd.result("STRESS")
    except KeyError:
        stress = None
    if stress is not None:
        from ..fe.elasticity import von_mises

        xs = frd.coordinates[frd.node_index(stress.nodes), :2] * to_m
        comps = [stress.component(c) for c in ("SXX", "SYY", "SZZ", "SXY", "SYZ", "SZX")]
        for name, c in zip(("SXX", "SYY", "SZZ", "SXY", "SYZ", "SZX"), comps, strict=True):
            _finite(c, stress.nodes, "STRESS", name, source)
        sxx, syy, szz, sxy, syz, szx = (np.asarray(c) * to_pa for c in comps)
        tensor = np.stack([np.stack([sxx, sxy, szx], -1), np.stack([sxy, syy, syz], -1),
                           np.stack([szx, syz, szz], -1)], -2)
        vm = von_mises(tensor)
        offset = np.abs(xs[:, 0] - x0)
        width = float(np.abs(xy[p > 0, 0] - x0).max())
        for b in (1, 2):
            mine = np.array([node_body.get(int(n)) == b for n in stress.nodes])
            sign = 1.0 if centre[b] > y0 else -1.0
            below = mine & (sign * (xs[:, 1] - y0) >= 0)
            sel = below & (offset <= max(tol, 1e-6 * scale))
            if sel.sum() >= 5:
                axis[b] = AxisStress(np.abs(xs[sel, 1] - y0), vm[sel])
            else:  # an unstructured mesh: no node column on the axis
                line = _axis_interpolated(xs[below], vm[below], x0, y0, width)
                if line is not None:
                    axis[b] = line
                    details_axis = "von Mises on the axis interpolated (no node column there)"
    x = (xy[:, 0] - x0)
    if details_axis:
        details_extra = {"axis stresses": details_axis}
    else:
        details_extra = {}
    details = {**details_extra, "reader": "calculix_plane", "units": units or "mm", "model": model,
               "contact line": how, "bodies": told, "elements": sorted(types),
               "thickness": thickness, "half model": half if model == "plane-strain" else None,
               "force convention": ("per unit length: F2 sum / thickness"
                                    + (" x 2 (half model)" if half else "")
                                    if model == "plane-strain" else
                                    "full circle: CalculiX's .frd F2 sum as it is"),
               "plane stress": plane_stress}
    return PlaneResult(model, x, p, force, source=source,
                       half_model=half and model == "plane-strain",
                       reaction=reaction if reaction > 0 else math.nan, axis=axis,
                       details=details)
