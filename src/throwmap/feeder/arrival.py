"""The feeder search's screens: which side arrives first at an end stop, on the exact model or the engine's table.

An end stop holds whatever side reaches it first (the flips that would free a wrong side roll outward,
into the stop), so a pocket at the arm's end feeds side k when, under the arm that really throws
(the recoiling arm with ω jitter), side k is the first to pass the stop from wherever the part is
dropped, and side k jogs into the stop at every ω the jitter gives. :func:`arrival` measures both
on the engine's tabulated one-throw map (:func:`throwmap.design.passage.recoil_table`, 1 cm grid,
ω·(1 + σz) for z = −3 … 3) with Markov chains from drops over the inner arm
(:func:`throwmap.design.passage.first_passage`), for end stops X from just beyond the drop zone
to the table's end. A candidate's score is its best X's share of chains that arrive first on the
target side where that side holds (its *predicted* feed rate); a wrong arrival counts against it.

With a pocket (``pocket_depth`` > 0) the stop a side meets first is the pocket's lip, not its end wall: the
floor is as long as the part's footprint on the target side plus a clearance (:func:`pocket_clearance`) and its lip a ramp down to it
(:class:`~throwmap.design.cavity.Pocket`), so a part whose outermost vertex passes the lip's top edge tips in on
whatever side it lies — a wrong side jams there, tilted (measured in the feeding experiment: a part screened
"first at the wall" was caught by the lip on a side that would have flipped to the target a few cm farther
out). Arrival is therefore counted at the lip, ``X − (ℓ_k + clearance + depth / tan ramp)`` for target side k,
and ``X`` is the end wall.

Drops: CM abscissa uniform over ``DROP_X`` (a chute onto the inner arm); end walls are considered from
beyond every side's outermost vertex from there (+1 cm) to ``WALL_X_MAX``; a pocket's lip may lie over the drop
zone, and a part dropped past it is in the pocket on the side it was dropped on.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, RegimeWarning
from ..system.arm import Arm
from .family import Variant

__all__ = ["Arrival", "arrival", "arrivals", "screen_table", "exact_table", "lip_offset", "pocket_clearance", "DROP_X", "TABLE_STEP", "TABLE_X_MAX", "WALL_X_MAX"]

DROP_X = (0.0, 0.25)
"""The drop zone: CM abscissa range over which parts arrive on the arm, m."""
TABLE_STEP = 0.01
"""The grid of the engine table, m."""
TABLE_X_MAX = 0.56
"""The table's reach, m (the draft's arm is about 0.6 m)."""
WALL_X_MAX = 0.6
"""The farthest end wall screened, m (the draft's arm is about 0.6 m long)."""


def pocket_clearance(part, side: int) -> float:
    """The floor a pocket for ``side`` needs beyond the side's length, m: the part's overhang past both ends of the
    side (its footprint on the floor, the width of its vertices projected on the side, less the side's length — a
    part whose side meets its neighbours at obtuse angles is wider than the side) plus the
    :class:`~throwmap.design.cavity.Pocket` clearance (5 mm). A pocket only the side's length long wedges such a
    part tilted against its end wall (measured: every trial of a pentagon with 5 cm of overhang)."""
    from ..design.cavity import Pocket

    w = np.asarray(part.w, dtype=float)
    ell = float(part.length[side])
    proj = (w - w[side]) @ ((w[(side + 1) % len(w)] - w[side]) / ell)  # the vertices along the side
    return max(float(proj.max() - proj.min()) - ell, 0.0) + float(Pocket().clearance)


def lip_offset(part, side: int, depth: float) -> float:
    """How far inward of the end wall a pocket ``depth`` m deep for ``side`` begins (the top of its lip ramp), m:
    ``ℓ_side + clearance + depth / tan(ramp)``, the clearance of :func:`pocket_clearance`, the ramp of
    :class:`~throwmap.design.cavity.Pocket` (0 for ``depth`` 0: a plain end stop)."""
    if depth <= 0:
        return 0.0
    from ..design.cavity import Pocket

    return (float(part.length[side]) + pocket_clearance(part, side)
            + float(depth) / math.tan(float(Pocket().ramp_angle)))


@dataclass(frozen=True, slots=True, eq=False)
class Arrival:
    """One screened feeder: the ``variant`` (part and weight) thrown at ``omega`` (rad/s) from an arm at ``h`` (m);
    per stable side its best end stop: ``best[k] = (X m, share first on k, share first on another side, holds)``;
    ``side`` the target side and ``X`` its end stop (m), ``predicted`` its share (0 when no X holds), ``time_s`` the
    screen's seconds (``screen_time_s`` in :meth:`to_dict`)."""

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
    lip: bool = False

    def to_dict(self) -> dict:
        return {"variant": self.variant.to_dict(), "omega_rad_s": self.omega, "h_m": self.h, "side": self.side,
                "end_stop_m": self.X, "predicted": self.predicted, "wrong_first": self.wrong,
                "per_side": {str(k): {"end_stop_m": v[0], "first": v[1], "wrong_first": v[2], "holds": v[3]}
                             for k, v in self.best.items()},
                "chains": self.chains, "model": self.model, "screen_time_s": self.time_s,
                "arrival_at": "pocket lip" if self.lip else "end wall"}


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
    """The end walls screened, every cm from just beyond every side's outermost vertex over the drop zone to
    ``WALL_X_MAX``, m."""
    lo = DROP_X[1] + float(np.max(part.uR)) + 0.01
    return np.round(np.arange(math.ceil(lo * 100) / 100, WALL_X_MAX + 1e-9, 0.01), 6)


def screen_table(part, omega: float, arm: Arm, *, sigma: float = 0.03, exact: bool = False,
                 workers: int | None = None):
    """The one-throw map a screen runs on: ``exact`` False, the engine's recoil table
    (:func:`throwmap.design.passage.recoil_table`, 7 × (stable sides) × 56 throws, 5–30 s on 2 cores); True,
    :func:`exact_table` on the exact "rigid_body" model, the impulse throw (the cheap screen, < 0.1 s)."""
    from ..design.passage import recoil_table

    with warnings.catch_warnings():  # a grid crosses regimes on purpose: the screen's shares are the verdict
        warnings.simplefilter("ignore", RegimeWarning)
        if exact:
            return exact_table(part, arm, omega, sigma=sigma)
        return recoil_table(part, arm, omega, sigma=sigma, step=TABLE_STEP, x_max=TABLE_X_MAX, workers=workers)


def arrival(variant: Variant, omega: float, arm: Arm, *, sides=None, sigma: float = 0.03, chains: int = 1500,
            throws: int = 60, seed: int = 0, table=None, pocket_depth: float = 0.0) -> Arrival:
    """Screen ``variant`` thrown at ``omega`` from the plain ``arm`` (its h, g and μ; see the module docstring) on
    ``table`` (:func:`screen_table`; None: the engine's, computed here): the best end wall of every side in ``sides``
    (None: every stable side) — arrival counted at the lip of a pocket ``pocket_depth`` m deep (0: at the end wall
    itself) —, and the side with the highest share."""
    return arrivals(variant, omega, arm, sides=sides, sigma=sigma, chains=chains, throws=throws, seed=seed,
                    table=table, depths=(pocket_depth,))[0]


def arrivals(variant: Variant, omega: float, arm: Arm, *, sides=None, sigma: float = 0.03, chains: int = 1500,
             throws: int = 60, seed: int = 0, table=None, depths=(0.0,)) -> list:
    """:func:`arrival` for each pocket depth in ``depths`` (m), on one run of the chains
    (:func:`throwmap.design.passage.first_passages`): each equals :func:`arrival` at that depth alone."""
    import time

    from ..design.passage import first_passages

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
        raise InvalidStateError("part", f"too long for the arm: its outermost vertex passes {WALL_X_MAX:g} m "
                                        f"from the drop zone {list(DROP_X)} m")
    exact = table is not None and float(table.recoil) == 0.0
    if table is None:
        table = screen_table(part, omega, arm, sigma=sigma)
    lips = {}  # (side, depth) → (offset, the lips inside the table)
    for d in depths:
        for k in sides:
            off = lip_offset(part, k, d)
            at = np.round(X - off, 6)
            lips[(k, d)] = (off, at[(at > 0.02) & (at <= TABLE_X_MAX - TABLE_STEP + 1e-9)])  # inside the table
    want = {}
    for (k, d), (_, at) in lips.items():
        if at.size:
            want[k] = np.union1d(want.get(k, np.zeros(0)), at)
    passages = first_passages(part, table, want, n=chains, throws=throws, seed=seed, x_range=DROP_X) if want else {}
    out = []
    for d in depths:
        best = {}
        for k in sides:
            off, at = lips[(k, d)]
            if at.size == 0:
                best[k] = (math.nan, 0.0, 1.0, False)
                continue
            p = passages[k]
            rows = np.searchsorted(p.X, at)
            good, wrong, holds = p.good[rows], p.wrong[rows], p.holds[rows]
            score = np.where(holds, good - 2.0 * wrong, -np.inf)
            i = int(np.argmax(score))
            held = bool(holds[i])
            best[k] = (round(float(at[i]) + off, 6), float(good[i]) if held else 0.0, float(wrong[i]), held)
        side = max(best, key=lambda k: best[k][1] - 2.0 * best[k][2])
        X_k, good, wrong, _ = best[side]
        out.append(Arrival(variant, float(omega), float(arm.h), int(side), X_k, good, wrong, best, int(chains),
                           (time.perf_counter() - t0) / len(depths), "rigid_body" if exact else "engine", d > 0))
    return out
