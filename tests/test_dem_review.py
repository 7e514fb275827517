"""Review of the DEM features (issues 26, 27) as their users meet them: files written the
way other people write them, hostile input, and hertz.impact at the ends of the float range.

References are independent of the library: Hertz's impact at 50 digits (mpmath), and a
trajectory made here by scipy's DOP853 at rtol 1e-12 (M delta'' = -K delta^1.5); the
tangential histories from Cattaneo-Mindlin's closed form with Masing's rule.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

pytest.importorskip("scipy")
pytest.importorskip("matplotlib")
mpmath = pytest.importorskip("mpmath")

import hertz  # noqa: E402
from fem_validation.cli import grade as grade_cli  # noqa: E402
from fem_validation.grading.impact import grade_impact, impact_reference  # noqa: E402
from fem_validation.results.contact import ResultError  # noqa: E402
from fem_validation.results.impact import ImpactTrajectory  # noqa: E402
from fem_validation.scenes import scene_from_toml  # noqa: E402

# Chung & Ooi Test 1: two glass spheres, R 10 mm, E 48 GPa, nu 0.2, reduced mass, 20 m/s
R, E, NU, M, V = 0.010, 48e9, 0.20, 0.005864306286700948, 20.0
GLASS = (f'name = "glass"\n[body1]\nRx = {R}\nRy = {R}\nE = {E}\nnu = {NU}\n'
         f'[body2]\nRx = {R}\nRy = {R}\nE = {E}\nnu = {NU}\n')
# two aluminium spheres, R 1 mm, pressed to 1 um (the LAMMPS page's pair)
ALU = ('name = "aluminium"\napproach = 1e-6\n[body1]\nRx = 1e-3\nRy = 1e-3\nE = 70e9\n'
       'nu = 0.33\n[body2]\nRx = 1e-3\nRy = 1e-3\nE = 70e9\nnu = 0.33\n')


def exact(e1, nu1, r1, e2, nu2, r2, mass, speed):
    """(delta_max, F_max, t_c) of a sphere on a sphere (r2, e2 may be inf) at 50 digits;
    t_c by quadrature of the energy equation, not by the Gamma-function closed form."""
    with mpmath.workdps(50):
        mp = mpmath.mpf
        inv = (1 - mp(nu1) ** 2) / mp(e1) + (0 if math.isinf(e2) else (1 - mp(nu2) ** 2) / mp(e2))
        rs = 1 / (1 / mp(r1) + (0 if math.isinf(r2) else 1 / mp(r2)))
        k = mp(4) / 3 / inv * mpmath.sqrt(rs)
        m, v = mp(mass), mp(speed)
        d = (5 * m * v ** 2 / (4 * k)) ** (mp(2) / 5)
        tc = 2 * mpmath.quad(lambda x: 1 / mpmath.sqrt(v ** 2 - 4 * k / (5 * m) * x ** mp(2.5)),
                             [0, d])
        return float(d), float(k * d ** mp(1.5)), float(tc)


@pytest.fixture(scope="module")
def run():
    """Test 1 integrated here, written every 2e-7 s (t_c / 200) from 1 us before touch."""
    from scipy.integrate import solve_ivp

    es = E / (2 * (1 - NU ** 2))
    k = 4 / 3 * es * math.sqrt(R / 2)

    def rhs(_, y):
        return [y[1], -k * max(y[0], 0.0) ** 1.5 / M]

    t = np.arange(-1e-6, 5.2e-5, 2e-7)
    s = solve_ivp(rhs, (t[0], t[-1]), [V * t[0], V], t_eval=t, method="DOP853", rtol=1e-12,
                  atol=1e-16)
    d, v = s.y
    return t, d, k * np.clip(d, 0, None) ** 1.5, v


def status(tmp_path, *argv):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return grade_cli.main([str(a) for a in argv] + ["--out", str(tmp_path / "out")])


def impact_cli(tmp_path, path, *extra, mass=M, speed=V):
    scene = tmp_path / "glass.toml"
    scene.write_text(GLASS)
    return status(tmp_path, "--impact", path, "--scene", scene, "--mass", repr(mass),
                  "--speed", repr(speed), *extra)


def one_line(capsys, *words):
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    for w in words:
        assert w in err, err


# --- trajectories as other people write them ---------------------------------------------

def test_foreign_trajectory_passes(tmp_path, run, capsys):
    """Columns out of order, an extra one, units in the names, spaces around the cells, CRLF
    line ends, a comment: the exact elastic run passes."""
    t, d, f, v = run
    p = tmp_path / "run.csv"
    with open(p, "w", newline="") as fh:
        fh.write("# my DEM code\r\n Fn [N] , extra , overlap_m , t_s , vn \r\n")
        for row in zip(f, d, t, v, strict=True):
            fh.write("{:.12e} , 7 , {:.12e} , {:.12e} , {:.12e}\r\n".format(*row))
    assert impact_cli(tmp_path, p) == 0, capsys.readouterr()


def test_linear_spring_same_peak_force_fails(tmp_path, capsys):
    """A linear spring-dashpot with Hertz's F_max and the same energy: k = F_max^2 / (M V^2);
    its overlap 2 delta_max F_max / ... differs, its duration pi sqrt(M / k)."""
    dmax, fmax, tc = exact(E, NU, R, E, NU, R, M, V)
    k = fmax ** 2 / (M * V ** 2)
    w = math.sqrt(k / M)
    tl = math.pi / w
    t = np.arange(-1e-6, tl + 1e-6, tl / 200)
    d = np.where((t > 0) & (t < tl), V / w * np.sin(w * t), np.where(t <= 0, V * t, -V * (t - tl)))
    f = np.where((t > 0) & (t < tl), k * d, 0.0)
    p = tmp_path / "linear.csv"
    np.savetxt(p, np.c_[t, d, f], delimiter=",", header="t,overlap,normal_force", comments="")
    assert abs(f.max() / fmax - 1) < 1e-3  # tuned to the same peak force
    assert impact_cli(tmp_path, p) == 1
    assert "max_overlap_rel_err" in capsys.readouterr().out


@pytest.mark.parametrize("row, col, value, words", [
    (100, 2, 1e300, ["line 102", "normal_force", "1e+300"]),
    (100, 1, -1e200, ["line 102", "overlap", "-1e+200"]),
    (100, 0, None, ["line 102", "increase strictly"]),
])
def test_hostile_trajectory_rows(tmp_path, run, capsys, row, col, value, words):
    """A huge value exits 2 naming the line (no internal error from an overflow); numbers
    in messages are plain (no 'np.float64(...)')."""
    a = np.c_[run[0], run[1], run[2]]
    a[row, col] = a[row - 1, col] if value is None else value
    p = tmp_path / "bad.csv"
    np.savetxt(p, a, delimiter=",", header="t,overlap,normal_force", comments="")
    assert impact_cli(tmp_path, p) == 2
    err = capsys.readouterr().err
    assert "np.float64" not in err and "Traceback" not in err, err
    for w in words:
        assert w in err, err


@pytest.mark.parametrize("mass, speed, extra, code, words", [
    (1e300, V, [], 2, ["mass", "1e+300", "radius"]),       # overlap beyond the radius
    (M, 1e-300, [], 2, ["speed", "1e-300"]),               # underflows: refused, never 0
    (M, 1e300, [], 2, ["speed", "1e+300"]),
    (1e-300, V, [], 1, []),                                # graded (fails), no 0-division
    (M, V, ["--damping", "tsuji:1e300"], 2, ["coefficient 1e+300", "gamma"]),
    (M, V, ["--damping", "mass_velocity:1e8", "--damping-attractive"], 2,
     ["never lets the bodies part"]),
])
def test_extreme_options(tmp_path, run, capsys, mass, speed, extra, code, words):
    p = tmp_path / "run.csv"
    np.savetxt(p, np.c_[run[0], run[1], run[2]], delimiter=",", header="t,overlap,normal_force",
               comments="")
    assert impact_cli(tmp_path, p, *extra, mass=mass, speed=speed) == code
    if code == 2:
        one_line(capsys, *words)


def test_unknown_law_listed_once(tmp_path, run, capsys):
    p = tmp_path / "run.csv"
    np.savetxt(p, np.c_[run[0], run[1], run[2]], delimiter=",",
               header="t,overlap,normal_force", comments="")
    assert impact_cli(tmp_path, p, "--damping", "foo:1") == 2
    err = capsys.readouterr().err
    assert err.count("lammps_tsuji,") == 1 and err.count("lammps_tsuji_sqrt2") == 1, err


def test_trajectory_type_refuses_huge():
    with pytest.raises(ResultError, match=r"row 1: field 'normal_force' is 1e\+200"):
        ImpactTrajectory([0.0, 1.0, 2.0], [-1.0, 1.0, -1.0], [0.0, 1e200, 0.0])


def test_grade_from_python_tiny_mass_no_zero_division(run):
    scene = scene_from_toml_text(GLASS)
    ref = impact_reference(scene, 1e-300, V)
    g = grade_impact(ImpactTrajectory(*run[:3]), ref, mass=1e-300, speed=V)
    assert not g.passed


def scene_from_toml_text(text):
    import pathlib
    import tempfile

    p = pathlib.Path(tempfile.mkdtemp()) / "s.toml"
    p.write_text(text)
    return scene_from_toml(p)


# --- hertz.impact ------------------------------------------------------------------------

@pytest.mark.parametrize("case", [
    (48e9, 0.2, 0.01, 48e9, 0.2, 0.01, M, V),                  # Chung & Ooi Test 1
    (70e9, 0.3, 0.1, math.inf, 0.3, math.inf, 11.3, 0.2),       # on a rigid wall
    (210e9, 0.3, 1e-6, 210e9, 0.3, 1e-6, 1e-15, 1e-9),          # micro-sphere, 1 nm/s
    (70e9, 0.33, 0.0025, 200e9, 0.3, math.inf, 1.7e-4, 1e3),    # 1 km/s on steel
])
def test_impact_against_mpmath(case):
    e1, nu1, r1, e2, nu2, r2, mass, speed = case
    b1 = hertz.Body.sphere(r1, E=e1, nu=nu1)
    b2 = hertz.Body.plane(E=e2, nu=nu2) if math.isinf(r2) else hertz.Body.sphere(r2, E=e2, nu=nu2)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hertz.HertzValidityWarning)
        got = hertz.impact(b1, b2, speed=speed, mass=mass)
    for g, x in zip((got.max_approach, got.max_force, got.duration),
                    exact(*case), strict=True):
        assert abs(g / x - 1) < 1e-14  # observed <= 2.3e-15


@pytest.mark.parametrize("speed, mass, words", [
    (1e-300, M, ["speed 1e-300", "mass 0.0058"]),
    (1e300, M, ["speed 1e+300"]),
    ([[1.0, 1e300]], [[M], [1.0]], ["speed 1e+300", "mass 0.0058"]),
])
def test_impact_beyond_floating_point_refused(speed, mass, words):
    b = hertz.Body.sphere(R, E=E, nu=NU)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hertz.HertzValidityWarning)
        with pytest.raises(ValueError) as info:
            hertz.impact(b, b, speed=speed, mass=mass)
    for w in words:
        assert w in str(info.value)


def test_impact_bits_scalar_array_float32():
    b = hertz.Body.sphere(R, E=E, nu=NU)
    grid = hertz.impact(b, b, speed=np.array([1.0, 20.0, 3.0]), mass=np.array([[M], [0.1]]))
    one = hertz.impact(b, b, speed=20.0, mass=0.1)
    for name in ("max_approach", "max_force", "duration", "max_pressure"):
        assert getattr(grid, name).shape == (2, 3)
        assert getattr(grid, name)[1, 1] == getattr(one, name)
    f32 = hertz.impact(b, b, speed=np.float32(20), mass=np.float32(0.1))
    assert f32.max_approach == hertz.impact(b, b, speed=20.0,
                                            mass=float(np.float32(0.1))).max_approach


# --- tangential histories ----------------------------------------------------------------

def cattaneo_loop(scene_path):
    """A force-driven fretting loop to 0.8 mu P in closed form (Cattaneo-Mindlin, Masing)."""
    b = hertz.Body.sphere(1e-3, E=70e9, nu=0.33)
    c = hertz.contact(b, b, approach=1e-6)
    p, mu = float(c.load), 0.5
    k = 8 * (70e9 / (2 * 1.33) / (2 * (2 - 0.33))) * float(c.a)   # 8 G* a, independent
    mp, qa = mu * p, 0.8 * mu * p
    ds = 3 * mp / (2 * k)

    def up(q):
        return ds * (1 - (1 - q / mp) ** (2 / 3))

    q1, q2, q3 = np.linspace(0, qa, 201), np.linspace(qa, -qa, 401)[1:], np.linspace(-qa, qa,
                                                                                      401)[1:]
    d = np.r_[up(q1), up(qa) - 2 * ds * (1 - (1 - (qa - q2) / (2 * mp)) ** (2 / 3)),
              -up(qa) + 2 * ds * (1 - (1 - (q3 + qa) / (2 * mp)) ** (2 / 3))]
    return d, np.r_[q1, q2, q3], p


def test_force_driven_semicolon_history_passes(tmp_path, capsys):
    """Hand-written: ';' and decimal commas, columns reversed and in mm, an extra column,
    CRLF, '# mu' line; force-driven (Q in equal steps): passes; reversed sign exits 2."""
    scene = tmp_path / "alu.toml"
    scene.write_text(ALU)
    d, q, p = cattaneo_loop(scene)
    h = tmp_path / "h.csv"
    with open(h, "w", newline="") as fh:
        fh.write("# mu = 0.5\r\n step ; Force [N] ; Displacement [mm] \r\n")
        for i, (a, b) in enumerate(zip(d, q, strict=True)):
            fh.write(f"{i} ; {b:.15e} ; {a * 1e3:.15e}\r\n".replace(".", ","))
    assert status(tmp_path, "--history", h, "--scene", scene) == 0, capsys.readouterr()
    np.savetxt(h, np.c_[d, -q], delimiter=",", header="displacement,force", comments="")
    assert status(tmp_path, "--history", h, "--scene", scene, "--mu", "0.5") == 2
    one_line(capsys, "negate the force")


def test_history_normal_force_beyond_hertz_refused(tmp_path, capsys):
    """One row of P = 1e300 N used to pass (the path error is scaled by mu P_max)."""
    scene = tmp_path / "alu.toml"
    scene.write_text(ALU)
    d, q, p = cattaneo_loop(scene)
    pn = np.full(len(d), p)
    pn[60] = 1e300
    h = tmp_path / "h.csv"
    np.savetxt(h, np.c_[d, q, pn], delimiter=",", header="displacement,force,normal_force",
               comments="")
    assert status(tmp_path, "--history", h, "--scene", scene, "--mu", "0.5") == 2
    one_line(capsys, "line 62", "1e+300", "radius")
    pn[60] = -1.0
    np.savetxt(h, np.c_[d, q, pn], delimiter=",", header="displacement,force,normal_force",
               comments="")
    assert status(tmp_path, "--history", h, "--scene", scene, "--mu", "0.5") == 2
    err = capsys.readouterr().err
    assert "got -1.0 at line 62" in err and "np.float64" not in err, err


def test_damped_impact_refuses_beyond_resolution():
    """gamma = sqrt(5/4) alpha: at alpha 1e20 the integration gave a negative restitution
    (-4e-19) and at 1e300 an infinite duration, with numpy overflow warnings."""
    b = hertz.Body.sphere(R, E=E, nu=NU)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for alpha in (1e20, 1e300):
            with pytest.raises(ValueError, match=r"coefficient 1e\+\d+ of law 'tsuji' .*gamma"):
                hertz.damped_impact(b, b, speed=V, mass=M, law="tsuji", coefficient=[0.1, alpha])
        # the cut-off restitution at the largest gamma allowed against the overdamped
        # asymptote of x'' = -(5/4) x^1.5 - gamma x^(1/4) x': the damping stops the body
        # at x0 = (5 / (4 gamma))^(4/5); the force is 0 again where gamma x0^(1/4) |v| =
        # (5/4) x0^1.5, |v| = (5/4)^2 / gamma^2 (observed within 7e-11)
        g = hertz.damped_impact(b, b, speed=V, mass=M, law="tsuji",
                                coefficient=hertz._impact.MAX_GAMMA / math.sqrt(1.25))
        assert abs(g.restitution * g.gamma ** 2 / 1.5625 - 1) < 1e-6


@pytest.mark.parametrize("angle", [90.0, -5.0, math.nan])
def test_lammps_deck_angle_message(angle):
    """The allowed range is stated as it is checked (it said '(-1, 89.999]')."""
    from fem_validation.decks.lammps import lammps_deck

    wall = ('name = "wall"\n[body1]\nRx = 2.5e-3\nRy = 2.5e-3\nE = 380e9\nnu = 0.23\n'
            '[body2]\nRx = "inf"\nRy = "inf"\nE = 380e9\nnu = 0.23\n')
    with pytest.raises(ValueError, match=r"angle_deg must be in "):
        lammps_deck(scene_from_toml_text(wall), "impact", speed=1.0, angle_deg=angle, mu=0.1)
    with pytest.raises(ValueError) as info:
        lammps_deck(scene_from_toml_text(wall), "impact", speed=1.0, angle_deg=angle, mu=0.1)
    assert "-1" not in str(info.value).split("got")[0]


def _gross_slip_run(flip):
    """Chung & Ooi Test 4 alumina at 60 deg (gross slip throughout): the normal impact
    integrated here, Q = -mu F_n on body 1, v_t and omega from its impulse (I = 2/5 m R^2)."""
    from scipy.integrate import cumulative_trapezoid, solve_ivp

    e, nu, r, m, v, mu = 380e9, 0.23, 0.0025, 4000 * 4 / 3 * math.pi * 0.0025 ** 3, 3.9, 0.092
    k = 4 / 3 * e / (1 - nu ** 2) * math.sqrt(r)
    t = np.arange(-2e-7, 1.5e-5, 2e-8)
    s = solve_ivp(lambda _, y: [y[1], -k * max(y[0], 0.0) ** 1.5 / m], (t[0], t[-1]),
                  [v * t[0], v], t_eval=t, method="DOP853", rtol=1e-12, atol=1e-18)
    d, vn = s.y
    fn = k * np.clip(d, 0, None) ** 1.5
    j = cumulative_trapezoid(mu * fn, t, initial=0.0)
    vt, om = v * math.tan(math.radians(60)) - j / m, 5 * j / (2 * m * r)
    return np.c_[t, d, fn, vn, (1 if flip else -1) * mu * fn, vt, om], m


@pytest.mark.parametrize("flip", [False, True])
def test_oblique_gross_slip_and_force_sign_note(tmp_path, flip):
    """Passes either way (the tangential force column is information), but a column of the
    other sign is named in the notes instead of passing unremarked."""
    import json
    import pathlib

    rows, m = _gross_slip_run(flip)
    p = tmp_path / "oblique.csv"
    np.savetxt(p, rows, delimiter=",", comments="",
               header="t,overlap,normal_force,v_n,tangential_force,v_t,omega")
    scene = pathlib.Path(__file__).parents[1] / "scenes" / "chung-ooi" / "test4-alumina.toml"
    assert status(tmp_path, "--impact", p, "--scene", scene, "--mass", repr(m), "--speed",
                  "3.9", "--mu", "0.092", "--angle-deg", "60") == 0
    notes = json.loads((tmp_path / "out" / "grade.json").read_text())
    text = json.dumps(notes)
    assert ("opposite sign" in text) == flip


def test_force_dipping_inside_contact_named(tmp_path, run, capsys):
    """A force that dips below 0 on the second row in contact (noise) used to be refused as
    'only 1 row(s) in contact' with nothing about why."""
    t, d, f, _ = run
    f = f.copy()
    i0 = int(np.argmax(f > 0))
    f[i0 + 1] = -8.0
    p = tmp_path / "dip.csv"
    np.savetxt(p, np.c_[t, d, f], delimiter=",", header="t,overlap,normal_force", comments="")
    assert impact_cli(tmp_path, p) == 2
    one_line(capsys, "only 1 row(s)", f"line {i0 + 3}", "-8 N", "positive again")


def test_lammps_deck_cli_damping_attractive(tmp_path, capsys):
    """deck --damping-attractive (LAMMPS's default, no limit_damping) writes the deck so
    and prints the grade command with --damping-attractive (no lmp needed)."""
    from fem_validation.__main__ import main

    scene = tmp_path / "alu.toml"
    scene.write_text(ALU)
    argv = ["deck", "--code", "lammps", "--case", "impact", "--speed", "1", "--damping",
            "coeff_restitution:0.8", "--scene", str(scene)]
    assert main(argv + ["--out", str(tmp_path / "a"), "--damping-attractive"]) == 0
    out = capsys.readouterr().out
    assert "--damping-attractive" in out.splitlines()[-1]
    assert "limit_damping" not in (tmp_path / "a" / "in.lammps").read_text()
    assert main(argv + ["--out", str(tmp_path / "b")]) == 0
    assert "--damping-attractive" not in capsys.readouterr().out
    assert "limit_damping" in (tmp_path / "b" / "in.lammps").read_text()


def test_a_whitespace_separated_trajectory_reads_as_a_csv(tmp_path):
    """numpy.savetxt's default (spaces), as a DEM user writes a trajectory: read like the
    comma-separated file, the same numbers."""
    from fem_validation.readers.csv_file import read_table

    rows = [(0.0, 0.0, 0.0), (1e-6, 2e-7, 3.5), (2e-6, 3e-7, 6.25)]
    spaced = tmp_path / "spaced.txt"
    spaced.write_text("t  overlap   normal_force\n"
                      + "".join(f"{a:.6e} {b:.6e}   {c:.6e}\n" for a, b, c in rows))
    commas = tmp_path / "commas.csv"
    commas.write_text("t,overlap,normal_force\n"
                      + "".join(f"{a:.6e},{b:.6e},{c:.6e}\n" for a, b, c in rows))

    def choose(t):
        return [(name, t.find([name], name, "column")) for name in ("t", "overlap",
                                                                      "normal_force")]

    a, b = read_table(spaced, choose), read_table(commas, choose)
    assert a.labels == b.labels == ["t", "overlap", "normal_force"]
    np.testing.assert_array_equal(a.values, b.values)
