"""hertz.contact on the hard scenes of tests/test_contact_exact.py against 60-digit mpmath.

    python benchmarks/hard_scenes.py

Prints, per scene, the relative error of a, b, p0, delta and alpha against
tests/reference.py (mpmath, independent of hertz), and the largest of each: the
figures quoted in the README's contact-kernel section.
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from reference import contact_ref  # noqa: E402
from test_contact_exact import HARD, rel_err  # noqa: E402

import hertz  # noqa: E402

FIELDS = ("a", "b", "p0", "delta", "alpha")


def main() -> None:
    worst = dict.fromkeys(FIELDS, 0.0)
    print("| scene | " + " | ".join(FIELDS) + " |")
    print("|---|" + "---|" * len(FIELDS))
    for name, (b1, b2, load, angle) in HARD.items():
        c = hertz.contact(hertz.Body(*b1), hertz.Body(*b2), load=load, angle=angle)
        ref = contact_ref(b1, b2, load, angle)
        errors = {f: rel_err(getattr(c, f), getattr(ref, f)) for f in FIELDS}
        worst = {f: max(worst[f], errors[f]) for f in FIELDS}
        print(f"| {name} | " + " | ".join(f"{errors[f]:.1e}" for f in FIELDS) + " |")
    print("| largest | " + " | ".join(f"{worst[f]:.1e}" for f in FIELDS) + " |")


if __name__ == "__main__":
    main()
