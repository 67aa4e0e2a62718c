"""Benchmark: batch throughput of the "rigid_body" kernel, closed-form vs RK4 sticking phase, and critical points.

Throws the canonical triangle (h = −0.01 m, random x on random stable sides,
ω ∈ [3, 6] rad/s, as ``bench_throw.py``) through
:func:`throwmap.kernels.rigid_body.throw_many_rigid_body` (closed-form sticking
phase, the default) and :func:`~throwmap.kernels.rigid_body.throw_many_rigid_body_rk4`
(the former RK4 sticking phase, "before"), same throws, same run, for several
friction coefficients (best of ``--repeat`` after a warm-up call). Prints
throws/s of both, their ratio, the agreement of the two (same status and side,
median |Δx|), and the ratio to the SciPy reference
(:func:`throwmap.testing.reference.reference_throw`), whose rate is measured in the
same run on ``--n-reference`` of the same starts (the goal is ≥ 100×; a rate typed
in from another run or machine would make the ratio meaningless). The batches
are timed on the parallel kernel, as a large batch runs. Then the median wall time of
:func:`throwmap.analysis.critical_points` on that triangle at ω = 4 rad/s, all
sides, model "rigid_body" (``--repeat-critical`` calls after a warm-up; the
goal is ≤ 10 ms). Usage::

    python benchmarks/bench_rigid_body.py [--n 200000] [--mu inf 1.5 0.5] [--n-reference 200]
"""

from __future__ import annotations

import argparse
import math
import os
import sys
import time

import numba
import numpy as np

import throwmap as tm
from throwmap.kernels import codes as C
import statistics

from throwmap.kernels.rigid_body import (LAW_ROUTH, arm_arrays, part_arrays, run_limits, throw_many_rigid_body,
                                        throw_many_rigid_body_rk4)

GOAL_RATIO = 100.0
GOAL_CRITICAL_MS = 10.0
OMEGA_CRITICAL = 4.0  # rad/s
H = -0.01  # m
OMEGA_RANGE = (3.0, 6.0)  # rad/s
X_MAX = 0.4  # m
X_MIN_MARGIN = 1e-3  # m


def sample_starts(part, n, rng):
    sides = np.asarray(part.stable_sides)[rng.integers(0, len(part.stable_sides), n)]
    x_min = -np.asarray(part.uL)[sides] + X_MIN_MARGIN
    x = x_min + (X_MAX - x_min) * rng.random(n)
    omega = rng.uniform(*OMEGA_RANGE, n)
    return x, sides.astype(np.int64), omega


def run_batch(part, arm, mu, x, sides, omega, kernel=throw_many_rigid_body):
    n = x.size
    x_out = np.empty(n)
    side_out = np.empty(n, dtype=np.int64)
    status_out = np.empty(n, dtype=np.int64)
    rec_out = np.empty((n, C.NREC))
    kernel(x, sides, omega, np.ones(n, dtype=np.bool_), part_arrays(part),
           arm_arrays(arm.h, arm.g, 0.0, arm.length_or_inf, arm.back, mu, LAW_ROUTH),  # no wall, as the model passes it
           run_limits(1e-14, 100_000, 10_000), x_out, side_out, status_out, rec_out)
    return x_out, side_out, status_out, rec_out


def best_time(fn, repeat):
    """Best wall time (s) of ``repeat`` calls, and the last result."""
    best, res = math.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = fn()
        best = min(best, time.perf_counter() - t0)
    return best, res


def bench_reference(part, arm, x, sides, omega):
    """Throws/s of the SciPy reference on these starts, measured now (after one warm-up throw)."""
    from throwmap.testing.reference import reference_throw

    reference_throw(part, arm, float(x[0]), int(sides[0]), float(omega[0]))
    t0 = time.perf_counter()
    for xi, si, oi in zip(x, sides, omega):
        reference_throw(part, arm, float(xi), int(si), float(oi))
    return len(x) / (time.perf_counter() - t0)


def bench_critical(part, arm, repeat):
    """Median and min wall time (ms) of critical_points, model "rigid_body", after a warm-up call."""
    from throwmap.analysis import critical_points

    critical_points(part, arm, OMEGA_CRITICAL, "rigid_body")
    times = []
    cp = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        cp = critical_points(part, arm, OMEGA_CRITICAL, "rigid_body")
        times.append(time.perf_counter() - t0)
    return {"median_ms": 1e3 * statistics.median(times), "min_ms": 1e3 * min(times), "repeat": repeat,
            "map_evaluations": cp.n_throws}


def bench(n=200_000, mus=(math.inf, 1.5, 0.5), repeat=3, seed=0, n_reference=200, repeat_critical=5) -> dict:
    part = tm.triangle_30_60_90(0.17)
    arm = tm.Arm(h=H)
    rng = np.random.default_rng(seed)
    x, sides, omega = sample_starts(part, n, rng)
    m = min(n_reference, n)
    reference_rate = bench_reference(part, arm, x[:m], sides[:m], omega[:m])
    out = {"n": n, "threads": numba.get_num_threads(), "cpu_count": os.cpu_count(), "reference_rate": reference_rate,
           "n_reference": m, "rows": []}
    for mu in mus:
        for kernel in (throw_many_rigid_body, throw_many_rigid_body_rk4):  # warm-up (JIT cache)
            run_batch(part, arm, mu, x[:16], sides[:16], omega[:16], kernel)
        best_rk4, (xb, sb, stb, _rb) = best_time(lambda: run_batch(part, arm, mu, x, sides, omega,
                                                                   throw_many_rigid_body_rk4), repeat)
        best, (xo, so, status, rec) = best_time(lambda: run_batch(part, arm, mu, x, sides, omega), repeat)
        same = (so == sb) & (status == stb)
        rate = n / best
        out["rows"].append({
            "mu": mu,
            "throws_per_s": rate,
            "us_per_throw": 1e6 * best / n,
            "throws_per_s_rk4": n / best_rk4,
            "speedup": best_rk4 / best,
            "same_pct": 100.0 * float(same.mean()),
            "dx_median_m": float(np.median(np.abs(xo - xb)[same])) if same.any() else math.nan,
            "ratio": rate / reference_rate,
            "ok": float(np.mean(status == C.OK)),
            "inconsistent": float(np.mean(status == C.INCONSISTENT)),
            "lift_off": float(np.mean(rec[:, C.N_LIFTOFFS] > 0)),
            "slip": float(np.mean(rec[:, C.N_SLIPS] > 0)),
        })
    if repeat_critical > 0:
        out["critical_points"] = bench_critical(part, arm, repeat_critical)
    return out


def format_report(res: dict) -> str:
    lines = [
        f"rigid_body batch: triangle_30_60_90(0.17), h = {H} m, ω ∈ [{OMEGA_RANGE[0]:g}, {OMEGA_RANGE[1]:g}] rad/s, "
        f"n = {res['n']}, {res['threads']} numba threads ({res['cpu_count']} cores)",
        "sticking phase: 'exact' closed form (default) vs 'rk4' (before), same throws, same run",
        f"{'mu':>6}{'exact /s':>12}{'µs/throw':>10}{'rk4 /s':>12}{'speedup':>9}{'same %':>9}{'med |Δx| m':>12}"
        f"{'× reference':>13}{'ok':>7}{'slip':>7}{'lift':>7}{'Painlevé':>10}",
    ]
    for r in res["rows"]:
        lines.append(f"{r['mu']:>6g}{r['throws_per_s']:>12.4g}{r['us_per_throw']:>10.2f}{r['throws_per_s_rk4']:>12.4g}"
                     f"{r['speedup']:>8.2f}×{r['same_pct']:>9.3f}{r['dx_median_m']:>12.2g}{r['ratio']:>12.0f}×"
                     f"{r['ok']:>7.3f}{r['slip']:>7.3f}{r['lift_off']:>7.3f}{r['inconsistent']:>10.4f}")
    worst = min(r["ratio"] for r in res["rows"])
    lines.append(f"reference (SciPy, measured in this run on {res['n_reference']} throws): "
                 f"{res['reference_rate']:.4g} throws/s; worst ratio {worst:.0f}× "
                 f"(goal ≥ {GOAL_RATIO:g}×: {'met' if worst >= GOAL_RATIO else 'NOT met'})")
    cp = res.get("critical_points")
    if cp:
        lines.append(f"critical_points (ω = {OMEGA_CRITICAL:g} rad/s, all sides, rigid_body): median "
                     f"{cp['median_ms']:.1f} ms, min {cp['min_ms']:.1f} ms over {cp['repeat']} calls, "
                     f"{cp['map_evaluations']} map evaluations (goal ≤ {GOAL_CRITICAL_MS:g} ms: "
                     f"{'met' if cp['median_ms'] <= GOAL_CRITICAL_MS else 'NOT met'})")
    return "\n".join(lines)


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200_000, help="throws per batch (default 200000)")
    ap.add_argument("--mu", type=float, nargs="+", default=[math.inf, 1.5, 0.5], help="friction coefficients")
    ap.add_argument("--repeat", type=int, default=3, help="batch runs, best taken (default 3)")
    ap.add_argument("--repeat-critical", type=int, default=5,
                    help="critical_points calls, median taken (default 5; 0: skip)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--n-reference", type=int, default=200,
                    help="throws of the SciPy reference timed in this run for the ratio (default 200)")
    args = ap.parse_args(argv)
    if args.n < 1 or args.repeat < 1 or args.repeat_critical < 0 or args.n_reference < 1:
        ap.error("--n, --repeat and --n-reference must be ≥ 1, --repeat-critical ≥ 0")
    res = bench(n=args.n, mus=tuple(args.mu), repeat=args.repeat, seed=args.seed, n_reference=args.n_reference,
                repeat_critical=args.repeat_critical)
    print(format_report(res))
    return res


if __name__ == "__main__":
    main(sys.argv[1:])
