"""Our block solution as VTU files: displacement, stress and Hertz's field at the
nodes of each body (ParaView)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..fe.elasticity import von_mises
from ..scenes import Scene
from .mesh import BlockMesh
from .solve import ContactSolution


def hertz_nodal_stress(c, p: np.ndarray, body: int) -> np.ndarray:
    """Hertz's stress at nodes p (3, n) of body 1 or 2, in the mesh frame, (n, 3, 3) [Pa].

    The nodes are put into the ellipse frame of ``c`` (a ``hertz.Contact``; z is
    the depth into the body: the mesh's z for body 1, -z for body 2),
    ``c.stress`` is evaluated there at once, and the tensors are turned back
    into the mesh frame.
    """
    from ..fe.surface import ellipse_rotation

    rot = ellipse_rotation(c.major_axis_angle, body)
    x, y, z = rot @ p
    exact = c.stress(x, y, np.maximum(z, 0.0), body=body)
    return np.einsum("ji,njk,kl->nil", rot, exact, rot)


def _tensor(s: np.ndarray) -> np.ndarray:
    """(n, 3, 3) -> (n, 9), rows xx xy xz yx yy yz zx zy zz (ParaView's tensor layout)."""
    return np.ascontiguousarray(s.reshape(len(s), 9))


def write_vtu(scene: Scene, mesh: BlockMesh, sol: ContactSolution, out: Path,
              nodal_stress: tuple | None = None, reference=None) -> list[Path]:
    """One .vtu per body, for ParaView.

    Point data: ``displacement`` [m]; ``stress_fem`` (the patch-recovered FEM
    stress, :func:`fem_validation.solvers.blocks.recovered_stress`), ``stress_hertz``
    (``Contact.stress`` at the node) and ``stress_difference`` (FEM - Hertz),
    9-component tensors in the mesh frame [Pa]; ``von_mises`` (of
    ``stress_fem``), ``von_mises_hertz`` and ``von_mises_difference`` [Pa];
    ``contact_pressure_fem``, ``contact_pressure_hertz`` and
    ``contact_pressure_difference`` [Pa] (zero off the contact face).

    Parameters
    ----------
    scene, mesh, sol : the run
    out : Path
        Directory; writes ``<scene>_body1.vtu`` and ``<scene>_body2.vtu``.
    nodal_stress : tuple of two ndarrays, optional
        The bodies' recovered stresses (``Comparison.nodal_stress``), computed
        here if not given.
    reference : hertz.Contact, optional
        The Hertz contact to write (default: the scene's at the force reached).
    """
    import meshio

    from .blocks import recovered_stress

    c = scene.hertz(sol.force) if reference is None else reference
    theta = c.major_axis_angle
    paths = []
    for i, (m, u) in enumerate(zip(mesh.bodies, (sol.u1, sol.u2), strict=True)):
        nodes = mesh.pairs[:, i]
        p_fem = np.zeros(m.nvertices)
        p_fem[nodes] = sol.pressure
        x, y = m.p[0, nodes], m.p[1, nodes]
        p_hertz = np.zeros(m.nvertices)
        p_hertz[nodes] = c.pressure(x * math.cos(theta) + y * math.sin(theta),
                                    -x * math.sin(theta) + y * math.cos(theta))
        fem = (recovered_stress(scene, mesh, sol, i + 1) if not nodal_stress
               else nodal_stress[i])
        exact = hertz_nodal_stress(c, m.p, i + 1)
        vm, vm_hertz = von_mises(fem), von_mises(exact)
        data = {"displacement": u, "von_mises": vm,
                "contact_pressure_fem": p_fem, "contact_pressure_hertz": p_hertz,
                "contact_pressure_difference": p_fem - p_hertz,
                "stress_fem": _tensor(fem), "stress_hertz": _tensor(exact),
                "stress_difference": _tensor(fem - exact), "von_mises_hertz": vm_hertz,
                "von_mises_difference": vm - vm_hertz}
        path = out / f"{scene.name}_body{i + 1}.vtu"
        meshio.write(path, meshio.Mesh(m.p.T, [("tetra", m.t.T)], point_data=data))
        paths.append(path)
    return paths
