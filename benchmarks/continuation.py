"""Continuation of the draft's triangle along ω: timing, events, and the check against brute-force basins.

    python benchmarks/continuation.py                       # "paper" and "rigid_body", ω 3.5 … 5.0, 31 values
    python benchmarks/continuation.py --models paper --n 11 # smaller
    python benchmarks/continuation.py --out bench-cont      # JSON and figures kept there

For each model: one :func:`throwmap.analysis.continuation.continuation` over ``--n`` values of ω (the triangle of
hypotenuse 17 cm, h = −1 cm, 200 starts per stable side up to 0.6 m, 500 throws), timed, its events printed; then
at 5 values of the grid an independent :func:`throwmap.analysis.basins` run on a grid five times denser (1000
starts per side, its own limit-set search) and the basin and escape shares compared: they differ by what the
coarser grid cannot resolve (≈ 1/200 of a side per boundary). A reference (one ``basins`` call at ω = 4) is timed
in the same run, so the ratio reads the same on a busy machine.
"""

from __future__ import annotations

import argparse
import json
import time
import warnings
from pathlib import Path

import numpy as np


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--models", nargs="+", default=["paper", "rigid_body"])
    ap.add_argument("--n", type=int, default=31, help="values of ω")
    ap.add_argument("--out", default=None, help="folder for continuation-<model>.json / .png")
    a = ap.parse_args(argv)

    import throwmap as tm
    from throwmap.analysis import basins
    from throwmap.analysis.continuation import Resolution, continuation

    warnings.simplefilter("ignore")
    tri = tm.triangle_30_60_90(0.17)
    arm = tm.Arm(h=-0.01)
    grid = np.linspace(3.5, 5.0, a.n)
    out = Path(a.out) if a.out else None
    if out:
        out.mkdir(parents=True, exist_ok=True)
    for model in a.models:
        basins(tri, arm, 4.0, model, grid=50, n_check=0)  # kernels compiled before anything is timed
        t = time.perf_counter()
        basins(tri, arm, 4.0, model, grid=200, n_check=0)
        ref = time.perf_counter() - t
        t = time.perf_counter()
        c = continuation(tri, arm, "omega", grid, model=model, resolution=Resolution())
        dt = time.perf_counter() - t
        print(f"## {model}: {a.n} values of ω in {dt:.1f} s ({c.evaluations} evaluations, "
              f"{c.evaluations - a.n} to locate events); reference basins at ω = 4: {ref:.2f} s "
              f"(ratio {dt / ref:.0f})")
        print(c.table())
        if out:
            (out / f"continuation-{model}.json").write_text(json.dumps(c.to_dict(), indent=1) + "\n")
            c.plot(out / f"continuation-{model}.png")
        print(f"\n| ω | continuation: attractors (share) | escape | basins ×5 grid: attractors (share) | escape | "
              f"max |Δ share| |")
        print("|---|---|---|---|---|---|")
        for w in grid[np.linspace(0, a.n - 1, 5).round().astype(int)]:
            p = next(q for q in c.points if q.value == w)
            b = basins(tri, arm, float(w), model, grid=1000, n_check=0)
            esc_b = sum(v for k, v in b.escapes.items() if k != "unresolved")
            mine = sorted((round(min(x[1] for x in q.bands), 3), q.fraction) for q in p.attractors)
            theirs = sorted((round(min(x[1] for x in q.bands), 3), q.fraction) for q in b.attractors if q.fraction > 0)
            diff = abs(p.escape_fraction - esc_b)
            if len(mine) == len(theirs):
                diff = max([diff] + [abs(f0 - f1) for (_, f0), (_, f1) in zip(mine, theirs)])
            else:
                diff = float("nan")
            print(f"| {w:.3f} | {', '.join(f'{f:.3f}' for _, f in mine) or 'none'} | {p.escape_fraction:.3f} | "
                  f"{', '.join(f'{f:.3f}' for _, f in theirs) or 'none'} | {esc_b:.3f} | {diff:.3f} |")
        print()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
