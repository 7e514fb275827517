"""The stress picture of the ``hertz --plot`` command (needs matplotlib, the plot extra).

Imported only when a figure is asked for: ``import hertz`` never loads matplotlib, and
this module imports it only in :func:`stress_figure`, so that it imports (and pytest's
doctest collection of hertz/ passes) without the plot extra.
"""

from __future__ import annotations

import numpy as np


def von_mises(tensor: np.ndarray) -> np.ndarray:
    """The von Mises stress of stress tensors (..., 3, 3)."""
    s = np.linalg.eigvalsh(tensor)
    return np.sqrt(0.5 * ((s[..., 0] - s[..., 1]) ** 2 + (s[..., 1] - s[..., 2]) ** 2
                          + (s[..., 2] - s[..., 0]) ** 2))


def stress_figure(c, body: int = 1, title: str = "", n: int = 121):
    """A figure of the stresses below a scalar point contact ``c`` in one body.

    Left and middle: the von Mises stress / p0 in the symmetry planes y = 0
    (through the major axis a) and x = 0 (through the minor axis b), depth
    to 2.5 b, with the contact and the maxima of ``c.subsurface(body)``
    marked.  Right: the principal stresses, tau1 and von Mises along the z
    axis, over p0.
    """
    import matplotlib

    matplotlib.use("Agg")  # files only; no display needed
    import matplotlib.pyplot as plt

    if np.ndim(c.a) != 0:
        raise ValueError("the stress figure is for one contact (scalar inputs)")
    m = c.subsurface(body)
    depth = 2.5 * c.b
    z = np.linspace(0.0, depth, n)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.6), constrained_layout=True)
    for ax, (name, half, plane) in zip(axes[:2], (("x (major axis)", 1.6 * c.a, "y = 0"),
                                                   ("y (minor axis)", 1.6 * c.b, "x = 0")),
                                       strict=True):
        u = np.linspace(-half, half, n)
        along, depth = np.meshgrid(u, z)
        tensor = (c.stress(along, 0.0, depth, body) if plane == "y = 0"
                  else c.stress(0.0, along, depth, body))
        field = von_mises(tensor) / c.p0
        mesh = ax.pcolormesh(along * 1e3, depth * 1e3, field, shading="auto", cmap="viridis")
        ax.contour(along * 1e3, depth * 1e3, field, levels=8, colors="white", linewidths=0.5)
        semi = c.a if plane == "y = 0" else c.b
        ax.plot([-semi * 1e3, semi * 1e3], [0.0, 0.0], color="red", lw=4,
                label="contact patch")
        ax.plot([0.0], [m.z_von_mises * 1e3], "w*", ms=12,
                label=f"max von Mises {m.von_mises / c.p0:.3f} p0")
        if plane == "x = 0":
            ax.plot([m.y_tau_orthogonal * 1e3, -m.y_tau_orthogonal * 1e3],
                    [m.z_tau_orthogonal * 1e3] * 2, "r^", ms=8,
                    label=f"max |tau_yz| {m.tau_orthogonal / c.p0:.3f} p0")
        ax.invert_yaxis()
        ax.set_aspect("auto")  # the depth scale is kept, the width stretched to the panel
        ax.set_xlabel(f"{name} [mm]")
        ax.set_ylabel("depth z [mm]")
        ax.set_title(f"von Mises / p0, plane {plane}")
        ax.legend(loc="lower right", fontsize=7, framealpha=0.8)
        fig.colorbar(mesh, ax=ax, shrink=0.9)
    tensor = c.stress(0.0, 0.0, z, body)
    principal = np.linalg.eigvalsh(tensor) / c.p0
    ax = axes[2]
    for k, label in enumerate(("sigma_3", "sigma_2", "sigma_1")):
        ax.plot(principal[:, k], z * 1e3, label=label)
    ax.plot((principal[:, 2] - principal[:, 0]) / 2, z * 1e3, "k--", label="tau1")
    ax.plot(von_mises(tensor) / c.p0, z * 1e3, "k-", lw=2, label="von Mises")
    ax.plot([m.tau_max / c.p0], [m.z_tau_max * 1e3], "ko")
    ax.axvline(0.0, color="grey", lw=0.5)
    ax.invert_yaxis()
    ax.set_xlabel("stress / p0 (tension positive)")
    ax.set_ylabel("depth z [mm]")
    ax.set_title("on the axis x = y = 0")
    ax.legend(fontsize=8)
    fig.suptitle(f"{title}: body {body}, p0 = {c.p0 / 1e9:.4g} GPa, a = {c.a * 1e3:.4g} mm, "
                 f"b = {c.b * 1e3:.4g} mm")
    return fig
