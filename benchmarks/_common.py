"""Shared by the benchmark scripts: the machine's description and README updates."""

from __future__ import annotations

import platform
from pathlib import Path

README = Path(__file__).resolve().parents[1] / "README.md"


def cpu_name() -> str:
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def describe() -> str:
    import numpy
    import scipy

    import hertz

    return (f"hertz {hertz.__version__}, numpy {numpy.__version__}, scipy {scipy.__version__}, "
            f"Python {platform.python_version()}, {cpu_name()}")


def replace_readme_section(marker: str, text: str, readme: Path = README) -> None:
    """Put ``text`` between the lines <!-- marker --> and <!-- /marker --> of the README."""
    begin, end = f"<!-- {marker} -->", f"<!-- /{marker} -->"
    content = readme.read_text()
    if begin not in content or end not in content:
        raise SystemExit(f"{readme} has no {begin} ... {end} section")
    head, rest = content.split(begin, 1)
    readme.write_text(f"{head}{begin}\n{text.strip()}\n{end}{rest.split(end, 1)[1]}")
