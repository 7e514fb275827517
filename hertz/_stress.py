"""Stresses below a Hertz contact (Python face of hertz/_stress_kernel.c).

The closed forms live in C (the file says what it computes and from which
equations); this module checks and shapes the input, scales by p0 and the
lengths, and wraps the maxima in :class:`Subsurface`.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from . import _ufuncs
from ._validate import (
    as_float_array,
    first_failure,
    int_to_float,
    is_duck_array,
    require,
    with_index,
)

__all__ = ["LineSubsurface", "Subsurface"]

_CRITERIA = ("von_mises", "tresca")


@dataclass(frozen=True, slots=True)
class Subsurface:
    """The largest stresses below a point contact, in one body.

    Stresses in Pa, positions in m in the ellipse frame (x along the major
    axis a, y along the minor axis b, z the depth below the surface).  For a
    contact without load every field is 0.

    Attributes
    ----------
    tau_max, z_tau_max : float or ndarray
        The largest principal shear stress (s1 - s3)/2 [Pa] and its depth [m];
        it lies on the z axis.
    von_mises, z_von_mises : float or ndarray
        The largest von Mises stress [Pa] and its depth [m], on the z axis.
    tau_orthogonal, y_tau_orthogonal, z_tau_orthogonal : float or ndarray
        The largest |tau_yz| in the plane x = 0 through the minor axis [Pa]
        (the orthogonal shear stress of rolling along the minor axis,
        Lundberg-Palmgren) and where it is (y > 0) [m].
    tensile, x_tensile, y_tensile : float or ndarray
        The largest tensile (principal) stress on the surface [Pa] and where
        on the edge of the ellipse it is (x, y >= 0) [m].
    """

    tau_max: float | np.ndarray
    z_tau_max: float | np.ndarray
    von_mises: float | np.ndarray
    z_von_mises: float | np.ndarray
    tau_orthogonal: float | np.ndarray
    y_tau_orthogonal: float | np.ndarray
    z_tau_orthogonal: float | np.ndarray
    tensile: float | np.ndarray
    x_tensile: float | np.ndarray
    y_tensile: float | np.ndarray


@dataclass(frozen=True, slots=True)
class LineSubsurface:
    """The largest stresses below a line contact, in one body.

    Attributes
    ----------
    tau_max, z_tau_max : float or ndarray
        The largest principal shear stress (s1 - s3)/2 [Pa] (on the z axis) and its
        depth [m], over all three principal stresses, the out-of-plane
        s_yy = nu (s_xx + s_zz) included.  For nu >= 0.2423 it is the in-plane
        maximum of the textbooks (0.300 p0 at 0.786 b); below that the largest
        shear is (s_yy - s_zz)/2 and lies shallower: 0.408 p0 at 0.173 b for
        nu = 0.1, 0.5 p0 at the surface for nu = 0.  Long point contacts agree.
    von_mises, z_von_mises : float or ndarray
        The largest von Mises stress [Pa] (plane strain, on the z axis) and its depth [m].
    tau_orthogonal, x_tau_orthogonal, z_tau_orthogonal : float or ndarray
        The largest |tau_xz| [Pa] (p0/4) and where it is (x > 0) [m].
    """

    tau_max: float | np.ndarray
    z_tau_max: float | np.ndarray
    von_mises: float | np.ndarray
    z_von_mises: float | np.ndarray
    tau_orthogonal: float | np.ndarray
    x_tau_orthogonal: float | np.ndarray
    z_tau_orthogonal: float | np.ndarray


def _field_units(cls) -> dict:
    """{field: unit} of a maxima type: positions (x_, y_, z_) in m, stresses in Pa, for
    results of pandas, xarray, pint or dask values (hertz._interop)."""
    return {f.name: "m" if f.name[:2] in ("x_", "y_", "z_") else "Pa"
            for f in dataclasses.fields(cls)}


SUBSURFACE_UNITS = _field_units(Subsurface)
LINE_SUBSURFACE_UNITS = _field_units(LineSubsurface)


def poisson_of(nu_pair, body) -> float | np.ndarray:
    """nu of body 1 or 2 from a contact's (nu1, nu2)."""
    if type(body) is bool or not isinstance(body, (int, np.integer)) or body not in (1, 2):
        raise ValueError(f"body must be 1 or 2, got {body!r}")
    return nu_pair[int(body) - 1]


def _scalar_or_array(x):
    return float(x) if np.ndim(x) == 0 and not is_duck_array(x) else x


_COORDINATE = {"any": "a coordinate in m (not NaN)", "finite": "a finite coordinate in m",
               "depth": "a depth >= 0 in m (finite)"}


def coordinate(value, name: str, kind: str = "finite"):
    """A point's coordinate [m], a numpy float64 or array; NaN (and, unless ``kind``
    is "any", an infinite value or, for "depth", a negative one) raises the ValueError
    naming the parameter, the value and its index."""
    if type(value) is float or type(value) is int:
        value = float(value) if type(value) is float else int_to_float(value, name)
        if not (value == value and (kind == "any" or abs(value) < math.inf)
                and (kind != "depth" or value >= 0.0)):
            raise ValueError(f"{name} must be {_COORDINATE[kind]}, got {value!r}")
        return np.float64(value)  # (x / a of a zero-load contact: inf, not ZeroDivisionError)
    arr = as_float_array(value, name)
    if kind == "any":
        good = not np.isnan(arr).any()
    else:
        good = bool(np.isfinite(arr).all()) and (kind != "depth" or not (arr < 0).any())
    if not good:
        with np.errstate(invalid="ignore"):
            ok = (arr == arr if kind == "any" else np.abs(arr) < np.inf) & (
                arr >= 0 if kind == "depth" else True)
        require(name, arr, ok, _COORDINATE[kind])
    return arr


def _unloaded_as_unit(a, b):
    """(a, b) with the elements of a contact without load (a = b = 0, a valid contact
    whose stresses are all zero) replaced by a unit circle, and where they were (or None):
    the kernels see a valid ellipse, the results are scaled by p0 = 0 and a = 0."""
    if type(a) is float:
        return (1.0, 1.0, True) if a == 0.0 else (a, b, None)
    if is_duck_array(a) or is_duck_array(b):
        return a, b, None
    unloaded = np.asarray(a) == 0.0
    if not unloaded.any():
        return a, b, None
    return np.where(unloaded, 1.0, a), np.where(unloaded, 1.0, b), unloaded


def _contact_index_error(exc, a, b, line):
    """``exc`` with the index of the first contact the kernel refuses, if an array."""
    shape = np.broadcast_shapes(np.shape(a), np.shape(b))
    if not shape:
        return exc
    a, b = np.broadcast_to(a, shape), np.broadcast_to(b, shape)
    with np.errstate(invalid="ignore", over="ignore"):
        # the kernels' range (hertz/_stress_kernel.h, HERTZ_STRESS_EAXES)
        ok = (b > 0) & (b < np.inf) if line else (b > 0) & (a >= b) & (a < np.inf) & (
            b >= 1e-70 * a)
    if ok.all():
        return exc
    return with_index(exc, shape, first_failure(ok))


def point_stress(a, b, p0, nu, x, y, z):
    """The stress tensor [Pa], shape (..., 3, 3), at points (x, y, z) [m]."""
    x, y, z = coordinate(x, "x"), coordinate(y, "y"), coordinate(z, "z", "depth")
    shape = np.broadcast_shapes(*(np.shape(v) for v in (a, b, nu, p0, x, y, z)))
    a, b, _ = _unloaded_as_unit(a, b)
    out = np.empty(shape + (3, 3))
    # the ufunc writes the six components straight into the tensor's views
    try:
        _ufuncs.point_stress(a, b, nu, x, y, z, out=(
            out[..., 0, 0], out[..., 1, 1], out[..., 2, 2], out[..., 1, 2], out[..., 0, 2],
            out[..., 0, 1]))
    except ValueError as exc:
        raise _contact_index_error(exc, a, b, line=False) from None
    out[..., 2, 1] = out[..., 1, 2]
    out[..., 2, 0] = out[..., 0, 2]
    out[..., 1, 0] = out[..., 0, 1]
    out *= np.asarray(p0)[..., None, None]
    return out


def subsurface(a, b, p0, nu) -> Subsurface:
    """The maxima below a point contact, scaled to Pa and m."""
    a, b, unloaded = _unloaded_as_unit(a, b)
    try:
        (tau, z_tau, vm, z_vm, orth, y_orth, z_orth, tens, x_tens,
         y_tens) = _ufuncs.subsurface(a, b, nu)
    except ValueError as exc:
        raise _contact_index_error(exc, a, b, line=False) from None
    if unloaded is not None:   # the maxima of a vanishing load are at the surface's origin
        z_tau, z_vm, y_orth, z_orth, x_tens, y_tens = (
            np.where(unloaded, 0.0, v) for v in (z_tau, z_vm, y_orth, z_orth, x_tens, y_tens))
    return Subsurface(*(_scalar_or_array(v) for v in (
        tau * p0, z_tau, vm * p0, z_vm, orth * p0, y_orth, z_orth, tens * p0, x_tens, y_tens)))


def line_stress(half_width, p0, nu, x, z):
    """The stress tensor [Pa], shape (..., 3, 3), of a line contact at (x, z) [m]."""
    x, z = coordinate(x, "x"), coordinate(z, "z", "depth")
    half_width, _, _ = _unloaded_as_unit(half_width, half_width)
    try:
        sxx, szz, sxz, syy = _ufuncs.line_stress(half_width, nu, x, z)
    except ValueError as exc:
        raise _contact_index_error(exc, half_width, half_width, line=True) from None
    zero = np.zeros_like(sxx)
    rows = [[sxx, zero, sxz], [zero, syy, zero], [sxz, zero, szz]]
    out = np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)
    return out * np.asarray(p0)[..., None, None]


def line_subsurface(half_width, p0, nu) -> LineSubsurface:
    half_width, _, unloaded = _unloaded_as_unit(half_width, half_width)
    try:
        tau, z_tau, vm, z_vm, orth, x_orth, z_orth = _ufuncs.line_subsurface(half_width, nu)
    except ValueError as exc:
        raise _contact_index_error(exc, half_width, half_width, line=True) from None
    if unloaded is not None:
        z_tau, z_vm, x_orth, z_orth = (np.where(unloaded, 0.0, v)
                                       for v in (z_tau, z_vm, x_orth, z_orth))
    return LineSubsurface(*(_scalar_or_array(v) for v in (
        tau * p0, z_tau, vm * p0, z_vm, orth * p0, x_orth, z_orth)))


def yield_p0(maxima, yield_strength, criterion: str):
    """The peak pressure at which the maxima reach the yield strength [Pa].

    von Mises: von_mises = yield_strength; Tresca: 2 tau_max = yield_strength.
    The maxima are those of the same contact at its own p0 (they scale with it).
    """
    if criterion not in _CRITERIA:
        raise ValueError(f"criterion must be one of {_CRITERIA}, got {criterion!r}")
    strength = as_float_array(yield_strength, "yield_strength")
    with np.errstate(invalid="ignore"):
        require("yield_strength", strength, (strength > 0) & (strength < np.inf),
                "a positive, finite stress in Pa")
    ratio = maxima[0] if criterion == "von_mises" else 2.0 * maxima[1]
    return strength / ratio


def load_for_p0(p0, ellipticity, ellip_e, e_star, rho_sum):
    """The load [N] that gives the peak pressure p0 [Pa] to a contact of this geometry.

    From the contact formulas (a = lambda b, b = (3 E(m) P / (pi lambda E* rho_sum))**(1/3),
    p0 = 3 P / (2 pi a b)): P = (8 pi / 3) lambda t**2 p0, t = E(m) p0 / (E* rho_sum).
    The geometry fields alone, no cube of a pressure ratio: no overflow or underflow
    before the result's own (the factors are grouped so that a large t meets a small p0).
    """
    t = (p0 / e_star) / rho_sum * ellip_e
    out = (8.0 * np.pi / 3.0) * ((ellipticity * t) * (t * p0))
    return float(out) if np.ndim(out) == 0 else out
