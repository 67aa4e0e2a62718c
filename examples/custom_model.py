"""Adding a throw model: the paper's exact map with a jittered release rate.

A model is one class with a name, a frozen options dataclass, its features, and
``throw_one``/``throw_batch``/``trajectory``; :func:`throwmap.models.register` makes it
available to ``throw``, ``throw_batch``, ``iterate``, every analysis function and
the CLI by name. Here: the arm's release rate is ω (1 + σ ε), ε ~ N(0, 1) drawn
from a seeded generator — a first stochastic throw map. Prints the jittered
map's landing spread next to the exact one and writes ``custom_model.json``.

Run: ``python examples/custom_model.py [OUT_DIR]``.
"""

from __future__ import annotations

import json
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

import throwmap as tm
from throwmap.models import BatchArrays, Features, get_model, register, unregister


@dataclass(frozen=True, slots=True)
class JitterOptions:
    """``sigma``: relative standard deviation of the release rate; ``seed`` of the draws."""

    sigma: float = 0.02
    seed: int = 0


class JitteredPaper:
    name = "paper_jitter"
    summary = "model 'paper' with the release rate jittered by a relative Gaussian sigma"
    options_type = JitterOptions
    features = Features()

    def __init__(self):
        self.base = get_model("paper")
        self.base_options = self.base.options_type()

    def _rates(self, omega, o: JitterOptions):
        rng = np.random.default_rng(o.seed)
        return np.maximum(np.asarray(omega, dtype=float) * (1.0 + o.sigma * rng.standard_normal(np.shape(omega))), 0.0)

    def throw_one(self, part, system, x, side, omega, o):
        return self.base.throw_one(part, system, x, side, float(self._rates(omega, o)), self.base_options)

    def throw_batch(self, part, system, x, side, omega, valid, o, progress=None) -> BatchArrays:
        return self.base.throw_batch(part, system, x, side, self._rates(omega, o), valid, self.base_options)

    def trajectory(self, part, system, x, side, omega, o, dt):  # features.trajectory is False
        raise NotImplementedError


def main(out_dir: str | Path = "out") -> dict:
    register(JitteredPaper(), replace=True)
    try:
        part, arm = tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01)
        x = np.full(2000, 0.25)
        exact = tm.throw_batch(part, arm, x, 0, 4.0, model="paper")
        noisy = tm.throw_batch(part, arm, x, 0, 4.0, model="paper_jitter", sigma=0.02, seed=1)
        one = tm.throw(part, arm, 0.25, 0, 4.0, model="paper_jitter", sigma=0.0)
        cp = tm.critical_points(part, arm, 4.0, model="paper_jitter", sigma=0.0)  # analysis takes it by name too
        cp_paper = tm.critical_points(part, arm, 4.0, model="paper")
        result = {
            "model": "paper_jitter", "sigma": 0.02, "seed": 1, "n": int(x.size),
            "exact_x_m": float(exact.x[0]), "exact_side": int(exact.side[0]),
            "jitter_x_mean_m": float(np.mean(noisy.x[noisy.ok])), "jitter_x_std_m": float(np.std(noisy.x[noisy.ok])),
            "jitter_same_side_share": float(np.mean(noisy.side == exact.side[0])),
            "sigma0_equals_paper": bool(one.x == exact.x[0] and one.side == exact.side[0]
                                        and all(cp.r[s] == cp_paper.r[s] for s in cp_paper.r)),
            "r_m": {int(s): float(v) for s, v in cp.r.items()},
            "models": list(tm.models.model_names()),
        }
    finally:
        unregister("paper_jitter")
    print(f"exact: x' = {result['exact_x_m']:.4f} m on side {result['exact_side']}; "
          f"σ = 2 %: x' = {result['jitter_x_mean_m']:.4f} ± {result['jitter_x_std_m']:.4f} m, "
          f"same side {100 * result['jitter_same_side_share']:.1f} % of {result['n']}; "
          f"σ = 0 reproduces 'paper' (throws and r_i): {result['sigma0_equals_paper']}")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    (out / "custom_model.json").write_text(json.dumps(result, indent=2))
    return result


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out")
