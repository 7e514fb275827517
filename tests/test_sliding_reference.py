"""The mpmath reference for the stresses of a sliding traction (issue 17 item 4, a start):
Cerruti's kernel against Hooke's law applied to Cerruti's displacement field, equilibrium,
the free surface, and the quadrature against a 1-D integral on the axis and against itself
at two sizes.  The library's closed forms (Hamilton 1983) are not written yet; this is the
check they will have to pass."""

import mpmath as mp
import pytest
import reference_sliding as ref


def _displacement(nu, shear_modulus, x, y, z):
    """Cerruti's displacement for a unit force along +x (Johnson, Contact Mechanics, ch. 3)."""
    rho = mp.sqrt(x * x + y * y + z * z)
    k = 1 - 2 * nu
    c = 1 / (4 * mp.pi * shear_modulus)
    return (c * (1 / rho + x * x / rho ** 3 + k * (1 / (rho + z) - x * x / (rho * (rho + z) ** 2))),
            c * (x * y / rho ** 3 - k * x * y / (rho * (rho + z) ** 2)),
            c * (x * z / rho ** 3 + k * x / (rho * (rho + z))))


@pytest.mark.parametrize("point", [(0.3, -0.7, 0.45), (-1.2, 0.4, 0.1), (0.05, 0.02, 2.0)])
def test_cerruti_kernel_is_hookes_law_of_the_displacement(point):
    with mp.workdps(30):
        nu, shear = mp.mpf("0.27"), mp.mpf("1.3")
        at = [mp.mpf(v) for v in point]

        def grad(i, j):  # d u_i / d x_j
            def f(t):
                moved = list(at)
                moved[j] = t
                return _displacement(nu, shear, *moved)[i]
            return mp.diff(f, at[j])
        g = [[grad(i, j) for j in range(3)] for i in range(3)]
        eps = [[(g[i][j] + g[j][i]) / 2 for j in range(3)] for i in range(3)]
        tr = eps[0][0] + eps[1][1] + eps[2][2]
        lam = 2 * shear * nu / (1 - 2 * nu)
        sig = [[lam * tr * (i == j) + 2 * shear * eps[i][j] for j in range(3)] for i in range(3)]
        kern = ref.cerruti(nu, *at)
        pairs = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
        for value, (i, j) in zip(kern, pairs, strict=True):
            assert abs(value - sig[i][j]) < mp.mpf(10) ** -20
        # the surface (z -> 0, away from the force) is free of traction
        surface = ref.cerruti(nu, at[0], at[1], mp.mpf(10) ** -25)
        assert max(abs(surface[k]) for k in (2, 4, 5)) < mp.mpf(10) ** -20
        # equilibrium: d s_ij / d x_j = 0
        comps = {(0, 0): 0, (1, 1): 1, (2, 2): 2, (0, 1): 3, (1, 0): 3, (0, 2): 4, (2, 0): 4,
                 (1, 2): 5, (2, 1): 5}
        for i in range(3):
            div = 0
            for j in range(3):
                def f(t, i=i, j=j):
                    moved = list(at)
                    moved[j] = t
                    return ref.cerruti(nu, *moved)[comps[(i, j)]]
                div += mp.diff(f, at[j])
            assert abs(div) < mp.mpf(10) ** -18


def test_quadrature_on_the_axis_against_a_one_dimensional_integral():
    s = ref.sliding_stress(1.0, 0.3, 0.0, 0.0, 0.5, 48, 24)
    assert abs(s[4] - ref.axis_shear(1.0, 0.5)) < 1.6e-20  # observed 1.06e-20
    assert max(abs(s[k]) for k in (0, 1, 2, 3, 5)) < 5e-22  # odd in x; observed 3.2e-22


def test_quadrature_converges():
    """Two sizes agree at an off-axis point: observed 1.0e-20 mu p0 (the working precision)
    between 64 x 32 and 96 x 48; at (0.9, 0.1, 0.1) a 1.4e-12 and (-0.5, 0.2, 0.05) a
    2.3e-11 between 48 x 24 and 96 x 48, then 2e-20 to 192 x 96."""
    coarse = ref.sliding_stress(1.0, 0.3, 0.4, -0.3, 0.3, 64, 32)
    fine = ref.sliding_stress(1.0, 0.3, 0.4, -0.3, 0.3, 96, 48)
    assert max(abs(u - v) for u, v in zip(coarse, fine, strict=True)) < 1.5e-20
