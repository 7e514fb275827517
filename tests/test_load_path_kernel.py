"""hertz.LoadPathSpring's compiled step (hertz/_load_path_kernel.c) is the numpy code it
replaced, bit for bit (issue 26, item 5: bit-identical to the scalar law).

The reference is that numpy code, kept in tests/reference_spring_stacks.py: both are
driven along the same random paths (P rising, falling, jumping, separating to 0;
increments small, fretting, sliding the whole contact, beyond the range of the scaled
bed; contacts reset), and the forces, the sliding flags, the stick ellipses and the whole
memory (every live piece of every stack, the sizes and displacements) must be the same
bits at every step.  The reference counts the branches it took, and the paths must reach
each (pops, cuts, pushes on and off the limit, merges, whole sliding, the re-basing of a
far displacement, growth of the stacks' width).
"""

import math

import numpy as np
import pytest
import reference_spring_stacks as ref

import hertz
from hertz import _ufuncs

E1, NU1, E2, NU2 = 210e9, 0.3, 70e9, 0.22


def _same_bits(a, b):
    """Equal, and with the same sign of zero (the bits of every element)."""
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype.kind == "f":
        return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))
    return np.array_equal(a, b)


def _loads(rng, n, steps):
    """Normal forces [N]: ramps up and down, jumps, rests, separations to 0."""
    load = rng.uniform(5.0, 80.0, n)
    rate = np.ones(n)
    out = np.empty((steps, n))
    for k in range(steps):
        change = rng.random(n)
        rate = np.where(change < 0.1, rng.choice([0.9, 0.97, 1.0, 1.03, 1.1], n), rate)
        load = load * rate
        load = np.where(change > 0.97, rng.uniform(0.01, 100.0, n), load)  # a jump
        load = np.where((change > 0.5) & (change < 0.52), 0.0, load)  # separation
        load = np.where(load == 0.0, np.where(change < 0.6, 0.0, 20.0), load)  # rest, back
        load = np.minimum(load, 300.0)
        out[k] = load
    return out


def _increments(rng, n, steps, scale):
    """Increments [m]: creeping, fretting, sliding, standing, beyond the double range of the
    scaled bed (1e300 m), each for a stretch of steps."""
    out = np.empty((steps, n))
    size = np.zeros(n)
    sizes = np.array([0.0, 1e-3, 0.02, 0.3, 1.0, 3.0])
    for k in range(steps):
        size = np.where(rng.random(n) < 0.05, rng.choice(sizes, n), size)
        out[k] = scale * rng.normal(0.0, 1.0, n) * size
        if k % 9 == 0:  # fretting: the same size with the sign reversed
            out[k] = -out[k - 1] if k else out[k]
        out[k] = np.where(rng.random(n) < 0.002, 1e300 * np.sign(out[k] + 0.5), out[k])
        out[k] = np.where(rng.random(n) < 0.01, -out[k - 1] if k else 0.0, out[k])
    return out


def _check_state(spring, bed, k):
    new = spring._bed
    assert _same_bits(new.count, bed.count), k
    assert _same_bits(new.alpha, bed.alpha), k
    assert _same_bits(new.delta, bed.delta), k
    for i in np.flatnonzero(bed.count):
        live = slice(0, bed.count[i])
        piece = np.stack([bed.E[i, live], bed.D[i, live], bed.B[i, live], bed.F[i, live]], 1)
        assert _same_bits(new.live(i), piece), (k, i)


@pytest.mark.parametrize(("uniform", "block"), [(False, None), (True, 7)])
def test_kernel_is_the_numpy_step(uniform, block, monkeypatch):
    """64 contacts (radii, mu and ellipses different, or one body and mu for all: the
    kernel reads one value with stride 0), 600 steps: the same bits as the numpy step at
    every step, every branch taken (the reference also in blocks of 7 contacts)."""
    if block:
        monkeypatch.setattr(ref._SpringStacks, "BLOCK", block)
    for key in ref.HITS:
        monkeypatch.setitem(ref.HITS, key, 0)
    rng = np.random.default_rng(26 + uniform)
    n, steps = 64, 600
    plane = hertz.Body.plane(E=E2, nu=NU2)
    if uniform:
        spring = hertz.LoadPathSpring(hertz.Body(4e-3, 9e-3, E=E1, nu=NU1), plane, 0.3,
                                      size=n)
        assert all(c.size == 1 for c in spring._constants)
    else:
        body = hertz.Body(rng.uniform(2e-3, 2e-2, n), rng.uniform(2e-3, 8e-2, n), E=E1,
                          nu=NU1)
        spring = hertz.LoadPathSpring(body, plane, rng.uniform(0.1, 0.6, n),
                                      direction=math.pi / 2)
        assert all(c.size == n for c in spring._constants)
    bed = ref._SpringStacks(n)
    scale = spring._reach * 20.0 ** (2.0 / 3.0)  # 3 mu P / (2 k) at 20 N
    displacement = np.zeros(n)
    for k, (load, inc) in enumerate(zip(_loads(rng, n, steps), _increments(rng, n, steps, scale),
                                        strict=True)):
        if k % 97 == 96:
            gone = np.flatnonzero(rng.random(n) < 0.2)
            spring.reset(gone)
            bed.reset(gone)
            displacement[gone] = 0.0
        with np.errstate(over="ignore"):
            displacement = displacement + inc
        if not np.isfinite(displacement).all():  # beyond a double: refused, tested below
            displacement -= inc
            inc = np.where(np.isfinite(displacement + inc), inc, 0.0)
            displacement += inc
        force = spring.step(load, inc)
        expected = ref.step(bed, load, inc, spring._mu, spring._reach, spring._a_ref,
                            spring._b_ref)
        for name, got, want in zip(("force", "sliding", "stick_a", "stick_b"),
                                   (force, spring.sliding, spring.stick_a, spring.stick_b),
                                   expected, strict=True):
            assert _same_bits(got, want), (k, name)
        assert _same_bits(spring.normal_force, load), k
        assert _same_bits(spring.displacement, displacement), k
        _check_state(spring, bed, k)
    assert min(ref.HITS.values()) > 0, ref.HITS
    assert spring._bed.pieces.shape[1] > 4  # the stacks grew
    assert spring.sliding.any() and not spring.sliding.all()


def test_one_contact_is_the_numpy_step():
    """One contact (shape ()): a press, a push, a rise of P while creeping (a piece a
    step), a fall, a slide, a separation: the numpy step's bits."""
    ball = hertz.Body.sphere(0.01, E=E1, nu=NU1)
    plane = hertz.Body.plane(E=E2, nu=NU2)
    spring = hertz.LoadPathSpring(ball, plane, 0.3)
    bed = ref._SpringStacks(1)
    u = float(spring._reach[0]) * 50.0 ** (2.0 / 3.0)
    path = ([(50.0, 0.0), (50.0, 0.4 * u)] + [(50.0 + 3 * j, 1e-3 * u) for j in range(40)]
            + [(170.0 - 4 * j, -0.01 * u) for j in range(40)] + [(20.0, 5.0 * u), (0.0, 0.0),
                                                                  (30.0, -u)])
    for k, (p, d) in enumerate(path):
        q = spring.step(p, d)
        assert isinstance(q, float)
        expected = ref.step(bed, np.array([p]), np.array([d]), spring._mu, spring._reach,
                            spring._a_ref, spring._b_ref)
        assert _same_bits(q, expected[0][0]), k
        assert spring.sliding == expected[1][0] and _same_bits(spring.stick_a, expected[2][0])
        _check_state(spring, bed, k)
    assert spring._bed.pieces.shape[1] >= 42  # 40 pieces from the rise, and room for 2


def test_checks_leave_the_state_unchanged():
    """A bad normal force, increment or accumulated displacement anywhere in the batch: the
    error names the first bad contact, and nothing of the state has changed."""
    balls = hertz.Body.sphere(np.full((2, 3), 0.01), E=E1, nu=NU1)
    plane = hertz.Body.plane(E=E2, nu=NU2)
    spring = hertz.LoadPathSpring(balls, plane, 0.3)
    spring.step([[10.0, 20.0, 30.0], [40.0, 50.0, 60.0]], 1e-7)
    spring.step(70.0, [[1e-7, -1e-6, 0.0], [1e307, 1e-6, 0.0]])
    before = {name: getattr(spring, name) for name in ("force", "normal_force",
                                                       "displacement", "stick_a", "stick_b",
                                                       "sliding", "memory")}
    stacks = spring._bed
    names = ("count", "alpha", "delta", "top", "pieces")
    memory = [getattr(stacks, name).copy() for name in names]
    bad = [([[1.0, 2.0, 3.0], [4.0, -0.5, math.nan]], 0.0,
            r"normal_force must be a non-negative, finite force in N, got -0\.5 at index "
            r"\(1, 1\)"),
           ([[1.0, 2.0, 3.0], [4.0, math.inf, 1.0]], math.nan,
            r"normal_force .*got inf at index \(1, 1\)"),
           (1.0, [[0.0, 0.0, -math.inf], [math.nan, 0.0, 0.0]],
            r"increment must be a finite displacement in m, got -inf at index \(0, 2\)"),
           (1.0, [[0.0, 0.0, 0.0], [1.7e308, 0.0, 0.0]],
            r"increment must keep the accumulated displacement within the range of a "
            r"double .*got 1\.7e\+308 m on 1e\+307 m at index \(1, 0\)")]
    for load, inc, message in bad:
        with pytest.raises(ValueError, match=message):
            spring.step(load, inc)
        for name, value in before.items():
            assert np.array_equal(getattr(spring, name), value), name
        for name, b in zip(names, memory, strict=True):
            assert _same_bits(getattr(stacks, name), b), name


def test_binding_refuses_wrong_arrays():
    """The private binding checks what it is given: dtypes, lengths, contiguity, and room
    for a step in every stack (it never writes beyond the arrays)."""
    n = 3

    def args(**change):
        a = dict(count=np.zeros(n, dtype=np.intp), alpha=np.zeros(n), delta=np.zeros(n),
                 top=np.zeros((n, 4)), pieces=np.zeros((n, 4, 4)), alpha1=np.ones(n),
                 load=np.ones(n), increment=np.zeros(n), mu=np.full(1, 0.3),
                 reach=np.ones(n), force=np.zeros(n), normal_force=np.zeros(n),
                 displacement=np.zeros(n), sliding=np.zeros(n, dtype=bool),
                 front=np.zeros(n))
        a.update(change)
        return list(a.values())

    assert _ufuncs.load_path_step(*args()) == (0, 1)
    with pytest.raises(TypeError, match="load must be of dtype float64"):
        _ufuncs.load_path_step(*args(load=np.ones(n, dtype=np.float32)))
    with pytest.raises(TypeError, match="count must be of dtype intp"):
        _ufuncs.load_path_step(*args(count=np.zeros(n, dtype=np.int8)))
    with pytest.raises(ValueError, match="increment must be 1-d of length 3$"):
        _ufuncs.load_path_step(*args(increment=np.zeros(1)))
    with pytest.raises(ValueError, match="reach must be 1-d of length 3 or 1"):
        _ufuncs.load_path_step(*args(reach=np.ones(2)))
    with pytest.raises(ValueError, match="front must be C-contiguous and aligned and "
                                         "writeable"):
        _ufuncs.load_path_step(*args(front=np.broadcast_to(0.0, (n,))))
    with pytest.raises(ValueError, match="delta must be C-contiguous"):
        _ufuncs.load_path_step(*args(delta=np.zeros(2 * n)[::2]))
    with pytest.raises(ValueError, match=r"pieces must be .* of shape \(3, width >= 2, 4\)"):
        _ufuncs.load_path_step(*args(pieces=np.zeros((n, 4, 3))))
    with pytest.raises(ValueError, match=r"top must be a writeable.* of shape \(3, 4\)"):
        _ufuncs.load_path_step(*args(top=np.zeros((n, 4), dtype=np.float32)))
    with pytest.raises(TypeError, match="sliding must be a numpy array"):
        _ufuncs.load_path_step(*args(sliding=[False] * n))
    with pytest.raises(TypeError, match="takes 15 arguments, got 14"):
        _ufuncs.load_path_step(*args()[:-1])
    full = np.array([0, 3, 1], dtype=np.intp)  # width 4: room for 2 more, not 3
    with pytest.raises(RuntimeError, match=r"contact 1 holds a count outside \[0, width - 2"):
        _ufuncs.load_path_step(*args(count=full))
    assert full[1] == 3  # left as it was (the others made their step)


@pytest.mark.parametrize("i", range(9))
def test_every_bad_value_is_found(i):
    """A bad value at any of 9 contacts (the check runs 4 contacts at a time, then the
    rest): a negative (the smallest subnormal), infinite or NaN normal force, an increment
    not finite, a displacement beyond a double; -0.0 N is a force of 0."""
    ball = hertz.Body.sphere(np.full(9, 0.01), E=E1, nu=NU1)
    spring = hertz.LoadPathSpring(ball, hertz.Body.plane(E=E2, nu=NU2), 0.3)
    spring.step(np.full(9, -0.0), 0.0)
    spring.step(10.0, 1e300)

    def at(value, fill):
        out = np.full(9, fill)
        out[i] = value
        return out

    for value in (-5e-324, -1.0, math.inf, -math.inf, math.nan):
        with pytest.raises(ValueError, match=rf"normal_force must .* at index {i}$"):
            spring.step(at(value, 1.0), 0.0)
    for value in (math.inf, -math.inf, math.nan):
        with pytest.raises(ValueError, match=rf"increment must be a finite .* at index {i}$"):
            spring.step(1.0, at(value, 0.0))
    with pytest.raises(ValueError, match=rf"accumulated displacement .* at index {i}$"):
        spring.step(1.0, at(1.7976931348623157e308, 0.0))
    assert spring.displacement.tolist() == [1e300] * 9
