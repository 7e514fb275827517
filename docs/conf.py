"""Sphinx configuration of the hertz documentation.

Build: ``pip install -e ".[docs]"`` then
``sphinx-build -W --keep-going -b html docs docs/_build/html``.

Prose is MyST markdown; pages with ``{code-cell}`` blocks are MyST markdown notebooks
that myst-nb executes at every build (``nb_execution_mode = "force"``), so every number
and figure they show comes from code that ran; an error in a cell fails the build. The
API reference is autosummary over the public names, with numpydoc docstrings.

Intersphinx without network: the build machine and CI reach package registries only, so
intersphinx cannot download the projects' objects.inv. The inventories are local files,
docs/_inventories/*.inv, written by ``python docs/_inventories/make_inventories.py`` from
the list of objects these pages refer to, with each project's real documentation URL as
the base: links go to the published pages and the build needs no network. A missing
``{doc}`numpy:...``` target fails the build (-W); tests/test_docs.py checks that every
numpy, scipy, dask and meshio object the pages refer to is in the list and that the
committed files are the script's output, so the list cannot rot silently. Chosen over
downloading at build time (impossible here) and over committing the projects' full
inventories (they cannot be fetched here, and a stale copy would not say which links
the pages need). meshio publishes no Sphinx documentation: its entries point to its
README and source on GitHub.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
try:
    import hertz
except ImportError:  # not installed: the checkout's, built in place (setup.py build_ext -i)
    sys.path.insert(0, str(ROOT))
    import hertz

project = "hertz"
author = "the hertz developers"
copyright = "2026, the hertz developers"  # noqa: A001
release = hertz.__version__
version = release

extensions = [
    "myst_nb",
    "numpydoc",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.intersphinx",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",  # [source] links from the API reference to the code
]

source_suffix = {".rst": "restructuredtext", ".md": "myst-nb"}  # rst first: autosummary writes .rst
exclude_patterns = ["_build", "_inventories", "**.ipynb_checkpoints", "fem/*.md",
                    "speed_vs_error.md", "api/public_names.rst"]
root_doc = "index"

# MyST
myst_enable_extensions = ["colon_fence", "dollarmath", "deflist"]
myst_heading_anchors = 3

# myst-nb: execute every notebook page at every build, fail on any error.
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_timeout = 60
nb_execution_show_tb = True
nb_merge_streams = True

# autodoc / autosummary / numpydoc. The API reference lists every name of each module's
# __all__: write_api_names() writes api/public_names.rst (not committed, included by
# api/index.md) from them before the build, so a new public name is documented without
# touching the pages; autosummary writes a stub page for each (api/generated/).
API_MODULES = ("hertz", "hertz.methods", "fem_validation")
autosummary_imported_members = True
autodoc_typehints = "none"
autodoc_default_options = {"members": True, "inherited-members": False}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False



def _data_doc(module_name: str, name: str) -> str:
    """The ``#:`` comment of a module constant, from the module that defines it."""
    from sphinx.pycode import ModuleAnalyzer

    prefix = module_name.split(".")[0]
    for mod_name in sorted(m for m in sys.modules if m == prefix or m.startswith(prefix + ".")):
        mod = sys.modules[mod_name]
        if getattr(mod, name, None) is not getattr(sys.modules[module_name], name):
            continue
        try:
            docs = ModuleAnalyzer.for_module(mod_name).find_attr_docs()
        except Exception:  # noqa: BLE001  (a module without source: no comment)
            continue
        if ("", name) in docs:
            text = " ".join(line.strip() for line in docs[("", name)] if line.strip())
            return _ABSOLUTE.sub(r"\\|\1\\|", text)
    return ""


def api_names_rst() -> str:
    """reStructuredText of the API reference's lists: one section per module of
    API_MODULES, classes and functions in an autosummary table, constants as py:data."""
    import importlib
    import inspect

    out = []
    for module_name in API_MODULES:
        module = importlib.import_module(module_name)
        names = list(module.__all__)
        code = [n for n in names if inspect.isclass(getattr(module, n))
                or callable(getattr(module, n))]
        data = [n for n in names if n not in code]
        title = f"``{module_name}``"
        out += [title, "-" * len(title), "", f".. automodule:: {module_name}", "   :no-members:",
                "   :no-index:", "", f".. currentmodule:: {module_name}", "",
                ".. autosummary::", "   :toctree: generated", "   :nosignatures:", "",
                *(f"   {n}" for n in sorted(code, key=lambda n: (not n[0].isupper(), n))), ""]
        if data:
            out += ["Constants:", ""]
        for n in data:
            value = repr(getattr(module, n))
            out += [f".. py:data:: {module_name}.{n}"]
            if len(value) <= 120:
                out += [f"   :value: {value}"]
            out += ["", f"   {_data_doc(module_name, n) or 'See the module.'}", ""]
    return "\n".join(out) + "\n"


def write_api_names() -> None:
    path = DOCS / "api" / "public_names.rst"
    text = api_names_rst()
    if not path.exists() or path.read_text() != text:
        path.write_text(text)


autosummary_generate = ["api/public_names.rst"]  # written by write_api_names() below

# intersphinx from local inventories (see the module docstring).
_INV = DOCS / "_inventories"
intersphinx_mapping = {
    "python": ("https://docs.python.org/3/", str(_INV / "python.inv")),
    "numpy": ("https://numpy.org/doc/stable/", str(_INV / "numpy.inv")),
    "scipy": ("https://docs.scipy.org/doc/scipy/", str(_INV / "scipy.inv")),
    "dask": ("https://docs.dask.org/en/stable/", str(_INV / "dask.inv")),
    "meshio": ("https://github.com/nschloe/meshio/", str(_INV / "meshio.inv")),
}
intersphinx_timeout = 1

# The CalculiX how-to (howto/calculix.md) comes from another branch: where it is missing,
# its toctree entry is dropped (_drop_missing_calculix) and the tutorial's link to it is
# left out (an ``only:: calculix`` block).
HAVE_CALCULIX = (DOCS / "howto" / "calculix.md").exists()
if HAVE_CALCULIX and "tags" in globals():  # Sphinx injects ``tags``; a test imports this file
    tags.add("calculix")  # noqa: F821

html_theme = "furo"
html_title = f"hertz {release}"
html_static_path = []
html_show_sourcelink = False


_ABSOLUTE = re.compile(r"(?<![\\\w`])\|(?=[^\s|])([^|`]*?[^\s|\\])\|(?![\w`])")


def _escape_plain_math(app, what, name, obj, options, lines):
    """Docstrings write their math as plain text: absolute values ``|tau_yz|`` (which
    docutils reads as a substitution) and powers ``k'**2`` (after a quote, ``**`` would
    start bold text). Escape both."""
    for i, line in enumerate(lines):
        line = _ABSOLUTE.sub(r"\\|\1\\|", line)
        lines[i] = line.replace("'**", "'\\**")


_ONLY_CALCULIX = re.compile(r"^```\{only\} calculix\n.*?^```\n", re.M | re.S)


def _drop_missing_calculix(app, docname, source):
    if not HAVE_CALCULIX:
        if docname == "howto/index":
            source[0] = source[0].replace("\ncalculix\n", "\n")
        source[0] = _ONLY_CALCULIX.sub("", source[0])


def setup(app):
    app.connect("autodoc-process-docstring", _escape_plain_math)
    app.connect("source-read", _drop_missing_calculix)


write_api_names()
