"""The feeder search's engine screen: which side arrives first at an end stop under the real arm.

An end stop holds whatever side reaches it first (the flips that would free a wrong side roll outward,
into the stop), so a pocket at the arm's end feeds side k when, under the arm that really throws
(the recoiling arm with ω jitter), side k is the first to pass the stop from wherever the part is
dropped, and side k jogs into the stop at every ω the jitter gives. :func:`arrival` measures both
on the engine's tabulated one-throw map (:func:`throwmap.design.passage.recoil_table`, 1 cm grid,
ω·(1 + σz) for z = −3 … 3) with Markov chains from drops over the inner arm
(:func:`throwmap.design.passage.first_passage`), for end stops X from just beyond the drop zone
to the table's end. A candidate's score is its best X's share of chains that arrive first on the
target side where that side holds (its *predicted* feed rate); a wrong arrival counts against it.

Drops: CM abscissa uniform over ``DROP_X`` (a chute onto the inner arm); end stops are considered
only beyond every side's outermost vertex from there (+1 cm), so no drop lands in the pocket.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, RegimeWarning
from ..system.arm import Arm
from .family import Variant

__all__ = ["Arrival", "arrival", "exact_table", "DROP_X", "TABLE_STEP", "TABLE_X_MAX"]

DROP_X = (0.0, 0.25)
"""The drop zone: CM abscissa range over which parts arrive on the arm, m."""
TABLE_STEP = 0.01
"""The grid of the engine table, m."""
TABLE_X_MAX = 0.56
"""The table's reach, m (the draft's arm is about 0.6 m)."""


@dataclass(frozen=True, slots=True, eq=False)
class Arrival:
    """One screened feeder: the ``variant`` (part and weight) thrown at ``omega`` (rad/s) from an arm at ``h`` (m);
    per stable side its best end stop: ``best[k] = (X m, share first on k, share first on another side, holds)``;
    ``side`` the target side and ``X`` its end stop (m), ``predicted`` its share (0 when no X holds), ``time_s``."""

    variant: Variant
    omega: float
    h: float
    side: int
    X: float
    predicted: float
    wrong: float
    best: dict
    chains: int
    time_s: float
    model: str = "engine"

    def to_dict(self) -> dict:
        return {"variant": self.variant.to_dict(), "omega_rad_s": self.omega, "h_m": self.h, "side": self.side,
                "end_stop_m": self.X, "predicted": self.predicted, "wrong_first": self.wrong,
                "per_side": {str(k): {"end_stop_m": v[0], "first": v[1], "wrong_first": v[2], "holds": v[3]}
                             for k, v in self.best.items()},
                "chains": self.chains, "model": self.model, "time_s": self.time_s}


def exact_table(part, arm: Arm, omega: float, *, sigma: float = 0.03):
    """The exact model's one-throw map on the same grid as the engine table (the impulse throw, no recoil): a
    :class:`~throwmap.design.passage.RecoilTable` with ``recoil`` 0. Cost: ≈ 1,000 exact throws (< 0.1 s once
    compiled)."""
    from ..design.passage import Z_LEVELS, RecoilTable
    from ..throws.throw import throw_batch

    xs = np.arange(0.0, TABLE_X_MAX, TABLE_STEP)
    sides = tuple(part.stable_sides)
    nk = part.n_sides
    shape = (len(Z_LEVELS), nk, xs.size)
    st, xn, sn = np.full(shape, -1, dtype=np.int64), np.full(shape, np.nan), np.full(shape, -1, dtype=np.int64)
    uL = np.asarray(part.uL, dtype=float)
    X = np.concatenate([xs[xs + uL[k] > 0.002] for k in sides])
    K = np.concatenate([np.full(int(np.sum(xs + uL[k] > 0.002)), k) for k in sides])
    I = np.concatenate([np.flatnonzero(xs + uL[k] > 0.002) for k in sides])
    for a, z in enumerate(Z_LEVELS):
        b = throw_batch(part, arm, X, K, np.full(X.size, omega * (1.0 + sigma * z)), model="rigid_body",
                        on_invalid="status")
        st[a, K, I], xn[a, K, I], sn[a, K, I] = np.asarray(b.status), np.asarray(b.x), np.asarray(b.side)
    return RecoilTable(xs, Z_LEVELS, float(omega), float(sigma), float(arm.h), float(arm.mu), 0.0, 0.0, st, xn, sn)


def _stops(part) -> np.ndarray:
    lo = DROP_X[1] + float(np.max(part.uR)) + 0.01
    return np.round(np.arange(math.ceil(lo * 100) / 100, TABLE_X_MAX - TABLE_STEP, 0.01), 6)


def arrival(variant: Variant, omega: float, arm: Arm, *, sides=None, sigma: float = 0.03, chains: int = 1500,
            throws: int = 60, seed: int = 0, workers: int | None = None, exact: bool = False) -> Arrival:
    """Screen ``variant`` thrown at ``omega`` from the plain ``arm`` (its h, g and μ; see the module docstring):
    the best end stop of every side in ``sides`` (None: every stable side), and the side with the highest share.
    ``exact`` False: the engine's recoil table, 7 × (stable sides) × 56 throws (5–30 s on 2 cores); True:
    :func:`exact_table` on the exact "rigid_body" model, the impulse throw (the cheap screen, < 0.1 s)."""
    import time

    from ..design.passage import first_passage, recoil_table

    t0 = time.perf_counter()
    part = variant.part
    if sides is None:
        sides = tuple(part.stable_sides)
    else:  # a weight can make a side of the bare part unstable: it is left out
        sides = tuple(k for k in (part.check_side(s, require_stable=False, field="side") for s in sides)
                      if k in part.stable_sides)
        if not sides:
            raise InvalidStateError("sides", f"none of them is stable for {part.name} (stable: {list(part.stable_sides)})")
    X = _stops(part)
    if X.size == 0:
        raise InvalidStateError("part", f"too long for the arm: its outermost vertex passes {TABLE_X_MAX:g} m "
                                        f"from the drop zone {list(DROP_X)} m")
    with warnings.catch_warnings():  # a grid crosses regimes on purpose: the screen's shares are the verdict
        warnings.simplefilter("ignore", RegimeWarning)
        if exact:
            table = exact_table(part, arm, omega, sigma=sigma)
        else:
            table = recoil_table(part, arm, omega, sigma=sigma, step=TABLE_STEP, x_max=TABLE_X_MAX, workers=workers)
    best = {}
    for k in sides:
        p = first_passage(part, table, k, n=chains, throws=throws, seed=seed, x_range=DROP_X, X=X)
        score = np.where(p.holds, p.good - 2.0 * p.wrong, -np.inf)
        i = int(np.argmax(score))
        held = bool(p.holds[i])
        best[k] = (float(p.X[i]), float(p.good[i]) if held else 0.0, float(p.wrong[i]), held)
    side = max(best, key=lambda k: best[k][1] - 2.0 * best[k][2])
    X_k, good, wrong, _ = best[side]
    return Arrival(variant, float(omega), float(arm.h), int(side), X_k, good, wrong, best, int(chains),
                   time.perf_counter() - t0, "rigid_body" if exact else "engine")
