"""Benchmark: the compiled throw map against the SciPy reference, in one run.

Measures, after warm-up (JIT caches loaded, first calls made):

(a) ``throwmap.testing.reference.reference_throw`` per throw on ``--n-reference`` throws of
    the canonical triangle (random x on random stable sides, ω ∈ [3, 6] rad/s);
(b) ``throw_batch`` throughput on ``--n`` throws from the same distribution, for
    model "paper" and "small_angle" (best of ``--repeat``);
(c) the latency of one ``throw()`` call, median over ``--n-single`` calls.

Prints machine information and a table (throws/s, µs/throw) with the two goals:
batch/reference ≥ 100× and a single ``throw()`` ≤ 30 µs. ``--json PATH`` also
writes the figures. Usage::

    python benchmarks/bench_throw.py [--n 1000000] [--json bench.json]
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import time

import numpy as np

import throwmap as tm
from throwmap.testing.reference import reference_throw

GOAL_RATIO = 100.0
"""Required speed-up of the batch (model "paper") over the reference."""
GOAL_SINGLE_US = 30.0
"""Required median latency of one ``throw()`` call, µs."""
H = -0.01  # m, arm height (paper's regime for the triangle)
OMEGA_RANGE = (3.0, 6.0)  # rad/s
X_MAX = 0.4  # m
X_MIN_MARGIN = 1e-3  # m above each side's x_min


def sample_starts(part, n, rng):
    """``n`` random starts ``(x, side, omega)``: a uniform stable side, x uniform above its x_min, ω uniform."""
    sides = np.asarray(part.stable_sides)[rng.integers(0, len(part.stable_sides), n)]
    x_min = -np.asarray(part.uL)[sides] + X_MIN_MARGIN
    x = x_min + (X_MAX - x_min) * rng.random(n)
    omega = rng.uniform(*OMEGA_RANGE, n)
    return x, sides, omega


def machine_info() -> dict:
    import numba
    import scipy

    try:
        usable = len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        usable = os.cpu_count()
    return {
        "platform": platform.platform(),
        "processor": platform.processor() or platform.machine(),
        "cpu_count": os.cpu_count(),
        "usable_cores": usable,
        "numba_threads": numba.get_num_threads(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "numba": numba.__version__,
        "throwmap": tm.__version__,
    }


def bench_reference(part, arm, x, sides, omega):
    """Seconds per throw of the reference, and its outcomes."""
    reference_throw(part, arm, float(x[0]), int(sides[0]), float(omega[0]))  # warm-up
    out = []
    t0 = time.perf_counter()
    for xi, si, oi in zip(x, sides, omega):
        out.append(reference_throw(part, arm, float(xi), int(si), float(oi)))
    return (time.perf_counter() - t0) / len(x), out


def bench_batch(part, arm, x, sides, omega, model, repeat):
    """Best wall time of ``throw_batch`` over ``repeat`` runs, and the last result."""
    tm.throw_batch(part, arm, x[:16], sides[:16], omega[:16], model=model)  # warm-up (JIT cache)
    best = float("inf")
    res = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = tm.throw_batch(part, arm, x, sides, omega, model=model)
        best = min(best, time.perf_counter() - t0)
    return best, res


def bench_single(part, arm, x, sides, omega, n_calls):
    """Median seconds of one ``throw()`` call (model "paper") over ``n_calls`` calls."""
    m = len(x)
    for i in range(min(m, 100)):  # warm-up
        tm.throw(part, arm, float(x[i]), int(sides[i]), float(omega[i]), model="paper")
    times = []
    args = [(float(x[i % m]), int(sides[i % m]), float(omega[i % m])) for i in range(n_calls)]
    clock = time.perf_counter
    for xi, si, oi in args:
        t0 = clock()
        tm.throw(part, arm, xi, si, oi, model="paper")
        times.append(clock() - t0)
    return statistics.median(times)


def agreement(ref_out, batch, n_ref, tol=1e-6):
    """How many reference throws the batch reproduces (same side and status, |Δx| < tol)."""
    ok = 0
    compared = 0
    for i, r in enumerate(ref_out[:n_ref]):
        if r["ill_conditioned"]:
            continue
        compared += 1
        status = tm.Status(int(batch.status[i])).label
        if status == r["status"] and int(batch.side[i]) == r["side"] and abs(float(batch.x[i]) - r["x"]) < tol:
            ok += 1
    return ok, compared


def run(n=1_000_000, n_reference=200, n_single=10_000, repeat=3, seed=0) -> dict:
    """Run the three measurements; returns the figures as a dict."""
    part = tm.triangle_30_60_90(0.17)
    arm = tm.Arm(h=H)
    rng = np.random.default_rng(seed)
    x, sides, omega = sample_starts(part, max(n, n_reference), rng)
    x_b, sides_b, omega_b = x[:n], sides[:n], omega[:n]

    s_ref, ref_out = bench_reference(part, arm, x[:n_reference], sides[:n_reference], omega[:n_reference])
    t_paper, res_paper = bench_batch(part, arm, x_b, sides_b, omega_b, "paper", repeat)
    t_small, _ = bench_batch(part, arm, x_b, sides_b, omega_b, "small_angle", repeat)
    s_single = bench_single(part, arm, x, sides, omega, n_single)
    agree, compared = agreement(ref_out, res_paper, min(n_reference, n))

    ref_rate = 1.0 / s_ref
    paper_rate = n / t_paper
    small_rate = n / t_small
    return {
        "machine": machine_info(),
        "part": part.name,
        "arm_h": H,
        "omega_range": list(OMEGA_RANGE),
        "seed": seed,
        "n_reference": n_reference,
        "n_batch": n,
        "n_single": n_single,
        "repeat": repeat,
        "reference_throws_per_s": ref_rate,
        "reference_us_per_throw": 1e6 * s_ref,
        "batch_paper_throws_per_s": paper_rate,
        "batch_paper_us_per_throw": 1e6 * t_paper / n,
        "batch_small_angle_throws_per_s": small_rate,
        "batch_small_angle_us_per_throw": 1e6 * t_small / n,
        "single_throw_us": 1e6 * s_single,
        "single_throws_per_s": 1.0 / s_single,
        "ratio_batch_paper_over_reference": paper_rate / ref_rate,
        "ratio_single_over_reference": s_ref / s_single,
        "goal_ratio": GOAL_RATIO,
        "goal_single_us": GOAL_SINGLE_US,
        "meets_ratio_goal": paper_rate / ref_rate >= GOAL_RATIO,
        "meets_single_goal": 1e6 * s_single <= GOAL_SINGLE_US,
        "reference_agreement": {"agree": agree, "compared": compared},
    }


def format_report(res: dict) -> str:
    m = res["machine"]
    lines = [
        f"throwmap {m['throwmap']} benchmark — {res['part']}, h = {res['arm_h']} m, "
        f"ω ∈ [{res['omega_range'][0]:g}, {res['omega_range'][1]:g}] rad/s, seed {res['seed']}",
        f"machine: {m['platform']} ({m['processor']}), {m['cpu_count']} cores "
        f"({m['usable_cores']} usable, {m['numba_threads']} numba threads)",
        f"python {m['python']}, numpy {m['numpy']}, scipy {m['scipy']}, numba {m['numba']}",
        "",
        f"{'method':<34}{'throws':>10}{'throws/s':>14}{'µs/throw':>12}",
        f"{'-' * 70}",
        f"{'reference (SciPy, per throw)':<34}{res['n_reference']:>10d}{res['reference_throws_per_s']:>14.4g}"
        f"{res['reference_us_per_throw']:>12.1f}",
        f"{'throw_batch, model paper':<34}{res['n_batch']:>10d}{res['batch_paper_throws_per_s']:>14.4g}"
        f"{res['batch_paper_us_per_throw']:>12.3f}",
        f"{'throw_batch, model small_angle':<34}{res['n_batch']:>10d}{res['batch_small_angle_throws_per_s']:>14.4g}"
        f"{res['batch_small_angle_us_per_throw']:>12.3f}",
        f"{'throw() single call (median)':<34}{res['n_single']:>10d}{res['single_throws_per_s']:>14.4g}"
        f"{res['single_throw_us']:>12.2f}",
        f"{'-' * 70}",
        f"batch (paper) / reference: {res['ratio_batch_paper_over_reference']:,.0f}×  "
        f"(goal ≥ {res['goal_ratio']:g}×: {'met' if res['meets_ratio_goal'] else 'NOT met'})",
        f"single throw(): {res['single_throw_us']:.2f} µs  "
        f"(goal ≤ {res['goal_single_us']:g} µs: {'met' if res['meets_single_goal'] else 'NOT met'})",
        f"batch reproduces the reference on {res['reference_agreement']['agree']}"
        f"/{res['reference_agreement']['compared']} sampled throws (|Δx| < 1e-6 m, same side and status)",
    ]
    return "\n".join(lines)


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=1_000_000, help="throws per throw_batch call (default 10^6)")
    ap.add_argument("--n-reference", type=int, default=200, help="reference throws timed (default 200)")
    ap.add_argument("--n-single", type=int, default=10_000, help="single throw() calls timed (default 10^4)")
    ap.add_argument("--repeat", type=int, default=3, help="throw_batch runs, best taken (default 3)")
    ap.add_argument("--seed", type=int, default=0, help="random seed of the sampled starts (default 0)")
    ap.add_argument("--json", metavar="PATH", default=None, help="also write the figures as JSON to PATH")
    args = ap.parse_args(argv)
    for name in ("n", "n_reference", "n_single", "repeat"):
        if getattr(args, name) < 1:
            ap.error(f"--{name.replace('_', '-')} must be ≥ 1")
    res = run(n=args.n, n_reference=args.n_reference, n_single=args.n_single, repeat=args.repeat, seed=args.seed)
    print(format_report(res))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as fh:
            json.dump(res, fh, indent=2)
            fh.write("\n")
    return res


if __name__ == "__main__":
    main(sys.argv[1:])
