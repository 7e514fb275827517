"""The figure of the tangential contact: docs/tangential.png.

    python tools/tangential_figure.py [--out docs/tangential.png]

The ``hertz`` command's default scene (a bearing ball on its inner race, b/a = 0.10),
mu = 0.1.  Left: the contact ellipse and the Cattaneo-Mindlin stick ellipses at
Q/(mu P) = 0.3, 0.6, 0.9.  Middle: the shear traction / (mu p0) along the major and minor
axes at Q/(mu P) = 0.6, under Coulomb's limit (the pressure / p0).  Right: the fretting
loops (Mindlin-Deresiewicz, Masing's rule) at amplitudes 0.3, 0.6, 0.9 mu P along the
major axis and 0.9 mu P along the minor axis, the virgin curves, the energy per cycle.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import hertz  # noqa: E402
from hertz.cli import DEFAULT_SCENE  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(ROOT / "docs" / "tangential.png"))
    args = parser.parse_args(argv)
    s = DEFAULT_SCENE
    c = hertz.contact(hertz.Body(**s["body1"]), hertz.Body(**s["body2"]), load=s["load"])
    mu = 0.1
    limit = mu * c.load
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))

    ax = axes[0]
    t = np.linspace(0, 2 * np.pi, 400)
    ax.plot(c.a * np.cos(t) * 1e3, c.b * np.sin(t) * 1e3, "k", label="contact ellipse")
    for q in (0.3, 0.6, 0.9):
        st = c.tangential(q * limit, mu)
        ax.plot(st.stick_a * np.cos(t) * 1e3, st.stick_b * np.sin(t) * 1e3,
                label=f"stick zone, Q/(mu P) = {q}")
    ax.set_xlabel("x along the major axis [mm]")
    ax.set_ylabel("y [mm] (stretched: b/a = %.2f)" % (c.b / c.a))
    ax.set_ylim(-1.6 * c.b * 1e3, 1.6 * c.b * 1e3)
    ax.set_title(f"{s['name']}\na = {c.a * 1e3:.3f} mm, b = {c.b * 1e3:.3f} mm")
    ax.legend(fontsize=8, loc="upper right", ncol=2)

    ax = axes[1]
    st = c.tangential(0.6 * limit, mu)
    r = np.linspace(-1, 1, 801)
    ax.plot(r, st.traction(r * c.a, 0.0) / (mu * c.p0), label="traction along x (y = 0)")
    ax.plot(r, st.traction(0.0, r * c.b) / (mu * c.p0), "--", label="traction along y (x = 0)")
    ax.plot(r, c.pressure(r * c.a, 0.0) / c.p0, "k:", label="Coulomb limit mu p / (mu p0)")
    ax.set_xlabel("x / a  or  y / b")
    ax.set_ylabel("shear traction / (mu p0)")
    ax.set_title("Cattaneo-Mindlin traction, Q/(mu P) = 0.6\n(the same in x/a and y/b)")
    ax.legend(fontsize=8)

    ax = axes[2]
    for direction, style, name, amplitudes in ((0.0, "-", "along a", (0.3, 0.6, 0.9)),
                                               (np.pi / 2, "--", "along b", (0.9,))):
        for q in amplitudes:
            loop = c.fretting(q * limit, mu, direction)
            force, disp = loop.loop(201)
            ax.plot(disp * 1e6, force / limit, style,
                    label=f"{name}, Q* = {q} mu P: W = {loop.energy * 1e6:.3g} uJ")
        virgin = c.tangential(np.linspace(0, 1, 201) * limit, mu, direction)
        ax.plot(virgin.displacement * 1e6, virgin.force / limit, "k" + style, lw=0.8)
    ax.set_xlabel("relative tangential displacement [um]")
    ax.set_ylabel("Q / (mu P)")
    ax.set_title(f"fretting loops and virgin curves (black), mu = {mu}")
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(args.out)


if __name__ == "__main__":
    main()
