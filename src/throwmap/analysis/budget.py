"""Guarding large analyses: estimate memory and time up front, refuse above a limit (issue 10, item 2).

A user-given size (a basin grid, a number of limit-set starts, a critical-point grid)
drives the cost of an analysis. Before the work starts, :func:`guard_work` estimates
its memory from the arrays it will hold (bytes per configuration) and its time from
a small sample of throws measured in the same run (:func:`seconds_per_throw`), and
refuses with one line that says how big it is and how to go bigger: raise the
limits (``max_memory`` in bytes, ``max_seconds``; on the command line
``--max-memory`` in GB and ``--max-time`` in s) or pass ``force=True`` (``--force``).
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..errors import InvalidStateError, shown
from .maps import ConfigMap

__all__ = ["DEFAULT_MAX_MEMORY", "DEFAULT_MAX_SECONDS", "seconds_per_throw", "guard_work", "check_limits",
           "human_bytes", "human_seconds"]

DEFAULT_MAX_MEMORY = 2e9
"""Most memory an analysis may plan to hold, bytes (2 GB), unless told otherwise."""
DEFAULT_MAX_SECONDS = 1800.0
"""Longest an analysis may plan to run, s (30 min), unless told otherwise."""
SAMPLE = 256
"""Configurations thrown once to measure the time per throw."""


def human_bytes(b: float) -> str:
    for unit, f in (("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if b >= f:
            return f"{b / f:.3g} {unit}"
    return f"{b:.0f} B"


def human_seconds(t: float) -> str:
    if t >= 3600:
        return f"{t / 3600:.3g} h"
    if t >= 60:
        return f"{t / 60:.3g} min"
    return f"{t:.3g} s"


def check_limits(max_memory, max_seconds, force) -> tuple[float, float, bool]:
    """Validate the limits: positive finite bytes and seconds, ``force`` a bool."""
    out = []
    for name, v in (("max_memory", max_memory), ("max_seconds", max_seconds)):
        if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)) or not (
                math.isfinite(float(v)) and float(v) > 0):
            raise InvalidStateError(name, f"must be a positive finite number, got {shown(v)}")
        out.append(float(v))
    if not isinstance(force, bool):
        raise InvalidStateError("force", f"must be True or False, got {shown(force)}")
    return out[0], out[1], force


def seconds_per_throw(cmap: ConfigMap, n: int = SAMPLE) -> float:
    """Seconds per configuration of one map step, measured on ``n`` configurations spread over the domain.

    A first call on a few configurations warms the kernels (compilation is not counted).
    """
    xs, ss = [], []
    per = max(2, n // max(1, len(cmap.sides)))
    for s in cmap.sides:
        xs.append(np.linspace(cmap.x_lo[s], cmap.x_hi[s], per + 1)[1:])
        ss.append(np.full(per, s, dtype=np.int64))
    x, s = np.concatenate(xs), np.concatenate(ss)
    cmap(x[:2], s[:2])
    t0 = time.perf_counter()
    cmap(x, s)
    return (time.perf_counter() - t0) / x.size


def guard_work(what: str, field: str, n_configs: int, bytes_per_config: float, max_memory: float,
               max_seconds: float, force: bool, *, throws_per_config: float = 0.0, cmap: ConfigMap | None = None,
               hint: str = "a coarser grid") -> dict:
    """Refuse work whose estimate exceeds the limits; return the estimate.

    Memory: ``n_configs × bytes_per_config``. Time (when ``cmap`` is given and
    ``throws_per_config`` > 0): ``n_configs × throws_per_config ×`` the time per throw
    measured now on a sample. Raises :class:`~throwmap.errors.InvalidStateError` on
    ``field`` with one line (size, estimates, limits, and how to go bigger) unless
    ``force``. Returns ``{"n_configs", "memory_bytes", "seconds", "seconds_per_throw"}``.
    """
    mem = float(n_configs) * float(bytes_per_config)
    est = {"n_configs": int(n_configs), "memory_bytes": mem, "seconds": math.nan, "seconds_per_throw": math.nan}
    how = (f"raise max_memory/max_seconds (CLI --max-memory GB, --max-time s), pass force=True (--force), "
           f"or use {hint}")
    if force:
        return est
    if mem > max_memory:
        raise InvalidStateError(field, f"{what} on {n_configs:,} configurations needs ≈ {human_bytes(mem)} of memory, "
                                       f"over the limit of {human_bytes(max_memory)}: {how}")
    if cmap is not None and throws_per_config > 0:
        t = seconds_per_throw(cmap)
        secs = float(n_configs) * throws_per_config * t
        est.update(seconds=secs, seconds_per_throw=t)
        if secs > max_seconds:
            raise InvalidStateError(field, f"{what} on {n_configs:,} configurations needs ≈ {human_seconds(secs)} "
                                           f"({throws_per_config:.3g} throws each at {1e6 * t:.3g} µs measured now), "
                                           f"over the limit of {human_seconds(max_seconds)}: {how}")
    return est
