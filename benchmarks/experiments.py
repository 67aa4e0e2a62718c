"""Benchmark: Monte Carlo experiments — trials/s and the projected time of 1,000 trials on 2 workers.

For each registered experiment (``--experiments``, default all) with its built-in
example config: run ``--n`` trials (seed 0) through :func:`throwmap.experiments.run_experiment`
on each worker count in ``--workers`` (default 1 and 2), after one warm-up trial in this
process, and report the wall time, trials/s and the time 1,000 trials would take at that
rate ("1,000 from CPU": the trials' CPU time spread over 2 cores, what an unloaded 2-core
machine would take whatever else shares this one). The same-run reference is one engine throw
(the triangle, h = −1 cm, length 0.6 m, μ = 0.8, from x = 0.15 m on side 1 at ω = 4 rad/s):
median of ``--repeat`` throws, so a
trial's cost (CPU time of this process and its worker processes per trial) reads in engine throws
whatever the machine and the number of workers. The guide's target: 1,000
single-part trials in ≤ 5 min on 2 cores.

Prints the machine and a table; ``--json PATH`` also writes the figures; ``--quick``
runs tiny sizes (the smoke test). Usage::

    python benchmarks/experiments.py [--experiments settle,feed] [--n 40] [--json experiments.json]
    python benchmarks/experiments.py --experiments feed --config examples/feed_recoil.toml --workers 2
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from pathlib import Path

import throwmap as tm
from throwmap.budget import Limits
from throwmap.experiments import experiment_names, get_experiment
from throwmap.experiments.base import trial_generator
from throwmap.experiments.runner import run_experiment

TARGET_S = 300.0
"""The guide's budget for 1,000 single-part trials on 2 cores, s."""
TARGET_TWO_PART_S = 600.0
"""The guide's budget for 1,000 two-part assembly trials on 2 cores, s."""
TWO_PART = ("assemble", "assemble-sequential", "assemble-serial")


def target_s(name: str) -> float:
    """The guide's budget for 1,000 trials of experiment ``name`` on 2 cores, s."""
    return TARGET_TWO_PART_S if name in TWO_PART else TARGET_S


def engine_throw_s(repeat: int) -> float:
    """Median wall time of one engine throw (s), the same-run reference."""
    part = tm.triangle_30_60_90(0.17)
    arm = tm.Arm(h=-0.01, length=0.6, mu=0.8)
    tm.throw(part, arm, 0.15, 1, 4.0, model="engine")  # warm-up
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        tm.throw(part, arm, 0.15, 1, 4.0, model="engine")
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def bench_experiment(name: str, n: int, workers: tuple[int, ...], ref_s: float, config: Path | None = None) -> dict:
    exp = get_experiment(name)
    if config is None:
        cfg = exp.config_type()
    else:
        from throwmap.experiments.base import read_config

        cfg = read_config(exp, config)
    exp.trial(cfg, 0, trial_generator(0, 0))  # warm-up (imports, caches)
    out = {"experiment": name, "config": None if config is None else str(config), "n": n, "runs": []}
    for w in workers:
        t, c0 = time.perf_counter(), os.times()
        r = run_experiment(name, cfg, n=n, seed=0, workers=w, limits=Limits(force=True))
        wall, c1 = time.perf_counter() - t, os.times()
        # CPU of this process and of its finished worker processes: the trials' cost whatever the load
        cpu = sum(getattr(c1, k) - getattr(c0, k) for k in ("user", "system", "children_user", "children_system"))
        rate = n / wall
        out["runs"].append({"workers": w, "wall_s": wall, "cpu_s": cpu, "trials_per_s": rate,
                            "projected_1000_s": 1000 / rate, "engine_throws_per_trial": cpu / n / ref_s,
                            "cpu_s_per_trial": cpu / n, "projected_1000_cpu_2_cores_s": 1000 * cpu / n / 2,
                            "success_rate": r.success_rate})
    return out


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--experiments", default=None, help="comma list (default: every registered experiment)")
    ap.add_argument("--n", type=int, default=40, help="trials per run")
    ap.add_argument("--workers", default="1,2", help="comma list of worker counts")
    ap.add_argument("--repeat", type=int, default=20, help="engine throws timed for the reference")
    ap.add_argument("--json", type=Path, default=None, help="also write the figures here")
    ap.add_argument("--quick", action="store_true", help="tiny sizes (smoke test)")
    ap.add_argument("--config", type=Path, default=None,
                    help="a config file for the (single) experiment, e.g. examples/feed_recoil.toml (default: built-in)")
    a = ap.parse_args(argv)
    if a.quick:
        a.n, a.repeat = 4, 2
    if a.n < 1 or a.repeat < 1:
        ap.error("--n and --repeat must be ≥ 1")
    names = tuple(s.strip() for s in a.experiments.split(",")) if a.experiments else experiment_names()
    if a.config is not None and len(names) != 1:
        ap.error("--config needs exactly one experiment (--experiments NAME)")
    workers = tuple(int(w) for w in a.workers.split(","))
    ref = engine_throw_s(a.repeat)
    machine = {"cpu_count": os.cpu_count(), "python": sys.version.split()[0], "throwmap": tm.__version__}
    print(f"machine: {machine['cpu_count']} cores, Python {machine['python']}, throwmap {machine['throwmap']}")
    print(f"reference: one engine throw (triangle, ω = 4 rad/s) = {1e3 * ref:.1f} ms (median of {a.repeat})")
    w = max(20, max(len(n) for n in names) + 2)
    print(f"{'experiment':<{w}}{'workers':>8}{'trials':>8}{'wall s':>9}{'trials/s':>10}{'1,000 trials':>15}"
          f"{'engine throws':>17}{'CPU s/trial':>12}{'1,000 from CPU':>16}  verdict (from CPU, 2 cores)")
    print(f"{'':<{w}}{'':>8}{'':>8}{'':>9}{'':>10}{'at this rate':>15}{'per trial (CPU)':>17}{'':>12}"
          f"{'on 2 cores':>16}  targets: ≤ {TARGET_S / 60:.0f} min one part, ≤ {TARGET_TWO_PART_S / 60:.0f} min two")
    results = []
    for name in names:
        res = bench_experiment(name, a.n, workers, ref, a.config)
        results.append(res)
        for run in res["runs"]:
            proj, proj_cpu = run["projected_1000_s"], run["projected_1000_cpu_2_cores_s"]
            verdict = ("meets" if proj_cpu <= target_s(name) else "misses") + f" ≤ {target_s(name) / 60:.0f} min"
            print(f"{name:<{w}}{run['workers']:>8}{a.n:>8}{run['wall_s']:>9.2f}{run['trials_per_s']:>10.2f}"
                  f"{proj / 60:>11.2f} min{run['engine_throws_per_trial']:>17.1f}{run['cpu_s_per_trial']:>12.3f}"
                  f"{proj_cpu / 60:>12.2f} min  {verdict}")
    data = {"machine": machine, "reference_engine_throw_s": ref, "experiments": results,
            "target_s": {r["experiment"]: target_s(r["experiment"]) for r in results}}
    if a.json is not None:
        a.json.write_text(json.dumps(data, indent=2) + "\n")
    return data


if __name__ == "__main__":
    main()
