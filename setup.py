"""Build of the compiled core, hertz._ufuncs (the rest is in pyproject.toml).

One extension module from the C files split by concern: _kernel.c (the
ellipse solver), _contact_kernel.c (the contact formulas) and _ufuncs.c (the
numpy binding, which needs numpy's headers).
"""

import numpy
from setuptools import Extension, setup

SOURCES = ["hertz/_ufuncs.c", "hertz/_kernel.c", "hertz/_contact_kernel.c"]
HEADERS = ["hertz/_coefficients.h", "hertz/_kernel.h", "hertz/_contact_kernel.h"]

setup(
    ext_modules=[
        Extension(
            "hertz._ufuncs",
            sources=SOURCES,
            depends=HEADERS,
            include_dirs=[numpy.get_include()],
            extra_compile_args=["-fno-math-errno", "-fno-trapping-math", "-ffp-contract=off"],
        )
    ]
)
