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


# --- issue 18, item 8: mixed inputs, chunks, the methods, errors with the global index ---

FIELDS = ("a", "b", "load", "p0", "delta", "stiffness", "ellipticity", "alpha", "m", "K", "E",
          "e_star", "rho_x", "rho_y", "major_axis_angle")


@pytest.fixture
def no_compute():
    """Fail if anything is computed inside the block (the results must stay lazy)."""
    import dask

    def refuse(*args, **kwargs):
        raise AssertionError("something was computed")

    with dask.config.set(scheduler=refuse):
        yield


def assert_same_contact(lazy_contact, ref):
    for field in FIELDS:
        value = getattr(lazy_contact, field)
        assert isinstance(value, da.Array), field
        np.testing.assert_array_equal(value.compute(), getattr(ref, field), err_msg=field)


def test_numpy_beside_dask_takes_the_dask_chunks(inputs):
    radius, load, angle = inputs
    race = hertz.Body(-0.03, 0.05, 70e9, 0.33)
    lazy_load = da.from_array(load, chunks=3000)
    c = hertz.contact(hertz.Body.sphere(radius, *STEEL), race, load=lazy_load, angle=angle)
    assert c.a.chunks == lazy_load.chunks
    assert_same_contact(c, hertz.contact(hertz.Body.sphere(radius, *STEEL), race, load=load,
                                         angle=angle))


def test_differently_chunked_dask_arrays(inputs):
    radius, load, angle = inputs
    race = hertz.Body(-0.03, 0.05, 70e9, 0.33)
    c = hertz.contact(hertz.Body.sphere(da.from_array(radius, chunks=3000), *STEEL), race,
                      load=da.from_array(load, chunks=4000),
                      angle=da.from_array(angle, chunks=(1000, 2500, 6500)))
    assert_same_contact(c, hertz.contact(hertz.Body.sphere(radius, *STEEL), race, load=load,
                                         angle=angle))


def test_only_the_load_lazy_gives_lazy_geometry(inputs, no_compute):
    _, load, _ = inputs
    ball, race = hertz.Body.sphere(6e-3, *STEEL), hertz.Body(-6.2e-3, 40e-3, *STEEL)
    c = hertz.contact(ball, race, load=lazy(load))
    for field in FIELDS:
        value = getattr(c, field)
        assert isinstance(value, da.Array) and value.shape == load.shape, field


def test_only_the_load_lazy_is_exact(inputs):
    _, load, _ = inputs
    ball, race = hertz.Body.sphere(6e-3, *STEEL), hertz.Body(-6.2e-3, 40e-3, *STEEL)
    assert_same_contact(hertz.contact(ball, race, load=lazy(load)),
                        hertz.contact(ball, race, load=load))


def test_broadcast_of_dask_against_numpy():
    radius = np.linspace(2e-3, 2e-2, 7)[:, None]
    load = np.linspace(1.0, 2e3, 5)
    plane = hertz.Body.plane(*STEEL)
    c = hertz.contact(hertz.Body.sphere(da.from_array(radius, chunks=(3, 1)), *STEEL), plane,
                      load=load)
    assert c.a.shape == (7, 5)
    assert_same_contact(c, hertz.contact(hertz.Body.sphere(radius, *STEEL), plane, load=load))


def test_methods_of_a_lazy_contact_are_lazy(inputs, no_compute):
    radius, load, _ = inputs
    c = hertz.contact(hertz.Body.sphere(lazy(radius), *STEEL), hertz.Body.plane(*STEEL),
                      load=lazy(load))
    assert c.stress(0.0, 0.0, 1e-4).shape == load.shape + (3, 3)
    assert isinstance(c.stress(0.0, 0.0, 1e-4), da.Array)
    assert all(isinstance(v, da.Array) for v in vars_of(c.subsurface()))
    assert isinstance(c.first_yield_load(1e9), da.Array)
    assert isinstance(c.pressure(0.0, 0.0), da.Array)


def vars_of(result):
    import dataclasses

    return [getattr(result, f.name) for f in dataclasses.fields(result)]


def test_methods_of_a_lazy_contact_are_exact(inputs):
    radius, load, _ = inputs
    plane = hertz.Body.plane(70e9, 0.33)
    c = hertz.contact(hertz.Body.sphere(da.from_array(radius, chunks=3000), *STEEL), plane,
                      load=lazy(load))
    ref = hertz.contact(hertz.Body.sphere(radius, *STEEL), plane, load=load)
    x, z = np.linspace(-1e-4, 1e-4, load.size), np.linspace(0.0, 3e-4, load.size)
    for body in (1, 2):
        np.testing.assert_array_equal(c.stress(x, 0.0, z, body=body).compute(),
                                      ref.stress(x, 0.0, z, body=body))
        for lazy_field, field in zip(vars_of(c.subsurface(body)), vars_of(ref.subsurface(body)),
                                     strict=True):
            np.testing.assert_array_equal(lazy_field.compute(), field)
        for criterion in ("von_mises", "tresca"):
            np.testing.assert_array_equal(
                c.first_yield_load(1.2e9, body, criterion).compute(),
                ref.first_yield_load(1.2e9, body, criterion))
    np.testing.assert_array_equal(c.pressure(x, 0.0).compute(), ref.pressure(x, 0.0))


def test_line_contact_methods_on_dask(inputs):
    radius, load, _ = inputs
    plane = hertz.Body.plane(*STEEL)
    lc = hertz.line_contact(hertz.Body.cylinder(lazy(radius), *STEEL), plane, load)
    ref = hertz.line_contact(hertz.Body.cylinder(radius, *STEEL), plane, load)
    np.testing.assert_array_equal(lc.stress(1e-5, 2e-5).compute(), ref.stress(1e-5, 2e-5))
    for lazy_field, field in zip(vars_of(lc.subsurface()), vars_of(ref.subsurface()),
                                 strict=True):
        np.testing.assert_array_equal(lazy_field.compute(), field)


def test_compute_errors_name_the_global_index(inputs):
    radius, load, _ = inputs
    plane = hertz.Body.plane(*STEEL)
    bad = load.copy()
    bad[7777] = -1.0  # in the fourth of four chunks, at 7777 - 7500 = 277 within it
    c = hertz.contact(hertz.Body.sphere(da.from_array(radius, chunks=3000), *STEEL), plane,
                      load=lazy(bad))
    with pytest.raises(ValueError, match=r"^load must be a finite value >= 0 in N, got -1\.0 "
                                         r"at index 7777$"):
        c.a.compute()
    bad_radius = radius.copy()
    bad_radius[6001] = 0.0
    c = hertz.contact(hertz.Body.sphere(da.from_array(bad_radius, chunks=2000), *STEEL), plane,
                      load=load)
    for field in ("b", "rho_x"):  # the load pass and the geometry pass
        with pytest.raises(ValueError, match=r"body1\.Rx must be a nonzero radius.*got 0\.0 at "
                                             r"index 6001$"):
            getattr(c, field).compute()
    alpha = load.copy()
    alpha[9999] = 0.0
    with pytest.raises(ValueError, match=r"alpha must be a positive.*got 0\.0 at index 9999$"):
        hertz.ellipticity(lazy(alpha)).compute()


def test_compute_errors_name_the_global_index_in_2d():
    radius = da.from_array(np.linspace(2e-3, 2e-2, 40).reshape(4, 10), chunks=(3, 4))
    c = hertz.contact(hertz.Body.sphere(radius, *STEEL), hertz.Body.plane(*STEEL), load=10.0)
    depth = np.full((4, 10), 1e-5)
    depth[3, 9] = -2.0
    with pytest.raises(ValueError, match=r"z must be a depth >= 0 in m.*, got -2\.0 at index "
                                         r"\(3, 9\)$"):
        c.stress(0.0, 0.0, depth).compute()
    strength = np.full(10, 1e9)
    strength[6] = -5.0  # broadcast over the rows: one of (0, 6) .. (3, 6)
    with pytest.raises(ValueError, match=r"yield_strength must be a positive.*got -5\.0 at "
                                         r"index \([0-3], 6\)$"):
        c.first_yield_load(strength).compute()
    line = hertz.line_contact(hertz.Body.cylinder(radius, *STEEL), hertz.Body.plane(*STEEL),
                              da.where(da.arange(10) == 8, -1.0, 1e5))
    with pytest.raises(ValueError, match=r"load_per_length must be.*got -1\.0 at index "
                                         r"\([0-3], 8\)$"):
        line.p0.compute()


def test_bad_options_and_types_raise_at_once_not_at_compute(no_compute):
    radius = da.from_array(np.linspace(1e-2, 2e-2, 10), chunks=3)
    c = hertz.contact(hertz.Body.sphere(radius, *STEEL), hertz.Body.plane(*STEEL), load=1.0)
    with pytest.raises(ValueError, match=r"^body must be 1 or 2, got 3$"):
        c.subsurface(body=3)
    with pytest.raises(ValueError, match=r"^criterion must be one of"):
        c.first_yield_load(1e9, criterion="rankine")
    with pytest.raises(TypeError, match=r"^z must be a real number"):
        c.stress(0.0, 0.0, "deep")
    with pytest.raises(TypeError, match=r"^load must be a real number.*dask array of dtype bool"):
        hertz.contact(hertz.Body.sphere(radius, *STEEL), hertz.Body.plane(*STEEL),
                      load=da.ones(10, dtype=bool, chunks=5))


def test_zero_dimensional_dask_arrays():
    ball = hertz.Body.sphere(da.from_array(np.array(0.01)), *STEEL)
    ref = hertz.contact(hertz.Body.sphere(0.01, *STEEL), hertz.Body.plane(*STEEL), load=10.0)
    c = hertz.contact(ball, hertz.Body.plane(*STEEL), load=10.0)
    for field in FIELDS:
        assert getattr(c, field).compute() == getattr(ref, field), field
    assert c.subsurface().tau_max.compute() == ref.subsurface().tau_max
    bad = hertz.contact(ball, hertz.Body.plane(*STEEL), load=da.from_array(np.array(-1.0)))
    with pytest.raises(ValueError, match=r"^load must be a finite value >= 0 in N, got -1\.0$"):
        bad.p0.compute()
