"""Physics kernels: plain functions of floats and arrays (SI units), compiled with Numba.

No classes, no I/O, no validation: the public API in :mod:`throwmap.throws.throw`
validates once and calls these. Setting ``NUMBA_DISABLE_JIT=1`` runs them as
plain Python (slow, but debuggable).

Numba's on-disk cache (``cache=True``) is keyed on each function's own source
file only, so a kernel that calls into an edited module would keep running the
stale machine code. On import we therefore hash every kernel source and drop the
cache files when the hash changed.
"""

from __future__ import annotations

import hashlib
from pathlib import Path


def _invalidate_stale_numba_cache() -> None:
    here = Path(__file__).parent
    digest = hashlib.sha256()
    for src in sorted(here.glob("*.py")):
        digest.update(src.name.encode())
        digest.update(src.read_bytes())
    stamp_value = digest.hexdigest()
    cache = here / "__pycache__"
    stamp = cache / "kernels.sha256"
    try:
        if stamp.read_text() == stamp_value:
            return
    except OSError:
        pass
    try:
        cache.mkdir(exist_ok=True)
        for f in list(cache.glob("*.nbi")) + list(cache.glob("*.nbc")):
            f.unlink(missing_ok=True)
        stamp.write_text(stamp_value)
    except OSError:  # read-only install: numba falls back to its own cache locator
        pass


_invalidate_stale_numba_cache()
