"""The tangential API around the partial-slip state: Tangential.maxima of arrays of
contacts (each element bit for bit the scalar search), the repr of the results, and
FrettingLoop.loop of pandas and xarray results."""

import dataclasses

import numpy as np
import pytest

import hertz
from hertz._friction import SlidingMaxima, sliding_maxima

BALL = hertz.Body(0.01, 0.03, E=210e9, nu=0.3)
BLOCK = hertz.Body.plane(E=70e9, nu=0.22)
MU = 0.4
MAXIMA_FIELDS = [f.name for f in dataclasses.fields(SlidingMaxima)]


# ------------------------------------------------------------------ maxima of arrays
@pytest.fixture(scope="module")
def array_state():
    """Two loads (axis 0) by two forces along the major axis (axis 1): two contact
    ellipses, partial slip and sliding (the limit mu P), dissimilar bodies."""
    loads = np.array([[60.0], [100.0]])
    c = hertz.contact(BALL, BLOCK, load=loads)
    force = np.array([0.5, 1.0]) * MU * loads  # Q/(mu P) = 1/2 and 1
    return loads, c, c.tangential(force, MU)


@pytest.mark.parametrize("body", [1, 2])
def test_maxima_of_an_array_is_the_scalar_search_bit_for_bit(array_state, body):
    loads, c, t = array_state
    m = t.maxima(body=body)
    assert type(m) is SlidingMaxima
    for name in MAXIMA_FIELDS:
        value = getattr(m, name)
        assert isinstance(value, np.ndarray) and value.shape == (2, 2), name
    for i, j in np.ndindex(2, 2):
        # the same contact and force given alone, as scalars
        one = hertz.contact(BALL, BLOCK, load=float(loads[i, 0]))
        alone = one.tangential(float(t.force[i, j]), MU).maxima(body=body)
        for name in MAXIMA_FIELDS:
            assert getattr(m, name)[i, j] == getattr(alone, name), (name, i, j)
    # sliding (j = 1) is the sliding field; partial slip (j = 0) is below it: the stick
    # zone carries less traction than mu p
    assert np.all(t.sliding[:, 1]) and not np.any(t.sliding[:, 0])
    assert np.all(m.von_mises[:, 0] < m.von_mises[:, 1])
    assert np.all(m.tensile[:, 0] < m.tensile[:, 1])


def test_maxima_of_an_array_broadcasts_a_scalar_field():
    # a (1, 2) contact, a scalar force: the maxima have the contact's shape, each that of
    # the contact alone (by sliding_maxima directly: an independent path through the
    # arguments)
    c = hertz.contact(BALL, BLOCK, load=np.array([[80.0, 120.0]]))
    t = c.tangential(20.0, MU)
    m = t.maxima(body=2)
    assert m.tau_max.shape == (1, 2)
    for j in range(2):
        ref = sliding_maxima(c.a[0, j], c.b[0, j], c.p0[0, j], MU, 0.22, 0.0,
                             float(t.stick_a[0, j] / c.a[0, j]))
        for name in MAXIMA_FIELDS:
            assert getattr(m, name)[0, j] == getattr(ref, name), name


def test_maxima_of_an_array_names_the_bad_element_before_searching():
    t = hertz.contact(BALL, BLOCK, load=np.array([[60.0, 80.0], [90.0, 100.0]])).tangential(
        10.0, MU)
    bad = dataclasses.replace(t, _p0=np.array([[1e9, 1e9], [1e9, np.nan]]))
    with pytest.raises(ValueError, match=r"^p0 must be a finite pressure >= 0 in Pa, got nan "
                                         r"at index \(1, 1\)$"):
        bad.maxima()
    bad = dataclasses.replace(t, stick_a=np.array([[1e-4, 1e-4], [np.nan, 1e-4]]))
    with pytest.raises(ValueError, match=r"^stick_ratio must be c/a in \[0, 1\], got nan "
                                         r"at index \(1, 0\)$"):
        bad.maxima(body=1)
    with pytest.raises(ValueError, match="body must be 1 or 2"):
        t.maxima(body=3)
