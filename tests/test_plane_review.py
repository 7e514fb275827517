"""Review of the 2-D grades on CalculiX runs built by hand (tests/data/calculix_plane_hand:
gmsh + numpy, tools/make_plane_hand_runs.py, not fem_validation's deck writer; .frd gzipped):

* roller: a WHOLE half-disc roller (R 10 mm) on a block 20 x 10 mm, plane strain, CPE4,
  one *MATERIAL for both bodies, the block's elements first, shuffled node numbers, a
  node-based slave surface (TYPE=NODE) on the roller, node-to-surface contact, 0.02 mm
  imposed on the roller's cut, an unstructured mesh with no node column on the axis;
* sphere: a quarter-disc sphere (R 10 mm) on a block 10 x 10 mm, axisymmetric, CAX4,
  one material, surface-to-surface contact (node-to-surface diverged in ccx 2.20 here).

Graded against an independent evaluation (own .frd parser, numpy.polyfit of p^2 on x^2
over 0.1-0.9 of Hertz's width, force from the block's bottom reactions, Hertz's closed
form).  Regressions: body 1 was the block (the mesh's order) where the curvature
said roller; the force summed CalculiX's contact forces at the slave nodes (0 for a slave
body 1); no von Mises on the axis of an unstructured mesh.
"""

from __future__ import annotations

import gzip
import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

DATA = Path(__file__).parent / "data" / "calculix_plane_hand"
E, NU, R = 210e3, 0.3, 10.0  # MPa, -, mm (the deck's units)


@pytest.fixture(scope="module")
def hand(tmp_path_factory):
    """The folder of the runs, .frd unzipped beside their decks."""
    out = tmp_path_factory.mktemp("calculix_plane_hand")
    for name in ("roller", "sphere"):
        shutil.copy(DATA / f"{name}.inp", out / f"{name}.inp")
        shutil.copy(DATA / f"{name}.toml", out / f"{name}.toml")
        (out / f"{name}.frd").write_bytes(gzip.decompress((DATA / f"{name}.frd.gz")
                                                          .read_bytes()))
    return out


def _last_blocks(path):
    """{name: (components, {node: values})} of the last increment, and the nodes' x, y."""
    nodes, last = {}, {}
    lines = Path(path).read_text().splitlines()
    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("    2C"):
            i += 1
            while not lines[i].startswith(" -3"):
                s = lines[i]
                nodes[int(s[3:13])] = (float(s[13:25]), float(s[25:37]))
                i += 1
        elif line.startswith(" -4"):
            name, comps, data = line[5:13].strip(), [], {}
            i += 1
            while lines[i].startswith(" -5"):
                comps.append(lines[i][5:13].strip())
                i += 1
            while not lines[i].startswith(" -3"):
                s = lines[i]
                if s.startswith(" -1"):
                    data[int(s[3:13])] = [float(s[13 + 12 * k:25 + 12 * k])
                                          for k in range((len(s) - 13) // 12)]
                i += 1
            last[name] = (comps, data)
        i += 1
    return nodes, last


def _independent(path, model):
    """Force [N/mm or N], width and p0 errors against Hertz, by an independent route."""
    nodes, last = _last_blocks(path)
    comps, data = last["CONTACT"]
    k = comps.index("CPRESS")
    xp = np.array(sorted((nodes[n][0], v[k]) for n, v in data.items() if v[k] != 0))
    comps, data = last["FORC"]
    force = abs(sum(v[1] for n, v in data.items() if abs(nodes[n][1] + 10.0) < 1e-7))
    e_star = E / (2 * (1 - NU ** 2))
    if model == "plane-strain":
        width = math.sqrt(4 * force * R / (math.pi * e_star))      # Johnson (4.43)
        p0 = 2 * force / (math.pi * width)
    else:
        width = (3 * force * R / (4 * e_star)) ** (1 / 3)         # Johnson (4.22)
        p0 = 3 * force / (2 * math.pi * width ** 2)
    x = np.abs(xp[:, 0])
    sel = (x > 0.1 * width) & (x < 0.9 * width)
    slope, c0 = np.polyfit(x[sel] ** 2, xp[sel, 1] ** 2, 1)
    return {"force": force, "width": math.sqrt(-c0 / slope) / width - 1,
            "p0": math.sqrt(c0) / p0 - 1}


@pytest.fixture(scope="module")
def independent(hand):
    return _independent(hand / "roller.frd", "plane-strain")


@pytest.fixture(scope="module")
def graded(hand):
    from fem_validation.cli import grade as grade_cli

    out = hand / "grade"
    status = grade_cli.main([str(hand / "roller.frd"), "--scene", str(hand / "roller.toml"),
                             "--out", str(out)])
    return status, json.loads((out / "grade.json").read_text())


def test_hand_built_run_is_graded_as_the_independent_evaluation(graded, independent):
    status, g = graded
    assert status == 0 and g["passed"] and g["model"] == "plane-strain"
    assert g["force"] == pytest.approx(independent["force"] * 1e3, rel=1e-5)  # N/mm -> N/m
    assert abs(g["half_width_rel_err"] - independent["width"]) < 0.005
    assert abs(g["p0_rel_err"] - independent["p0"]) < 0.005
    assert abs(independent["width"]) < 0.01 and abs(independent["p0"]) < 0.02


def test_hand_built_run_von_mises_on_an_axis_without_nodes(graded):
    _, g = graded
    # Hertz line contact: 0.557 p0 at 0.70 b (nu 0.3); the axis has no node column here
    assert abs(g["von_mises_rel_err"]) < 0.03
    assert set(g["stress"]) == {"body1", "body2"}


@pytest.mark.parametrize("body1", [None, "ROLLER", "BLOCK"])
def test_force_leaves_out_the_contact_forces_and_body_order(body1, hand, independent):
    from fem_validation.readers.calculix_plane import read_calculix_plane

    r = read_calculix_plane(hand / "roller.frd", radii=(0.01, math.inf), body1=body1)
    assert r.force == pytest.approx(independent["force"] * 1e3, rel=1e-5)
    assert r.reaction == pytest.approx(r.force, rel=1e-5)


def test_body_one_is_the_body_whose_radius_fits(hand):
    from fem_validation.readers.calculix_plane import read_calculix_plane

    def read(radii, body1=None):
        return read_calculix_plane(hand / "roller.frd", radii=radii, body1=body1)

    # the mesh's first connected part is the block; the roller's radius is the scene's
    # body 1: body 1 is the roller, as if named by its element set
    r, roller = read((0.01, math.inf)), read((0.01, math.inf), "ROLLER")
    assert "closer to the scene's" in r.details["bodies"]
    np.testing.assert_array_equal(r.axis[1].von_mises, roller.axis[1].von_mises)
    swapped, block = read((math.inf, 0.01)), read((math.inf, 0.01), "BLOCK")
    np.testing.assert_array_equal(swapped.axis[1].von_mises, block.axis[1].von_mises)
    assert not np.array_equal(r.axis[1].von_mises[:5], block.axis[1].von_mises[:5])


def test_csv_with_suffixed_columns_and_semicolons(tmp_path, hand, independent):
    from fem_validation.cli import grade as grade_cli
    from fem_validation.readers.calculix_plane import read_calculix_plane

    r = read_calculix_plane(hand / "roller.frd", radii=(0.01, math.inf))
    rows = "\n".join(f"{x * 1e3:.7f};{p / 1e6:.5f}" for x, p in zip(r.x, r.pressure,
                                                                  strict=True))
    f = tmp_path / "line.csv"
    f.write_text(f"# model = plane-strain\n# force = {r.force / 1e3:.6f}\nr_mm;p_MPa\n{rows}\n")
    status = grade_cli.main([str(f), "--scene", str(hand / "roller.toml"), "--columns",
                             "x=r_mm,p=p_MPa", "--out", str(tmp_path / "g")])
    g = json.loads((tmp_path / "g" / "grade.json").read_text())
    assert status == 0 and g["force"] == pytest.approx(independent["force"] * 1e3, rel=1e-5)
    assert abs(g["half_width_rel_err"] - independent["width"]) < 0.005


def test_hand_built_axisymmetric_run_within_half_a_point(hand, tmp_path):
    from fem_validation.cli import grade as grade_cli

    ind = _independent(hand / "sphere.frd", "axisymmetric")
    out = tmp_path / "grade"
    status = grade_cli.main([str(hand / "sphere.frd"), "--scene", str(hand / "sphere.toml"),
                             "--out", str(out)])
    g = json.loads((out / "grade.json").read_text())
    assert status == 0 and g["passed"] and g["model"] == "axisymmetric"
    assert g["force"] == pytest.approx(ind["force"], rel=1e-5)   # the full circle [N]
    assert abs(g["a_rel_err"] - ind["width"]) < 0.005
    assert abs(g["p0_rel_err"] - ind["p0"]) < 0.005
    assert abs(ind["width"]) < 0.01 and abs(ind["p0"]) < 0.01


def test_quadratic_elements_halved_pressure_is_explained():
    import hertz
    from fem_validation.grading.plane import grade_plane
    from fem_validation.results.plane import PlaneResult, PlaneScene

    scene = PlaneScene("roller", "plane-strain", hertz.Body.cylinder(0.01, 210e9, 0.3),
                       hertz.Body.plane(210e9, 0.3))
    lc = scene.hertz(1e6)
    x = np.linspace(-2 * lc.half_width, 2 * lc.half_width, 161)
    p = 0.5 * lc.pressure(x)                     # CPRESS of CPE8 node-to-surface: halved
    for elements, explained in (([10], True), ([9], False)):
        g = grade_plane(PlaneResult("plane-strain", x, p, 1e6,
                                    details={"elements": elements}), scene)
        assert not g.passed and g.pressure_integral_rel_err == pytest.approx(-0.5, abs=0.01)
        assert any("quadratic 2-D elements" in n for n in g.notes) == explained


def test_hertz_command_load_on_a_line_contact_names_load_per_length(capsys):
    from hertz import cli

    for option in (["--load", "100"], ["--approach", "1e-6"]):
        assert cli.main(["--scene", str(DATA / "roller.toml"), *option]) == 2
        err = capsys.readouterr().err
        assert "load_per_length [N/m]" in err and len(err.strip().splitlines()) == 1


def test_deck_of_a_line_contact_scene_is_plane_strain(tmp_path, capsys):
    pytest.importorskip("gmsh")
    from fem_validation.__main__ import main

    assert main(["deck", "--scene", str(DATA / "roller.toml"), "--format", "calculix",
                 "--level", "0", "--out", str(tmp_path / "d")]) == 0
    assert "plane-strain, CPE4" in capsys.readouterr().out
    assert "TYPE=CPE4" in (tmp_path / "d" / "hertz.inp").read_text()


@pytest.mark.parametrize("block, columns", [("CONTACT", slice(49, 61)),   # CPRESS
                                            ("FORC", slice(25, 37))])      # F2
def test_nan_in_a_frd_is_named(hand, tmp_path, capsys, block, columns):
    from fem_validation.cli import grade as grade_cli

    lines = (hand / "roller.frd").read_text().split("\n")
    start = max(k for k, line in enumerate(lines) if line.startswith(f" -4  {block}"))
    k = next(k for k in range(start, len(lines)) if lines[k].startswith(" -1")
             and abs(float(lines[k][columns])) > 1)
    lines[k] = lines[k][:columns.start] + "         NaN" + lines[k][columns.stop:]
    (tmp_path / "bad.frd").write_text("\n".join(lines))
    shutil.copy(hand / "roller.inp", tmp_path / "bad.inp")
    status = grade_cli.main([str(tmp_path / "bad.frd"), "--scene", str(hand / "roller.toml"),
                             "--out", str(tmp_path / "g")])
    err = capsys.readouterr().err
    assert status == 2 and len(err.strip().splitlines()) == 1
    assert f"bad.frd: {block} {'CPRESS' if block == 'CONTACT' else 'F2'} is not a finite" in err
