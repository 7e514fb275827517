"""History-only tangential grading of a DEM code's force-displacement history
(fem_validation.grading.tangential_history, its result type, reader, report and CLI).

The histories are written out here from closed forms at 50 digits (mpmath), independently
of the grader and of hertz: Hertz's a = (3 P R* / (4 E*))^(1/3), Mindlin's no-slip stiffness
k = 8 G* a (1/G* = sum (2 - nu) / G), his virgin curve Q(delta) = mu P (1 - (1 -
delta / delta_s)^(3/2)) with delta_s = 3 mu P / (2 k) (the inverse of delta = (3 mu P /
(16 G* a)) (1 - (1 - Q / (mu P))^(2/3))), Masing's branches Q_r -+ 2 Q_virgin(|delta -
delta_r| / 2); where P varies, the closed forms of the spring-bed (MDR) solution: lowering P
at a held displacement leaves the virgin state of the new P, raising it changes nothing.
The linear laws (LAMMPS pair_style granular's mindlin and mindlin/force) are stepped by a
loop of their own here.

Mutation tests: a stiffness 1% or 2% off fails; k_t = 4 G a fails the stiffness check by
+(2 - nu) - 1 = +67%; a linear spring with Mindlin's k passes the stiffness to 1e-6 and
fails the loop energy at -100%.
"""

from __future__ import annotations

import doctest
import json
import math

import numpy as np
import pytest

mpmath = pytest.importorskip("mpmath")
pytest.importorskip("matplotlib")

import hertz  # noqa: E402
from fem_validation.cli import grade as grade_cli  # noqa: E402
from fem_validation.grading import tangential_history as gh  # noqa: E402
from fem_validation.readers.history_csv import read_dem_history  # noqa: E402
from fem_validation.results import tangential_history as rh  # noqa: E402
from fem_validation.results.contact import ResultError  # noqa: E402
from fem_validation.scenes import Scene  # noqa: E402

mp = mpmath.mp
mp.dps = 50
E, NU, R, P, MU = 70e9, 0.33, 1e-3, 10.0, 0.3
BALL = hertz.Body.sphere(R, E=E, nu=NU)
SCENE = Scene("aluminium spheres", BALL, BALL, P)
SCENE_TOML = ('name = "aluminium spheres"\nload = 10.0\n[body1]\nRx = 1e-3\nRy = 1e-3\n'
              'E = 70e9\nnu = 0.33\n[body2]\nRx = 1e-3\nRy = 1e-3\nE = 70e9\nnu = 0.33\n')


def constants(p):
    """(a [m], k = 8 G* a [N/m], delta_s [m]) at the normal force p, 50 digits."""
    e, nu, p = mp.mpf(E), mp.mpf(NU), mp.mpf(p)
    g = e / (2 * (1 + nu))
    g_star = 1 / (2 * (2 - nu) / g)
    e_star = 1 / (2 * (1 - nu * nu) / e)
    a = mp.cbrt(3 * p * (mp.mpf(R) / 2) / (4 * e_star))
    k = 8 * g_star * a
    return a, k, 3 * mp.mpf(MU) * p / (2 * k)


def virgin(delta, p=P):
    """Mindlin's virgin curve Q(delta) [N] (odd), mu P beyond delta_s."""
    _, _, ds = constants(p)
    x = mp.mpf(delta)
    s = mp.sign(x)
    r = min(abs(x) / ds, mp.mpf(1))
    return s * mp.mpf(MU) * mp.mpf(p) * (1 - (1 - r) ** mp.mpf(1.5))


def test_virgin_curve_inverts_mindlins_displacement():
    """delta = (3 mu P / (16 G* a)) (1 - (1 - Q/(mu P))^(2/3)) and Q(delta) above are
    inverses, and hertz's Tangential.displacement agrees with the first."""
    a, k, ds = constants(P)
    c = hertz.contact(BALL, BALL, load=P)
    for q in (0.01, 0.3, 0.9):
        lim = mp.mpf(MU) * P
        qq = mp.mpf(q) * lim
        g_star = k / (8 * a)
        delta = 3 * lim / (16 * g_star * a) * (1 - (1 - qq / lim) ** (mp.mpf(2) / 3))
        assert abs(virgin(delta) / qq - 1) < mp.mpf(10) ** -40
        assert abs(float(c.tangential(float(qq), MU).displacement) / float(delta) - 1) < 1e-13


def displacement_loop(amplitude, steps=200):
    """0 -> u1 in `steps`, u1 -> -u1 -> u1 in 2 `steps` each [m]."""
    up = np.linspace(0.0, amplitude, steps + 1)
    down = np.linspace(amplitude, -amplitude, 2 * steps + 1)[1:]
    return np.concatenate([up, down, np.linspace(-amplitude, amplitude, 2 * steps + 1)[1:]])


def md_forces(d, p=P):
    """Mindlin-Deresiewicz's forces along a ramp -> -u1 -> u1 displacement loop."""
    u1 = max(d)
    i1 = int(np.argmax(d))
    i2 = int(np.argmin(d))
    q1 = virgin(u1, p)
    q2 = q1 - 2 * virgin((u1 - min(d)) / 2, p)
    out = []
    for i, x in enumerate(d):
        if i <= i1:
            out.append(virgin(x, p))
        elif i <= i2:
            out.append(q1 - 2 * virgin((mp.mpf(u1) - x) / 2, p))
        else:
            out.append(q2 + 2 * virgin((x - mp.mpf(min(d))) / 2, p))
    return np.array([float(v) for v in out])


def linear_capped(d, k, limit):
    """A linear spring of stiffness k capped at +-limit, displacement-driven."""
    f, prev, out = 0.0, 0.0, []
    for x in d:
        f = min(max(f + k * (x - prev), -limit), limit)
        prev = x
        out.append(f)
    return np.array(out)


_, K, DS = (float(x) for x in constants(P))
D = displacement_loop(0.6 * DS)


def history(d, q, p=P, **kw):
    return rh.TangentialHistory(displacement=d, force=q, normal_force=p, mu=MU,
                                source="path.csv", **kw)


def test_mindlin_deresiewicz_history_passes():
    g = gh.grade_history(history(D, md_forces(D)), SCENE)
    assert g.passed and g.driven == "displacement"
    m = g.metrics
    # the compliance line leaves (2/27) q^2 of Mindlin's curve: 4.0e-5 observed
    assert abs(m["initial_stiffness_rel_err"]) < 6e-5
    assert abs(m["reversal_stiffness_rel_err"]) < 6e-5
    assert abs(m["force_rel_err_max"]) < 1e-12 and m["branch_err_max"] < 1e-12
    # the trapezoid rule on 400 steps per branch: -1/m^2 = -6.3e-6
    assert abs(m["loop_energy_rel_err"] + 6.3e-6) < 1e-6
    assert any("micro-slip" in line for line in g.diagnosis)


def test_force_driven_history_uses_the_same_forces():
    """A force-driven loop (forces in equal steps): detected, its displacement against
    Mindlin's at the same forces, the energy at the same force amplitude."""
    a, k, ds = constants(P)
    qs = np.concatenate([np.linspace(0, 0.7, 201), np.linspace(0.7, -0.7, 401)[1:],
                         np.linspace(-0.7, 0.7, 401)[1:]]) * MU * P
    q1 = mp.mpf(qs.max())

    def disp(q):  # Mindlin's virgin displacement (odd), and Masing's branches
        s = mp.sign(q)
        return s * ds * (1 - (1 - abs(mp.mpf(q)) / (mp.mpf(MU) * P)) ** (mp.mpf(2) / 3))

    d = [disp(q) for q in qs[:201]]
    d += [disp(q1) - 2 * disp((q1 - mp.mpf(q)) / 2) for q in qs[201:601]]
    d += [-disp(q1) + 2 * disp((mp.mpf(q) + q1) / 2) for q in qs[601:]]
    d = np.array([float(x) for x in d])
    g = gh.grade_history(history(d, qs), SCENE)
    assert g.driven == "force" and g.passed
    assert abs(g.metrics["force_rel_err_max"]) < 1e-12 and g.metrics["branch_err_max"] < 1e-12
    w = float(hertz.contact(BALL, BALL, load=P).fretting(0.7 * MU * P, MU).energy)
    assert g.reference["loop_energy"] == pytest.approx(w, rel=1e-14)


def test_linear_spring_with_mindlins_stiffness():
    """LAMMPS's mindlin at constant P: the stiffness exact, no micro-slip, no loop energy;
    a pass with --law linear-capped, the distance to the physics reported."""
    q = linear_capped(D, K, MU * P)
    g = gh.grade_history(history(D, q), SCENE)
    assert not g.passed
    assert abs(g.metrics["initial_stiffness_rel_err"]) < 1e-6
    assert abs(g.metrics["reversal_stiffness_rel_err"]) < 1e-6
    assert g.metrics["loop_energy_rel_err"] == pytest.approx(-1.0, abs=1e-9)
    assert g.check("loop_energy_rel_err").status == "fail"
    assert g.diagnosis[0].startswith("no-slip stiffness exact")
    assert any(line.startswith("no micro-slip: a linear spring capped at mu P")
               for line in g.diagnosis)
    claimed = gh.grade_history(history(D, q), SCENE, law="linear-capped")
    assert claimed.passed and claimed.metrics["law_force_err_max"] < 1e-12
    assert claimed.check("loop_energy_rel_err").status == "information"
    assert claimed.metrics["force_rel_err_max"] == g.metrics["force_rel_err_max"] > 0.1


@pytest.mark.parametrize("error", [0.0, 0.02])
def test_force_driven_linear_law(error):
    """A linear law driven by force (--driven force): its displacements against
    delta + dQ / k; a stiffness 2% off fails the law and the stiffness."""
    q = linear_capped(D, K * (1 + error), MU * P)
    g = gh.grade_history(history(D, q), SCENE, driven="force", law="linear-capped")
    assert g.driven == "force" and g.passed == (error == 0)
    # |Q/k - Q/(k (1 + e))| over the largest displacement Q/(k (1 + e)) = e
    assert g.metrics["law_force_err_max"] == pytest.approx(error, abs=1e-12)
    assert g.metrics["initial_stiffness_rel_err"] == pytest.approx(error, abs=1e-12)


def test_four_g_stiffness_fails_by_two_minus_nu():
    """k_t = 4 G a (LAMMPS's kt = 4G): (2 - nu) = 1.67 x Mindlin's 8 G* a."""
    g_shear = E / (2 * (1 + NU))
    a = float(constants(P)[0])
    q = linear_capped(D, 4 * g_shear * a, MU * P)
    g = gh.grade_history(history(D, q), SCENE)
    assert g.metrics["initial_stiffness_rel_err"] == pytest.approx(1 - NU, abs=1e-9)
    assert g.check("initial_stiffness_rel_err").status == "fail"
    assert "4 G a" in g.diagnosis[0]
    assert any("with the stiffness above" in line for line in g.diagnosis)


@pytest.mark.parametrize("error", [0.01, -0.01, 0.02])
def test_a_stiffness_one_or_two_percent_off_fails(error):
    """Mindlin-Deresiewicz with k (1 + error): the same forces at displacements / (1 + e)."""
    g = gh.grade_history(history(D / (1 + error), md_forces(D)), SCENE)
    assert g.metrics["initial_stiffness_rel_err"] == pytest.approx(error, abs=1e-4)
    assert g.check("initial_stiffness_rel_err").status == "fail"
    assert abs(g.metrics["force_rel_err_max"]) > 0.005


def test_reversed_sign_is_refused_naming_the_convention():
    with pytest.raises(ResultError, match="opposes the displacement.*negate the force"):
        history(D, -linear_capped(D, K, MU * P))


def test_too_few_points_and_no_ramp_are_refused():
    with pytest.raises(ResultError, match="never leaves 0"):
        history(np.zeros(5), np.zeros(5))
    with pytest.raises(ResultError, match="ramp .* holds 1 point"):
        gh.grade_history(history([0.0, 1e-7, 0.0], [0.0, 0.2, 0.0]), SCENE)
    coarse = np.linspace(0, 0.5 * DS, 6)
    with pytest.raises(ResultError, match="stiffness check needs 2"):
        gh.grade_history(history(coarse, md_forces(coarse)), SCENE)


def test_force_beyond_mu_p_is_refused():
    with pytest.raises(ResultError, match="exceeds mu P"):
        gh.grade_history(history(D, 2 * linear_capped(D, K, MU * P)), SCENE)


# --- varying normal force ------------------------------------------------------------------

def mindlin_force_law(d, p, a, k, form):
    """LAMMPS's mindlin (form "displacement") or mindlin/force (form "force"), stepped."""
    hist, out, prev = 0.0, [], 0.0
    for x, pi, ai, ki in zip(d, p, a, k, strict=True):
        inc, prev = x - prev, x
        if ai == 0:
            hist = 0.0
            out.append(0.0)
            continue
        hist += ki * inc if form == "force" else inc
        f = hist if form == "force" else ki * hist
        if abs(f) > MU * pi:
            f = math.copysign(MU * pi, f)
            hist = f if form == "force" else f / ki
        out.append(f)
    return np.array(out)


def press_push_lift_press(n=60):
    """Pressed to 1 um, pushed to 0.15 delta_s, lifted to 0.4 um, pressed back to 1 um:
    (displacement, P, Mindlin-Deresiewicz's Q, a, k) per row."""
    def load(dn):  # Hertz at an approach dn of two equal spheres, 50 digits
        e_star = 1 / (2 * (1 - mp.mpf(NU) ** 2) / E)
        return mp.mpf(4) / 3 * e_star * mp.sqrt(mp.mpf(R) / 2) * mp.mpf(dn) ** mp.mpf(1.5)

    dn = np.concatenate([np.linspace(0, 1e-6, n + 1), np.full(n, 1e-6),
                         np.linspace(1e-6, 0.4e-6, n + 1)[1:],
                         np.linspace(0.4e-6, 1e-6, n + 1)[1:]])
    p0 = float(load(1e-6))
    d1 = 0.15 * float(constants(p0)[2])
    d = np.concatenate([np.zeros(n + 1), np.linspace(0, d1, n + 1)[1:], np.full(2 * n, d1)])
    p = np.array([float(load(x)) for x in dn])
    q = np.array([float(virgin(x, pi)) if x > 0 else 0.0 for x, pi in zip(d, p, strict=True)])
    lifted = 3 * n
    q[lifted + 1:] = q[lifted]  # pressing back at a held displacement changes nothing
    a = np.array([float(constants(pi)[0]) if pi > 0 else 0.0 for pi in p])
    k = np.array([float(constants(pi)[1]) if pi > 0 else 0.0 for pi in p])
    return d, p, q, a, k


def test_varying_normal_force_against_load_path_spring():
    d, p, q, a, k = press_push_lift_press()
    g = gh.grade_history(history(d, q, p), SCENE)
    assert g.varying and g.passed and g.reference["model"] == "hertz.LoadPathSpring"
    assert g.metrics["path_force_err_max"] < 1e-12
    assert [s["state"] for s in g.states] == ["end of press", "end of push", "end of lift",
                                              "end of press back"]
    assert not any(s["parts"] for s in g.states)


@pytest.mark.parametrize("form, variant", [("force", "mindlin/force"),
                                           ("displacement", "mindlin")])
def test_lammps_laws_part_from_mindlin_deresiewicz(form, variant):
    """At the end of the lift (P1, the displacement d1 held): Mindlin-Deresiewicz's
    virgin Q(P1, d1); mindlin/force keeps k(P0) d1, mindlin gives k(P1) d1."""
    d, p, q_md, a, k = press_push_lift_press()
    q = mindlin_force_law(d, p, a, k, form)
    g = gh.grade_history(history(d, q, p), SCENE)
    assert not g.passed and g.check("path_force_err_max").status == "fail"
    assert [s["state"] for s in g.states if s["parts"]] == ["end of push", "end of lift",
                                                           "end of press back"]
    lift = next(s for s in g.states if s["state"] == "end of lift")
    push = next(s for s in g.states if s["state"] == "end of push")
    k_lift = k[push["row"]] if form == "force" else k[lift["row"]]
    expected = k_lift * d[lift["row"]] / q_md[lift["row"]] - 1
    assert lift["rel_err"] == pytest.approx(expected, rel=1e-12)
    assert any(f"LAMMPS's {variant} " in line for line in g.diagnosis)
    claimed = gh.grade_history(history(d, q, p), SCENE, law=variant)
    assert claimed.passed and claimed.metrics["law_force_err_max"] < 1e-12
    with pytest.raises(ResultError, match="linear-capped is defined at constant normal"):
        gh.grade_history(history(d, q, p), SCENE, law="linear-capped")


def test_pressing_before_the_push_is_left_out_at_constant_p():
    """A DEM run presses (P rises, no motion), then cycles at constant P: graded at
    constant P from the row before the first motion."""
    press = np.linspace(0, P, 11)[1:-1]
    d = np.concatenate([np.zeros(press.size), D])
    q = np.concatenate([np.zeros(press.size), md_forces(D)])
    p = np.concatenate([press, np.full(D.size, P)])
    g = gh.grade_history(history(d, q, p), SCENE)
    assert not g.varying and g.passed and g.metrics["branch_err_max"] < 1e-12
    assert any("normal loading" in n for n in g.notes)


def test_driving_quantity_detection():
    assert gh.detect_driving(history(D, md_forces(D)))[0] == "displacement"


def test_docstring_examples():
    for module in (gh, rh):
        assert doctest.testmod(module).failed == 0


# --- the file and the command line ---------------------------------------------------------

def write(path, d, q, p=None, header="displacement,force", lead=""):
    cols = [d, q] + ([p] if p is not None else [])
    rows = "\n".join(",".join(repr(float(v)) for v in row) for row in zip(*cols, strict=True))
    path.write_text(lead + header + ("," + "normal_force" if p is not None else "") + "\n"
                    + rows + "\n", encoding="utf-8")
    return path


@pytest.fixture
def scene_file(tmp_path):
    f = tmp_path / "scene.toml"
    f.write_text(SCENE_TOML)
    return f


def run(args, capsys):
    status = grade_cli.main(args)
    out = capsys.readouterr()
    return status, out.out, out.err


def test_cli_grades_and_writes(tmp_path, scene_file, capsys):
    f = write(tmp_path / "lin.csv", D, linear_capped(D, K, MU * P), lead="# mu = 0.3\n")
    status, out, err = run(["--history", str(f), "--scene", str(scene_file), "--law",
                            "linear-capped", "--out", str(tmp_path / "g")], capsys)
    assert status == 0 and out.startswith("PASSED"), err
    g = json.loads((tmp_path / "g" / "grade.json").read_text())
    assert g["kind"] == "tangential history" and g["law"] == "linear-capped"
    assert g["driven"] == "displacement" and abs(g["initial_stiffness_rel_err"]) < 1e-6
    md = (tmp_path / "g" / "grade.md").read_text()
    assert "no micro-slip" in md and "hertz.TangentialSpring at the history's own " \
                                      "displacements" in md
    assert (tmp_path / "g" / "grade.png").stat().st_size > 10_000
    status, out, _ = run(["--history", str(f), "--scene", str(scene_file), "--out",
                          str(tmp_path / "g")], capsys)
    assert status == 1 and "loop_energy_rel_err" in out


def test_cli_reads_spreadsheet_csv(tmp_path, scene_file, capsys):
    """A byte-order mark, comments, semicolons with decimal commas, mm units."""
    q = md_forces(D)
    rows = "\n".join(f"{float(x) * 1e3!r};{float(y)!r}".replace(".", ",")
                     for x, y in zip(D, q, strict=True))
    f = tmp_path / "excel.csv"
    f.write_text("\ufeff# exported\n# mu = 0.3\n# units = mm\ndisplacement;force\n" + rows
                 + "\n", encoding="utf-8")
    status, out, err = run(["--history", str(f), "--scene", str(scene_file), "--out",
                            str(tmp_path / "g")], capsys)
    assert status == 0, err
    h = read_dem_history(f, default_normal_force=P)
    assert h.displacement[-1] == pytest.approx(D[-1], rel=1e-15)


@pytest.mark.parametrize("case, pattern", [
    ("nan", "non-finite.*line 4"),
    ("sign", "opposes the displacement"),
    ("flat", "never leaves 0"),
    ("mu", "no coefficient of friction"),
    ("both", "normal_force column: --normal-force"),
    ("snapshot", "--snapshot do.es. not apply to --history"),
    ("law-varying", "linear-capped is defined at constant normal force")])
def test_cli_bad_input_exits_2(tmp_path, scene_file, capsys, case, pattern):
    q = linear_capped(D, K, MU * P)
    args = ["--mu", "0.3"]
    if case == "nan":
        q = q.copy()
        q[2] = math.nan
    if case == "sign":
        q = -q
    d = np.zeros(D.size) if case == "flat" else D
    p = None
    if case in ("both", "law-varying"):
        p = np.linspace(P, 2 * P, D.size)
    if case == "mu":
        args = []
    if case == "both":
        args += ["--normal-force", "5"]
    if case == "snapshot":
        args += ["--snapshot", "3"]
    if case == "law-varying":
        args += ["--law", "linear-capped"]
    f = write(tmp_path / "h.csv", d, q, p)
    status, out, err = run(["--history", str(f), "--scene", str(scene_file), "--out",
                            str(tmp_path / "g"), *args], capsys)
    assert status == 2, (out, err)
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    import re

    assert re.search(pattern, err), err


def test_cli_law_refused_in_another_mode(tmp_path, scene_file, capsys):
    status, _, err = run(["--force-approach", "x.csv", "--law", "mindlin", "--scene",
                          str(scene_file), "--out", str(tmp_path / "g")], capsys)
    assert status == 2 and "--law only apply to --history" in err
