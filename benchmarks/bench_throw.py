"""Benchmark: the compiled throw map against the SciPy reference, in one run.

Measures, after warm-up (JIT caches loaded, first calls made):

(a) ``throwmap.testing.reference.reference_throw`` per throw on ``--n-reference`` throws of
    the canonical triangle (random x on random stable sides, ω ∈ [3, 6] rad/s);
(b) ``throw_batch`` throughput on ``--n`` throws from the same distribution, for
    model "paper" and "small_angle" (best of ``--repeat`` after one full-size warm-up
    call, whose time is also shown: its first touch of the ~0.2 GB output arrays costs
    page faults that later calls, reusing the allocator's memory, do not pay);
(c) the latency of one ``throw()`` call, median over ``--n-single`` calls;
(d) the per-throw cost of the "paper" kernel by phase, on one thread: kernels that
    stop after the release setup, after the first contact (Eq. 3), after the impact
    (Eq. 4), and the whole throw (pivot/landing cascade); with the mean number of
    first-contact steps; and the batch kernel alone (``throw_many``, no API checks).

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

import math

import numpy as np
from numba import njit

import throwmap as tm
from throwmap.kernels import codes as C
from throwmap.kernels.flight import gap, gap_constants, release_state, touch_time
from throwmap.kernels.impact import plastic_impact
from throwmap.kernels.paper import _throw, throw_many
from throwmap.kernels.roll import side_angles
from throwmap.models.paper import PaperOptions
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
    """Best wall time of ``throw_batch`` over ``repeat`` runs after a full-size warm-up call, the last result,
    and the warm-up call's time (it includes the first touch of freshly mapped output memory)."""
    tm.throw_batch(part, arm, x[:16], sides[:16], omega[:16], model=model)  # JIT cache
    t0 = time.perf_counter()
    res = tm.throw_batch(part, arm, x, sides, omega, model=model)
    cold = time.perf_counter() - t0
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = tm.throw_batch(part, arm, x, sides, omega, model=model)
        best = min(best, time.perf_counter() - t0)
    return best, res, cold


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


@njit(cache=True)
def _phases(x, side, omega, h, g, length, back, rho2, w, beta, d, uL, uR, ell, stable, tol, max_iter, max_impacts,
            n_samples, stop, count_steps):
    """Run the "paper" kernel's phases on every start, stopping after phase ``stop`` (0 release, 1 first
    contact, 2 impact, 3 whole throw); returns a checksum and the total number of first-contact steps."""
    nv = w.shape[0]
    work = np.empty((4, nv))
    rec = np.empty(C.NREC)
    ta_j, tb_j = side_angles(d, uL, uR)
    traj = np.empty((0, 4))
    tags = np.empty(0, np.int64)
    ts = np.zeros(8)
    acc = 0.0
    steps = 0
    for i in range(x.shape[0]):
        if stop == 3:
            acc += _throw(x[i], side[i], omega[i], h, g, 0.0, length, back, rho2, w, beta, d, uL, uR, ell, stable, tol,
                          max_iter, max_impacts, n_samples, ta_j, tb_j, work, rec, traj, tags, ts)[0]
            continue
        x0 = x[i]
        om = omega[i]
        dk = d[side[i]]
        vx, vy0, _ = release_state(x0, dk, h, om)
        pu = work[0]
        pv = work[1]
        c0 = work[2]
        b = work[3]
        cb = math.cos(beta[side[i]])
        sb = math.sin(beta[side[i]])
        for j in range(nv):
            pu[j] = cb * w[j, 0] - sb * w[j, 1]
            pv[j] = sb * w[j, 0] + cb * w[j, 1]
            b[j] = om * (x0 + pu[j])
        gap_constants(dk, pv, ell, c0)
        if stop == 0:
            acc += c0[0] + b[0]
            continue
        t, jc = touch_time(c0, b, pu, pv, vy0, om, g, ell, -1, 0.0, tol, max_iter)
        if count_steps:
            steps += flight_steps(c0, b, pu, pv, vy0, om, g, ell, tol, max_iter)
        if stop == 1:
            acc += t
            continue
        cp = math.cos(om * t)
        sp = math.sin(om * t)
        rx = cp * pu[jc] - sp * pv[jc]
        ry = sp * pu[jc] + cp * pv[jc]
        vxp, vyp, wp = plastic_impact(vx, vy0 - g * t, om, rx, ry, rho2)
        acc += wp + math.atan2(-ry, -rx)
    return acc, steps


@njit(cache=True)
def flight_steps(c0, b, ru, rv, vy, w, g, ell, tol, max_iter):
    """Lower-bound steps :func:`~throwmap.kernels.flight.touch_time` takes (same stopping rule, no polish)."""
    n = ru.shape[0]
    t = 0.0
    for it in range(max_iter):
        wt = w * t
        s = math.sin(wt)
        c = math.cos(wt)
        step = math.inf
        hit = False
        for j in range(n):
            gj, dg = gap(t, j, c0, b, ru, rv, vy, w, g)
            scale = abs(c0[j]) + (abs(b[j]) + abs(w * ru[j])) * t + 0.5 * g * t * t + abs(rv[j] * (1.0 - c))
            if gj <= tol * scale and (t > 0.0 or dg <= 0.0):
                hit = True
                continue
            M = g + w * w * ell[j]
            gp = max(gj, 0.0)
            disc = math.sqrt(dg * dg + 2.0 * M * gp)
            sj = (dg + disc) / M if dg >= 0.0 else 2.0 * gp / (disc - dg)
            step = min(step, sj)
        if hit:
            return it + 0 * (s + c)
        t += step
    return max_iter


def bench_phases(part, arm, x, sides, omega, repeat):
    """ns per throw (one thread) after each phase of the "paper" kernel, and mean first-contact steps."""
    o = PaperOptions()
    args = (np.ascontiguousarray(x), np.ascontiguousarray(sides, dtype=np.int64), np.ascontiguousarray(omega),
            arm.h, arm.g, arm.length_or_inf, arm.back, part.radius_of_gyration**2, part.w, part.beta, part.d, part.uL,
            part.uR, part.ell, part.stable, o.tol, o.max_iter, o.max_impacts, o.n_samples)
    out = {}
    for stop, name in enumerate(("release", "first_contact", "impact", "whole_throw")):
        _phases(*(a[:16] if isinstance(a, np.ndarray) and a.shape == np.shape(x) else a for a in args), stop, False)
        best = float("inf")
        for _ in range(repeat):
            t0 = time.process_time()
            _phases(*args, stop, False)
            best = min(best, time.process_time() - t0)
        out[name] = 1e9 * best / len(x)
    out["first_contact_steps_mean"] = _phases(*args, 1, True)[1] / len(x)
    return out


def bench_kernel(part, arm, x, sides, omega, repeat):
    """Best wall time of the batch kernel ``throw_many`` alone (outputs preallocated)."""
    o = PaperOptions()
    m = len(x)
    s = np.ascontiguousarray(sides, dtype=np.int64)
    valid = np.ones(m, dtype=bool)
    outs = (np.empty(m), np.empty(m, dtype=np.int64), np.empty(m, dtype=np.int64), np.empty((m, C.NREC)))
    geo = (arm.h, arm.g, 0.0, arm.length_or_inf, arm.back, part.radius_of_gyration**2, part.w, part.beta, part.d, part.uL,
           part.uR, part.ell, part.stable, o.tol, o.max_iter, o.max_impacts, o.n_samples)
    throw_many(x[:16], s[:16], omega[:16], valid[:16], *geo, *(a[:16] for a in outs))
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        throw_many(x, s, omega, valid, *geo, *outs)
        best = min(best, time.perf_counter() - t0)
    return best


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
    t_paper, res_paper, cold_paper = bench_batch(part, arm, x_b, sides_b, omega_b, "paper", repeat)
    t_small, _, _ = bench_batch(part, arm, x_b, sides_b, omega_b, "small_angle", repeat)
    s_single = bench_single(part, arm, x, sides, omega, n_single)
    t_kernel = bench_kernel(part, arm, x_b, sides_b, omega_b, repeat)
    n_ph = min(n, 200_000)
    phases = bench_phases(part, arm, x_b[:n_ph], sides_b[:n_ph], omega_b[:n_ph], repeat)
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
        "batch_paper_first_call_throws_per_s": n / cold_paper,
        "kernel_paper_throws_per_s": n / t_kernel,
        "phases_ns_per_throw_one_thread": phases,
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


def _phase_line(ph: dict) -> str:
    rel = ph["release"]
    fc = ph["first_contact"] - rel
    imp = ph["impact"] - ph["first_contact"]
    casc = ph["whole_throw"] - ph["impact"]
    return (f"paper kernel per throw, one thread: {ph['whole_throw']:.0f} ns = release {rel:.0f} + first contact "
            f"{fc:.0f} ({ph['first_contact_steps_mean']:.2f} steps + polish) + impact {imp:.0f} + "
            f"pivot/landing cascade and records {casc:.0f}")


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
        f"{'  its warm-up call (fresh memory)':<34}{res['n_batch']:>10d}"
        f"{res['batch_paper_first_call_throws_per_s']:>14.4g}{1e6 / res['batch_paper_first_call_throws_per_s']:>12.3f}",
        f"{'throw_many kernel alone, paper':<34}{res['n_batch']:>10d}{res['kernel_paper_throws_per_s']:>14.4g}"
        f"{1e6 / res['kernel_paper_throws_per_s']:>12.3f}",
        f"{'throw_batch, model small_angle':<34}{res['n_batch']:>10d}{res['batch_small_angle_throws_per_s']:>14.4g}"
        f"{res['batch_small_angle_us_per_throw']:>12.3f}",
        f"{'throw() single call (median)':<34}{res['n_single']:>10d}{res['single_throws_per_s']:>14.4g}"
        f"{res['single_throw_us']:>12.2f}",
        f"{'-' * 70}",
        f"batch (paper) / reference: {res['ratio_batch_paper_over_reference']:,.0f}×  "
        f"(goal ≥ {res['goal_ratio']:g}×: {'met' if res['meets_ratio_goal'] else 'NOT met'})",
        f"single throw(): {res['single_throw_us']:.2f} µs  "
        f"(goal ≤ {res['goal_single_us']:g} µs: {'met' if res['meets_single_goal'] else 'NOT met'})",
        _phase_line(res["phases_ns_per_throw_one_thread"]),
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
