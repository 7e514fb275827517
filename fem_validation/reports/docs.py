"""Put a report into the documentation: the table between a page's markers and its
figures into docs/fem/ (``--readme``, run from the repository root)."""

from __future__ import annotations

import shutil
from pathlib import Path


def readme_section(marker: str) -> tuple[Path, str]:
    """The page holding the <!-- marker --> section (README.md or a docs/**/*.md page of
    the checkout in the working directory) and its text; ValueError if none or several
    do (checked before a run, so that --readme outside a checkout fails at once)."""
    begin, end = f"<!-- {marker} -->", f"<!-- /{marker} -->"
    pages = [Path("README.md"), *sorted(Path("docs").glob("**/*.md"))]
    found = [(page, text) for page in pages if page.is_file()
             for text in [page.read_text(encoding="utf-8")] if begin in text and end in text]
    if len(found) != 1:
        where = "no page" if not found else ", ".join(str(page) for page, _ in found)
        raise ValueError(f"--readme: {where} of README.md and docs/**/*.md (in {Path.cwd()}) "
                         f"holds the {begin} ... {end} section: run from the repository's "
                         "root")
    return found[0]


def publish(marker: str, text: str, images) -> None:
    """Replace the section between <!-- marker --> and <!-- /marker --> of the page that
    holds it and copy the images to docs/fem/."""
    page, content = readme_section(marker)
    begin, end = f"<!-- {marker} -->", f"<!-- /{marker} -->"
    head, rest = content.split(begin, 1)
    page.write_text(f"{head}{begin}\n{text.strip()}\n{end}{rest.split(end, 1)[1]}",
                    encoding="utf-8")
    docs = Path("docs") / "fem"
    docs.mkdir(parents=True, exist_ok=True)
    for src, name in images:
        shutil.copyfile(src, docs / name)
