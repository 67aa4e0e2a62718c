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
        if self.side is not None:
            if isinstance(self.side, bool) or not isinstance(self.side, (int, np.integer)) or self.side < 0:
                raise InvalidStateError("goal.side", f"must be a side index ≥ 0, got {self.side!r}")
            for name in ("lo", "hi"):
                if math.isnan(getattr(self, name)):
                    raise InvalidStateError(f"goal.{name}", "must be a number (m), got nan")
            if not self.lo <= self.hi:
                raise InvalidStateError("goal.lo", f"must be ≤ hi, got lo = {self.lo} m > hi = {self.hi} m")

    def check(self, cells, labels) -> None:
        """Refuse a goal these ``cells`` and absorbing ``labels`` can never reach: a side the cells do not
        cover, a label not among ``labels``, a [lo, hi] outside the cells on its side."""
        if self.label is not None:
            if self.label not in labels:
                raise InvalidStateError("goal.label", f"unknown state {self.label!r}; the throws end in "
                                                      f"{', '.join(labels)} or a cell")
            return
        left, right, side = cells.bounds()
        on = side == self.side
        if not on.any():
            raise InvalidStateError("goal.side", f"side {self.side} has no cells (sides {sorted(set(side.tolist()))})")
        if self.hi < left[on].min() or self.lo > right[on].max():
            raise InvalidStateError("goal.lo", f"[{self.lo}, {self.hi}] m is outside the cells of side {self.side} "
                                               f"({left[on].min():.4g} … {right[on].max():.4g} m)")

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
    from ..budget import check_count

    if not isinstance(goal, GoalSet):
        raise InvalidStateError("goal", f"must be a GoalSet, got {type(goal).__name__}")
    n = check_count("n", n, minimum=1)
    k_max = check_count("k_max", k_max, minimum=0)
    goal.check(cells, tuple(step.labels))
    if initial is None:
        raise InvalidStateError("initial", "give the starts' distribution over the cells (weights, one per cell)")
    try:
        w = np.asarray(initial, dtype=float)[: cells.n]
    except (TypeError, ValueError):
        raise InvalidStateError("initial", "must be weights, one per cell") from None
    if w.shape != (cells.n,) or not np.all(np.isfinite(w)) or np.any(w < 0) or w.sum() <= 0:
        raise InvalidStateError("initial", f"must be {cells.n} finite weights ≥ 0, not all 0")
    rng = as_generator(rng)
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
