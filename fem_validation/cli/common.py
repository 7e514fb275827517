"""What every ``python -m fem_validation`` command line shares.

One argument parser (:class:`OneLineParser`: errors as one line, negative numbers as
values, ``--debug`` everywhere), the option types that refuse non-finite numbers, the
guard that turns every failure into one line and an exit status (:func:`guarded`), the
check of an ``--out`` folder (:func:`out_dir`) and of a hand-written input before a
reader sees it (:func:`small_input`), and the one-line answer when an optional package
is missing (:func:`require`).

Exit statuses of every command: 0 done (every check passed), 1 a check failed, 2 bad
input (a usage error, a malformed file, a missing optional package), 3 an internal error
(a defect: please report it), 130 interrupted.
"""

from __future__ import annotations

import argparse
import importlib.util
import math
import os
import stat
import sys
import traceback
import warnings
from collections.abc import Callable, Iterable
from pathlib import Path

from ..limits import MAX_TEXT_BYTES

__all__ = ["EXIT_FAILED", "FEM_RUN", "EXIT_INTERNAL", "EXIT_INTERRUPTED", "EXIT_USAGE", "OPTIONAL",
           "MissingExtra", "OneLineParser", "Unknown", "UsageError", "add_overwrite", "choices",
           "direction", "fem_constants", "finite", "guarded", "index", "out_dir", "positive",
           "require", "small_input", "vector"]

EXIT_FAILED = 1
EXIT_USAGE = 2
EXIT_INTERNAL = 3
EXIT_INTERRUPTED = 130

#: Optional modules the commands import: the package that installs each (pip's name).
OPTIONAL = {"skfem": "scikit-fem", "gmsh": "gmsh", "pyamg": "pyamg", "meshio": "meshio",
            "matplotlib": "matplotlib", "h5py": "h5py", "netCDF4": "netCDF4"}
EXTRA = 'pip install "hertz-contact[fem]"'
#: What a finite-element run of our own needs (mesh, solve, write VTU, plot).
FEM_RUN = ("skfem", "gmsh", "pyamg", "meshio", "matplotlib")


class UsageError(ValueError):
    """A command line that cannot be run (one line, exit status 2)."""


class MissingExtra(UsageError):
    """An optional package a mode needs is not installed (one line, exit status 2)."""


def _missing_message(module: str, what: str) -> str:
    root = module.split(".")[0]
    return (f"{what} needs {OPTIONAL.get(root, root)} (module {root!r}), which is not "
            f"installed: {EXTRA} installs it")


def require(modules: Iterable[str], what: str) -> None:
    """Raise :class:`MissingExtra` naming the first of ``modules`` that is not installed.

    Parameters
    ----------
    modules : iterable of str
        Import names (``"gmsh"``, ``"skfem"``).
    what : str
        What needs them, for the message (``"deck"``).
    """
    for module in modules:
        try:
            found = importlib.util.find_spec(module) is not None
        except (ImportError, ValueError):
            found = False
        if not found:
            raise MissingExtra(_missing_message(module, what))


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return " " not in text.strip()


def _is_numbers(text: str) -> bool:
    parts = text.replace(",", " ").split()
    return bool(parts) and all(_is_number(p) for p in parts)


def vector(text: str) -> list[float]:
    """Three finite numbers from ``"X,Y,Z"`` or ``"X Y Z"`` (an option type)."""
    try:
        v = [float(x) for x in text.replace(",", " ").split()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"not three numbers: {text!r}") from None
    if len(v) != 3 or not all(math.isfinite(x) for x in v):
        raise argparse.ArgumentTypeError(f"not three finite numbers: {text!r}")
    return v


def direction(text: str) -> list[float]:
    """A direction: three finite numbers, not all zero (an option type, as :func:`vector`)."""
    v = vector(text)
    if not any(v):
        raise argparse.ArgumentTypeError(f"a direction cannot be the zero vector: {text!r}")
    return v


def _number(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None


def finite(text: str) -> float:
    """A finite number (an option type: ``inf`` and ``nan`` are refused)."""
    x = _number(text)
    if not math.isfinite(x):
        raise argparse.ArgumentTypeError(f"must be a finite number, got {text!r}")
    return x


def positive(text: str) -> float:
    """A finite number > 0 (an option type)."""
    x = _number(text)
    if not (math.isfinite(x) and x > 0):
        raise argparse.ArgumentTypeError(f"must be a finite number > 0, got {text!r}")
    return x


def index(text: str) -> int:
    """An integer >= 1 (an option type: a path index)."""
    try:
        k = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an integer: {text!r}") from None
    if k < 1:
        raise argparse.ArgumentTypeError(f"must be a path index >= 1, got {text!r}")
    return k


class OneLineParser(argparse.ArgumentParser):
    """argparse with its errors as one-line UsageErrors, numbers as values, and --debug.

    A token that reads as a number or a list of them (``-1``, ``-1e-3``, ``-inf``,
    ``-1,0,0``) is always a value, never an option, so that ``--origin -1e-3 0 0`` and
    ``--friction-ratio -0.5`` reach the option (and its check) as written; an option of
    type :func:`vector` takes its three numbers as one token (``1,0,0``) or as three
    (``1 0 0``).  Every parser accepts
    ``--debug`` (the traceback of an internal error, see :func:`guarded`).
    """

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("formatter_class", argparse.RawDescriptionHelpFormatter)
        super().__init__(*args, **kwargs)
        self.add_argument("--debug", action="store_true",
                          help="on an internal error, print its traceback (to report it)")

    def error(self, message):
        raise UsageError(f"{self.prog}: {message}")

    def _parse_optional(self, arg_string):
        if arg_string[:1] in self.prefix_chars and _is_numbers(arg_string):
            return None  # a value (argparse's own test misses -1e-3, -inf, -.5 and -1,0,0)
        return super()._parse_optional(arg_string)

    def _vector_action(self, token: str):
        """The vector-typed action ``token`` names in full or as a unique prefix, else None."""
        if not token.startswith("--") or "=" in token:
            return None
        names = [s for s in self._option_string_actions if s.startswith(token)]
        action = (self._option_string_actions[token] if token in self._option_string_actions
                  else self._option_string_actions[names[0]] if len(names) == 1 else None)
        return action if action is not None and action.type in (vector, direction) else None

    def parse_known_args(self, args=None, namespace=None):
        args = list(sys.argv[1:] if args is None else args)
        joined, i = [], 0
        while i < len(args):
            joined.append(args[i])
            if (self._vector_action(args[i]) is not None and len(args) >= i + 4
                    and all(_is_number(t) for t in args[i + 1:i + 4])):
                joined.append(" ".join(args[i + 1:i + 4]))
                i += 3
            i += 1
        return super().parse_known_args(joined, namespace)


def small_input(path, what: str, limit: int = MAX_TEXT_BYTES) -> Path:
    """``path``, refused before any reader sees it if it is larger than ``limit`` or not
    a regular file (a device such as /dev/zero, a pipe).  A path that cannot be inspected
    (missing, no permission) is passed on for its reader to report.

    Raises
    ------
    UsageError
        Naming the option and the file.
    """
    path = Path(path)
    try:
        st = os.stat(path)
    except OSError:
        return path
    if not stat.S_ISREG(st.st_mode) and not stat.S_ISDIR(st.st_mode):
        raise UsageError(f"{what} {str(path)!r} is not a regular file (a device or a pipe): "
                         "give the file itself")
    if stat.S_ISREG(st.st_mode) and st.st_size > limit:
        raise UsageError(f"{what} {str(path)!r} is {st.st_size} bytes, larger than the "
                         f"{limit} bytes a hand-written file of this kind is given (is it the "
                         "right file?)")
    return path


def out_dir(path, overwrite: bool, replaces: Iterable[str] = ()) -> Path:
    """The ``--out`` folder, created and checked writable, refused where it holds files.

    A new or empty folder is used as it is; one holding anything else is refused unless
    ``overwrite`` (``--overwrite``), except that the files named in ``replaces`` (the
    files an earlier run of the same command wrote, for a command whose output is a
    report recomputed from its inputs, as ``grade``) are replaced without it.

    Raises
    ------
    UsageError
        The folder holds other files and ``overwrite`` is not given.
    ValueError
        The folder cannot be created or written (:func:`fem_validation.cli.common.prepare_out`).
    """
    path = Path(path)
    if path.is_dir() and not overwrite:
        try:
            held = sorted(p.name for p in path.iterdir())
        except OSError:
            held = []  # prepare_out names the reason
        others = [name for name in held if name not in set(replaces)]
        if others:
            shown = ", ".join(others[:3]) + (f" and {len(others) - 3} more"
                                             if len(others) > 3 else "")
            raise UsageError(f"--out {str(path)!r} is not empty (it holds {shown}): give a new "
                             "or empty folder, or --overwrite to write into it anyway")
    from .common import prepare_out

    return prepare_out(path)


def add_overwrite(parser: argparse.ArgumentParser, replaces: str = "") -> None:
    """The ``--overwrite`` option of a command that writes into ``--out``."""
    parser.add_argument("--overwrite", action="store_true",
                        help="write into an --out folder that already holds files (without "
                             "it, a folder that is not empty is refused" +
                             (f"; {replaces}" if replaces else "") + ")")


class Unknown:
    """A constant of a module that cannot be imported (the fem extra is missing): ``?``
    in a help text."""

    def __format__(self, spec: str) -> str:
        return "?"

    def __repr__(self) -> str:
        return "?"


def fem_constants(names: dict[str, Iterable[str]]) -> tuple[dict, str]:
    """Constants of fem_validation's modules for the help texts, without failing where
    the fem extra is missing.

    Parameters
    ----------
    names : dict
        Module (its path below the package, ``"solvers.mesh"``) to the names wanted from it.

    Returns
    -------
    constants : dict
        Name to value, or to an :class:`Unknown` where the module cannot be imported.
    note : str
        Empty, or a paragraph for the help saying which package is missing and how to
        install it.
    """
    import importlib

    constants, missing = {}, []
    for module, wanted in names.items():
        try:
            m = importlib.import_module(f"fem_validation.{module}")
        except ModuleNotFoundError as exc:
            m = None
            missing.append((exc.name or module).split(".")[0])
        for name in wanted:
            constants[name] = getattr(m, name) if m is not None else Unknown()
    note = ""
    if missing:
        packages = ", ".join(dict.fromkeys(OPTIONAL.get(x, x) for x in missing))
        note = (f"\n\nNot installed here: {packages}; these runs need them ({EXTRA}), and the "
                "defaults shown as ? are its.")
    return constants, note


def choices(values):
    """``sorted(values)``, or None (any value; the run then says what is missing) for an
    :class:`Unknown`."""
    return None if isinstance(values, Unknown) else sorted(values)


def _first_line(text: str) -> str:
    return (text.splitlines() or [""])[0]


def guarded(name: str, body: Callable[[list[str]], int], argv: list[str]) -> int:
    """Run a command's ``body(argv)`` and turn every exception into one line on stderr.

    Parameters
    ----------
    name : str
        The command, prefixed to every line (``"fem_validation grade"``).
    body : callable
        Parses ``argv``, runs, returns the exit status (0 or 1).
    argv : list of str
        The arguments after the command's name; ``--debug`` among them prints the
        traceback of any error before its line.

    Returns
    -------
    int
        ``body``'s status; 2 for bad input (:class:`ValueError`, including
        :class:`UsageError` and the readers' errors, :class:`OSError`,
        :class:`~fem_validation.errors.FEMValidationError`, a missing optional
        package); 3 for anything else (a defect: "internal error ... please report");
        130 on Ctrl-C.  Never 1, which means a failed check.

    Notes
    -----
    A backstop for warnings: the commands compute so that none arises (a grade notes
    Hertz's validity warning in its files), and any Python warning that still does is
    held and, after a run that ends without an error, printed as at most one line
    ``NAME: warning: ...`` (with how many more there were); after an error only the
    error's line is printed.  ``--debug`` prints every warning as it comes.
    """
    if "--debug" in argv:
        return _guarded(name, body, argv)
    with warnings.catch_warnings(record=True) as caught:
        status = _guarded(name, body, argv)
    if caught and status in (0, EXIT_FAILED):
        more = f" (and {len(caught) - 1} more warning(s))" if len(caught) > 1 else ""
        first = _first_line(f"{caught[0].category.__name__}: {caught[0].message}")[:300]
        print(f"{name}: warning: {first}{more}", file=sys.stderr)
    return status


def _guarded(name: str, body: Callable[[list[str]], int], argv: list[str]) -> int:
    """:func:`guarded` without its hold on warnings."""
    from ..errors import FEMValidationError

    debug = "--debug" in argv
    try:
        return body(argv)
    except KeyboardInterrupt:
        print(f"\n{name}: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except ModuleNotFoundError as exc:
        if debug:
            traceback.print_exc()
        if (exc.name or "").split(".")[0] in OPTIONAL:
            print(f"{name}: error: {_missing_message(exc.name, 'this')}", file=sys.stderr)
            return EXIT_USAGE
        line = f"ModuleNotFoundError: {exc}"
    except (ValueError, OSError, FEMValidationError) as exc:
        if debug:
            traceback.print_exc()
        print(_first_line(f"{name}: error: {exc}"), file=sys.stderr)
        return EXIT_USAGE
    except MemoryError as exc:
        if debug:
            traceback.print_exc()
        print(f"{name}: out of memory (MemoryError{': ' + str(exc) if str(exc) else ''}): "
              "the run needs more memory than this machine has; with a small input this is "
              "a defect (please report; rerun with --debug for the traceback)", file=sys.stderr)
        return EXIT_INTERNAL
    except RecursionError as exc:
        if debug:
            traceback.print_exc()
        line = f"RecursionError: {exc}"
    except Exception as exc:  # noqa: BLE001 - every other failure is a defect of ours
        if debug:
            traceback.print_exc()
        line = f"{type(exc).__name__}: {exc}"
    print(_first_line(f"{name}: internal error: {line}")[:500]
          + " (please report; rerun with --debug for the traceback)", file=sys.stderr)
    return EXIT_INTERNAL


def prepare_out(path) -> Path:
    """The output directory, created; ValueError (one line) where it cannot be written.

    Refused: an existing file, a directory that cannot be created, one where no file
    can be written (probed by creating and removing a temporary file).
    """
    import tempfile

    path = Path(path)
    if path.exists() and not path.is_dir():
        raise ValueError(f"--out {str(path)!r} exists and is not a directory")
    try:
        path.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=path, prefix=".probe"):
            pass
    except OSError as exc:
        raise ValueError(f"--out {str(path)!r} cannot be written: "
                         f"{exc.strerror or exc}") from None
    return path
