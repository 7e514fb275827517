"""The validation scenes: pairs of bodies, a target load and the angle between them."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

import hertz

STEEL = {"E": 210e9, "nu": 0.3}
ALUMINIUM = {"E": 70e9, "nu": 0.33}
#: Semi-major axis over the smallest radius for the default loads (Hertz needs a << R).
A_OVER_R = 0.03
#: The largest curvature ratio the block meshes support.  Measured at level 0 on 2 shared
#: cores: alpha 1000 meshes, solves and compares in 33 s and 278 MB (55k dofs), 1e4 in 131 s
#: and 677 MB (189k dofs), 1e5 did not finish in 400 s (issue 18: 77 s and 1.9 GB, then a
#: math domain error; 1e9 meshed for over 5 minutes).  The README validates up to 100.
MAX_ALPHA = 1000.0


@dataclass(frozen=True)
class Scene:
    """Two bodies pressed together.

    Attributes
    ----------
    name : str
        Identifier used in file names and reports.
    body1, body2 : hertz.Body
        The bodies; body 1 is the upper block of the model.
    load : float
        Target normal force [N]; the finite-element run reports the force it
        actually reached and is compared with Hertz at that force.
    angle : float
        Angle from body 1's x axis to body 2's x axis [rad].
    """

    name: str
    body1: hertz.Body
    body2: hertz.Body
    load: float
    angle: float = 0.0

    def hertz(self, load: float | None = None) -> hertz.Contact:
        """The Hertz solution at ``load`` (default: the scene's target load)."""
        return hertz.contact(self.body1, self.body2, load=self.load if load is None else load,
                             angle=self.angle)

    @property
    def curvature_tensor(self) -> np.ndarray:
        """2x2 relative curvature tensor of the gap in body 1's frame [1/m].

        Built from the radii directly (not from hertz), so that the orientation
        found by the finite elements is an independent check.
        """
        c, s = math.cos(self.angle), math.sin(self.angle)
        rot = np.array([[c, -s], [s, c]])
        k1 = np.diag([1 / self.body1.Rx, 1 / self.body1.Ry])
        k2 = np.diag([1 / self.body2.Rx, 1 / self.body2.Ry])
        return k1 + rot @ k2 @ rot.T

    @property
    def symmetric(self) -> bool:
        """True when the planes x = 0 and y = 0 are planes of symmetry (quarter model)."""
        return abs(self.curvature_tensor[0, 1]) <= 1e-12 * abs(self.curvature_tensor).max()

    @property
    def e_star(self) -> float:
        return self.hertz().e_star


def _load_for(body1, body2, angle, a_over_r=A_OVER_R) -> float:
    """The load whose semi-major axis is a_over_r times the smallest radius."""
    r_min = min(abs(r) for b in (body1, body2) for r in (b.Rx, b.Ry) if math.isfinite(r))
    a1 = hertz.contact(body1, body2, load=1.0, angle=angle).a
    return (a_over_r * r_min / a1) ** 3


def equal_steel(alpha: float, radius: float = 0.01) -> Scene:
    """Two identical steel bodies with principal radii R and alpha R (ratio alpha)."""
    if not alpha >= 1:
        raise ValueError(f"alpha must be >= 1, got {alpha!r}")
    b = hertz.Body(radius, alpha * radius, **STEEL)
    return Scene(f"alpha-{alpha:g}", b, b, _load_for(b, b, 0.0))


def steel_on_aluminium() -> Scene:
    """A steel ellipsoid on an aluminium one, principal planes aligned (alpha = 2.38)."""
    b1 = hertz.Body(0.010, 0.020, **STEEL)
    b2 = hertz.Body(0.015, 0.050, **ALUMINIUM)
    return Scene("steel-aluminium", b1, b2, _load_for(b1, b2, 0.0))


def crossed_30deg() -> Scene:
    """Two steel ellipsoids with principal planes 30 degrees apart (major axis at -75 deg)."""
    b = hertz.Body(0.010, 0.020, **STEEL)
    angle = math.radians(30.0)
    return Scene("crossed-30deg", b, b, _load_for(b, b, angle), angle)


def default_scenes() -> list[Scene]:
    """alpha = 1, 3, 10 (steel), steel on aluminium, and principal planes at 30 degrees."""
    return [equal_steel(1), equal_steel(3), equal_steel(10), steel_on_aluminium(),
            crossed_30deg()]


NAMED = {"steel-aluminium": steel_on_aluminium, "crossed-30deg": crossed_30deg}


#: The longest scene name a scene file may give [characters].
MAX_NAME = 100


def scene_from_toml(path) -> Scene:
    """A :class:`Scene` from a ``hertz`` TOML scene file (SI; the format of :mod:`hertz.cli`).

    The file needs ``[body1]`` and ``[body2]``, each with all of Rx, Ry [m]
    (negative concave, "inf" flat), E [Pa] and nu; ``load`` [N] or ``approach``
    [m] (at most one: the target; a graded result brings its own force, so
    neither is needed there: the target load is then NaN), ``angle_deg`` and
    ``name`` (default: the file's stem; one line of at most :data:`MAX_NAME`
    printable characters) are optional; the tangential keys of the format (``tangential``,
    ``mu``, ``direction_deg``) are checked and not used.  The file is read through hertz's
    scene reader, :func:`hertz._scene.read_scene` (at most 1 MiB), one parser for both
    packages.  Unlike the ``hertz``
    command, nothing is filled in from its default scene: a grade against a body
    the file does not describe would be a wrong number.

    Raises
    ------
    ValueError
        Naming the file and the key: unreadable file, a file over 1 MiB, invalid
        TOML, a missing or unknown key, a value that is not a number, a name that is
        not one printable line, bodies without a Hertz contact.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> f = pathlib.Path(tempfile.mkdtemp()) / "ball.toml"
    >>> _ = f.write_text('load = 100.0\\n[body1]\\nRx = 0.01\\nRy = 0.01\\nE = 210e9\\nnu = 0.3\\n'
    ...                  '[body2]\\nRx = "inf"\\nRy = "inf"\\nE = 210e9\\nnu = 0.3\\n')
    >>> s = scene_from_toml(f)
    >>> s.name, s.load, round(s.hertz().a * 1e6, 1)
    ('ball', 100.0, 186.6)
    """
    from pathlib import Path

    from hertz._scene import read_scene

    path = Path(path)
    where = f"scene file {str(path)!r}"
    # every key of the format is read (the tangential ones, which a hertz scene may hold,
    # are checked and not used here); the bodies must be complete
    data = read_scene(path, complete=True)
    bodies = []
    for name in ("body1", "body2"):
        try:
            bodies.append(hertz.Body(**data[name]))
        except (TypeError, ValueError) as exc:
            raise ValueError(f"{where}: [{name}]: {exc}") from None
    angle = math.radians(data.get("angle_deg", 0.0))
    try:
        if "approach" in data:
            load = hertz.contact(*bodies, angle=angle, approach=data["approach"]).load
        else:
            load = data.get("load", 1.0)
            hertz.contact(*bodies, load=load, angle=angle)  # can these bodies touch at a point?
            if "load" not in data:
                load = math.nan
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{where}: {exc}") from None
    name = data.get("name", path.stem)
    if not isinstance(name, str):
        raise ValueError(f"{where}: name must be a string, got {type(name).__name__}")
    if not name.strip() or len(name) > MAX_NAME or not name.isprintable():
        # the name goes into file names, reports and the heading line of a deck: a line
        # break there would start a keyword line of its own
        raise ValueError(f"{where}: name must be one line of at most {MAX_NAME} printable "
                         f"characters, got {name[:MAX_NAME]!r}")
    return Scene(name, bodies[0], bodies[1], load, angle)
