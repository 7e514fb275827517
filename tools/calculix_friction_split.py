"""Split CalculiX's force deficit in the frictional grade into its causes, by tied decks.

The frictional CalculiX grade of two steel spheres (R 10 mm, 830.8 N, mu 0.3, level 0,
docs/howto/calculix.md, "With Coulomb friction") finds the force against the tangential
displacement 7-9.5% low.  A frictional level-0 run costs 15-20 minutes of ccx; a tied deck
(:mod:`fem_validation.decks.friction_tied`: the same half model, the contact bonded over
Hertz's disc r <= a, the far face moved along x) is one linear solve of 10-60 s and holds
every part of the model's tangential compliance except the contact law's.  Its compliance
C_FE, with the blocks' Cerruti settlement 2 Q (3 - 2 nu)/(8 pi G H) added as the frictional
reader adds it, is compared with Mindlin's no-slip compliance of two half-spaces,
2 (2 - nu)/(8 G a) (closed form, written out here); the force error at a given corrected
displacement is then C_M / (C_FE + 2 c_Cerruti) - 1.

    python tools/calculix_friction_split.py --out DIR      # the study of the docs, 8 min CPU
    python tools/calculix_friction_split.py --out DIR --levels 0 --extents 40 80 \
        --faces levelled flat --radius-factors 1 2            # a grid of cases instead

Each case varies one thing against the deck: the blocks' size H (half-width = depth, in
units of a; the deck's own is 10 a for this scene, where the paraboloid's rise caps it),
their contact faces (the deck's paraboloids, scaled with the blocks so that the geometry
stays self-similar; flat; or levelled off beyond 3.5 a at the scene's own radii), a/R
(--radius-factors: the radii times F and the load over F, the same a) and the mesh level.
The script writes DIR/L{level}_H{extent}[_faces][_RF]/tied.inp, runs ccx there
(OMP_NUM_THREADS=--threads; skipped when tied.dat is already there) and prints a Markdown
table, also written to DIR/split.md with DIR/split.json: each case's excess compliance
(C_FE + Cerruti - C_M)/C_M, the flat-faced blocks extrapolated to infinite size (the excess
of a finite block goes as 1/H), and the deck's excess split into its shares (finite blocks,
curved faces, mesh, the stick slope's elastic slip), each share's force error at the
frictional run's two ramp points (Cattaneo-Mindlin's contact in series with the share's
compliance) and their sum, against what that run measured.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

SPHERES = (Path(__file__).resolve().parents[1] / "scenes" / "calculix"
           / "two-steel-spheres.toml").read_text()
#: What the frictional level-0 run gave (docs/howto/calculix.md): P reached [N], and per
#: ramp the ramp's increments, the fraction of the peak displacement of its worst point
#: and that point's force error.
FRICTIONAL_RUN = {"P": 796.5, "ramps": ((2, 0.5, -0.0948), (1, 1.0, -0.0704)),
                  "mu": 0.3, "ratio": 0.8}
#: Imposed displacement of the tied decks [m] (linear: any value gives the compliance).
DISPLACEMENT = 1e-6


def scaled_scene(scene, factor: float):
    """``scene`` with every radius times ``factor`` and the load over it: the same a."""
    import dataclasses

    import hertz

    bodies = [hertz.Body(Rx=b.Rx * factor, Ry=b.Ry * factor, E=b.E, nu=b.nu)
              for b in (scene.body1, scene.body2)]
    return dataclasses.replace(scene, body1=bodies[0], body2=bodies[1],
                               load=scene.load / factor)


#: "levelled" faces: the exact paraboloids out to this many a (the deck's master surface
#: reaches 3.5 a), levelled off beyond (the deck's capped_height, knee 0.5).
LEVELLED_OVER_A = 3.5


def tied_model(scene, level: int, extent: float | None = None, faces: str = "paraboloid"):
    """The deck's half model, with blocks ``extent`` a wide and deep (None: the deck's own).

    ``faces``:

    * "paraboloid": the deck's geometry, self-similar at other block sizes: the radii
      scale with the blocks and the load goes as their inverse (the same a), so that the
      paraboloids rise as far, in units of the block, at its edges (blocks beyond the
      deck's 40 a cap get that cap raised);
    * "flat": the same blocks, their contact faces left flat;
    * "levelled": the scene's own radii, blocks of any size, the faces the exact
      paraboloids out to :data:`LEVELLED_OVER_A` a and levelled off beyond.
    """
    from fem_validation.decks import model as dm

    c = scene.hertz()
    own = dm.block_extent(scene) * c.b / c.a
    extent = own if extent is None else extent
    factor = 1.0 if math.isclose(extent, own, rel_tol=1e-9) else extent / own
    saved = dm.EXTENT_OVER_A, dm.paraboloid_height, dm.block_extent
    height = dm.paraboloid_height
    if faces == "flat":
        dm.paraboloid_height = lambda body, x, y: np.zeros_like(x)
    elif faces == "levelled":
        r_k = LEVELLED_OVER_A * c.a
        cap = height(scene.body1, np.array([r_k]), np.array([0.0]))[0] / dm.RISE_KNEE
        dm.paraboloid_height = lambda body, x, y: dm.capped_height(height(body, x, y), cap)
        dm.block_extent = lambda s: extent * c.a / c.b
        factor = 1.0
    elif faces != "paraboloid":
        raise ValueError(f"faces must be 'paraboloid', 'flat' or 'levelled', got {faces!r}")
    dm.EXTENT_OVER_A = max(dm.EXTENT_OVER_A, own * factor * (1 + 1e-9))
    try:
        return dm.build_model(scene if factor == 1 else scaled_scene(scene, factor), level,
                              "half")
    finally:
        dm.EXTENT_OVER_A, dm.paraboloid_height, dm.block_extent = saved


def total_force(dat: Path) -> float:
    """The x reaction of MOVED in ccx's .dat (``*NODE PRINT, TOTALS=ONLY``), last step [N]."""
    text = dat.read_text()
    found = re.findall(r"total force \(fx,fy,fz\) for set MOVED[^\n]*\n\s*\n\s*(\S+)", text)
    if not found:
        raise SystemExit(f"{dat}: no total force of set MOVED (did ccx finish?)")
    return float(found[-1])


def run_ccx(folder: Path, threads: int) -> float:
    """Run ``ccx -i tied`` in ``folder``; its CPU seconds (recorded, if the .dat was there)."""
    cpu = folder / "ccx_cpu_s.txt"
    if (folder / "tied.dat").exists() and "total force" in (folder / "tied.dat").read_text():
        return float(cpu.read_text()) if cpu.exists() else math.nan
    env = {**os.environ, "OMP_NUM_THREADS": str(threads)}
    t0 = os.times()
    with open(folder / "ccx.log", "w") as log:
        subprocess.run(["ccx", "-i", "tied"], cwd=folder, env=env, stdout=log,
                       stderr=subprocess.STDOUT, check=True)
    t1 = os.times()
    seconds = (t1.children_user - t0.children_user) + (t1.children_system - t0.children_system)
    cpu.write_text(f"{seconds:.2f}\n")
    return seconds


def mindlin(E: float, nu: float, a: float) -> float:
    """No-slip compliance of two identical half-spaces bonded over a disc of radius a."""
    g = E / (2 * (1 + nu))
    return 2 * (2 - nu) / (8 * g * a)


def cerruti(E: float, nu: float, depth: float) -> float:
    """Cerruti's displacement per unit force on the axis at ``depth`` of a half-space."""
    g = E / (2 * (1 + nu))
    return (3 - 2 * nu) / (8 * math.pi * g * depth)


def mindlin_partial(q, mu, p, c_m):
    """Cattaneo-Mindlin's displacement of two identical spheres at Q (virgin curve)."""
    return 1.5 * mu * p * c_m * (1 - (1 - q / (mu * p)) ** (2 / 3))


def inverse(f, target, high):
    lo, hi = 0.0, high
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < target else (lo, mid)
    return 0.5 * (lo + hi)


def ramp_error(d_imposed: float, excess: float, corr: float, mu: float, p: float,
               c_m: float) -> float:
    """The force error of a frictional run at one imposed displacement, predicted.

    The run's tangential response is taken as Cattaneo-Mindlin's contact at the run's P
    (no-slip compliance ``c_m``) in series with ``excess`` [m/N], the bodies' compliance
    beyond Mindlin's half-spaces once the blocks' Cerruti settlement ``corr`` [m/N] is
    added back: its force Q solves d_imposed = delta_M(Q) + (excess - corr) Q.  The reader
    reports d_imposed + corr Q, and the reference force is delta_M's inverse there.
    """
    top = mu * p * (1 - 1e-12)
    q = inverse(lambda x: mindlin_partial(x, mu, p, c_m) + (excess - corr) * x, d_imposed,
                top)
    q_ref = inverse(lambda x: mindlin_partial(x, mu, p, c_m), d_imposed + corr * q, top)
    return q / q_ref - 1


#: The default study: (radius factor, faces, level, block extent in a).  Level 0 at the
#: deck's blocks and larger ones with its paraboloid faces (self-similar) and flat faces;
#: levelled faces at three a/R; levels 1 and 2 for the mesh's trend.  About 8 minutes of
#: ccx CPU (level 2 alone 4 minutes and about 4 GB).
STUDY = ([(1.0, "paraboloid", 0, e) for e in (10, 20, 40, 80)]
         + [(1.0, "flat", 0, e) for e in (10, 20, 40, 80)]
         + [(f, "levelled", 0, 40) for f in (1.0, 2.0, 4.0)]
         + [(1.0, "flat", 1, e) for e in (40, 80)]
         + [(1.0, "levelled", 1, 40), (1.0, "paraboloid", 1, 10), (1.0, "flat", 2, 80)])


def folder_name(rf: float, faces: str, level: int, extent: float) -> str:
    return (f"L{level}_H{extent:g}" + ("" if faces == "paraboloid" else f"_{faces}")
            + ("" if rf == 1 else f"_R{rf:g}"))


def one_run(out: Path, scene, case, threads: int, run: bool) -> dict:
    """Write (and run) one tied deck; its row of figures."""
    from fem_validation.decks.friction_tied import write_tied_inp

    rf, faces, level, extent = case
    folder = out / folder_name(*case)
    folder.mkdir(exist_ok=True)
    s = scene if rf == 1 else scaled_scene(scene, rf)
    model = tied_model(s, level, extent, faces)
    pairs = write_tied_inp(model, folder / "tied.inp", DISPLACEMENT)
    c, b = scene.hertz(), scene.body1
    row = {"radius_factor": rf, "a_over_R": c.a / (b.Rx * rf), "faces": faces,
           "level": level, "extent_over_a": extent, "nodes": len(model.nodes),
           "pairs": len(pairs), "depth": model.info["block_depth"]}
    if not run:
        return row
    row["ccx_cpu_s"] = round(run_ccx(folder, threads), 1)
    q = 2 * total_force(folder / "tied.dat")
    c_fe, c_m = DISPLACEMENT / q, mindlin(b.E, b.nu, c.a)
    corr = 2 * cerruti(b.E, b.nu, row["depth"])
    row.update({"Q": q, "C_FE": c_fe, "cerruti_over_CM": corr / c_m,
                "excess_over_CM": (c_fe + corr) / c_m - 1,
                "force_err": c_m / (c_fe + corr) - 1})
    return row


def extrapolate(rows, rf, faces, level):
    """The excess at infinite blocks: 1/H through the two largest blocks of a series."""
    rs = sorted((r for r in rows if (r["radius_factor"], r["faces"], r["level"])
                 == (rf, faces, level)), key=lambda r: r["extent_over_a"])
    if len(rs) < 2:
        return None
    (h1, e1), (h2, e2) = ((r["extent_over_a"], r["excess_over_CM"]) for r in rs[-2:])
    return (e2 * h2 - e1 * h1) / (h2 - h1), h1, h2


def flat_infinite(rows) -> dict:
    """Flat faces, infinite blocks, per level: 1/H through the two largest blocks, or one
    block less level 0's block term (the block term is the same at every level)."""
    out = {}
    inf0 = extrapolate(rows, 1.0, "flat", 0)
    for level in sorted({r["level"] for r in rows if r["faces"] == "flat"}):
        e = extrapolate(rows, 1.0, "flat", level)
        if e is not None:
            out[level] = e[0]
            continue
        one = [r for r in rows if r["faces"] == "flat" and r["level"] == level
               and r["radius_factor"] == 1.0]
        ref = inf0 and find(rows, 1.0, "flat", 0, one[0]["extent_over_a"])
        if one and ref:
            out[level] = one[0]["excess_over_CM"] - (ref["excess_over_CM"] - inf0[0])
    return out


def find(rows, rf, faces, level, extent):
    for r in rows:
        if (r["radius_factor"], r["faces"], r["level"], r["extent_over_a"]) == (
                rf, faces, level, extent):
            return r
    return None


def decomposition(scene, rows) -> tuple[list[str], dict]:
    """The deck's excess compliance at level 0 split into its shares, each share's force
    error at the frictional run's ramp points, and the prediction of those points."""
    from fem_validation.decks.inp import friction_path

    deck, flat = find(rows, 1.0, "paraboloid", 0, 10), find(rows, 1.0, "flat", 0, 10)
    inf = flat_infinite(rows)
    if deck is None or flat is None or 0 not in inf:
        return [], {}
    finest = max(inf)
    shares = {"finite blocks (free sides, rigid and clamped far faces) beyond Cerruti's "
              "correction": flat["excess_over_CM"] - inf[0],
              "curved faces (paraboloids, a/R = 0.03) against Mindlin's flat half-spaces":
              deck["excess_over_CM"] - flat["excess_over_CM"],
              f"level-0 mesh against level {finest} (flat faces, infinite blocks)":
              inf[0] - inf[finest]}
    if finest:
        shares[f"level {finest} itself (flat faces, infinite blocks)"] = inf[finest]
    c, b = scene.hertz(), scene.body1
    run = FRICTIONAL_RUN
    p_run, mu = run["P"], run["mu"]
    a_run = c.a * (p_run / scene.load) ** (1 / 3)
    c_run = mindlin(b.E, b.nu, a_run)
    half = tied_model(scene, 0)
    peak = friction_path(half, mu, run["ratio"]).peak
    corr = 2 * cerruti(b.E, b.nu, deck["depth"])
    # the stick slope's elastic slip at the centre of Mindlin's no-slip traction,
    # q(0) / lambda = Q / (2 pi a^2 lambda), as a compliance
    slip = 1 / (2 * math.pi * a_run ** 2 * half.penalty)
    shares["stick slope (elastic slip q(0)/lambda at the centre)"] = slip / c_run
    points = [(n, f * peak) for n, f, _ in run["ramps"]]
    lines = ["| share | compliance (of C_M) | force, ramp 2, first point | force, ramp 1 |",
             "|---|---|---|---|"]
    out = {"shares": {}, "prediction": []}
    for name, share in shares.items():
        errs = [ramp_error(d, share * c_run, corr, mu, p_run, c_run) for _, d in points]
        out["shares"][name] = {"compliance": share, "ramp": errs}
        lines.append(f"| {name} | {100 * share:+.2f}% | {100 * errs[0]:+.2f}% | "
                     f"{100 * errs[1]:+.2f}% |")
    total = sum(shares.values())
    pred = [ramp_error(d, total * c_run, corr, mu, p_run, c_run) for _, d in points]
    lines.append(f"| all together (predicted) | {100 * total:+.2f}% | {100 * pred[0]:+.2f}% | "
                 f"{100 * pred[1]:+.2f}% |")
    lines.append(f"| measured (frictional run) | | {100 * run['ramps'][0][2]:+.2f}% | "
                 f"{100 * run['ramps'][1][2]:+.2f}% |")
    out["prediction"] = pred
    return lines, out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--levels", type=int, nargs="+",
                    help="a grid of levels x extents x faces x radius factors instead of the "
                         "default study")
    ap.add_argument("--extents", type=float, nargs="+", default=[10.0],
                    help="block half-width = depth in units of a (10: the deck's own here)")
    ap.add_argument("--faces", nargs="+", choices=("paraboloid", "flat", "levelled"),
                    default=["paraboloid"], help="the blocks' contact faces")
    ap.add_argument("--radius-factors", type=float, nargs="+", default=[1.0],
                    help="the spheres' radii times these, the load over them (the same a)")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--no-run", action="store_true", help="write the decks only")
    args = ap.parse_args(argv)

    from fem_validation.decks import read_scene

    args.out.mkdir(parents=True, exist_ok=True)
    scene_path = args.out / "spheres.toml"
    scene_path.write_text(SPHERES)
    scene = read_scene(scene_path)
    cases = STUDY if args.levels is None else [
        (r, f, v, e) for r in args.radius_factors for f in args.faces for v in args.levels
        for e in args.extents]
    rows = []
    for case in cases:
        rows.append(one_run(args.out, scene, case, args.threads, not args.no_run))
        print(json.dumps(rows[-1]), flush=True)
    if args.no_run:
        return 0
    lines = ["| a/R | faces | level | blocks (a) | nodes | tied pairs | Cerruti (of C_M) | "
             "C_FE + Cerruti - C_M (of C_M) | force error | ccx CPU |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['a_over_R']:.4g} | {r['faces']} | {r['level']} | "
                     f"{r['extent_over_a']:g} | {r['nodes']} | {r['pairs']} | "
                     f"{100 * r['cerruti_over_CM']:.2f}% | {100 * r['excess_over_CM']:+.2f}% | "
                     f"{100 * r['force_err']:+.2f}% | {r['ccx_cpu_s']:.0f} s |")
    extrapolated = {}
    for key in sorted({(r["radius_factor"], r["faces"], r["level"]) for r in rows}):
        e = extrapolate(rows, *key)
        if e is not None:
            extrapolated[f"{key[1]} faces, R x {key[0]:g}, level {key[2]}"] = e[0]
            lines.append(f"\n{key[1]} faces, radii x {key[0]:g}, level {key[2]}: excess "
                         f"extrapolated to infinite blocks (1/H through {e[1]:g} a and "
                         f"{e[2]:g} a): {100 * e[0]:+.2f}% of C_M")
    for level, e in flat_infinite(rows).items():
        lines.append(f"\nflat faces, infinite blocks, level {level}: {100 * e:+.2f}% of C_M")
    split_lines, split = decomposition(scene, rows)
    if split_lines:
        lines += ["", *split_lines]
    text = "\n".join(lines)
    print(text)
    (args.out / "split.md").write_text(text + "\n")
    (args.out / "split.json").write_text(json.dumps(
        {"rows": rows, "extrapolated_excess": extrapolated, **split}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
