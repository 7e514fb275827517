"""The hertz command: default scene, --json, scene files, one-line errors with status 2."""

import json
import shutil
import subprocess
import sys

import pytest

import hertz
from hertz.cli import main


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def test_default_scene_table(capsys):
    status, out, err = run(capsys)
    assert status == 0 and err == ""
    assert "bearing ball on inner race" in out
    for label in ("semi-major axis a", "semi-minor axis b", "peak pressure p0", "approach delta",
                  "stiffness", " mm", " GPa"):
        assert label in out


def test_default_scene_json_matches_the_api(capsys):
    status, out, _ = run(capsys, "--json")
    data = json.loads(out)
    c = hertz.contact(hertz.Body(6e-3, 6e-3, 210e9, 0.3), hertz.Body(-6.2e-3, 40e-3, 210e9, 0.3),
                      load=1500.0)
    assert status == 0
    for key in ("a", "b", "p0", "delta", "load", "alpha", "e_star"):
        assert data[key] == getattr(c, key)


def test_options_override_the_scene(capsys):
    _, out, _ = run(capsys, "--json", "--load", "800", "--r2x", "inf", "--r2y", "inf",
                    "--e2", "70e9", "--nu2", "0.33")
    data = json.loads(out)
    c = hertz.contact(hertz.Body.sphere(6e-3, 210e9, 0.3), hertz.Body.plane(70e9, 0.33), load=800.0)
    assert data["a"] == c.a and data["p0"] == c.p0


def test_approach_and_angle(capsys):
    _, out, _ = run(capsys, "--json", "--approach", "1e-5", "--angle-deg", "30")
    data = json.loads(out)
    c = hertz.contact(hertz.Body(6e-3, 6e-3, 210e9, 0.3), hertz.Body(-6.2e-3, 40e-3, 210e9, 0.3),
                      approach=1e-5, angle=0.5235987755982988)
    assert data["load"] == pytest.approx(c.load, rel=1e-15)


def test_scene_file(tmp_path, capsys):
    scene = tmp_path / "crossed.toml"
    scene.write_text('name = "crossed cylinders"\nload = 100.0\nangle_deg = 90.0\n'
                     '[body1]\nRx = 0.01\nRy = "inf"\n[body2]\nRx = 0.01\nRy = "inf"\n')
    status, out, _ = run(capsys, "--scene", str(scene))
    assert status == 0 and "crossed cylinders" in out
    _, out, _ = run(capsys, "--scene", str(scene), "--json")
    c = hertz.contact(hertz.Body.cylinder(0.01, 210e9, 0.3), hertz.Body.cylinder(0.01, 210e9, 0.3),
                      load=100.0, angle=1.5707963267948966)
    assert json.loads(out)["a"] == pytest.approx(c.a, rel=1e-15)


@pytest.mark.parametrize("argv, message", [
    (["--load=-5"], "load must be a finite value >= 0"),
    (["--load", "abc"], "not a number"),
    (["--nu1", "0.7"], "nu must be a Poisson's ratio"),
    (["--r1x", "0"], "Rx must be a nonzero radius"),
    (["--bogus"], "unrecognized arguments"),
    (["--load", "1", "--approach", "1e-6"], "not allowed with"),
    (["--scene", "/no/such/file.toml"], "cannot read scene file"),
    (["--r2x", "inf", "--r2y", "inf", "--r1y", "inf"], "line contact"),
])
def test_bad_input_is_one_line_and_status_2(capsys, argv, message):
    status, out, err = run(capsys, *argv)
    assert status == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("hertz: error: ") and message in err


@pytest.mark.parametrize("text, message", [
    ("load = [1.0, 2.0]\n", "load must be a number, got an array"),
    ("[body1]\nRx = [1e-3, 2e-3]\n", "body1.Rx must be a number, got an array"),
    ("x = " + "[" * 5000 + "]" * 5000 + "\n", "nested too deeply"),
    ('angle_deg = "thirty"\n', "angle_deg must be a number, got 'thirty'"),
    ("angle_deg = true\n", "angle_deg must be a number"),
    ("load = 1.0\napproach = 1e-6\n", "give one of load and approach, not both"),
    ("name = 5\n", "name must be a string"),
    ("[body2]\nE = {x = 1}\n", "body2.E must be a number, got a table"),
])
def test_hostile_scene_files(tmp_path, capsys, text, message):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    status, out, err = run(capsys, "--scene", str(path))
    assert status == 2 and out == ""
    assert err.count("\n") == 1 and message in err


def test_json_is_strict(capsys):
    status, out, _ = run(capsys, "--json", "--load", "1e308", "--e1", "1e-300", "--e2", "1e-300")
    data = json.loads(out, parse_constant=lambda name: pytest.fail(f"non-JSON {name}"))
    assert status == 0 and data["load"] == 1e308
    assert data["stiffness"] is not None  # finite: the exact path does not overflow
    assert any(value is None for value in data.values())  # p0 overflows: null, not Infinity


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="/dev/full is Linux's")
def test_a_full_disk_is_one_line_and_status_2():
    exe = shutil.which("hertz")
    cmd = [exe] if exe else [sys.executable, "-m", "hertz.cli"]
    with open("/dev/full", "w") as full:
        done = subprocess.run(cmd, stdout=full, stderr=subprocess.PIPE, text=True)
    assert done.returncode == 2 and "Traceback" not in done.stderr
    assert done.stderr.count("\n") == 1 and "No space left on device" in done.stderr


def test_bad_scene_file(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text("load = [\n")
    assert run(capsys, "--scene", str(bad))[0] == 2
    bad.write_text("lode = 5\n")
    status, _, err = run(capsys, "--scene", str(bad))
    assert status == 2 and "unknown key 'lode'" in err


def test_console_script_runs_without_traceback():
    exe = shutil.which("hertz")
    cmd = [exe] if exe else [sys.executable, "-m", "hertz.cli"]
    ok = subprocess.run(cmd, capture_output=True, text=True)
    assert ok.returncode == 0 and "semi-major axis a" in ok.stdout
    bad = subprocess.run(cmd + ["--load=-5"], capture_output=True, text=True)
    assert bad.returncode == 2 and "Traceback" not in bad.stderr
    assert bad.stderr.strip().count("\n") == 0
    closed = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    closed.stdout.close()  # the reader goes away before the table is written
    assert closed.wait() == 0 and closed.stderr.read() == b""


def test_import_hertz_is_light():
    """numpy and the kernel only: no scipy, FEM packages or matplotlib at import."""
    code = ("import sys, hertz; print(sorted(m for m in ('scipy', 'gmsh', 'matplotlib', 'skfem', "
            "'meshio', 'pyamg', 'mpmath') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.strip() == "[]"
