"""Estimating an open-loop chain's work up front and refusing it above the limits (``throwmap chain throw``).

The sizes a user gives (the cell size, throws per cell, μ nodes, ``k_max``, Monte Carlo trials) drive:

* memory: per μ node three dense transition matrices of N × N states (the chain and its two halves) kept for
  the mixture, a working copy while a curve is computed, the throws of one μ node (:data:`BYTES_PER_THROW`
  each), the distributions of ``k_max + 2`` steps, and per Monte Carlo trial its state and ``k_max + 1``
  flags of the band;
* time: the chain's throws and the Monte Carlo's (at most ``trials × k_max``), at the time per throw measured
  now (``timer``), and the linear algebra (``k_max`` vector–matrix steps per μ node, a few N³ solves).

:func:`guard_chain` refuses with one line that names the field carrying the largest share and the estimate,
like :func:`throwmap.budget.guard_work`, unless ``force``.
"""

from __future__ import annotations

import math

from ..budget import Limits, human_bytes, human_seconds
from ..errors import InvalidStateError

__all__ = ["BYTES_PER_THROW", "BYTES_PER_TRIAL", "count_cells", "guard_chain"]

BYTES_PER_THROW = 400.0
"""Memory per throw of a chain's build (starts, ends, labels, targets, the batch's work arrays), bytes."""
BYTES_PER_TRIAL = 1000.0
"""Memory per Monte Carlo trial besides its band flags (its arm, state, hit), bytes."""
SECONDS_PER_FLOP = 1e-9
STEP_OVERHEAD_S = 5e-6

_HINTS = {"cell": "a larger --cell", "samples": "fewer --samples", "mu_nodes": "fewer --mu-nodes",
          "k_max": "a smaller --k-max", "trials": "fewer --trials"}


def count_cells(part, arm, size: float, breaks=()) -> int:
    """The number of cells :meth:`~throwmap.stochastic.cells.Cells.on_arm` will cut (at most; 0 where a side
    is unbounded: ``on_arm`` refuses that itself), without making them."""
    from ..system.starts import start_interval

    n = 0
    for k in part.stable_sides:
        lo, hi = start_interval(part, arm, k)
        if not (math.isfinite(lo) and math.isfinite(hi)) or not hi > lo:
            continue
        n += max(1, math.ceil((hi - lo) / size - 1e-9)) + sum(1 for b in breaks if lo < b < hi)
    return n


def guard_chain(*, n_cells: int, n_labels: int, samples: int, n_mu: int, k_max: int, trials: int,
                limits=None, timer=None) -> dict:
    """Refuse the chain's work above ``limits`` (:class:`~throwmap.budget.Limits`: memory in bytes, time in s)
    unless ``limits.force`` (module
    docstring); ``timer()``: seconds per throw, measured only when the memory fits. Returns the estimate
    ``{"memory_bytes", "seconds", "seconds_per_throw"}``."""
    limits = Limits.of(limits)
    max_memory, max_seconds, force = limits.max_memory, limits.max_seconds, limits.force
    N = n_cells + n_labels
    per_node = 3 * N * N * 8.0
    mats = n_mu * per_node + N * N * 8.0
    mem = {"mu_nodes" if 5 * per_node <= max_memory < mats else "cell": mats,
           "samples": n_cells * samples * BYTES_PER_THROW,
           "k_max": (k_max + 2) * N * 8.0 * 2,
           "trials": trials * (BYTES_PER_TRIAL + 9.0 * (k_max + 1))}
    total = sum(mem.values())
    est = {"memory_bytes": total, "seconds": math.nan, "seconds_per_throw": math.nan}
    how = "raise --max-memory (GB) / --max-time (s), pass --force, or use "
    sizes = (f"{n_cells:,} cells × {samples:,} throws × {n_mu:,} μ nodes, k ≤ {k_max:,}"
             + (f", {trials:,} Monte Carlo trials" if trials else ""))
    if force:
        return est
    if total > max_memory:
        field = max(mem, key=mem.get)
        raise InvalidStateError(field, f"the chain ({sizes}) needs ≈ {human_bytes(total)} of memory, over the "
                                       f"limit of {human_bytes(max_memory)}: {how}{_HINTS[field]}")
    t = float(timer()) if timer is not None else 0.0
    step = STEP_OVERHEAD_S + 2 * N * N * SECONDS_PER_FLOP
    secs = {"samples": n_cells * samples * n_mu * t,
            "trials": trials * k_max * t,
            "k_max": n_mu * (k_max + 2) * step,
            "cell": (3 * n_mu + 10) * N ** 3 * SECONDS_PER_FLOP}
    if n_mu / 5 > samples / 32:
        secs["mu_nodes"] = secs.pop("samples")
    est.update(seconds=sum(secs.values()), seconds_per_throw=t)
    if est["seconds"] > max_seconds:
        field = max(secs, key=secs.get)
        raise InvalidStateError(field, f"the chain ({sizes}) needs ≈ {human_seconds(est['seconds'])} "
                                       f"({1e6 * t:.3g} µs per throw measured now), over the limit of "
                                       f"{human_seconds(max_seconds)}: {how}{_HINTS[field]}")
    return est
