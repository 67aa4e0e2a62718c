"""Building the engine's C helper: cffi's generated module compiled with the interpreter's own compiler settings.

The helper is built on first use (no step at install): its C sources (this package's ``*.c``/``*.h``) and cffi's
glue are compiled with ``sysconfig``'s ``CC``/``CCSHARED``/``LDSHARED`` (``$CC``/``$LDSHARED`` win) into
``__pycache__`` beside them, or, where that is read-only, the user cache directory (``$XDG_CACHE_HOME/throwmap``,
``~/.cache/throwmap``). The file name carries a digest of the sources, the compiler flags and the cffi and Python
versions, so an edited source is rebuilt and a stale build never loaded. Builds go to a temporary file renamed into
place, so processes starting together (a worker pool) may each build but never load a half-written file.

Floating point: ``-ffp-contract=off`` keeps the compiler from fusing a multiply and an add (a fused result differs
from Python's in the last bit), and ``-fno-builtin-sin``/``cos``/``exp`` keep each call to libm's own function (the
one Python's ``math`` calls) instead of a merged ``sincos``; nothing is built with ``-ffast-math``. A successful build
removes the other builds of the helper in its directory (earlier sources).
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib.util
import io
import os
import shlex
import subprocess
import sys
import sysconfig
import tempfile

__all__ = ["SOURCES", "build", "cdef", "source"]

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCES = ("api.h", "chipmunk.h", "friction.c", "exact.c", "checks.c")
"""The helper's C text, concatenated in this order into one translation unit."""
CALLBACK = ('extern "Python" int tm_enumerate(void *py, int k, double *rows, double *u0, double m_inv, double i_inv, '
            "double scale, double *out);\n"
            'extern "Python" void tm_py_begin(void *py, cpArbiter *arb, int ia, int ib);\n'
            'extern "Python" void tm_py_separate(void *py, int ia, int ib);')
FLAGS = ("-O2", "-ffp-contract=off", "-fno-strict-aliasing", "-fno-builtin-sin", "-fno-builtin-cos", "-fno-builtin-exp")
"""Compiler flags: no fused multiply-add, and sin/cos/exp called as libm's functions (as Python's math module calls
them), never merged into one ``sincos`` call or expanded inline."""


def _read(name: str) -> str:
    with open(os.path.join(HERE, name), encoding="utf-8") as f:
        return f.read()


def cdef() -> str:
    """The declarations Python sees (``api.h`` and the callback into Python)."""
    return _read("api.h") + "\n" + CALLBACK + "\n"


def source() -> str:
    """The C source of the helper's one translation unit."""
    defines = "#define TM_HYPOT_FMA 1\n" if sys.version_info >= (3, 12) else ""
    return defines + "#include <stddef.h>\n" + "\n".join(_read(name) for name in SOURCES)


def _digest() -> str:
    import cffi

    h = hashlib.sha256()
    for part in (cdef(), source(), " ".join(FLAGS), cffi.__version__, sys.version, sysconfig.get_platform(),
                 os.environ.get("CC", ""), os.environ.get("LDSHARED", "")):
        h.update(part.encode())
        h.update(b"\0")
    return h.hexdigest()[:16]


def _cache_dirs() -> list[str]:
    dirs = [os.path.join(HERE, "__pycache__")]
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    dirs.append(os.path.join(base, "throwmap"))
    return dirs


def _load(name: str, path: str):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _compile(name: str, target: str) -> None:
    """Build module ``name`` at ``target`` (raises on failure)."""
    import cffi

    ffi = cffi.FFI()
    ffi.cdef(cdef())
    ffi.set_source(name, source())
    directory = os.path.dirname(target)
    os.makedirs(directory, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=directory, prefix=".build-") as tmp:
        c_file, o_file = os.path.join(tmp, name + ".c"), os.path.join(tmp, name + ".o")
        with contextlib.redirect_stdout(io.StringIO()):  # (cffi says "generating …")
            ffi.emit_c_code(c_file)
        cc = shlex.split(os.environ.get("CC") or sysconfig.get_config_var("CC") or "cc")
        ccshared = shlex.split(sysconfig.get_config_var("CCSHARED") or "-fPIC")
        include = sysconfig.get_paths()["include"]
        ldshared = shlex.split(os.environ.get("LDSHARED") or sysconfig.get_config_var("LDSHARED") or "")
        ldshared = ldshared or [*cc, "-shared"]
        so_file = os.path.join(tmp, name + (sysconfig.get_config_var("EXT_SUFFIX") or ".so"))
        for cmd in ([*cc, *ccshared, *FLAGS, "-I", include, "-c", c_file, "-o", o_file],
                    [*ldshared, o_file, "-o", so_file, "-lm"]):
            done = subprocess.run(cmd, capture_output=True, text=True, check=False)
            if done.returncode != 0:
                raise OSError(f"{' '.join(cmd[:1])} failed: {(done.stderr or done.stdout).strip()[-2000:]}")
        os.replace(so_file, target)
    suffix = sysconfig.get_config_var("EXT_SUFFIX") or ".so"
    for old in os.listdir(directory):  # builds of earlier sources (a process still using one keeps its mapping)
        if old.startswith("_throwmap_engine_") and old.endswith(suffix) and old != os.path.basename(target):
            with contextlib.suppress(OSError):
                os.remove(os.path.join(directory, old))


def build():
    """The compiled helper module (its ``ffi`` and ``lib``), built if needed; raises OSError/ImportError where it
    cannot be built or loaded."""
    name = "_throwmap_engine_" + _digest()
    suffix = sysconfig.get_config_var("EXT_SUFFIX") or ".so"
    for directory in _cache_dirs():
        path = os.path.join(directory, name + suffix)
        if os.path.exists(path):
            return _load(name, path)
    errors = []
    for directory in _cache_dirs():
        path = os.path.join(directory, name + suffix)
        try:
            _compile(name, path)
        except (OSError, subprocess.SubprocessError) as exc:
            errors.append(f"{directory}: {exc}")
            continue
        return _load(name, path)
    raise OSError("; ".join(errors))
