"""Compiling the numerical kernels ahead of their first use, and telling when a call is about to compile.

The exact models run as Numba kernels, compiled on a kernel's first call and kept on disk
(:mod:`throwmap.kernels.numba_cache`; ``NUMBA_CACHE_DIR`` moves the cache). A fresh checkout has no cache: its
first throw on the ``rigid_body`` model compiles about 130 functions (≈ 90 CPU-s), the built-in example about
200. :func:`compile_kernels` compiles them all at once — the groups of :data:`GROUPS` in parallel processes,
each by small calls of the public API (nothing is specialised by hand, so what is compiled is what a call
uses) — and ``make`` runs it at install (``throwmap compile``). :func:`cold` tells whether a model's throw kernel
still has to be compiled, so that a command can say so before a silent minute.
"""

from __future__ import annotations

import os
import time
from concurrent.futures import ProcessPoolExecutor, as_completed

__all__ = ["GROUPS", "compile_kernels", "cold"]


def _setup():
    from .system.arm import Arm
    from .system.catalogue import triangle_30_60_90

    return triangle_30_60_90(0.17), Arm(h=-0.01)


def _rigid_body() -> None:
    """Model "rigid_body" on a bare, tilted and walled arm: a throw, a serial batch, a trajectory (one automaton,
    ≈ 90 CPU-s: compiled once, in one process; the groups that follow it load it from the cache)."""
    import math

    import numpy as np

    from .system.arm import Arm
    from .system.fixtures import Wall
    from .throws.orbit_trajectory import throw_trajectory
    from .throws.throw import throw, throw_batch

    part, arm = _setup()
    walled, wall = Arm(h=-0.01, length=0.35), (Wall(height=0.05, mu=0.5),)
    throw(part, arm, 0.2, 0, 4.0, "rigid_body")
    throw(part, walled, 0.25, 2, 5.0, "rigid_body", fixtures=wall, alpha=-math.radians(10.0))
    throw_batch(part, arm, np.linspace(0.1, 0.3, 8), 0, 4.0, "rigid_body")
    throw_batch(part, walled, np.linspace(0.2, 0.3, 8), 2, 5.0, "rigid_body", fixtures=wall, alpha=-math.radians(10.0))
    throw_trajectory(part, arm, 0.2, 0, 4.0, "rigid_body")


def _rigid_body_parallel() -> None:
    """Model "rigid_body": the parallel batch (a batch of at least ``PARALLEL_MIN`` starts)."""
    import numpy as np

    from .kernels.rigid_body import PARALLEL_MIN
    from .throws.throw import throw_batch

    part, arm = _setup()
    throw_batch(part, arm, np.linspace(0.1, 0.3, PARALLEL_MIN + 1), 0, 4.0, "rigid_body")


def _recoil() -> None:
    """Model "rigid_body" thrown by the recoiling arm (the feeding experiment's throw)."""
    from .system.motion import RecoilThrow
    from .throws.throw import throw

    part, arm = _setup()
    throw(part, arm, 0.2, 0, 4.0, "rigid_body", realisation=RecoilThrow.for_release_rate(4.0))


def _paper() -> None:
    """Models "paper", "small_angle" and "small_angle2": a throw, serial and parallel batches, a trajectory, an
    orbit."""
    import numpy as np

    from .kernels import paper as kp
    from .kernels import small_angle as ks
    from .throws.orbit import iterate
    from .throws.orbit_trajectory import throw_trajectory
    from .throws.throw import throw, throw_batch

    part, arm = _setup()
    for model, pmin in (("paper", kp.PARALLEL_MIN), ("small_angle", ks.PARALLEL_MIN),
                        ("small_angle2", ks.PARALLEL_MIN)):
        throw(part, arm, 0.2, 0, 4.0, model)
        for n in (8, pmin + 1):
            throw_batch(part, arm, np.linspace(0.1, 0.3, n), 0, 4.0, model)
        iterate(part, arm, (0.2, 0), 4.0, n=3, model=model)
    throw_trajectory(part, arm, 0.2, 0, 4.0, "paper")


GROUPS = {"rigid_body": _rigid_body, "paper": _paper, "rigid_body_parallel": _rigid_body_parallel,
          "recoil": _recoil}
"""What :func:`compile_kernels` compiles, by small calls of the public API (the analysis, design and experiments
have no kernels of their own: they throw through these)."""
AFTER = {"rigid_body_parallel": "rigid_body", "recoil": "rigid_body"}
"""A group that starts only once another has ended: it calls that group's kernels, which it then loads from the
cache instead of compiling them a second time in parallel."""


def _group(name: str) -> float:
    import warnings

    t = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # regime notes of the small calls are not the user's
        GROUPS[name]()
    return time.perf_counter() - t


def _order() -> list:
    """The groups, each after the group it waits for (:data:`AFTER`)."""
    out: list = []
    while len(out) < len(GROUPS):
        out += [g for g in GROUPS if g not in out and AFTER.get(g, g) in out + [g]]
    return out


def compile_kernels(workers: int = 0, progress=None) -> dict:
    """Compile every group of :data:`GROUPS` in parallel processes (at most ``workers`` at once; 0: one per core;
    1: all in this process, in order), a group of :data:`AFTER` once the group it waits for has ended, and return
    the seconds each group took (a kernel already cached loads in milliseconds). ``progress(name, done, total)``
    is called as each group ends."""
    workers = min(len(GROUPS), workers or os.cpu_count() or 1)
    out: dict = {}
    if workers == 1:
        for name in _order():
            out[name] = _group(name)
            if progress is not None:
                progress(name, len(out), len(GROUPS))
        return out
    import multiprocessing

    with ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("spawn")) as pool:
        waiting = [g for g in _order() if g in AFTER]
        running = {pool.submit(_group, g): g for g in GROUPS if g not in AFTER}
        while running:
            fut = next(as_completed(running))
            name = running.pop(fut)
            out[name] = fut.result()
            if progress is not None:
                progress(name, len(out), len(GROUPS))
            for g in [g for g in waiting if AFTER[g] in out]:
                waiting.remove(g)
                running[pool.submit(_group, g)] = g
    return out


_KERNELS = {"rigid_body": ("throwmap.kernels.rigid_body", "throw_one_rigid_body"),
            "paper": ("throwmap.kernels.paper", "throw_one"),
            "small_angle": ("throwmap.kernels.small_angle", "throw_many_small_angle_serial"),
            "small_angle2": ("throwmap.kernels.small_angle", "throw_many_small_angle_serial")}
"""Each exact model's first kernel (module, name): compiled on the model's first throw."""


def cold(model: str = "rigid_body") -> bool:
    """Whether the first kernel of ``model`` (an exact model) has no compiled code on disk for the kernels as they
    are now (its first call compiles). False for the engines (no kernels) and when the cache cannot be read
    (nothing is claimed)."""
    spec = _KERNELS.get(model)
    if spec is None:
        return False
    try:
        import importlib

        kernel = getattr(importlib.import_module(spec[0]), spec[1])
        return not kernel._cache._cache_file._load_index()  # numba's index, empty when the sources changed since
    except Exception:  # a numba without these internals: say nothing
        return False
