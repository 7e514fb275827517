"""The tied counterpart of the frictional CalculiX deck (fem_validation.decks.friction_tied).

The deck bonds the node pairs of the two contact faces within a radius by ``*EQUATION``
and moves body 1's far face along x: checked here against the model's geometry (every
pair shares x and y, lies within the radius, and every slave node within it is paired)
and against what ccx needs of an equation (a dependent degree of freedom appears once and
carries no boundary condition).  ccx itself is not run here: one run costs 8 s of CPU at
level 0; tools/calculix_friction_split.py runs the study (docs/howto/calculix.md).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from fem_extra import require

require("skfem", "gmsh", "scipy")

SPHERES = (Path(__file__).resolve().parents[1] / "scenes" / "calculix"
           / "two-steel-spheres.toml").read_text()
#: Hertz's contact radius of SPHERES, written out: a = (3 P R' / (4 E*))^(1/3),
#: R' = R/2, E* = E / (2 (1 - nu^2)).
A = (3 * 830.7692307692308 * 0.005 / (4 * 210e9 / (2 * (1 - 0.09)))) ** (1 / 3)


@pytest.fixture(scope="module")
def half(tmp_path_factory):
    from fem_validation.decks import read_scene
    from fem_validation.decks.model import build_model

    path = tmp_path_factory.mktemp("scene") / "spheres.toml"
    path.write_text(SPHERES)
    return build_model(read_scene(path), 0, "half")


@pytest.fixture(scope="module")
def deck(half, tmp_path_factory):
    from fem_validation.decks.friction_tied import write_tied_inp

    path = tmp_path_factory.mktemp("tied") / "tied.inp"
    pairs = write_tied_inp(half, path, 2e-6)
    return pairs, path.read_text()


def test_pairs_share_x_y_and_fill_the_disc(half):
    from fem_validation.decks.friction_tied import tied_pairs

    assert math.isclose(half.contact.a, A, rel_tol=1e-12)
    pairs = tied_pairs(half, A)
    slave, master = half.nodes[pairs[:, 0]], half.nodes[pairs[:, 1]]
    np.testing.assert_allclose(slave[:, :2], master[:, :2], atol=1e-12)
    assert np.isin(pairs[:, 0], half.node_sets["SLAVE"]).all()
    assert np.isin(pairs[:, 1], half.node_sets["MASTER"]).all()
    assert np.isin(pairs[:, 0], half.node_sets["BODY1"]).all()
    assert np.isin(pairs[:, 1], half.node_sets["BODY2"]).all()
    # the paraboloid faces: the gap between a pair is r^2 / R (two spheres of R = 10 mm)
    r = np.hypot(slave[:, 0], slave[:, 1])
    np.testing.assert_allclose(slave[:, 2] - master[:, 2], r ** 2 / 0.01, rtol=1e-9,
                               atol=1e-15)
    assert r.max() <= A * (1 + 1e-9)
    # every slave node in the disc is tied, once
    s = half.node_sets["SLAVE"]
    inside = s[np.hypot(*half.nodes[s, :2].T) <= A * (1 + 1e-9)]
    assert sorted(pairs[:, 0]) == sorted(inside)
    # both sides of x = 0, both axes reached: the whole disc of the half model
    assert slave[:, 0].min() < -0.9 * A and slave[:, 0].max() > 0.9 * A
    assert slave[:, 1].max() > 0.9 * A


def test_deck_text(half, deck):
    pairs, text = deck
    assert "*CONTACT PAIR" not in text and "*FRICTION" not in text
    assert "*ELEMENT, TYPE=C3D10, ELSET=BODY1" in text
    assert re.search(r"^MOVED, 1, 1, 0\.002$", text, re.M)   # 2e-6 m in mm
    for line in ("FIXED, 1, 3, 0.", "MOVED, 2, 3, 0.", "SYMY, 2, 2, 0."):
        assert line in text.splitlines()
    block = text.split("*EQUATION\n", 1)[1].split("*BOUNDARY", 1)[0].splitlines()
    counts, terms = block[0::2], block[1::2]
    assert set(counts) == {"2"}
    dependent = []
    for t in terms:
        s, d1, c1, m, d2, c2 = (x.strip() for x in t.split(","))
        assert d1 == d2 and float(c1) == 1.0 and float(c2) == -1.0
        dependent.append((int(s), int(d1)))
        assert (int(s) - 1, int(m) - 1) in {tuple(p) for p in pairs}
    # u_y of a slave node on y = 0 is fixed by SYMY: no equation for it
    on_plane = np.isin(pairs[:, 0], half.node_sets["SYMY"]).sum()
    assert len(terms) == 3 * len(pairs) - on_plane
    assert len(set(dependent)) == len(dependent)
    fixed = {(int(n) + 1, d) for name, dofs in (("FIXED", (1, 2, 3)), ("MOVED", (1, 2, 3)),
                                                ("SYMY", (2,)))
             for n in half.node_sets[name] for d in dofs}
    assert not fixed & set(dependent)


@pytest.mark.parametrize("kwargs, match", [
    ({"displacement": 0.0}, "displacement must be a finite number > 0"),
    ({"displacement": float("nan")}, "displacement must be"),
    ({"displacement": 1e-6, "radius": -1.0}, "radius must be a finite number > 0"),
    ({"displacement": 1e-6, "radius": float("inf")}, "radius must be a finite number > 0"),
    ({"displacement": 1e-6, "units": "inch"}, "units must be one of"),
])
def test_bad_input(half, tmp_path, kwargs, match):
    from fem_validation.decks.friction_tied import write_tied_inp

    with pytest.raises(ValueError, match=match):
        write_tied_inp(half, tmp_path / "t.inp", **kwargs)
    assert not (tmp_path / "t.inp").exists()


def test_quarter_model_refused(half, tmp_path):
    from fem_validation.decks.friction_tied import write_tied_inp
    from fem_validation.decks.model import build_model

    quarter = build_model(half.scene, 0, "quarter")
    with pytest.raises(ValueError, match="half model .* got a quarter model"):
        write_tied_inp(quarter, tmp_path / "t.inp", 1e-6)
