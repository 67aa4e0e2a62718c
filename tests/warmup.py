"""Compile the Numba kernels once, before the test workers start.

Numba caches each kernel on disk (``throwmap.kernels.numba_cache``), but on a fresh clone the
cache is empty and every pytest-xdist worker would compile the same kernels for itself: on two
cores that doubles the largest cost of the suite. ``conftest.pytest_configure`` runs this
module in the controlling process, the chains of groups below in parallel processes (one per core at most); the
workers then load the kernels from the cache.

The models' groups are the library's own (:mod:`throwmap.warmup`, what ``throwmap compile`` runs: a bare,
tilted and walled arm, batches below and above the parallel threshold, a trajectory, a recoil arm); the tests add
the kernels' RK4 reference and the throw benchmark's own kernels.

    python tests/warmup.py [GROUP ...]      # the groups in this process, in order (all when none is named)
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

import numpy as np


def _setup():
    import throwmap as tm

    return tm, tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01)


def paper():
    """Models "paper", "small_angle" and "small_angle2": the library's own warm-up group (throwmap.warmup)."""
    from throwmap import warmup

    warmup.GROUPS["paper"]()


def rigid_body():
    """Model "rigid_body" on a bare, tilted and walled arm and the recoil arm: the library's own warm-up group."""
    from throwmap import warmup

    for group in ("rigid_body", "rigid_body_parallel", "recoil"):
        warmup.GROUPS[group]()


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


GROUPS = {"rigid_body": rigid_body, "reference": reference, "paper": paper, "bench": bench}

CHAINS = (("rigid_body", "reference"), ("paper", "bench"))
"""Groups run in one process, in order: "reference" calls the automaton "rigid_body" compiles (run apart it would
compile it again). The two chains take about as long (≈ 160 s and ≈ 135 s of one core)."""


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
