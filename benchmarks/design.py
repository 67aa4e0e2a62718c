"""Benchmark: one limit-set design run against one critical_points call, measured in the same run.

The feeder design problem (:data:`throwmap.design.examples.FEEDER`: the 17 cm plexiglas
triangle, 50 g of lead starting at its centroid, ω = 5 rad/s, h = −1 cm, 60 cm arm, targets
r = {32, 15.5, 23.5} cm) on ``rigid_body`` after warm-up (JIT caches loaded, a first call made):

(1) one :func:`throwmap.analysis.critical_points` call (r_i only, to 0.1 µm, as the design
    uses it): median wall time over ``--repeat`` calls;
(2) one :func:`throwmap.design.design` run (Levenberg–Marquardt with central-difference
    Jacobians): median wall time over ``--repeat`` runs, its feature evaluations and steps;
(3) the ratio (2)/(1): the cost of a design in critical-point evaluations.

Prints the machine and a table; ``--json PATH`` writes the figures. Usage::

    python benchmarks/design.py [--repeat 5] [--json bench_design.json]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time
from pathlib import Path


def main(argv=None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--json", type=Path, default=None)
    a = ap.parse_args(argv)
    if a.repeat < 1:
        ap.error("--repeat must be ≥ 1")

    import numba

    from throwmap.design import design
    from throwmap.design.examples import FEEDER, exact_r, feeder_arm, plexiglas_triangle

    plate, arm = plexiglas_triangle(), feeder_arm()
    fd_part = design(plate, arm, FEEDER["omega_start"], FEEDER["targets"], weight_mass=FEEDER["weight_mass"]).part

    def one_cp():
        return exact_r(fd_part, arm, FEEDER["omega_start"], xtol=1e-7)

    def one_design():
        return design(plate, arm, FEEDER["omega_start"], FEEDER["targets"], weight_mass=FEEDER["weight_mass"])

    one_cp()  # warm-up
    t_cp, t_design = [], []
    res = None
    for _ in range(a.repeat):
        t0 = time.perf_counter()
        one_cp()
        t_cp.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        res = one_design()
        t_design.append(time.perf_counter() - t0)
    cp_ms = 1000 * statistics.median(t_cp)
    design_ms = 1000 * statistics.median(t_design)
    out = {"machine": {"cpu_count": os.cpu_count(), "numba_threads": numba.get_num_threads()},
           "repeat": a.repeat, "critical_points_ms": cp_ms, "design_ms": design_ms,
           "ratio_design_over_critical_points": design_ms / cp_ms, "design_evaluations": res.n_evaluations,
           "design_steps": res.n_steps, "design_success": res.success}
    print(f"machine: {out['machine']['cpu_count']} cores, numba threads {out['machine']['numba_threads']}")
    print(f"{'what':<44} {'median ms':>10}")
    print(f"{'critical_points (r_i to 0.1 µm, rigid_body)':<44} {cp_ms:>10.2f}")
    print(f"{'design (feeder problem, LM, FD Jacobians)':<44} {design_ms:>10.2f}   "
          f"({res.n_evaluations} evaluations, {res.n_steps} steps, success {res.success})")
    print(f"ratio design / critical_points: {out['ratio_design_over_critical_points']:.1f}")
    if a.json is not None:
        a.json.write_text(json.dumps(out, indent=2) + "\n")
    return out


if __name__ == "__main__":
    main()
