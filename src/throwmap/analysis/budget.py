"""Guarding large analyses: estimate memory and time up front, refuse above a limit.

A user-given size (a basin grid, a number of limit-set starts, a critical-point grid)
drives the cost of an analysis. Before the work starts, :func:`guard_work` estimates
its memory from the arrays it will hold (bytes per configuration) and its time from
a small sample of throws measured in the same run (:func:`seconds_per_throw`), and
refuses with one line that says how big it is and how to go bigger: raise the
limits (:class:`~throwmap.budget.Limits`: ``max_memory`` in bytes, ``max_seconds``; on the command
line ``--max-memory`` in GB and ``--max-time`` in s) or force it (``--force``).

The generic guard lives in :mod:`throwmap.budget` (shared with ``iterate`` and the
studies); this module re-exports it and adds the map-specific timer.
"""

from __future__ import annotations

import time

import numpy as np

from .. import budget as _budget
from ..budget import DEFAULT_LIMITS, Limits, check_count, human_bytes, human_seconds
from .maps import ConfigMap

__all__ = ["DEFAULT_LIMITS", "Limits", "seconds_per_throw", "guard_work", "check_count", "human_bytes",
           "human_seconds"]

TIMED_ABOVE = 10**6
"""Throws above which the work's time is estimated before it starts (below, only a time limit set by hand is
checked: measuring costs a few hundred throws)."""

SAMPLE = 256
"""Configurations thrown once to measure the time per throw."""


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


def guard_work(what: str, field: str, n_configs: int, bytes_per_config: float, limits: Limits | None = None, *,
               throws_per_config: float = 0.0, cmap: ConfigMap | None = None, hint: str = "a coarser grid",
               timed_above: float = TIMED_ABOVE) -> dict:
    """Refuse work whose estimate exceeds the limits; return the estimate.

    :func:`throwmap.budget.guard_work` with the time per throw measured on ``cmap``
    (:func:`seconds_per_throw`, a few hundred throws) when it is given and the work is worth timing: over
    ``timed_above`` throws, or any size when the time limit was set below the default 30 min (``--max-time``). Memory: ``n_configs × bytes_per_config``;
    time: ``n_configs × throws_per_config ×`` the measured time per throw. Raises
    :class:`~throwmap.errors.InvalidStateError` on ``field`` unless ``limits.force``. Returns
    ``{"n_configs", "memory_bytes", "seconds", "seconds_per_throw"}``.
    """
    limits = Limits.of(limits)
    worth = float(n_configs) * float(throws_per_config) > timed_above or limits.max_seconds < DEFAULT_LIMITS.max_seconds
    timer = None if cmap is None or not worth else (lambda: seconds_per_throw(cmap))
    return _budget.guard_work(what, field, n_configs, bytes_per_config, limits,
                              throws_per_config=throws_per_config, timer=timer, hint=hint)
