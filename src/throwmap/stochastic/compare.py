"""The chain against the Monte Carlo: P(goal by throw k) inside the pointwise Wilson 95 % band.

For trials with hitting throws ``T_j`` (the throw after which trial j reached the goal; −1 or None when it
never did), the Monte Carlo estimate is p̂_k = #{j : 0 ≤ T_j ≤ k} / n with the Wilson 95 % interval
(:func:`throwmap.experiments.stats.wilson_interval`) at every k; :func:`compare_curve` reports which k the
chain's curve lies inside that band and the fraction of k inside. The bands are pointwise: a correct chain
is outside at about 5 % of the k in the long run (more clustered, since p̂_k are correlated in k).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, shown
from ..experiments.stats import wilson_interval

__all__ = ["Comparison", "mc_curve", "compare_curve"]


def mc_curve(hits, k_max: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """``(p̂, low, high, n)`` for k = 0 … ``k_max`` from the trials' hitting throws (< 0 or nan: never)."""
    h = np.asarray([np.nan if v is None else float(v) for v in hits], dtype=float)
    n = h.size
    if n == 0:
        raise InvalidStateError("trials", "need at least one trial")
    ks = np.arange(int(k_max) + 1)
    hit = np.where(np.isfinite(h) & (h >= 0), h, np.inf)
    counts = (hit[None, :] <= ks[:, None]).sum(axis=1)
    band = np.array([wilson_interval(int(c), n) for c in counts])
    return counts / n, band[:, 0], band[:, 1], n


@dataclass(frozen=True, slots=True, eq=False)
class Comparison:
    """P(goal by k): the chain's ``chain`` and the Monte Carlo's ``mc`` with its Wilson band ``low``/``high``
    at ``k`` = 0 … K from ``n`` trials; ``inside`` per k; ``label`` names the experiment; ``meta`` how."""

    k: np.ndarray
    chain: np.ndarray
    mc: np.ndarray
    low: np.ndarray
    high: np.ndarray
    n: int
    label: str = ""
    meta: dict = field(default_factory=dict)

    @property
    def inside(self) -> np.ndarray:
        return (self.chain >= self.low - 1e-12) & (self.chain <= self.high + 1e-12)

    @property
    def fraction_inside(self) -> float:
        return float(self.inside.mean())

    @property
    def max_outside(self) -> float:
        """The largest distance (probability) of the chain's curve outside the band (0 when inside)."""
        return float(np.max(np.maximum(self.low - self.chain, self.chain - self.high).clip(min=0.0)))

    def summary(self) -> dict:
        out = {"label": self.label, "trials": self.n, "k_max": int(self.k[-1]),
               "fraction_inside": self.fraction_inside, "k_outside": [int(k) for k in self.k[~self.inside]],
               "max_outside": self.max_outside, "sup_abs_diff": float(np.max(np.abs(self.chain - self.mc))),
               "final": {"chain": float(self.chain[-1]), "mc": float(self.mc[-1]),
                         "band": [float(self.low[-1]), float(self.high[-1])]}}
        out.update(self.meta)
        return out

    def to_dict(self) -> dict:
        return dict(self.summary(), k=self.k.tolist(), chain=self.chain.tolist(), mc=self.mc.tolist(),
                    low=self.low.tolist(), high=self.high.tolist())

    def plot(self, ax=None, **kw):
        """The chain's curve over the Monte Carlo points and band (:func:`throwmap.viz.chain.plot_goal_curve`)."""
        from ..viz.chain import plot_goal_curve

        return plot_goal_curve(self.k, self.chain, self.mc, self.low, self.high, n=self.n, label=self.label,
                               fraction=self.fraction_inside, ax=ax, **kw)


def compare_curve(chain_curve, hits, k_max: int | None = None, *, label: str = "", meta=None) -> Comparison:
    """The chain's P(goal by k) (k = 0 … ≥ k_max) against trials' hitting throws ``hits`` (module docstring).
    ``k_max`` default: the largest hitting throw of the trials (at least 1), capped by the chain curve's length."""
    c = np.asarray(chain_curve, dtype=float)
    h = np.asarray([np.nan if v is None else float(v) for v in hits], dtype=float)
    if k_max is None:
        fin = h[np.isfinite(h) & (h >= 0)]
        k_max = max(1, int(fin.max()) if fin.size else 1)
    if isinstance(k_max, bool) or not isinstance(k_max, (int, np.integer)) or k_max < 0:
        raise InvalidStateError("k_max", f"must be an integer ≥ 0, got {shown(k_max)}")
    k_max = min(int(k_max), c.size - 1)
    p, lo, hi, n = mc_curve(h, k_max)
    return Comparison(np.arange(k_max + 1), c[: k_max + 1], p, lo, hi, n, label, dict(meta or {}))
