"""Hertz's validity check (a > A_OVER_R_LIMIT |R|) made inside the compiled kernel: the
batch loops count the contacts beyond it per thread, the scalar path tests it in C.  The
count must equal numpy's elementwise test of the same operations, element for element,
whatever the path (plain, AVX2, AVX-512) and whatever thread calls."""

import threading
import warnings

import numpy as np
import pytest

import hertz
from hertz import _contact, _ufuncs

STEEL = {"E": 210e9, "nu": 0.3}


def numpy_beyond(a, radii):
    t = a * _contact._INVERSE_LIMIT
    return sum_any(np.abs(r) < t for r in radii)


def sum_any(tests):
    out = None
    for t in tests:
        out = t if out is None else out | t
    return int(np.count_nonzero(out))


def random_batch(n, seed):
    rng = np.random.default_rng(seed)
    radii = np.exp(rng.uniform(np.log(1e-3), np.log(1e-1), (4, n)))
    radii[2] *= rng.choice([-1.0, 1.0], n) * 3  # some concave, none over-conforming
    args = [radii[0], radii[1], np.abs(radii[2]), radii[3], rng.uniform(-3, 3, n),
            210e9, 0.3, 70e9, 0.33, rng.uniform(1.0, 3000.0, n)]
    return args


@pytest.mark.parametrize("path", ["plain", "avx2", "avx512"])
def test_the_kernel_count_is_numpy_s_test_on_every_path(path):
    if path not in _ufuncs.build_info()["paths"]:
        pytest.skip(f"no {path} path in this build")
    before = _ufuncs.path()
    try:
        _ufuncs.path(path)
        args = random_batch(50_001, 1)
        _ufuncs.beyond()
        out = _ufuncs.contact_load(*args)
        count = _ufuncs.beyond()[0]
    finally:
        _ufuncs.path(before)
    expected = numpy_beyond(out[0], args[:4])
    assert 0 < expected < 50_001  # the batch straddles the limit
    assert count == expected
    assert _ufuncs.beyond() == (0, 0.0, 0.0, 0)  # read and reset


def test_the_count_is_exact_one_ulp_either_side_of_the_limit():
    """A ball on a plane whose a sits at the limit: R moved one ulp either way switches
    the count, as numpy's test does."""
    ball_a = hertz.contact(hertz.Body.sphere(0.01, **STEEL), hertz.Body.plane(**STEEL),
                           load=1e5).a
    edge = ball_a * _contact._INVERSE_LIMIT
    radii = np.array([np.nextafter(edge, 0), edge, np.nextafter(edge, np.inf)])
    inf = np.full(3, np.inf)
    a = np.full(3, ball_a)
    # the kernel's own a for these radii differs; count with a fixed a through the test
    # the kernel applies: drive it with the radii and the a it computes
    args = [radii, radii, inf, inf, 0.0, 210e9, 0.3, 210e9, 0.3, np.full(3, 1e5)]
    _ufuncs.beyond()
    out = _ufuncs.contact_load(*args)
    assert _ufuncs.beyond()[0] == numpy_beyond(out[0], args[:4])
    assert numpy_beyond(a, (radii,)) == 1  # only the radius one ulp below a * 3 is beyond


def test_each_thread_reads_its_own_count():
    args = random_batch(20_000, 2)
    expected = numpy_beyond(_ufuncs.contact_load(*args)[0], args[:4])
    quiet = [a * 1e-6 if i == 9 else a for i, a in enumerate(args)]
    counts = {}
    barrier = threading.Barrier(2)

    def work(name, batch):
        barrier.wait()
        total = 0
        for _ in range(20):
            _ufuncs.beyond()
            _ufuncs.contact_load(*batch)
            total += _ufuncs.beyond()[0]
        counts[name] = total

    threads = [threading.Thread(target=work, args=("loud", args)),
               threading.Thread(target=work, args=("quiet", quiet))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert counts == {"loud": 20 * expected, "quiet": 0}


def test_scalar_fast_path_warns_and_raises_under_error_filters():
    ball, plane = hertz.Body.sphere(1e-3, **STEEL), hertz.Body.plane(**STEEL)
    with warnings.catch_warnings():
        warnings.simplefilter("error", hertz.HertzValidityWarning)
        hertz.contact(ball, plane, 1.0)  # a/R = 0.05: silent
        with pytest.raises(hertz.HertzValidityWarning, match="times the smallest radius"):
            hertz.contact(ball, plane, 1e5)


def test_scalar_fast_path_gives_the_general_path_s_bits():
    ball, race = hertz.Body(6e-3, 6e-3, **STEEL), hertz.Body(-6.2e-3, 40e-3, **STEEL)
    fast = hertz.contact(ball, race, 1500.0, 0.3)
    general = hertz.contact(ball, race, np.array([1500.0]), np.array([0.3]))
    for name in ("a", "b", "load", "p0", "delta", "stiffness", "ellipticity", "e_star"):
        assert getattr(fast, name) == getattr(general, name)[0], name


def test_scalar_fast_path_declines_what_it_does_not_take():
    ball = hertz.Body(6e-3, 6e-3, **STEEL)
    assert _ufuncs.contact_bodies(0, ball, ball, 0.0, 1) is NotImplemented  # an int load
    assert _ufuncs.contact_bodies(0, ball, "x", 0.0, 1.0) is NotImplemented
    assert hertz.contact(ball, ball, 1).load == 1.0
    with pytest.raises(TypeError, match="body2 must be a hertz.Body"):
        hertz.contact(ball, "x", 1.0)


def test_the_warning_names_the_largest_ratio_as_numpy_finds_it():
    """The kernel reports the count and the a and |R| of the largest a/R; the message names
    the same element, count and ratio as the elementwise numpy check."""
    args = random_batch(30_000, 3)
    rng = np.random.default_rng(4)
    body1 = hertz.Body(args[0], args[1], 210e9, 0.3)
    body2 = hertz.Body(args[2], args[3], 70e9, 0.33)
    load = rng.uniform(1.0, 3000.0, 30_000)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        c = hertz.contact(body1, body2, load=load, angle=args[4])
    t = c.a * _contact._INVERSE_LIMIT
    radii = np.abs(np.array(args[:4]))
    beyond = (radii < t).any(axis=0)
    ratio = np.where(beyond, c.a / radii.min(axis=0), -np.inf)
    i = int(np.argmax(ratio))
    assert len(caught) == 1
    message = str(caught[0].message)
    assert message.startswith(f"{int(beyond.sum())} of 30000 contacts have a semi-major axis")
    assert f"a/R = {ratio[i]:.4g} at index {i} " in message


@pytest.mark.parametrize("layout", ["C", "F"])
@pytest.mark.parametrize("address", ["reported", "dropped"])
def test_the_warning_names_the_same_element_for_any_layout(layout, address, monkeypatch):
    """The kernel also reports where the a it names lies, which spares hertz.contact a
    search over the batch; without it (a loop that wrote a buffer) the search finds the
    same element: the one numpy finds, in C and in Fortran order."""
    from hertz._validate import index_text

    if address == "dropped":
        beyond = _ufuncs.beyond
        monkeypatch.setattr(_ufuncs, "beyond", lambda: (*beyond()[:3], 0))
    args = random_batch(20_000, 5)
    radii = [np.asarray(r).reshape(100, 200) for r in args[:4]]
    if layout == "F":
        radii = [np.asfortranarray(r) for r in radii]
    load = np.random.default_rng(6).uniform(1.0, 3000.0, (100, 200))
    body1 = hertz.Body(radii[0], radii[1], 210e9, 0.3)
    body2 = hertz.Body(radii[2], radii[3], 70e9, 0.33)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        c = hertz.contact(body1, body2, load=load)
    r = np.abs(np.array(radii)).min(axis=0)
    beyond_limit = r < c.a * _contact._INVERSE_LIMIT
    ratio = np.where(beyond_limit, c.a / r, -np.inf)
    i = int(np.argmax(ratio))  # the first of the largest, in C order
    assert len(caught) == 1
    message = str(caught[0].message)
    assert f"a/R = {ratio.flat[i]:.4g}{index_text((100, 200), i)} " in message


def test_a_wrong_address_is_not_believed():
    """An address outside the batch, or at an element that is not the one reported, falls
    back to the search."""
    a = np.array([1.0, 5.0, 3.0])
    body = hertz.Body(np.array([1.0, 1.0, 1.0]), 1.0, 210e9, 0.3)
    plane = hertz.Body.plane(210e9, 0.3)
    for address in (a.ctypes.data + 8 * 7, a.ctypes.data, a.ctypes.data + 3):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            _contact._warn_counted(a, body, plane, 1, 5.0, 1.0, address)
        assert " at index 1 " in str(caught[0].message)


def test_a_batch_written_in_place_is_not_searched(monkeypatch):
    """Where the loops wrote the output array itself, the warning's element is taken at the
    address the kernel reported: no pass over the batch (numpy's search is not called)."""
    args = random_batch(5_000, 7)
    body1 = hertz.Body(args[0], args[1], 210e9, 0.3)
    body2 = hertz.Body(args[2], args[3], 70e9, 0.33)

    def no_search(*_):
        raise AssertionError("searched the batch")

    monkeypatch.setattr(_contact.np, "flatnonzero", no_search)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        hertz.contact(body1, body2, load=args[9], angle=args[4])
    assert len(caught) == 1
