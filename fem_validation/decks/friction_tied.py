"""The tied counterpart of a frictional deck: the contact bonded over a disc, one linear solve.

A frictional CalculiX deck (``deck --friction MU``) costs about 100 s of ccx CPU per
increment at level 0.  Its tangential compliance has two parts that no frictional run
separates: the contact's (Coulomb's law, the stick slope, the stick zone's resolution)
and the bodies' (the elements, the finite blocks with free sides and clamped far faces).
The tied deck keeps the second and removes the first: the same half model of
paraboloid-faced blocks, the node pairs of the two contact faces (the blocks' contact
faces share their nodes' x and y) bonded by ``*EQUATION`` within a radius of the contact's
centre (Hertz's a by default: Mindlin's no-slip problem), no normal load, no
``*CONTACT PAIR``, and body 1's far face moved rigidly along x.  For elastically similar
bodies the bonded disc under a tangential load is exactly Mindlin's no-slip problem
(the tangential and normal problems uncouple), whose compliance is
(2 - nu1)/(8 G1 a) + (2 - nu2)/(8 G2 a) (:func:`hertz.tangential_compliance`); each clamped
block of depth H then misses Cerruti's Q (3 - 2 nu)/(8 pi G H)
(:func:`fem_validation.halfspace.cerruti_settlement`), as the frictional reader adds.

Examples
--------
Two steel spheres of radius 10 mm at 830.77 N (a = 0.3 mm), level 0:

>>> import hertz
>>> from fem_validation.scenes import Scene
>>> from fem_validation.decks.model import build_model
>>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
>>> half = build_model(Scene("spheres", ball, ball, 830.77), 0, "half")
>>> pairs = tied_pairs(half, half.contact.a)
>>> pairs.shape, bool((half.nodes[pairs[:, 0], :2] == half.nodes[pairs[:, 1], :2]).all())
((212, 2), True)

``write_tied_inp(half, "tied.inp", 1e-6)`` writes the deck; ``ccx -i tied`` solves it
in about 8 s of CPU, and twice the x reaction of MOVED over 1e-6 m is the stiffness.
tools/calculix_friction_split.py runs the study of docs/howto/calculix.md.
"""

from __future__ import annotations

import math

import numpy as np

from .inp import UNITS, _g, _lines, one_line
from .model import DeckModel

#: The pairs' x, y must agree to this fraction of the contact element size h0.
PAIR_TOLERANCE = 1e-6


def tied_pairs(model: DeckModel, radius: float) -> np.ndarray:
    """The node pairs (slave, master) of the contact faces within ``radius`` of the axis.

    Parameters
    ----------
    model : DeckModel
        A half or whole model of paraboloid-faced blocks (their contact faces share the
        nodes' x and y: :mod:`fem_validation.solvers.mesh`).
    radius : float
        Radius of the bonded disc [m], > 0; a node at r <= radius (1 + 1e-9) is tied.

    Returns
    -------
    ndarray of int, shape (n, 2)
        0-based node indices: a slave node and the master node at its x, y.

    Raises
    ------
    ValueError
        A model of another geometry, a radius that is not a finite number > 0, a slave
        node without a master node at its x, y, or no pair within the radius.
    """
    from scipy.spatial import cKDTree

    if model.geometry != "paraboloid-blocks":
        raise ValueError(f"a tied deck needs paraboloid-faced blocks (matching contact faces), "
                         f"got {model.geometry}")
    if isinstance(radius, bool) or not (isinstance(radius, int | float)
                                        and math.isfinite(radius) and radius > 0):
        raise ValueError(f"radius must be a finite number > 0 [m], got {radius!r}")
    slave, master = model.node_sets["SLAVE"], model.node_sets["MASTER"]
    xy_s, xy_m = model.nodes[slave, :2], model.nodes[master, :2]
    inside = np.hypot(xy_s[:, 0], xy_s[:, 1]) <= radius * (1 + 1e-9)
    if not inside.any():
        raise ValueError(f"no contact node within radius {radius!r} m (element size at the "
                         f"contact {model.h0:.3g} m)")
    dist, k = cKDTree(xy_m).query(xy_s[inside])
    bad = dist > PAIR_TOLERANCE * model.h0
    if bad.any():
        node = slave[inside][np.argmax(bad)]
        raise ValueError(f"slave node {node + 1} has no master node at its x, y (nearest "
                         f"{dist.max():.3g} m away): the contact faces do not match")
    return np.column_stack([slave[inside], master[k]])


def write_tied_inp(model: DeckModel, path, displacement: float, radius: float | None = None,
                   units: str = "mm", command: str | None = None) -> np.ndarray:
    """Write the tied deck: the contact bonded within ``radius``, MOVED moved along x.

    Parameters
    ----------
    model : DeckModel
        A half model of paraboloid-faced blocks (``build_model(scene, level, "half")``).
    path : path-like
        The .inp file.
    displacement : float
        The far face's displacement along x [m], > 0 (its other components 0).
    radius : float, optional
        Radius of the bonded disc [m]; default Hertz's a at the scene's load.
    units : {"mm", "SI"}
    command : str, optional
        Recorded in a comment.

    Returns
    -------
    ndarray of int, shape (n, 2)
        The tied pairs (:func:`tied_pairs`).

    The total tangential force is twice the x reaction of MOVED (half model), printed
    to the .dat by ``*NODE PRINT, NSET=MOVED, TOTALS=ONLY``.
    """
    if model.symmetry != "half":
        raise ValueError(f"a tied deck is written for the half model (y >= 0, loaded along "
                         f"x), got a {model.symmetry} model")
    if units not in UNITS:
        raise ValueError(f"units must be one of {sorted(UNITS)}, got {units!r}")
    if isinstance(displacement, bool) or not (isinstance(displacement, int | float)
                                              and math.isfinite(displacement)
                                              and displacement > 0):
        raise ValueError(f"displacement must be a finite number > 0 [m], got "
                         f"{displacement!r}")
    radius = model.contact.a if radius is None else radius
    pairs = tied_pairs(model, radius)
    ul, us = UNITS[units]["length"], UNITS[units]["stress"]
    lu = UNITS[units]["names"]["length"]
    s = model.scene
    out = [f"** hertz tied deck (CalculiX): {one_line(s.name)}",
           f"** half model of paraboloid-faced blocks, level {model.level}, blocks "
           f"{model.info['block_half_width'] * ul:.6g} {lu} wide (half) and "
           f"{model.info['block_depth'] * ul:.6g} {lu} deep",
           f"** contact bonded (*EQUATION) within r = {radius * ul:.6g} {lu}: "
           f"{len(pairs)} node pairs; no normal load",
           f"** MOVED moved along x by {displacement * ul:.6g} {lu}; the total force is "
           f"twice the reaction of MOVED"]
    if command:
        out.append(f"** written by: {one_line(command, None)}")
    out += ["*HEADING", f"hertz tied {one_line(s.name)}", "*NODE, NSET=NALL"]
    out += [f"{i + 1}, {_g(x)}, {_g(y)}, {_g(z)}"
            for i, (x, y, z) in enumerate(model.nodes * ul)]
    for body in (1, 2):
        idx = np.nonzero(model.body == body)[0]
        out.append(f"*ELEMENT, TYPE=C3D10, ELSET=BODY{body}")
        out += [f"{e + 1}, " + ", ".join(map(str, row))
                for e, row in zip(idx, model.elements[idx] + 1, strict=True)]
    for name in ("MOVED", "FIXED", "SYMY"):
        out += [f"*NSET, NSET={name}", _lines(model.node_sets[name] + 1)]
    for body, b in ((1, s.body1), (2, s.body2)):
        out += [f"*MATERIAL, NAME=MATERIAL{body}", "*ELASTIC", f"{_g(b.E * us)}, {_g(b.nu)}",
                f"*SOLID SECTION, ELSET=BODY{body}, MATERIAL=MATERIAL{body}"]
    # the slave node is the dependent term; on y = 0 its u_y is fixed by SYMY already
    on_plane = np.isin(pairs[:, 0], model.node_sets["SYMY"])
    out.append("*EQUATION")
    for (sl, ma), plane in zip(pairs + 1, on_plane, strict=True):
        for dof in (1, 3) if plane else (1, 2, 3):
            out += ["2", f"{sl}, {dof}, 1., {ma}, {dof}, -1."]
    out += ["*BOUNDARY", "FIXED, 1, 3, 0.", "MOVED, 2, 3, 0.", "SYMY, 2, 2, 0.",
            "*STEP", "*STATIC", "*BOUNDARY", f"MOVED, 1, 1, {_g(displacement * ul)}",
            "*NODE FILE", "U, RF", "*NODE PRINT, NSET=MOVED, TOTALS=ONLY", "RF",
            "*END STEP"]
    with open(path, "w", encoding="ascii") as f:
        f.write("\n".join(out) + "\n")
    return pairs
