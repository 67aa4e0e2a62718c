"""How often the recoiling arm and the impulse idealisation land a throw on the same side (one figure, with its
interval): random throws of the draft's triangle on model "rigid_body", each thrown both ways.

    python benchmarks/recoil_same_side.py            # 400 throws, seed 20261207 (≈ 2–3 min on one core)
    python benchmarks/recoil_same_side.py --n 100

Throws: side uniform over the stable sides, x uniform over the side's admissible starts up to 0.6 m, ω uniform in
[3, 6] rad/s, h = −1 cm, μ = 1; the recoil is :class:`~throwmap.engine.RecoilThrow` for the release rate (3°, the
PD overshoot); throws refused by either (not ``ok``) are drawn again. "rigid_body" matches the engine on recoil throws
(same side ≥ 99 %, see the validation page).
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=400)
    ap.add_argument("--seed", type=int, default=20261207)
    a = ap.parse_args(argv)

    import throwmap as tm
    from throwmap.engine import RecoilThrow
    from throwmap.experiments.stats import wilson_interval
    from throwmap.system.starts import start_interval

    warnings.simplefilter("ignore")
    rng = np.random.default_rng(a.seed)
    part, arm = tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01, mu=1.0)
    same = n = refused = 0
    t0 = time.perf_counter()
    while n < a.n:
        side = int(rng.choice(part.stable_sides))
        w = float(rng.uniform(3.0, 6.0))
        lo, hi = start_interval(part, arm, side)
        x = float(rng.uniform(lo, min(hi, 0.6)))
        impulse = tm.throw(part, arm, x, side, w, "rigid_body")
        recoil = tm.throw(part, arm, x, side, w, "rigid_body", realisation=RecoilThrow.for_release_rate(w))
        if impulse.status.label != "ok" or recoil.status.label != "ok":
            refused += 1
            continue
        n += 1
        same += int(impulse.side == recoil.side)
    lo, hi = wilson_interval(same, n)
    print(f"recoil and impulse land on the same side in {same}/{n} = {100 * same / n:.1f} % of throws (Wilson 95 % "
          f"[{100 * lo:.1f}, {100 * hi:.1f}] %; seed {a.seed}, {refused} refused and redrawn, "
          f"{time.perf_counter() - t0:.0f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
