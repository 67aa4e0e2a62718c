"""Physics kernels: plain functions of floats and arrays (SI units), compiled with Numba.

No classes, no I/O, no validation: the public API in :mod:`throwmap.throws.throw`
validates once and calls these. Setting ``NUMBA_DISABLE_JIT=1`` runs them as
plain Python (slow, but debuggable).

Numba's on-disk cache (``cache=True``) is keyed on each function's own source
file only, so a kernel calling into an edited module would keep running stale
machine code. :mod:`~throwmap.kernels.numba_cache` registers a cache locator for
this package whose source stamp covers all its files; it reads and writes
nothing at import (the stamp is computed when a kernel is first called).
"""

from .numba_cache import install as _install_cache_locator

_install_cache_locator()
