"""The hertz command: default scene, --json, scene files, one-line errors with status 2,
hostile input (no traceback, ever), the scene-file format in --help and --print-scene."""

import json
import math
import os
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest
from hypothesis import given
from hypothesis import strategies as st

import hertz
from hertz.cli import DEFAULT_SCENE, _toml_number, _toml_string, main

#: The directory holding the hertz package these tests import: the command runs from it
#: (``python -m hertz.cli``), not from whatever ``hertz`` script is on PATH.
HERTZ_ROOT = str(Path(hertz.__file__).resolve().parent.parent)
LINUX = sys.platform.startswith("linux")


def command_env(**extra):
    path = os.pathsep.join(p for p in (HERTZ_ROOT, os.environ.get("PYTHONPATH")) if p)
    return {**os.environ, "PYTHONPATH": path, **extra}


def run_command(*argv, cwd=None, env=None, **kwargs):
    """``python -m hertz.cli *argv`` in a subprocess: (status, stdout, stderr) as text."""
    kwargs.setdefault("stdout", subprocess.PIPE)
    done = subprocess.run([sys.executable, "-m", "hertz.cli", *argv], cwd=cwd,
                          env=command_env(**(env or {})), stderr=subprocess.PIPE, **kwargs)
    out = done.stdout.decode("utf-8", "replace") if done.stdout is not None else ""
    return done.returncode, out, done.stderr.decode("utf-8", "replace")


def assert_one_line_error(status, out, err, message):
    assert "Traceback" not in err
    assert status == 2 and out == "", (status, out, err)
    assert err.count("\n") == 1 and err.startswith("hertz: error: ") and message in err, err


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


@pytest.mark.skipif(not LINUX, reason="/dev/full is Linux's")
@pytest.mark.parametrize("argv", [[], ["--json"], ["--help"], ["--print-scene"]])
def test_a_full_disk_is_one_line_and_status_2(argv):
    with open("/dev/full", "w") as full:
        status, out, err = run_command(*argv, stdout=full)
    assert_one_line_error(status, out, err, "No space left on device")


def test_bad_scene_file(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text("load = [\n")
    assert run(capsys, "--scene", str(bad))[0] == 2
    bad.write_text("lode = 5\n")
    status, _, err = run(capsys, "--scene", str(bad))
    assert status == 2 and "unknown key 'lode'" in err


def test_the_command_runs_without_traceback():
    status, out, err = run_command()
    assert status == 0 and "semi-major axis a" in out and err == ""
    assert_one_line_error(*run_command("--load=-5"), "load must be a finite value >= 0")
    closed = subprocess.Popen([sys.executable, "-m", "hertz.cli"], env=command_env(),
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    closed.stdout.close()  # the reader goes away before the table is written
    assert closed.wait() == 0 and closed.stderr.read() == b""


def test_import_hertz_is_light():
    """numpy and the kernel only: no scipy, FEM packages or matplotlib at import."""
    code = ("import sys, hertz; print(sorted(m for m in ('scipy', 'gmsh', 'matplotlib', 'skfem', "
            "'meshio', 'pyamg', 'mpmath') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.strip() == "[]"


# --- hostile input: every failure is one line on stderr and status 2, never a traceback ---

DEEP = 3000
HOSTILE = [
    # (id, argv, files to create {name: text}, message on stderr)
    ("integer beyond a double", ["--scene", "s.toml"], {"s.toml": "load = 1" + "0" * 400},
     "load must be a number a double can hold (|x| < 1.8e308), got an integer of 401 digits"),
    ("negative integer beyond a double in a body", ["--scene", "s.toml"],
     {"s.toml": "[body2]\nE = -1" + "0" * 320}, "body2.E must be a number a double can hold"),
    ("integer of 5000 digits", ["--scene", "s.toml"], {"s.toml": "load = 1" + "0" * 5000},
     "cannot be read"),
    ("array nested 3000 deep", ["--scene", "s.toml"],
     {"s.toml": "x = " + "[" * DEEP + "]" * DEEP}, "nested too deeply"),
    ("inline table nested 3000 deep", ["--scene", "s.toml"],
     {"s.toml": "load = " + "{a = " * DEEP + "1" + "}" * DEEP}, "nested too deeply"),
    ("dotted key 3000 deep", ["--scene", "s.toml"], {"s.toml": ".".join(["a"] * DEEP) + " = 1"},
     "unknown key 'a'"),
    ("table 3000 deep in a body", ["--scene", "s.toml"],
     {"s.toml": "[body1." + ".".join(["a"] * DEEP) + "]\n"}, "unknown key(s) in [body1]: 'a'"),
    ("array 300 deep as a load", ["--scene", "s.toml"],
     {"s.toml": "load = " + "[" * 300 + "1" + "]" * 300},
     "load must be a number, got an array: [[[[["),
    ("not UTF-8", ["--scene", "s.toml"], {"s.toml": b'name = "\xff"\n'}, "is not valid TOML"),
    ("scene file is a directory", ["--scene", "."], {}, "cannot read scene file '.'"),
    ("load beyond a double", ["--load", "1e400"], {}, "load must be a finite value >= 0"),
    ("angle not a number", ["--angle-deg", "nan"], {}, "angle"),
    ("plot: empty name", ["--plot", ""], {}, "--plot needs a file name"),
    ("plot: a directory", ["--plot", "figs"], {"figs/": None}, "'figs' is a directory"),
    ("plot: no suffix", ["--plot", "figure"], {}, "'figure' has no suffix naming the format"),
    ("plot: missing directory", ["--plot", "no/such/dir.png"], {},
     "cannot write the plot 'no/such/dir.png'"),
    ("plot of a zero load", ["--load", "0", "--plot", "zero.png"], {},
     "the load is zero: there are no stresses to draw"),
    ("print-scene over an existing file", ["--print-scene", "old.toml"],
     {"old.toml": "load = 5\n"}, "'old.toml' exists"),
    ("print-scene: empty name", ["--print-scene", ""], {}, "--print-scene needs a file name"),
    ("print-scene with --json", ["--print-scene", "--json"], {},
     "--print-scene writes the scene only: --json not allowed with it"),
    ("print-scene of a bad scene", ["--nu1", "0.7", "--print-scene", "bad.toml"], {},
     "nu must be a Poisson's ratio"),
]
if LINUX:
    HOSTILE += [
        ("plot to /dev/full", ["--plot", "/dev/full"], {}, "'/dev/full' has no suffix"),
        ("scene /dev/zero", ["--scene", "/dev/zero"], {}, "larger than 1048576 bytes"),
    ]


@pytest.mark.parametrize("argv, files, message", [case[1:] for case in HOSTILE],
                         ids=[case[0] for case in HOSTILE])
def test_hostile_input_is_one_line_and_status_2(tmp_path, argv, files, message):
    for name, content in files.items():
        if content is None:
            (tmp_path / name).mkdir()
        elif isinstance(content, bytes):
            (tmp_path / name).write_bytes(content)
        else:
            (tmp_path / name).write_text(content)
    before = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    status, out, err = run_command(*argv, cwd=tmp_path)
    assert_one_line_error(status, out, err, message)
    after = {p: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    assert after == before  # nothing written, nothing changed (no figs.png, zero.png, ...)
    assert not Path("/dev/full.png").exists()


def test_plot_format_must_be_one_matplotlib_writes(tmp_path):
    pytest.importorskip("matplotlib")
    status, out, err = run_command("--plot", "figure.xyz", cwd=tmp_path)
    assert_one_line_error(status, out, err, "matplotlib does not write 'xyz' files")
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("name", ["figure.pdf", "figure.SVG", "figure.png"])
def test_plot_writes_the_path_given_in_the_format_of_its_suffix(tmp_path, name):
    pytest.importorskip("matplotlib")
    status, out, err = run_command("--plot", name, "--yield-strength", "1.5e9", cwd=tmp_path)
    assert status == 0 and err == ""
    assert [p.name for p in tmp_path.iterdir()] == [name]
    magic = {"pdf": b"%PDF", "svg": b"<?xml", "png": b"\x89PNG"}[name.rsplit(".")[1].lower()]
    assert (tmp_path / name).read_bytes().startswith(magic)
    assert "bearing ball on inner race (default scene)" in out  # not relabelled


@pytest.mark.skipif(os.name != "posix", reason="closes descriptor 1 with the shell")
def test_closed_stdout_is_an_error_not_a_silent_success():
    command = f"{sys.executable!s} -m hertz.cli --json >&-"
    done = subprocess.run(["sh", "-c", command], env=command_env(), capture_output=True,
                          text=True)
    assert_one_line_error(done.returncode, done.stdout, done.stderr,
                          "cannot write the output: standard output is closed")


NAME = "Kugel auf Ring \u00e4\u2014\U0001d70e \"quoted\" \\ $x^$"


@pytest.mark.parametrize("env", [{"PYTHONIOENCODING": "ascii"}, {"LC_ALL": "C", "LANG": "C"}])
def test_a_name_the_output_cannot_encode(tmp_path, env):
    scene = tmp_path / "s.toml"
    scene.write_text('name = "Kugel auf Ring \u00e4\u2014\U0001d70e \\"quoted\\" \\\\ $x^$"\n',
                     encoding="utf-8")
    status, out, err = run_command("--scene", str(scene), env=env)
    assert status == 0 and err == ""
    first = out.splitlines()[0]
    assert first.startswith("Hertz point contact: Kugel auf Ring ")
    if env.get("PYTHONIOENCODING") == "ascii":
        assert out.isascii() and "\\xe4\\u2014\\U0001d70e" in first
    status, out, err = run_command("--scene", str(scene), "--json", env=env)
    assert status == 0 and err == "" and json.loads(out)["scene"] == NAME
    status, out, err = run_command("--scene", str(scene), "--print-scene", env=env)
    assert status == 0 and err == "" and tomllib.loads(out)["name"] == NAME


@pytest.mark.parametrize("argv", [
    ["--yield-strength=1.7e308", "--r2x=-0.999", "--e1=1e20"],  # first yield beyond a double
    ["--json", "--yield-strength=1e300", "--r2x=1e-30"],
    ["--nu1=-6.2e-3", "--yield-strength=0.5", "--r2x=0.5", "--approach=5e-324"],  # load underflows
])
def test_no_warning_on_stderr_of_a_successful_run(argv):
    """No Python warning (numpy's overflow and the like) reaches stderr; only the command's
    own validity line where a is not small against R (R = 1e-30 m)."""
    status, out, err = run_command(*argv, env={"PYTHONWARNINGS": "always"})
    assert status == 0 and "Warning" not in err
    assert all(line.startswith("hertz: warning: ") for line in err.splitlines())
    assert (err != "") == ("--r2x=1e-30" in argv)


def test_first_yield_load_where_the_contact_load_overflows(capsys):
    """An approach of 1e300 m overflows the load; the first-yield load, which does not
    depend on the load, is still a number (that of the same bodies at 1000 N)."""
    status, out, err = run(capsys, "--json", "--yield-strength=0.5", "--r2x=1e300",
                           "--approach=1e300")
    row = json.loads(out)["stresses"]["body1"]
    c = hertz.contact(hertz.Body(6e-3, 6e-3, 210e9, 0.3), hertz.Body(1e300, 40e-3, 210e9, 0.3),
                      load=1000.0)
    # an approach of 1e300 m is far outside a << R: one validity line, nothing else
    assert status == 0 and err.startswith("hertz: warning: ") and err.count("\n") == 1
    assert json.loads(out)["load"] is None
    assert row["first_yield_load_von_mises"] == pytest.approx(c.first_yield_load(0.5),
                                                              rel=1e-13)


def test_overflow_is_said_not_printed_as_inf(capsys):
    status, out, err = run(capsys, "--yield-strength=1.7e308", "--r2x=-0.999", "--e1=1e20")
    assert status == 0 and "first yield, von Mises     overflow" in out and "inf" not in out


@pytest.mark.parametrize("argv, label", [
    ([], "bearing ball on inner race (default scene)"),
    (["--yield-strength", "1e9"], "bearing ball on inner race (default scene)"),
    (["--json"], "bearing ball on inner race (default scene)"),
    (["--load", "800"], "custom scene"),
    (["--angle-deg", "0"], "custom scene"),  # given, even if equal to the default
    (["--nu2", "0.3"], "custom scene"),
])
def test_only_options_that_change_the_scene_relabel_it(capsys, argv, label):
    status, out, _ = run(capsys, "--json", *argv)
    assert status == 0 and json.loads(out)["scene"] == label


# --- a zero load is a contact without a patch ----------------------------------------------

def race_contact(load):
    return hertz.contact(hertz.Body(6e-3, 6e-3, 210e9, 0.3),
                         hertz.Body(-6.2e-3, 40e-3, 210e9, 0.3), load=load)


@pytest.mark.parametrize("given", [["--load", "0"], ["--approach", "0"]])
def test_zero_load(capsys, given):
    status, out, err = run(capsys, *given, "--json", "--yield-strength", "1.5e9")
    data = json.loads(out)
    assert status == 0 and err == ""
    assert data["a"] == data["b"] == data["p0"] == data["load"] == data["delta"] == 0.0
    assert data["ellipticity"] == race_contact(1500.0).ellipticity  # the shape under any load
    for body in ("body1", "body2"):
        row = data["stresses"][body]
        assert row["tau_max"] == row["von_mises"] == row["tensile"] == 0.0
        assert row["z_tau_max"] is None and row["x_tensile"] is None
        # P_y = P (p0_y/p0)**3 with p0 ~ P**(1/3): the first-yield load does not depend on
        # the load, so the zero-load contact's is that of the same bodies at 1500 N
        for criterion in ("von_mises", "tresca"):
            expected = race_contact(1500.0).first_yield_load(1.5e9, int(body[-1]), criterion)
            assert row[f"first_yield_load_{criterion}"] == pytest.approx(expected, rel=1e-13)
    status, out, err = run(capsys, *given)
    assert status == 0 and "semi-major axis a       0 m" in out
    assert "zero load: no contact patch" in out and "stresses below the contact: none" in out


# --- the scene-file format in --help; --print-scene writes what --scene reads -------------

def test_help_ends_with_the_scene_format_and_the_default_scene(capsys):
    with pytest.raises(SystemExit) as done:
        main(["--help"])
    out = capsys.readouterr().out
    assert done.value.code == 0
    format_part, default_part = out.split("default scene (hertz --print-scene FILE writes it")
    for key, unit in (("name", ""), ("load", "[N]"), ("approach", "[m]"),
                      ("angle_deg", "[deg]"), ("Rx", "[m]"), ("Ry", "[m]"), ("E", "[Pa]"),
                      ("nu", "[-]")):
        assert f"  {key} {unit}".rstrip() in format_part
    assert "[body1], [body2]" in format_part
    toml_text = "\n".join(line[2:] for line in default_part.splitlines()[1:])
    scene = tomllib.loads(toml_text)
    # the built-in scene of the module docstring: a 12 mm ball on a 6.2 mm groove of a race
    # of 40 mm rolling radius, steel on steel, 1500 N
    assert scene == {"name": "bearing ball on inner race (default scene)", "load": 1500.0,
                     "angle_deg": 0.0,
                     "body1": {"Rx": 0.006, "Ry": 0.006, "E": 210e9, "nu": 0.3},
                     "body2": {"Rx": -0.0062, "Ry": 0.04, "E": 210e9, "nu": 0.3}}


@pytest.mark.parametrize("argv", [
    [],
    ["--load", "800", "--angle-deg", "33.3", "--r2x", "inf"],
    ["--approach", "1e-5", "--r1x", "0.1", "--r1y", "-0.3", "--r2x", "0.0123456789012345678",
     "--e2", "70.3e9", "--nu2", "0.33"],
    ["--load", "1e-300", "--r1x", "1e-3", "--r1y", "2.5e-3", "--nu1", "-0.999", "--e1", "1e300",
     "--r2x", "1e-6", "--r2y", "1e6"],
    ["--load", "0"],
    ["--load", "800", "--tangential", "123.456789", "--mu", "0.17"],
])
def test_print_scene_reads_back_to_the_same_result(tmp_path, capsys, argv):
    path = tmp_path / "scene.toml"
    assert run(capsys, *argv, "--print-scene", str(path)) == (0, "", "")
    direct = run(capsys, *argv, "--json", "--yield-strength", "1e9")
    assert direct[0] == 0
    assert run(capsys, "--scene", str(path), "--json", "--yield-strength", "1e9") == direct
    # to stdout, the same file
    status, out, _ = run(capsys, *argv, "--print-scene")
    assert status == 0 and out == path.read_text()
    assert run(capsys, *argv, "--print-scene", "-")[1] == out


def test_print_scene_of_a_scene_file_keeps_its_name(tmp_path, capsys):
    source = tmp_path / "crossed.toml"
    source.write_text('name = "crossed cylinders"\nload = 100\nangle_deg = 90\n'
                      '[body1]\nRx = 0.01\nRy = "inf"\n[body2]\nRx = 0.01\nRy = inf\n')
    out = run(capsys, "--scene", str(source), "--print-scene")[1]
    scene = tomllib.loads(out)
    assert scene["name"] == "crossed cylinders" and scene["load"] == 100.0
    assert scene["body1"]["Ry"] == math.inf and scene["body2"]["E"] == DEFAULT_SCENE["body2"]["E"]


@given(st.floats(allow_nan=False) | st.sampled_from([5e-324, -0.0, 1e-310, 2.0**1023]))
def test_a_toml_number_reads_back_to_the_same_double(x):
    text = _toml_number(x)
    back = tomllib.loads(f"x = {text}")["x"]
    assert isinstance(back, float) and back == x and math.copysign(1, back) == math.copysign(1, x)
    assert len(text) <= len(repr(x)) + 2  # the shortest form, not 17 digits


@given(st.text(alphabet=st.characters(blacklist_categories=("Cs",))))
def test_a_toml_string_reads_back_to_the_same_text(text):
    assert tomllib.loads(f"n = {_toml_string(text)}")["n"] == text
    ascii_only = _toml_string(text, "ascii")
    assert ascii_only.isascii() and tomllib.loads(f"n = {ascii_only}")["n"] == text


# --- --tangential FORCE --mu MU ------------------------------------------------------------

#: a steel ball of radius 5 mm on glass, 200 N: dissimilar materials, so the no-slip
#: stiffness sums two different bodies' (2 - nu)/G
BALL_ON_GLASS = ("--r1x", "5e-3", "--r1y", "5e-3", "--e1", "210e9", "--nu1", "0.3",
                 "--r2x", "inf", "--r2y", "inf", "--e2", "70e9", "--nu2", "0.22",
                 "--load", "200")


def test_tangential_of_a_sphere_on_a_plane_against_closed_forms_and_the_api():
    force, mu, load = 37.0, 0.25, 200.0
    status, out, err = run_command(*BALL_ON_GLASS, "--tangential", str(force), "--mu", str(mu),
                                   "--json")
    assert status == 0 and err == ""
    data = json.loads(out)
    t = data["tangential"]
    # the API, bit for bit
    c = hertz.contact(hertz.Body.sphere(5e-3, 210e9, 0.3), hertz.Body.plane(70e9, 0.22),
                      load=load)
    api = c.tangential(force, mu)
    assert t["no_slip_stiffness"] == c.tangential_stiffness() == api.no_slip_stiffness
    for key in ("stick_a", "stick_b", "displacement", "stiffness"):
        assert t[key] == getattr(api, key), key
    assert t["fretting_energy"] == c.fretting(force, mu).energy
    assert t["sliding"] is False and t["force"] == force and t["mu"] == mu
    # closed forms for a circle (Mindlin 1949; Johnson, Contact Mechanics, ch. 7)
    a = data["a"]
    k = 8 * a / ((2 - 0.3) * 2 * 1.3 / 210e9 + (2 - 0.22) * 2 * 1.22 / 70e9)
    q = force / (mu * load)
    # (observed: 0 to 2.2e-16 for the first four, 2.9e-15 for the energy's cancelling form)
    assert t["no_slip_stiffness"] == pytest.approx(k, rel=1e-15)
    assert t["stick_a"] == t["stick_b"] == pytest.approx(a * (1 - q) ** (1 / 3), rel=1e-15)
    delta = 3 * mu * load * (1 - (1 - q) ** (2 / 3)) / (2 * k)
    assert t["displacement"] == pytest.approx(delta, rel=1e-15)
    assert t["stiffness"] == pytest.approx(k * (1 - q) ** (1 / 3), rel=1e-15)
    energy = (36 * (mu * load) ** 2 / (5 * k)
              * (1 - (1 - q) ** (5 / 3) - 5 * q / 6 * (1 + (1 - q) ** (2 / 3))))
    assert t["fretting_energy"] == pytest.approx(energy, rel=5e-15)


def test_tangential_table_and_the_limit_of_friction():
    status, out, err = run_command(*BALL_ON_GLASS, "--tangential", "50", "--mu", "0.25")
    assert status == 0 and err == ""
    assert "tangential force Q = 50 N along the major axis, mu = 0.25" in out
    assert "no-slip stiffness along Q" in out and "stick zone semi-axes          0 m, 0 m" in out
    assert "sliding                       yes" in out and " uJ per cycle" in out
    assert "tangential" not in run_command(*BALL_ON_GLASS, "--json")[1]


def test_tangential_in_a_scene_file(tmp_path):
    scene = tmp_path / "ball.toml"
    scene.write_text('load = 200\ntangential = "37"\nmu = 0.25\n[body1]\nRx = 5e-3\n'
                     'Ry = 5e-3\n[body2]\nRx = "inf"\nRy = "inf"\nE = 70e9\nnu = 0.22\n')
    from_file = json.loads(run_command("--scene", str(scene), "--json")[1])
    direct = json.loads(run_command(*BALL_ON_GLASS, "--tangential", "37", "--mu", "0.25",
                                    "--json")[1])
    assert from_file["tangential"] == direct["tangential"]
    # an option overrides the file
    assert json.loads(run_command("--scene", str(scene), "--mu", "0.5", "--json")[1]
                      )["tangential"]["mu"] == 0.5


@pytest.mark.parametrize("argv, message", [
    (["--tangential", "10", "--mu", "0"], "mu must be a positive, finite coefficient of "
                                          "friction, got 0.0"),
    (["--tangential", "10", "--mu", "-0.2"], "mu must be a positive"),
    (["--tangential", "10", "--mu", "inf"], "mu must be a positive"),
    (["--tangential=-1", "--mu", "0.3"], "tangential must be a finite force >= 0 in N, got -1.0"),
    (["--tangential", "nan", "--mu", "0.3"], "tangential must be a finite force"),
    (["--tangential", "60.5", "--mu", "0.3"], "tangential = 60.5 N is above mu * load = 60.0 N: "
                                              "the contact slides as a whole"),
    (["--tangential", "10"], "--tangential needs --mu"),
    (["--mu", "0.3"], "--mu needs --tangential"),
    (["--tangential", "10", "--mu", "0.3", "--load", "0"], "needs a normal load > 0"),
    (["--tangential", "abc", "--mu", "0.3"], "not a number"),
])
def test_tangential_errors_are_one_line_and_status_2(argv, message):
    # the load 200 N of BALL_ON_GLASS, unless the case gives its own
    assert_one_line_error(*run_command(*BALL_ON_GLASS, *argv), message)


def test_help_names_the_tangential_keys(capsys):
    with pytest.raises(SystemExit):
        main(["--help"])
    out = capsys.readouterr().out
    assert "  tangential [N]" in out and "  mu [-]" in out and "--tangential N" in out
