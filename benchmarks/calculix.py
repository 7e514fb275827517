"""CalculiX against Hertz: run benchmark decks in ccx and grade them, one row per run.

    python benchmarks/calculix.py --scene FILE.toml --out DIR [--levels 0 1]
                                  [--penalty-factors 10] [--slaves 1] [--threads 2]

For every combination of mesh level, penalty factor (slope over E*/h0) and
slave body: ``python -m fem_validation deck`` writes DIR/<run>/hertz.inp, ccx
runs it (wall-clock time measured around the ccx process, OMP_NUM_THREADS =
--threads), :func:`fem_validation.readers.calculix.read_calculix` reads the
.frd and :func:`fem_validation.grading.contact.grade` grades it with its default
tolerances.  Prints a markdown table (a, b, p0 from the p^2 fit; the profile
RMS along both axes; the von Mises maxima on the axis of each body; force,
nodes, Newton iterations, wall and CPU seconds of ccx) and writes DIR/calculix.json and
DIR/calculix.md.  Needs ccx on PATH (Debian: apt-get install calculix-ccx).
"""

from __future__ import annotations

import argparse
import itertools
import json
import os
import platform
import re
import resource
import shutil
import subprocess
import sys
import time
from pathlib import Path


def _cpu() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown processor"


def run_one(scene: Path, out: Path, level: int, penalty: float, slave: int,
            threads: int) -> dict:
    from fem_validation.decks import read_scene
    from fem_validation.grading.contact import grade
    from fem_validation.readers.calculix import read_calculix

    deck = [sys.executable, "-m", "fem_validation", "deck", "--scene", str(scene), "--format",
            "calculix", "--out", str(out), "--level", str(level), "--penalty-factor",
            str(penalty), "--slave", str(slave)]
    subprocess.run(deck, check=True, capture_output=True)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    run = subprocess.run([shutil.which("ccx"), "-i", "hertz"], cwd=out, env=env,
                         capture_output=True, text=True)
    seconds = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if run.returncode != 0 or "Job finished" not in run.stdout:
        raise RuntimeError(f"ccx failed in {out}: {run.stdout[-1500:]}")
    # hertz.sta: a header, then one line per increment: step, inc, attempts, iterations, ...
    last = (out / "hertz.sta").read_text().strip().splitlines()[-1].split()
    iterations = int(last[3]) if len(last) > 3 and last[3].isdigit() else None
    g = grade(read_calculix(out / "hertz.frd"), read_scene(scene))
    nodes = len(re.findall(r"^\d+, ", (out / "hertz.inp").read_text().split("*ELEMENT")[0],
                           flags=re.M))
    return {"level": level, "penalty_factor": penalty, "slave": slave, "nodes": nodes,
            "seconds": seconds, "cpu_seconds": cpu, "iterations": iterations, "force": g.force,
            "passed": g.passed, "failed": g.failed,
            **{k: g.metrics[k] for k in ("a_rel_err", "b_rel_err", "p0_rel_err", "rms_major",
                                         "rms_minor", "edge_a_rel_err", "a_moments_rel_err",
                                         "pressure_integral_rel_err", "approach_rel_err")},
            **{f"von_mises_rel_err_body{i}": g.stress.get(f"body{i}", {}).get(
                "von_mises_rel_err") for i in (1, 2)}}


def table(rows: list[dict]) -> str:
    head = ("| level | nodes | penalty [E*/h0] | slave | a | b | p0 | RMS major | RMS minor "
            "| VM max body 1 | VM max body 2 | approach | Newton its | ccx wall [s] "
            "| ccx CPU [s] | grade |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")

    def pct(x):
        return "n/a" if x is None else f"{100 * x:+.2f}%"

    return head + "\n".join(
        f"| {r['level']} | {r['nodes']} | {r['penalty_factor']:g} | {r['slave']} "
        f"| {pct(r['a_rel_err'])} | {pct(r['b_rel_err'])} | {pct(r['p0_rel_err'])} "
        f"| {100 * r['rms_major']:.1f}% | {100 * r['rms_minor']:.1f}% "
        f"| {pct(r['von_mises_rel_err_body1'])} | {pct(r['von_mises_rel_err_body2'])} "
        f"| {pct(r['approach_rel_err'])} | {r['iterations']} | {r['seconds']:.0f} "
        f"| {r['cpu_seconds']:.0f} "
        f"| {'pass' if r['passed'] else 'fail'} |" for r in rows) + "\n"


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scene", type=Path, required=True)
    p.add_argument("--out", type=Path, required=True)
    p.add_argument("--levels", type=int, nargs="+", default=[0, 1])
    p.add_argument("--penalty-factors", type=float, nargs="+", default=[10.0])
    p.add_argument("--slaves", type=int, nargs="+", default=[1])
    p.add_argument("--threads", type=int, default=2)
    args = p.parse_args()
    if shutil.which("ccx") is None:
        print("ccx not found (Debian: apt-get install calculix-ccx)", file=sys.stderr)
        return 2
    rows = []
    for level, penalty, slave in itertools.product(args.levels, args.penalty_factors,
                                                   args.slaves):
        out = args.out / f"level{level}_penalty{penalty:g}_slave{slave}"
        rows.append(run_one(args.scene, out, level, penalty, slave, args.threads))
        print(table(rows[-1:]).splitlines()[-1], flush=True)
    command = "python benchmarks/calculix.py " + " ".join(sys.argv[1:])
    load = os.getloadavg()[0]
    text = (f"CalculiX {_ccx_version()} on {_cpu()}, {args.threads} threads (load average "
            f"{load:.1f} at the end: wall times count other processes); errors are "
            f"(ccx - Hertz) / Hertz at the force each run reached; `{command}`.\n\n"
            + table(rows))
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / "calculix.md").write_text(text)
    (args.out / "calculix.json").write_text(json.dumps({"command": command, "rows": rows},
                                                       indent=1) + "\n")
    print(text)
    return 0


def _ccx_version() -> str:
    out = subprocess.run([shutil.which("ccx"), "-v"], capture_output=True, text=True).stdout
    m = re.search(r"Version\s+(\S+)", out)
    return m.group(1) if m else "(unknown version)"


if __name__ == "__main__":
    sys.exit(main())
