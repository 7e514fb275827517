"""Malformed 2-D results, scenes and command lines (issue 25, item 3): one clear error
naming the file (and line or field), never a traceback or a silent NaN."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import numpy as np
import pytest

import hertz
from fem_validation.grading.plane import grade_plane
from fem_validation.readers.plane import read_plane_result
from fem_validation.results.contact import ResultError
from fem_validation.results.plane import (
    AxisStress,
    PlaneResult,
    PlaneScene,
    plane_scene_from_toml,
)

DATA = Path(__file__).parent / "data"
PLANE = DATA / "calculix_plane"
STEEL = {"E": 210e9, "nu": 0.3}
BODIES = """[body1]
Rx = {r1x}
Ry = {r1y}
E = 210e9
nu = 0.3
[body2]
Rx = "inf"
Ry = "inf"
E = 210e9
nu = 0.3
"""
X = [0.0, 1e-4, 2e-4, 3e-4]
P = [1e9, 0.8e9, 0.5e9, 0.0]


@pytest.mark.parametrize("kwargs, message", [
    ({"model": "3d"}, "model must be one of plane-strain, axisymmetric, got '3d'"),
    ({"x": [0.0, math.nan, 2e-4, 3e-4]}, "x[1] must be finite"),
    ({"pressure": [1e9, -0.5e9, 0.5e9, 0.0]}, "pressure[1] = -500000000.0 is negative"),
    ({"pressure": [0.0, 0.0, 0.0, 0.0]}, "no node is in contact"),
    ({"x": [0.0, 1e-4]}, "x and pressure differ in length: 2 and 4"),
    ({"x": [0.0, 1e-4], "pressure": [1e9, 0.0]}, "needs 3 or more nodes, got 2"),
    ({"force": 0.0}, "force must be a finite force > 0 [N], got 0.0"),
    ({"force": math.inf}, "force must be a finite force > 0 [N], got inf"),
    ({"force": "10"}, "force must be a number, got str"),
    ({"x": [0.0, -1e-4, 2e-4, 3e-4]}, "x[1] = -0.0001: an axisymmetric model holds radii"),
    ({"reaction": -1.0}, "reaction must be NaN (none) or a finite force > 0"),
    ({"axis": {3: None}}, "axis must map body 1 or 2 to an AxisStress"),
    ({"active": [True, False]}, "active must hold one flag per node (4), got 2"),
])
def test_plane_result_refuses(kwargs, message):
    args = {"model": "axisymmetric", "x": X, "pressure": P, "force": 10.0,
            "source": "r.csv", **kwargs}
    with pytest.raises(ResultError) as err:
        PlaneResult(**args)
    assert message in str(err.value) and str(err.value).startswith("r.csv: ")


def test_axis_stress_refuses_mismatch():
    with pytest.raises(ResultError, match="differ in length: 2 and 3"):
        AxisStress([0.0, 1.0], [1.0, 2.0, 3.0])


def test_half_model_refuses_negative_x():
    with pytest.raises(ResultError, match="a half model holds x >= 0 only"):
        PlaneResult("plane-strain", [-1e-4, 0.0, 1e-4], [0.5e9, 1e9, 0.5e9], 1e5,
                    half_model=True)


@pytest.mark.parametrize("top, r1y, message", [
    ("load_per_length = 1e5\nload = 3.0\n", '"inf"', "not load and load_per_length"),
    ("load_per_length = 1e5\n", "0.01", "needs parallel cylinders along y"),
    ("", "0.02", "neither a line contact"),
    ("load = 100.0\n", '"inf"', "a plane-strain scene takes load_per_length [N/m], not load"),
    ("load_per_length = -1.0\n", '"inf"', "load_per_length"),
])
def test_scene_refuses(tmp_path, top, r1y, message):
    f = tmp_path / "s.toml"
    f.write_text(top + BODIES.format(r1x="0.01", r1y=r1y))
    with pytest.raises(ValueError) as err:
        plane_scene_from_toml(f)
    assert message in str(err.value) and "s.toml" in str(err.value)


def test_scene_model_must_fit_the_bodies(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text(BODIES.format(r1x="0.01", r1y='"inf"'))
    with pytest.raises(ValueError, match="an axisymmetric model needs bodies of revolution"):
        plane_scene_from_toml(f, "axisymmetric")


def test_grade_refuses_another_scene_or_model():
    line = PlaneScene("roller", "plane-strain", hertz.Body.cylinder(0.01, **STEEL),
                      hertz.Body.plane(**STEEL))
    r = PlaneResult("axisymmetric", X, P, 10.0)
    with pytest.raises(ValueError, match="is a axisymmetric model and the scene 'roller' a "
                                         "plane-strain one"):
        grade_plane(r, line)
    lc = line.hertz(1e5)
    x = np.linspace(0, 2 * lc.half_width, 50)
    wrong = PlaneResult("plane-strain", 1000 * x, lc.pressure(x), 1e5, half_model=True)
    with pytest.raises(ResultError, match="a different scene, force or units"):
        grade_plane(wrong, line)
    ok = PlaneResult("plane-strain", x, lc.pressure(x), 1e5, half_model=True)
    with pytest.raises(ValueError, match="unknown metric 'a_rel_err' for a plane-strain"):
        grade_plane(ok, line, {"a_rel_err": 0.01})


# --- CSV ---------------------------------------------------------------------------------

@pytest.mark.parametrize("text, message", [
    ("x,p\n0,1e9\n1e-4,8e8\n2e-4,0\n", "the model is not known"),
    ("# model = 3d\nx,p\n0,1e9\n1e-4,8e8\n2e-4,0\n", "line 1: model must be one of"),
    ("# model = axisymmetric\nx,q\n0,1e9\n1e-4,8e8\n2e-4,0\n", "no pressure column"),
    ("# model = axisymmetric\nx,p\n0,1e9\n1e-4,oops\n2e-4,0\n", "line 4"),
    ("# model = axisymmetric\n# force = -3\nx,p\n0,1e9\n1e-4,8e8\n2e-4,0\n",
     "the force must be a finite number > 0, got -3.0"),
    ("# model = plane-strain\n# symmetry = quarter\nx,p\n0,1e9\n1e-4,8e8\n2e-4,0\n",
     "symmetry of a 2-D line is half or whole"),
    ("# model = axisymmetric\nx,p\n0,1e9\n1e-4,nan\n2e-4,0\n", "line 4"),
])
def test_csv_refuses(tmp_path, text, message):
    f = tmp_path / "line.csv"
    f.write_text(text)
    with pytest.raises(ResultError) as err:
        read_plane_result(f)
    assert message in str(err.value) and "line.csv" in str(err.value)


# --- CalculiX ----------------------------------------------------------------------------

def test_frd_of_a_3d_model_is_not_2d():
    with pytest.raises(ResultError, match="not a 2-D model: element types"):
        read_plane_result(DATA / "calculix" / "two_cubes.frd", model="plane-strain")


def test_frd_without_deck_needs_the_model(tmp_path):
    shutil.copy(PLANE / "plane_strain.frd", tmp_path / "run.frd")
    with pytest.raises(ResultError, match="give --model plane-strain or axisymmetric"):
        read_plane_result(tmp_path / "run.frd")
    r = read_plane_result(tmp_path / "run.frd", model="plane-strain", radii=(0.01, math.inf))
    assert r.details["contact line"] == "the nodes with contact output (no deck)"
    assert r.force == pytest.approx(1.2512784e6, rel=1e-6)


def test_frd_model_contradicting_the_deck():
    with pytest.raises(ResultError, match="--model axisymmetric, but the deck"):
        read_plane_result(PLANE / "plane_strain.frd", model="axisymmetric")


def test_truncated_frd(tmp_path):
    data = (PLANE / "plane_strain.frd").read_bytes()
    (tmp_path / "cut.frd").write_bytes(data[: len(data) // 3])
    shutil.copy(PLANE / "plane_strain.inp", tmp_path / "cut.inp")
    with pytest.raises(ResultError) as err:
        read_plane_result(tmp_path / "cut.frd")
    assert "cut.frd" in str(err.value)


def test_deck_mixing_element_kinds(tmp_path):
    shutil.copy(PLANE / "plane_strain.frd", tmp_path / "mix.frd")
    text = (PLANE / "plane_strain.inp").read_text().replace(
        "*ELEMENT, TYPE=CPE4, ELSET=BLOCK", "*ELEMENT, TYPE=CAX4, ELSET=BLOCK")
    (tmp_path / "mix.inp").write_text(text)
    with pytest.raises(ResultError, match="mixes element kinds"):
        read_plane_result(tmp_path / "mix.frd")


def test_missing_file_and_folder(tmp_path):
    with pytest.raises(ResultError, match="no such file"):
        read_plane_result(tmp_path / "none.frd")
    with pytest.raises(ResultError, match="not a regular file"):
        read_plane_result(tmp_path)


# --- meshio ------------------------------------------------------------------------------

def test_meshio_refusals(tmp_path):
    meshio = pytest.importorskip("meshio")
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    tet = tmp_path / "tet.vtu"
    meshio.write(tet, meshio.Mesh(pts, [("tetra", np.array([[0, 1, 2, 3]]))],
                                  point_data={"p": np.ones(4)}))
    with pytest.raises(ResultError, match="z = 0"):
        read_plane_result(tet, model="axisymmetric")
    flat = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1.0, 0]])
    nop = tmp_path / "nop.vtu"
    meshio.write(nop, meshio.Mesh(flat, [("quad", np.array([[0, 1, 2, 3]]))],
                                  point_data={"temperature": np.ones(4)}))
    with pytest.raises(ResultError, match="no contact pressure among the point fields"):
        read_plane_result(nop, model="axisymmetric")
    with pytest.raises(ResultError, match="a mesh file does not say its model"):
        read_plane_result(nop)
    lines = tmp_path / "lines.vtu"
    meshio.write(lines, meshio.Mesh(flat, [("line", np.array([[0, 1]]))],
                                    point_data={"p": np.ones(4)}))
    with pytest.raises(ResultError, match="no 2-D cells"):
        read_plane_result(lines, model="plane-strain")


# --- command lines -----------------------------------------------------------------------

def _scene(tmp_path, r1y='"inf"'):
    f = tmp_path / "s.toml"
    f.write_text(BODIES.format(r1x="0.01", r1y=r1y))
    return str(f)


@pytest.mark.parametrize("extra, message", [
    (["--symmetry", "quarter"], "--symmetry do(es) not apply to a 2-D result"),
    (["--model", "axisymmetric"], "an axisymmetric model needs bodies of revolution"),
    (["--tolerance", "a_rel_err=0.01"], "tolerance 'a_rel_err': unknown metric"),
])
def test_grade_command_refuses(tmp_path, capsys, extra, message):
    from fem_validation.cli import grade as grade_cli

    status = grade_cli.main([str(PLANE / "plane_strain.frd"), "--scene", _scene(tmp_path),
                             "--out", str(tmp_path / "out"), *extra])
    err = capsys.readouterr().err
    assert status == 2 and message in err and len(err.strip().splitlines()) == 1


def test_hertz_command_line_contact_refusals(tmp_path, capsys):
    from hertz import cli

    f = tmp_path / "line.toml"
    f.write_text("load_per_length = 1e5\n" + BODIES.format(r1x="0.01", r1y='"inf"'))
    assert cli.main(["--scene", str(f), "--plot", str(tmp_path / "x.png")]) == 2
    assert "takes none of --plot" in capsys.readouterr().err
    f.write_text("load_per_length = -1e5\n" + BODIES.format(r1x="0.01", r1y='"inf"'))
    assert cli.main(["--scene", str(f)]) == 2
    assert "load_per_length" in capsys.readouterr().err
    f.write_text("load_per_length = 1e5\napproach = 1e-6\n"
                 + BODIES.format(r1x="0.01", r1y='"inf"'))
    assert cli.main(["--scene", str(f)]) == 2
    assert "not approach and load_per_length" in capsys.readouterr().err


@pytest.mark.parametrize("extra, message", [
    (["--format", "msh"], "writes a frictionless CalculiX or Abaqus deck"),
    (["--format", "calculix", "--friction", "0.3"], "no --friction"),
])
def test_deck_command_refuses(tmp_path, capsys, extra, message):
    from fem_validation.__main__ import main

    f = tmp_path / "line.toml"
    f.write_text("load_per_length = 1e5\n" + BODIES.format(r1x="0.01", r1y='"inf"'))
    status = main(["deck", "--scene", str(f), "--model", "plane-strain", "--out",
                   str(tmp_path / "out"), *extra])
    err = capsys.readouterr().err
    assert status == 2 and message in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "out").exists()
