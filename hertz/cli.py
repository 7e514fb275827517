"""The ``hertz`` command: solve one Hertz point contact and print it.

With no arguments it solves a built-in scene: a 12 mm bearing ball on the
inner race of a deep-groove ball bearing (groove radius 6.2 mm, race radius
40 mm in the rolling direction), steel on steel, 1500 N.  Options or a TOML
scene file change any of it::

    hertz --load 800 --json
    hertz --scene my_scene.toml --angle-deg 30
    hertz --yield-strength 1.5e9 --plot stresses.png

A scene file holds the same names as the options::

    name = "crossed cylinders"
    load = 100.0          # N (or: approach = 1e-6, in m)
    angle_deg = 90.0
    [body1]
    Rx = 0.01             # m; negative concave, "inf" flat
    Ry = "inf"
    E = 210e9             # Pa
    nu = 0.3
    [body2]
    Rx = 0.01
    Ry = "inf"
    E = 210e9
    nu = 0.3

Errors (bad values, a missing file, no Hertz contact, output that cannot
be written) print one line on stderr and exit with status 2.  ``--json``
prints strict JSON: a value that overflows a double is ``null``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import tomllib

from ._contact import Body, contact

DEFAULT_SCENE = {
    "name": "bearing ball on inner race (default scene)",
    "body1": {"Rx": 6e-3, "Ry": 6e-3, "E": 210e9, "nu": 0.3},
    "body2": {"Rx": -6.2e-3, "Ry": 40e-3, "E": 210e9, "nu": 0.3},
    "load": 1500.0,
    "angle_deg": 0.0,
}

_BODY_KEYS = ("Rx", "Ry", "E", "nu")


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, status 2
        raise _UsageError(message)


class _UsageError(Exception):
    pass


def _number(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None


def _parser() -> argparse.ArgumentParser:
    p = _Parser(prog="hertz", description="Hertz point contact of two elastic bodies "
                "(SI units; radii negative for concave, inf for flat).")
    p.add_argument("--scene", metavar="FILE", help="TOML scene file (options override it)")
    for i in (1, 2):
        g = p.add_argument_group(f"body {i}")
        for axis in "xy":
            g.add_argument(f"--r{i}{axis}", type=_number, metavar="M",
                           help=f"body {i} radius along its {axis} axis [m]")
        g.add_argument(f"--e{i}", type=_number, metavar="PA", help=f"body {i} Young's modulus [Pa]")
        g.add_argument(f"--nu{i}", type=_number, metavar="NU", help=f"body {i} Poisson's ratio [-]")
    load = p.add_mutually_exclusive_group()
    load.add_argument("--load", type=_number, metavar="N", help="normal force [N]")
    load.add_argument("--approach", type=_number, metavar="M",
                      help="approach of the bodies [m] (the load is computed)")
    p.add_argument("--angle-deg", type=_number, metavar="DEG",
                   help="angle between the bodies' x axes [degrees]")
    p.add_argument("--yield-strength", type=_number, metavar="PA",
                   help="yield strength of both bodies [Pa]: adds the load at which each first "
                        "yields (von Mises and Tresca)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="draw the von Mises stress below the contact (needs matplotlib: "
                        "pip install 'hertz-contact[plot]')")
    p.add_argument("--json", action="store_true", help="print one JSON object instead of a table")
    return p


def _read_scene(path: str) -> dict:
    try:
        with open(path, "rb") as f:
            scene = tomllib.load(f)
    except OSError as exc:
        raise _UsageError(f"cannot read scene file {path!r}: {exc.strerror}") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise _UsageError(f"scene file {path!r} is not valid TOML: {exc}") from None
    except RecursionError:
        raise _UsageError(f"scene file {path!r} is nested too deeply to read") from None
    merged = {k: (dict(v) if isinstance(v, dict) else v) for k, v in DEFAULT_SCENE.items()}
    merged["name"] = path
    for key, value in scene.items():
        if key in ("body1", "body2"):
            if not isinstance(value, dict):
                raise _UsageError(f"scene file: [{key}] must be a table")
            unknown = set(value) - set(_BODY_KEYS)
            if unknown:
                names = ", ".join(sorted(unknown))
                raise _UsageError(f"scene file: unknown key(s) in [{key}]: {names}")
            merged[key].update(value)
        elif key in ("load", "approach", "angle_deg"):
            merged[key] = _scalar(value, key)
        elif key == "name":
            if not isinstance(value, str):
                raise _UsageError(f"scene file: name must be a string, got {_kind(value)}")
            merged[key] = value
        else:
            raise _UsageError(f"scene file: unknown key {key!r}")
    if "approach" in scene:
        if "load" in scene:
            raise _UsageError("scene file: give one of load and approach, not both")
        merged.pop("load")
    return merged


def _kind(value) -> str:
    return {list: "an array", dict: "a table"}.get(type(value), type(value).__name__)


def _scalar(value, name: str) -> float:
    """A number from a scene file: an int or float, or a string that spells one ("inf")."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise _UsageError(f"{name} must be a number, got {_kind(value)}: {value!r}"[:200])
    if isinstance(value, str):
        try:
            return float(value)
        except ValueError:
            raise _UsageError(f"{name} must be a number, got {value!r}") from None
    return float(value)


def _scene(args) -> dict:
    scene = _read_scene(args.scene) if args.scene else {
        k: (dict(v) if isinstance(v, dict) else v) for k, v in DEFAULT_SCENE.items()}
    for i in (1, 2):
        for key, opt in zip(_BODY_KEYS, (f"r{i}x", f"r{i}y", f"e{i}", f"nu{i}"), strict=True):
            value = getattr(args, opt)
            if value is not None:
                scene[f"body{i}"][key] = value
    if args.load is not None:
        scene["load"] = args.load
        scene.pop("approach", None)
    if args.approach is not None:
        scene["approach"] = args.approach
        scene.pop("load", None)
    if args.angle_deg is not None:
        scene["angle_deg"] = args.angle_deg
    if any(vars(args)[k] is not None for k in vars(args) if k not in ("scene", "json")) \
            and not args.scene:
        scene["name"] = "custom scene"
    return scene


def _body(spec: dict, name: str) -> Body:
    values = {key: _scalar(spec[key], f"{name}.{key}") for key in _BODY_KEYS}
    try:
        return Body(**values)
    except (TypeError, ValueError) as exc:
        raise _UsageError(f"{name}: {exc}") from None


def _solve(scene: dict):
    body1, body2 = _body(scene["body1"], "body1"), _body(scene["body2"], "body2")
    angle = scene.get("angle_deg", 0.0)
    kwargs = {"approach": scene["approach"]} if "approach" in scene else {"load": scene["load"]}
    try:
        return body1, body2, contact(body1, body2, angle=math.radians(angle), **kwargs)
    except TypeError as exc:
        raise _UsageError(str(exc)) from None


_PREFIXES = [(1e9, "G"), (1e6, "M"), (1e3, "k"), (1.0, ""), (1e-3, "m"), (1e-6, "u"), (1e-9, "n")]


def _si(value: float, unit: str) -> str:
    if value == 0 or not math.isfinite(value):
        return f"{value:g} {unit}"
    for scale, prefix in _PREFIXES:
        if abs(value) >= scale:
            return f"{value / scale:.6g} {prefix}{unit}"
    return f"{value:.6g} {unit}"


def _radius_text(r: float) -> str:
    return "flat" if math.isinf(r) else _si(r, "m")


def _table(scene, body1, body2, c) -> str:
    rows = [
        ("load P", _si(c.load, "N")),
        ("semi-major axis a", _si(c.a, "m")),
        ("semi-minor axis b", _si(c.b, "m")),
        ("ellipticity a/b", f"{c.ellipticity:.6g}"),
        ("curvature ratio alpha", f"{c.alpha:.6g}"),
        ("peak pressure p0", _si(c.p0, "Pa")),
        ("mean pressure", _si(c.p_mean, "Pa")),
        ("contact area", f"{c.area:.6g} m^2"),
        ("approach delta", _si(c.delta, "m")),
        ("stiffness dP/d(delta)", _si(c.stiffness, "N/m")),
        ("major axis angle", f"{math.degrees(c.major_axis_angle):.6g} deg (from body 1's x axis)"),
        ("E* (reduced modulus)", _si(c.e_star, "Pa")),
        ("rho_x, rho_y", f"{c.rho_x:.6g}, {c.rho_y:.6g} 1/m"),
        ("elliptic m, K(m), E(m)", f"{c.m:.6g}, {c.K:.6g}, {c.E:.6g}"),
    ]
    lines = [f"Hertz point contact: {scene['name']}"]
    for i, b in ((1, body1), (2, body2)):
        lines.append(f"  body {i}: Rx = {_radius_text(b.Rx)}, Ry = {_radius_text(b.Ry)}, "
                     f"E = {_si(b.E, 'Pa')}, nu = {b.nu:g}")
    lines.append(f"  angle between x axes: {scene.get('angle_deg', 0.0):g} deg")
    width = max(len(name) for name, _ in rows)
    lines.extend(f"  {name:<{width}}  {value}" for name, value in rows)
    return "\n".join(lines)


_MAXIMA = ("tau_max", "z_tau_max", "von_mises", "z_von_mises", "tau_orthogonal",
           "y_tau_orthogonal", "z_tau_orthogonal", "tensile", "x_tensile", "y_tensile")


def _finite(value: float):
    return value if math.isfinite(value) else None


def _stresses(c, yield_strength) -> dict:
    """{"body1": {...}, "body2": {...}}: the subsurface maxima and first-yield loads."""
    out = {}
    for body in (1, 2):
        maxima = c.subsurface(body)
        row = {k: _finite(float(getattr(maxima, k))) for k in _MAXIMA}
        if yield_strength is not None:
            for criterion in ("von_mises", "tresca"):
                load = c.first_yield_load(yield_strength, body=body, criterion=criterion)
                row[f"first_yield_load_{criterion}"] = _finite(float(load))
        out[f"body{body}"] = row
    return out


def _json(scene, c, stresses) -> str:
    keys = ("a", "b", "p0", "delta", "load", "ellipticity", "alpha", "m", "K", "E", "e_star",
            "rho_x", "rho_y", "rho_sum", "major_axis_angle", "p_mean", "area", "stiffness")
    out = {"scene": scene["name"], **{k: _finite(float(getattr(c, k))) for k in keys},
           "stresses": stresses}
    return json.dumps(out, allow_nan=False)


def _stress_table(stresses, yield_strength) -> list[str]:
    lines = ["  stresses below the contact (frictionless; each body with its own nu):"]
    labels = [("largest shear stress tau1", "tau_max", "z_tau_max", "Pa", "depth"),
              ("largest von Mises stress", "von_mises", "z_von_mises", "Pa", "depth"),
              ("orthogonal shear |tau_yz|", "tau_orthogonal", "z_tau_orthogonal", "Pa", "depth"),
              ("surface tension at edge", "tensile", None, "Pa", None)]
    width = max(len(label) for label, *_ in labels) + 2
    for body in (1, 2):
        row = stresses[f"body{body}"]
        lines.append(f"    body {body}:")
        for label, key, where, unit, kind in labels:
            value = _si(row[key], unit) if row[key] is not None else "overflow"
            at = f" at {kind} {_si(row[where], 'm')}" if where and row[where] is not None else ""
            if key == "tau_orthogonal" and row["y_tau_orthogonal"] is not None:
                at += f", y = {_si(row['y_tau_orthogonal'], 'm')}"
            if key == "tensile" and row["x_tensile"] is not None:
                at = (f" at x = {_si(row['x_tensile'], 'm')}, "
                      f"y = {_si(row['y_tensile'], 'm')}")
            lines.append(f"      {label:<{width}}{value}{at}")
        if yield_strength is not None:
            for criterion, name in (("von_mises", "von Mises"), ("tresca", "Tresca")):
                load = row[f"first_yield_load_{criterion}"]
                text = _si(load, "N") if load is not None else "overflow"
                lines.append(f"      {'first yield, ' + name:<{width}}{text} "
                             f"(yield strength {_si(yield_strength, 'Pa')})")
    return lines


def main(argv=None) -> int:
    """Entry point of the ``hertz`` command; returns the exit status."""
    try:
        args = _parser().parse_args(argv)
        scene = _scene(args)
        body1, body2, c = _solve(scene)
        stresses = _stresses(c, args.yield_strength)
        if args.plot:
            _plot(c, scene, args.plot)
    except (_UsageError, ValueError) as exc:
        print(f"hertz: error: {exc}", file=sys.stderr)
        return 2
    try:
        if args.json:
            text = _json(scene, c, stresses)
        else:
            text = "\n".join([_table(scene, body1, body2, c),
                              *_stress_table(stresses, args.yield_strength)])
        print(text, flush=True)
    except BrokenPipeError:  # `hertz | head`: the reader left; stop quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except OSError as exc:  # a full disk, a closed descriptor
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        print(f"hertz: error: cannot write the output: {exc.strerror or exc}", file=sys.stderr)
        return 2
    return 0


def _plot(c, scene, path: str) -> None:
    try:
        from ._plot import stress_figure
    except ImportError as exc:
        raise _UsageError(f"--plot needs matplotlib ({exc.name} is not installed): "
                          "pip install 'hertz-contact[plot]'") from None
    try:
        stress_figure(c, title=scene["name"]).savefig(path, dpi=130)
    except (OSError, ValueError) as exc:
        raise _UsageError(f"cannot write the plot {path!r}: {exc}") from None


if __name__ == "__main__":
    sys.exit(main())
