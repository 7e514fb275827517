"""The numpy implementation of hertz.LoadPathSpring's step, kept as the reference of the
compiled kernel (hertz/_load_path_kernel.c): tests/test_load_path_kernel.py drives both
along random paths and asserts the same bits in the forces and the whole state.

This is the code the kernel replaced (hertz/_load_path.py before it), unchanged but for
the step's post-processing, gathered in :func:`step`: the per-contact stacks of pieces
(:class:`_SpringStacks`, :class:`_Block`; the algorithm is described in their docstrings
and in hertz/_load_path.py's module docstring).
"""

import numpy as np

#: How often each branch of a step ran (contacts), for the tests to check their paths
#: reach every one.
HITS = dict.fromkeys(("gone", "leaving", "sliding", "cut", "all_slide", "entering",
                      "on_limit", "merged", "whole", "far"), 0)

_EPS = np.finfo(float).eps


def _piece_integral(x0, x1, c0, c2):
    """int_x0^x1 (c0 + c2 x^2) dx (as _SpringBed._integral)."""
    w = x1 - x0
    return w * (c0 + c2 * (x1 * x1 + x1 * x0 + x0 * x0) * (1.0 / 3.0))


class _SpringStacks:
    """The spring bed for N contacts in numpy arrays: contact i holds count[i] pieces
    (inner edges E, coefficients D, B, the force below F), the algorithm of
    hertz._load_path._SpringStacks (whose docstring describes it), advanced in blocks
    of contacts by passes over only the contacts that pop pieces.
    """

    BLOCK = 16384  # contacts advanced together: the temporaries stay in cache

    def __init__(self, n):
        self.count = np.zeros(n, dtype=np.intp)
        self.alpha = np.zeros(n)
        self.delta = np.zeros(n)
        self.E = np.zeros((n, 4))
        self.D = np.zeros((n, 4))
        self.B = np.zeros((n, 4))
        self.F = np.zeros((n, 4))

    def reset(self, rows):
        self.count[rows] = 0
        self.alpha[rows] = 0.0
        self.delta[rows] = 0.0

    def _room(self, need):
        width = self.E.shape[1]
        if need > width:
            grow = max(need, 2 * width) - width
            for name in ("E", "D", "B", "F"):
                setattr(self, name, np.pad(getattr(self, name), ((0, 0), (0, grow))))

    def move(self, alpha1, d_delta):
        """Move every contact to the scaled size alpha1 with the scaled increment
        d_delta; return Q / (mu P_ref) and the innermost x that slid (alpha1 if none,
        0 out of contact)."""
        self._room(int(self.count.max(initial=0)) + 2)  # a step pushes 2 pieces at most
        n = alpha1.size
        q = np.empty(n)
        front = np.empty(n)
        for start in range(0, n, self.BLOCK):
            s = slice(start, start + self.BLOCK)
            _Block(self, s).move(alpha1[s], d_delta[s], q[s], front[s])
        return q, front


class _Block:
    """One block of the contacts of a :class:`_SpringStacks`: views of its arrays, the
    pieces' arrays flattened (piece j of contact i at i * width + j) so that reading
    one piece per contact is a single gather."""

    def __init__(self, stacks, s):
        self.count, self.alpha, self.delta = stacks.count[s], stacks.alpha[s], stacks.delta[s]
        self.w = stacks.E.shape[1]
        self.D2, self.F2 = stacks.D[s], stacks.F[s]
        self.E, self.D, self.B, self.F = (a[s].ravel() for a in (stacks.E, stacks.D,
                                                                 stacks.B, stacks.F))

    def move(self, alpha1, d_delta, q_out, front_out):
        count, w = self.count, self.w
        gone = alpha1 == 0.0
        HITS["gone"] += int(gone.sum())
        if gone.any():
            r = np.flatnonzero(gone)
            count[r] = 0
            self.alpha[r] = 0.0
            self.delta[r] = 0.0
        alpha0 = self.alpha
        delta1 = self.delta + d_delta
        a2 = alpha1 * alpha1
        front = alpha1.copy()
        # springs leaving: pop the pieces that start at or beyond the new size
        rows = np.flatnonzero(alpha1 < alpha0)
        HITS["leaving"] += rows.size
        while rows.size:
            out = self.E[rows * w + count[rows] - 1] >= alpha1[rows]
            rows = rows[out]
            count[rows] -= 1
        top_end = np.minimum(alpha0, alpha1)  # where the old springs end now
        # springs sliding: an outer interval of the old ones, to +L (s = 1) or -L (s = -1)
        rows = np.flatnonzero(count > 0)
        if rows.size:
            i = rows * w + count[rows] - 1
            x = top_end[rows]
            u = (delta1[rows] - self.D[i]) + self.B[i] * (x * x)
            # beyond the limit by more than the rounding of u (a piece on its limit
            # that does not move stays on it, not slid by a few ulp)
            tol = _tolerance(delta1[rows], alpha1[rows])
            limit = (alpha1[rows] - x) * (alpha1[rows] + x) + tol
            up, down = u > limit, u < -limit
            slides = up | down
            HITS["sliding"] += int(slides.sum())
            if slides.any():
                self._slide(rows[slides], np.where(up[slides], 1.0, -1.0), delta1, alpha1,
                            top_end, front, tol[slides])
        # springs entering: one piece from the old size, on the limit if it slides
        rows = np.flatnonzero(alpha1 > alpha0)
        if rows.size:
            a0, a1 = alpha0[rows], alpha1[rows]
            d = (a1 - a0) * (a1 + a0)
            ratio = d_delta[rows] / d
            on_limit = np.abs(ratio) > 1.0
            HITS["entering"] += rows.size
            HITS["on_limit"] += int(on_limit.sum())
            coef = np.where(on_limit, np.sign(ratio), ratio)
            self._push(rows, a0, delta1[rows] - coef * a2[rows], -coef)
            front[rows] = np.where(on_limit & (front[rows] == a1), a0, front[rows])
        self.alpha[...] = alpha1
        delta = self.delta
        delta[...] = delta1
        # a contact sliding as a whole: one piece on the limit, delta from 0 again
        whole = (count == 1) & (front == 0.0)
        HITS["whole"] += int(whole.sum())
        if whole.any():
            r = np.flatnonzero(whole)
            self.D[r * w] -= delta[r]
            delta[r] = 0.0
        far = np.abs(delta) > 4.0 * a2
        HITS["far"] += int((far & (count > 0)).sum())
        if far.any():
            r = np.flatnonzero(far & (count > 0))
            self.D2[r] -= delta[r, None]
            self.F2[r] += delta[r, None] * self.E.reshape(-1, w)[r]
            delta[far] = 0.0
        q_out[...] = self.force()
        front_out[...] = np.where(gone, 0.0, front)

    def _push(self, rows, edge, D, B):  # noqa: N803 (the module docstring's names)
        """Push the piece [edge, ...) with the coefficients (D, B) on the given rows
        (merged with the top piece where that has the same coefficients)."""
        if rows.size == 0:
            return
        w = self.w
        n = self.count[rows]
        i = rows * w + np.maximum(n - 1, 0)
        same = (n > 0) & (self.D[i] == D) & (self.B[i] == B)
        HITS["merged"] += int(same.sum())
        if same.any():
            keep = ~same
            rows, edge, D, B, n, i = rows[keep], edge[keep], D[keep], B[keep], n[keep], i[keep]
            if rows.size == 0:
                return
        F = np.where(n > 0, self.F[i] + _piece_integral(  # noqa: N806
            self.E[i], edge, -self.D[i], self.B[i]), 0.0)
        j = rows * w + n
        self.E[j] = edge
        self.D[j] = D
        self.B[j] = B
        self.F[j] = F
        self.count[rows] = n + 1

    def _slide(self, rows, sense, delta1, alpha1, top_end, front, tol):
        """Pop the pieces whose inner edge slides, cut the piece that holds the front c,
        push the piece on the limit from c (rows: the contacts whose outer old spring
        slides, ``sense`` the way)."""
        w = self.w
        n = self.count[rows]
        a1, d1 = alpha1[rows], delta1[rows]
        tiny = 4.0 * _EPS * a1
        # find the innermost piece whose inner edge does not slide (all of it: c = 0)
        k = n - 1
        active = np.arange(rows.size)
        while active.size:
            j = k[active]
            i = rows[active] * w + j
            e = self.E[i]
            u = (d1[active] - self.D[i]) + self.B[i] * (e * e)
            lim = (a1[active] - e) * (a1[active] + e) + tol[active]
            edge_slides = sense[active] * u > lim
            k[active[edge_slides & (j == 0)]] = -1  # everything slides
            active = active[edge_slides & (j > 0)]
            k[active] -= 1
        cut = k >= 0
        HITS["cut"] += int(cut.sum())
        HITS["all_slide"] += int((~cut).sum())
        kk = np.maximum(k, 0)
        i = rows * w + kk
        e0 = self.E[i]
        end = top_end[rows]
        e1 = np.minimum(np.where(kk + 1 < n, self.E[rows * w + np.minimum(kk + 1, w - 1)],
                                 end), end)
        d_k, b_k = self.D[i], self.B[i]
        # the front in piece k: s (d1 - d_k + b_k c^2) = a1^2 - c^2
        with np.errstate(divide="ignore", invalid="ignore"):
            c = np.sqrt((a1 * a1 - sense * (d1 - d_k)) / (1.0 + sense * b_k))
        c = np.where(np.isfinite(c), np.clip(c, e0, e1), e1)
        c = np.where(cut, c, 0.0)
        c = np.where(cut & (c - e0 <= tiny), e0, c)  # a sliver that sticks: slides too
        slid = end - c > tiny  # a sliver that slides: nothing slid
        rows, sense, c, e0, k = rows[slid], sense[slid], c[slid], e0[slid], k[slid]
        a1, d1 = a1[slid], d1[slid]
        # keep the pieces below the front (piece k if a stretch of it sticks)
        count = np.where(c > e0, k + 1, np.maximum(k, 0))
        self.count[rows] = np.where(c == 0.0, 0, count)
        self._push(rows, c, d1 - sense * (a1 * a1), -sense)
        front[rows] = c

    def force(self):
        """Q / (mu P_ref) of every contact: (3/2) int_0^a u dx."""
        n = self.count
        i = np.arange(n.size) * self.w + np.maximum(n - 1, 0)
        e, D, B, F = self.E[i], self.D[i], self.B[i], self.F[i]  # noqa: N806
        q = F + self.delta * e + _piece_integral(e, self.alpha, self.delta - D, B)
        return np.where(n > 0, 1.5 * q, 0.0)


def _tolerance(delta1, alpha1):
    """The rounding of u = (delta - D) + B x^2 against the limit: 8 eps (|delta| + a^2)."""
    return 8.0 * _EPS * (np.abs(delta1) + alpha1 * alpha1)



def step(bed, load, inc, mu, reach, a_ref, b_ref):
    """One step of LoadPathSpring after its input checks: the bed moved in place; return
    (force, sliding, stick_a, stick_b) as LoadPathSpring.step computed them."""
    alpha = np.cbrt(load)
    bound = np.maximum(alpha, bed.alpha)
    bound = 4.0 * bound * bound
    with np.errstate(over="ignore"):
        scaled = np.clip(inc * (1.0 / reach), -bound, bound)
    scaled, front = bed.move(alpha, scaled)
    limit = mu * load
    force = mu * scaled
    sliding = (alpha > 0.0) & ((front == 0.0) | (np.abs(force) >= limit))
    front = np.where(sliding, 0.0, front)
    force = np.where(sliding, np.copysign(limit, scaled), force)
    return force, sliding, front * a_ref, front * b_ref
