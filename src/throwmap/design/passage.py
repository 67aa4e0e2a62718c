"""First passage under the jittered recoil arm: which side reaches the arm's end first (Sec. V-C, corrected).

The feeder design of :mod:`throwmap.design.examples` places critical points on the exact
(impulse) map; the experiment's arm recoils (Flatland, :class:`~throwmap.engine.RecoilThrow`) and
jitters ω by σ = 3 % per throw, and on that map the side that reaches an end stop first is what
an end stop captures: a vertical stop holds *every* side that reaches it, because the flips that
would free a wrong side roll outward over its end vertex and the stop blocks them (measured:
``throwmap experiment feed``, 46/200 wrong-side captures of the impulse design).

This module measures, for a part on a plain arm:

* :func:`recoil_table` — the engine's one-throw map on a grid: every side, CM abscissa ``x``
  (step ``step`` m) and ω·(1 + σ z) for integer z ∈ [−3, 3] (pymunk, recoil arm, one throw each);
* :func:`first_passage` — Monte Carlo Markov chains on that table (ω jitter z ~ N(0, 1) rounded,
  random starts on the arm): for each end-stop position X (m) the share of chains whose
  outermost vertex first passes X on the target side (``good``), on another side (``wrong``; a chain
  that starts past X is there on the side it starts on),
  never within ``throws`` throws or after leaving the arm (the rest), and whether the target side
  with its outer vertex at X jogs *into* the stop for every z (``holds``: a necessary condition
  for the stop to keep it).

The table is a nearest-grid approximation (a chain at x uses the grid point nearest x and shifts
the landing by the offset, a translation the map does not quite have); :func:`first_passage` is a
screen for the design search, and the feeding experiment in the engine is the verdict.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError
from ..system.arm import Arm
from ..system.part import Part

__all__ = ["RecoilTable", "Passage", "recoil_table", "first_passage", "first_passages", "check_chains"]

Z_LEVELS = tuple(range(-3, 4))
"""ω levels of the table, in units of the jitter σ."""


@dataclass(frozen=True, slots=True, eq=False)
class RecoilTable:
    """The engine's one-throw map on a grid (SI units).

    ``status[a, k, i]``, ``x_next[a, k, i]``, ``side_next[a, k, i]``: the throw at
    ω·(1 + σ ``z[a]``) from rest on side ``k`` with CM abscissa ``x[i]`` (status ``-1``: no rest
    there, x + u_L ≤ 0). ``recoil`` (rad) and ``zeta`` the arm's recoil, ``h``/``mu`` the arm's.
    """

    x: np.ndarray
    z: tuple
    omega: float
    sigma: float
    h: float
    mu: float
    recoil: float
    zeta: float
    status: np.ndarray
    x_next: np.ndarray
    side_next: np.ndarray


def recoil_table(part: Part, arm: Arm, omega: float, *, sigma: float = 0.03, step: float = 0.005,
                 x_max: float = 0.56, recoil: float = math.radians(3.0), zeta: float = 0.2,
                 workers: int | None = None) -> RecoilTable:
    """Tabulate the recoil arm's throw map of ``part`` on the plain, unbounded ``arm`` (see the module docstring).

    Cost: 7 × (number of sides) × ``x_max/step`` engine throws (≈ 2,300 for the defaults, ≈ 10 s on 2 cores).
    """
    from ..engine.api import engine_batch
    from ..system.motion import RecoilThrow

    for name, v in (("omega", omega), ("sigma", sigma), ("step", step), ("x_max", x_max), ("recoil", recoil),
                    ("zeta", zeta)):
        if isinstance(v, bool) or not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise InvalidStateError(name, f"must be a finite number > 0, got {v!r}")
    if sigma >= 1.0 / 3.0:
        raise InvalidStateError("sigma", f"must be < 1/3 (the table throws at ω(1 − 3σ) > 0), got {sigma!r}")
    if zeta >= 1.0:
        raise InvalidStateError("zeta", f"must be < 1 (the recoil loop is underdamped), got {zeta!r}")
    if recoil > math.pi / 4:
        raise InvalidStateError("recoil", f"must be ≤ π/4 rad (45°), got {recoil!r}")
    if x_max / step > 5000:
        raise InvalidStateError("step", f"{x_max / step:.0f} grid points per side: use a step ≥ x_max/5000")
    if x_max / step < 10:
        raise InvalidStateError("step", f"must be ≤ x_max/10 = {x_max / 10:g} m (at least 10 grid points), got {step!r}")
    plain = Arm(h=arm.h, g=arm.g, length=None, mu=arm.mu, back=arm.back)
    xs = np.arange(0.0, x_max, step)
    sides = tuple(part.stable_sides)
    nk = max(sides) + 1
    st = np.full((len(Z_LEVELS), nk, xs.size), -1, dtype=np.int64)
    xn = np.full((len(Z_LEVELS), nk, xs.size), np.nan)
    sn = np.full((len(Z_LEVELS), nk, xs.size), -1, dtype=np.int64)
    uL = np.asarray(part.uL, dtype=float)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for a, z in enumerate(Z_LEVELS):
            w = omega * (1.0 + sigma * z)
            real = RecoilThrow.for_release_rate(w, recoil=recoil, zeta=zeta)
            for k in sides:
                valid = xs + uL[k] > 0.002
                r = engine_batch(part, plain, xs, np.full(xs.size, k), np.full(xs.size, w), valid=valid,
                                 workers=workers, realisation=real)
                st[a, k, valid] = np.asarray(r.status)[valid]
                xn[a, k, valid] = np.asarray(r.x)[valid]
                sn[a, k, valid] = np.asarray(r.side)[valid]
    return RecoilTable(xs, Z_LEVELS, float(omega), float(sigma), float(arm.h), float(arm.mu), float(recoil),
                       float(zeta), st, xn, sn)


@dataclass(frozen=True, slots=True, eq=False)
class Passage:
    """First passage over end-stop positions ``X`` (m, the outermost vertex's abscissa).

    ``good``/``wrong``: shares of ``n`` chains that first pass X on ``target`` / another side;
    ``holds``: the target side with its outer vertex at X jogs into the stop at every ω level;
    ``left``: share of chains that left the arm (behind the joint, or a refused throw) before passing.
    """

    X: np.ndarray
    good: np.ndarray
    wrong: np.ndarray
    holds: np.ndarray
    target: int
    n: int
    throws: int
    seed: int
    x_range: tuple

    def window(self, purity: float = 0.99) -> list:
        """The X (m) where ``good ≥ purity``, ``wrong == 0`` and the target side holds."""
        ok = (self.good >= purity) & (self.wrong == 0) & self.holds
        return [round(float(x), 9) for x in self.X[ok]]

    def rows(self) -> list[dict]:
        return [{"X_m": round(float(x), 9), "good": float(g), "wrong": float(w), "holds": bool(h)}
                for x, g, w, h in zip(self.X, self.good, self.wrong, self.holds)]


def _holds(part: Part, table: RecoilTable, target: int, X: float) -> bool:
    from ..records.outcome import Status

    step = float(table.x[1] - table.x[0])
    j = int(round((X - float(part.uR[target])) / step))
    if j < 0 or j >= table.x.size:
        return False
    for a in range(len(table.z)):
        if (table.status[a, target, j] != int(Status.OK) or table.side_next[a, target, j] != target
                or table.x_next[a, target, j] < table.x[j] - 1e-3):
            return False
    return True


def check_chains(n, throws, seed) -> None:
    """Refuse chain settings :func:`first_passage` cannot run (checked before a table is built)."""
    if isinstance(n, bool) or not (isinstance(n, int) and 1 <= n <= 1_000_000):
        raise InvalidStateError("n", f"must be an integer in [1, 1000000], got {n!r}")
    if isinstance(throws, bool) or not (isinstance(throws, int) and throws >= 1):
        raise InvalidStateError("throws", f"must be an integer ≥ 1, got {throws!r}")
    if isinstance(seed, bool) or not (isinstance(seed, (int, np.integer)) and seed >= 0):
        raise InvalidStateError("seed", f"must be an integer ≥ 0, got {seed!r}")


def first_passage(part: Part, table: RecoilTable, target: int, *, n: int = 3000, throws: int = 60, seed: int = 0,
                  x_range: tuple | None = None, X=None) -> Passage:
    """Markov chains on ``table`` from ``n`` random rests (side uniform, CM x uniform in ``x_range``, m;
    default from the joint to 0.35 m): see the module docstring."""
    target = part.check_side(target, field="target")
    if X is None:  # end stops from 30 cm (5 cm on a short table) to the table's end, every cm
        x_end = float(table.x[-1])
        X = np.arange(0.30 if x_end > 0.35 else 0.05, x_end, 0.01)
    return first_passages(part, table, {target: X}, n=n, throws=throws, seed=seed, x_range=x_range)[target]


def first_passages(part: Part, table: RecoilTable, stops: dict, *, n: int = 3000, throws: int = 60, seed: int = 0,
                   x_range: tuple | None = None) -> dict:
    """:func:`first_passage` for several targets at once: ``stops`` maps each target side to its end-stop positions
    X (m); the chains are run once, over every stop of every target, and each target's :class:`Passage` read off
    them (the same chains, so each equals what :func:`first_passage` gives for that target alone)."""
    from ..records.outcome import Status

    check_chains(n, throws, seed)
    stops = {part.check_side(t, field="target"): np.asarray(X, dtype=float) for t, X in stops.items()}
    for X in stops.values():
        if X.size == 0 or not np.all(np.isfinite(X)):
            raise InvalidStateError("X", f"needs at least one finite end-stop position inside the table (x ≤ {table.x[-1]:g} m)")
    X, where = np.unique(np.concatenate(list(stops.values())), return_inverse=True)
    rng = np.random.default_rng(seed)
    uL, uR = np.asarray(part.uL, dtype=float), np.asarray(part.uR, dtype=float)
    sides = np.asarray(part.stable_sides)
    step = float(table.x[1] - table.x[0])
    lo_x, hi_x = (0.0, 0.35) if x_range is None else (float(x_range[0]), float(x_range[1]))
    side = sides[rng.integers(0, sides.size, n)]
    lo = np.maximum(lo_x, -uL[side] + 0.003)
    x = lo + rng.uniform(0.0, 1.0, n) * np.maximum(hi_x - lo, 0.0)
    alive = np.ones(n, dtype=bool)
    first = np.full((X.size, n), -1)
    start = (x + uR[side])[None, :] > X[:, None]  # a part that starts past a stop is there on the side it rests on
    first = np.where(start, side[None, :], first)
    ok_status = int(Status.OK)
    for _ in range(throws):
        idx = np.flatnonzero(alive)
        if idx.size == 0:
            break
        a = np.clip(np.rint(rng.standard_normal(idx.size)), -3, 3).astype(int) + 3
        j = np.rint(x[idx] / step).astype(int)
        inside = (j >= 0) & (j < table.x.size)
        jj = np.clip(j, 0, table.x.size - 1)
        k = side[idx]
        st = table.status[a, k, jj]
        good = inside & (st == ok_status)
        alive[idx[~good]] = False
        g = idx[good]
        x[g] = table.x_next[a[good], k[good], jj[good]] + (x[g] - table.x[jj[good]])
        side[g] = table.side_next[a[good], k[good], jj[good]]
        v = x[g] + uR[side[g]]
        sub = first[:, g]
        hit = (sub < 0) & (v[None, :] > X[:, None])  # (stops, chains): first past the stop now
        first[:, g] = np.where(hit, side[g][None, :], sub)
    out = {}
    at = 0
    for target, Xt in stops.items():
        rows = first[where[at:at + Xt.size]]
        at += Xt.size
        good = (rows == target).mean(axis=1)
        wrong = ((rows >= 0) & (rows != target)).mean(axis=1)
        holds = np.array([_holds(part, table, target, float(Xq)) for Xq in Xt])
        out[target] = Passage(Xt, good, wrong, holds, int(target), int(n), int(throws), int(seed), (lo_x, hi_x))
    return out
