"""Write the intersphinx inventories of docs/conf.py without network.

    python docs/_inventories/make_inventories.py

The build machine and CI reach package registries only, so intersphinx cannot
download numpy's, scipy's, dask's or Python's objects.inv. This script writes
one small inventory per project (the Sphinx inventory format, version 2) with
the objects these pages refer to and the pages where each project documents
them; docs/conf.py gives intersphinx these files and the projects' real base
URLs. To link a new object, add it to OBJECTS and re-run.
"""

from __future__ import annotations

import zlib
from pathlib import Path

HERE = Path(__file__).resolve().parent


def _generated(name: str, base: str = "reference/generated/") -> str:
    return f"{base}{name}.html#{name}"


# project: [(name, domain:role, uri relative to the project's base URL, display name)]
OBJECTS: dict[str, list[tuple[str, str, str, str]]] = {
    "python": [
        ("dataclasses.dataclass", "py:function",
         "library/dataclasses.html#dataclasses.dataclass", "-"),
        ("tomllib", "py:module", "library/tomllib.html#module-tomllib", "-"),
        ("float", "py:class", "library/functions.html#float", "-"),
        ("ValueError", "py:exception", "library/exceptions.html#ValueError", "-"),
        ("TypeError", "py:exception", "library/exceptions.html#TypeError", "-"),
    ],
    "numpy": [
        ("numpy.ndarray", "py:class", _generated("numpy.ndarray"), "-"),
        ("numpy.ufunc", "py:class", _generated("numpy.ufunc"), "-"),
        ("numpy.broadcast_to", "py:function", _generated("numpy.broadcast_to"), "-"),
        ("numpy.linspace", "py:function", _generated("numpy.linspace"), "-"),
        ("numpy.meshgrid", "py:function", _generated("numpy.meshgrid"), "-"),
        ("numpy.random.Generator", "py:class",
         "reference/random/generator.html#numpy.random.Generator", "-"),
        ("user/basics.broadcasting", "std:doc", "user/basics.broadcasting.html", "Broadcasting"),
        ("reference/ufuncs", "std:doc", "reference/ufuncs.html", "Universal functions (ufunc)"),
    ],
    "scipy": [
        ("scipy.special.ellipk", "py:data", _generated("scipy.special.ellipk"), "-"),
        ("scipy.special.ellipe", "py:data", _generated("scipy.special.ellipe"), "-"),
    ],
    "dask": [
        ("dask.array.Array", "py:class", "generated/dask.array.Array.html#dask.array.Array",
         "-"),
        ("dask.compute", "py:function", "api.html#dask.compute", "-"),
        ("dask.array.random.default_rng", "py:function",
         "generated/dask.array.random.default_rng.html#dask.array.random.default_rng", "-"),
        ("array", "std:doc", "array.html", "Dask Array"),
    ],
    # meshio has no Sphinx site: its README documents read/write and the Mesh class.
    "meshio": [
        ("meshio.read", "py:function", "#usage", "-"),
        ("meshio.Mesh", "py:class", "blob/main/src/meshio/_mesh.py", "-"),
    ],
}

VERSIONS = {"python": "3", "numpy": "stable", "scipy": "stable", "dask": "stable",
            "meshio": "5"}


def inventory(project: str, entries) -> bytes:
    header = (f"# Sphinx inventory version 2\n# Project: {project}\n"
              f"# Version: {VERSIONS[project]}\n"
              "# The remainder of this file is compressed using zlib.\n").encode()
    body = "".join(f"{name} {role} 1 {uri} {display}\n"
                   for name, role, uri, display in sorted(entries)).encode()
    return header + zlib.compress(body, 9)


def main() -> None:
    for project, entries in OBJECTS.items():
        path = HERE / f"{project}.inv"
        path.write_bytes(inventory(project, entries))
        print(f"wrote {path} ({len(entries)} objects)")


if __name__ == "__main__":
    main()
