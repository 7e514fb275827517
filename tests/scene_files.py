"""Scene files the tests write as a user writes them (TOML): one template for the steel
ball on a steel half-space that most command-line tests grade or refuse."""


def ball_on_plane(name: str, load: float, radius: float = 0.01) -> str:
    """The scene file of a steel ball of ``radius`` [m] pressed on a steel half-space
    with ``load`` [N] (E 210 GPa, nu 0.3), named ``name``."""
    return f"""name = "{name}"
load = {load!r}
[body1]
Rx = {radius!r}
Ry = {radius!r}
E = 210e9
nu = 0.3
[body2]
Rx = "inf"
Ry = "inf"
E = 210e9
nu = 0.3
"""
