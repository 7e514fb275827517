"""hertz on dask arrays: lazy, the same bits as numpy, bad input raising when computed."""

import numpy as np
import pytest

import hertz

da = pytest.importorskip("dask.array")

STEEL = (210e9, 0.3)


@pytest.fixture
def inputs():
    rng = np.random.default_rng(3)
    n = 10_000
    return rng.uniform(2e-3, 2e-2, n), rng.uniform(1.0, 2e3, n), rng.uniform(-3, 3, n)


def lazy(x):
    return da.from_array(x, chunks=x.size // 4)


def test_ellipticity_is_lazy_and_exact(inputs):
    alpha = inputs[1]
    out = hertz.ellipticity(lazy(alpha))
    assert isinstance(out, da.Array)
    np.testing.assert_array_equal(out.compute(), hertz.ellipticity(alpha))
    np.testing.assert_array_equal(hertz.ellipticity(lazy(alpha), iterations=0).compute(),
                                  hertz.ellipticity(alpha, iterations=0))


def test_contact_is_lazy_and_exact(inputs):
    radius, load, angle = inputs
    race = hertz.Body(-0.03, 0.05, 70e9, 0.33)
    c = hertz.contact(hertz.Body.sphere(lazy(radius), *STEEL), race, load=lazy(load),
                      angle=lazy(angle))
    ref = hertz.contact(hertz.Body.sphere(radius, *STEEL), race, load=load, angle=angle)
    for field in ("a", "b", "load", "p0", "delta", "stiffness", "ellipticity", "alpha", "m", "K",
                  "E", "e_star", "rho_x", "rho_y", "major_axis_angle"):
        value = getattr(c, field)
        assert isinstance(value, da.Array), field
        np.testing.assert_array_equal(value.compute(), getattr(ref, field), err_msg=field)
    assert isinstance(c.pressure(0.0, 0.0), da.Array)


def test_approach_and_line_contact_on_dask(inputs):
    radius, load, _ = inputs
    ball, plane = hertz.Body.sphere(0.01, *STEEL), hertz.Body.plane(*STEEL)
    delta = load * 1e-9
    np.testing.assert_array_equal(hertz.contact(ball, plane, approach=lazy(delta)).load.compute(),
                                  hertz.contact(ball, plane, approach=delta).load)
    cyl = hertz.Body.cylinder(lazy(radius), *STEEL)
    lc = hertz.line_contact(cyl, plane, lazy(load))
    np.testing.assert_array_equal(
        lc.half_width.compute(),
        hertz.line_contact(hertz.Body.cylinder(radius, *STEEL), plane, load).half_width)


def test_bad_values_raise_when_computed_not_before(inputs):
    radius, load, _ = inputs
    bad_load = da.where(da.arange(load.size) == 7000, -1.0, lazy(load))
    c = hertz.contact(hertz.Body.sphere(lazy(radius), *STEEL), hertz.Body.plane(*STEEL),
                      load=bad_load)  # nothing is computed yet
    with pytest.raises(ValueError, match=r"load must be a finite value >= 0 in N, got -1\.0"):
        c.a.compute()
    bad_alpha = da.where(da.arange(load.size) == 3, 0.0, lazy(load))
    out = hertz.ellipticity(bad_alpha)
    with pytest.raises(ValueError, match=r"alpha must be a positive number.*got 0\.0"):
        out.compute()
    bad_body = hertz.Body.sphere(da.where(da.arange(load.size) == 5, 0.0, lazy(radius)), *STEEL)
    with pytest.raises(ValueError, match=r"body1\.Rx must be a nonzero radius"):
        hertz.contact(bad_body, hertz.Body.plane(*STEEL), load=1.0).b.compute()
