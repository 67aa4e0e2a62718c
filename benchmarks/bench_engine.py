"""Benchmark: pymunk engine throws per second per core, its cost per throw, and a plain-pymunk reference.

Throws ``--n`` random impulse throws of the canonical triangle (h = −0.01 m,
μ = 1.5, x uniform on random stable sides up to 0.45 m, ω ∈ [3, 7] rad/s) with
the default :class:`throwmap.engine.EngineSettings` (0.125 ms step near
contacts, 0.5 ms in smooth contact phases, exact free flight), first in one
process (throws/s per core), the same throws through the model ``tm.throw(..., "engine")`` (input checks and
the exact model as oracle, :mod:`throwmap.models.engine_oracle`), then over all cores with
``throw_batch(..., model="engine", workers=0)``.

Per throw it prints the run's cost (pymunk steps, fine and coarse; exact-flight
leaps; rounds of checks; clearance evaluations) and, measured in the same run, a
*reference*: a plain pymunk loop — the triangle resting on the arm, the same
space settings, ``space.step`` called as many times per throw at the same step
sizes and nothing else. The ratio engine ÷ reference is the figure to compare
between machines (figures on a shared machine are noisy; the ratio much less).

The engine steps through its C helper (:mod:`throwmap.engine.pymunk.native`:
friction hook, exact solve, step loop and checks in C; the line "C helper" says
whether it is in use): it calls Chipmunk's ``cpSpaceStep`` without pymunk's
``Space.step`` wrapper, which the reference pays on every step. So the time is
split against a second loop timed the same way, *Chipmunk alone*: the same
steps through pymunk's raw ``lib.cpSpaceStep``. Per throw: Chipmunk's own step
time (that loop), pymunk's wrapper (reference − that loop), and the engine
beyond Chipmunk's steps (engine − that loop: set-up, checks, leaps, callbacks,
friction hook and exact solves, reruns at half the step).
Usage::

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
from throwmap.engine import EngineSettings, engine_run
from throwmap.engine.pymunk import native
from throwmap.system.fixtures import arm_solids
from throwmap.system.pose import pose_at_rest


def cases(n: int, seed: int = 0):
    part = tm.triangle_30_60_90()
    rng = np.random.default_rng(seed)
    k = rng.integers(0, 3, n)
    x = np.array([rng.uniform(-part.uL[s] + 0.005, 0.45) for s in k])
    om = rng.uniform(3.0, 7.0, n)
    return part, x, k, om


def plain_pymunk_seconds(part, arm, n_fine: int, n_coarse: int, settings: EngineSettings, raw: bool = False) -> float:
    """Seconds for ``n_fine`` steps of ``dt`` and ``n_coarse`` of ``coarse_dt`` of a plain pymunk space.

    The space: the arm's solid (kinematic) and the part resting on side 0 at
    x = 0.2 m, with the engine's gravity, iterations, collision slop, friction
    and empty begin/separate handlers; ``space.step`` in a bare loop, or with
    ``raw`` Chipmunk's ``cpSpaceStep`` through pymunk's cffi ``lib`` (no wrapper).
    """
    import pymunk as pm

    space = pm.Space()
    space.gravity = (0.0, -arm.g)
    space.iterations = settings.iterations
    space.collision_slop = settings.collision_slop
    body_arm = pm.Body(body_type=pm.Body.KINEMATIC)
    (piece,), _ = arm_solids(arm.h, 2.4, settings.arm_thickness, ())
    solid = pm.Poly(body_arm, [tuple(v) for v in piece.tolist()])
    solid.friction, solid.elasticity = arm.mu, 0.0
    space.add(body_arm, solid)
    x, y, phi = pose_at_rest(part, arm.h, 0.2, 0)
    body = pm.Body(part.mass, part.mass * part.radius_of_gyration**2)
    body.position, body.angle = (x, y), phi
    shape = pm.Poly(body, [tuple(v) for v in part.w.tolist()])
    shape.friction, shape.elasticity = 1.0, 0.0
    space.add(body, shape)
    space.on_collision(begin=lambda *a: None, separate=lambda *a: None)
    dt, coarse = settings.dt, settings.coarse_dt
    if raw:
        from pymunk._chipmunk import lib

        step, handle = lib.cpSpaceStep, space._space
        t0 = time.perf_counter()
        for _ in range(n_fine):
            step(handle, dt)
        for _ in range(n_coarse):
            step(handle, coarse)
        return time.perf_counter() - t0
    step = space.step
    t0 = time.perf_counter()
    for _ in range(n_fine):
        step(dt)
    for _ in range(n_coarse):
        step(coarse)
    return time.perf_counter() - t0


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=200)
    ap.add_argument("--json", type=str, default=None)
    args = ap.parse_args(argv)
    if args.n < 1:
        ap.error("--n must be ≥ 1")
    part, x, k, om = cases(args.n)
    arm = tm.Arm(h=-0.01, mu=1.5)
    settings = EngineSettings()
    engine_run(part, arm, float(x[0]), int(k[0]), float(om[0]))  # warm-up
    plain_pymunk_seconds(part, arm, 100, 100, settings)
    tot = dict(steps=0, coarse=0, leaps=0, checks=0, clearance=0, sim=0.0)
    tm.throw(part, arm, float(x[0]), int(k[0]), float(om[0]), "engine")  # warm-up of the exact model's kernels
    t_engine = t_ref = t_raw = t_model = 0.0
    for i in range(args.n):  # engine and references interleaved, so that all see the same machine load
        t0 = time.perf_counter()
        r = engine_run(part, arm, float(x[i]), int(k[i]), float(om[i]))
        t_engine += time.perf_counter() - t0
        t_ref += plain_pymunk_seconds(part, arm, r.n_steps - r.n_coarse, r.n_coarse, settings)
        t_raw += plain_pymunk_seconds(part, arm, r.n_steps - r.n_coarse, r.n_coarse, settings, raw=True)
        t0 = time.perf_counter()
        tm.throw(part, arm, float(x[i]), int(k[i]), float(om[i]), "engine")
        t_model += time.perf_counter() - t0
        tot["steps"] += r.n_steps
        tot["coarse"] += r.n_coarse
        tot["leaps"] += r.n_leaps
        tot["checks"] += r.n_checks
        tot["clearance"] += r.n_clearance
        tot["sim"] += r.t_end
    t0 = time.perf_counter()
    tm.throw_batch(part, arm, x, k, om, model="engine", workers=0)
    t_all = time.perf_counter() - t0
    n = args.n
    cores = os.cpu_count() or 1
    per = {key: v / n for key, v in tot.items()}
    res = {
        "n": n, "cores": cores, "python": sys.version.split()[0], "machine": platform.machine(),
        "throws_per_s_one_core": n / t_engine, "model_throws_per_s_one_core": n / t_model,
        "ratio_model_over_engine_run": t_engine / t_model, "throws_per_s_all_cores": n / t_all,
        "reference_throws_per_s": n / t_ref, "ratio_engine_over_reference": t_ref / t_engine,
        "steps_per_throw": per["steps"], "coarse_steps_per_throw": per["coarse"], "leaps_per_throw": per["leaps"],
        "checks_per_throw": per["checks"], "clearances_per_throw": per["clearance"],
        "simulated_s_per_throw": per["sim"], "ms_per_throw": 1e3 * t_engine / n,
        "ms_in_pymunk_steps_per_throw": 1e3 * t_ref / n, "ms_in_chipmunk_steps_per_throw": 1e3 * t_raw / n,
        "ms_in_pymunk_wrapper_per_throw": 1e3 * (t_ref - t_raw) / n,
        "ms_beyond_chipmunk_per_throw": 1e3 * (t_engine - t_raw) / n,
        "us_per_step_reference": 1e6 * t_ref / tot["steps"], "us_per_step_chipmunk": 1e6 * t_raw / tot["steps"],
        "c_helper": native.available(), "c_helper_reason": native.reason(),
    }
    print(f"engine benchmark: {n} throws, {cores} cores, Python {res['python']} ({res['machine']})")
    print(f"  one core : {res['throws_per_s_one_core']:8.1f} throws/s  ({res['ms_per_throw']:.2f} ms/throw)")
    print(f"  model 'engine' (checks, exact-model oracle): {res['model_throws_per_s_one_core']:8.1f} throws/s on one "
          f"core, {res['ratio_model_over_engine_run']:.3f} of engine_run's rate")
    print(f"  all cores: {res['throws_per_s_all_cores']:8.1f} throws/s")
    print(f"  reference: {res['reference_throws_per_s']:8.1f} throws/s  (plain pymunk loop, same steps per throw, "
          f"{res['us_per_step_reference']:.2f} µs/step)")
    print(f"  engine / reference: {res['ratio_engine_over_reference']:.3f}")
    print(f"  C helper: {'in use' if res['c_helper'] else 'not used (' + str(res['c_helper_reason']) + ')'}")
    print(f"  per throw: {per['steps']:.0f} pymunk steps ({per['steps'] - per['coarse']:.0f} at dt, "
          f"{per['coarse']:.0f} at coarse_dt), {per['leaps']:.1f} exact-flight leaps, {per['checks']:.0f} check rounds, "
          f"{per['clearance']:.1f} clearances, {per['sim']:.3f} s simulated")
    print(f"  time per throw: {res['ms_in_chipmunk_steps_per_throw']:.2f} ms in Chipmunk's steps "
          f"({res['us_per_step_chipmunk']:.2f} µs/step, cpSpaceStep alone), "
          f"{res['ms_in_pymunk_wrapper_per_throw']:.2f} ms more through pymunk's Space.step (reference); "
          f"the engine {res['ms_beyond_chipmunk_per_throw']:.2f} ms beyond Chipmunk's steps")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(res, f, indent=2)
    return res


if __name__ == "__main__":
    main()
