"""Compile the Numba kernels once, before the test workers start.

Numba caches each kernel on disk (``throwmap.kernels.numba_cache``), but on a fresh clone the
cache is empty and every pytest-xdist worker would compile the same kernels for itself: on two
cores that doubles the largest cost of the suite. ``conftest.pytest_configure`` runs this
module in the controlling process, the chains of groups below in parallel processes (one per core at most); the
workers then load the kernels from the cache.

Each group makes the calls that compile one model's kernels through the public API, with the
argument types the tests use (a bare, tilted and walled arm, a batch below and above the
parallel threshold, a trajectory, a recoil arm).

    python tests/warmup.py [GROUP ...]      # the groups in this process, in order (all when none is named)
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np


def throw_trajectory(*a, **kw):
    from throwmap.throws.orbit_trajectory import throw_trajectory as tt

    return tt(*a, **kw)


def _setup():
    import throwmap as tm

    return tm, tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01)


def _batch_sizes(parallel_min: int) -> tuple[int, int]:
    return 8, parallel_min + 1


def paper():
    """Models "paper" and "small_angle": one throw, its trajectory, serial and parallel batches."""
    tm, part, arm = _setup()
    from throwmap.kernels import paper as kp
    from throwmap.kernels import small_angle as ks

    for model, pmin in (("paper", kp.PARALLEL_MIN), ("small_angle", ks.PARALLEL_MIN)):
        tm.throw(part, arm, 0.2, 0, 4.0, model)
        for n in _batch_sizes(pmin):
            tm.throw_batch(part, arm, np.linspace(0.1, 0.3, n), 0, 4.0, model)
    throw_trajectory(part, arm, 0.2, 0, 4.0, "paper")


def rigid_body():
    """Model "rigid_body" on a bare, tilted and walled arm: a throw, serial and parallel batches."""
    tm, part, arm = _setup()
    from throwmap.kernels.rigid_body import PARALLEL_MIN

    walled = tm.Arm(h=-0.01, length=0.35)
    wall = (tm.Wall(height=0.05, mu=0.5),)
    tm.throw(part, arm, 0.2, 0, 4.0, "rigid_body")
    tm.throw(part, walled, 0.25, 2, 5.0, "rigid_body", fixtures=wall, alpha=-math.radians(10.0))
    for n in _batch_sizes(PARALLEL_MIN):
        tm.throw_batch(part, arm, np.linspace(0.1, 0.3, n), 0, 4.0, "rigid_body")
    tm.throw_batch(part, walled, np.linspace(0.2, 0.3, 8), 2, 5.0, "rigid_body", fixtures=wall,
                   alpha=-math.radians(10.0))
    throw_trajectory(part, arm, 0.2, 0, 4.0, "rigid_body")


def reference():
    """The kernels' RK4 reference sticking phase, called as the kernel tests call it."""
    tm, part, arm = _setup()
    from throwmap.kernels import codes as C
    from throwmap.kernels import rigid_body as RB

    n = 8
    x, k, om = np.linspace(0.1, 0.3, n), np.zeros(n, np.int64), np.full(n, 4.0)
    out = np.empty(n), np.empty(n, np.int64), np.empty(n, np.int64), np.empty((n, C.NREC))
    for fn in (RB.throw_many_rigid_body_rk4, RB.throw_many_rigid_body):
        fn(x, k, om, np.ones(n, bool), RB.part_arrays(part),
           RB.arm_arrays(arm.h, arm.g, 0.0, arm.length_or_inf, arm.back, 1.5, RB.LAW_ROUTH), RB.run_limits(1e-14, 200, 200),
           *out)


def moving():
    """Model "rigid_body" on a moving arm: the recoil arm's throw and its hand-over to the automaton."""
    tm, part, arm = _setup()
    from throwmap.system.motion import RecoilThrow

    tm.throw(part, arm, 0.2, 0, 4.0, "rigid_body", realisation=RecoilThrow.for_release_rate(4.0))


def bench():
    """``benchmarks/bench_throw.py``'s own kernels (its reference integrator), at the sizes its test uses."""
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "benchmarks" / "bench_throw.py"
    spec = importlib.util.spec_from_file_location("bench_throw", path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # as the test loads it: Numba's cache then names an importable module
    spec.loader.exec_module(mod)
    mod.main(["--n", "2000", "--n-reference", "5", "--n-single", "50", "--repeat", "1"])


GROUPS = {"rigid_body": rigid_body, "reference": reference, "moving": moving, "paper": paper, "bench": bench}

CHAINS = (("rigid_body", "reference", "moving"), ("paper", "bench"))
"""Groups run in one process, in order: "reference" and "moving" call the automaton "rigid_body" compiles (run
apart they would compile it again). The two chains take about as long (≈ 160 s and ≈ 135 s of one core)."""


def warm(chains=CHAINS, workers: int | None = None, stream=sys.stderr) -> float:
    """Run each chain of groups in its own process, at most ``workers`` at once (default: the cores; one worker
    runs them all in one process); returns the seconds taken. A group that fails is reported and left to the tests."""
    workers = max(1, workers or os.cpu_count() or 1)
    chains = [tuple(c) for c in chains]
    if workers == 1:
        chains = [tuple(g for c in chains for g in c)]
    here = os.path.abspath(__file__)

    def run(chain):
        p = subprocess.run([sys.executable, here, *chain], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        if p.returncode:
            tail = p.stderr.strip().splitlines()[-1:] or ["?"]
            print(f"warm-up of {', '.join(chain)} failed (the tests compile it themselves): {tail[0]}", file=stream)

    t0 = time.perf_counter()
    with ThreadPoolExecutor(min(workers, len(chains))) as pool:
        list(pool.map(run, chains))
    return time.perf_counter() - t0


if __name__ == "__main__":
    for n in sys.argv[1:] or list(GROUPS):
        GROUPS[n]()
