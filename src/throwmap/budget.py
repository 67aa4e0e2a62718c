"""Guarding large work: estimate memory and time up front, refuse above a limit.

A user-given size (a number of throws ``n``, a grid ``n_x``, a basin grid, a number
of limit-set starts) drives the cost of a computation. Before the work starts,
:func:`guard_work` estimates its memory from the arrays it will hold (bytes per
unit of work) and its time from a few throws measured in the same run (a ``timer``
that returns seconds per throw), and refuses with one line that says how big it is
and how to go bigger: raise the limits (``max_memory`` in bytes, ``max_seconds``;
on the command line ``--max-memory`` in GB and ``--max-time`` in s) or pass
``force=True`` (``--force``). :func:`check_count` refuses counts no array can hold
(beyond a 64-bit index) whatever the limits.

The three limits travel as one value, :class:`Limits` (``limits=`` in every function that
guards its work; :data:`DEFAULT_LIMITS` when not given; :meth:`Limits.from_cli` from the
command line's options).

This module depends on nothing but :mod:`throwmap.errors`, so every layer (throws,
studies, analysis) can use it; :mod:`throwmap.analysis.budget` re-exports it with
its map-specific timer.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from .errors import InvalidStateError, shown

__all__ = ["DEFAULT_LIMITS", "DEFAULT_MAX_MEMORY", "DEFAULT_MAX_SECONDS", "Limits", "MAX_COUNT", "guard_work",
           "check_limits", "check_count", "cli_limits", "human_bytes", "human_seconds"]

DEFAULT_MAX_MEMORY = 2e9
"""Most memory a computation may plan to hold, bytes (2 GB), unless told otherwise."""
DEFAULT_MAX_SECONDS = 1800.0
"""Longest a computation may plan to run, s (30 min), unless told otherwise."""
MAX_COUNT = int(np.iinfo(np.int64).max)
"""Largest count of anything (throws, grid points) an array can index: 2^63 − 1."""


@dataclass(frozen=True, slots=True)
class Limits:
    """How much work a computation may plan before it is refused: ``max_memory`` (bytes, > 0),
    ``max_seconds`` (s, > 0), or ``force`` (no refusal; the estimate is still made).

    One value, passed as ``limits=`` wherever work is guarded (:func:`guard_work`); on the command line
    ``--max-memory`` (GB), ``--max-time`` (s) and ``--force`` (:meth:`from_cli`).
    """

    max_memory: float = DEFAULT_MAX_MEMORY
    max_seconds: float = DEFAULT_MAX_SECONDS
    force: bool = False

    def __post_init__(self):
        mem, secs, force = check_limits(self.max_memory, self.max_seconds, self.force)
        object.__setattr__(self, "max_memory", mem)
        object.__setattr__(self, "max_seconds", secs)
        object.__setattr__(self, "force", force)

    @classmethod
    def from_cli(cls, max_memory_gb, max_time, force) -> "Limits":
        """From the command line's ``--max-memory`` (GB), ``--max-time`` (s) and ``--force``; errors name
        ``max_memory`` / ``max_time`` (the options as typed)."""
        for name, v, unit in (("max_memory", max_memory_gb, "GB"), ("max_time", max_time, "s")):
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
                raise InvalidStateError(name, f"must be a positive finite number ({unit}), got {shown(v)}")
        return cls(float(max_memory_gb) * 1e9, float(max_time), bool(force))

    @classmethod
    def of(cls, limits) -> "Limits":
        """``limits`` itself, or :data:`DEFAULT_LIMITS` for None; anything else is refused on ``limits``."""
        if limits is None:
            return DEFAULT_LIMITS
        if not isinstance(limits, cls):
            raise InvalidStateError("limits", f"must be a throwmap.budget.Limits, got {type(limits).__name__}")
        return limits


def human_bytes(b: float) -> str:
    for unit, f in (("PB", 1e15), ("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if b >= f:
            return f"{b / f:.3g} {unit}"
    return f"{b:.0f} B"


def human_seconds(t: float) -> str:
    if t >= 86400:
        return f"{t / 86400:.3g} days"
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


def cli_limits(max_memory_gb, max_time, force) -> Limits:
    """:meth:`Limits.from_cli`: the limits of the command line's ``--max-memory`` (GB), ``--max-time`` (s) and
    ``--force``."""
    return Limits.from_cli(max_memory_gb, max_time, force)


def check_count(field: str, n, *, minimum: int = 0) -> int:
    """``n`` as an ``int``: an integer (not a bool) from ``minimum`` up to :data:`MAX_COUNT`.

    Raises :class:`~throwmap.errors.InvalidStateError` on ``field`` otherwise — one
    line, whatever the limits (no array can hold more than 2^63 − 1 items).
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
        raise InvalidStateError(field, f"must be an integer ≥ {minimum}, got {shown(n)}")
    n = int(n)
    if n < minimum:
        raise InvalidStateError(field, f"must be an integer ≥ {minimum}, got {n}")
    if n > MAX_COUNT:
        raise InvalidStateError(field, f"is too large: {shown(n, 30)} is over 2^63 − 1, the most any array can hold")
    return n


def guard_work(what: str, field: str, n_configs: int, bytes_per_config: float, limits: Limits | None = None, *,
               throws_per_config: float = 0.0, timer: Callable[[], float] | None = None, hint: str = "a coarser grid",
               unit: str = "configurations") -> dict:
    """Refuse work whose estimate exceeds the limits; return the estimate.

    Memory: ``n_configs × bytes_per_config`` (bytes). Time (when ``timer`` is given
    and ``throws_per_config`` > 0): ``n_configs × throws_per_config × timer()``, where
    ``timer()`` measures the seconds per throw now (called only if the memory fits and
    not ``limits.force``). Raises :class:`~throwmap.errors.InvalidStateError` on ``field``
    with one line (size, estimates, limits, and how to go bigger) unless ``limits.force``
    (``limits``: a :class:`Limits`, None for :data:`DEFAULT_LIMITS`).
    Returns ``{"n_configs", "memory_bytes", "seconds", "seconds_per_throw"}``.
    """
    limits = Limits.of(limits)
    max_memory, max_seconds = limits.max_memory, limits.max_seconds
    mem = float(n_configs) * float(bytes_per_config)
    est = {"n_configs": int(n_configs), "memory_bytes": mem, "seconds": math.nan, "seconds_per_throw": math.nan}
    how = (f"raise the limits, limits=Limits(max_memory=…, max_seconds=…) (CLI --max-memory GB, --max-time s), "
           f"pass limits=Limits(force=True) (--force), or use {hint}")
    if limits.force:
        return est
    if mem > max_memory:
        raise InvalidStateError(field, f"{what} on {n_configs:,} {unit} needs ≈ {human_bytes(mem)} of memory, "
                                       f"over the limit of {human_bytes(max_memory)}: {how}")
    if timer is not None and throws_per_config > 0:
        t = float(timer())
        secs = float(n_configs) * throws_per_config * t
        est.update(seconds=secs, seconds_per_throw=t)
        if secs > max_seconds:
            each = (f"{1e6 * t:.3g} µs per throw measured now" if unit == "throws" and throws_per_config == 1
                    else f"{throws_per_config:.3g} throws each at {1e6 * t:.3g} µs measured now")
            raise InvalidStateError(field, f"{what} on {n_configs:,} {unit} needs ≈ {human_seconds(secs)} "
                                           f"({each}), over the limit of {human_seconds(max_seconds)}: {how}")
    return est


DEFAULT_LIMITS = Limits()
"""2 GB and 30 min, not forced."""
