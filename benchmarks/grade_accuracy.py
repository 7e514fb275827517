"""How exactly the grader (fem_validation.grading.contact) reads a, b, p0 off nodal pressures.

Exact Hertz pressure p0 sqrt(1 - x^2/a^2 - y^2/b^2), written out here, sampled on square
grids (spacing h) of the whole contact or a quarter, graded against the same scene: the p^2
fit must give a, b, p0 to rounding; the moments (pressure x lumped area) carry the
quadrature error of the lumping; the profile RMS is the linear interpolation of the
square-root edge.  Then a CalculiX-like smeared edge (a tail of 0.15 p0 falling to zero at
(1 + w) a, the force the pressure integral): the fit, the moments and the edge of the
pressed region against w.

    python benchmarks/grade_accuracy.py
"""

import math

import numpy as np

from fem_validation.grading import contact as fg
from fem_validation.results.contact import ContactResult
from fem_validation.scenes import crossed_30deg, equal_steel


def exact(c, x, y):
    """Hertz's pressure at model coordinates (x along body 1's x axis)."""
    t = c.major_axis_angle
    u, v = x * math.cos(t) + y * math.sin(t), -x * math.sin(t) + y * math.cos(t)
    return c.p0 * np.sqrt(np.clip(1 - (u / c.a) ** 2 - (v / c.b) ** 2, 0, None))


def grid(c, h, quarter, extent):
    xs = np.arange(0.0 if quarter else -extent, extent, h)
    x, y = (g.ravel() for g in np.meshgrid(xs, xs, indexing="ij"))
    return np.column_stack([x, y, np.zeros_like(x)])


def percent(m, key):
    return f"{100 * m[key]:+.3f}%"


def main():
    keys = ("a_fit_rel_err", "b_fit_rel_err", "p0_rel_err", "a_moments_rel_err",
            "b_moments_rel_err")
    print("| scene | model | h/b | a (fit) | b (fit) | p0 (fit) | a (moments) | b (moments) "
          "| RMS major | RMS minor | p integral | edge a |")
    print("|" + "---|" * 12)
    for scene in (equal_steel(1), equal_steel(10), crossed_30deg()):
        c = scene.hertz()
        for sym in ("quarter", "whole"):
            if sym == "quarter" and not scene.symmetric:
                continue
            for hb in (0.1, 0.05, 0.025):
                pts = grid(c, hb * c.b, sym == "quarter", 1.5 * c.a)
                r = ContactResult(points=pts, pressure=exact(c, pts[:, 0], pts[:, 1]),
                                  force=c.load, symmetry=sym)
                m = fg.grade(r, scene).metrics
                cells = [percent(m, k) for k in keys]
                cells += [f"{100 * m['rms_major']:.2f}%", f"{100 * m['rms_minor']:.2f}%",
                          percent(m, "pressure_integral_rel_err"), percent(m, "edge_a_rel_err")]
                print(f"| {scene.name} | {sym} | {hb} | " + " | ".join(cells) + " |")
    scene = equal_steel(1)
    c = scene.hertz()
    print("\nsmeared edge (circle, quarter, h = 0.05 b): a tail of 0.15 p0 falling linearly "
          "to zero at (1 + w) a; the force is the pressure integral")
    for w in (0.05, 0.1, 0.2):
        pts = grid(c, 0.05 * c.b, True, 1.6 * c.a)
        rr = np.hypot(pts[:, 0], pts[:, 1]) / c.a
        p = exact(c, pts[:, 0], pts[:, 1])
        tail = (rr > 0.98) & (rr < 1 + w)
        p[tail] = np.maximum(p[tail], 0.15 * c.p0 * (1 - (rr[tail] - 1) / w).clip(0, 1))
        area = fg.lumped_area(pts[:, :2], fg.surface_triangles(pts[:, :2]))
        r = ContactResult(points=pts, pressure=p, force=4 * float(p @ area), symmetry="quarter")
        m = fg.grade(r, scene).metrics
        print(f"w = {w}: a (fit) {percent(m, 'a_fit_rel_err')}, p0 (fit) "
              f"{percent(m, 'p0_rel_err')}, a (moments) {percent(m, 'a_moments_rel_err')}, "
              f"edge a {percent(m, 'edge_a_rel_err')}")


if __name__ == "__main__":
    main()
