"""The Monte Carlo of an open-loop stochastic throw map: the reference a chain is checked against.

:class:`GoalSet` is a goal both a chain and a simulation understand: the rests on ``side`` with
``lo ≤ x ≤ hi`` (m), or an absorbing label (``"off_end"``, ``"behind_joint"``). :func:`open_loop_trials`
throws ``n`` parts, each from a start drawn from a distribution over cells, with its own μ (drawn once per
trial by the noise) and every throw's ω jittered, until the goal is reached, the part leaves the arm or
``k_max`` throws; it returns each trial's hitting throw (−1: not reached) — the input of
:func:`throwmap.stochastic.compare.compare_curve`.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError
from ..rng import as_generator

__all__ = ["GoalSet", "open_loop_trials"]


@dataclass(frozen=True, slots=True)
class GoalSet:
    """Rests on ``side`` within ``[lo, hi]`` (m), or the absorbing state ``label``."""

    side: int | None = None
    lo: float = -math.inf
    hi: float = math.inf
    label: str | None = None

    def __post_init__(self):
        if (self.label is None) == (self.side is None):
            raise InvalidStateError("goal", "give either a side (with lo, hi) or a label")

    @property
    def breaks(self) -> tuple:
        return tuple(v for v in (self.lo, self.hi) if math.isfinite(v))

    def mask(self, chain) -> np.ndarray:
        """The chain's goal states: the label, or the cells on ``side`` inside [lo, hi] (the cells are cut
        at lo and hi: :attr:`breaks`)."""
        if self.label is not None:
            return chain.states([self.label])
        left, right, side = chain.cells.bounds()
        cellmask = (side == self.side) & (left >= self.lo - 1e-12) & (right <= self.hi + 1e-12)
        return np.concatenate([cellmask, np.zeros(chain.n - chain.n_cells, dtype=bool)])

    def reached(self, x, side, label) -> np.ndarray:
        if self.label is not None:
            return np.asarray(label) == self.label
        x, side = np.asarray(x), np.asarray(side)
        return (np.asarray(label) == "") & (side == self.side) & (x >= self.lo) & (x <= self.hi)

    def to_dict(self) -> dict:
        return {"label": self.label} if self.label else {"side": self.side, "lo_m": self.lo, "hi_m": self.hi}


def open_loop_trials(step, cells, initial, goal: GoalSet, *, n: int = 400, k_max: int = 50, rng=None,
                     mu_spread: bool = True) -> np.ndarray:
    """Hitting throws of ``n`` simulated trials of ``step`` (a :class:`~throwmap.stochastic.build.ThrowStep`):
    the start drawn from ``initial`` over ``cells`` (a cell, then x uniform in it), μ per trial from the
    step's noise (unless ``mu_spread`` is False), then throws until the goal, the arm is left or ``k_max``."""
    rng = as_generator(rng)
    w = np.asarray(initial, dtype=float)[: cells.n]
    w = w / w.sum()
    left, right, side = cells.bounds()
    c = rng.choice(cells.n, size=n, p=w)
    x = right[c] - rng.random(n) * (right[c] - left[c])
    s = side[c].astype(np.int64)
    noise = step.noise
    arms = [noise.arm(step.arm, rng) if (mu_spread and noise is not None) else step.arm for _ in range(n)]
    hits = np.full(n, -1, dtype=np.int64)
    lab = np.full(n, "", dtype=object)
    hits[goal.reached(x, s, lab)] = 0
    groups: dict = {}
    for j, a in enumerate(arms):
        groups.setdefault(a.mu, []).append(j)
    steps = {mu: step.with_arm(dataclasses.replace(step.arm, mu=mu)) for mu in groups}
    active = hits < 0
    for k in range(1, int(k_max) + 1):
        if not active.any():
            break
        for mu, js in groups.items():
            js = np.asarray(js)
            js = js[active[js]]
            if js.size == 0:
                continue
            xn, sn, ln = steps[mu](x[js], s[js], rng)
            x[js], s[js], lab[js] = xn, sn, ln
        reached = active & goal.reached(x, s, lab)
        hits[reached] = k
        active &= ~reached & (lab == "")
    return hits
