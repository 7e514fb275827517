"""The DEM tangential laws advanced for N contacts at once (issue 26, item 5).

* A batch is N independent contacts: hertz.TangentialSpring and hertz.LoadPathSpring over
  N contacts give, bit for bit, the forces, sliding flags, displacements and memory of N
  springs of one contact each, on random paths with reversals, sliding, P varying and
  contacts leaving (reset, or P = 0) and entering.
* TangentialSpring is the law it was before it was vectorised: a reference step built on
  hertz._tangential._Masing (the Masing engine of tangential_history) gives the same bits.
* Closed forms (mpmath at 50 digits, from E, nu, R and P alone): Mindlin's virgin curve
  Q = mu P [1 - (1 - delta/delta_s)^(3/2)], delta_s = 3 mu P / (2 k), k = 8 a /
  sum((2 - nu)/G); Masing's branch after sliding; Mindlin and Deresiewicz's P raised at a
  fixed displacement (nothing changes) and proportional loading (Q = r P while
  delta = 3 r P / (2 k(P))).
* hertz.load_path (the force-driven spring bed, a separate implementation) gives back its
  forces when the batch is driven by its displacements.
"""

import math

import mpmath as mp
import numpy as np
import pytest

import hertz
from hertz import _tangential

mp.mp.dps = 50
E1, NU1, E2, NU2 = 210e9, 0.3, 70e9, 0.22
R = 0.01

# Observed, relative to mu P, worst over the contacts below (x86-64, numpy 2.4): the
# virgin curve 1.3e-16 (TangentialSpring) and 2.1e-16 (LoadPathSpring), the Masing branch
# 1.7e-16 and 2.8e-16; P raised at a fixed displacement 1.1e-16; proportional loading
# 6.3e-16; load_path's forces given back 2.3e-16 of mu P_max.  Tolerances 1.5x above.
TOL_CURVE = 4.5e-16
TOL_RAISED = 1.7e-16
TOL_PROPORTIONAL = 9.5e-16
TOL_LOAD_PATH = 3.5e-16


def _bodies(radius=R):
    return (hertz.Body.sphere(radius, E=E1, nu=NU1), hertz.Body.plane(E=E2, nu=NU2))


def _reach_mp(load, mu, radius=R):
    """delta_s = 3 mu P / (2 k) [m] of a sphere on a plane, from Hertz and Mindlin."""
    load, mu, radius = mp.mpf(load), mp.mpf(mu), mp.mpf(radius)
    e_star = 1 / ((1 - mp.mpf(NU1) ** 2) / E1 + (1 - mp.mpf(NU2) ** 2) / E2)
    a = mp.cbrt(3 * load * radius / (4 * e_star))
    g1, g2 = E1 / (2 * (1 + mp.mpf(NU1))), E2 / (2 * (1 + mp.mpf(NU2)))
    k = 8 * a / ((2 - mp.mpf(NU1)) / g1 + (2 - mp.mpf(NU2)) / g2)
    return 3 * mu * load / (2 * k)


def _virgin_mp(t):
    """Q / (mu P) at delta = t delta_s on the virgin curve (0 <= t <= 1)."""
    return 1 - (1 - mp.mpf(t)) ** mp.mpf(1.5)


def _path(rng, n, steps, scale):
    """Increments of random size and sign: small walks, fretting, long slides, rests."""
    out = np.empty((steps, n))
    for k in range(steps):
        kind = k % 5
        size = [0.05, 0.3, 1.0, 3.0, 0.0][kind]
        out[k] = scale * rng.normal(0.0, size, n) * (rng.random(n) < 0.85)
    return out


# ----------------------------------------------------------------------- TangentialSpring
@pytest.mark.parametrize("block", [None, 7])
def test_tangential_batch_is_n_scalar_springs(block, monkeypatch):
    """One batch of 24 contacts (different loads, mu, directions, ellipses) against 24
    springs of one contact: the same bits at every step, through reversals, sliding and
    contacts reset (leaving, their slot taken by a new contact); also in blocks of 7
    contacts (the batch is advanced in blocks)."""
    if block:
        monkeypatch.setattr(_tangential._MasingSpring, "BLOCK", block)
    rng = np.random.default_rng(7)
    n = 24
    ratio = 10.0 ** rng.uniform(0, 2, n)
    load = rng.uniform(1.0, 100.0, n)
    mu = rng.uniform(0.1, 0.6, n)
    direction = rng.uniform(0, np.pi, n)
    body1 = hertz.Body(5e-3, 5e-3 * ratio, E=E1, nu=NU1)
    body2 = hertz.Body.plane(E=E2, nu=NU2)
    batch = hertz.TangentialSpring(hertz.contact(body1, body2, load=load), mu, direction)
    singles = [hertz.TangentialSpring(
        hertz.contact(hertz.Body(5e-3, 5e-3 * ratio[i], E=E1, nu=NU1), body2, load=load[i]),
        mu[i], direction[i]) for i in range(n)]
    scale = batch._reach
    deepest = 0
    for k, inc in enumerate(_path(rng, n, 300, scale)):
        if k % 37 == 36:  # some contacts leave; their slots start again empty
            gone = rng.random(n) < 0.3
            batch.reset(gone)
            for i in np.flatnonzero(gone):
                singles[i].reset()
        force = batch.step(inc)
        assert np.array_equal(force, [s.step(inc[i]) for i, s in enumerate(singles)]), k
        assert np.array_equal(batch.sliding, [s.sliding for s in singles]), k
        assert np.array_equal(batch.displacement, [s.displacement for s in singles]), k
        assert np.array_equal(batch.memory, [s.memory for s in singles]), k
        deepest = max(deepest, batch.memory.max())
    assert deepest >= 3  # nested loops were remembered


def _reference_spring(contact, mu, increments):
    """TangentialSpring's step as it was before it was vectorised (hertz 0.1.0): the
    _Masing engine of tangential_history, then the sliding rules."""
    limit = np.asarray(mu * contact.load, dtype=float).reshape(-1)
    along = 1.0 / np.asarray(contact.tangential_stiffness(), dtype=float).reshape(-1)
    reach = 1.5 * limit * along
    engine = _tangential._Masing(limit.size,
                                 lambda x: limit * _tangential._virgin_inverse(x / reach))
    out = []
    for inc in increments:
        x = engine.x + inc
        force = engine.step(x)
        slid = ~engine.virgin & (engine.depth == 0)
        force = np.where(slid, engine.sense * limit, force)
        over = np.abs(force) >= limit
        force = np.where(over, np.sign(force) * limit, force)
        engine.depth[over] = 0
        engine.virgin[over] = False
        engine.y = force
        engine.x = np.where(over | slid, 0.0, engine.x)
        out.append((force, over | slid))
    return out


def test_tangential_spring_is_the_law_before_vectorisation():
    """The vectorised step (dense tops of the stack, sliding contacts skipped, blocks)
    gives the bits of the step before it, on 200 contacts over 600 random steps."""
    rng = np.random.default_rng(11)
    n = 200
    ball, plane = _bodies()
    contact = hertz.contact(ball, plane, load=rng.uniform(1.0, 100.0, n))
    spring = hertz.TangentialSpring(contact, 0.3)
    increments = _path(rng, n, 600, spring._reach)
    for k, (inc, (force, slid)) in enumerate(zip(increments,
                                                 _reference_spring(contact, 0.3, increments),
                                                 strict=True)):
        assert np.array_equal(spring.step(inc), force), k
        assert np.array_equal(spring.sliding, slid), k


def test_tangential_batch_virgin_curve_and_masing_branch():
    """Contacts of different loads pushed to t delta_s (Mindlin's virgin curve), then to
    sliding, then back by 2 s delta_s (Masing's branch from mu P), against mpmath."""
    loads = np.array([1.0, 3.0, 10.0, 30.0, 100.0, 55.5])
    t = np.array([0.001, 0.1, 0.5, 0.9, 0.999, 0.3])
    s = np.array([0.002, 0.2, 0.5, 0.75, 0.98, 0.4])
    mu = 0.3
    ball, plane = _bodies()
    spring = hertz.TangentialSpring(hertz.contact(ball, plane, load=loads), mu)
    reach = np.array([float(_reach_mp(p, mu)) for p in loads])
    virgin = spring.step(t * reach)
    spring.step(3.0 * reach)
    assert spring.sliding.all()
    back = spring.step(-2.0 * s * reach)
    for i, p in enumerate(loads):
        limit = mu * mp.mpf(p)
        want_virgin = limit * _virgin_mp(t[i])
        want_back = limit - 2 * limit * _virgin_mp(s[i])
        assert abs(virgin[i] - want_virgin) / limit < TOL_CURVE, i
        assert abs(back[i] - want_back) / limit < TOL_CURVE, i


def test_tangential_memory_is_the_open_loops():
    """Memory: a reversal remembered per open loop; closing a loop drops two points,
    sliding drops all."""
    ball, plane = _bodies()
    spring = hertz.TangentialSpring(hertz.contact(ball, plane, load=50.0), 0.3, size=2)
    u = float(_reach_mp(50.0, 0.3))
    for d in (0.5, -0.3, 0.2, -0.1, 0.05):  # nested, shrinking loops
        spring.step([d * u, d * u])
    assert spring.memory.tolist() == [4, 4]
    spring.step([-0.1 * u, 3.0 * u])  # a reversal (+1) closes a loop (-2); slides
    assert spring.memory.tolist() == [3, 0] and spring.sliding.tolist() == [False, True]


# ----------------------------------------------------------------------- LoadPathSpring
def test_load_path_batch_is_n_scalar_springs():
    """A batch of 16 contacts (radii, mu different) on random paths of P and increments,
    P = 0 (separation) at times, some slots reset: the bits of 16 single springs.  (The
    compiled step is the numpy code it replaced, bit for bit: test_load_path_kernel.py.)"""
    rng = np.random.default_rng(5)
    n = 16
    radius = rng.uniform(2e-3, 2e-2, n)
    mu = rng.uniform(0.1, 0.6, n)
    _, plane = _bodies()
    batch = hertz.LoadPathSpring(hertz.Body.sphere(radius, E=E1, nu=NU1), plane, mu)
    singles = [hertz.LoadPathSpring(hertz.Body.sphere(radius[i], E=E1, nu=NU1), plane, mu[i])
               for i in range(n)]
    load = rng.uniform(10.0, 100.0, n)
    scale = batch._reach * 40.0 ** (2.0 / 3.0)  # 3 mu P / (2 k) at 40 N
    for k, inc in enumerate(_path(rng, n, 300, scale)):
        kind = k % 4
        if kind == 1:
            load = load * rng.uniform(0.6, 1.5, n)
        elif kind == 2:
            load = np.where(rng.random(n) < 0.05, 0.0, rng.uniform(1.0, 100.0, n))
        if k % 41 == 40:
            gone = np.flatnonzero(rng.random(n) < 0.3)
            batch.reset(gone)
            for i in gone:
                singles[i].reset()
        force = batch.step(load, inc)
        assert np.array_equal(force, [s.step(load[i], inc[i]) for i, s in enumerate(singles)])
        for name in ("sliding", "displacement", "stick_a", "stick_b", "normal_force",
                     "memory"):
            assert np.array_equal(getattr(batch, name), [getattr(s, name) for s in singles]), \
                (k, name)
    assert batch.sliding.any() and not batch.sliding.all()


def test_load_path_batch_closed_forms():
    """Mindlin-Deresiewicz by mpmath: pushed to t delta_s at P0 (the virgin curve), P
    raised to P1 at a fixed displacement (nothing changes), back by 2 s delta_s(P0) after
    sliding at P1 (Masing's branch at P1 from the sliding point); and, in another batch,
    Q/P = r fixed from zero (delta = 3 r P / (2 k(P)))."""
    loads = np.array([2.0, 10.0, 40.0, 90.0])
    t = np.array([0.01, 0.4, 0.8, 0.995])
    s = np.array([0.05, 0.3, 0.6, 0.9])
    mu = 0.35
    ball, plane = _bodies()
    spring = hertz.LoadPathSpring(ball, plane, mu, size=loads.size)
    reach = np.array([float(_reach_mp(p, mu)) for p in loads])
    spring.step(loads, 0.0)
    pushed = spring.step(loads, t * reach)
    raised = spring.step(2.0 * loads, 0.0)
    high = np.array([float(_reach_mp(2.0 * p, mu)) for p in loads])
    spring.step(2.0 * loads, 3.0 * high)
    back = spring.step(2.0 * loads, -2.0 * s * high)
    for i, p in enumerate(loads):
        limit = mu * mp.mpf(p)
        assert abs(pushed[i] - limit * _virgin_mp(t[i])) / limit < TOL_CURVE, i
        assert abs(raised[i] - pushed[i]) / limit < TOL_RAISED, i
        limit2 = 2 * limit
        assert abs(back[i] - (limit2 - 2 * limit2 * _virgin_mp(s[i]))) / limit2 < TOL_CURVE

    ratio = np.array([0.05, 0.2, 0.34])  # Q/P < mu
    path = np.linspace(0.5, 80.0, 12)
    proportional = hertz.LoadPathSpring(ball, plane, mu, size=ratio.size)
    before = np.zeros(ratio.size)
    for p in path:
        # delta = 3 r P / (2 k(P)) = (r / mu) delta_s(P)
        delta = np.array([float(r / mu * _reach_mp(p, mu)) for r in ratio])
        q = proportional.step(p, delta - before)
        before = delta
        assert np.all(np.abs(q - ratio * p) / (mu * p) < TOL_PROPORTIONAL), p
    assert proportional.memory.max() <= path.size


@pytest.mark.parametrize("direction", [0.0, math.pi / 2])
def test_load_path_batch_gives_back_load_paths_forces(direction):
    """Four (P, Q) paths solved by hertz.load_path (force-driven, the _SpringBed), their
    displacements fed to one batch: the batch gives back the four force histories."""
    body1 = hertz.Body(5e-3, 1.5e-2, E=E1, nu=NU1)
    body2 = hertz.Body.plane(E=E2, nu=NU2)
    mu = 0.375
    loads = np.array([[20, 20, 32, 32, 28, 12, 12, 25, 30, 30, 14.0],
                      [10, 40, 40, 80, 80, 60, 20, 20, 50, 50, 50.0],
                      [50, 50, 50, 50, 50, 50, 50, 50, 50, 50, 50.0],
                      [5, 15, 25, 35, 45, 55, 45, 35, 25, 15, 5.0]]).T
    forces = np.array([[0, 4, 4, 7, -3, -3, 2, 6, -5, -11.25, -5.25],
                       [0, 0, 5, 5, 20, 10, -5, 2, 2, -15, 18.75],
                       [0, 10, -10, 5, -5, 2, -2, 1, -18.75, 0, 18.75],
                       [1, 3, 5, 7, 9, 11, 9, 7, 5, 3, 1.0]]).T
    disp = np.array([hertz.load_path(body1, body2, loads[:, j], forces[:, j], mu,
                                     direction=direction).displacement
                     for j in range(4)]).T
    spring = hertz.LoadPathSpring(body1, body2, mu, direction=direction, size=4)
    back = np.array([spring.step(p, d) for p, d in zip(loads, np.diff(disp, axis=0,
                                                                      prepend=0.0),
                                                       strict=True)])
    assert np.abs(back - forces).max() < TOL_LOAD_PATH * mu * loads.max()


def test_load_path_memory():
    """Pieces: a contact fretting at constant P keeps a few; sliding as a whole leaves
    one; P rising at a standing displacement adds one (the ring that entered unloaded)
    and no more; P rising while the displacement
    creeps adds one a step (the springs that enter carry different forces)."""
    ball, plane = _bodies()
    spring = hertz.LoadPathSpring(ball, plane, 0.3, size=3)
    u = float(_reach_mp(50.0, 0.3))
    spring.step(50.0, 0.0)
    for k in range(200):
        spring.step(50.0, [0.4 * u * (-1) ** k, 3.0 * u * (-1) ** k, 0.0])
    assert spring.memory.tolist()[:2] == [3, 1] and spring.sliding.tolist()[1]
    for k in range(100):
        spring.step(50.0 + k, [0.0, 0.0, 1e-3 * u])
    assert spring.memory.tolist() == [4, 2, 101]  # the unloaded ring: one piece
    spring.step(0.0, 0.0)
    assert spring.memory.tolist() == [0, 0, 0] and spring.force.tolist() == [0, 0, 0]


# ----------------------------------------------------------------------- bad input
def test_bad_input():
    ball, plane = _bodies()
    c = hertz.contact(ball, plane, load=[10.0, 20.0, 30.0])
    spring = hertz.TangentialSpring(c, 0.3)
    with pytest.raises(ValueError, match=r"where must be a boolean mask .*\(3,\)"):
        spring.reset(np.ones(4, dtype=bool))
    with pytest.raises(ValueError, match="where must hold indices from -3 to 2.*got 3"):
        spring.reset([3])
    with pytest.raises(ValueError, match="increment must broadcast"):
        spring.step([1e-9, 2e-9])
    with pytest.raises(ValueError, match="size must be a non-negative int"):
        hertz.TangentialSpring(c, 0.3, size=-1)
    with pytest.raises(ValueError, match="size = 2 contacts does not broadcast"):
        hertz.TangentialSpring(c, 0.3, size=2)
    springs = hertz.LoadPathSpring(ball, plane, 0.3, size=3)
    with pytest.raises(ValueError, match=r"normal_force .*-1\.0.* at index 1"):
        springs.step([1.0, -1.0, 2.0], 0.0)
    with pytest.raises(ValueError, match=r"increment .*at index 2"):
        springs.step(1.0, [0.0, 0.0, math.nan])
    with pytest.raises(ValueError, match="normal_force must broadcast"):
        springs.step([1.0, 2.0], 0.0)
    assert springs.normal_force.tolist() == [0.0, 0.0, 0.0]  # the state is unchanged
    with pytest.raises(ValueError, match="where must be a boolean mask"):
        springs.reset([0.5])
