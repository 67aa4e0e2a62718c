"""The kernels' Numba cache: stamped by the whole package, and nothing written at ``import throwmap``."""

import os
import subprocess
import sys
import textwrap
from pathlib import Path

import throwmap.kernels.numba_cache as nc

INIT = """
from throwmap.kernels.numba_cache import KernelsCacheLocator, install
import os

class Locator(KernelsCacheLocator):
    root = os.path.dirname(os.path.abspath(__file__))

if os.environ.get("TINY_LOCATOR", "1") == "1":
    install(Locator)
"""
CALLEE = """
from numba import njit

@njit(cache=True)
def f():
    return {value}
"""
CALLER = """
from numba import njit
from .callee import f

@njit(cache=True)
def g():
    return f() + 10
"""
RUN = "import tiny.caller as c; print(c.g(), c.g.stats.cache_hits.get(c.g.signatures[0], 0))"


def _env(root, locator):
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CACHE_DIR", "NUMBA_DISABLE_JIT")}
    env["PYTHONPATH"] = os.pathsep.join([str(root)] + sys.path)
    env["TINY_LOCATOR"] = "1" if locator else "0"
    env["PYTHONDONTWRITEBYTECODE"] = "1"  # Python's own .pyc check misses a same-size edit within the second
    return env


def _run(root, locator):
    out = subprocess.run([sys.executable, "-c", RUN], env=_env(root, locator), capture_output=True, text=True,
                         check=True)
    value, hits = out.stdout.split()
    return int(value), int(hits)


def _package(tmp_path, value):
    pkg = tmp_path / "tiny"
    pkg.mkdir(exist_ok=True)
    (pkg / "__init__.py").write_text(textwrap.dedent(INIT))
    (pkg / "caller.py").write_text(textwrap.dedent(CALLER))
    _edit(pkg, value)
    return pkg


def _edit(pkg, value):
    callee = pkg / "callee.py"
    callee.write_text(textwrap.dedent(CALLEE.format(value=value)))


def test_editing_a_callee_recompiles_its_caller(tmp_path):
    """With the package locator, a fresh process sees the edited callee through the cached caller."""
    pkg = _package(tmp_path, 1)
    assert _run(tmp_path, locator=True) == (11, 0)  # compiled and saved
    assert _run(tmp_path, locator=True) == (11, 1)  # loaded from the cache: caching is on
    assert list((pkg / "__pycache__").glob("caller.g-*.nbi"))
    _edit(pkg, 2)
    assert _run(tmp_path, locator=True) == (12, 0)  # the caller's entry is stale: recompiled


def test_a_source_edited_after_import_is_not_cached_as_fresh(tmp_path):
    """Code compiled from sources as imported, saved after an edit, is not loaded by the next process."""
    pkg = _package(tmp_path, 1)
    code = ("import tiny.caller as c, pathlib, os; p = pathlib.Path(c.__file__).with_name('callee.py'); "
            "p.write_text(p.read_text().replace('return 1', 'return 2')); print(c.g())")
    out = subprocess.run([sys.executable, "-c", code], env=_env(tmp_path, True), capture_output=True, text=True,
                         check=True)
    assert out.stdout.split() == ["11"]  # the callee as imported
    assert "return 2" in (pkg / "callee.py").read_text()
    assert _run(tmp_path, locator=True) == (12, 0)


def test_numba_default_locator_keeps_the_stale_caller(tmp_path):
    """The failure the locator prevents: numba's own stamp covers only the caller's file."""
    pkg = _package(tmp_path, 1)
    assert _run(tmp_path, locator=False) == (11, 0)
    _edit(pkg, 2)
    assert _run(tmp_path, locator=False) == (11, 1)  # stale machine code of the old callee


def test_stamp_covers_every_source_of_the_package(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "a.py").write_text("x = 1\n")
    (tmp_path / "sub" / "b.py").write_text("y = 1\n")
    stamp = nc.PackageStamp(str(tmp_path))
    before = stamp.value()
    assert stamp == before and isinstance(before, bytes)
    (tmp_path / "sub" / "b.py").write_text("y = 2\n")
    assert stamp != before
    import pickle

    assert pickle.loads(pickle.dumps(stamp)) == stamp.value()  # pickled as the digest


WATCH = """
import os, sys
roots = [os.path.abspath(p) for p in sys.argv[1:]]
bad = []
WRITE = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_APPEND | os.O_TRUNC

def hook(event, args):
    if event == "open" and args and isinstance(args[0], (str, bytes, os.PathLike)):
        path, mode, flags = args[0], args[1], args[2]
        writes = (mode is not None and any(c in str(mode) for c in "wax+")) or (flags & WRITE)
        if writes:
            bad.append(("open", os.fsdecode(path)))
    elif event in ("os.mkdir", "os.remove", "os.rename", "os.replace", "os.rmdir", "os.truncate"):
        bad.append((event, str(args[0])))

sys.addaudithook(hook)
import throwmap
import throwmap.kernels.numba_cache as nc
assert not nc._memo, "the package digest was computed at import"
print(repr(bad))
"""


def test_import_throwmap_writes_nothing():
    """``import throwmap`` opens no file for writing, makes or removes none, and hashes no source."""
    kernels = Path(nc.PACKAGE_DIR)
    out = subprocess.run([sys.executable, "-B", "-c", WATCH, str(kernels)], capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "[]", out.stdout
