"""Benchmark: batch throughput of the "rigid_body" kernel against the SciPy reference's rate.

Throws the canonical triangle (h = −0.01 m, random x on random stable sides,
ω ∈ [3, 6] rad/s, as ``bench_throw.py``) through
:func:`throwmap.kernels.rigid_body.throw_many_rigid_body` for several friction
coefficients (best of ``--repeat`` after a warm-up call) and prints throws/s and
the ratio to the SciPy reference's 421 throws/s (``--reference-rate``; the goal
is ≥ 100×). Usage::

    python benchmarks/bench_rigid_body.py [--n 200000] [--mu inf 1.5 0.5]
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
from throwmap.kernels.rigid_body import throw_many_rigid_body

REFERENCE_RATE = 421.0
"""Throws/s of :func:`throwmap.testing.reference.reference_throw` measured on this machine (bench_throw.py)."""
GOAL_RATIO = 100.0
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


def run_batch(part, arm, mu, x, sides, omega):
    n = x.size
    x_out = np.empty(n)
    side_out = np.empty(n, dtype=np.int64)
    status_out = np.empty(n, dtype=np.int64)
    rec_out = np.empty((n, C.NREC))
    throw_many_rigid_body(x, sides, omega, np.ones(n, dtype=np.bool_), arm.h, arm.g, arm.length_or_inf,
                          part.radius_of_gyration**2, mu, part.w, part.beta, part.d, part.uL, part.uR, part.ell,
                          part.stable, 1e-14, 100_000, 10_000, x_out, side_out, status_out, rec_out)
    return status_out, rec_out


def bench(n=200_000, mus=(math.inf, 1.5, 0.5), repeat=3, seed=0, reference_rate=REFERENCE_RATE) -> dict:
    part = tm.triangle_30_60_90(0.17)
    arm = tm.Arm(h=H)
    rng = np.random.default_rng(seed)
    x, sides, omega = sample_starts(part, n, rng)
    out = {"n": n, "threads": numba.get_num_threads(), "cpu_count": os.cpu_count(), "reference_rate": reference_rate,
           "rows": []}
    for mu in mus:
        run_batch(part, arm, mu, x[:16], sides[:16], omega[:16])  # warm-up (JIT cache)
        best = math.inf
        status = rec = None
        for _ in range(repeat):
            t0 = time.perf_counter()
            status, rec = run_batch(part, arm, mu, x, sides, omega)
            best = min(best, time.perf_counter() - t0)
        rate = n / best
        out["rows"].append({
            "mu": mu,
            "throws_per_s": rate,
            "us_per_throw": 1e6 * best / n,
            "ratio": rate / reference_rate,
            "ok": float(np.mean(status == C.OK)),
            "inconsistent": float(np.mean(status == C.INCONSISTENT)),
            "lift_off": float(np.mean(rec[:, C.N_LIFTOFFS] > 0)),
            "slip": float(np.mean(rec[:, C.N_SLIPS] > 0)),
        })
    return out


def format_report(res: dict) -> str:
    lines = [
        f"rigid_body batch: triangle_30_60_90(0.17), h = {H} m, ω ∈ [{OMEGA_RANGE[0]:g}, {OMEGA_RANGE[1]:g}] rad/s, "
        f"n = {res['n']}, {res['threads']} numba threads ({res['cpu_count']} cores)",
        f"{'mu':>6}{'throws/s':>14}{'µs/throw':>11}{'× reference':>13}{'ok':>8}{'slip':>8}{'lift':>8}{'Painlevé':>10}",
    ]
    for r in res["rows"]:
        lines.append(f"{r['mu']:>6g}{r['throws_per_s']:>14.4g}{r['us_per_throw']:>11.2f}{r['ratio']:>12.0f}×"
                     f"{r['ok']:>8.3f}{r['slip']:>8.3f}{r['lift_off']:>8.3f}{r['inconsistent']:>10.4f}")
    worst = min(r["ratio"] for r in res["rows"])
    lines.append(f"reference: {res['reference_rate']:g} throws/s; worst ratio {worst:.0f}× "
                 f"(goal ≥ {GOAL_RATIO:g}×: {'met' if worst >= GOAL_RATIO else 'NOT met'})")
    return "\n".join(lines)


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200_000, help="throws per batch (default 200000)")
    ap.add_argument("--mu", type=float, nargs="+", default=[math.inf, 1.5, 0.5], help="friction coefficients")
    ap.add_argument("--repeat", type=int, default=3, help="batch runs, best taken (default 3)")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--reference-rate", type=float, default=REFERENCE_RATE,
                    help=f"SciPy reference throws/s (default {REFERENCE_RATE:g})")
    args = ap.parse_args(argv)
    if args.n < 1 or args.repeat < 1:
        ap.error("--n and --repeat must be ≥ 1")
    res = bench(n=args.n, mus=tuple(args.mu), repeat=args.repeat, seed=args.seed, reference_rate=args.reference_rate)
    print(format_report(res))
    return res


if __name__ == "__main__":
    main(sys.argv[1:])
