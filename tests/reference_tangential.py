"""Independent mpmath reference for tangential (Cattaneo-Mindlin) contact; does not import hertz.

Everything here comes from Cerruti's point-force solution integrated over the traction, not
from the closed forms in K(m), E(m) of hertz/_tangential.py.

Cerruti: a tangential point force F along x on the surface of a half-space (shear modulus G,
Poisson's ratio nu) displaces the surface point at offset r (cos t, sin t) by

    u_x = F / (2 pi G) [(1 - nu) + nu cos^2 t] / r,   u_y = F / (2 pi G) nu cos t sin t / r

(Johnson, Contact Mechanics, ch. 3; for a force along y swap cos and sin in u_y's
partner: u_y = F / (2 pi G) [(1 - nu) + nu sin^2 t] / r).

The displacement at a field point (x0, y0) of the ellipse x^2/a^2 + y^2/b^2 <= 1 is written in
polar coordinates (rho, t) centred on the field point. Along a ray, 1 - x^2/a^2 - y^2/b^2 is a
quadratic A (R - rho)(rho + R') with A = cos^2 t / a^2 + sin^2 t / b^2 and R, R' > 0 the
distances to the edge forwards and backwards, so the radial integral of the two tractions used
here is elementary (h = (R + R')/2, s = (R - R')/2):

    int_0^R (A (R - rho)(rho + R'))^(-1/2) d rho = (pi/2 + asin(s/h)) / sqrt(A)
    int_0^R (A (R - rho)(rho + R'))^(1/2)  d rho = sqrt(A) (h^2 (pi/4 + asin(s/h)/2)
                                                           + s sqrt(R R') / 2)

and the angular integral is taken by mpmath.quad (tanh-sinh) on the four quadrants. The
1/r of the kernel cancels the rho of the area element. For a very long ellipse the
integrand has peaks of width b/a at t = 0 and pi, which are quadrant ends (tanh-sinh
clusters its nodes there); off-centre points add breakpoints at the directions to the ends
of the axes.

The relative displacement of the two bodies is the sum of the two bodies' displacements
(Mindlin's uncoupled solution: the normal-tangential coupling of dissimilar bodies is
neglected). The Masing branches and the loop energy are integrated numerically here from the
quadrature's virgin curve.
"""

import mpmath as mp

__all__ = ["DPS", "displacement_hertz_traction", "displacement_no_slip", "loop_energy",
           "masing_unloading", "no_slip_compliance", "partial_slip_displacement",
           "sliding_displacement", "slip_misalignment", "virgin"]

DPS = 50


def _rays(a, b, x0, y0, t):
    """A(t), R(t), R'(t) for the ray from (x0, y0) in direction t."""
    c, s = mp.cos(t), mp.sin(t)
    A = c * c / (a * a) + s * s / (b * b)
    B = x0 * c / (a * a) + y0 * s / (b * b)  # 1 - |p + rho e|^2 = (1 - |p|^2) - 2 B rho - A rho^2
    c0 = 1 - x0 * x0 / (a * a) - y0 * y0 / (b * b)
    disc = mp.sqrt(B * B + A * c0)
    R = (disc - B) / A
    rb = (disc + B) / A
    return A, R, rb


def _angular(f, a, b, x0, y0):
    pts = [0, mp.pi / 2, mp.pi, 3 * mp.pi / 2, 2 * mp.pi]
    if x0 or y0:  # directions to the ends of the axes, where the integrand turns fastest
        extra = [mp.atan2(yy - y0, xx - x0) % (2 * mp.pi)
                 for xx, yy in ((a, 0), (-a, 0), (0, b), (0, -b))]
        pts = sorted(set(pts + extra))
    return mp.quad(f, pts)


def _moments(weight_radial, a, b, x0, y0, axis):
    """(i0, i2): the angular integrals of the radial integral times 1 and times the
    squared direction cosine along the force (cos^2 t for x, sin^2 t for y), and the
    transverse one I_t (cos t sin t)."""
    def parts(t):
        A, R, rb = _rays(a, b, x0, y0, t)
        w = weight_radial(A, R, rb)
        c, s = mp.cos(t), mp.sin(t)
        return w, w * (c * c if axis == "x" else s * s), w * c * s

    if not (x0 or y0):  # the centre: the integrand has the ellipse's symmetry (and no
        # transverse part), so one quadrant suffices
        i0 = 4 * mp.quad(lambda t: parts(t)[0], [0, mp.pi / 2])
        i2 = 4 * mp.quad(lambda t: parts(t)[1], [0, mp.pi / 2])
        return i0, i2, mp.mpf(0)
    i0 = _angular(lambda t: parts(t)[0], a, b, x0, y0)
    i2 = _angular(lambda t: parts(t)[1], a, b, x0, y0)
    i_t = _angular(lambda t: parts(t)[2], a, b, x0, y0)
    return i0, i2, i_t


def _inverse_sqrt_radial(A, R, rb):
    h, s = (R + rb) / 2, (R - rb) / 2
    return (mp.pi / 2 + mp.asin(s / h)) / mp.sqrt(A)


def _sqrt_radial(A, R, rb):
    h, s = (R + rb) / 2, (R - rb) / 2
    return mp.sqrt(A) * (h * h * (mp.pi / 4 + mp.asin(s / h) / 2) + s * mp.sqrt(R * rb) / 2)


def _bodies_sum(i0, i2, i_t, bodies):
    """(along, transverse) displacement per unit traction scale, summed over bodies (G, nu)."""
    along = sum(((1 - nu) * i0 + nu * i2) / (2 * mp.pi * G) for G, nu in bodies)
    transverse = sum(nu * i_t / (2 * mp.pi * G) for G, nu in bodies)
    return along, transverse


def displacement_no_slip(a, b, bodies, x0=0, y0=0, axis="x"):
    """Relative displacement (along, transverse) [m per N] at (x0, y0) under the no-slip
    traction (1/(2 pi a b)) (1 - x^2/a^2 - y^2/b^2)^(-1/2) of unit force along ``axis``."""
    with mp.workdps(DPS):
        a, b, x0, y0 = mp.mpf(a), mp.mpf(b), mp.mpf(x0), mp.mpf(y0)
        bodies = [(mp.mpf(G), mp.mpf(nu)) for G, nu in bodies]
        i0, i2, i_t = _moments(_inverse_sqrt_radial, a, b, x0, y0, axis)
        along, trans = _bodies_sum(i0, i2, i_t, bodies)
        scale = 1 / (2 * mp.pi * a * b)
        return along * scale, trans * scale


def no_slip_compliance(a, b, bodies, axis="x"):
    """No-slip tangential compliance [m/N] along a principal axis (at the centre)."""
    return displacement_no_slip(a, b, bodies, 0, 0, axis)[0]


def _outside_moments(a, b, x0, y0, axis):
    """(i0, i2, i_t) of the traction sqrt(1 - r^2) at a point outside the ellipse: a ray
    meets the ellipse, if at all, between the roots rho1 < rho2 of the quadratic, and
    int_rho1^rho2 (A (rho2 - rho)(rho - rho1))^(1/2) d rho = pi (B^2 + A c0) / (2 A^(3/2));
    the angle runs over the cone between the two tangents from the point."""
    r0 = mp.sqrt((x0 / a) ** 2 + (y0 / b) ** 2)
    psi, half = mp.atan2(y0 / b, x0 / a), mp.acos(1 / r0)
    towards = mp.atan2(-y0, -x0)
    edges = []
    for phi in (psi - half, psi + half):  # the tangent points (a cos phi, b sin phi)
        t = mp.atan2(b * mp.sin(phi) - y0, a * mp.cos(phi) - x0)
        edges.append(towards + ((t - towards + mp.pi) % (2 * mp.pi) - mp.pi))
    c0 = 1 - (x0 / a) ** 2 - (y0 / b) ** 2

    def parts(t):
        c, s = mp.cos(t), mp.sin(t)
        A = c * c / (a * a) + s * s / (b * b)
        B = x0 * c / (a * a) + y0 * s / (b * b)
        disc = B * B + A * c0
        if disc <= 0 or B >= 0:
            return mp.mpf(0), mp.mpf(0), mp.mpf(0)
        w = mp.pi * disc / (2 * A * mp.sqrt(A))
        return w, w * (c * c if axis == "x" else s * s), w * c * s

    lo, hi = min(edges), max(edges)
    return tuple(mp.quad(lambda t, k=k: parts(t)[k], [lo, towards, hi]) for k in range(3))


def displacement_hertz_traction(a, b, bodies, x0=0, y0=0, axis="x"):
    """Relative displacement (along, transverse) [m per Pa] at (x0, y0) under the traction
    sqrt(1 - x^2/a^2 - y^2/b^2) along ``axis`` (times the peak value in Pa); (x0, y0)
    inside or outside the ellipse."""
    with mp.workdps(DPS):
        a, b, x0, y0 = mp.mpf(a), mp.mpf(b), mp.mpf(x0), mp.mpf(y0)
        bodies = [(mp.mpf(G), mp.mpf(nu)) for G, nu in bodies]
        if (x0 / a) ** 2 + (y0 / b) ** 2 < 1:
            i0, i2, i_t = _moments(_sqrt_radial, a, b, x0, y0, axis)
        else:
            i0, i2, i_t = _outside_moments(a, b, x0, y0, axis)
        return _bodies_sum(i0, i2, i_t, bodies)


def partial_slip_displacement(a, b, load, mu, force, bodies, axis="x", x0=0, y0=0):
    """Cattaneo-Mindlin relative displacement [m] at a stick point (x0, y0).

    The traction is mu p0 sqrt(1 - r^2) minus mu p0 c sqrt(1 - r^2/c^2) on the stick ellipse
    of ratio c with force mu P c^3 = mu P - Q (Mindlin's construction); the displacement of the
    second term at (x0, y0) is c^2 times the first's at (x0/c, y0/c) (scaling of the
    half-space). Returns (displacement, c)."""
    with mp.workdps(DPS):
        a, b, load, mu, force = (mp.mpf(v) for v in (a, b, load, mu, force))
        p0 = 3 * load / (2 * mp.pi * a * b)
        c = mp.cbrt(1 - force / (mu * load))
        full = displacement_hertz_traction(a, b, bodies, x0, y0, axis)[0]
        if c == 0:
            return mu * p0 * full, c
        stick = displacement_hertz_traction(a, b, bodies, x0 / c, y0 / c, axis)[0]
        return mu * p0 * (full - c * c * stick), c


def sliding_displacement(a, b, load, mu, bodies, axis="x"):
    """The displacement [m] at the onset of sliding (Q = mu P) along ``axis``: the centre
    displacement of the traction mu p0 sqrt(1 - r^2), by quadrature."""
    with mp.workdps(DPS):
        a, b, load, mu = (mp.mpf(v) for v in (a, b, load, mu))
        p0 = 3 * load / (2 * mp.pi * a * b)
        return mu * p0 * displacement_hertz_traction(a, b, bodies, 0, 0, axis)[0]


def virgin(reach, load, mu, force):
    """The virgin curve: displacement [m] at ``force`` from the sliding displacement ``reach``:
    the stick ellipse of ratio c = (1 - Q/(mu P))^(1/3) carries a Hertz-shaped traction c times
    smaller over an ellipse c times smaller, whose displacement is c^2 that of the whole.
    Elementary, so it is evaluated with 15 guard digits (1 - c^2 and the loop's branch
    differences cancel as the force -> 0)."""
    with mp.workdps(DPS + 15):
        c = mp.cbrt(1 - mp.mpf(force) / (mp.mpf(mu) * mp.mpf(load)))
        return reach * (1 - c * c)


def masing_unloading(reach, load, mu, amplitude, forces):
    """Displacements [m] on the unloading branch from Q* = amplitude, by Masing's rule
    delta(Q) = delta(Q*) - 2 f((Q* - Q)/2) with the quadrature's virgin curve f."""
    with mp.workdps(DPS + 15):
        top = virgin(reach, load, mu, amplitude)
        return [top - 2 * virgin(reach, load, mu, (mp.mpf(amplitude) - mp.mpf(q)) / 2)
                for q in forces]


def loop_energy(reach, load, mu, amplitude):
    """Energy [J] dissipated per cycle Q* -> -Q* -> Q*: the area between the Masing branches,
    integrated numerically (mpmath.quad) from the quadrature's virgin curve."""
    with mp.workdps(DPS + 15):
        qa = mp.mpf(amplitude)
        top = virgin(reach, load, mu, qa)

        def gap(q):  # unloading branch minus reloading branch
            return ((top - 2 * virgin(reach, load, mu, (qa - q) / 2))
                    - (-top + 2 * virgin(reach, load, mu, (qa + q) / 2)))
        return mp.quad(gap, [-qa, 0, qa])


def slip_misalignment(a, b, bodies, q, direction, points):
    """Angle [deg] between the slip and the force's line at points (x0, y0) of the slip
    annulus, for Mindlin's traction at Q/(mu P) = q along ``direction`` [rad].

    The traction is Mindlin's: mu p0 (sqrt(1 - r^2) - c sqrt(1 - r^2/c^2)) along the force,
    c = (1 - q)^(1/3), i.e. cos t times the x-axis problem plus sin t times the y-axis one.
    The slip is the surface's relative displacement there minus the stick zone's rigid
    displacement; Coulomb's law wants it parallel to the traction, and it is not exactly:
    this is the size of the approximation that Mindlin's solution (and this library)
    makes.  The common factor mu p0 drops out."""
    with mp.workdps(DPS):
        a, b, direction = mp.mpf(a), mp.mpf(b), mp.mpf(direction)
        c = mp.cbrt(1 - mp.mpf(q))
        cos_t, sin_t = mp.cos(direction), mp.sin(direction)
        rigid = {axis: displacement_hertz_traction(a, b, bodies, 0, 0, axis)[0] * (1 - c * c)
                 for axis in "xy"}
        out = []
        for x0, y0 in points:
            x0, y0 = mp.mpf(x0), mp.mpf(y0)
            u = {}
            for axis in "xy":
                full = displacement_hertz_traction(a, b, bodies, x0, y0, axis)
                stick = displacement_hertz_traction(a, b, bodies, x0 / c, y0 / c, axis)
                u[axis] = (full[0] - c * c * stick[0], full[1] - c * c * stick[1])
            slip_x = cos_t * (u["x"][0] - rigid["x"]) + sin_t * u["y"][1]
            slip_y = cos_t * u["x"][1] + sin_t * (u["y"][0] - rigid["y"])
            along = abs(slip_x * cos_t + slip_y * sin_t) / mp.hypot(slip_x, slip_y)
            out.append(mp.degrees(mp.acos(min(along, 1))))
        return out
