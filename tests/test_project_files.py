"""The files a user of the library expects beside the code: the licence, how to cite it,
the changelog and the bibliography, each consistent with the package metadata and with
what the code cites (issue 22 item 13).

They skip when the tests run without the source tree beside them (an installed wheel).
"""

import re
import tomllib
import unicodedata
from pathlib import Path

import pytest

import hertz

ROOT = Path(__file__).resolve().parent.parent
needs_source_tree = pytest.mark.skipif(not (ROOT / "pyproject.toml").is_file(),
                                       reason=f"no pyproject.toml at {ROOT}")

#: The seed paper, as its own title page states it (the seed's LaTeX source).
PAPER_TITLE = "Proposal for fast computational method for Hertzian contact theory"
PAPER_AUTHORS = [("Hokada", "Shintaro"), ("Iizuka", "Shunsuke"), ("Takada", "Satoshi")]
PAPER_ARXIV = "2508.06967"

#: The three clauses of the BSD-3-Clause licence (SPDX's text), in short.
BSD_3_CLAUSES = ("Redistributions of source code must retain the above copyright notice",
                 "Redistributions in binary form must reproduce the above copyright notice",
                 "Neither the name of the copyright holder nor the names of its")


def pyproject():
    return tomllib.loads((ROOT / "pyproject.toml").read_text())


@needs_source_tree
def test_the_licence_is_bsd_3_clause_and_the_metadata_says_so():
    text = (ROOT / "LICENSE").read_text()
    assert text.startswith("BSD 3-Clause License")
    for clause in BSD_3_CLAUSES:
        assert clause in " ".join(text.split()), clause
    project = pyproject()["project"]
    assert project["license"] == {"text": "BSD-3-Clause"}
    assert "License :: OSI Approved :: BSD License" in project["classifiers"]
    # the copyright line is the documentation's (docs/conf.py)
    conf = (ROOT / "docs" / "conf.py").read_text()
    holder = re.search(r'^copyright = "(.+?)"', conf, re.M).group(1)
    assert f"Copyright (c) {holder}" in text


@needs_source_tree
def test_the_project_urls_are_real_addresses():
    """Only addresses the project can state: no placeholder host or name."""
    urls = pyproject()["project"]["urls"]
    assert urls, "no [project.urls]"
    for label, url in urls.items():
        assert re.fullmatch(r"https://[\w.-]+\.[a-z]{2,}/\S*", url), (label, url)
        assert not re.search(r"example|placeholder|your-?name|owner|TODO", url, re.I), url
    assert urls["Paper"] == f"https://arxiv.org/abs/{PAPER_ARXIV}"


@needs_source_tree
def test_citation_cff_describes_the_software_and_the_paper():
    yaml = pytest.importorskip("yaml")
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    # the keys CFF 1.2.0 requires, and their types
    assert cff["cff-version"] == "1.2.0"
    assert isinstance(cff["message"], str) and cff["message"].strip()
    assert isinstance(cff["title"], str) and cff["title"].strip()
    assert cff["authors"] and all(isinstance(a, dict) and ("name" in a or "family-names" in a)
                                  for a in cff["authors"])
    # the software's metadata agrees with the package's
    assert cff["type"] == "software"
    assert cff["version"] == hertz.__version__ == pyproject()["project"]["version"]
    assert cff["license"] == pyproject()["project"]["license"]["text"]
    # the paper, with the data of its own title page
    (paper,) = [r for r in cff["references"] if r["title"] == PAPER_TITLE]
    assert paper["type"] == "article"
    assert [(a["family-names"], a["given-names"]) for a in paper["authors"]] == PAPER_AUTHORS
    assert paper["url"] == f"https://arxiv.org/abs/{PAPER_ARXIV}"
    assert {"type": "other", "value": f"arXiv:{PAPER_ARXIV}",
            "description": "arXiv identifier"} in paper["identifiers"]
    # every key is one CFF 1.2.0 defines for its level (a misspelt key is not an error in
    # YAML, but CFF validators reject it)
    top = {"abstract", "authors", "cff-version", "commit", "contact", "date-released", "doi",
           "identifiers", "keywords", "license", "license-url", "message",
           "preferred-citation", "references", "repository", "repository-artifact",
           "repository-code", "title", "type", "url", "version"}
    assert set(cff) <= top, set(cff) - top


@needs_source_tree
def test_the_changelog_has_unreleased_and_the_current_version():
    text = (ROOT / "CHANGELOG.md").read_text()
    headings = re.findall(r"^## \[([^\]]+)\]", text, re.M)
    assert headings[0] == "Unreleased"
    assert hertz.__version__ in headings


@needs_source_tree
def test_the_sdist_carries_licence_citation_and_changelog():
    manifest = (ROOT / "MANIFEST.in").read_text().split()
    for name in ("LICENSE", "CITATION.cff", "CHANGELOG.md"):
        assert name in manifest, name


def _fold(text):
    """ASCII spelling of names: Jäger -> Jaeger, Heß -> Hess."""
    text = text.replace("ä", "ae").replace("ö", "oe").replace("ü", "ue").replace("ß", "ss")
    return unicodedata.normalize("NFKD", text).encode("ascii", "ignore").decode()


#: "Greenwood 1985", "Mindlin & Deresiewicz (1953)", "Zienkiewicz and Zhu 1992",
#: "Antoine et al. 2006": a citation by name and year.
CITATION = re.compile(r"\b([A-Z][a-z]+(?:[ -](?:&|and)?[ ]?[A-Z][a-z]+)?)(?: et al\.)?,? \(?"
                      r"((?:18|19|20)\d\d)\b")
#: Capitalised words before a year that are not authors.
NOT_AUTHORS = {"Contact", "Mechanics", "Solids", "Springer", "Python", "January", "Level",
               "November"}


def _cited_in_the_project():
    """(name, year, where) for each author-year citation in the code, tests and docs."""
    found = []
    paths = [*ROOT.glob("hertz/*.[ch]"), *ROOT.glob("hertz/*.py"),
             *ROOT.glob("fem_validation/**/*.py"), *ROOT.glob("tests/*.py"),
             *(p for p in ROOT.glob("docs/**/*.md") if "_build" not in p.parts
               and "jupyter_execute" not in p.parts)]
    for path in paths:
        if path.name in ("test_project_files.py", "bibliography.md"):
            continue
        for match in CITATION.finditer(path.read_text(errors="replace")):
            names, year = match.group(1), match.group(2)
            surnames = [w for w in re.split(r"[ &-]+|\band\b", names)
                        if w and w[0].isupper() and w not in NOT_AUTHORS]
            if surnames:
                found.append((surnames[0], year, path.relative_to(ROOT).as_posix()))
    return found


@needs_source_tree
def test_every_work_cited_by_name_and_year_is_in_the_bibliography():
    bibliography = _fold((ROOT / "docs" / "bibliography.md").read_text())
    entries = re.findall(r"^\*\*(.+?)\*\*", bibliography, re.M)
    cited = _cited_in_the_project()
    assert len(cited) > 20  # the scan finds the citations at all
    missing = sorted({(name, year, where) for name, year, where in cited
                      if not any(name in e and year in e for e in entries)})
    assert missing == []


@needs_source_tree
def test_nothing_cites_a_references_file_the_project_does_not_hold():
    assert not (ROOT / "REFERENCES.md").exists()
    paths = [*ROOT.glob("hertz/*.[ch]"), *ROOT.glob("hertz/*.py"),
             *ROOT.glob("fem_validation/**/*.py"), *ROOT.glob("tests/*.py"),
             *ROOT.glob("docs/**/*.md"), *ROOT.glob("docs/*.py"), ROOT / "README.md"]
    citing = [p.relative_to(ROOT).as_posix() for p in paths
              if p.name != "test_project_files.py"
              and re.search(r"\bREFERENCES\b", p.read_text(errors="replace"))]
    assert citing == []


@needs_source_tree
def test_the_bibliography_is_in_the_site_and_the_source_is_linked():
    index = (ROOT / "docs" / "index.md").read_text()
    toctree = re.search(r"```\{toctree\}(.*?)```", index, re.S).group(1)
    assert "bibliography" in toctree.split()
    conf = (ROOT / "docs" / "conf.py").read_text()
    assert '"sphinx.ext.viewcode"' in conf
    assert re.search(r'myst_enable_extensions = \[[^\]]*"dollarmath"', conf)
