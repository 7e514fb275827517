"""python -m fem_validation MODE ...: picks the mode and hands it to
:mod:`fem_validation.cli` (``--help`` lists the modes)."""

from __future__ import annotations

import sys

from .cli.common import guarded
from .cli.deck import _deck
from .cli.validate import _parser, _validate


def main(argv=None) -> int:
    """Entry point of ``python -m fem_validation``: the exit status (0 done, 1 a check
    failed, 2 bad input, 3 an internal error, 130 interrupted)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if not argv:  # a bare command prints the help rather than start minutes of meshing
        return guarded("fem_validation", lambda _: print(_parser().format_help()) or 0, argv)
    mode, rest = argv[0], argv[1:]
    if mode == "deck":
        return guarded("fem_validation deck", _deck, rest)
    if mode == "friction":
        from .cli.friction import main as friction_main

        return friction_main(rest)
    if mode == "grade":
        from .cli.grade import main as grade_main

        return grade_main(rest)
    if mode == "validate":
        return guarded("fem_validation validate",
                       lambda a: _validate(a, "python -m fem_validation validate"), rest)
    return guarded("fem_validation", _validate, argv)


if __name__ == "__main__":
    sys.exit(main())
