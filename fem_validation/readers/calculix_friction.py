"""A frictional CalculiX run (.frd + .inp) -> a TangentialResult for the tangential grader.

The run is a deck of :mod:`fem_validation.decks` written with ``--friction``
(or any deck of that shape): a normal step, then steps that move the node set
MOVED (body 1's far face) along x with the result written at every increment
(``*NODE FILE`` U, RF; ``*CONTACT FILE`` CDIS, CSTR).  What is read, and from
where:

* **the path**: one point per increment of the .frd, from the last increment
  of the normal step (tangential displacement 0) on.  ``displacement`` is the
  mean D1 of MOVED plus the Cerruti settlement Q (3 - 2 nu)/(8 pi G H) of each
  clamped block of depth H at the increment's force (the far faces of finite
  blocks do not show it; :func:`fem_validation.halfspace.cerruti_settlement`),
  depths and materials from problem.json; ``force`` is the summed reaction F1
  of MOVED times the symmetry's multiplicity: the force the support exerts on
  body 1 along x, which body 1 passes on to body 2 through the contact (its
  only other load), so it is the tangential force Q that body 1 exerts on
  body 2;
* **the normal force** P: the summed reaction -F3 of MOVED at the path's
  first point (the end of the normal step) times the multiplicity; its largest
  change along the path is in ``details``;
* **the surface and its tractions** at the snapshot (default the first
  reversal): the slave nodes of the deck's ``*CONTACT PAIR`` (as
  :func:`fem_validation.readers.calculix.read_calculix`), ``CPRESS`` and the
  shear (``CSHEAR1``, ``CSHEAR2``).  Measured on a run of ccx 2.20 (two
  steel spheres, slave on body 1, pushed along +x, contact plane z = 0): the
  two components are the global x and y, and the integral of CSHEAR1 over the
  slave surface is +Q (+3% at level 0, the pressure's integral +2% against
  P): the traction body 1 exerts on body 2, taken as it is
  (:data:`SLAVE_SIGN`; for a slave on body 2 the opposite sign is assumed by
  exchanging the roles, not measured);
* **mu** from the deck's ``*FRICTION`` line; the **frame** and **units** from
  problem.json (else the standard frame and mm).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..results.contact import ContactFrame, ResultError
from ..results.tangential import TangentialResult, path_reversals
from .calculix import (
    UNIT_FACTORS,
    _keyword_blocks,
    _param,
    _surface,
    _symmetry,
    components,
    contact_frame,
    deck_id,
    deck_units,
    problem_beside,
    slave_surface,
)
from .frd import read_frd

#: The traction body 1 exerts on body 2 is SLAVE_SIGN[slave body] times CalculiX's
#: (CSHEAR1, CSHEAR2): measured +1 with the slave on body 1 (its integral is +Q); -1 for
#: a slave on body 2 by exchanging the roles (not measured).
SLAVE_SIGN = {1: 1.0, 2: -1.0}


def node_set(inp_path, name: str) -> np.ndarray:
    """The node numbers of ``*NSET, NSET=name`` (plain lists of numbers) in a deck."""
    numbers, found = [], False
    for key, data in _keyword_blocks(inp_path, ("*NSET",)):
        if key.startswith("*NSET") and (_param(key, "NSET") or "").upper() == name.upper():
            found = True
            for line in data:
                where = f"{inp_path}: line {line.number}: *NSET, NSET={name}"
                for part in (p.strip() for p in line.split(",")):
                    if part and not part.lstrip("+-").isdecimal():
                        raise ResultError(f"{where}: expected node numbers, got {line!r}")
                    if part:
                        numbers.append(deck_id(part, where, "node"))
    if not found:
        raise ResultError(f"{inp_path}: no node set {name} (*NSET, NSET={name})")
    return np.unique(np.asarray(numbers, dtype=np.int64))


def friction_coefficient(inp_path) -> float:
    """mu of the deck's first ``*FRICTION`` (its data line: mu, stick slope)."""
    for key, data in _keyword_blocks(inp_path, ("*FRICTION",)):
        if key.startswith("*FRICTION") and data:
            try:
                mu = float(data[0].split(",")[0])
            except ValueError:
                mu = None
            if mu is None or not 0 <= mu < np.inf:
                raise ResultError(f"{inp_path}: *FRICTION: expected mu (a finite number >= 0) "
                                  f"first on its data line, got {data[0]!r}")
            return mu
    raise ResultError(f"{inp_path}: no *FRICTION with a data line (mu, stick slope): not a "
                      f"frictional deck; give mu")


def _groups(frd, source):
    """The .frd's result sets grouped by increment, in file order: [{name: FrdResult}]."""
    groups, keys = [], []
    for r in frd.results:
        key = (r.step, r.time)
        if not keys or keys[-1] != key:
            keys.append(key)
            groups.append({})
        groups[-1][r.name] = r
    need = ("DISP", "FORC", "CONTACT")
    full = [g for g in groups if all(n in g for n in need)]
    if len(full) < 3:
        raise ResultError(f"{source}: {len(full)} increments with DISP, FORC and CONTACT "
                          f"output; a frictional path needs the normal step's end and two or "
                          f"more tangential increments (*NODE FILE U, RF and *CONTACT FILE "
                          f"CDIS, CSTR at every increment)")
    return full


def read_calculix_tangential(path, inp=None, problem=None, units: str | None = None,
                             mu: float | None = None, symmetry: str | None = None,
                             snapshot: int | None = None, moved: str = "MOVED",
                             frame: ContactFrame | dict | None = None) -> TangentialResult:
    """Read a frictional CalculiX run into a :class:`TangentialResult` in SI.

    Parameters
    ----------
    path : path-like
        The .frd file (ASCII or binary).
    inp : path-like, optional
        The deck (default: the .inp beside the .frd with the same name).
    problem : path-like, optional
        problem.json of :mod:`fem_validation.decks` (default: beside the .frd):
        units, frame, materials and the blocks' depths for the Cerruti
        correction.  Without it the displacement is the imposed one, uncorrected
        (said in ``details``).
    units : {"mm", "SI"}, optional
        Default problem.json's, else mm.
    mu : float, optional
        Default: the deck's ``*FRICTION``.
    symmetry : {"whole", "half", "quarter"}, optional
        Default: from the coordinates (y >= 0 only: half).
    snapshot : int, optional
        Path index of the tractions (default: the first reversal).
    moved : str
        The node set moved along x (body 1's far face).
    frame : ContactFrame or dict, optional
        Or a dict of some of ``origin`` [m], ``normal``, ``x_axis``: the rest
        problem.json's, else found (:func:`fem_validation.readers.calculix.contact_frame`).
        Default problem.json's, else the standard frame.

    Returns
    -------
    TangentialResult

    Raises
    ------
    ResultError
        Naming the file and what is missing or contradictory.
    """
    from ..halfspace import cerruti_settlement

    path = Path(path)
    source = str(path)
    try:
        frd = read_frd(path)
    except OSError as exc:
        raise ResultError(f"{source}: cannot read: {exc.strerror}") from None
    except ValueError as exc:
        raise ResultError(str(exc)) from None
    inp_path = Path(inp) if inp is not None else path.with_suffix(".inp")
    if not inp_path.is_file():
        raise ResultError(f"{source}: the deck {inp_path} is needed (the slave surface, the "
                          f"node set {moved}, mu)")
    info = problem_beside(path, problem)
    units = deck_units(units, info, source)
    to_m, to_pa = UNIT_FACTORS[units]
    to_n = 1.0  # both unit systems use newtons
    mu = friction_coefficient(inp_path) if mu is None else mu

    sym = symmetry or _symmetry(frd.coordinates)
    mult = {"whole": 1, "half": 2, "quarter": 4}.get(sym)
    if mult is None:
        raise ResultError(f"{source}: symmetry must be whole, half or quarter, got {sym!r}")
    moved_nodes = node_set(inp_path, moved)
    groups = _groups(frd, source)
    d1, fx, fz = [], [], []
    for g in groups:
        disp, forc = g["DISP"], g["FORC"]
        for r in (disp, forc):
            if not np.isin(r.nodes, moved_nodes).any():
                raise ResultError(f"{source}: line {r.line}: result set {r.name} has no node "
                                  f"of the node set {moved}")
        d1.append(float(components(disp, ("D1",), source)[np.isin(disp.nodes, moved_nodes),
                                                          0].mean()))
        pick = np.isin(forc.nodes, moved_nodes)
        f13 = components(forc, ("F1", "F3"), source)[pick]
        fx.append(mult * float(f13[:, 0].sum()))
        fz.append(-mult * float(f13[:, 1].sum()))
    d1, fx, fz = np.array(d1) * to_m, np.array(fx) * to_n, np.array(fz) * to_n
    scale = np.abs(d1).max()
    if not scale > 0:
        raise ResultError(f"{source}: the node set {moved} never moves along x: not a "
                          f"frictional path")
    start = int(np.argmax(np.abs(d1) > 1e-9 * scale)) - 1
    if start < 0 or abs(d1[start]) > 1e-9 * scale:
        raise ResultError(f"{source}: the first increment already moves {moved} along x; "
                          f"the path must start from the normal step's end (D1 = 0)")
    groups, d1, fx, fz = groups[start:], d1[start:], fx[start:], fz[start:]
    sense = 1.0 if d1[1] > 0 else -1.0
    direction = 0.0 if sense > 0 else np.pi

    correction, note = 0.0, "none (no problem.json): the imposed displacement as it is"
    if info is not None and info.far_face_depths:
        depths = [d * to_m for d in info.far_face_depths]
        mats = info.need_materials("the Cerruti settlement of the far faces "
                                   "(model.far_face_depths)")
        try:
            correction = sum(cerruti_settlement(1.0, E * to_pa, nu, h)
                             for (E, nu), h in zip(mats, depths, strict=True))
        except (ArithmeticError, ValueError):  # E times depth underflows to 0
            correction = np.nan
        with np.errstate(all="ignore"):
            finite = np.isfinite(correction * np.abs(fx).max())
        if not finite:
            raise ResultError(f"problem.json {info.path!r}: keys 'model.far_face_depths' and "
                              f"'materials' give a Cerruti compliance of {correction} m/N, "
                              f"which at the path's forces is not finite: check their values")
        note = ("imposed displacement of MOVED plus Q (3 - 2 nu)/(8 pi G H) per block "
                "(Cerruti on the axis at the depth H of its far face)")
    displacement = sense * (d1 + correction * fx)
    force = sense * fx

    name, faces, nodes = slave_surface(inp_path)
    surface, tri = _surface(frd, faces, nodes, f"{inp_path}")
    reversals = path_reversals(displacement)
    snap = (reversals[0] if reversals else len(d1) - 1) if snapshot is None else snapshot
    if isinstance(snap, bool) or not isinstance(snap, int | np.integer) \
            or not 1 <= snap < len(d1):
        raise ResultError(f"{source}: snapshot must be an index 1..{len(d1) - 1} into the "
                          f"path of {len(d1)} increments, got {snapshot!r}")
    contact = groups[snap]["CONTACT"]
    lookup = {n: i for i, n in enumerate(contact.nodes.tolist())}
    missing = [n for n in surface.tolist() if n not in lookup]
    if missing:
        raise ResultError(f"{source}: slave node {missing[0]} has no contact output: the deck "
                          f"does not match the result")
    rows = [lookup[n] for n in surface.tolist()]
    tractions = components(contact, ("CPRESS", "CSHEAR1", "CSHEAR2"), source)[rows] * to_pa
    slave_body = 2 if info is not None and info.slave == "CONTACT2" else 1
    pressure, shear = tractions[:, 0], SLAVE_SIGN[slave_body] * tractions[:, 1:]
    points = frd.coordinates[frd.node_index(surface)] * to_m
    frame = contact_frame(frame, info, to_m, points, pressure, sym != "whole", source)
    details = {"solver": "CalculiX", "file": source, "units": units, "contact_surface":
               f"slave surface {name} of {inp_path.name}", "nodes": len(frd.nodes),
               "elements": len(frd.elements), "increments": len(d1),
               "version": next((h.split(None, 1)[1].strip() for h in frd.headers
                                if h.startswith("VERSION")), ""),
               "correction": note, "compliance_correction_m_per_N": correction,
               "imposed_displacement_m": (sense * d1).tolist(),
               "normal_force_path_N": fz.tolist(),
               "normal_force_change": float(np.abs(fz / fz[0] - 1).max()),
               "shear_sign": f"shear = {SLAVE_SIGN[slave_body]:+g} x (CSHEAR1, CSHEAR2), "
                             f"slave on body {slave_body}"}
    if info is not None:
        details |= {k: v for k, v in info.details.items()
                    if k in ("level", "penalty_factor", "stick_slope")}
    return TangentialResult(points=points, pressure=pressure, shear=shear,
                            normal_force=float(fz[0]), mu=mu, direction=direction,
                            displacement=displacement, force=force, snapshot=int(snap),
                            symmetry=sym, frame=frame, triangles=tri, source=source,
                            details=details)
