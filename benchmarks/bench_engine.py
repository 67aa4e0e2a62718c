"""Benchmark: pymunk engine throws per second per core (and with all cores).

Throws ``--n`` random impulse throws of the canonical triangle (h = −0.01 m,
μ = 1.5, x uniform on random stable sides up to 0.45 m, ω ∈ [3, 7] rad/s) with
the default :class:`throwmap.engine.EngineSettings` (0.125 ms step near
contacts, exact free flight), first in one process (throws/s per core), then
over all cores with ``throw_batch(..., model="engine", workers=0)``. Also
reports steps and leaps per throw. The issue's measured anchor for a plain
pymunk loop is 260–440 throws/s per core. Usage::

    python benchmarks/bench_engine.py [--n 200] [--json bench_engine.json]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time

import numpy as np

import throwmap as tm
from throwmap.engine import engine_run


def cases(n: int, seed: int = 0):
    part = tm.triangle_30_60_90()
    rng = np.random.default_rng(seed)
    k = rng.integers(0, 3, n)
    x = np.array([rng.uniform(-part.uL[s] + 0.005, 0.45) for s in k])
    om = rng.uniform(3.0, 7.0, n)
    return part, x, k, om


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200)
    ap.add_argument("--json", type=str, default=None)
    args = ap.parse_args(argv)
    part, x, k, om = cases(args.n)
    arm = tm.Arm(h=-0.01, mu=1.5)
    engine_run(part, arm, float(x[0]), int(k[0]), float(om[0]))  # warm-up
    t0 = time.perf_counter()
    steps = leaps = sim_time = 0
    for i in range(args.n):
        r = engine_run(part, arm, float(x[i]), int(k[i]), float(om[i]))
        steps += r.n_steps
        leaps += r.n_leaps
        sim_time += r.t_end
    t_one = time.perf_counter() - t0
    t0 = time.perf_counter()
    tm.throw_batch(part, arm, x, k, om, model="engine", workers=0)
    t_all = time.perf_counter() - t0
    cores = os.cpu_count() or 1
    res = {
        "n": args.n, "cores": cores, "python": sys.version.split()[0], "machine": platform.machine(),
        "throws_per_s_one_core": args.n / t_one, "throws_per_s_all_cores": args.n / t_all,
        "steps_per_throw": steps / args.n, "leaps_per_throw": leaps / args.n,
        "simulated_s_per_throw": sim_time / args.n, "ms_per_throw": 1e3 * t_one / args.n,
    }
    print(f"engine benchmark: {args.n} throws, {cores} cores, Python {res['python']} ({res['machine']})")
    print(f"  one core : {res['throws_per_s_one_core']:8.1f} throws/s  ({res['ms_per_throw']:.2f} ms/throw)")
    print(f"  all cores: {res['throws_per_s_all_cores']:8.1f} throws/s")
    print(f"  per throw: {res['steps_per_throw']:.0f} pymunk steps, {res['leaps_per_throw']:.1f} exact-flight leaps, "
          f"{res['simulated_s_per_throw']:.3f} s simulated")
    print("  anchor (issue, plain pymunk loop): 260–440 throws/s per core")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(res, f, indent=2)
    return res


if __name__ == "__main__":
    main()
