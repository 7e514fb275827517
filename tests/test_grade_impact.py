"""``python -m fem_validation grade --impact``: a DEM impact graded against the exact Hertz
impact (issue 27, item 5).

References are independent of the grader: Hertz's impact in closed form with its
constants from mpmath (delta_max from the energy, t_c = 2 (delta_max / V) Gamma(7/5)
Gamma(1/2) / Gamma(9/10)), Chung & Ooi's (2011) published Test 1 values, and trajectories
made here by integrating M delta'' = -K delta^1.5 with scipy's DOP853 at rtol 1e-12 (not
by the grader's inverse incomplete beta function).
"""

from __future__ import annotations

import json
import math
import os
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("scipy")
pytest.importorskip("matplotlib")
mpmath = pytest.importorskip("mpmath")

from fem_validation.cli import grade as grade_cli  # noqa: E402
from fem_validation.grading.impact import (  # noqa: E402
    grade_impact,
    hertz_closed_form,
    impact_reference,
)
from fem_validation.readers import csv_file  # noqa: E402
from fem_validation.readers.impact_csv import MAX_BYTES, read_impact  # noqa: E402
from fem_validation.results.contact import ResultError  # noqa: E402
from fem_validation.results.impact import ImpactTrajectory  # noqa: E402
from fem_validation.scenes import scene_from_toml  # noqa: E402

# Chung & Ooi (2011) Test 1: two glass spheres, R 10 mm, E 48 GPa, nu 0.20, 2800 kg/m^3,
# +-10 m/s
R, E, NU, RHO, V = 0.010, 48e9, 0.20, 2800.0, 20.0
GLASS_TOML = (f'name = "glass spheres"\n[body1]\nRx = {R}\nRy = {R}\nE = {E}\nnu = {NU}\n'
              f'[body2]\nRx = {R}\nRy = {R}\nE = {E}\nnu = {NU}\n')


def exact(mass=None, speed=V, e=E, nu=NU, radius=R):
    """(K, M, delta_max, F_max, t_c) of two equal spheres at 50 digits."""
    with mpmath.workdps(50):
        r = mpmath.mpf(radius) / 2
        e_star = mpmath.mpf(e) / (2 * (1 - mpmath.mpf(nu) ** 2))
        k = mpmath.mpf(4) / 3 * e_star * mpmath.sqrt(r)
        m = (mpmath.mpf(RHO) * 4 / 3 * mpmath.pi * mpmath.mpf(radius) ** 3 / 2
             if mass is None else mpmath.mpf(mass))
        v = mpmath.mpf(speed)
        dmax = (5 * m * v ** 2 / (4 * k)) ** (mpmath.mpf(2) / 5)
        fmax = k * dmax ** mpmath.mpf(1.5)
        tc = 2 * dmax / v * (mpmath.gamma(mpmath.mpf(7) / 5) * mpmath.gamma(mpmath.mpf(1) / 2)
                             / mpmath.gamma(mpmath.mpf(9) / 10))
        return tuple(float(x) for x in (k, m, dmax, fmax, tc))


K, M, DMAX, FMAX, TC = exact()


def integrate(k=K, mass=M, speed=V, steps=400, before=10, after=10, damping=0.0,
              cutoff=True):
    """A DEM-like record of the impact: rows every t_c / steps from ``before`` steps before
    the contact to ``after`` after it; the overlap is the (negative) gap outside the contact;
    M delta'' = -F integrated by DOP853 with F = K delta^1.5 + damping sqrt(K M)
    delta^(1/4) delta' (Tsuji's law; 0: elastic), cut off at 0 (``cutoff``)."""
    from scipy.integrate import solve_ivp

    def force(d, v):
        if d <= 0:
            return 0.0
        f = k * d ** 1.5 + damping * math.sqrt(k * mass) * d ** 0.25 * v
        return max(f, 0.0) if cutoff else f

    def rhs(_, y):
        return [y[1], -force(y[0], y[1]) / mass]

    def parted(_, y):
        return y[0] if y[1] < 0 else 1.0
    parted.terminal, parted.direction = True, -1
    tc_guess = 2.943 * (5 * mass * speed ** 2 / (4 * k)) ** 0.4 / speed
    sol = solve_ivp(rhs, (0, 3 * tc_guess), [0.0, speed], method="DOP853", rtol=1e-12,
                    atol=1e-20, dense_output=True, events=parted)
    tc = float(sol.t_events[0][0])
    v_out = float(sol.y_events[0][0][1])
    dt = tc_guess / steps
    t = np.arange(-before, int(tc / dt) + after + 1) * dt + 0.37 * dt  # off the grid
    d = np.empty_like(t)
    v = np.empty_like(t)
    for j, tj in enumerate(t):
        if tj < 0:
            d[j], v[j] = speed * tj, speed
        elif tj > tc:
            d[j], v[j] = v_out * (tj - tc), v_out
        else:
            d[j], v[j] = sol.sol(tj)
    f = np.array([force(a, b) if 0 <= tj <= tc else 0.0 for a, b, tj in zip(d, v, t, strict=True)])
    return t, d, f, v, tc, v_out


def write(path: Path, columns: dict, header=None, sep=",") -> Path:
    names = list(columns)
    rows = np.column_stack([np.asarray(columns[n], dtype=float) for n in names])
    lines = [sep.join(header or names)] + [sep.join(repr(float(x)) for x in row) for row in rows]
    path.write_text("\n".join(lines) + "\n")
    return path


def grade(argv) -> int:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        status = grade_cli.main([str(a) for a in argv])
    assert [f"{w.category.__name__}: {w.message}" for w in caught] == []
    return status


@pytest.fixture(scope="module")
def record():
    return integrate()


@pytest.fixture
def scene(tmp_path):
    p = tmp_path / "glass.toml"
    p.write_text(GLASS_TOML)
    return p


def cli(tmp_path, scene, csv, *extra, mass=M, speed=V):
    return grade(["--impact", csv, "--scene", scene, "--mass", repr(mass), "--speed",
                  repr(speed), "--out", tmp_path / "out", *extra])


# --- the references ---------------------------------------------------------------------

def test_chung_ooi_test1_published():
    """Chung & Ooi (2011), Test 1, glass: delta_max 274.11 um, F_max 10.697 kN, t_c 40.34 us
    (the published digits), from the closed form and from the scene's bodies."""
    assert round(DMAX * 1e6, 2) == 274.11
    assert round(FMAX / 1e3, 3) == 10.697
    assert round(TC * 1e6, 2) == 40.34


def test_reference_against_mpmath(tmp_path, scene):
    """The grader's reference for the glass spheres, whichever way hertz gives it, is
    Hertz's impact at 50 digits to 1e-12."""
    ref = impact_reference(scene_from_toml(scene), M, V)
    assert ref.restitution == 1.0
    for got, want in ((ref.max_approach, DMAX), (ref.max_force, FMAX), (ref.duration, TC)):
        assert got == pytest.approx(want, rel=1e-12)
    closed = hertz_closed_form(K, M, V)
    for got, want in ((closed.max_approach, DMAX), (closed.max_force, FMAX),
                      (closed.duration, TC)):
        assert got == pytest.approx(want, rel=1e-13)


def test_history_against_integration(record):
    """The reference's F(t) against DOP853's integration of M delta'' = -K delta^1.5."""
    t, d, f, _, tc, v_out = record
    assert tc == pytest.approx(TC, rel=1e-9)
    assert -v_out == pytest.approx(V, rel=1e-9)
    ref = hertz_closed_form(K, M, V)
    assert np.abs(ref.force_of_time(t) - f).max() < 1e-7 * FMAX


# --- elastic runs pass, the linear spring fails ------------------------------------------

def test_elastic_run_passes(tmp_path, scene, record, capsys):
    t, d, f, *_ = record
    csv = write(tmp_path / "run.csv", {"t_s": t, "overlap_m": d, "normal_force_N": f})
    assert cli(tmp_path, scene, csv) == 0
    out = capsys.readouterr()
    assert out.err == "" and out.out.startswith("PASSED")
    g = json.loads((tmp_path / "out" / "grade.json").read_text())
    for key in ("max_overlap_rel_err", "max_force_rel_err", "duration_rel_err",
                "restitution_err", "force_overlap_rms", "force_time_rms", "passed"):
        assert key in g
    assert g["passed"] is True
    # the duration found from the sampled force record is within far less than a step
    assert abs(g["duration_rel_err"]) < 0.05 * (TC / 400) / TC
    assert abs(g["restitution_err"]) < 1e-9
    assert {c["name"] for c in g["checks"]} >= {"max_overlap_rel_err", "duration_rel_err"}
    assert all(c["tolerance_basis"] for c in g["checks"] if c["tolerance"] is not None)
    assert (tmp_path / "out" / "grade.png").stat().st_size > 10_000
    assert "tolerance from" in (tmp_path / "out" / "grade.md").read_text()


def test_linear_spring_fails(tmp_path, scene, capsys):
    """A linear spring-dashpot (no dashpot: e = 1) tuned to Hertz's F_max: x(t) = V/w
    sin(w t), k = F_max^2 / (M V^2); its overlap is 0.8 delta_max and t_c 0.85 Hertz's."""
    k = FMAX ** 2 / (M * V * V)
    w = math.sqrt(k / M)
    dt = TC / 400
    t = np.arange(-10, int(math.pi / w / dt) + 11) * dt + 0.37 * dt
    x = V / w * np.sin(w * np.clip(t, 0, math.pi / w))
    x = np.where(t < 0, V * t, np.where(t > math.pi / w, -V * (t - math.pi / w), x))
    f = np.where((t > 0) & (t < math.pi / w), k * x, 0.0)
    assert f.max() == pytest.approx(FMAX, rel=1e-4)
    csv = write(tmp_path / "linear.csv", {"t": t, "overlap": x, "normal_force": f})
    assert cli(tmp_path, scene, csv) == 1
    assert capsys.readouterr().out.startswith("FAILED")
    g = json.loads((tmp_path / "out" / "grade.json").read_text())
    failed = {c["name"] for c in g["checks"] if c["pass"] is False}
    assert {"max_overlap_rel_err", "duration_rel_err", "force_overlap_rms",
            "force_time_rms"} <= failed
    assert g["max_overlap_rel_err"] == pytest.approx(-0.2, abs=2e-3)


@pytest.mark.parametrize("what, metric", [
    ("overlap", "max_overlap_rel_err"), ("force", "max_force_rel_err"),
    ("time", "duration_rel_err"), ("rebound", "restitution_err"),
    ("speed", "impact_speed_rel_err"), ("law", "force_overlap_rms")])
def test_a_one_percent_error_fails(record, what, metric):
    """Each tolerance is tight enough that a deliberate 1-2% error fails it."""
    t, d, f, *_ = record
    t, d, f = t.copy(), d.copy(), f.copy()
    if what == "overlap":
        d *= 1.015
    elif what == "force":
        f *= 1.015
    elif what == "time":
        t *= 1.015
    elif what == "rebound":
        after = t > TC
        d[after] = d[after] * 0.98
    elif what == "speed":
        t /= 1.015
        d = d.copy()
    elif what == "law":
        f = f * (1 + 0.03 * (d / DMAX - 0.5))
    ok = grade_impact(ImpactTrajectory(t, d, f), hertz_closed_form(K, M, V), mass=M, speed=V)
    assert ok.check(metric).status == "fail", (what, ok.check(metric))
    base = grade_impact(ImpactTrajectory(*record[:3]), hertz_closed_form(K, M, V), mass=M,
                        speed=V)
    assert base.check(metric).status == "pass"


def test_coarse_sampling_widens_the_tolerances(record):
    """Tolerances follow the output step: every 8th row of the record still passes; the
    peak bound and the duration's dt / t_c are what the grade states."""
    t, d, f, *_ = record
    g = grade_impact(ImpactTrajectory(t[::8], d[::8], f[::8]), hertz_closed_form(K, M, V),
                     mass=M, speed=V)
    assert g.passed, g.failed
    dt = 8 * TC / 400 * 2.943 / (TC * V / DMAX)
    assert g.check("duration_rel_err").tolerance == pytest.approx(1e-3 + dt / TC, rel=1e-2)
    bound = FMAX * dt * dt / (8 * M * DMAX)
    assert g.check("max_overlap_rel_err").tolerance == pytest.approx(1e-3 + bound, rel=1e-2)


def test_clipped_overlap_and_velocity_column(tmp_path, record):
    """Restitution from the overlap's slope inside the contact where the code writes 0
    outside it (bounded by the force there), and from a v_n column."""
    t, d, f, v, *_ = record
    clipped = np.clip(d, 0, None)
    g = grade_impact(ImpactTrajectory(t, clipped, f), hertz_closed_form(K, M, V), mass=M,
                     speed=V)
    assert g.passed, g.failed
    assert "first two rows in contact" in g.measured["restitution_method"]
    g = grade_impact(ImpactTrajectory(t, clipped, f, v_n=-v), hertz_closed_form(K, M, V),
                     mass=M, speed=V)
    assert g.measured["restitution"] == pytest.approx(1.0, abs=1e-9)
    assert "v_n column" in g.measured["restitution_method"]


def test_reader_spreadsheet_csv(tmp_path, record):
    """A byte-order mark, comment lines, ';' separators and decimal commas, units in the
    names (mm)."""
    t, d, f, *_ = record
    rows = "\n".join(f"{float(a)!r};{float(b) * 1e3!r};{float(c)!r}".replace(".", ",")
                     for a, b, c in zip(t, d, f, strict=True))
    p = tmp_path / "excel.csv"
    p.write_text("\ufeff# a LAMMPS run\n# units = mm\nTime [s];Overlap [mm];Fn\n" + rows + "\n",
                 encoding="utf-8")
    r = read_impact(p)
    assert r.details["units"] == "mm"
    np.testing.assert_allclose(r.overlap, d, rtol=1e-15, atol=1e-300)


# --- bad input: exit 2 with one line ------------------------------------------------------

def one_line(capsys, *words):
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    for w in words:
        assert w in err, (w, err)


@pytest.mark.parametrize("name, text, words", [
    ("empty", "", ["no header row"]),
    ("header only", "t,overlap,normal_force\n", ["no header row and data rows"]),
    ("missing column", "t,overlap\n0,0\n1,1\n2,0\n", ["no normal_force column"]),
    ("nan", "t,overlap,normal_force\n0,-1e-6,0\n1e-6,1e-6,nan\n2e-6,-1e-6,0\n",
     ["non-finite", "line 3"]),
    ("t back", "t,overlap,normal_force\n0,-1e-6,0\n2e-6,1e-6,1\n1e-6,-1e-6,0\n",
     ["increase strictly", "line 4"]),
    ("no contact", "t,overlap,normal_force\n0,-2e-6,0\n1e-6,-1e-6,0\n2e-6,-1e-6,0\n",
     ["holds no contact"]),
    ("starts in contact", "t,overlap,normal_force\n0,1e-6,1\n1e-6,2e-6,2\n2e-6,-1e-6,0\n",
     ["starts in contact"]),
    ("few rows", "t,overlap,normal_force\n0,-1e-6,0\n1e-6,1e-6,1\n2e-6,-1e-6,0\n",
     ["only 1 row(s) in contact"]),
    ("oblique part", "t,overlap,normal_force,v_t\n0,-1e-6,0,1\n1e-6,1e-6,1,1\n2e-6,-1e-6,0,1\n",
     ["needs all of", "omega"]),
    ("bad unit", "t [ms],overlap,normal_force\n0,-1e-6,0\n1,1e-6,1\n2,-1e-6,0\n",
     ["'ms'"]),
])
def test_malformed_trajectory(tmp_path, scene, capsys, name, text, words):
    p = tmp_path / "bad.csv"
    p.write_text(text)
    assert cli(tmp_path, scene, p) == 2
    one_line(capsys, *words)


@pytest.mark.parametrize("argv, words", [
    (["--mass", "-1"], ["--mass", "> 0"]),
    (["--speed", "nan"], ["--speed"]),
    (["--damping", "tsuji"], ["LAW:VALUE"]),
    (["--angle-deg", "95", "--mu", "0.1"], ["--angle-deg"]),
    (["--tolerance", "nonsense=1"], ["unknown metric"]),
    (["--damping-attractive"], ["--damping"]),
    (["--damping", "lammps_tsuji:1.5"], ["lammps_tsuji", "(0, 1]", "1.5"]),
    (["--damping", "tsuij:0.5"], ["unknown law", "'tsuij'", "lammps_tsuji_sqrt2"]),
])
def test_bad_options(tmp_path, scene, record, capsys, argv, words):
    t, d, f, *_ = record
    csv = write(tmp_path / "run.csv", {"t": t, "overlap": d, "normal_force": f})
    assert grade(["--impact", csv, "--scene", scene, "--mass", repr(M), "--speed", "20",
                  "--out", tmp_path / "out", *argv]) == 2
    one_line(capsys, *words)


def test_missing_mass_and_other_modes(tmp_path, scene, record, capsys):
    t, d, f, *_ = record
    csv = write(tmp_path / "run.csv", {"t": t, "overlap": d, "normal_force": f})
    assert grade(["--impact", csv, "--scene", scene, "--speed", "20", "--out",
                  tmp_path / "o"]) == 2
    one_line(capsys, "--mass")
    assert grade(["--impact", csv, "--force-approach", csv, "--scene", scene, "--mass", "1",
                  "--speed", "20", "--out", tmp_path / "o"]) == 2
    one_line(capsys, "--force-approach")


def test_huge_file(tmp_path, scene, capsys):
    """A file over the size cap is refused before it is read (a sparse file: instant)."""
    p = tmp_path / "huge.csv"
    with open(p, "wb") as fh:
        fh.truncate(MAX_BYTES + 1)
    assert cli(tmp_path, scene, p) == 2
    one_line(capsys, "bytes", str(MAX_BYTES))
    os.remove(p)


def test_row_cap(tmp_path, scene, capsys, monkeypatch):
    """More rows than the CSV reader's cap: one line, not a memory blow-up."""
    monkeypatch.setattr(csv_file, "MAX_ROWS", 50)
    p = write(tmp_path / "long.csv", {"t": np.arange(60.0), "overlap": np.zeros(60),
                                      "normal_force": np.zeros(60)})
    assert cli(tmp_path, scene, p) == 2
    one_line(capsys, "more than 50 data rows")


def test_trajectory_type_validates():
    with pytest.raises(ResultError, match="3 or more rows"):
        ImpactTrajectory([0.0, 1.0], [0.0, 1.0], [0.0, 1.0])
    with pytest.raises(ResultError, match="'overlap' has 2 values"):
        ImpactTrajectory([0.0, 1.0, 2.0], [0.0, 1.0], [0.0, 1.0, 0.0])
    with pytest.raises(ValueError, match="mass"):
        grade_impact(ImpactTrajectory([0.0, 1.0, 2.0], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0]),
                     hertz_closed_form(K, M, V), mass=-1.0, speed=V)


# --- a damped contact: graded against its own law's restitution ---------------------------

@pytest.mark.parametrize("alpha_run, passes", [(0.5, True), (0.55, False)])
def test_damped_tsuji(tmp_path, scene, capsys, alpha_run, passes):
    """Tsuji's law F = K delta^1.5 + alpha sqrt(M K) delta^(1/4) delta', cut off at 0,
    integrated here by DOP853, graded with --damping tsuji:0.5: the run with alpha 0.5
    passes, one with alpha 0.55 fails on the restitution."""
    import hertz

    if not hasattr(hertz, "damped_impact") and not hasattr(hertz, "restitution"):
        pytest.skip("this hertz has no damped impact yet")
    t, d, f, *_ = integrate(damping=alpha_run)
    csv = write(tmp_path / "damped.csv", {"t": t, "overlap": d, "normal_force": f})
    assert cli(tmp_path, scene, csv, "--damping", "tsuji:0.5") == (0 if passes else 1)
    g = json.loads((tmp_path / "out" / "grade.json").read_text())
    assert g["reference"]["restitution"] < 0.9
    status = {c["name"]: c["status"] for c in g["checks"]}
    assert status["force_overlap_rms"] == "not available"
    assert status["restitution_err"] == ("pass" if passes else "fail")


# --- oblique, gross slip: Coulomb's rigid-body impulse is exact there --------------------

ALUMINA_TOML = ('name = "alumina on a rigid plane"\n[body1]\nRx = 0.0025\nRy = 0.0025\n'
                'E = 380e9\nnu = 0.23\n[body2]\nRx = "inf"\nRy = "inf"\nE = "inf"\nnu = 0.23\n')


def oblique_record(mu, theta_deg, mu_run=None, steps=400):
    """Chung & Ooi Test 4 (alumina ball, R 2.5 mm, on a rigid plane, |v| 3.9 m/s), in gross
    slip: Q = -mu P throughout, so the centre's v_t loses mu J / m and the spin gains
    R mu J / I (J the normal impulse), independently of any partial-slip theory."""
    radius, e_mod, nu, rho = 0.0025, 380e9, 0.23, 4000.0
    m = rho * 4 / 3 * math.pi * radius ** 3
    inertia = 0.4 * m * radius ** 2
    k = 4 / 3 * e_mod / (1 - nu ** 2) * math.sqrt(radius)
    theta = math.radians(theta_deg)
    vn, vt0 = 3.9 * math.cos(theta), 3.9 * math.sin(theta)
    t, d, f, v, tc, _ = integrate(k=k, mass=m, speed=vn, steps=steps)
    dt = np.diff(t, prepend=t[0])
    impulse = np.cumsum(0.5 * (f + np.roll(f, 1)) * dt)  # trapezoid of P dt
    q = -(mu_run or mu) * f
    v_t = vt0 - (mu_run or mu) * impulse / m
    omega = radius * (mu_run or mu) * impulse / inertia
    return m, vn, {"t": t, "overlap": d, "normal_force": f, "tangential_force": q,
                   "v_t": v_t, "omega": omega}


@pytest.mark.parametrize("mu_run, passes", [(0.092, True), (0.094, False)])
def test_oblique_gross_slip(tmp_path, capsys, mu_run, passes):
    import hertz

    try:
        from hertz import oblique_impact  # noqa: F401
    except ImportError:
        pytest.importorskip("hertz._oblique")
    scene = tmp_path / "alumina.toml"
    scene.write_text(ALUMINA_TOML)
    m, vn, cols = oblique_record(0.092, 45.0, mu_run)
    csv = write(tmp_path / "oblique.csv", cols)
    status = cli(tmp_path, scene, csv, "--mu", "0.092", "--angle-deg", "45", mass=m, speed=vn)
    assert status == (0 if passes else 1), capsys.readouterr()
    g = json.loads((tmp_path / "out" / "grade.json").read_text())
    st = {c["name"]: c["status"] for c in g["checks"]}
    for name in ("tangential_restitution_err", "rebound_angle_err_deg", "spin_rel_err"):
        assert st[name] == ("pass" if passes else "fail"), (name, st)
    assert g["reference"]["oblique"]["gross_slip"] is True
    # Coulomb: the contact point loses 7 mu V_n (2 mu V_n (1 + m R^2 / I))
    e_t = (3.9 * math.sin(math.radians(45)) - 7 * 0.092 * vn) / (3.9 * math.sin(math.radians(45)))
    assert g["reference"]["oblique"]["tangential_restitution"] == pytest.approx(e_t, rel=1e-9)
    assert hertz is not None


# --- the Chung & Ooi scenes and the page's tables -----------------------------------------

ROOT = Path(__file__).resolve().parents[1]


def chung_ooi():
    import importlib.util

    spec = importlib.util.spec_from_file_location("chung_ooi_table",
                                                  ROOT / "tools" / "chung_ooi_table.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules.setdefault("chung_ooi_table", mod)  # its dataclasses look themselves up
    spec.loader.exec_module(mod)
    return sys.modules["chung_ooi_table"]


def test_chung_ooi_page_and_scenes_are_the_scripts_output():
    """docs/howto/dem-impacts.md's tables and scenes/chung-ooi/*.toml are what
    tools/chung_ooi_table.py writes (rerun it with --write-page --write-scenes)."""
    tool = chung_ooi()
    for case in tool.CASES:
        path = tool.SCENES / f"{case.slug}.toml"
        assert path.read_text() == tool.scene_toml(case), path
    assert tool.page_block(tool.PAGE.read_text()) == tool.tables()


def test_chung_ooi_scenes_against_mpmath():
    """Each scene read as fem_validation reads it, at the script's mass and speed: the
    grader's reference against Hertz's impact at 50 digits (E* and R* of the two bodies,
    the rigid plane adding nothing)."""
    import hertz

    tool = chung_ooi()
    for case in tool.CASES:
        e, nu, _ = tool.MATERIALS[case.material]
        with mpmath.workdps(50):
            one = (1 - mpmath.mpf(nu) ** 2) / mpmath.mpf(e)
            e_star = 1 / (one if case.other == "wall" else 2 * one)
            r1 = mpmath.mpf(case.radius)
            r_star = {"wall": r1, "sphere": r1 / 2,
                      "sphere5": 1 / (1 / r1 + 1 / mpmath.mpf(case.radius2))}[case.other]
            k = mpmath.mpf(4) / 3 * e_star * mpmath.sqrt(r_star)
            dmax = (5 * mpmath.mpf(case.mass) * mpmath.mpf(case.speed) ** 2 / (4 * k)) ** 0.4
            fmax = k * dmax ** mpmath.mpf(1.5)
            tc = 2 * dmax / mpmath.mpf(case.speed) * (
                mpmath.gamma(mpmath.mpf(7) / 5) * mpmath.sqrt(mpmath.pi)
                / mpmath.gamma(mpmath.mpf(9) / 10))
        with warnings.catch_warnings():  # the scene's check at 1 N: a/R 1.8 for Test 5
            warnings.simplefilter("ignore", hertz.HertzValidityWarning)
            scene = scene_from_toml(tool.SCENES / f"{case.slug}.toml")
        ref = impact_reference(scene, case.mass, case.speed)
        assert ref.max_approach == pytest.approx(float(dmax), rel=1e-12), case.slug
        assert ref.max_force == pytest.approx(float(fmax), rel=1e-12), case.slug
        assert ref.duration == pytest.approx(float(tc), rel=1e-12), case.slug


def test_damped_attractive(tmp_path, scene, capsys):
    """Tsuji's law not cut off: the damping pulls at the end until the overlap returns to
    0; graded with --damping-attractive against hertz's cutoff=False, it passes, and
    against the cut-off law (its duration and restitution) it fails."""
    import hertz

    if not hasattr(hertz, "damped_impact"):
        pytest.skip("this hertz has no damped impact yet")
    t, d, f, *_ = integrate(damping=0.5, cutoff=False)
    assert f.min() < 0
    csv = write(tmp_path / "pull.csv", {"t": t, "overlap": d, "normal_force": f})
    assert cli(tmp_path, scene, csv, "--damping", "tsuji:0.5", "--damping-attractive") == 0
    assert cli(tmp_path, scene, csv, "--damping", "tsuji:0.5") == 1


def test_unit_hint(record):
    """An overlap written in mm and read as m fails with the likely cause named."""
    t, d, f, *_ = record
    g = grade_impact(ImpactTrajectory(t, d * 1e3, f), hertz_closed_form(K, M, V), mass=M,
                     speed=V)
    assert not g.passed
    assert "mm" in g.hint and "1e+3" in g.hint
    assert g.summary.startswith("FAILED") and g.hint in g.summary


# --- LAMMPS's damping keywords, and a damping that pulls (found running LAMMPS) ----------

#: Tsuji's alpha(e) as LAMMPS's src/GRANULAR/gran_sub_mod_damping.cpp writes it (Marshall
#: 2009, eq. 53), copied here from LAMMPS, not from the grader.
LAMMPS_POLY = (1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218)


def lammps_tsuji(e, factor=1.0, limit=False, k=K, mass=M, speed=V):
    """(restitution, duration) of LAMMPS's ``damping tsuji e`` integrated here by DOP853
    at rtol 1e-12 in its own dimensional form: F = F_n + alpha sqrt(m_eff F_n / delta)
    delta', F_n = K delta^1.5, alpha = factor poly(e); ``limit``: ``limit_damping`` (F
    cut off at 0: the bodies part where it reaches 0), else until the overlap is 0."""
    from scipy.integrate import solve_ivp

    alpha = factor * sum(c * e ** i for i, c in enumerate(LAMMPS_POLY))

    def total(d, v):
        if d <= 0:
            return 0.0
        fn = k * d ** 1.5
        return fn + alpha * math.sqrt(mass * fn / d) * v

    def rhs(_, y):
        f = total(y[0], y[1])
        return [y[1], -(max(f, 0.0) if limit else f) / mass]

    def ends(_, y):
        if y[1] >= 0:
            return 1.0
        return total(y[0], y[1]) if limit else y[0]

    ends.terminal, ends.direction = True, -1
    tc = 3 * (5 * mass * speed ** 2 / (4 * k)) ** 0.4 / speed
    s = solve_ivp(rhs, (0, 3 * tc), [0.0, speed], method="DOP853", rtol=1e-12, atol=1e-20,
                  events=ends)
    return -float(s.y_events[0][0][1]) / speed, float(s.t_events[0][0])


@pytest.mark.parametrize("law, factor", [("lammps_tsuji", 1.0),
                                         ("lammps_tsuji_sqrt2", math.sqrt(2.0))])
@pytest.mark.parametrize("cutoff", [True, False])
def test_lammps_tsuji_against_lammps_own_force_law(scene, law, factor, cutoff):
    """--damping lammps_tsuji:E is LAMMPS's (22 Jul 2025) damping tsuji E, alpha = poly(E);
    lammps_tsuji_sqrt2:E the development sources' sqrt(2) poly(E): restitution and
    duration against LAMMPS's force law integrated here (observed: 1.35e-11, 4.5e-12)."""
    import hertz

    if not hasattr(hertz, "damped_impact"):
        pytest.skip("this hertz has no damped impact yet")
    e, tc = lammps_tsuji(0.8, factor, limit=cutoff)
    ref = impact_reference(scene_from_toml(scene), M, V, damping=f"{law}:0.8", cutoff=cutoff)
    assert ref.restitution - e == pytest.approx(0, abs=2e-11)
    assert ref.duration / tc - 1 == pytest.approx(0, abs=7e-12)
    assert ref.attractive is (not cutoff)
    if law == "lammps_tsuji" and not cutoff:
        # lmp 22 Jul 2025 (update 4), damping tsuji 0.8 without limit_damping, two
        # aluminium spheres at 1 m/s, t_c / 2000 steps: free-flight e = 0.85338384
        assert e == pytest.approx(0.85338384, abs=2e-6)


def pulling_record(alpha=0.5, steps=400, before=10, after=10):
    """Tsuji's law not cut off, integrated by DOP853 (rtol 1e-12): rows every t_c / steps,
    one of them exactly where the force changes sign on the way out, the force written in
    fixed point (six decimals), as a code printing ``%f`` does, so that it reads 0 there.
    Returns the columns, the time of the force's zero, the overlap's zero (the contact's
    end), the speed out and the step."""
    from scipy.integrate import solve_ivp

    def force(d, v):
        return K * d ** 1.5 + alpha * math.sqrt(K * M) * d ** 0.25 * v if d > 0 else 0.0

    def rhs(_, y):
        return [y[1], -force(y[0], y[1]) / M]

    def pulls(_, y):
        return force(y[0], y[1]) if y[1] < 0 else 1.0

    def parted(_, y):
        return y[0] if y[1] < 0 else 1.0

    pulls.direction = -1
    parted.terminal, parted.direction = True, -1
    sol = solve_ivp(rhs, (0, 3 * TC), [0.0, V], method="DOP853", rtol=1e-12, atol=1e-20,
                    dense_output=True, events=[pulls, parted])
    t_zero, t_end = float(sol.t_events[0][0]), float(sol.t_events[1][0])
    v_out = float(sol.y_events[1][0][1])
    dt = TC / steps
    t = t_zero + dt * np.arange(-int(t_zero / dt) - before, int((t_end - t_zero) / dt)
                                + after + 1)
    d = np.array([V * x if x < 0 else v_out * (x - t_end) if x > t_end else sol.sol(x)[0]
                  for x in t])
    v = np.array([V if x < 0 else v_out if x > t_end else sol.sol(x)[1] for x in t])
    f = np.array([float(f"{force(a, b):.6f}") for a, b in zip(d, v, strict=True)])
    return {"t": t, "overlap": d, "normal_force": f}, t_zero, t_end, v_out, dt


def test_attractive_contact_ends_where_the_overlap_returns_to_zero(tmp_path, scene):
    """With --damping-attractive the contact lasts until the overlap is back at 0 (not to
    the force's first zero, here a row written as 0) and the restitution is the speed of
    the free flight after it: against the integration's own end and speed."""
    import hertz

    if not hasattr(hertz, "damped_impact"):
        pytest.skip("this hertz has no damped impact yet")
    columns, t_zero, t_end, v_out, dt = pulling_record()
    t, f = columns["t"], columns["normal_force"]
    k = int(np.argmin(np.abs(t - t_zero)))
    assert f[k] == 0 and f[k + 1] < 0             # the row at the sign change reads 0
    csv = write(tmp_path / "pull.csv", columns)
    assert cli(tmp_path, scene, csv, "--damping", "tsuji:0.5", "--damping-attractive") == 0
    g = json.loads((tmp_path / "out" / "grade.json").read_text())
    m = g["measured"]
    assert m["attractive"] and m["end_method"] == "the overlap's zero, interpolated"
    assert (m["t_end"] - t_end) / dt == pytest.approx(0, abs=5e-6)   # observed 3.2e-6
    assert m["restitution"] == pytest.approx(-v_out / V, abs=1e-9)    # free flight: exact
    # the contact measured as a cut-off one ends at that row, and fails
    assert cli(tmp_path, scene, csv, "--damping", "tsuji:0.5") == 1
    g = json.loads((tmp_path / "out" / "grade.json").read_text())
    assert g["measured"]["t_end"] < t_zero + dt and not g["measured"]["attractive"]
    # from Python the measure follows the reference (cutoff=False: attractive)
    ref = impact_reference(scene_from_toml(scene), M, V, damping="tsuji:0.5", cutoff=False)
    r = ImpactTrajectory(t, columns["overlap"], f)
    assert grade_impact(r, ref, mass=M, speed=V).passed
    forced = grade_impact(r, ref, mass=M, speed=V, attractive=False)
    assert not forced.passed and any("compare different contacts" in n for n in forced.notes)
