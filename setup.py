"""Build of the compiled core, hertz._ufuncs, and of the package data (the rest is in
pyproject.toml).

One extension module from every C file in hertz/ (the ellipse solver, the contact formulas,
the numpy binding, ...), compiled with flags chosen per compiler so that every build gives
the same bits:

=====================================  =============================================
compiler (``build_ext`` sees)          floating-point flags
=====================================  =============================================
GCC, Clang, Apple Clang (x86_64,       ``-fno-fast-math -fno-math-errno
arm64), any other Unix-style ``cc``    -fno-trapping-math -ffp-contract=off``; the
                                       first three only if the compiler takes them,
                                       ``-ffp-contract=off`` always (no fused
                                       multiply-adds: GCC contracts by default, and
                                       Clang does on arm64 where FMA is baseline)
MSVC                                   ``/fp:precise`` (no ``/fp:fast``, no
                                       ``/fp:contract``, no ``/arch:AVX2``: x64 MSVC
                                       then emits no FMA)
=====================================  =============================================

The AVX2 code in hertz/_kernel.c and hertz/_contact_kernel.c is chosen by the
preprocessor, not here: GCC-style ``target_clones`` and the AVX2 start-only path with a
run-time CPU check on x86-64 Linux (GCC or Clang), the plain C path everywhere else (MSVC,
Apple Clang on Intel and arm64 Macs, aarch64). ``HERTZ_PLAIN=1`` in the
environment defines ``HERTZ_PLAIN`` and builds the plain path everywhere.

The geometry of fem_validation (meshes/*.geo, the place to read and edit it) is copied into
the build as fem_validation/meshes/*.geo, so that a wheel carries it.
"""

import os
import tempfile
from pathlib import Path

import numpy
from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.build_py import build_py

HERE = Path(__file__).resolve().parent
#: Paths relative to the project root, as setuptools wants them.
SOURCES = sorted(f"hertz/{p.name}" for p in (HERE / "hertz").glob("*.c"))
HEADERS = sorted(f"hertz/{p.name}" for p in (HERE / "hertz").glob("*.h"))
GEOMETRY = sorted(f"meshes/{p.name}" for p in (HERE / "meshes").glob("*.geo"))

#: Unix-style compilers: always (no contraction of a*b + c into a fused multiply-add).
UNIX_REQUIRED = ["-ffp-contract=off"]
#: Unix-style compilers: where accepted, in this order (-fno-fast-math first, so that a
#: -ffast-math from CFLAGS is undone and the next two still apply).
UNIX_OPTIONAL = ["-fno-fast-math", "-fno-math-errno", "-fno-trapping-math"]
MSVC_FLAGS = ["/fp:precise"]


def accepts(compiler, flag):
    """Whether ``compiler`` (a distutils CCompiler) compiles an empty C file with ``flag``."""
    with tempfile.TemporaryDirectory() as tmp:
        source = Path(tmp, "probe.c")
        source.write_text("int hertz_probe(void) { return 0; }\n")
        try:
            compiler.compile([str(source)], output_dir=tmp, extra_postargs=[flag])
        except Exception:  # CompileError, or the compiler missing altogether
            return False
    return True


def float_flags(compiler):
    """The floating-point flags for ``compiler`` (see the module docstring)."""
    if compiler.compiler_type == "msvc":
        return list(MSVC_FLAGS)
    return [flag for flag in UNIX_OPTIONAL if accepts(compiler, flag)] + UNIX_REQUIRED


class BuildExt(build_ext):
    """build_ext with the floating-point flags of the compiler it found."""

    def build_extensions(self):
        flags = float_flags(self.compiler)
        command = getattr(self.compiler, "compiler_so", None) or [self.compiler.compiler_type]
        print(f"hertz: building with {command[0]} ({self.compiler.compiler_type}), "
              f"floating-point flags: {' '.join(flags)}")
        for ext in self.extensions:
            ext.extra_compile_args = [*ext.extra_compile_args, *flags]
        super().build_extensions()


class BuildPy(build_py):
    """build_py that also puts meshes/*.geo into the build as fem_validation/meshes/*.geo.

    Editable installs read the package from the source tree and fem_validation finds
    meshes/ beside it, so nothing is copied there (and nothing is written into the tree).
    """

    def _geometry_targets(self):
        return [(src, os.path.join(self.build_lib, "fem_validation", "meshes",
                                   os.path.basename(src))) for src in GEOMETRY]

    def run(self):
        super().run()
        if getattr(self, "editable_mode", False):
            return
        if not GEOMETRY:
            raise FileNotFoundError("meshes/*.geo not found: fem_validation needs its geometry "
                                    "(build from a checkout or from the sdist)")
        for src, dst in self._geometry_targets():
            self.mkpath(os.path.dirname(dst))
            self.copy_file(src, dst, preserve_mode=False)

    def get_outputs(self, include_bytecode=True):
        outputs = super().get_outputs(include_bytecode)
        if getattr(self, "editable_mode", False):
            return outputs
        return outputs + [dst for _, dst in self._geometry_targets()]


def extension():
    """The extension module hertz._ufuncs (HERTZ_PLAIN=1 in the environment: plain C only)."""
    macros = [("HERTZ_PLAIN", None)] if os.environ.get("HERTZ_PLAIN", "") not in ("", "0") else []
    return Extension("hertz._ufuncs", sources=SOURCES, depends=HEADERS,
                     include_dirs=[numpy.get_include()], define_macros=macros)


if __name__ == "__main__":  # setuptools' build backend runs this file as __main__ too
    setup(ext_modules=[extension()], cmdclass={"build_ext": BuildExt, "build_py": BuildPy})
