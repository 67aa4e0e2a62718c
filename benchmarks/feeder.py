"""The feeder designer on parts nobody tuned for: random convex plates, one search each, a table.

    python benchmarks/feeder.py                                  # 20 plates (seed 2026) + the draft's triangle
    python benchmarks/feeder.py --parts 5 --budget 3 --n 100     # smaller
    python benchmarks/feeder.py --out bench-feeder               # rows kept in bench-feeder/rows.jsonl (resumable)
    python benchmarks/feeder.py --weight none --out bench-plain  # the same plates, no lead weight allowed

Each plate is drawn by :func:`throwmap.feeder.random_plate` (4–6 vertices, 6–15 cm across, 20–80 g,
``numpy.random.default_rng(seed)``), then :func:`throwmap.feeder.design_feeder` searches a feeder for it
with the stated budget and verification size. The table gives per part: the fed side, the lead weight
the design uses (or none), the verification and its rerun (another seed), both pooled less the verification's first
trials (they chose the candidate) with their Wilson 95 % interval and the range a new run of as many trials lands in with 95 % probability, the wall time, or the reason
for none; the summary the share of parts fed, with and without a weight. The draft's
triangle is the first row (its hardware fed 19 of 20).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
import warnings
from pathlib import Path

import numpy as np


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--parts", type=int, default=20, help="random plates (the triangle is added)")
    ap.add_argument("--seed", type=int, default=2026, help="seed of the plates")
    ap.add_argument("--budget", type=float, default=10.0, help="minutes per part")
    ap.add_argument("--n", type=int, default=200, help="engine trials of a verification (and of its rerun)")
    ap.add_argument("--n-pre", type=int, default=20, help="first engine trials of a candidate")
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--out", default="bench-feeder", help="folder: one sub-folder per part, rows.jsonl")
    ap.add_argument("--no-triangle", action="store_true")
    ap.add_argument("--weight", default="auto", help="lead weight allowed: auto, none or the heaviest in kg")
    a = ap.parse_args(argv)

    from throwmap.feeder import VerifyPlan, design_feeder, random_plate
    from throwmap.feeder.search import evidence
    from throwmap.io.config import resolve_part

    warnings.simplefilter("ignore")
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    rows_path = out / "rows.jsonl"
    done = {}
    if rows_path.exists():
        for line in rows_path.read_text(encoding="utf-8").splitlines():
            try:
                r = json.loads(line)
                done[r["id"]] = r
            except (ValueError, KeyError):
                pass
    rng = np.random.default_rng(a.seed)
    parts = [] if a.no_triangle else [("triangle", resolve_part("triangle").part)]
    parts += [(f"plate-{i:02d}", random_plate(rng)) for i in range(a.parts)]
    weight = a.weight if a.weight in ("auto", "none") else float(a.weight)
    plan = VerifyPlan(n_pre=a.n_pre, n_verify=a.n, seed=1, workers=a.workers, budget_s=60.0 * a.budget)
    print(f"# feeder benchmark: {len(parts)} parts (plates seed {a.seed}), budget {a.budget:g} min/part, weight {a.weight}, "
          f"verification {a.n_pre} + {a.n} + rerun {a.n} trials, {a.workers} workers", flush=True)
    print("| part | vertices | size cm | mass g | fed side | weight | verification | rerun | both runs, less the first trials "
          "(Wilson 95 %) | "
          "a new run lands in (95 %) | time s | reason |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for pid, part in parts:
        if pid in done:
            r = done[pid]
        else:
            t0 = time.perf_counter()
            error = ""
            try:
                res = design_feeder(part, out / pid, plan=plan, weight=weight)
            except Exception as err:  # a crash is a row of the table, not the end of the benchmark
                res = None
                error = f"error: {type(err).__name__}: {err}"
            f = None if res is None else res.feeder
            r = {"id": pid, "name": part.name, "vertices": len(part.vertices),
                 "size_cm": [round(100 * float(np.ptp(np.asarray(part.vertices)[:, i])), 1) for i in (0, 1)],
                 "mass_g": round(1000 * part.mass, 1), "success": bool(res and res.success),
                 "side": None if res is None else res.side,
                 "weight": None if f is None or f.variant.weight is None else f.variant.weight.to_dict(),
                 "verified": None if res is None else res.verified, "rerun": None if res is None else res.rerun,
                 "time_s": round(time.perf_counter() - t0, 1),
                 "reason": error if res is None else ("" if res.success else res.reason), "seed": a.seed,
                 "weight_allowed": a.weight, "budget_min": a.budget}
            with rows_path.open("a", encoding="utf-8") as fh:
                fh.write(json.dumps(r) + "\n")
        rows.append(r)
        v, rr = r["verified"], r["rerun"]
        if r["success"]:
            w = "none" if r["weight"] is None else f"{1000 * r['weight']['mass_kg']:.0f} g"
            got, again, why = f"{v['successes']}/{v['n']}", f"{rr['successes']}/{rr['n']}", ""
            e = evidence(v, rr)  # both runs less the first trials that chose the candidate
            both = f"{e['successes']}/{e['n']} [{100 * e['ci95'][0]:.1f}, {100 * e['ci95'][1]:.1f}] %"
            new = "{}–{}/{}".format(*e["rerun95"]["successes"], e["rerun95"]["n"])
        else:
            w = got = again = both = new = "-"
            why = r["reason"]
        print(f"| {r['id']} | {r['vertices']} | {r['size_cm'][0]} × {r['size_cm'][1]} | {r['mass_g']} | "
              f"{r['side'] if r['success'] else '-'} | {w} | {got} | {again} | {both} | {new} | {r['time_s']} | {why} |",
              flush=True)
    fed = [r for r in rows if r["success"]]
    plain = [r for r in fed if r["weight"] is None]
    print(f"\nfed {len(fed)}/{len(rows)} parts ({len(plain)} without a weight, {len(fed) - len(plain)} with one); "
          f"time per part median {np.median([r['time_s'] for r in rows]):.0f} s, max "
          f"{max(r['time_s'] for r in rows):.0f} s", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
