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

and, for GCC alone (not Clang, whose ``-O2`` vectorises as its ``-O3`` does),
``-ftree-vectorize -fvect-cost-model=dynamic``: GCC's ``-O2`` (what Debian's and
Ubuntu's Python 3.12+ put in CFLAGS, so what ``pip install`` from source gets there)
vectorises with its "very cheap" cost model, which takes no loop whose count is not a
known multiple of the vector width, so every block loop of the kernels stayed scalar
(3-5x slower). These two flags decide which loops run on vectors, never a result.

The SIMD code paths are chosen by the preprocessor, not here (hertz/_kernel.h): on x86-64
Linux with GCC or Clang the block functions are compiled for AVX-512, AVX2 (with FMA) and
the baseline, and one is picked at run time for the processor; the plain C path
everywhere else (MSVC, Apple Clang on Intel and arm64 Macs, aarch64). ``HERTZ_PLAIN=1`` in
the environment defines ``HERTZ_PLAIN`` and builds the plain path everywhere.

The compiler, its version and the whole compile command are written into a header in the
build's temporary folder (``hertz_build_info.h``) for ``hertz._ufuncs.build_info()`` and
``hertz.show_config()``.

The geometry of fem_validation (meshes/*.geo, the place to read and edit it) is copied into
the build as fem_validation/meshes/*.geo, so that a wheel carries it.
"""

import os
import shlex
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
#: GCC only (not Clang): the vectoriser with its dynamic cost model, whatever -O level
#: CFLAGS give (see the module docstring).
GCC_VECTOR_FLAGS = ["-ftree-vectorize", "-fvect-cost-model=dynamic"]


def accepts(compiler, flag, text="int hertz_probe(void) { return 0; }\n"):
    """Whether ``compiler`` (a distutils CCompiler) compiles ``text`` (an empty C file) with
    ``flag``."""
    with tempfile.TemporaryDirectory() as tmp:
        source = Path(tmp, "probe.c")
        source.write_text(text)
        try:
            compiler.compile([str(source)], output_dir=tmp, extra_postargs=[flag])
        except Exception:  # CompileError, or the compiler missing altogether
            return False
    return True


#: Compiles with GCC only (Clang and the Intel compilers define __GNUC__ too).
GCC_ONLY = ("#if !defined(__GNUC__) || defined(__clang__) || defined(__INTEL_COMPILER) \\\n"
            "    || defined(__INTEL_LLVM_COMPILER)\n#error not GCC\n#endif\n"
            "int hertz_probe(void) { return 0; }\n")


def is_gcc(compiler):
    """Whether ``compiler`` is GCC itself (not Clang, Apple Clang or MSVC)."""
    return compiler.compiler_type != "msvc" and accepts(compiler, "-O2", GCC_ONLY)


def float_flags(compiler):
    """The floating-point flags for ``compiler`` (see the module docstring)."""
    if compiler.compiler_type == "msvc":
        return list(MSVC_FLAGS)
    return [flag for flag in UNIX_OPTIONAL if accepts(compiler, flag)] + UNIX_REQUIRED


def vector_flags(compiler):
    """The vectoriser flags for ``compiler``: GCC_VECTOR_FLAGS for GCC, none for others."""
    return list(GCC_VECTOR_FLAGS) if is_gcc(compiler) else []


def c_string(text):
    """``text`` as a C string literal (ASCII, other characters as ?)."""
    text = text.encode("ascii", "replace").decode("ascii")
    text = "".join(c if c.isprintable() else "?" for c in text)
    return '"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


def write_build_info(directory, command, flags):
    """hertz_build_info.h in ``directory``: the compile command and setup.py's flags."""
    os.makedirs(directory, exist_ok=True)
    path = Path(directory, "hertz_build_info.h")
    text = (f"#define HERTZ_BUILD_COMMAND {c_string(shlex.join(command))}\n"
            f"#define HERTZ_BUILD_FLAGS {c_string(shlex.join(flags))}\n")
    if not path.is_file() or path.read_text() != text:  # unchanged: no rebuild
        path.write_text(text)
    return str(directory)


class BuildExt(build_ext):
    """build_ext with the floating-point flags of the compiler it found."""

    def build_extensions(self):
        flags = float_flags(self.compiler)
        vector = vector_flags(self.compiler)
        command = getattr(self.compiler, "compiler_so", None) or [self.compiler.compiler_type]
        print(f"hertz: building with {command[0]} ({self.compiler.compiler_type}), "
              f"floating-point flags: {' '.join(flags)}"
              + (f", vectoriser flags: {' '.join(vector)}" if vector else ""))
        info = write_build_info(os.path.join(self.build_temp, "hertz_build_info"),
                                list(command), flags + vector)
        for ext in self.extensions:
            ext.extra_compile_args = [*ext.extra_compile_args, *flags, *vector]
            ext.include_dirs = [*ext.include_dirs, info]
            ext.define_macros = [*ext.define_macros, ("HERTZ_BUILD_INFO", None)]
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
