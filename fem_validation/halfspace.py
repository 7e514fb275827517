"""Closed-form half-space corrections: the settlement of a block's far face under a
point load (Boussinesq, normal; Cerruti, tangential), which turn a finite block's
displacement into a half-space's."""

from __future__ import annotations

import numpy as np


def boussinesq_settlement(load: float, E: float, nu: float, depth: float) -> float:
    """Displacement of a half-space under a point load at depth ``depth`` on its axis [m].

    u = P (1 + nu)(3 - 2 nu) / (2 pi E depth), P [N], E [Pa]: what a block
    clamped at that depth does not show, to be added to its approach.
    """
    if not depth > 0:
        raise ValueError(f"depth must be > 0, got {depth!r}")
    return load * (1 + nu) * (3 - 2 * nu) / (2 * np.pi * E * depth)


def cerruti_settlement(force: float, E: float, nu: float, depth: float) -> float:
    """Displacement along a tangential point force of a half-space, on the axis at ``depth``.

    u = Q (3 - 2 nu) / (8 pi G depth), G = E / (2 (1 + nu)) (Cerruti's solution,
    x = y = 0, z = depth): what a block clamped at that depth would not show if it were
    otherwise a half-space.  A block with free sides is softer than a half-space, so
    adding this overstates its compliance (docs/explanation/fem-friction.md: 0.3% at
    blocks 160 a deep).  Q [N], E [Pa], depth [m].
    """
    if not depth > 0:
        raise ValueError(f"depth must be > 0, got {depth!r}")
    shear_modulus = E / (2 * (1 + nu))
    return force * (3 - 2 * nu) / (8 * np.pi * shear_modulus * depth)
