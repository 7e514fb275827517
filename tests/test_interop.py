"""hertz on pandas, xarray and pint inputs (issue 18, item 8).

The reference is hertz's own numpy path on the same values (the wrappers must
not change a bit), plus the semantics promised in the Contact docstring:
index, dimensions and units preserved; a closed form checks the pint path
independently.
"""

import dataclasses
import math
import subprocess
import sys

import numpy as np
import pytest

import hertz

STEEL = (210e9, 0.3)
FIELDS = ("a", "b", "load", "p0", "delta", "stiffness", "ellipticity", "alpha", "m", "K", "E",
          "e_star", "rho_x", "rho_y", "major_axis_angle")
UNITS = {"a": "m", "b": "m", "load": "N", "p0": "Pa", "delta": "m", "stiffness": "N/m",
         "ellipticity": "", "alpha": "", "m": "", "K": "", "E": "", "e_star": "Pa",
         "rho_x": "1/m", "rho_y": "1/m", "major_axis_angle": "rad"}


@pytest.fixture
def pd():
    return pytest.importorskip("pandas", reason="pandas is not installed")


@pytest.fixture
def xr():
    return pytest.importorskip("xarray", reason="xarray is not installed")


@pytest.fixture
def ureg():
    pint = pytest.importorskip("pint", reason="pint is not installed")
    return pint.UnitRegistry()


def fields_of(result):
    return {f.name: getattr(result, f.name) for f in dataclasses.fields(result)}


def test_import_hertz_imports_none_of_them():
    code = ("import sys, hertz; print(sorted({m.split('.')[0] for m in sys.modules} & "
            "{'dask', 'pandas', 'xarray', 'pint', 'matplotlib'}))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "[]"


# ------------------------------------------------------------------------------ pandas

@pytest.fixture
def table(pd):
    rng = np.random.default_rng(5)
    index = pd.Index([f"ball{i}" for i in range(6)], name="part")
    return pd.DataFrame({"radius": rng.uniform(2e-3, 2e-2, 6), "load": rng.uniform(1, 2e3, 6),
                         "angle": rng.uniform(-3, 3, 6)}, index=index)


def test_series_of_radii_and_loads_give_series_on_the_index(pd, table):
    race = hertz.Body(-0.03, 0.05, 70e9, 0.33)
    c = hertz.contact(hertz.Body.sphere(table["radius"], *STEEL), race, load=table["load"],
                      angle=table["angle"])
    ref = hertz.contact(hertz.Body.sphere(table["radius"].to_numpy(), *STEEL), race,
                        load=table["load"].to_numpy(), angle=table["angle"].to_numpy())
    for field in FIELDS:
        value = getattr(c, field)
        assert isinstance(value, pd.Series), field
        assert value.index.equals(table.index) and value.name == field
        np.testing.assert_array_equal(value.to_numpy(), getattr(ref, field), err_msg=field)
    for derived in ("rho_sum", "p_mean", "area"):
        assert isinstance(getattr(c, derived), pd.Series)
        np.testing.assert_array_equal(getattr(c, derived).to_numpy(), getattr(ref, derived))


def test_series_beside_numpy_and_scalars_broadcast_by_position(pd, table):
    plane = hertz.Body.plane(*STEEL)
    load = np.linspace(10.0, 60.0, 6)
    c = hertz.contact(hertz.Body.sphere(table["radius"], *STEEL), plane, load=load)
    ref = hertz.contact(hertz.Body.sphere(table["radius"].to_numpy(), *STEEL), plane, load=load)
    assert c.a.index.equals(table.index)
    np.testing.assert_array_equal(c.a.to_numpy(), ref.a)
    c = hertz.contact(hertz.Body.sphere(0.01, *STEEL), plane, load=table["load"])
    assert c.rho_x.index.equals(table.index)  # the geometry too, though it is one
    np.testing.assert_array_equal(c.rho_x.to_numpy(), np.full(6, 100.0))  # 1/R


def test_dataframe_columns_and_whole_dataframes(pd, table):
    plane = hertz.Body.plane(*STEEL)
    frame = table[["radius", "load"]]
    c = hertz.contact(hertz.Body.sphere(frame, *STEEL), plane, load=frame * 1e3)
    assert isinstance(c.p0, pd.DataFrame)
    assert c.p0.index.equals(frame.index) and c.p0.columns.equals(frame.columns)
    ref = hertz.contact(hertz.Body.sphere(frame.to_numpy(), *STEEL), plane,
                        load=frame.to_numpy() * 1e3)
    np.testing.assert_array_equal(c.p0.to_numpy(), ref.p0)


def test_pandas_inputs_are_not_aligned_but_refused(pd, table):
    plane = hertz.Body.plane(*STEEL)
    ball = hertz.Body.sphere(table["radius"], *STEEL)
    with pytest.raises(ValueError, match=r"index of load differs from that of body1\.Rx.*align"):
        hertz.contact(ball, plane, load=table["load"].iloc[::-1])
    with pytest.raises(ValueError, match=r"load of shape \(4,\) does not broadcast to the "
                                         r"shape \(6,\)"):
        hertz.contact(ball, plane, load=np.ones(4))
    with pytest.raises(TypeError, match="all as DataFrames"):
        hertz.contact(hertz.Body.sphere(table[["radius"]], *STEEL), plane, load=table["load"])


def test_pandas_bad_values_name_parameter_value_and_index(pd, table):
    plane = hertz.Body.plane(*STEEL)
    load = table["load"].copy()
    load.iloc[2] = -1.0
    with pytest.raises(ValueError, match=r"load must be a finite value >= 0 in N, got -1\.0 at "
                                         r"index 2 \(label 'ball2'\)$"):
        hertz.contact(hertz.Body.sphere(table["radius"], *STEEL), plane, load=load)
    radius = pd.Series([0.01, None, 0.02], dtype="Float64")  # a missing value
    with pytest.raises(ValueError, match=r"^Rx must be a nonzero radius.*got nan at index 1$"):
        hertz.Body.sphere(radius, *STEEL)
    nu = pd.Series([0.3, 0.3, 0.7], index=["p", "q", "r"])
    with pytest.raises(ValueError, match=r"^nu must be a Poisson's ratio.*got 0\.7 at index 2 "
                                         r"\(label 'r'\)$"):
        hertz.Body.sphere(0.01, 210e9, nu)
    frame = pd.DataFrame({"x": [1.0, 2.0], "y": [3.0, -4.0]}, index=["r1", "r2"])
    with pytest.raises(ValueError, match=r"got -4\.0 at index \(1, 1\) \(row 'r2', column 'y'\)$"):
        hertz.contact(hertz.Body.sphere(0.01, *STEEL), plane, load=frame)
    with pytest.raises(TypeError, match="Rx must be a real number"):
        hertz.Body.sphere(pd.Series(["a", "b"]), *STEEL)


def test_body_keeps_its_own_series(pd, table):
    radius = table["radius"].copy()
    ball = hertz.Body.sphere(radius, *STEEL)
    first = radius.iloc[0]
    radius.iloc[0] = 1.0  # the caller's Series changes afterwards
    assert isinstance(ball.Rx, pd.Series) and ball.Rx.index.equals(table.index)
    assert ball.Rx.iloc[0] == first


def test_methods_of_a_pandas_contact(pd, table):
    plane = hertz.Body.plane(70e9, 0.33)
    c = hertz.contact(hertz.Body.sphere(table["radius"], *STEEL), plane, load=table["load"])
    ref = hertz.contact(hertz.Body.sphere(table["radius"].to_numpy(), *STEEL), plane,
                        load=table["load"].to_numpy())
    depth = pd.Series(np.linspace(0.0, 1e-4, 6), index=table.index)
    stress = c.stress(0.0, 0.0, depth, body=2)
    assert type(stress) is np.ndarray  # a tensor has no pandas form: numpy, in index order
    np.testing.assert_array_equal(stress, ref.stress(0.0, 0.0, depth.to_numpy(), body=2))
    for name, value in fields_of(c.subsurface()).items():
        assert isinstance(value, pd.Series) and value.index.equals(table.index), name
        np.testing.assert_array_equal(value.to_numpy(), getattr(ref.subsurface(), name))
    fyl = c.first_yield_load(1.5e9, criterion="tresca")
    assert isinstance(fyl, pd.Series) and fyl.index.equals(table.index)
    np.testing.assert_array_equal(fyl.to_numpy(), ref.first_yield_load(1.5e9, criterion="tresca"))
    p = c.pressure(depth, 0.0)
    np.testing.assert_array_equal(p.to_numpy(), ref.pressure(depth.to_numpy(), 0.0))


def test_line_contact_and_ellipticity_of_series(pd, table):
    plane = hertz.Body.plane(*STEEL)
    lc = hertz.line_contact(hertz.Body.cylinder(table["radius"], *STEEL), plane,
                            table["load"] * 1e3)
    ref = hertz.line_contact(hertz.Body.cylinder(table["radius"].to_numpy(), *STEEL), plane,
                             table["load"].to_numpy() * 1e3)
    for name, value in fields_of(lc).items():
        if name != "_nu":
            assert isinstance(value, pd.Series) and value.index.equals(table.index), name
            np.testing.assert_array_equal(value.to_numpy(), getattr(ref, name))
    sub = lc.subsurface()
    np.testing.assert_array_equal(sub.z_tau_max.to_numpy(), ref.subsurface().z_tau_max)
    alpha = pd.Series([1.0, 10.0, 1e6], index=["x", "y", "z"])
    lam = hertz.ellipticity(alpha)
    assert isinstance(lam, pd.Series) and list(lam.index) == ["x", "y", "z"]
    np.testing.assert_array_equal(lam.to_numpy(), hertz.ellipticity(alpha.to_numpy()))


def test_mixtures_that_are_refused(pd, xr, table):
    da = pytest.importorskip("dask.array")
    plane = hertz.Body.plane(*STEEL)
    with pytest.raises(TypeError, match="dask array beside the pandas input"):
        hertz.contact(hertz.Body.sphere(table["radius"], *STEEL), plane,
                      load=da.ones(6, chunks=3))
    with pytest.raises(TypeError, match="pandas or xarray inputs, not both"):
        hertz.contact(hertz.Body.sphere(table["radius"], *STEEL), plane,
                      load=xr.DataArray(np.ones(6), dims="part"))


# ------------------------------------------------------------------------------ xarray

def test_dataarrays_broadcast_by_dimension_name(xr):
    radius = xr.DataArray([4e-3, 6e-3, 8e-3], dims="ball", coords={"ball": [4, 6, 8]})
    load = xr.DataArray([100.0, 500.0], dims="load", coords={"load": [100, 500]})
    angle = xr.DataArray([[0.0, 0.3, 0.6], [0.1, 0.4, 0.7]], dims=("load", "ball"))
    race = hertz.Body(-0.03, 0.05, 70e9, 0.33)
    c = hertz.contact(hertz.Body.sphere(radius, *STEEL), race, load=load, angle=angle)
    ref = hertz.contact(hertz.Body.sphere(radius.values[:, None], *STEEL), race,
                        load=load.values[None, :], angle=angle.values.T)
    for field in FIELDS:
        value = getattr(c, field)
        assert isinstance(value, xr.DataArray) and value.dims == ("ball", "load"), field
        assert list(value["ball"].values) == [4, 6, 8] and value.name == field
        np.testing.assert_array_equal(value.values, getattr(ref, field), err_msg=field)


def test_dataarray_coordinates_must_match(xr):
    radius = xr.DataArray([4e-3, 6e-3], dims="case", coords={"case": [0, 1]})
    load = xr.DataArray([10.0, 20.0], dims="case", coords={"case": [1, 2]})
    with pytest.raises(ValueError, match=r"coordinates of body1\.Rx, body1\.Ry, load differ"):
        hertz.contact(hertz.Body.sphere(radius, *STEEL), hertz.Body.plane(*STEEL), load=load)
    with pytest.raises(ValueError, match=r"load of shape \(3,\) does not broadcast"):
        hertz.contact(hertz.Body.sphere(radius, *STEEL), hertz.Body.plane(*STEEL),
                      load=np.ones(3))
    load = xr.DataArray([1.0, -5.0], dims="load")
    with pytest.raises(ValueError, match=r"got -5\.0 at index \(0, 1\) \(case=0, load=1\)$"):
        hertz.contact(hertz.Body.sphere(radius, *STEEL), hertz.Body.plane(*STEEL), load=load)


def test_dask_backed_dataarrays_stay_lazy(xr):
    pytest.importorskip("dask.array")
    import dask

    radius = xr.DataArray(np.linspace(2e-3, 2e-2, 50), dims="ball").chunk(20)
    load = xr.DataArray(np.linspace(1.0, 1e3, 4), dims="load")
    plane = hertz.Body.plane(*STEEL)

    def refuse(*args, **kwargs):
        raise AssertionError("something was computed")

    with dask.config.set(scheduler=refuse):
        c = hertz.contact(hertz.Body.sphere(radius, *STEEL), plane, load=load)
        sub = c.subsurface()
        assert c.a.chunks is not None and sub.tau_max.chunks is not None
        assert c.a.dims == ("ball", "load")
    ref = hertz.contact(hertz.Body.sphere(radius.values[:, None], *STEEL), plane,
                        load=load.values)
    np.testing.assert_array_equal(c.a.values, ref.a)
    np.testing.assert_array_equal(sub.tau_max.values, ref.subsurface().tau_max)


def test_methods_of_an_xarray_contact(xr):
    radius = xr.DataArray([4e-3, 6e-3, 8e-3], dims="ball")
    plane = hertz.Body.plane(*STEEL)
    c = hertz.contact(hertz.Body.sphere(radius, *STEEL), plane, load=100.0)
    ref = hertz.contact(hertz.Body.sphere(radius.values[:, None], *STEEL), plane, load=100.0)
    depth = xr.DataArray([0.0, 5e-5, 1e-4, 2e-4], dims="depth")
    s = c.stress(0.0, 0.0, depth)
    assert s.dims == ("ball", "depth", "row", "column")
    np.testing.assert_array_equal(s.values, ref.stress(0.0, 0.0, depth.values[None, :]))
    assert float(s.sel(row="z", column="z")[0, 0]) == -ref.p0[0, 0]  # sigma_zz = -p0
    fyl = c.first_yield_load(1e9)
    assert fyl.dims == ("ball",)
    np.testing.assert_array_equal(fyl.values, ref.first_yield_load(1e9)[:, 0])


# ------------------------------------------------------------------------------ pint

def test_sphere_of_quantities_is_kept_in_si(ureg):
    ball = hertz.Body.sphere(5 * ureg.mm, 210 * ureg.GPa, 0.3)
    assert ball.Rx.units == ureg.m and ball.E.units == ureg.Pa
    assert ball.Rx.magnitude == (5 * ureg.mm).to("m").magnitude and ball.E.magnitude == 210e9
    assert ball.nu == 0.3


def test_contact_of_quantities_gives_quantities_in_si(ureg):
    ball = hertz.Body.sphere(5 * ureg.mm, 210 * ureg.GPa, 0.3)
    plane = hertz.Body.plane(210 * ureg.GPa, 0.3)
    c = hertz.contact(ball, plane, load=0.1 * ureg.kN)
    ref = hertz.contact(hertz.Body.sphere(ball.Rx.magnitude, *STEEL), hertz.Body.plane(*STEEL),
                        load=(0.1 * ureg.kN).to("N").magnitude)
    for field in FIELDS:
        value = getattr(c, field)
        assert value.units == ureg.Unit(UNITS[field] or "dimensionless"), field
        assert value.magnitude == getattr(ref, field), field
    assert c.area.units == ureg.m ** 2
    # an independent check: sphere on a plane at 50 digits, a = (3 P R / (4 E*))**(1/3),
    # E* = E / (2 (1 - nu**2)), p0 = 3 P / (2 pi a**2), delta = a**2 / R
    mp = pytest.importorskip("mpmath").mp
    mp.dps = 50
    e_star = mp.mpf(210e9) / (2 * (1 - mp.mpf("0.3") ** 2))
    radius, load = mp.mpf(5) / 1000, mp.mpf(100)
    a = (3 * load * radius / (4 * e_star)) ** (mp.mpf(1) / 3)
    # observed 3e-17, 3.8e-16, 8e-17 (AMD EPYC): one ulp, and 1.5x for p0
    assert abs(c.a.magnitude / a - 1) < 2.3e-16
    assert abs(c.p0.magnitude / (3 * load / (2 * mp.pi * a * a)) - 1) < 6e-16
    assert abs(c.delta.magnitude / (a * a / radius) - 1) < 2.3e-16
    assert math.isclose(c.a.to("mm").magnitude, c.a.magnitude * 1e3, rel_tol=2.3e-16)


def test_quantity_arrays_approach_p0_and_angles(ureg):
    ball = hertz.Body(6 * ureg.mm, 6 * ureg.mm, 210 * ureg.GPa, 0.3)
    race = hertz.Body(-6.2e-3, 40e-3, *STEEL)  # plain numbers beside quantities: SI
    c = hertz.contact(ball, race, approach=np.array([1.0, 5.0, 10.0]) * ureg.um)
    ref = hertz.contact(hertz.Body(6e-3, 6e-3, *STEEL), race, approach=np.array([1e-6, 5e-6, 1e-5]))
    np.testing.assert_allclose(c.load.to("N").magnitude, ref.load, rtol=1e-15)
    c = hertz.contact(ball, race, p0=2 * ureg.GPa)
    assert c.load.units == ureg.N and c.load.magnitude == hertz.contact(
        hertz.Body(6e-3, 6e-3, *STEEL), race, p0=2e9).load
    cyl = hertz.Body.cylinder(10 * ureg.mm, *STEEL)
    crossed = hertz.contact(cyl, cyl, load=10.0, angle=90 * ureg.degree)
    plain = hertz.contact(hertz.Body.cylinder(0.01, *STEEL), hertz.Body.cylinder(0.01, *STEEL),
                          load=10.0, angle=math.pi / 2)
    assert math.isclose(crossed.a.magnitude, plain.a, rel_tol=1e-15)


def test_quantities_of_the_wrong_dimension_are_refused(ureg):
    with pytest.raises(TypeError, match=r"^Rx must be a length \(a quantity convertible to m\), "
                                        r"got a quantity in kilogram$"):
        hertz.Body.sphere(5 * ureg.kg, 210 * ureg.GPa, 0.3)
    with pytest.raises(TypeError, match=r"^E must be a pressure \(or modulus\) \(a quantity "
                                        r"convertible to Pa\), got a quantity in millimeter$"):
        hertz.Body.sphere(5 * ureg.mm, 210 * ureg.mm, 0.3)
    ball = hertz.Body.sphere(5 * ureg.mm, 210 * ureg.GPa, 0.3)
    with pytest.raises(TypeError, match=r"^load must be a force.*convertible to N\), got a "
                                        r"quantity in millimeter$"):
        hertz.contact(ball, ball, load=5 * ureg.mm)
    with pytest.raises(TypeError, match=r"^angle must be an angle.*got a quantity in meter$"):
        hertz.contact(ball, ball, load=5.0, angle=1 * ureg.m)
    with pytest.raises(ValueError, match=r"^Rx must be a nonzero radius.*got 0\.0 at index 1$"):
        hertz.Body.sphere(np.array([1.0, 0.0]) * ureg.mm, *STEEL)


def test_methods_of_a_quantity_contact(ureg):
    ball = hertz.Body.sphere(5 * ureg.mm, 210 * ureg.GPa, 0.3)
    plane = hertz.Body.plane(*STEEL)
    c = hertz.contact(ball, plane, load=100 * ureg.N)
    ref = hertz.contact(hertz.Body.sphere(5e-3, *STEEL), plane, load=100.0)
    s = c.stress(0 * ureg.mm, 0 * ureg.mm, 0.05 * ureg.mm)
    assert s.units == ureg.Pa
    np.testing.assert_array_equal(s.magnitude, ref.stress(0.0, 0.0, (0.05 * ureg.mm).to("m")
                                                          .magnitude))
    for name, value in fields_of(c.subsurface()).items():
        unit = ureg.m if name[:2] in ("x_", "y_", "z_") else ureg.Pa
        assert value.units == unit and value.magnitude == getattr(ref.subsurface(), name), name
    fyl = c.first_yield_load(900 * ureg.MPa)
    assert fyl.units == ureg.N and fyl.magnitude == ref.first_yield_load(900e6)
    assert c.pressure(c.a, 0 * ureg.m).magnitude == 0.0
    with pytest.raises(TypeError, match=r"^yield_strength must be a pressure"):
        c.first_yield_load(900 * ureg.N)
    roller = hertz.Body.cylinder(5 * ureg.mm, *STEEL)
    lc = hertz.line_contact(roller, plane, 100 * ureg.N / ureg.mm)
    assert lc.half_width.units == ureg.m and lc.load_per_length.magnitude == 1e5
    assert lc.half_width.magnitude == hertz.line_contact(hertz.Body.cylinder(5e-3, *STEEL), plane,
                                                         1e5).half_width


def test_quantities_with_pandas_are_refused(ureg, pd):
    with pytest.raises(TypeError, match="pint Quantities inside or beside pandas"):
        hertz.contact(hertz.Body.sphere(5 * ureg.mm, *STEEL), hertz.Body.plane(*STEEL),
                      load=pd.Series([1.0, 2.0]))


def test_complex_and_non_numeric_pandas_are_refused(pd):
    with pytest.raises(TypeError, match=r"^Rx must be a real number.*complex128"):
        hertz.Body.sphere(pd.Series([1e-2 + 1e-3j]), *STEEL)
    with pytest.raises(TypeError, match=r"^Rx must be a number, an array, a pandas Series"):
        hertz.Body.sphere(pd.Index([1e-2]), *STEEL)


def test_quantities_of_dask_arrays_stay_lazy(ureg):
    da = pytest.importorskip("dask.array")
    radius = da.from_array(np.array([4.0, 6.0, 8.0]), chunks=2) * ureg.mm
    c = hertz.contact(hertz.Body.sphere(radius, *STEEL), hertz.Body.plane(*STEEL), load=10.0)
    assert isinstance(c.a.magnitude, da.Array) and c.a.units == ureg.m
    ref = hertz.contact(hertz.Body.sphere(np.array([4.0, 6.0, 8.0]) * 1e-3, *STEEL),
                        hertz.Body.plane(*STEEL), load=10.0)
    np.testing.assert_array_equal(c.a.magnitude.compute(), ref.a)


def test_line_contact_of_dataarrays(xr):
    radius = xr.DataArray([4e-3, 8e-3], dims="roller", coords={"roller": ["r4", "r8"]})
    load = xr.DataArray([1e4, 1e5, 1e6], dims="load")
    plane = hertz.Body.plane(*STEEL)
    lc = hertz.line_contact(hertz.Body.cylinder(radius, *STEEL), plane, load)
    ref = hertz.line_contact(hertz.Body.cylinder(radius.values[:, None], *STEEL), plane,
                             load.values)
    assert lc.half_width.dims == ("roller", "load")
    np.testing.assert_array_equal(lc.half_width.values, ref.half_width)
    np.testing.assert_array_equal(lc.stress(0.0, 1e-5).values, ref.stress(0.0, 1e-5))


# ------------------------------------------------------------------------------ tangential

TANGENTIAL_UNITS = {"force": "N", "mu": "", "direction": "rad", "stick_a": "m", "stick_b": "m",
                    "slip_area": "m**2", "displacement": "m", "displacement_transverse": "m",
                    "stiffness": "N/m", "no_slip_stiffness": "N/m", "dundurs_beta": ""}
FRETTING_UNITS = {"amplitude": "N", "displacement_amplitude": "m", "energy": "J",
                  "stiffness": "N/m", "mu": "", "load": "N"}


def public(result):
    return {k: v for k, v in fields_of(result).items() if not k.startswith("_")}


def test_tangential_of_a_quantity_contact_in_si_units(ureg):
    ball = hertz.Body.sphere(5 * ureg.mm, 210 * ureg.GPa, 0.3)
    glass = hertz.Body.plane(70 * ureg.GPa, 0.22)
    c = hertz.contact(ball, glass, load=0.1 * ureg.kN)
    ref = hertz.contact(hertz.Body.sphere(5e-3, *STEEL), hertz.Body.plane(70e9, 0.22), load=100.0)
    k = c.tangential_stiffness(30 * ureg.deg)
    assert k.units == ureg.N / ureg.m and k.magnitude == ref.tangential_stiffness(math.pi / 6)
    t = c.tangential(12 * ureg.N, 0.3, direction=1.0)
    t_ref = ref.tangential(12.0, 0.3, direction=1.0)
    for name, unit in TANGENTIAL_UNITS.items():
        value = getattr(t, name)
        assert value.units == ureg.Unit(unit or "dimensionless"), name
        assert value.magnitude == getattr(t_ref, name), name
    assert t.sliding is False
    x = 0.5 * c.a
    tr = t.traction(x.to("mm"), 0 * ureg.m)
    assert tr.units == ureg.Pa and tr.magnitude == t_ref.traction(0.5 * ref.a, 0.0)
    loop = c.fretting(5000 * ureg.mN, 0.3)
    loop_ref = ref.fretting(5.0, 0.3)
    for name, unit in FRETTING_UNITS.items():
        value = getattr(loop, name)
        assert value.units == ureg.Unit(unit or "dimensionless"), name
        assert value.magnitude == getattr(loop_ref, name), name
    assert loop.unloading(-2 * ureg.N).magnitude == loop_ref.unloading(-2.0)
    assert loop.reloading(1 * ureg.N).units == ureg.m
    # a closed form beside the numpy path: W -> 2 Q*^3 / (9 mu P k) as Q* / (mu P) -> 0
    small = c.fretting(1 * ureg.mN, 0.3).energy.to("J").magnitude
    k0 = c.tangential_stiffness().magnitude
    assert abs(small / (2 * 1e-9 / (9 * 0.3 * 100.0 * k0)) - 1) < 1e-4
    with pytest.raises(TypeError, match=r"^force must be a force"):
        c.tangential(12 * ureg.m, 0.3)
    with pytest.raises(ValueError, match=r"^mu must be a positive"):
        c.fretting(1 * ureg.N, -0.3)


def test_tangential_of_pandas_and_xarray_contacts(pd, xr, table):
    plane = hertz.Body.plane(70e9, 0.33)
    c = hertz.contact(hertz.Body.sphere(table["radius"], *STEEL), plane, load=table["load"])
    ref = hertz.contact(hertz.Body.sphere(table["radius"].to_numpy(), *STEEL), plane,
                        load=table["load"].to_numpy())
    force = 0.1 * table["load"]
    k = c.tangential_stiffness(table["angle"])
    assert k.name == "tangential_stiffness" and k.index.equals(table.index)
    np.testing.assert_array_equal(k.to_numpy(), ref.tangential_stiffness(table["angle"]
                                                                           .to_numpy()))
    t, t_ref = c.tangential(force, 0.3), ref.tangential(force.to_numpy(), 0.3)
    for name, value in public(t).items():
        assert isinstance(value, pd.Series) and value.name == name, name
        assert value.index.equals(table.index), name
        np.testing.assert_array_equal(value.to_numpy(), np.broadcast_to(getattr(t_ref, name),
                                                                         (6,)), err_msg=name)
    assert t.sliding.dtype == bool
    tr = t.traction(0.3 * c.a, 0.0)
    assert tr.name == "traction"
    np.testing.assert_array_equal(tr.to_numpy(), t_ref.traction(0.3 * ref.a, 0.0))
    loop, loop_ref = c.fretting(force, 0.3), ref.fretting(force.to_numpy(), 0.3)
    for name, value in public(loop).items():
        assert isinstance(value, pd.Series) and value.name == name, name
        np.testing.assert_array_equal(value.to_numpy(), np.broadcast_to(getattr(loop_ref, name),
                                                                         (6,)), err_msg=name)
    with pytest.raises(ValueError, match=r"force must be at most mu \* load .* at index 2 "
                                         r"\(label 'ball2'\)"):
        c.tangential(force.where(force.index != "ball2", 1e6), 0.3)

    radius = xr.DataArray([4e-3, 6e-3, 8e-3], dims="ball")
    mu = xr.DataArray([0.2, 0.5], dims="friction")
    cx = hertz.contact(hertz.Body.sphere(radius, *STEEL), plane, load=100.0)
    ref = hertz.contact(hertz.Body.sphere(radius.values[:, None], *STEEL), plane, load=100.0)
    tx, tx_ref = cx.tangential(15.0, mu), ref.tangential(15.0, mu.values[None, :])
    assert tx.stick_b.dims == ("ball", "friction") and tx.stick_b.name == "stick_b"
    np.testing.assert_array_equal(tx.displacement.values, tx_ref.displacement)
    fx = cx.fretting(15.0, mu)
    assert fx.energy.name == "energy"
    np.testing.assert_array_equal(fx.energy.values, ref.fretting(15.0, mu.values[None, :]).energy)


def test_tangential_of_quantities_of_dask_arrays_stays_lazy(ureg):
    da = pytest.importorskip("dask.array")
    radius = da.from_array(np.array([4.0, 6.0, 8.0]), chunks=2) * ureg.mm
    c = hertz.contact(hertz.Body.sphere(radius, *STEEL), hertz.Body.plane(*STEEL), load=10.0)
    ref = hertz.contact(hertz.Body.sphere(np.array([4.0, 6.0, 8.0]) * 1e-3, *STEEL),
                        hertz.Body.plane(*STEEL), load=10.0)
    t = c.tangential(3.0 * ureg.N, 0.3)
    assert isinstance(t.stick_a.magnitude, da.Array) and t.stick_a.units == ureg.m
    np.testing.assert_array_equal(t.stick_a.magnitude.compute(), ref.tangential(3.0, 0.3).stick_a)
    assert t.sliding.compute().dtype == bool
    assert c.fretting(3.0, 0.3).energy.units == ureg.J
