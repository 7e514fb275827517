"""The Chung & Ooi (2011) DEM benchmark tests as hertz scenes, and this library's reference
quantities for them, for docs/howto/dem-impacts.md.

    python tools/chung_ooi_table.py                 # print the page's tables (Markdown)
    python tools/chung_ooi_table.py --write-scenes  # (re)write scenes/chung-ooi/*.toml
    python tools/chung_ooi_table.py --check         # exit 1 if the page or a scene differs

The inputs (materials, radii, speeds) are those of the paper's Tests 1-8 as the DEM codes'
own benchmark scripts state them (Yade's scripts for Tests 1-4; PySPH's for Tests 5-8,
not checked against the paper: see the page).  The reference quantities come from
``hertz.impact`` (delta_max, F_max, t_c of the elastic normal impact), ``hertz``'s damping
coefficient for a target restitution (Test 3) and ``hertz.oblique_impact`` (Test 4):
nothing on the page is typed by hand.  tests/test_grade_impact.py checks that the page's
tables and the scene files are what this script writes.
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:  # run from a checkout: its hertz
    sys.path.insert(0, str(ROOT))
PAGE = ROOT / "docs" / "howto" / "dem-impacts.md"
SCENES = ROOT / "scenes" / "chung-ooi"
BEGIN, END = "<!-- chung-ooi tables: begin (tools/chung_ooi_table.py) -->", \
    "<!-- chung-ooi tables: end -->"

#: name -> (E [Pa], nu, density [kg/m^3])
MATERIALS = {
    "glass": (4.8e10, 0.20, 2800.0),
    "limestone": (2.0e10, 0.25, 2500.0),
    "aluminium alloy (Test 2)": (7.0e10, 0.30, 2699.0),
    "magnesium alloy": (4.0e10, 0.35, 1800.0),
    "alumina": (3.8e11, 0.23, 4000.0),
    "cast iron": (1.0e11, 0.25, 7000.0),
    "aluminium alloy": (7.0e10, 0.33, 2700.0),
    "steel": (2.08e11, 0.30, 7850.0),
    "polyethylene": (1.0e9, 0.40, 1400.0),
    "copper": (1.2e11, 0.35, 8900.0),
    "nylon": (2.5e9, 0.40, 1000.0),
}


@dataclass(frozen=True)
class Case:
    """One material of one test: body 1 a sphere of radius ``radius``; body 2 the same
    sphere (``"sphere"``), a rigid plane (``"wall"``) or a sphere ``radius2`` of the same
    material and ``density2_factor`` times the density; ``speed`` the relative normal
    approach speed [m/s]."""

    test: int
    material: str
    radius: float
    other: str
    speed: float
    what: str
    radius2: float = math.nan
    density2_factor: float = 1.0

    @property
    def label(self) -> str:
        """The material's name as printed."""
        return self.material.split(" (")[0]

    @property
    def slug(self) -> str:
        return f"test{self.test}-{self.label.replace(' ', '-')}"

    @property
    def mass(self) -> float:
        """The reduced mass [kg]."""
        rho = MATERIALS[self.material][2]
        m1 = rho * 4.0 / 3.0 * math.pi * self.radius ** 3
        if self.other == "wall":
            return m1
        r2 = self.radius if self.other == "sphere" else self.radius2
        m2 = self.density2_factor * rho * 4.0 / 3.0 * math.pi * r2 ** 3
        return m1 * m2 / (m1 + m2)


CASES = (
    Case(1, "glass", 0.010, "sphere", 20.0, "two spheres head-on at +-10 m/s"),
    Case(1, "limestone", 0.010, "sphere", 20.0, "two spheres head-on at +-10 m/s"),
    Case(2, "aluminium alloy (Test 2)", 0.10, "wall", 0.2, "a sphere on a rigid plane"),
    Case(2, "magnesium alloy", 0.10, "wall", 0.2, "a sphere on a rigid plane"),
    Case(3, "alumina", 0.0025, "wall", 3.9, "a sphere on a rigid plane, e = 0.2 to 1"),
    Case(3, "cast iron", 0.0025, "wall", 3.9, "a sphere on a rigid plane, e = 0.2 to 1"),
    Case(4, "alumina", 0.0025, "wall", 3.9, "oblique, |v| 3.9 m/s, 5-85 deg, mu 0.092 "
                                            "(head-on row)"),
    Case(4, "aluminium alloy", 0.0025, "wall", 3.9, "oblique, |v| 3.9 m/s, 5-85 deg, mu 0.092 "
                                                    "(head-on row)"),
    Case(5, "steel", 1e-5, "wall", 5.0, "oblique, V_n 5 m/s, V_t 0.1-70 m/s, mu 0.3"),
    Case(5, "polyethylene", 1e-5, "wall", 5.0, "oblique, V_n 5 m/s, V_t 0.1-70 m/s, mu 0.3"),
    Case(6, "aluminium alloy", 0.10, "wall", 0.2, "V_n 0.2 m/s, spin 0.175-21 rad/s, mu 0.4"),
    Case(6, "nylon", 0.10, "wall", 0.2, "V_n 0.2 m/s, spin 0.175-21 rad/s, mu 0.4"),
    Case(7, "aluminium alloy", 0.10, "sphere", 0.4, "two spheres at +-0.2 m/s, spins "
                                                    "0.175-22 rad/s, mu 0.4"),
    Case(7, "copper", 0.10, "sphere", 0.4, "two spheres at +-0.2 m/s, spins 0.175-22 rad/s, "
                                           "mu 0.4"),
    Case(8, "aluminium alloy", 0.10, "sphere5", 0.2, "on a sphere of 5 R, 1000 x the "
                                                     "density, spins, mu 0.4",
         radius2=0.5, density2_factor=1000.0),
    Case(8, "nylon", 0.10, "sphere5", 0.2, "on a sphere of 5 R, 1000 x the density, spins, "
                                           "mu 0.4", radius2=0.5, density2_factor=1000.0),
)
#: Test 3's target restitutions; Test 4's incidences [deg] and friction.
TEST3_RESTITUTION = (0.2, 0.4, 0.6, 0.8, 1.0)
TEST4_ANGLES = (5, 15, 25, 35, 45, 55, 65, 75, 85)
TEST4_MU = 0.092
#: Test 5's tangential speeds [m/s] and friction; Test 6's spins before [rad/s] and friction
#: (a selection of the scripts' values).
TEST5_VT, TEST5_MU = (0.5, 1.0, 5.0, 10.0, 20.0, 40.0), 0.3
TEST6_SPIN, TEST6_MU = (0.175, 1.0, 3.0, 7.0, 12.0, 21.0), 0.4


def scene_toml(case: Case) -> str:
    """The scene file of a case (SI)."""
    e, nu, rho = MATERIALS[case.material]
    if case.other == "wall":
        body2 = f'Rx = "inf"\nRy = "inf"\nE = "inf"\nnu = {nu}\n'
    else:
        r2 = case.radius if case.other == "sphere" else case.radius2
        body2 = f"Rx = {r2!r}\nRy = {r2!r}\nE = {e:.6g}\nnu = {nu}\n"
    return (f"# Chung & Ooi (2011) Test {case.test}, {case.label}: {case.what}\n"
            f"# generated by tools/chung_ooi_table.py; grade a DEM run of it with\n"
            f"#   python -m fem_validation grade --impact RUN.csv \\\n"
            f"#       --scene scenes/chung-ooi/{case.slug}.toml \\\n"
            f"#       --mass {case.mass!r} --speed {case.speed!r} --out DIR\n"
            f"# density {rho} kg/m^3; reduced mass {case.mass!r} kg\n"
            f'name = "Chung & Ooi Test {case.test}, {case.label}"\n\n'
            f"[body1]\nRx = {case.radius!r}\nRy = {case.radius!r}\nE = {e:.6g}\nnu = {nu}\n\n"
            f"[body2]\n{body2}")


def bodies(case: Case):
    import hertz

    e, nu, _ = MATERIALS[case.material]
    ball = hertz.Body.sphere(case.radius, E=e, nu=nu)
    if case.other == "wall":
        return ball, hertz.Body.plane(E=math.inf, nu=nu)
    r2 = case.radius if case.other == "sphere" else case.radius2
    return ball, hertz.Body.sphere(r2, E=e, nu=nu)


def _g(x: float, digits: int = 6) -> str:
    return f"{x:.{digits}g}"


def normal_table() -> list[str]:
    import hertz

    rows = ["| test | material | E [Pa] | nu | density [kg/m^3] | R [m] | against | V [m/s] "
            "| M [kg] | delta_max [um] | F_max [N] | t_c [us] | e |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for c in CASES:
        e, nu, rho = MATERIALS[c.material]
        hit = hertz.impact(*bodies(c), speed=c.speed, mass=c.mass)
        against = {"wall": "rigid plane", "sphere": "same sphere",
                   "sphere5": f"sphere R {c.radius2:g} m"}[c.other]
        rows.append(f"| {c.test} | {c.label} | {_g(e, 3)} | {nu:g} | "
                    f"{rho:g} | {c.radius:g} | {against} | {c.speed:g} | {c.mass!r} | "
                    f"{_g(hit.max_approach * 1e6)} | {_g(hit.max_force)} | "
                    f"{_g(hit.duration * 1e6)} | {_g(hit.restitution, 3)} |")
    return rows


def damping_table() -> list[str]:
    from hertz._impact import damping_coefficient

    rows = ["| material | e | Tsuji alpha, force cut off at 0 | Tsuji alpha, attractive |",
            "|---|---|---|---|"]
    for c in (c for c in CASES if c.test == 3):
        for e in TEST3_RESTITUTION:
            cut, pull = (float(damping_coefficient(*bodies(c), c.speed, c.mass, "tsuji", e,
                                                   cutoff=k)) for k in (True, False))
            rows.append(f"| {c.material} | {e:g} | {_g(cut)} | {_g(pull)} |")
    return rows


def _oblique():
    import hertz

    found = getattr(hertz, "oblique_impact", None)
    if found is None:
        from hertz._oblique import oblique_impact as found
    return found


def _oblique_rows(case: Case, labels, speed, incidence, mu, spin=0.0) -> list[str]:
    """Rows of an oblique table: body 1 (a solid ball) on the fixed plane."""
    m = MATERIALS[case.material][2] * 4.0 / 3.0 * math.pi * case.radius ** 3
    r = _oblique()(*bodies(case), speed, incidence, m, mu, spin=spin)
    rows = []
    for k, label in enumerate(labels):
        rows.append(f"| {case.label} | {label} | {_g(float(r.tangential_restitution[k]), 5)} | "
                    f"{math.degrees(float(r.rebound_angle[k])):.3f} | "
                    f"{math.degrees(float(r.centre_rebound_angle[k])):.3f} | "
                    f"{_g(float(r.spin[k]), 5)} | "
                    f"{'yes' if bool(r.gross_slip[k]) else 'no'} |")
    return rows


def _oblique_header(what: str) -> list[str]:
    return [f"| material | {what} | tangential restitution (contact point) | rebound angle, "
            f"contact point [deg] | rebound angle, centre [deg] | spin after [rad/s] | gross "
            f"slip |", "|---|---|---|---|---|---|---|"]


def oblique_table() -> list[str]:
    """Test 4: |v| 3.9 m/s at incidences from 5 to 85 deg, no spin before."""
    import numpy as np

    rows = _oblique_header("incidence [deg]")
    theta = np.radians(np.array(TEST4_ANGLES, dtype=float))
    for c in (c for c in CASES if c.test == 4):
        rows += _oblique_rows(c, TEST4_ANGLES, c.speed, theta, TEST4_MU)
    return rows


def test5_table() -> list[str]:
    """Test 5: V_n 5 m/s, tangential speeds V_t, no spin before."""
    import numpy as np

    rows = _oblique_header("V_t [m/s]")
    vt = np.array(TEST5_VT)
    for c in (c for c in CASES if c.test == 5):
        rows += _oblique_rows(c, TEST5_VT, np.hypot(c.speed, vt), np.arctan2(vt, c.speed),
                              TEST5_MU)
    return rows


def test6_table() -> list[str]:
    """Test 6: V_n 0.2 m/s, no tangential speed, spins before."""
    import numpy as np

    rows = _oblique_header("spin before [rad/s]")
    w = np.array(TEST6_SPIN)
    for c in (c for c in CASES if c.test == 6):
        rows += _oblique_rows(c, TEST6_SPIN, c.speed, 0.0, TEST6_MU, spin=w)
    return rows


def tables() -> str:
    """The page's generated block (between :data:`BEGIN` and :data:`END`)."""
    import textwrap

    def prose(text):
        return textwrap.fill(text, width=90)

    lines = [BEGIN, "", "**The normal impact** (elastic; `hertz.impact`):", "",
             *normal_table(), "",
             prose("**Test 3**: the damping of Tsuji's law, F = K delta^1.5 + alpha sqrt(M K) "
                   "delta^(1/4) delta', that gives each restitution (the same for every "
                   "speed, mass and body; `hertz` damping coefficient, law `tsuji`):"), "",
             *damping_table(), "",
             prose(f"**Test 4**: oblique impact on the rigid plane, |v| 3.9 m/s, mu "
                   f"{TEST4_MU}, no spin before (`hertz.oblique_impact`; spin positive as "
                   f"topspin):"), "",
             *oblique_table(), "",
             prose(f"**Test 5**: oblique impact on the rigid plane at V_n 5 m/s and tangential "
                   f"speeds V_t, mu {TEST5_MU}, no spin before:"), "",
             *test5_table(), "",
             prose(f"**Test 6**: impact on the rigid plane at V_n 0.2 m/s, no tangential speed, "
                   f"spins before (positive as topspin), mu {TEST6_MU}:"), "",
             *test6_table(), "", END]
    return "\n".join(lines)


def page_block(text: str) -> str:
    """The generated block as the page holds it."""
    start, stop = text.index(BEGIN), text.index(END) + len(END)
    return text[start:stop]


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--write-scenes", action="store_true", help="write scenes/chung-ooi/")
    p.add_argument("--write-page", action="store_true", help="replace the page's tables")
    p.add_argument("--check", action="store_true", help="exit 1 where the page or a scene "
                                                        "differs from what this script writes")
    args = p.parse_args(argv)
    if args.write_scenes:
        SCENES.mkdir(parents=True, exist_ok=True)
        for c in CASES:
            (SCENES / f"{c.slug}.toml").write_text(scene_toml(c))
    block = tables()
    if args.write_page:
        text = PAGE.read_text()
        PAGE.write_text(text.replace(page_block(text), block))
    if args.check:
        bad = [str(SCENES / f"{c.slug}.toml") for c in CASES
               if not (SCENES / f"{c.slug}.toml").is_file()
               or (SCENES / f"{c.slug}.toml").read_text() != scene_toml(c)]
        if page_block(PAGE.read_text()) != block:
            bad.append(str(PAGE))
        if bad:
            print("differs from tools/chung_ooi_table.py: " + ", ".join(bad), file=sys.stderr)
            return 1
        return 0
    if not (args.write_scenes or args.write_page):
        print(block)
    return 0


if __name__ == "__main__":
    sys.exit(main())
