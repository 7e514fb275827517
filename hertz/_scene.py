"""The TOML scene format: one reader for every program that takes a scene file.

A scene file describes two bodies pressed together, in SI units::

    name = "bearing ball on inner race"
    load = 1500.0          # N (or: approach = ..., in m; or, for a line contact of
                           # parallel cylinders: load_per_length = ..., in N/m)
    angle_deg = 0.0        # degrees between the bodies' x axes

    [body1]
    Rx = 6e-3              # m; > 0 convex, < 0 concave, "inf" flat
    Ry = 6e-3
    E = 210e9              # Pa
    nu = 0.3

    [body2]
    ...

Every key is listed in :data:`SCENE_KEYS` and :data:`BODY_KEYS` (with its unit).
:func:`read_scene` reads a file (:func:`parse_scene` its text) into a dict of the
keys the file gives: numbers as Python floats, ``name`` a str, ``body1`` and
``body2`` dicts of floats.  What is missing stays missing: the ``hertz``
command fills it from its default scene, ``fem_validation`` asks for complete
bodies (``complete=True``).  Every error is a :class:`SceneError` (a ValueError)
of one line that names the file and the key.

Users: :mod:`hertz.cli` (``hertz --scene``) and ``fem_validation.scenes``.
This module imports nothing of hertz; ``tomllib`` is imported when a file is read.
"""

from __future__ import annotations

import math
import os

__all__ = ["BODY_KEYS", "MAX_SCENE_BYTES", "SCENE_KEYS", "SceneError", "parse_scene",
           "read_scene"]

#: The top-level keys of a scene file: (key, unit, meaning).
SCENE_KEYS = (
    ("name", "", "label printed with the results (default: the file's path)"),
    ("load", "N", "normal force, >= 0 (0: no contact patch, no stresses)"),
    ("approach", "m", "instead of load: the approach of the bodies (the load is computed)"),
    ("load_per_length", "N/m", "instead of load: a line contact (two parallel cylinders, "
     "Rx = R, Ry = inf, or a cylinder on a plane), normal force per unit length, >= 0"),
    ("angle_deg", "deg", "angle between the bodies' x axes"),
    ("tangential", "N", "tangential force, <= mu * load, along direction_deg"),
    ("mu", "-", "coefficient of friction, > 0 (tangential and mu: both or neither)"),
    ("direction_deg", "deg", "angle of the tangential force from the contact ellipse's major "
     "axis (default 0; with tangential)"),
)
#: The keys of the [body1] and [body2] tables: (key, unit, meaning).
BODY_KEYS = (
    ("Rx", "m", "principal radius along the body's x axis: > 0 convex, < 0 concave, inf flat"),
    ("Ry", "m", "principal radius along the body's y axis (same signs)"),
    ("E", "Pa", "Young's modulus, > 0"),
    ("nu", "-", "Poisson's ratio, in (-1, 0.5]"),
)
#: The tables of the two bodies.
BODIES = ("body1", "body2")
#: A scene file is a few lines; refusing big ones keeps ``--scene /dev/zero`` from
#: filling the memory.
MAX_SCENE_BYTES = 1 << 20

_NUMBER_KEYS = tuple(key for key, _, _ in SCENE_KEYS if key != "name")
_BODY_NAMES = tuple(key for key, _, _ in BODY_KEYS)


class SceneError(ValueError):
    """A scene file that cannot be read or used; the message is one line naming the
    file and, where one is at fault, the key.

    Attributes
    ----------
    source : str
        The file.
    reason : str or None
        The message without the file (``"body1.Rx must be a number, got 'wide'"``), for
        a program that names the file otherwise; None where the file as a whole is at
        fault (unreadable, too large, not TOML): the message is then all there is.
    key : str or None
        The key whose value is refused (``"body1.Rx"``, ``"name"``); None for the file's
        shape (an unknown or missing key or table, both load and approach).
    """

    def __init__(self, source: str, reason: str | None = None, key: str | None = None,
                 message: str | None = None):
        super().__init__(message if reason is None else f"scene file {source!r}: {reason}")
        self.source, self.reason, self.key = source, reason, key

    def __reduce__(self):  # (pickled across processes: the same fields again)
        message = str(self) if self.reason is None else None
        return type(self), (self.source, self.reason, self.key, message)


def read_scene(path, *, keys=None, complete: bool = False) -> dict:
    """The scene a TOML scene file gives: ``{key: value}`` of the keys it holds.

    Parameters
    ----------
    path : str or os.PathLike
        The file; read at most :data:`MAX_SCENE_BYTES` (1 MiB) far, decoded as UTF-8
        (a byte-order mark is dropped).
    keys : iterable of str, optional
        The top-level keys (besides the ``[body1]`` and ``[body2]`` tables) that the
        caller takes; any other is an error listing these.  Default: all of
        :data:`SCENE_KEYS`.
    complete : bool
        Whether both bodies must be given with every one of Rx, Ry, E and nu (nothing
        filled in from a default).

    Returns
    -------
    dict
        In the file's order: ``name`` (str), the numbers (float; a string that spells
        one, such as ``"inf"``, is read as it), ``body1`` and ``body2``
        (dicts of floats).  At most one of ``load``, ``approach`` and
        ``load_per_length`` (a line contact: the bodies are parallel cylinders or planes).

    Raises
    ------
    SceneError
        One line naming the file and, where one is at fault, the key: a file that
        cannot be read or is over 1 MiB, invalid TOML (or not UTF-8), nesting too deep,
        an unknown or (``complete``) missing key, a value that is not a number (or a
        string for ``name``), more than one of ``load``, ``approach`` and
        ``load_per_length``.
    """
    source = os.fspath(path)
    where = f"scene file {source!r}"
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_SCENE_BYTES + 1)
    except OSError as exc:
        raise SceneError(source, message=f"cannot read {where}: {exc.strerror or exc}"
                         ) from None
    if len(data) > MAX_SCENE_BYTES:
        raise SceneError(source, message=f"{where} is larger than {MAX_SCENE_BYTES} bytes (a "
                         "scene is a few lines)")
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise SceneError(source, message=f"{where} is not valid TOML: {exc}") from None
    return parse_scene(text, source, keys=keys, complete=complete)


def parse_scene(text: str, source: str, *, keys=None, complete: bool = False) -> dict:
    """The scene of the TOML ``text`` of the scene file ``source`` (the path, for the
    messages); see :func:`read_scene` for ``keys``, ``complete``, the result and the
    errors.

    Examples
    --------
    >>> from hertz._scene import parse_scene
    >>> parse_scene('load = 100\\n[body1]\\nRx = "inf"\\nnu = 0.3\\n', "s.toml")
    {'load': 100.0, 'body1': {'Rx': inf, 'nu': 0.3}}
    >>> try:
    ...     parse_scene("[body1]\\nRx = 0.01\\n", "s.toml", complete=True)
    ... except ValueError as exc:
    ...     print(exc)
    scene file 's.toml': [body1] needs exactly Rx, Ry, E, nu; missing Ry, E, nu
    """
    import tomllib

    where = f"scene file {source!r}"
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(source, message=f"{where} is not valid TOML: {exc}") from None
    except RecursionError:
        raise SceneError(source, message=f"{where} is nested too deeply to read") from None
    except ValueError as exc:  # an integer of more than 4300 digits
        raise SceneError(source, message=f"{where} cannot be read: {exc}") from None
    allowed = ("name", *_NUMBER_KEYS) if keys is None else tuple(keys)
    scene = {}
    for key, value in data.items():
        if key in BODIES:
            scene[key] = _body(value, key, source, complete)
        elif key == "name" and key in allowed:
            if not isinstance(value, str):
                raise SceneError(source, f"name must be a string, got {_kind(value)}", key)
            scene[key] = value
        elif key in _NUMBER_KEYS and key in allowed:
            scene[key] = _number(value, key, source)
        else:
            raise SceneError(source, f"unknown key {_show(key)} (allowed: "
                                     f"{', '.join(allowed)}, [body1], [body2])")
    if complete:
        for key in BODIES:
            if key not in scene:
                raise SceneError(source, f"the [{key}] table is missing")
    targets = [key for key in ("load", "approach", "load_per_length") if key in scene]
    if targets == ["load", "approach"]:
        raise SceneError(source, "give one of load and approach, not both (a scene has at "
                                 "most one target: load [N] or approach [m])")
    if len(targets) > 1:
        raise SceneError(source, f"give one of load, approach and load_per_length, not "
                                 f"{' and '.join(targets)} (a scene has at most one target: "
                                 f"load [N], approach [m] or, for a line contact, "
                                 f"load_per_length [N/m])")
    return scene


def _body(value, key: str, source: str, complete: bool) -> dict:
    """A [body1] or [body2] table: its numbers."""
    if not isinstance(value, dict):
        raise SceneError(source, f"[{key}] must be a table, got {_kind(value)}")
    unknown = sorted(set(value) - set(_BODY_NAMES))
    missing = [k for k in _BODY_NAMES if k not in value] if complete else []
    if complete and (unknown or missing):
        raise SceneError(source, f"[{key}] needs exactly {', '.join(_BODY_NAMES)}"
                         + (f"; missing {', '.join(missing)}" if missing else "")
                         + (f"; unknown {', '.join(_plain(k) for k in unknown)}"
                            if unknown else ""))
    if unknown:
        raise SceneError(source, f"unknown key(s) in [{key}]: "
                         f"{', '.join(_show(k) for k in unknown)} "
                         f"(allowed: {', '.join(_BODY_NAMES)})")
    return {k: _number(v, f"{key}.{k}", source) for k, v in value.items()}


def _number(value, name: str, source: str) -> float:
    """A number of a scene file: an int or float, or a string that spells one ("inf",
    "1e-3").  A NaN passes: the caller's checks of the value (hertz.Body, hertz.contact)
    name it with its meaning ("a nonzero radius", "a finite value >= 0")."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise SceneError(source, f"{name} must be a number, got {_kind(value)}: "
                                 f"{_show(value)}", name)
    if isinstance(value, str):
        try:
            x = float(value)
        except ValueError:
            raise SceneError(source, f"{name} must be a number, got {_show(value)}",
                             name) from None
    else:
        try:
            x = float(value)
        except OverflowError:  # an integer beyond the largest double
            digits = math.floor(math.log10(abs(value))) + 1
            raise SceneError(source, f"{name} must be a number a double can hold "
                             f"(|x| < 1.8e308), got an integer of {digits} digits", name
                             ) from None
    return x


def _plain(key: str) -> str:
    """A key as it is where it is printable, else its repr (one line)."""
    return key if key.isprintable() and len(key) <= 80 else _show(key)


def _kind(value) -> str:
    return {list: "an array", dict: "a table"}.get(type(value), type(value).__name__)


def _show(value, limit: int = 80) -> str:
    """repr(value), shortened; never an exception (deep nesting, huge integers)."""
    try:
        text = repr(value)
    except (RecursionError, ValueError):
        text = f"<{_kind(value)}>"
    return text if len(text) <= limit else text[:limit - 3] + "..."
