"""A mesh series: the observed order of convergence of each metric and its
Richardson-extrapolated value, as Code_Aster's validation reports give them (V6.03.150:
observed orders of displacement and pressure over a series of meshes).

Method, per metric e (a relative error against Hertz, :mod:`fem_validation.grading.contact`),
on the three finest meshes h1 > h2 > h3 with values e1, e2, e3 (Roache's grid convergence
study, ASME V&V 20):

* the **observed order** p solves (e1 - e2) / (e2 - e3) = (h1^p - h2^p) / (h2^p - h3^p)
  (for a constant ratio r = h1/h2 = h2/h3, p = ln((e1 - e2)/(e2 - e3)) / ln r); it is
  defined where the differences have one sign (monotone convergence: 0 < (e2 - e3) /
  (e1 - e2) < 1 for equal ratios), reported as NaN with the kind of behaviour otherwise
  ("oscillating", "diverging", "converged": the three values equal to rounding);
* the **extrapolated value** e_ext = e3 + (e3 - e2) / ((h2/h3)^p - 1), the value at h -> 0;
* its **uncertainty**: the grid convergence index of the finest mesh, Fs |e3 - e2| /
  ((h2/h3)^p - 1) with the safety factor Fs = 1.25 (three meshes).

Two meshes give no order; a ``expected_order`` given is compared with the observed one.
The mesh size h of a result is measured on its contact surface inside the contact
(:func:`mesh_size`, sqrt(2 x the mean triangle area)): any measure proportional to the
element size gives the same order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

#: The safety factor of the grid convergence index with three meshes (Roache).
SAFETY_FACTOR = 1.25
#: The largest observed order searched [-]: beyond, the values are converged to rounding.
MAX_ORDER = 20.0
#: Relative size of the differences below which three values count as converged.
CONVERGED = 1e-12


@dataclass(frozen=True)
class Convergence:
    """One metric over a mesh series.

    Attributes
    ----------
    name : str
        The metric.
    h : tuple of float
        The mesh sizes [m], coarse to fine.
    values : tuple of float
        The metric on each mesh.
    order : float
        The observed order p from the three finest meshes (NaN where not defined).
    extrapolated : float
        The Richardson-extrapolated value at h -> 0 (NaN where the order is not defined).
    uncertainty : float
        The grid convergence index of the finest mesh, in the metric's units (NaN where
        the order is not defined).
    behaviour : {"monotone", "oscillating", "diverging", "converged", "too few meshes",
        "not available"}
    orders : tuple of float
        The observed order of each consecutive triple of meshes, coarse to fine.
    """

    name: str
    h: tuple
    values: tuple
    order: float
    extrapolated: float
    uncertainty: float
    behaviour: str
    orders: tuple = field(default=())

    def to_dict(self) -> dict:
        def clean(v):
            return None if isinstance(v, float) and not math.isfinite(v) else v
        return {"name": self.name, "h": list(self.h), "values": [clean(v) for v in self.values],
                "order": clean(self.order), "extrapolated": clean(self.extrapolated),
                "uncertainty": clean(self.uncertainty), "behaviour": self.behaviour,
                "orders": [clean(v) for v in self.orders]}


def observed_order(h, values) -> tuple[float, str]:
    """The observed order of three values on meshes h1 > h2 > h3 (and the behaviour).

    Parameters
    ----------
    h : sequence of 3 floats
        Mesh sizes, decreasing, > 0.
    values : sequence of 3 floats

    Returns
    -------
    (float, str)
        p, "monotone"; or NaN and "oscillating", "diverging", "converged" or
        "not available" (a value not finite).

    Examples
    --------
    >>> p, how = observed_order([0.4, 0.2, 0.1], [0.16, 0.04, 0.01])   # e = h**2
    >>> round(p, 12), how
    (2.0, 'monotone')
    >>> observed_order([0.4, 0.2, 0.1], [0.1, -0.05, 0.02])[1]
    'oscillating'
    """
    h1, h2, h3 = (float(x) for x in h)
    h1, h2, h3 = h1 / h3, h2 / h3, 1.0  # in units of the finest: no under- or overflow
    e1, e2, e3 = (float(x) for x in values)
    if not all(math.isfinite(x) for x in (e1, e2, e3)):
        return math.nan, "not available"
    d21, d32 = e1 - e2, e2 - e3
    scale = max(abs(e1), abs(e2), abs(e3), 1e-300)
    if abs(d21) <= CONVERGED * scale and abs(d32) <= CONVERGED * scale:
        return math.nan, "converged"
    if d21 * d32 <= 0:
        return math.nan, "oscillating"
    ratio = d21 / d32  # (h1^p - h2^p) / (h2^p - h3^p), increasing in p from its p->0 limit

    def g(p):
        return (h1 ** p - h2 ** p) - ratio * (h2 ** p - h3 ** p)

    low = math.log(h1 / h2) / math.log(h2 / h3)  # the ratio as p -> 0
    if ratio <= low:
        return math.nan, "diverging"
    from scipy.optimize import brentq

    if g(MAX_ORDER) < 0:
        return math.nan, "converged"
    return float(brentq(g, 1e-9, MAX_ORDER, xtol=1e-14, rtol=1e-14)), "monotone"


def richardson(h, values) -> Convergence:
    """The observed order, extrapolated value and uncertainty of one metric's series
    (see the module docstring); the name is left empty.

    Parameters
    ----------
    h : sequence of floats
        Mesh sizes, any order (sorted coarse to fine here), distinct, > 0.
    values : sequence of floats
        The metric on each mesh.

    Raises
    ------
    ValueError
        Naming the parameter: lengths differ, a size not finite > 0, two equal sizes.

    Examples
    --------
    >>> c = richardson([0.1, 0.2, 0.4], [1 + 0.5 * 0.01, 1 + 0.5 * 0.04, 1 + 0.5 * 0.16])
    >>> round(c.order, 10), round(c.extrapolated, 12)
    (2.0, 1.0)
    """
    h = np.asarray(h, dtype=float).ravel()
    v = np.asarray(values, dtype=float).ravel()
    if h.shape != v.shape:
        raise ValueError(f"h and values must have the same length, got {h.size} and {v.size}")
    if not (np.isfinite(h).all() and (h > 0).all()):
        raise ValueError(f"h: mesh sizes must be finite numbers > 0, got {h.tolist()}")
    order = np.argsort(-h, kind="stable")
    h, v = h[order], v[order]
    if len(np.unique(h)) != len(h):
        raise ValueError(f"h: two meshes of the same size {h.tolist()}: a series needs "
                         f"distinct sizes")
    if len(h) < 3:
        return Convergence("", tuple(h.tolist()), tuple(v.tolist()), math.nan, math.nan,
                           math.nan, "too few meshes")
    orders = tuple(observed_order(h[k:k + 3], v[k:k + 3])[0] for k in range(len(h) - 2))
    p, how = observed_order(h[-3:], v[-3:])
    ext = unc = math.nan
    if how == "monotone":
        growth = (h[-2] / h[-1]) ** p - 1
        ext = float(v[-1] + (v[-1] - v[-2]) / growth)
        unc = float(SAFETY_FACTOR * abs(v[-1] - v[-2]) / growth)
    elif how == "converged":
        ext, unc = float(v[-1]), 0.0
    return Convergence("", tuple(h.tolist()), tuple(v.tolist()), p, ext, unc, how, orders)


def mesh_size(points_xy: np.ndarray, triangles: np.ndarray | None, pressure) -> float:
    """A result's mesh size [m]: sqrt(2 A), A the mean area (in the contact plane) of the
    surface triangles whose three nodes carry pressure: the spacing of a square grid cut
    into triangles, about the edge of a mesh of triangles.

    Parameters
    ----------
    points_xy : ndarray, shape (n, 2)
        The contact surface's nodes in the contact plane [m].
    triangles : ndarray of int, shape (m, 3), or None
        Its triangles (None: a Delaunay triangulation).
    pressure : ndarray, shape (n,)
        Nodal pressure or force (> 0 in contact).

    Raises
    ------
    ValueError
        No triangle has three nodes in contact.

    Examples
    --------
    >>> import numpy as np
    >>> g = np.stack(np.meshgrid(np.arange(5.0), np.arange(5.0)), -1).reshape(-1, 2) * 0.1
    >>> round(mesh_size(g, None, np.ones(len(g))), 12)
    0.1
    """
    from ..fe.surface import surface_triangles

    xy = np.asarray(points_xy, dtype=float)
    tri = surface_triangles(xy) if triangles is None else np.asarray(triangles)
    pressed = np.asarray(pressure) > 0
    tri = tri[pressed[tri].all(axis=1)]
    d1, d2 = xy[tri[:, 1]] - xy[tri[:, 0]], xy[tri[:, 2]] - xy[tri[:, 0]]
    area = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    area = area[area > 0]
    if not len(area):
        raise ValueError("mesh_size: no surface triangle has its three nodes in contact")
    return float(math.sqrt(2.0 * area.mean()))


@dataclass(frozen=True)
class Series:
    """A mesh series graded: one :class:`Convergence` per metric.

    Attributes
    ----------
    scene : str
    sources : tuple of str
        The results, coarse to fine.
    h : tuple of float
        Their mesh sizes [m], coarse to fine.
    passed : tuple of bool
        Each result's own grade.
    metrics : dict
        ``{name: Convergence}``.
    expected_order : float or None
        The order the method should reach (reported beside the observed one).
    """

    scene: str
    sources: tuple
    h: tuple
    passed: tuple
    metrics: dict
    expected_order: float | None = None

    def to_dict(self) -> dict:
        return {"kind": "mesh series", "scene": self.scene, "sources": list(self.sources),
                "h": list(self.h), "passed": list(self.passed),
                "expected_order": self.expected_order,
                "safety_factor": SAFETY_FACTOR,
                "metrics": {k: c.to_dict() for k, c in self.metrics.items()}}


#: The metrics of a series (relative errors against Hertz), those a grade gives.
SERIES_METRICS = ("a_rel_err", "b_rel_err", "p0_rel_err", "a_fit_rel_err", "b_fit_rel_err",
                  "a_moments_rel_err", "b_moments_rel_err", "rms_major", "rms_minor",
                  "approach_rel_err", "von_mises_rel_err", "z_von_mises_rel_err")


def grade_series(grades, h, scene_name: str = "", expected_order: float | None = None
                 ) -> Series:
    """A mesh series from each mesh's grade (:func:`fem_validation.grading.contact.grade`)
    and mesh size.

    Parameters
    ----------
    grades : sequence of Grade
        At least 2 (3 for an order).
    h : sequence of float
        Their mesh sizes [m] (:func:`mesh_size`), distinct.
    scene_name : str
    expected_order : float, optional

    Raises
    ------
    ValueError
        Fewer than 2 grades, lengths that differ, sizes not distinct.
    """
    grades = list(grades)
    if len(grades) < 2:
        raise ValueError(f"a mesh series needs at least 2 results (3 for an order), got "
                         f"{len(grades)}")
    h = np.asarray(h, dtype=float)
    if len(h) != len(grades):
        raise ValueError(f"h: one size per result, got {len(h)} for {len(grades)}")
    order = np.argsort(-h, kind="stable")
    metrics = {}
    for name in SERIES_METRICS:
        values = [float(grades[k].metrics.get(name, math.nan)) for k in order]
        if not any(math.isfinite(v) for v in values):
            continue
        c = richardson(h[order], values)
        metrics[name] = Convergence(name, c.h, c.values, c.order, c.extrapolated,
                                    c.uncertainty, c.behaviour, c.orders)
    return Series(scene_name, tuple(grades[k].source for k in order),
                  tuple(float(x) for x in h[order]),
                  tuple(bool(grades[k].passed) for k in order), metrics, expected_order)
