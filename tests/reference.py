"""Independent high-precision references (mpmath), kept apart from hertz's code.

Nothing here imports hertz.  The ellipse ratio is the root of Harris's
relation (the seed's eq. (alpha_lambda_relation))

    alpha = (lambda**2 E(m) - K(m)) / (K(m) - E(m)),   m = 1 - 1/lambda**2,

found by a bracketing solver in u = ln(lambda) with mpmath's own complete
elliptic integrals (parameter convention), at 50 significant digits plus
guard digits for the cancellation near alpha = 1 and the tiny 1 - m at large
alpha.  (The committed table tests/data/reference_lambda.csv was written at 50.)  The
contact quantities follow the seed's section 2 literally.

Importing this module sets mpmath's working precision to 60 digits, so that
differences taken by the caller keep their accuracy.
"""

from __future__ import annotations

import csv
import math
import pathlib
from dataclasses import dataclass

import mpmath as mp

DIGITS = 60
mp.mp.dps = DIGITS  # callers compare against these values: keep 60 digits throughout
TABLE = pathlib.Path(__file__).with_name("data") / "reference_lambda.csv"


def _bracket(t):
    """Bracket of u = ln(lambda) for t = ln(alpha) > 0: lambda**2 lies between
    alpha and min(alpha**2, alpha (t + 2)**2)."""
    return t / 2, min(t, t / 2 + mp.log(t + 2))


def _workdps(alpha: mp.mpf) -> int:
    # 1 - m = 1/lambda**2 >= 1/(alpha (ln(alpha) + 2)**2) must be resolved next to 1.
    t = mp.log(alpha)
    return DIGITS + 40 + int(mp.log10(alpha) + 2 * mp.log10(t + 2))


def _alpha_of_u(u):
    lam2 = mp.exp(2 * u)
    m = 1 - 1 / lam2
    k, e = mp.ellipk(m), mp.ellipe(m)
    return (lam2 * e - k) / (k - e)


def ellipse_ref(alpha) -> tuple[mp.mpf, mp.mpf, mp.mpf, mp.mpf]:
    """(lambda, m, K(m), E(m)) for alpha (a float taken as exact), as mpf.

    lambda = l_y / l_x solves Harris's relation; for alpha < 1 it is
    1/lambda(1/alpha) and m, K, E are those of the ellipse (m from its axes).
    """
    a = mp.mpf(alpha)
    if a <= 0 or not mp.isfinite(a):
        raise ValueError(alpha)
    if a == 1:
        return mp.mpf(1), mp.mpf(0), mp.pi / 2, mp.pi / 2
    flip = a < 1
    with mp.workdps(_workdps(1 / a if flip else a)):
        target = 1 / a if flip else a
        t = mp.log(target)
        u = mp.findroot(lambda u: mp.log(_alpha_of_u(u)) - t, _bracket(t), solver="anderson",
                        tol=mp.mpf(10) ** (-2 * DIGITS))
        lam = mp.exp(u)
        m = 1 - 1 / lam**2
        k, e = mp.ellipk(m), mp.ellipe(m)
        out = (1 / lam if flip else lam), m, k, e
    return tuple(+x for x in out)


def curvatures_ref(r1x, r1y, r2x, r2y, angle):
    """Eigenvalues (rho_x >= rho_y) of the gap's curvature tensor, exact inputs.

    Evaluated at 800 digits or more, so that a nearly singular tensor (crossed
    cylinders at an angle of 1e-150, conforming radii equal to 1e-16, radii of
    1e-300 beside 1e300) keeps 50 correct digits in rho_y = det / rho_x: the
    digits grow with the decimal spread of the radii and with a small angle.
    """
    finite = [abs(r) for r in (r1x, r1y, r2x, r2y) if not math.isinf(r)]
    spread = math.log10(max(finite)) - math.log10(min(finite)) if finite else 0.0
    small = -math.log10(abs(angle)) if 0 < abs(angle) < 1 else 0.0
    with mp.workdps(max(800, int(200 + 3 * spread + 4 * small))):
        c, s = mp.cos(mp.mpf(angle)), mp.sin(mp.mpf(angle))
        k = [0 if math.isinf(r) else 1 / mp.mpf(r) for r in (r1x, r1y, r2x, r2y)]
        a = k[0] + k[2] * c * c + k[3] * s * s
        b = k[1] + k[2] * s * s + k[3] * c * c
        off = (k[2] - k[3]) * c * s
        half = mp.sqrt(((a - b) / 2) ** 2 + off**2)
        rho_x = (a + b) / 2 + half
        rho_y = (a * b - off**2) / rho_x if rho_x else (a + b) / 2 - half
        return +rho_x, +rho_y


@dataclass
class ContactRef:
    a: mp.mpf
    b: mp.mpf
    p0: mp.mpf
    delta: mp.mpf
    alpha: mp.mpf
    lam: mp.mpf


def contact_ref(body1, body2, load, angle=0.0) -> ContactRef:
    """The seed's contact formulas evaluated in mpmath; bodies are (Rx, Ry, E, nu) tuples."""
    rho_x, rho_y = curvatures_ref(body1[0], body1[1], body2[0], body2[1], angle)
    with mp.workdps(DIGITS + 40):
        e_star = 1 / sum((1 - mp.mpf(nu) ** 2) / mp.mpf(e) for _, _, e, nu in (body1, body2))
        alpha = rho_x / rho_y
        rho_sum = rho_x + rho_y
        P = mp.mpf(load)
    lam, m, k, e = ellipse_ref(alpha)
    with mp.workdps(DIGITS + 40):
        lx = (3 * e * P / (mp.pi * lam * e_star * rho_sum)) ** (mp.mpf(1) / 3)
        ly = lam * lx
        p0 = 3 * P / (2 * mp.pi * lx * ly)
        delta = k / 2 * (9 * rho_sum / e * (P / (mp.pi * lam * e_star)) ** 2) ** (mp.mpf(1) / 3)
        return ContactRef(ly, lx, p0, delta, alpha, lam)


def load_table():
    """Rows of the committed reference table: dicts of float alpha and mpf values."""
    rows = []
    with TABLE.open() as f:
        for row in csv.DictReader(row for row in f if not row.startswith("#")):
            rows.append({"alpha": float.fromhex(row["alpha_hex"]), "group": row["group"],
                         **{k: mp.mpf(row[k]) for k in ("lambda", "m", "K", "E")}})
    return rows
