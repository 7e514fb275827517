"""Shared by the benchmark scripts: the machine's description and documentation updates."""

from __future__ import annotations

import platform
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
DOCS = ROOT / "docs"


def cpu_name() -> str:
    """The processor's name, as ``hertz.show_config()`` reports it (from the checkout
    where hertz is not installed: hertz._build_info is pure Python)."""
    import sys

    if str(ROOT) not in sys.path:
        sys.path.append(str(ROOT))
    from hertz._build_info import _cpu_name

    return _cpu_name()


def describe() -> str:
    import numpy
    import scipy

    import hertz

    return (f"hertz {hertz.__version__}, numpy {numpy.__version__}, scipy {scipy.__version__}, "
            f"Python {platform.python_version()}, {cpu_name()}")


def marked_files(readme: Path = README) -> list[Path]:
    """The files a marked section may live in: the README, then every docs/**/*.md."""
    docs = readme.parent / "docs"
    return [readme, *sorted(p for p in docs.rglob("*.md") if "_build" not in p.parts)]


def replace_readme_section(marker: str, text: str, readme: Path = README) -> Path:
    """Put ``text`` between the lines <!-- marker --> and <!-- /marker -->.

    The section is looked for in ``readme`` and in every Markdown page under the docs/
    folder beside it (the tables moved from the README into the documentation site);
    exactly one file must hold it. Returns the file written; raises SystemExit naming
    the files searched if none (or more than one) holds the marker.
    """
    begin, end = f"<!-- {marker} -->", f"<!-- /{marker} -->"
    candidates = marked_files(readme)
    found = [p for p in candidates if p.exists() and begin in (content := p.read_text())
             and end in content]
    if len(found) != 1:
        where = ", ".join(str(p.relative_to(readme.parent)) for p in found)
        raise SystemExit(
            f"the section {begin} ... {end} must be in exactly one of README.md and "
            f"docs/**/*.md; found in {len(found)} ({where or 'none'})")
    path = found[0]
    content = path.read_text()
    head, rest = content.split(begin, 1)
    path.write_text(f"{head}{begin}\n{text.strip()}\n{end}{rest.split(end, 1)[1]}")
    return path
