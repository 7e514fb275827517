"""The speed of every build a user gets: the checkout compiled the ways users compile it.

    python benchmarks/builds.py [--n 1000000] [--rounds 5] [--passes 3] [--docs]
                                [--only NAME ...]

Builds hertz._ufuncs from this checkout (``setup.py build_ext``, the same flags as ``pip
install``) into temporary folders, one per configuration:

* GCC with the running Python's flags (sysconfig's CFLAGS: ``-O3 -fwrapv`` for a
  python.org or pyenv build);
* GCC with ``-O2 -fno-strict-overflow``, what Debian's and Ubuntu's Python 3.12+ put in
  CFLAGS (so what ``pip install`` from source compiles with there);
* GCC with ``-O2``;
* Clang (the compiler of every Mac);
* ``HERTZ_PLAIN=1`` with GCC and with Clang: the plain C path, the code that macOS, Windows
  (MSVC) and aarch64 compile.

Each build is loaded in a fresh process as hertz._ufuncs (under the checkout's Python
package) and timed the way benchmarks/solver.py times: N = 1e6, CPU time, the contenders
interleaved within each round, each time divided by that of one scipy.special.ellipk +
ellipe pass over N parameters in the same round; the processes of the builds alternate
(``--passes`` times), and the medians of all rounds are reported. Contenders: hertz.contact
of two general convex bodies at random angles (four radii log-uniform in 1-100 mm, steel
on aluminium, N loads), the same at angle 0, the kernel alone (the ufunc
``contact_load`` that hertz.contact calls, without its Python layer) and
hertz.ellipticity (alpha log-uniform in [1, 1e6]); on builds with an AVX-512 path, the
general case also on the AVX2 path (``_ufuncs.path("avx2")``: the same bits). The table
names the processor, the compilers (as each build reports them) and the load average;
``--docs`` also writes it into docs/explanation/solver.md.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: name, environment, what it stands for
CONFIGURATIONS = [
    ("gcc", {"CC": "gcc"}, "GCC, this Python's flags"),
    ("gcc-distro", {"CC": "gcc", "CFLAGS": "-O2 -fno-strict-overflow"},
     "GCC, `-O2 -fno-strict-overflow` (Debian's and Ubuntu's Python 3.12+)"),
    ("gcc-O2", {"CC": "gcc", "CFLAGS": "-O2"}, "GCC, `-O2`"),
    ("clang", {"CC": "clang"}, "Clang, this Python's flags"),
    ("plain", {"CC": "gcc", "HERTZ_PLAIN": "1"},
     "`HERTZ_PLAIN=1`, GCC (the path of MSVC, macOS, aarch64)"),
    ("plain-clang", {"CC": "clang", "HERTZ_PLAIN": "1"}, "`HERTZ_PLAIN=1`, Clang"),
]
COLUMNS = ["general", "angle0", "kernel", "ellipticity", "general-avx2"]
HEADERS = ["hertz.contact, two general bodies at random angles",
           "the same at angle 0", "the kernel alone (contact_load ufunc)",
           "hertz.ellipticity", "general bodies, AVX2 path"]


def build(name: str, env: dict, where: Path) -> Path:
    """setup.py build_ext of the checkout with ``env``; the path of the module built."""
    environment = {k: v for k, v in os.environ.items()
                   if k not in ("CC", "CFLAGS", "HERTZ_PLAIN", "LDSHARED")}
    environment.update(env)
    lib, temp = where / name / "lib", where / name / "temp"
    done = subprocess.run([sys.executable, "setup.py", "build_ext", "--build-lib", str(lib),
                           "--build-temp", str(temp)], cwd=ROOT, env=environment,
                          capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"build {name} failed:\n{done.stdout[-3000:]}\n{done.stderr[-3000:]}")
    return next((lib / "hertz").glob("_ufuncs*"))


def time_module(so: str, n: int, rounds: int) -> dict:
    """In a fresh process: ratios to ellipk + ellipe of each contender, one per round."""
    import importlib.machinery
    import importlib.util
    import warnings

    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    loader = importlib.machinery.ExtensionFileLoader("hertz._ufuncs", so)
    module = importlib.util.module_from_spec(importlib.util.spec_from_loader("hertz._ufuncs",
                                                                             loader))
    loader.exec_module(module)
    sys.modules["hertz._ufuncs"] = module
    sys.path.insert(0, str(ROOT))
    import numpy as np
    from scipy import special

    import hertz
    import hertz._contact

    assert hertz._contact._ufuncs is module
    warnings.simplefilter("ignore")  # the random bodies are large against their loads
    rng = np.random.default_rng(0)
    m = rng.uniform(0.0, 1.0, n)
    alpha = np.exp(rng.uniform(0.0, np.log(1e6), n))
    loads = rng.uniform(1.0, 2000.0, n)
    angles = rng.uniform(-np.pi, np.pi, n)
    radii = np.exp(rng.uniform(np.log(1e-3), np.log(1e-1), (4, n)))
    steel = hertz.Body(radii[0], radii[1], 210e9, 0.3)
    aluminium = hertz.Body(radii[2], radii[3], 70e9, 0.33)
    args = [radii[0], radii[1], radii[2], radii[3], angles, 210e9, 0.3, 70e9, 0.33, loads]
    info = module.build_info()

    def on_avx2():
        module.path("avx2")
        try:
            hertz.contact(steel, aluminium, load=loads, angle=angles)
        finally:
            module.path("avx512")

    contenders = {
        "reference": lambda: (special.ellipk(m), special.ellipe(m)),
        "general": lambda: hertz.contact(steel, aluminium, load=loads, angle=angles),
        "angle0": lambda: hertz.contact(steel, aluminium, load=loads),
        "kernel": lambda: module.contact_load(*args),
        "ellipticity": lambda: hertz.ellipticity(alpha),
    }
    if info["path"] == "avx512":
        contenders["general-avx2"] = on_avx2
    times = {k: [] for k in contenders}
    for f in contenders.values():  # warm-up
        f()
    for _ in range(rounds):
        for name, f in contenders.items():
            t0 = time.process_time()
            f()
            times[name].append(time.process_time() - t0)
    ref = np.array(times.pop("reference"))
    return {"ratios": {k: list(np.array(v) / ref) for k, v in times.items()},
            "reference_ns": float(np.median(ref) / n * 1e9), "compiler": info["compiler"],
            "path": info["path"], "paths": list(info["paths"])}


def cpu_name() -> str:
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from _common import cpu_name as name

    return name()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=1_000_000)
    ap.add_argument("--rounds", type=int, default=5, help="rounds per process")
    ap.add_argument("--passes", type=int, default=3, help="processes per build, alternating")
    ap.add_argument("--only", nargs="+", choices=[c[0] for c in CONFIGURATIONS],
                    help="these builds only")
    ap.add_argument("--docs", action="store_true",
                    help="also write the table into docs/explanation/solver.md")
    ap.add_argument("--time", metavar="MODULE", help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.time:
        print(json.dumps(time_module(args.time, args.n, args.rounds)))
        return
    configurations = [c for c in CONFIGURATIONS if not args.only or c[0] in args.only]
    load_before = os.getloadavg()
    with tempfile.TemporaryDirectory(prefix="hertz-builds-") as tmp:
        modules = {}
        for name, env, _ in configurations:
            print(f"building {name} ...", file=sys.stderr, flush=True)
            modules[name] = build(name, env, Path(tmp))
        results = {name: None for name in modules}
        for p in range(args.passes):
            for name, so in modules.items():
                print(f"timing {name}, pass {p + 1} of {args.passes} ...", file=sys.stderr,
                      flush=True)
                done = subprocess.run([sys.executable, __file__, "--time", str(so), "--n",
                                       str(args.n), "--rounds", str(args.rounds)],
                                      capture_output=True, text=True)
                if done.returncode != 0:
                    raise SystemExit(f"timing {name} failed:\n{done.stderr[-3000:]}")
                r = json.loads(done.stdout)
                if results[name] is None:
                    results[name] = r
                else:
                    for k, v in r["ratios"].items():
                        results[name]["ratios"][k] += v
    load_after = os.getloadavg()
    import numpy as np
    import scipy

    compilers = sorted({r["compiler"] for r in results.values()})
    ns = np.median([r["reference_ns"] for r in results.values()])
    lines = [f"{cpu_name()}, {os.cpu_count()} logical CPUs, load average "
             f"{load_before[0]:.1f} before and {load_after[0]:.1f} after; "
             f"{', '.join(compilers)}; Python {sys.version.split()[0]}, numpy "
             f"{np.__version__}, scipy {scipy.__version__}; {time.strftime('%Y-%m-%d')}; "
             f"`python benchmarks/builds.py` (N = {args.n:.0e}, medians of "
             f"{args.passes} x {args.rounds} interleaved rounds; one ellipk + ellipe pass "
             f"took {ns:.1f} ns per element)", "",
             "| build | code path | " + " | ".join(HEADERS) + " |",
             "|---|---|" + "---|" * len(HEADERS)]
    for name, _, label in configurations:
        r = results[name]
        cells = [f"{np.median(r['ratios'][k]):.2f}" if k in r["ratios"] else "-"
                 for k in COLUMNS]
        lines.append(f"| {label} | {r['path']} ({r['compiler']}) | " + " | ".join(cells) + " |")
    text = "\n".join(lines)
    print(text)
    if args.docs:
        sys.path.insert(0, str(Path(__file__).resolve().parent))
        from _common import replace_readme_section

        replace_readme_section("builds-table", text)


if __name__ == "__main__":
    main()
