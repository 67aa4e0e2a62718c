"""Benchmark: the analysis layer — critical points, limit sets and a 10⁶-configuration basin map.

For the canonical triangle (hypotenuse 0.17 m, h = −0.01 m, ω = 4 rad/s: one band on all
three sides) and each analytic model (``--models``, default paper and rigid_body),
after warm-up (JIT caches loaded, first calls made):

(1) :func:`throwmap.analysis.critical_points`, all three sides: median wall time over
    ``--repeat`` calls, ms, and the map evaluations it used;
(2) :func:`throwmap.analysis.limit_set` with the default caps: median wall time over
    ``--repeat-limit`` calls, and the throws it used;
(3) :func:`throwmap.analysis.basins` on ``--grid`` configurations per side (default
    333 334, i.e. 10⁶ in all) with the cell method: wall time, throws (every map
    evaluation, counted), throws/s, the exact-orbit check's agreement on ``--n-check``
    configurations, and the certificate.

Prints the machine (CPU cores, numba threads) and a table; ``--json PATH`` also writes
the figures; ``--quick`` runs tiny sizes (for the smoke test). Usage::

    python benchmarks/bench_analysis.py [--grid 333334] [--json bench_analysis.json]
"""

from __future__ import annotations

import argparse
from pathlib import Path
import json
import statistics
import sys
import time


import throwmap as tm
from throwmap.analysis import ConfigMap, RecurrenceCaps, ThrowMap, basins, critical_points, limit_set

H = -0.01  # m, arm height (paper's regime for the triangle)
OMEGA = 4.0  # rad/s: one band attractor on all three sides
MODELS = ("paper", "rigid_body")
GRID_FULL = 333_334  # configurations per side: 10⁶ in all on the triangle's three stable sides


class CountingMap(ConfigMap):
    """A configuration map that counts the physical throws it is asked for (map evaluations × throws per step)."""

    def __init__(self, inner: ConfigMap):
        self.inner = inner
        self.sides = inner.sides
        self.x_lo = inner.x_lo
        self.x_hi = inner.x_hi
        self.throws_per_step = inner.throws_per_step
        self.label = inner.label
        self.throws = 0

    def step(self, x, side):
        self.throws += x.size * self.throws_per_step
        return self.inner.step(x, side)

    def describe(self) -> dict:
        return self.inner.describe()


def machine_info() -> dict:
    """The machine description :mod:`bench_throw` prints (loaded from beside this file)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("bench_throw", Path(__file__).with_name("bench_throw.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.machine_info()


def _timed(fn, repeat: int):
    """Median and all wall times (s) of ``repeat`` calls, and the last result."""
    times, res = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), times, res


def bench_critical(part, arm, model: str, repeat: int) -> dict:
    critical_points(part, arm, OMEGA, model)  # warm-up
    med, times, cp = _timed(lambda: critical_points(part, arm, OMEGA, model), repeat)
    return {"median_ms": 1e3 * med, "min_ms": 1e3 * min(times), "repeat": repeat, "map_evaluations": cp.n_throws,
            "r_m": {str(s): cp.r[s] for s in cp.sides}, "l_m": {str(s): cp.l[s] for s in cp.sides},
            "l_method": cp.l_method}


def bench_limit(part, arm, model: str, repeat: int) -> dict:
    caps = RecurrenceCaps()  # the defaults, recorded with the figures
    limit_set(part, arm, OMEGA, model, n_starts=4)  # warm-up
    counter = CountingMap(ThrowMap(part, arm, OMEGA, model))

    def run():
        counter.throws = 0
        return limit_set(counter, caps=caps)

    med, times, ls = _timed(run, repeat)
    return {"median_s": med, "min_s": min(times), "repeat": repeat, "throws": counter.throws,
            "throws_per_s": counter.throws / med, "kind": ls.kind, "n_attractors": len(ls.attractors),
            "n_starts": ls.n_starts, "transient_used": ls.transient_used, "caps": ls.recurrence_caps.to_dict()}


def bench_basins(part, arm, model: str, grid: int, n_check: int, seed: int) -> dict:
    basins(part, arm, OMEGA, model, grid=50, method="cells", n_check=5, n_seeds=4)  # warm-up
    counter = CountingMap(ThrowMap(part, arm, OMEGA, model))
    t0 = time.perf_counter()
    b = basins(counter, grid=grid, method="cells", n_check=n_check, rng=seed)
    wall = time.perf_counter() - t0
    return {"grid_per_side": grid, "n_configs": b.n_configs, "wall_s": wall, "throws": counter.throws,
            "throws_per_s": counter.throws / wall, "configs_per_s": b.n_configs / wall,
            "check_n": b.check.get("n", 0), "check_agreement": b.check.get("agreement", float("nan")),
            "n_exact_finish": b.check.get("n_exact_finish", 0), "unique": b.certificate.unique,
            "fractions": {str(k): v for k, v in b.fractions.items()}, "max_throws_to_reach": int(b.throws.max()),
            "statement": b.certificate.statement}


def run(models=MODELS, repeat=5, repeat_limit=3, grid=GRID_FULL, n_check=1000, seed=0) -> dict:
    part = tm.triangle_30_60_90(0.17)
    arm = tm.Arm(h=H)
    out = {"machine": machine_info(), "part": part.name, "arm_h": H, "omega": OMEGA, "seed": seed,
           "models": list(models), "critical_points": {}, "limit_set": {}, "basins": {}}
    for model in models:
        out["critical_points"][model] = bench_critical(part, arm, model, repeat)
        out["limit_set"][model] = bench_limit(part, arm, model, repeat_limit)
        out["basins"][model] = bench_basins(part, arm, model, grid, n_check, seed)
    return out


def format_report(res: dict) -> str:
    m = res["machine"]
    lines = [
        f"throwmap {m['throwmap']} analysis benchmark — {res['part']}, h = {res['arm_h']} m, "
        f"ω = {res['omega']:g} rad/s, seed {res['seed']}",
        f"machine: {m['platform']} ({m['processor']}), {m['cpu_count']} cores "
        f"({m['usable_cores']} usable, {m['numba_threads']} numba threads)",
        f"python {m['python']}, numpy {m['numpy']}, numba {m['numba']}",
        "",
        "(1) critical_points, all sides",
        f"{'model':<12}{'median ms':>11}{'min ms':>10}{'repeats':>9}{'map evals':>11}  l from",
    ]
    for model, r in res["critical_points"].items():
        lines.append(f"{model:<12}{r['median_ms']:>11.1f}{r['min_ms']:>10.1f}{r['repeat']:>9d}"
                     f"{r['map_evaluations']:>11d}  {r['l_method']}")
    lines += ["", "(2) limit_set, default caps",
              f"{'model':<12}{'median s':>10}{'min s':>9}{'repeats':>9}{'throws':>11}{'throws/s':>12}  result"]
    for model, r in res["limit_set"].items():
        lines.append(f"{model:<12}{r['median_s']:>10.3f}{r['min_s']:>9.3f}{r['repeat']:>9d}{r['throws']:>11d}"
                     f"{r['throws_per_s']:>12.4g}  {r['kind']} from {r['n_starts']} starts "
                     f"(transient {r['transient_used']})")
    lines += ["", "(3) basins, method cells",
              f"{'model':<12}{'configs':>10}{'wall s':>9}{'throws':>11}{'throws/s':>12}{'exact check':>20}"
              f"{'exact finish':>14}  certificate"]
    for model, r in res["basins"].items():
        check = f"{100 * r['check_agreement']:.2f} % of {r['check_n']}" if r["check_n"] else "-"
        lines.append(f"{model:<12}{r['n_configs']:>10d}{r['wall_s']:>9.2f}{r['throws']:>11d}"
                     f"{r['throws_per_s']:>12.4g}{check:>20}{r['n_exact_finish']:>14d}  "
                     f"{'unique' if r['unique'] else 'not unique'}")
    return "\n".join(lines)


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--models", nargs="+", default=list(MODELS), choices=["paper", "small_angle", "small_angle2",
                                                                          "rigid_body"])
    ap.add_argument("--repeat", type=int, default=5, help="critical_points calls, median taken (default 5)")
    ap.add_argument("--repeat-limit", type=int, default=3, help="limit_set calls, median taken (default 3)")
    ap.add_argument("--grid", type=int, default=GRID_FULL,
                    help=f"basin grid, configurations per side (default {GRID_FULL}: 10⁶ in all)")
    ap.add_argument("--n-check", type=int, default=1000, help="exact orbits checking the cell method (default 1000)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--quick", action="store_true", help="tiny sizes, one repeat (smoke test)")
    ap.add_argument("--json", type=str, default=None, help="also write the figures to this JSON file")
    args = ap.parse_args(argv)
    if args.quick:
        args.repeat, args.repeat_limit, args.grid, args.n_check = 1, 1, 2000, 50
    if args.repeat < 1 or args.repeat_limit < 1 or args.grid < 2 or args.n_check < 0:
        ap.error("--repeat and --repeat-limit must be ≥ 1, --grid ≥ 2, --n-check ≥ 0")
    res = run(models=tuple(args.models), repeat=args.repeat, repeat_limit=args.repeat_limit, grid=args.grid,
              n_check=args.n_check, seed=args.seed)
    print(format_report(res))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump(res, fh, indent=2, default=float)
    return res


if __name__ == "__main__":
    main(sys.argv[1:])
