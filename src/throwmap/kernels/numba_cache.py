"""Numba's on-disk cache for the kernels, keyed on the whole kernels package.

Numba's own locators stamp a cached function with the hash of *its own* source
file only, so a kernel that calls into an edited module (``paper.throw_one`` →
``flight.touch_time``) would keep loading its stale machine code. The locator
here (:class:`KernelsCacheLocator`, registered first in numba's locator list on
import of :mod:`throwmap.kernels`) serves every function defined under the
kernels package and stamps it with one digest of *all* the package's ``.py``
files (subpackages included): editing any kernel source invalidates every
kernel's cache entry.

Nothing is read or written at import: the locator is built from path strings
(plus one ``access(2)`` check per kernels directory: is its ``__pycache__``
writable? if not, numba's user-wide cache directory is used, as numba does), the
stamp (:class:`PackageStamp`) is computed only when numba first compares or saves
a cache index (the first call of a kernel), and the cache directory is created
only when numba saves. Functions outside the package fall through to numba's
own locators. ``NUMBA_CACHE_DIR`` is honoured as numba does.
"""

from __future__ import annotations

import hashlib
import os
import time

import functools

from numba.core import config
from numba.core import caching
from numba.core.caching import _CacheLocator
from numba.misc.appdirs import AppDirs

__all__ = ["KernelsCacheLocator", "PackageStamp", "package_digest", "install"]

PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))
"""Root of the kernels package: every function defined below it uses this locator."""

_memo: dict = {}
_LOADED_NS = time.time_ns()
"""When this module (hence every kernel, imported after it) was loaded: sources edited later are not what runs."""


def _sources(root: str) -> list[str]:
    out = []
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if d != "__pycache__")
        out.extend(os.path.join(dirpath, f) for f in sorted(filenames) if f.endswith(".py"))
    return out


def package_digest(root: str = PACKAGE_DIR) -> bytes:
    """SHA-256 over the relative paths and contents of every ``.py`` file under ``root``.

    Memoised on the files' (mtime, size), so repeated calls cost one ``stat`` per file.
    A file modified after this process loaded the kernels makes the digest
    ``b"edited:"`` + a digest that no later process computes: code compiled now
    (from the sources as they were at import) is then never loaded from the cache.
    """
    files = _sources(root)
    stats = tuple((f, st.st_mtime_ns, st.st_size) for f in files for st in (os.stat(f),))
    key = (root, stats)
    digest = _memo.get(key)
    if digest is None:
        h = hashlib.sha256()
        for f in files:
            h.update(os.path.relpath(f, root).encode())
            h.update(b"\0")
            with open(f, "rb") as fh:
                h.update(fh.read())
            h.update(b"\0")
        digest = h.digest()
        if any(m > _LOADED_NS for _, m, _ in stats):
            digest = b"edited:" + digest + str(_LOADED_NS).encode()
        _memo.clear()
        _memo[key] = digest
    return digest


@functools.lru_cache(maxsize=None)
def _writable(directory: str) -> bool:
    """Whether ``directory/__pycache__`` can be written (or created), checked once per directory."""
    cache = os.path.join(directory, "__pycache__")
    if os.path.isdir(cache):
        return os.access(cache, os.W_OK | os.X_OK)
    return os.access(directory, os.W_OK | os.X_OK)


class PackageStamp:
    """A source stamp evaluated on use: equal to the package digest (bytes) at the time it is compared.

    Numba compares the stamp stored in a cache index with this one and pickles
    this one into the index it saves; it pickles as the digest's bytes.
    """

    __slots__ = ("root",)

    def __init__(self, root: str = PACKAGE_DIR):
        self.root = root

    def value(self) -> bytes:
        return package_digest(self.root)

    def __eq__(self, other):
        if isinstance(other, PackageStamp):
            other = other.value()
        return self.value() == other

    def __ne__(self, other):
        return not self.__eq__(other)

    def __hash__(self):
        return hash(self.value())

    def __reduce__(self):
        return bytes, (self.value(),)

    def __repr__(self):
        return f"PackageStamp({self.root!r})"


class KernelsCacheLocator(_CacheLocator):
    """In-tree cache (``<module dir>/__pycache__``, or under ``NUMBA_CACHE_DIR``) stamped by the package digest."""

    root = PACKAGE_DIR

    def __init__(self, py_func, py_file):
        self._py_file = py_file
        self._lineno = py_func.__code__.co_firstlineno
        if config.CACHE_DIR:
            self._cache_path = os.path.join(config.CACHE_DIR, self.get_suitable_cache_subpath(py_file))
        else:
            here = os.path.dirname(py_file)
            if _writable(here):
                self._cache_path = os.path.join(here, "__pycache__")
            else:  # a read-only install: numba's user-wide cache directory
                user = AppDirs(appname="numba", appauthor=False).user_cache_dir
                self._cache_path = os.path.join(user, self.get_suitable_cache_subpath(py_file))

    def ensure_cache_path(self):
        os.makedirs(self._cache_path, exist_ok=True)

    def get_cache_path(self):
        return self._cache_path

    def get_source_stamp(self):
        return PackageStamp(self.root)

    def get_disambiguator(self):
        return str(self._lineno)

    @classmethod
    def from_function(cls, py_func, py_file):
        path = os.path.abspath(py_file)
        if os.path.commonpath([path, cls.root]) != cls.root:
            return None
        return cls(py_func, path)


def install(locator=KernelsCacheLocator) -> None:
    """Put ``locator`` first in numba's locator list (once)."""
    impl = getattr(caching, "CacheImpl", None) or caching._CacheImpl  # named _CacheImpl before numba 0.61
    classes = impl._locator_classes
    if locator not in classes:
        classes.insert(0, locator)
