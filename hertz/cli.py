"""The ``hertz`` command: solve one Hertz point contact and print it.

With no arguments it solves a built-in scene: a 12 mm bearing ball on the
inner race of a deep-groove ball bearing (groove radius 6.2 mm, race radius
40 mm in the rolling direction), steel on steel, 1500 N.  Options or a TOML
scene file change any of it::

    hertz --load 800 --json
    hertz --print-scene my_scene.toml        # the default scene, to edit
    hertz --scene my_scene.toml --angle-deg 30
    hertz --yield-strength 1.5e9 --plot stresses.png
    hertz --tangential 200 --mu 0.3          # Cattaneo-Mindlin partial slip, fretting
    hertz --tangential 200 --mu 0.3 --direction 45   # the force 45 degrees off the major axis

``hertz --help`` ends with the scene-file format (every key, its unit and
default) and the default scene; both are generated from ``SCENE_KEYS``,
``BODY_KEYS`` (the format, in ``hertz._scene``, which reads scene files for
``--scene``) and ``DEFAULT_SCENE`` below, which is what ``--print-scene`` writes.

Errors (bad values, a missing or oversized file, no Hertz contact, output
that cannot be written) print one line on stderr and exit with status 2.
A contact too large for Hertz's theory (a > ``hertz.A_OVER_R_LIMIT`` times the
smallest radius: often a Young's modulus in GPa) adds one warning line on stderr
after the output; the status stays 0.  Negative numbers go as written
(``--r2x -6.6e-3``).  ``--json`` prints strict JSON: a value that overflows a
double is ``null``; its keys are listed in docs/howto/command-line.md.
"""

from __future__ import annotations

import argparse
import io
import json
import math
import os
import re
import sys
import warnings

import numpy as np

from . import __version__
from ._contact import Body, HertzValidityWarning, contact
from ._scene import BODY_KEYS, SCENE_KEYS, SceneError, read_scene

DEFAULT_SCENE = {
    "name": "bearing ball on inner race (default scene)",
    "body1": {"Rx": 6e-3, "Ry": 6e-3, "E": 210e9, "nu": 0.3},
    "body2": {"Rx": -6.2e-3, "Ry": 40e-3, "E": 210e9, "nu": 0.3},
    "load": 1500.0,
    "angle_deg": 0.0,
}

#: The keys of a [body1] or [body2] table (the format: hertz._scene).
_BODY_KEYS = tuple(key for key, _, _ in BODY_KEYS)
#: Options that change the scene (the others only add output).
_SCENE_OPTIONS = ("r1x", "r1y", "e1", "nu1", "r2x", "r2y", "e2", "nu2", "load", "approach",
                  "angle_deg", "tangential", "mu", "direction_deg")
#: The scene keys of the tangential force, set together or not at all.
_TANGENTIAL_KEYS = ("tangential", "mu")
_PLOT_EXTRA = "pip install 'hertz-contact[plot]'"


#: A value on the command line, not an option, where it starts with '-' and a digit, '.' and a
#: digit, "inf" or "nan": every negative number as written (-6.6e-3, -.5, -1E+3, -inf,
#: -Infinity), and typos of one (-5e) that the option's own check then names. argparse's
#: own pattern takes only -12 and -1.5, and says "expected one argument" for the rest.
_NEGATIVE_NUMBER = re.compile(r"^-(?:\.?\d|inf|nan)", re.IGNORECASE)


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors and negative numbers as written: ``--r2x -6.6e-3``
    and ``--r2x -inf`` give the option its value (argparse would take them for options
    and say "expected one argument"); the option's own check then judges it."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = _NEGATIVE_NUMBER

    def error(self, message):  # one line, status 2
        raise _UsageError(message)

    def print_help(self, file=None):  # a help that cannot be written is an error too
        _write(self.format_help().rstrip("\n"), file)


class _UsageError(Exception):
    pass


class _ReaderLeftError(Exception):
    """The reader of stdout went away (``hertz | head``): stop quietly."""


def _number(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None


def _parser() -> argparse.ArgumentParser:
    p = _Parser(prog="hertz", description="Hertz point contact of two elastic bodies, or "
                "a line contact of parallel cylinders (a --scene with load_per_length) "
                "(SI units; radii negative for concave, inf for flat).",
                epilog=_help_epilog(), formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", metavar="FILE", help="TOML scene file (format below; options "
                   "override it)")
    p.add_argument("--print-scene", nargs="?", const="-", metavar="FILE",
                   help="write the scene (the default one, changed by any options and "
                        "--scene given) as a TOML file to start from, to FILE (never over an "
                        "existing file) or to stdout (no FILE, or -), and exit")
    for i in (1, 2):
        g = p.add_argument_group(f"body {i}")
        for axis in "xy":
            g.add_argument(f"--r{i}{axis}", type=_number, metavar="M",
                           help=f"body {i} radius along its {axis} axis [m]")
        g.add_argument(f"--e{i}", type=_number, metavar="PA", help=f"body {i} Young's modulus [Pa]")
        g.add_argument(f"--nu{i}", type=_number, metavar="NU", help=f"body {i} Poisson's ratio [-]")
    load = p.add_mutually_exclusive_group()
    load.add_argument("--load", type=_number, metavar="N", help="normal force [N], >= 0")
    load.add_argument("--approach", type=_number, metavar="M",
                      help="approach of the bodies [m] (the load is computed)")
    p.add_argument("--angle-deg", type=_number, metavar="DEG",
                   help="angle between the bodies' x axes [degrees]")
    p.add_argument("--tangential", type=_number, metavar="N",
                   help="tangential force [N] along --direction (default: the contact "
                        "ellipse's major axis), rising from 0 at constant load (with --mu): "
                        "adds the no-slip tangential stiffness, the stick zone, the "
                        "displacement, the tangent stiffness, whether it slides, and the "
                        "energy of a fretting cycle between -N and N (Cattaneo-Mindlin, "
                        "Mindlin-Deresiewicz)")
    p.add_argument("--mu", type=_number, metavar="MU",
                   help="coefficient of friction [-], > 0 (with --tangential)")
    p.add_argument("--direction", dest="direction_deg", type=_number, metavar="DEG",
                   help="angle of the tangential force from the contact ellipse's major axis "
                        "[degrees], default 0 (with --tangential)")
    p.add_argument("--yield-strength", type=_number, metavar="PA",
                   help="yield strength of both bodies [Pa]: adds the load at which each first "
                        "yields (von Mises and Tresca)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="draw the von Mises stress below the contact into FILE, in the format "
                        "its suffix names (.png, .pdf, .svg, ...; needs matplotlib: "
                        f"{_PLOT_EXTRA})")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of a table")
    p.add_argument("--version", action="version",
                   version=f"hertz {__version__} (distribution hertz-contact)")
    return p


# --- the scene file: format, reading, writing --------------------------------------------

def _help_epilog() -> str:
    """The scene-file format and the default scene, for the end of ``hertz --help``."""
    def rows(keys, indent):
        named = [(f"{key} [{unit}]" if unit else key, meaning) for key, unit, meaning in keys]
        width = max(len(key) for key, _ in named) + 2
        for key, meaning in named:
            yield f"{indent}{key:<{width}}{meaning}"

    lines = ["scene file (--scene FILE; TOML, SI units):", *rows(SCENE_KEYS, "  "),
             "  [body1], [body2]: one table per body, with", *rows(BODY_KEYS, "    "),
             "  Every key is optional: a missing one keeps the default scene's value (give",
             "  load or approach, not both); options on the command line override the file.",
             "  Numbers are TOML integers or floats (inf, -inf), or strings that spell one",
             "  (\"inf\", \"1e-3\"). Names the output's encoding cannot show are printed with",
             "  \\x.., \\u.. escapes.",
             "",
             "default scene (hertz --print-scene FILE writes it, to edit):"]
    lines += ["  " + line if line else "" for line in scene_toml(DEFAULT_SCENE).splitlines()]
    return "\n".join(lines)


def scene_toml(scene: dict, encoding: str | None = None) -> str:
    """The scene as a TOML scene file that ``hertz --scene`` reads back to the same scene.

    Numbers are written in their shortest form that reads back to the same double;
    characters of the name that ``encoding`` cannot encode are written as TOML escapes.
    """
    load = ("approach", "m") if "approach" in scene else ("load", "N")
    top = [(load[0], _toml_number(scene[load[0]]),
            f"{load[1]}" + ("  (or: approach = ..., in m)" if load[0] == "load" else
                            "  (or: load = ..., in N)")),
           ("angle_deg", _toml_number(scene.get("angle_deg", 0.0)),
            "degrees between the bodies' x axes")]
    comments = {"Rx": "m; > 0 convex, < 0 concave, inf flat", "Ry": "m", "E": "Pa", "nu": "-"}
    lines = ["# hertz scene file: hertz --scene FILE reads it; hertz --help lists every key",
             f"name = {_toml_string(scene['name'], encoding)}"]
    if "tangential" in scene:
        top += [("tangential", _toml_number(scene["tangential"]),
                 "N along direction_deg (0 <= it <= mu * load)"),
                ("mu", _toml_number(scene["mu"]), "-, coefficient of friction"),
                ("direction_deg", _toml_number(scene.get("direction_deg", 0.0)),
                 "degrees from the contact ellipse's major axis")]
    lines += _aligned(top)
    if "tangential" not in scene:
        lines.append("# tangential = 100.0  # N along the major axis, with mu = 0.3: partial "
                     "slip and fretting")
    for name in ("body1", "body2"):
        lines += ["", f"[{name}]"]
        lines += _aligned([(key, _toml_number(scene[name][key]), comments[key])
                           for key in _BODY_KEYS])
    return "\n".join(lines) + "\n"


def _aligned(rows) -> list[str]:
    width = max(len(f"{key} = {value}") for key, value, _ in rows) + 2
    return [f"{f'{key} = {value}':<{width}}# {comment}" for key, value, comment in rows]


def _toml_number(value) -> str:
    """The shortest TOML float that reads back to ``float(value)`` exactly."""
    x = float(value)
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    text = repr(x)
    for digits in range(1, 18):  # %g is shorter for large and small magnitudes (2.1e+11)
        short = f"{x:.{digits}g}"
        if float(short) == x:
            text = min(text, short, key=len)
            break
    return text if any(c in text for c in ".e") else text + ".0"  # a float, not an integer


def _toml_string(text: str, encoding: str | None = None) -> str:
    """A TOML basic string; control characters and what ``encoding`` cannot hold escaped."""
    out = []
    for ch in text:
        code = ord(ch)
        if 0xD800 <= code <= 0xDFFF:  # a lone surrogate (undecodable bytes of a path)
            ch, code = "\ufffd", 0xFFFD
        if ch in '"\\':
            out.append("\\" + ch)
        elif code < 0x20 or code == 0x7F or not _encodable(ch, encoding):
            out.append(f"\\u{code:04X}" if code <= 0xFFFF else f"\\U{code:08X}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _encodable(ch: str, encoding: str | None) -> bool:
    if encoding is None:
        return True
    try:
        ch.encode(encoding)
    except UnicodeEncodeError:
        return False
    except LookupError:
        return True
    return True


def _read_scene(path: str) -> dict:
    """The scene of the file ``path`` (hertz._scene reads and checks it), on top of the
    default scene: a key the file leaves out keeps the default's value."""
    try:
        given = read_scene(path)
    except SceneError as exc:
        if exc.reason is None:  # the file as a whole: the message names it
            message = str(exc)
        elif exc.key not in (None, "name"):  # a number: worded as for the same option's
            message = exc.reason
        else:
            message = f"scene file: {exc.reason}"
        raise _UsageError(message) from None
    merged = _copy(DEFAULT_SCENE)
    merged["name"] = path
    for key, value in given.items():
        if key in ("body1", "body2"):
            merged[key].update(value)
        else:
            merged[key] = value
    if "approach" in given or "load_per_length" in given:
        merged.pop("load")
    return merged


def _copy(scene: dict) -> dict:
    return {k: (dict(v) if isinstance(v, dict) else v) for k, v in scene.items()}


def _printable(text: str) -> str:
    """``text`` with control and other non-printing characters written as escapes
    (``\\x1b``), so that a scene name cannot move the cursor or recolour a terminal."""
    return "".join(ch if ch.isprintable() else ch.encode("unicode_escape").decode("ascii")
                   for ch in text)


def _scene(args) -> dict:
    scene = _read_scene(args.scene) if args.scene else _copy(DEFAULT_SCENE)
    for i in (1, 2):
        for key, opt in zip(_BODY_KEYS, (f"r{i}x", f"r{i}y", f"e{i}", f"nu{i}"), strict=True):
            value = getattr(args, opt)
            if value is not None:
                scene[f"body{i}"][key] = value
    if args.load is not None:
        scene["load"] = args.load
        scene.pop("approach", None)
        scene.pop("load_per_length", None)
    if args.approach is not None:
        scene["approach"] = args.approach
        scene.pop("load", None)
        scene.pop("load_per_length", None)
    if args.angle_deg is not None:
        scene["angle_deg"] = args.angle_deg
    for key in (*_TANGENTIAL_KEYS, "direction_deg"):
        if getattr(args, key) is not None:
            scene[key] = getattr(args, key)
    given = [key for key in _TANGENTIAL_KEYS if key in scene]
    if len(given) == 1:
        missing = "mu" if given == ["tangential"] else "tangential"
        raise _UsageError(f"--{given[0]} needs --{missing} (scene key {missing}): the "
                          "tangential force and the coefficient of friction go together")
    if "direction_deg" in scene and not given:
        raise _UsageError("--direction needs --tangential and --mu (scene keys tangential, "
                          "mu): it is the direction of the tangential force")
    if not args.scene and any(getattr(args, opt) is not None for opt in _SCENE_OPTIONS):
        scene["name"] = "custom scene"
    return scene


# --- solving -------------------------------------------------------------------------------

def _body(spec: dict, name: str) -> Body:
    values = {key: float(spec[key]) for key in _BODY_KEYS}  # numbers: read_scene, argparse
    try:
        return Body(**values)
    except (TypeError, ValueError) as exc:
        raise _UsageError(f"{name}: {exc}") from None


def _solve(scene: dict):
    """(body1, body2, the contact, the warnings to print): the warnings are the messages
    of the HertzValidityWarning of the contact, if any (a contact too large for Hertz's
    theory, or a unit mistake), printed by the caller once the output is written."""
    body1, body2 = _body(scene["body1"], "body1"), _body(scene["body2"], "body2")
    degrees = scene.get("angle_deg", 0.0)
    if not math.isfinite(degrees):
        raise _UsageError(f"--angle-deg (scene key angle_deg) must be a finite angle in "
                          f"degrees, got {degrees!r}")
    kwargs = {"approach": scene["approach"]} if "approach" in scene else {"load": scene["load"]}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", HertzValidityWarning)
        try:
            c = contact(body1, body2, angle=math.radians(degrees), **kwargs)
        except TypeError as exc:
            raise _UsageError(str(exc)) from None
        except ValueError as exc:
            if not str(exc).startswith("the bodies make a line contact"):
                raise
            given = "an approach [m]" if "approach" in kwargs else "a load [N]"
            raise _UsageError(f"{str(exc).split(';')[0]}: {given} is a point contact's; "
                              f"give the force per unit length as load_per_length [N/m] in a "
                              f"--scene file (without --load or --approach)") from None
    notes = []
    for w in caught:
        if issubclass(w.category, HertzValidityWarning):
            notes.append(str(w.message))
        else:  # not ours: shown as it would have been
            warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    return body1, body2, c, notes


_MAXIMA = ("tau_max", "z_tau_max", "von_mises", "z_von_mises", "tau_orthogonal",
           "y_tau_orthogonal", "z_tau_orthogonal", "tensile", "x_tensile", "y_tensile")
_STRESSES = ("tau_max", "von_mises", "tau_orthogonal", "tensile")


def _finite(value: float, what: str):
    """The value, or None where it overflows a double; a NaN is an error, never printed."""
    value = float(value)
    if math.isnan(value):
        raise _UsageError(f"{what} is not a number for this scene (a defect of hertz: "
                          "please report the command line)")
    return value if math.isfinite(value) else None


def _stresses(scene, body1, body2, c, yield_strength) -> dict:
    """{"body1": {...}, "body2": {...}}: the subsurface maxima and first-yield loads.

    Without a contact patch (zero load) the stresses are 0 and their places None.  The
    first-yield load does not depend on the load (P_y = P (p0_y / p0)**3 with
    p0 ~ P**(1/3)); where the contact's own load or p0 is 0 or beyond a double, it is
    scaled from a 1 N contact of the same bodies.
    """
    scaled_from = c
    if yield_strength is not None and not (0 < c.load < math.inf and 0 < c.p0 < math.inf):
        scaled_from = contact(body1, body2, load=1.0,
                              angle=math.radians(scene.get("angle_deg", 0.0)))
    out = {}
    for body in (1, 2):
        if c.a > 0:
            maxima = c.subsurface(body)
            row = {k: _finite(getattr(maxima, k), f"body {body}'s {k}") for k in _MAXIMA}
        else:
            row = {k: (0.0 if k in _STRESSES else None) for k in _MAXIMA}
        if yield_strength is not None:
            for criterion in ("von_mises", "tresca"):
                load = scaled_from.first_yield_load(yield_strength, body=body,
                                                    criterion=criterion)
                row[f"first_yield_load_{criterion}"] = _finite(
                    load, f"body {body}'s first-yield load ({criterion})")
        out[f"body{body}"] = row
    return out


_CONTACT_FIELDS = ("a", "b", "p0", "delta", "load", "ellipticity", "alpha", "m", "K", "E",
                   "e_star", "rho_x", "rho_y", "rho_sum", "major_axis_angle", "p_mean", "area",
                   "stiffness")
#: The names of the output (table and --json) for Contact's fields where they differ: the
#: elliptic integrals K(m), E(m) are ellipk, ellipe (as scipy.special names them), so that
#: E is never read as Young's modulus (the scene's E).
_OUTPUT_NAMES = {"K": "ellipk", "E": "ellipe"}
#: Old keys of --json, still written (same values) for one release beside their new names
#: and listed in the output's "deprecated_keys" as {old: new}; then removed.
_DEPRECATED_KEYS = dict(_OUTPUT_NAMES)


def _fields(c) -> dict:
    return {_OUTPUT_NAMES.get(k, k): _finite(getattr(c, k), k) for k in _CONTACT_FIELDS}


def _tangential(scene, c) -> dict | None:
    """The tangential results of the scene's force, mu and direction (None without them):
    the no-slip stiffness along the force, Cattaneo-Mindlin's stick ellipse, displacement
    (along the force and across it) and tangent stiffness, whether it slides
    (force = mu P), and the energy of a fretting cycle between -force and force
    (Mindlin-Deresiewicz)."""
    if "tangential" not in scene:
        return None
    force, mu = scene["tangential"], scene["mu"]
    degrees = scene.get("direction_deg", 0.0)
    if not math.isfinite(degrees):
        raise _UsageError(f"--direction must be a finite angle in degrees (scene key "
                          f"direction_deg), got {degrees!r}")
    # reduced to [-180, 180] degrees first, exactly (IEEE remainder is exact): the radians
    # of a huge angle in degrees would carry its rounding into the kernel's reduction
    direction = math.radians(math.remainder(degrees, 360.0))
    if not (0 < mu < math.inf):
        raise _UsageError(f"mu must be a positive, finite coefficient of friction, got {mu!r}")
    if not (0 <= force < math.inf):
        raise _UsageError(f"tangential must be a finite force >= 0 in N, got {force!r}")
    load = float(c.load)
    if not (0 < load < math.inf):
        why = "zero: the contact carries no tangential force" if load == 0 else "beyond a double"
        raise _UsageError(f"a tangential force needs a normal load > 0 and finite; the load is "
                          f"{why}")
    limit = mu * load
    if force > limit:
        raise _UsageError(f"tangential = {force!r} N is above mu * load = {limit!r} N: the "
                          "contact slides as a whole (partial slip needs tangential <= mu * "
                          "load)")
    t = c.tangential(force, mu, direction)
    energy = c.fretting(force, mu, direction).energy
    # direction: rad from the major axis, as the API takes it
    out = {"force": force, "mu": mu, "direction": direction, "direction_deg": degrees}
    for key, value in (("no_slip_stiffness", t.no_slip_stiffness), ("stick_a", t.stick_a),
                       ("stick_b", t.stick_b), ("displacement", t.displacement),
                       ("displacement_transverse", t.displacement_transverse),
                       ("stiffness", t.stiffness), ("fretting_energy", energy)):
        out[key] = _finite(value, f"the tangential {key}")
    out["sliding"] = bool(t.sliding)
    return out


# --- output --------------------------------------------------------------------------------

_PREFIXES = [(1e9, "G"), (1e6, "M"), (1e3, "k"), (1.0, ""), (1e-3, "m"), (1e-6, "u"), (1e-9, "n")]


def _si(value: float | None, unit: str) -> str:
    if value is None:
        return "overflow"
    if value == 0 or not math.isfinite(value):
        return f"{value:g} {unit}"
    for scale, prefix in _PREFIXES:
        if abs(value) >= scale:
            return f"{value / scale:.6g} {prefix}{unit}"
    return f"{value:.6g} {unit}"


def _radius_text(r: float) -> str:
    return "flat" if math.isinf(r) else _si(r, "m")


def _g(value: float | None, unit: str = "") -> str:
    return "overflow" if value is None else f"{value:.6g}{unit}"


def _table(scene, body1, body2, f) -> str:
    angle = None if f["major_axis_angle"] is None else math.degrees(f["major_axis_angle"])
    rows = [
        ("load P", _si(f["load"], "N")),
        ("semi-major axis a", _si(f["a"], "m")),
        ("semi-minor axis b", _si(f["b"], "m")),
        ("ellipticity a/b", _g(f["ellipticity"])),
        ("curvature ratio alpha", _g(f["alpha"])),
        ("peak pressure p0", _si(f["p0"], "Pa")),
        ("mean pressure", _si(f["p_mean"], "Pa")),
        ("contact area", _g(f["area"], " m^2")),
        ("approach delta", _si(f["delta"], "m")),
        ("stiffness dP/d(delta)", _si(f["stiffness"], "N/m")),
        ("major axis angle", _g(angle, " deg (from body 1's x axis)")),
        ("E* (reduced modulus)", _si(f["e_star"], "Pa")),
        ("rho_x, rho_y", f"{_g(f['rho_x'])}, {_g(f['rho_y'])} 1/m"),
        ("elliptic m, K(m), E(m)", f"{_g(f['m'])}, {_g(f['ellipk'])}, {_g(f['ellipe'])}"),
    ]
    lines = [f"Hertz point contact: {_printable(scene['name'])}"]
    for i, b in ((1, body1), (2, body2)):
        lines.append(f"  body {i}: Rx = {_radius_text(b.Rx)}, Ry = {_radius_text(b.Ry)}, "
                     f"E = {_si(b.E, 'Pa')}, nu = {b.nu:g}")
    lines.append(f"  angle between x axes: {scene.get('angle_deg', 0.0):g} deg")
    width = max(len(name) for name, _ in rows)
    lines.extend(f"  {name:<{width}}  {value}" for name, value in rows)
    if f["a"] == 0:
        lines.append("  zero load: no contact patch; a/b, alpha and the axes' angle are those "
                     "of the patch at any load")
    return "\n".join(lines)


def _json(scene, fields, stresses, tangential, notes) -> str:
    extra = {} if tangential is None else {"tangential": tangential}
    old = {key: fields[new] for key, new in _DEPRECATED_KEYS.items()}
    return json.dumps({"scene": scene["name"], **fields, "stresses": stresses, **extra,
                       "warnings": notes, **old, "deprecated_keys": _DEPRECATED_KEYS},
                      allow_nan=False)


def _tangential_table(t) -> list[str]:
    rows = [("no-slip stiffness along Q", _si(t["no_slip_stiffness"], "N/m")),
            ("stick zone semi-axes", f"{_si(t['stick_a'], 'm')}, {_si(t['stick_b'], 'm')}"),
            ("displacement along Q", _si(t["displacement"], "m"))]
    if t["direction_deg"] != 0:
        rows.append(("displacement across Q", _si(t["displacement_transverse"], "m")
                     + " (90 deg counter-clockwise from Q)"))
    rows += [("tangent stiffness dQ/d(disp)", _si(t["stiffness"], "N/m")),
            ("sliding", "yes: Q = mu P, the whole contact slips" if t["sliding"] else
             "no: partial slip"),
            ("fretting loop energy", f"{_si(t['fretting_energy'], 'J')} per cycle between -Q "
             "and Q")]
    width = max(len(name) for name, _ in rows) + 2
    where = ("along the major axis" if t["direction_deg"] == 0 else
             f"at {t['direction_deg']:g} deg from the major axis")
    return [f"  tangential force Q = {_si(t['force'], 'N')} {where}, "
            f"mu = {t['mu']:g} (Cattaneo-Mindlin):",
            *(f"    {name:<{width}}{value}" for name, value in rows)]


def _stress_table(stresses, yield_strength, zero_load: bool) -> list[str]:
    labels = [("largest shear stress tau1", "tau_max", "z_tau_max", "depth"),
              ("largest von Mises stress", "von_mises", "z_von_mises", "depth"),
              ("orthogonal shear |tau_yz|", "tau_orthogonal", "z_tau_orthogonal", "depth"),
              ("surface tension at edge", "tensile", None, None)]
    width = max(len(label) for label, *_ in labels) + 2
    if zero_load:
        lines = ["  stresses below the contact: none (zero load)"]
    else:
        lines = ["  stresses below the contact (frictionless; each body with its own nu):"]
    for body in (1, 2):
        row = stresses[f"body{body}"]
        if not zero_load or yield_strength is not None:
            lines.append(f"    body {body}:")
        for label, key, where, kind in labels if not zero_load else ():
            at = f" at {kind} {_si(row[where], 'm')}" if where and row[where] is not None else ""
            if key == "tau_orthogonal" and row["y_tau_orthogonal"] is not None:
                at += f", y = {_si(row['y_tau_orthogonal'], 'm')}"
            if key == "tensile" and row["x_tensile"] is not None:
                at = (f" at x = {_si(row['x_tensile'], 'm')}, "
                      f"y = {_si(row['y_tensile'], 'm')}")
            lines.append(f"      {label:<{width}}{_si(row[key], 'Pa')}{at}")
        if yield_strength is not None:
            for criterion, name in (("von_mises", "von Mises"), ("tresca", "Tresca")):
                load = _si(row[f"first_yield_load_{criterion}"], "N")
                lines.append(f"      {'first yield, ' + name:<{width}}{load} "
                             f"(yield strength {_si(yield_strength, 'Pa')})")
    return lines


def _write(text: str, stream=None) -> None:
    """Write text and a newline to stdout (or ``stream``), whatever its encoding.

    Characters the stream's encoding cannot hold become backslash escapes.  A reader that
    went away raises _ReaderLeftError; any other failure, including a closed stdout, is a
    _UsageError.
    """
    stream = sys.stdout if stream is None else stream
    if stream is None:  # the interpreter found descriptor 1 closed (hertz >&-)
        raise _UsageError("cannot write the output: standard output is closed")
    encoding = getattr(stream, "encoding", None)
    if encoding:
        try:
            text = text.encode(encoding, "backslashreplace").decode(encoding)
        except LookupError:
            pass
    try:
        stream.write(text + "\n")
        stream.flush()
    except BrokenPipeError:
        if stream is sys.stdout:
            _silence_stdout()
        raise _ReaderLeftError from None
    except (OSError, ValueError) as exc:  # a full disk, a closed descriptor or file
        if stream is sys.stdout:
            _silence_stdout()
        raise _UsageError(f"cannot write the output: {getattr(exc, 'strerror', None) or exc}"
                          ) from None


def _silence_stdout() -> None:
    """After a failed write: point descriptor 1 at the null device, so that the
    interpreter's own flush at exit neither fails nor repeats the error."""
    try:
        if sys.stdout is not None:
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except (OSError, ValueError, io.UnsupportedOperation):
        pass


def _warn(notes) -> None:
    """Each warning as one line on stderr, after the output: the exit status stays 0."""
    for note in notes:
        _message("warning", note)


def _error(message: str) -> None:
    _message("error", message)


def _message(kind: str, message: str) -> None:
    if sys.stderr is None:
        return
    line = " ".join(str(message).split("\n"))
    if len(line) > 1000:
        line = line[:997] + "..."
    try:
        _write(f"hertz: {kind}: {line}", sys.stderr)
    except (_UsageError, _ReaderLeftError):
        pass


# --- the figure ----------------------------------------------------------------------------

def _plot_format(path: str) -> str:
    """The format of ``--plot PATH``: its suffix.  The path given is the path written."""
    if not path:
        raise _UsageError("--plot needs a file name such as stresses.png, got ''")
    if os.path.isdir(path):
        raise _UsageError(f"--plot {path!r} is a directory: give a file name such as "
                          f"{os.path.join(path, 'stresses.png')!r}")
    suffix = os.path.splitext(path)[1]
    if len(suffix) < 2:
        raise _UsageError(f"--plot {path!r} has no suffix naming the format: give e.g. "
                          f"{path + '.png'!r} (the path given is the path written)")
    folder = os.path.dirname(path)
    if folder and not os.path.isdir(folder):
        raise _UsageError(f"cannot write the plot {path!r}: there is no directory {folder!r}")
    return suffix[1:].lower()


def _plot(c, scene, path: str) -> None:
    fmt = _plot_format(path)
    if not c.a > 0:
        raise _UsageError("--plot: the load is zero: there are no stresses to draw")
    try:
        import matplotlib.pyplot as plt
        from matplotlib.backend_bases import FigureCanvasBase

        from ._plot import stress_figure
    except ImportError as exc:
        raise _UsageError(f"--plot needs matplotlib ({exc.name} is not installed): "
                          f"{_PLOT_EXTRA}") from None
    formats = FigureCanvasBase.get_supported_filetypes()
    if fmt not in formats:
        raise _UsageError(f"--plot {path!r}: matplotlib does not write {fmt!r} files "
                          f"(it writes {', '.join(sorted(formats))})")
    title = scene["name"].replace("$", r"\$")  # a name, not matplotlib math text
    figure = stress_figure(c, title=title)
    drawn = io.BytesIO()  # drawn in memory first: a failure leaves no half-written file
    try:
        figure.savefig(drawn, format=fmt, dpi=130)
    except Exception as exc:  # noqa: BLE001  (matplotlib raises many kinds)
        raise _UsageError(f"cannot draw the plot as {fmt}: {exc}") from None
    finally:
        plt.close(figure)
    existed = os.path.lexists(path)
    try:
        with open(path, "wb") as f:
            f.write(drawn.getvalue())
    except OSError as exc:
        if not existed:
            try:
                os.remove(path)
            except OSError:
                pass
        raise _UsageError(f"cannot write the plot {path!r}: {exc.strerror or exc}") from None


# --- the command ---------------------------------------------------------------------------

def _print_scene(scene: dict, path: str) -> None:
    if path in ("", None):
        raise _UsageError("--print-scene needs a file name or -, got ''")
    if path == "-":
        _write(scene_toml(scene, getattr(sys.stdout, "encoding", None)).rstrip("\n"))
        return
    try:
        with open(path, "x", encoding="utf-8") as f:  # never over an existing file
            f.write(scene_toml(scene))
    except FileExistsError:
        raise _UsageError(f"--print-scene: {path!r} exists; remove it or give another "
                          "name") from None
    except OSError as exc:
        raise _UsageError(f"cannot write the scene file {path!r}: {exc.strerror or exc}"
                          ) from None


def _run(argv) -> int:
    args = _parser().parse_args(argv)
    if args.print_scene is not None:
        extra = [opt for opt, given in (("--json", args.json), ("--plot", args.plot),
                                        ("--yield-strength", args.yield_strength))
                 if given not in (None, False)]
        if extra:
            raise _UsageError(f"--print-scene writes the scene only: {', '.join(extra)} "
                              "not allowed with it")
    elif sys.stdout is None:
        raise _UsageError("cannot write the output: standard output is closed")
    if args.plot is not None:
        _plot_format(args.plot)  # a bad name fails before any work
    scene = _scene(args)
    if "load_per_length" in scene:
        return _run_line(args, scene)
    # Overflow and underflow are reported as such (overflow, null); a NaN is an error
    # (_finite): numpy's floating-point warnings would only repeat them on stderr.
    with np.errstate(all="ignore"):
        body1, body2, c, notes = _solve(scene)
        if args.print_scene is not None:
            _print_scene(scene, args.print_scene)
            _warn(notes)
            return 0
        fields = _fields(c)
        tangential = _tangential(scene, c)
        with warnings.catch_warnings():  # the 1 N contact of the first-yield load: not the scene's
            warnings.simplefilter("ignore", HertzValidityWarning)
            stresses = _stresses(scene, body1, body2, c, args.yield_strength)
        if args.plot is not None:
            _plot(c, scene, args.plot)
    if args.json:
        text = _json(scene, fields, stresses, tangential, notes)
    else:
        text = "\n".join([_table(scene, body1, body2, fields),
                          *([] if tangential is None else _tangential_table(tangential)),
                          *_stress_table(stresses, args.yield_strength, not c.a > 0)])
    _write(text)
    _warn(notes)
    return 0


# --- a line contact (scene key load_per_length) ---------------------------------------------

_LINE_FIELDS = ("half_width", "p0", "p_mean", "load_per_length", "e_star", "rho_sum")
_LINE_MAXIMA = ("tau_max", "z_tau_max", "von_mises", "z_von_mises")


def _run_line(args, scene) -> int:
    """A scene with ``load_per_length``: the :class:`hertz.LineContact` of its bodies (two
    parallel cylinders, Rx = R and Ry = inf, or a cylinder on a plane), as a table or JSON,
    with the largest subsurface stresses of each body (plane strain)."""
    from ._contact import line_contact

    extra = [opt for opt, given in (("--print-scene", args.print_scene),
                                    ("--plot", args.plot),
                                    ("--yield-strength", args.yield_strength),
                                    ("--angle-deg", scene.get("angle_deg") or None),
                                    ("--tangential", scene.get("tangential")))
             if given is not None]
    if extra:
        raise _UsageError(f"a line contact (scene key load_per_length) takes none of "
                          f"{', '.join(extra)} (parallel cylinders, normal load only)")
    body1, body2 = _body(scene["body1"], "body1"), _body(scene["body2"], "body2")
    with warnings.catch_warnings(record=True) as caught, np.errstate(all="ignore"):
        warnings.simplefilter("always", HertzValidityWarning)
        try:
            lc = line_contact(body1, body2, scene["load_per_length"])
        except TypeError as exc:
            raise _UsageError(str(exc)) from None
        fields = {k: _finite(getattr(lc, k), k) for k in _LINE_FIELDS}
        stresses = {}
        for body in (1, 2):
            if lc.half_width > 0:
                m = lc.subsurface(body)
                stresses[f"body{body}"] = {k: _finite(getattr(m, k), f"body {body}'s {k}")
                                           for k in _LINE_MAXIMA}
            else:
                stresses[f"body{body}"] = {"tau_max": 0.0, "z_tau_max": None,
                                           "von_mises": 0.0, "z_von_mises": None}
    notes = [str(w.message) for w in caught if issubclass(w.category, HertzValidityWarning)]
    if args.json:
        text = json.dumps({"scene": scene["name"], "kind": "line", **fields,
                           "stresses": stresses, "warnings": notes}, indent=2,
                          allow_nan=False)
    else:
        lines = [f"Hertz line contact: {_printable(scene['name'])}"]
        for i, b in ((1, body1), (2, body2)):
            lines.append(f"  body {i}: Rx = {_radius_text(b.Rx)}, Ry = {_radius_text(b.Ry)}, "
                         f"E = {_si(b.E, 'Pa')}, nu = {b.nu:g}")
        rows = [("load per length P'", _si(fields["load_per_length"], "N/m")),
                ("half-width b", _si(fields["half_width"], "m")),
                ("peak pressure p0", _si(fields["p0"], "Pa")),
                ("mean pressure", _si(fields["p_mean"], "Pa")),
                ("E* (reduced modulus)", _si(fields["e_star"], "Pa")),
                ("relative curvature", _g(fields["rho_sum"], " 1/m"))]
        width = max(len(name) for name, _ in rows)
        lines += [f"  {name:<{width}}  {value}" for name, value in rows]
        lines.append("  stresses below the contact (plane strain, frictionless):")
        for body in (1, 2):
            row = stresses[f"body{body}"]
            lines.append(f"    body {body}: tau_max {_si(row['tau_max'], 'Pa')} at "
                         f"{_si(row['z_tau_max'], 'm')}, von Mises "
                         f"{_si(row['von_mises'], 'Pa')} at {_si(row['z_von_mises'], 'm')}")
        lines.append("  (the approach of a line contact depends on the bodies' sizes: "
                     "not given)")
        text = "\n".join(lines)
    _write(text)
    _warn(notes)
    return 0


def main(argv=None) -> int:
    """Entry point of the ``hertz`` command; returns the exit status.

    Every failure is one line on stderr and status 2, never a traceback.
    """
    try:
        return _run(argv)
    except _ReaderLeftError:  # `hertz | head`: the reader left; stop quietly
        return 0
    except (_UsageError, ValueError) as exc:
        message = str(exc)
    except RecursionError:
        message = "the input is nested too deeply"
    except MemoryError:
        message = "out of memory"
    except KeyboardInterrupt:
        _error("interrupted")
        return 130
    except Exception as exc:  # noqa: BLE001  (the promise: no traceback, ever)
        message = (f"unexpected {type(exc).__name__}: {exc} (a defect of hertz: please "
                   "report the command line)")
    _error(message)
    return 2


if __name__ == "__main__":
    sys.exit(main())
