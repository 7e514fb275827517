"""What a newcomer meets first (issue 22, items 12 and 13): negative numbers on the hertz
command line as written; a warning, from the command and from the API, where a contact is
too large for Hertz's theory (a > A_OVER_R_LIMIT R), which also catches Young's moduli in
GPa; --json keys that cannot be confused with the scene's E; a public name for every type
the API returns; constructors that show no private fields."""

import inspect
import json
import math
import re
import warnings

import numpy as np
import pytest

import hertz
from hertz.cli import DEFAULT_SCENE, _parser, main

STEEL = dict(E=210e9, nu=0.3)
E_STAR_STEEL = 210e9 / (2 * (1 - 0.3**2))


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


def sphere_on_plane_a(radius, load, e_star=E_STAR_STEEL):
    """Hertz's closed form for a sphere on a plane: a = (3 P R / (4 E*))^(1/3)."""
    return (3 * load * radius / (4 * e_star)) ** (1 / 3)


def load_for_a(a, radius, e_star=E_STAR_STEEL):
    return 4 * e_star * a**3 / (3 * radius)


# --- negative numbers as written, for every numeric option ------------------------------

#: a negative value for each numeric option, and the options it needs beside it
NEGATIVE = {
    "--r1x": ("-6.6e-3", ["--r2x", "6e-3", "--r2y", "6e-3"]),  # body 1 the groove
    "--r1y": ("-6.6e-3", ["--r2x", "6e-3", "--r2y", "6e-3"]),
    "--r2x": ("-6.6e-3", []),
    "--r2y": ("-4E-2", []),
    "--e1": ("-2.1e11", []),
    "--e2": ("-2.1e+11", []),
    "--nu1": ("-2e-1", []),
    "--nu2": ("-.25", []),
    "--load": ("-1.5e3", []),
    "--approach": ("-1e-6", []),
    "--angle-deg": ("-3e1", []),
    "--tangential": ("-1e2", ["--mu", "0.3"]),
    "--mu": ("-3e-1", ["--tangential", "100"]),
    "--direction": ("-4.5e1", ["--tangential", "100", "--mu", "0.3"]),
    "--yield-strength": ("-1.5e9", []),
}


def test_every_numeric_option_is_covered():
    numeric = {a.option_strings[0] for a in _parser()._actions
               if a.type is not None and a.type.__name__ == "_number"}
    assert numeric == set(NEGATIVE)


@pytest.mark.parametrize("option", sorted(NEGATIVE))
def test_a_negative_number_is_read_as_written(capsys, option):
    """``--r2x -6.6e-3`` is ``--r2x=-6.6e-3`` (argparse alone: "expected one argument")."""
    value, extra = NEGATIVE[option]
    spaced = run(capsys, "--json", option, value, *extra)
    joined = run(capsys, "--json", f"{option}={value}", *extra)
    assert spaced == joined
    status, out, err = spaced
    assert "expected one argument" not in err
    if status == 2:  # the option's own check judged the value: one line naming it
        assert out == "" and err.count("\n") == 1 and err.startswith("hertz: error: ")
        assert repr(float(value)) in err
    else:
        assert status == 0 and err == "" and json.loads(out)


def test_a_concave_radius_as_written_gives_hertz_contact(capsys):
    status, out, err = run(capsys, "--json", "--r2x", "-6.6e-3")
    race = hertz.Body(-6.6e-3, DEFAULT_SCENE["body2"]["Ry"], **STEEL)
    c = hertz.contact(hertz.Body.sphere(6e-3, **STEEL), race, load=DEFAULT_SCENE["load"])
    assert status == 0 and err == ""
    assert json.loads(out)["a"] == c.a


@pytest.mark.parametrize("argv, message", [
    (["--r2x", "-inf"], None),  # -inf is a flat surface, as inf
    (["--load", "-inf"], "load must be a finite value >= 0 in N, got -inf"),
    (["--e1", "-inf"], "body1: E must be a positive Young's modulus in Pa (inf for a rigid "
                       "body), got -inf"),
    (["--angle-deg", "-inf"], "--angle-deg (scene key angle_deg) must be a finite angle in "
                              "degrees, got -inf"),
    (["--load", "-5e"], "argument --load: not a number: '-5e'"),
    (["--mu", "-Infinity", "--tangential", "1"],
     "mu must be a positive, finite coefficient of friction, got -inf"),
])
def test_minus_inf_reaches_the_options_own_check(capsys, argv, message):
    status, out, err = run(capsys, *argv)
    if message is None:
        flat = run(capsys, argv[0], "inf")
        assert (status, err) == (0, "") and out == flat[1]
    else:
        assert status == 2 and out == "" and err == f"hertz: error: {message}\n"


# --- a contact too large for Hertz: the command's warning line ----------------------------

def test_the_default_scene_is_within_the_limit_and_silent(capsys):
    ball = hertz.Body.sphere(6e-3, **STEEL)
    race = hertz.Body(-6.2e-3, 40e-3, **STEEL)
    with warnings.catch_warnings():
        warnings.simplefilter("error", hertz.HertzValidityWarning)
        c = hertz.contact(ball, race, load=1500.0)
    assert c.a / 6e-3 < hertz.A_OVER_R_LIMIT
    status, out, err = run(capsys, "--json")
    assert status == 0 and err == "" and json.loads(out)["warnings"] == []


def test_young_s_modulus_in_gpa_warns_and_exits_0(capsys):
    """``hertz --e1 210 --e2 210``: a is 1000 times the default's (a ~ E*^(-1/3)), about
    1.84 m for a 6 mm ball; the command prints it, warns in one line, exits 0."""
    default = run(capsys, "--json")
    status, out, err = run(capsys, "--json", "--e1", "210", "--e2", "210")
    assert status == 0
    a = json.loads(out)["a"]
    assert a == pytest.approx(1000 * json.loads(default[1])["a"], rel=1e-12)
    assert err.count("\n") == 1 and err.startswith("hertz: warning: ")
    assert "E1 = 210 Pa and E2 = 210 Pa look like values in GPa or MPa" in err
    ratio = float(re.search(r"is ([\d.e+]+) times", err)[1])
    assert ratio == pytest.approx(a / 6e-3, rel=1e-3)
    assert json.loads(out)["warnings"] == [err[len("hertz: warning: "):-1]]
    status, table, err_table = run(capsys, "--e1", "210", "--e2", "210")
    assert status == 0 and "semi-major axis a" in table and err_table == err


def test_a_scene_in_mm_and_gpa_warns(capsys, tmp_path):
    scene = tmp_path / "mm.toml"
    scene.write_text("[body1]\nRx = 6\nRy = 6\nE = 210\n[body2]\nRx = -6.2\nRy = 40\nE = 210\n")
    status, out, err = run(capsys, "--scene", str(scene))
    assert status == 0 and out
    assert err.startswith("hertz: warning: ") and err.count("\n") == 1
    assert "look like values in GPa or MPa" in err


def test_an_error_after_a_warning_is_still_one_line(capsys):
    status, out, err = run(capsys, "--e1", "210", "--e2", "210", "--tangential", "1e9",
                           "--mu", "0.3")
    assert status == 2 and out == "" and err.count("\n") == 1
    assert err.startswith("hertz: error: tangential = ")


# --- the API's HertzValidityWarning -------------------------------------------------------

def test_the_warning_class_is_public():
    assert issubclass(hertz.HertzValidityWarning, UserWarning)
    assert "HertzValidityWarning" in hertz.__all__ and "A_OVER_R_LIMIT" in hertz.__all__
    # the FEM of real bodies: 1.1% at a/R = 0.2, growing as (a/R)^2; the limit is above
    assert 0.2 <= hertz.A_OVER_R_LIMIT < 0.5


def test_one_warning_per_call_with_the_count_and_the_largest_ratio():
    """A sphere on a plane at a/R = 0.1, 0.3, 0.45 and 2 (closed form): two beyond 1/3,
    one warning for the call, which names them and the largest a/R."""
    radius = 0.01
    ratios = np.array([0.1, 0.3, 0.45, 2.0])
    loads = load_for_a(ratios * radius, radius)
    ball, plane = hertz.Body.sphere(radius, **STEEL), hertz.Body.plane(**STEEL)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        c = hertz.contact(ball, plane, load=loads)
    assert c.a / radius == pytest.approx(ratios, rel=1e-12)
    assert [w.category for w in caught] == [hertz.HertzValidityWarning]
    message = str(caught[0].message)
    assert message.startswith("2 of 4 contacts have a semi-major axis a above 0.333")
    assert "the largest, a/R = 2 at index 3 " in message
    assert caught[0].filename == __file__  # it names the caller's line, not hertz's


def test_scalar_and_array_calls_agree_on_which_contacts_warn():
    radius = 0.01
    ball, plane = hertz.Body.sphere(radius, **STEEL), hertz.Body.plane(**STEEL)
    for ratio, expected in ((0.3, 0), (0.36, 1)):
        load = load_for_a(ratio * radius, radius)
        for value in (load, np.array([load]), np.float64(load)):
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                hertz.contact(ball, plane, load=value)
            assert len(caught) == expected, (ratio, type(value))


def test_the_radius_is_the_smallest_of_both_bodies_planes_and_larger_grooves_excluded():
    """A 6 mm ball in a 6.2 mm groove (race 40 mm) at a/R_ball = 0.31: silent, though a
    is 0.3 of the groove and a plane is in no contact's list; at 2000 N (a/R_ball 0.337)
    it warns with R = 6 mm."""
    ball, race = hertz.Body.sphere(6e-3, **STEEL), hertz.Body(-6.2e-3, 40e-3, **STEEL)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        quiet = hertz.contact(ball, race, load=1500.0)
        loud = hertz.contact(ball, race, load=2000.0)
    assert quiet.a / 6e-3 < 1 / 3 < loud.a / 6e-3
    assert len(caught) == 1 and "|R| = 0.006 m" in str(caught[0].message)
    a = sphere_on_plane_a(5e-3, 1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        hertz.contact(hertz.Body.sphere(5e-3, **STEEL), hertz.Body.plane(**STEEL), load=1.0)
        hertz.contact(ball, race, load=0.0)  # no contact patch: nothing to warn about
    assert a < 5e-3 / 3


def test_line_contact_warns_on_its_half_width():
    roller = hertz.Body.cylinder(1e-3, E=210, nu=0.3)  # E in GPa: b = 74 mm for R = 1 mm
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        lc = hertz.line_contact(roller, hertz.Body.plane(**STEEL), 1e3)
    assert lc.half_width > 1e-3
    assert [w.category for w in caught] == [hertz.HertzValidityWarning]
    assert "half-width b" in str(caught[0].message) and "E1 = 210 Pa" in str(caught[0].message)


# --- --json: ellipk, ellipe; K and E deprecated --------------------------------------------

def test_json_elliptic_integrals_cannot_be_read_as_young_s_modulus(capsys):
    special = pytest.importorskip("scipy.special")
    status, out, _ = run(capsys, "--json")
    data = json.loads(out)
    assert status == 0
    assert data["ellipk"] == pytest.approx(special.ellipk(data["m"]), rel=1e-13)
    assert data["ellipe"] == pytest.approx(special.ellipe(data["m"]), rel=1e-13)
    assert data["deprecated_keys"] == {"K": "ellipk", "E": "ellipe"}
    for old, new in data["deprecated_keys"].items():
        assert data[old] == data[new]


# --- public names for the API's types; no private fields in signatures --------------------

def test_every_type_the_api_returns_is_public():
    ball, plane = hertz.Body.sphere(0.01, **STEEL), hertz.Body.plane(**STEEL)
    c = hertz.contact(ball, plane, load=100.0)
    lc = hertz.line_contact(hertz.Body.cylinder(5e-3, **STEEL), plane, 1e5)
    t = c.tangential(10.0, 0.3)
    results = [c, lc, c.subsurface(), lc.subsurface(), t, t.maxima(), c.fretting(10.0, 0.3),
               hertz.load_path(ball, plane, [10.0, 10.0], [0.0, 1.0], 0.3),
               hertz.TangentialSpring(c, 0.3), hertz.LoadPathSpring(ball, plane, 0.3)]
    for result in results:
        name = type(result).__name__
        assert name in hertz.__all__ and getattr(hertz, name) is type(result), name
    assert hertz.__all__ == sorted(hertz.__all__)


def test_public_signatures_show_no_private_fields():
    for name in hertz.__all__:
        obj = getattr(hertz, name)
        if inspect.isclass(obj) and not issubclass(obj, Warning):
            params = inspect.signature(obj).parameters
            assert not [p for p in params if p.startswith("_")], name
    assert list(inspect.signature(hertz.Contact).parameters) == ["a", "b", "load", "p0",
                                                                 "delta", "stiffness"]


def test_contacts_made_internally_still_carry_their_private_fields():
    ball = hertz.Body.sphere(0.01, **STEEL)
    c = hertz.contact(ball, hertz.Body.plane(**STEEL), load=[50.0, 100.0])
    assert c.E[1] == pytest.approx(math.pi / 2) and c.subsurface(2).tau_max.shape == (2,)


def test_the_limit_is_the_same_test_on_every_path_to_the_last_bit():
    """Scalars compare a / A_OVER_R_LIMIT with each |R|; a batch on one geometry compares a
    with a precomputed cut-off, a batch of geometries a / A_OVER_R_LIMIT with its smallest
    |R|: the same
    contacts warn, within three ulps either side of the limit."""
    from hertz._contact import _check_size

    def flagged(a, body1, body2):
        """How many contacts the warning counts (0: none)."""
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            _check_size(a, body1, body2)
        if not caught:
            return 0
        count = re.match(r"(\d+) of", str(caught[0].message))
        return int(count[1]) if count else 1

    rng = np.random.default_rng(22)
    for radius in 10.0 ** rng.uniform(-200, 200, 200):
        values = [radius * hertz.A_OVER_R_LIMIT]
        for _ in range(3):
            values = [math.nextafter(values[0], 0.0), *values,
                      math.nextafter(values[-1], math.inf)]
        ball, plane = hertz.Body.sphere(radius, **STEEL), hertz.Body.plane(**STEEL)
        balls = hertz.Body.sphere(np.full(len(values), radius), **STEEL)
        one_by_one = [flagged(a, ball, plane) for a in values]
        assert one_by_one == [int(a * (1 / hertz.A_OVER_R_LIMIT) > radius) for a in values]
        assert 0 < sum(one_by_one) < len(values)  # the limit lies among them
        assert flagged(np.array(values), ball, plane) == sum(one_by_one)
        assert flagged(np.array(values), balls, plane) == sum(one_by_one)
