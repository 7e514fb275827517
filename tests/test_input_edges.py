"""Inputs at the edges of what numpy hands over: long doubles beyond the double range,
fractions, huge coordinates in the pressure, control characters in a scene name (found by
an audit after issue 18's fixes)."""

import os
import subprocess
import sys
import warnings
from fractions import Fraction

import numpy as np
import pytest

import hertz

BALL = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
PLANE = hertz.Body.plane(E=210e9, nu=0.3)


def test_fraction_is_a_real_number():
    # a Fraction is converted exactly as float() converts it
    assert hertz.contact(BALL, PLANE, load=Fraction(1, 3)).a == \
        hertz.contact(BALL, PLANE, load=float(Fraction(1, 3))).a
    assert hertz.Body(Fraction(1, 100), 0.01, 210e9, 0.3).Rx == 0.01


@pytest.mark.parametrize("value", [Fraction(10**400), [Fraction(1, 2), 10**400]])
def test_fraction_beyond_the_double_range_is_named(value):
    with pytest.raises(ValueError, match="load must be within the range of a double"):
        hertz.contact(BALL, PLANE, load=value)


@pytest.mark.skipif(np.finfo(np.longdouble).maxexp <= 1024, reason="long double is a double here")
@pytest.mark.parametrize(("text", "index"), [("1e400", ""), ("1e-400", ""), ("-1e4000", "")])
def test_long_double_beyond_the_double_range_is_named(text, index):
    value = np.longdouble(text)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ValueError, match=r"load must be within the range of a double.*"
                                             + text.replace("-", r"\-").replace("e", "e\\+?")):
            hertz.contact(BALL, PLANE, load=value)
        arr = np.array([1.0, 2.0, value], dtype=np.longdouble)
        with pytest.raises(ValueError, match="Rx must be within.* at index 2"):
            hertz.Body(arr, 0.01, 210e9, 0.3)


def test_long_double_within_range_is_the_double():
    x = np.longdouble(100) / 3
    assert hertz.contact(BALL, PLANE, load=x).a == hertz.contact(BALL, PLANE, load=float(x)).a


def test_pressure_far_away_is_zero_without_warnings():
    c = hertz.contact(BALL, PLANE, load=100.0)
    lc = hertz.line_contact(hertz.Body.cylinder(0.01, 210e9, 0.3), PLANE, 1e4)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert c.pressure(1e200, 0.0) == 0.0
        assert c.pressure(0.0, -1.7e308) == 0.0
        assert lc.pressure(1e308) == 0.0


def test_scene_name_control_characters_are_escaped(tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text('name = "a\\nb\\u001b[31mRED\\u0000z \\u00e9"\n', encoding="utf-8")
    out = subprocess.run([sys.executable, "-m", "hertz.cli", "--scene", str(scene)],
                         capture_output=True, check=True,
                         env={**os.environ, "PYTHONIOENCODING": "utf-8"})
    first = out.stdout.decode("utf-8").splitlines()[0]
    assert first == "Hertz point contact: a\\nb\\x1b[31mRED\\x00z \u00e9"
