"""Damping laws <-> restitution (hertz.restitution, hertz.damping_coefficient,
hertz.damped_impact) against a 30-digit Taylor-series integration
(tests/reference_impact.py), Schwager & Poschel's closed-form first-order coefficient, and
the laws' own invariants (Tsuji's speed independence, LAMMPS coeff_restitution's exact e).
"""

import math

import mpmath as mp
import numpy as np
import pytest
from reference_impact import damped_ref, elastic_ref

import hertz

pytestmark = pytest.mark.filterwarnings("ignore::hertz.HertzValidityWarning")

GLASS = (0.01, 0.01, 48e9, 0.2)
V, M = 20.0, 2800 * 4 / 3 * math.pi * 0.01**3 / 2
R_EFF = 0.005  # two 10 mm spheres


def _glass():
    return hertz.Body(*GLASS)


def _tsuji_poly(e):
    return (1.2728 - 4.2783 * e + 11.087 * e**2 - 22.348 * e**3 + 27.467 * e**4
            - 18.022 * e**5 + 4.8218 * e**6)


def _gamma(law, coef):
    """gamma of x'' = -(5/4) x^1.5 - gamma x^p x' from the law's force, derived here:
    x = delta / delta_max, tau = t V / delta_max, so a damping force c(delta) delta'
    becomes (c(delta) delta_max / (M V)) x' with delta = delta_max x."""
    K, dmax, _, _ = (float(x) for x in elastic_ref(GLASS, GLASS, V, M))
    c_over = {  # c(delta) / delta^p
        "velocity": coef,
        "mass_velocity": coef * M,
        "viscoelastic": coef * M * math.sqrt(R_EFF),  # eta0 M sqrt(R delta)
        "kuwabara_kono": 1.5 * coef * K,
        "tsuji": coef * math.sqrt(M * K),
        "lammps_tsuji": _tsuji_poly(coef) * math.sqrt(M * K),  # LAMMPS 22 Jul 2025
        "lammps_tsuji_sqrt2": math.sqrt(2) * _tsuji_poly(coef) * math.sqrt(M * K),
    }[law]
    p = {"velocity": 0, "mass_velocity": 0, "viscoelastic": 0.5, "kuwabara_kono": 0.5,
         "tsuji": 0.25, "lammps_tsuji": 0.25, "lammps_tsuji_sqrt2": 0.25}[law]
    return c_over * dmax**p * dmax / (M * V), p, dmax


# (law, coefficient, cutoff): each exponent p with and without the cutoff
CASES = [
    ("velocity", 120.0, True),
    ("mass_velocity", 2.2e4, False),
    ("tsuji", 0.4, True),
    ("lammps_tsuji", 0.6, False),
    ("lammps_tsuji_sqrt2", 0.6, True),
    ("viscoelastic", 1.9e7, True),
    ("kuwabara_kono", 2.2e-6, False),
]


@pytest.mark.parametrize("law, coef, cutoff", CASES)
def test_restitution_against_30_digit_integration(law, coef, cutoff):
    gamma, p, dmax = _gamma(law, coef)
    hit = hertz.damped_impact(_glass(), _glass(), V, M, law, coef, cutoff)
    assert hit.gamma == pytest.approx(gamma, rel=1e-14)
    e_ref, tau_ref = damped_ref(gamma, p, cutoff)
    assert 0.2 < hit.restitution < 0.95  # a damping that matters
    assert abs(hit.restitution - float(e_ref)) < 1e-12  # observed <= 1e-13
    assert abs(hit.duration * V / dmax / float(tau_ref) - 1) < 1e-12
    assert hertz.restitution(_glass(), _glass(), V, M, law, coef, cutoff) == hit.restitution


def test_schwager_poschel_first_order_coefficient():
    """Without the cutoff, e = 1 - C1 (3/2) A rho^(2/5) V^(1/5) + ..., rho = K/M, C1 =
    sqrt(pi) Gamma(3/5) / (2^(1/5) 5^(2/5) Gamma(21/10)) = 1.15344 (Schwager & Poschel
    1998; Brilliantov et al.'s force K (delta^(3/2) + (3/2) A delta^(1/2) delta'))."""
    c1 = mp.sqrt(mp.pi) * mp.gamma(mp.mpf(3) / 5) / (2 ** (mp.mpf(1) / 5) * 5 ** (mp.mpf(2) / 5)
                                                     * mp.gamma(mp.mpf(21) / 10))
    K = float(elastic_ref(GLASS, GLASS, V, M)[0])
    eps = 1.5 * (K / M) ** 0.4 * V ** 0.2  # per unit A
    A = 1e-4 / eps
    e1 = hertz.restitution(_glass(), _glass(), V, M, "kuwabara_kono", A, cutoff=False)
    e2 = hertz.restitution(_glass(), _glass(), V, M, "kuwabara_kono", 2 * A, cutoff=False)
    slope = (4 * (1 - e1) - (1 - e2)) / (2 * A * eps)  # Richardson: O(eps^2) removed
    assert abs(slope / float(c1) - 1) < 1e-7  # observed 8e-9


def test_tsuji_laws_do_not_depend_on_speed_mass_or_bodies():
    ellipsoid = hertz.Body(0.01, 0.03, 200e9, 0.3)
    other = hertz.Body(0.02, 0.05, 110e9, 0.34)
    for law, coef in (("tsuji", 0.4), ("coeff_restitution", 0.7), ("lammps_tsuji", 0.5),
                      ("lammps_tsuji_sqrt2", 0.5)):
        e = hertz.restitution(_glass(), _glass(), [0.01, 1.0, 100.0], [1e-6, 1.0, 1e3], law,
                              coef)
        e_other = hertz.restitution(ellipsoid, other, 3.0, 0.2, law, coef, angle=0.7)
        assert np.ptp(e) == 0.0 and abs(e_other - e[0]) < 1e-13
    # the others do
    for law, coef in (("viscoelastic", 1e7), ("kuwabara_kono", 1e-6), ("velocity", 50.0)):
        e = hertz.restitution(_glass(), _glass(), [1.0, 20.0], M, law, coef)
        assert abs(e[0] - e[1]) > 1e-3, law


@pytest.mark.parametrize("e_in", [0.1, 0.5, 0.9])
def test_lammps_coeff_restitution_is_exact_without_the_cutoff(e_in):
    """LAMMPS's coeff_restitution damping (-sqrt(5) ln e / sqrt(pi^2 + ln^2 e) sqrt(M K)
    delta^(1/4)) gives exactly the e it is given when the force may pull (its default);
    with limit_damping the rebound is faster."""
    e = hertz.restitution(_glass(), _glass(), V, M, "coeff_restitution", e_in, cutoff=False)
    assert abs(e - e_in) < 1e-12  # observed 3e-14
    cut = hertz.restitution(_glass(), _glass(), V, M, "coeff_restitution", e_in, cutoff=True)
    assert cut > e_in + 1e-3


@pytest.mark.parametrize("law", ["velocity", "viscoelastic", "tsuji", "coeff_restitution"])
@pytest.mark.parametrize("cutoff", [True, False])
def test_damping_coefficient_inverts_restitution(law, cutoff):
    target = np.array([0.3, 0.75])
    coef = hertz.damping_coefficient(_glass(), _glass(), V, M, law, target, cutoff)
    e = hertz.restitution(_glass(), _glass(), V, M, law, coef, cutoff)
    np.testing.assert_allclose(e, target, rtol=0, atol=1e-12)
    assert hertz.damping_coefficient(_glass(), _glass(), V, M, law, 1.0, cutoff) == (
        1.0 if law == "coeff_restitution" else 0.0)


def test_elastic_limit_and_shapes():
    hit = hertz.damped_impact(_glass(), _glass(), [1.0, 2.0], M, "velocity", 0.0)
    elastic = hertz.impact(_glass(), _glass(), [1.0, 2.0], M)
    np.testing.assert_array_equal(hit.restitution, [1.0, 1.0])
    np.testing.assert_allclose(hit.duration, elastic.duration, rtol=1e-15)
    np.testing.assert_allclose(hit.max_approach, elastic.max_approach, rtol=1e-15)
    e = hertz.restitution(_glass(), _glass(), 20.0, M, "tsuji", [[0.1], [0.4]])
    assert e.shape == (2, 1) and e[0, 0] > e[1, 0]


def test_heavy_damping_without_cutoff_never_parts():
    hit = hertz.damped_impact(_glass(), _glass(), V, M, "mass_velocity", 1e8, cutoff=False)
    assert hit.restitution == 0.0 and hit.duration == math.inf
    cut = hertz.damped_impact(_glass(), _glass(), V, M, "mass_velocity", 1e8, cutoff=True)
    assert 0 < cut.restitution < 1e-3 and math.isfinite(cut.duration)


@pytest.mark.parametrize("call, message", [
    (lambda: hertz.restitution(_glass(), _glass(), V, M, "linear", 1.0),
     "law must be one of coeff_restitution, .*, got 'linear'"),
    (lambda: hertz.restitution(_glass(), _glass(), V, M, "tsuji", -0.1),
     r"coefficient must be a finite damping coefficient >= 0, got -0.1"),
    (lambda: hertz.restitution(_glass(), _glass(), V, M, "tsuji", [0.1, math.nan]),
     r"coefficient must be .*, got nan at index 1"),
    (lambda: hertz.restitution(_glass(), _glass(), V, M, "coeff_restitution", 0.0),
     r"coefficient must be a LAMMPS restitution in \(0, 1\], got 0.0"),
    (lambda: hertz.damping_coefficient(_glass(), _glass(), V, M, "tsuji", 1.5),
     r"restitution must be a coefficient of restitution in \(0, 1\], got 1.5"),
    (lambda: hertz.damping_coefficient(_glass(), _glass(), V, M, "tsuji", 0.0),
     r"restitution must be a coefficient of restitution in \(0, 1\], got 0.0"),
    (lambda: hertz.restitution(_glass(), _glass(), -1.0, M, "tsuji", 0.1),
     "speed must be a positive"),
])
def test_bad_input(call, message):
    with pytest.raises(ValueError, match=message):
        call()
