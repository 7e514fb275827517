"""Principal relative curvatures of two bodies touching at a point.

Near the contact point the gap between the bodies is
h = (rho_x X**2 + rho_y Y**2)/2 in the principal frame (X, Y) of the sum of
the two curvature tensors (Johnson, *Contact Mechanics*, 1985, sec. 4.2):

    rho_x + rho_y = sum of the four principal curvatures,
    rho_x - rho_y = sqrt(g1**2 + g2**2 + 2 g1 g2 cos(2 psi)),
    g_i = 1/R_ix - 1/R_iy,

with psi the angle from body 1's x axis to body 2's x axis.  Here
rho_x >= rho_y, so the contact ellipse has its minor axis along X and its
major axis along Y.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np


class RelativeCurvature(NamedTuple):
    """Principal relative curvatures [1/m] and the major-axis direction [rad]."""

    rho_x: np.ndarray
    rho_y: np.ndarray
    major_axis_angle: np.ndarray


def _curvature(radius: np.ndarray) -> np.ndarray:
    with np.errstate(divide="ignore"):
        return 1.0 / radius  # inf -> 0 (flat)


def _pair_sum(ra: np.ndarray, rb: np.ndarray) -> np.ndarray:
    """1/ra + 1/rb; for opposite signs (a concave surface holding a convex one)
    as (ra + rb)/(ra rb), which keeps full precision however closely they conform."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore", under="ignore"):
        plain = _curvature(ra) + _curvature(rb)
        prod = ra * rb
        conforming = (ra + rb) / prod
    use = (prod < 0) & np.isfinite(prod)
    return np.where(use, conforming, plain)


def relative_curvature(r1x, r1y, r2x, r2y, angle) -> RelativeCurvature:
    """Principal relative curvatures of two bodies, their principal planes at ``angle``.

    The arguments are float64 arrays that broadcast together: the principal
    radii of body 1 and body 2 [m] (``inf`` flat, negative concave) and the
    angle [rad] from body 1's x axis to body 2's x axis.  ``major_axis_angle``
    is the angle from body 1's x axis to the direction of rho_y (the major
    axis of the contact ellipse), in (-pi/2, pi/2]; 0 for a circular contact.
    """
    # Trigonometry on the angle's own shape (usually a scalar).
    c, s = np.cos(angle), np.sin(angle)
    if not np.any(s):
        # Principal planes aligned (angle 0): the tensor is diagonal.
        a, b = _pair_sum(r1x, r2x), _pair_sum(r1y, r2y)
        rho_x, rho_y = np.maximum(a, b), np.minimum(a, b)
        theta = np.where(a < b, 0.0, 0.5 * np.pi)
        theta = np.where(a == b, 0.0, theta)
        return RelativeCurvature(rho_x, rho_y, theta)
    cc, ss, cs = c * c, s * s, c * s
    k1x, k1y, k2x, k2y = (_curvature(r) for r in (r1x, r1y, r2x, r2y))
    # Curvature tensor of the gap in body 1's frame: [[a, off], [off, b]].
    a = k1x + k2x * cc + k2y * ss
    b = k1y + k2x * ss + k2y * cc
    off = (k2x - k2y) * cs
    aligned = s == 0.0
    if np.any(aligned):
        a = np.where(aligned, _pair_sum(r1x, r2x), a)
        b = np.where(aligned, _pair_sum(r1y, r2y), b)
    # det = a b - off**2, expanded so that it is a sum of positive terms when
    # both bodies are convex.
    det = k1x * k1y + k2x * k2y + k1x * (k2x * ss + k2y * cc) + k1y * (k2x * cc + k2y * ss)
    half_sum, radius = 0.5 * (a + b), np.hypot(0.5 * (a - b), off)
    rho_x = half_sum + radius
    with np.errstate(divide="ignore", invalid="ignore"):
        rho_y = np.where(rho_x > 0, det / rho_x, half_sum - radius)
    if np.any(aligned):
        rho_x = np.where(aligned, np.maximum(a, b), rho_x)
        rho_y = np.where(aligned, np.minimum(a, b), rho_y)
    # Direction of rho_x is atan2(2 off, a - b)/2; the major axis is normal to it.
    theta = 0.5 * np.arctan2(2.0 * off, a - b) + 0.5 * np.pi
    theta = np.where(theta > 0.5 * np.pi, theta - np.pi, theta)
    theta = np.where(rho_x == rho_y, 0.0, theta)
    return RelativeCurvature(rho_x, rho_y, theta)
