"""The recurrence test: orbits of a configuration map and the attractors they end on (paper Sec. III-D).

In the manner of Attractors.jl, each orbit is thrown ``transient`` times, then
``n_record`` more throws are recorded (every cap is a field of
:class:`~throwmap.analysis.caps.RecurrenceCaps`, with its default and unit).

* An orbit that fails a throw is an escape, with that throw's status as its fate.
* An orbit whose recorded tail repeats with period p ≤ ``max_period`` — every
  recorded state equals the one p throws later on the same side to within ``tol`` —
  is a cycle (p = 1: a fixed point), once the map confirms it: applied p times from
  the cycle's first point it must come back to within ``tol`` on the same side
  (:mod:`throwmap.analysis.cycles`; the residual is kept on the attractor). Cycles
  with the same points are one attractor.
* A tail that moves one way only on every side (a drift, or an approach that has not
  settled) lies on no attractor found: label −1, fate ``"unresolved"``; so is a group
  of wandering tails whose span still moves when ``max_transient`` runs out.
* Any other orbit is a band. Band orbits that share a cell of ``cell`` metres on a
  side are one attractor (union–find); its intervals are the recorded x per side,
  split where consecutive points are more than ``band_gap`` apart, and filled by
  images of the band (``fill_rounds`` rounds of ``n_fill`` throws).

While the recorded tails of the wandering orbits are not stationary (a side's span
differs between their halves by more than ``band_gap``), still close in on a cycle,
or lie on a set that leaks off the arm (a chaotic saddle: a long transient, not an
attractor), the orbits go on, up to ``max_transient`` throws discarded in all.

:func:`find_attractors` is the whole test and returns a :class:`Recurrence`; it knows
nothing of the results built on it (:class:`~throwmap.analysis.limitset.LimitSet`,
:class:`~throwmap.analysis.basins.Basins`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown
from ..kernels import codes as C
from ..rng import as_generator
from .attractors import FATE_UNRESOLVED, LABEL_ESCAPE, Attractor, merge_intervals
from .caps import RecurrenceCaps, resolve_caps
from .cycles import closing as _closing
from .cycles import cycle_residual, verified_cycles
from .maps import ConfigMap
from .tails import run_orbits

__all__ = ["Recurrence", "find_attractors", "run_orbits", "start_grid", "check_starts", "cycle_residual"]


# --- tests on the recorded tails -----------------------------------------------------------------------------


def _periods(X, S, max_period: int, tol: float) -> np.ndarray:
    """Smallest period p ≤ max_period of each recorded tail (0: none)."""
    m = X.shape[0]
    per = np.zeros(m, dtype=np.int64)
    for p in range(1, max_period + 1):
        todo = per == 0
        if not np.any(todo):
            break
        a, b = X[todo, p:], X[todo, :-p]
        same = np.all(np.abs(a - b) <= tol, axis=1) & np.all(S[todo, p:] == S[todo, :-p], axis=1)
        per[np.flatnonzero(todo)[same]] = p
    return per


def _stationary(X, S, gap: float) -> bool:
    """Whether the recorded tails look stationary: per side, the first and second halves span the same x to ``gap``."""
    h = X.shape[1] // 2
    for k in np.unique(S[S >= 0]):
        a = X[:, :h][S[:, :h] == k]
        b = X[:, h:][S[:, h:] == k]
        if a.size == 0 or b.size == 0:
            return False
        if abs(b.min() - a.min()) > gap or abs(b.max() - a.max()) > gap:
            return False
    return True


def _converging(X, tol: float) -> bool:
    """Whether some tail is still closing in on a cycle: its second half spans under half its first half."""
    h = X.shape[1] // 2
    a = np.nanmax(X[:, :h], axis=1) - np.nanmin(X[:, :h], axis=1)
    b = np.nanmax(X[:, h:], axis=1) - np.nanmin(X[:, h:], axis=1)
    return bool(np.any((b < 0.5 * a) & (a > tol)))


def _leaky(cmap: ConfigMap, X, S, gap: float, n: int = 200) -> bool:
    """Whether the set the tails wander on leaks: sampled images of its intervals leave the arm.

    A leaky chaotic set is a long transient (a chaotic saddle), not an attractor: its
    orbits are followed further until they escape or ``max_transient`` runs out.
    """
    ok = S >= 0
    bands = merge_intervals({int(k): X[ok & (S == k)] for k in np.unique(S[ok])}, gap)
    xs, ss = [], []
    for k, lo, hi in bands:
        xs.append(np.linspace(lo, hi, n) if hi > lo else np.array([lo]))
        ss.append(np.full(xs[-1].size, k, dtype=np.int64))
    if not xs:
        return False
    _, _, st = cmap(np.concatenate(xs), np.concatenate(ss))
    return bool(np.any(st != C.OK))


def _drifting(X, S, idx) -> np.ndarray:
    """Whether each tail moves one way only on every side it visits (≥ 3 times): a drift, not a band.

    A band orbit comes back (its same-side steps change sign); a tail that only moves
    on — a drift, or a monotone approach still unsettled — lies on no attractor found.
    """
    out = np.zeros(idx.size, dtype=bool)
    for j, i in enumerate(idx):
        seen = False
        drift = True
        for k in np.unique(S[i][S[i] >= 0]):
            d = np.diff(X[i][S[i] == k])
            if d.size < 2:
                continue
            seen = True
            if not (np.all(d > 0) or np.all(d < 0)):
                drift = False
                break
        out[j] = seen and drift
    return out


def _settle(cmap: ConfigMap, x0, s0, caps: RecurrenceCaps, progress=None):
    """Orbits until the wandering tails are stationary, converged and trapped (or ``max_transient`` is spent).

    Returns ``(X, S, fate, per, alive, used, settled)``: the recorded tails, fates, each
    tail's period (0: none; only tails that close under one more throw count), the starts
    still on the arm, the throws discarded in all, and whether the tails settled before
    ``max_transient`` ran out.
    """
    X, S, fate, fstep = run_orbits(cmap, x0, s0, caps.transient, caps.n_record, progress)
    m = X.shape[0]
    used = caps.transient
    late = bool(np.any(fstep > caps.transient))  # orbits escaped while being recorded
    while True:
        alive = np.flatnonzero(fate == C.OK)
        per = np.zeros(m, dtype=np.int64)
        if alive.size:
            per[alive] = _periods(X[alive], S[alive], caps.max_period, caps.tol)
            cyc = alive[per[alive] > 0]
            per[cyc[~_closing(cmap, X, S, cyc, per, caps.tol)]] = 0
        wander = alive[per[alive] == 0]
        if wander.size == 0 or (not late and _stationary(X[wander], S[wander], caps.band_gap)
                                and not _converging(X[wander], caps.tol)
                                and not _leaky(cmap, X[wander], S[wander], caps.band_gap)):
            return X, S, fate, per, alive, used, True
        if used + caps.n_record + caps.transient > caps.max_transient:
            return X, S, fate, per, alive, used, False
        # not yet stationary, still converging, or leaking orbits (a chaotic saddle, not an
        # attractor): go on from where the orbits are, discarding what was recorded
        Xn, Sn, fn, fs = run_orbits(cmap, X[alive, -1], S[alive, -1], caps.transient, caps.n_record)
        X[alive], S[alive], fate[alive] = Xn, Sn, fn
        late = bool(np.any(fs > caps.transient))
        used += caps.n_record + caps.transient


# --- grouping tails into attractors --------------------------------------------------------------------------


class _UnionFind:
    def __init__(self, n):
        self.p = list(range(n))

    def find(self, a):
        while self.p[a] != a:
            self.p[a] = self.p[self.p[a]]
            a = self.p[a]
        return a

    def union(self, a, b):
        ra, rb = self.find(a), self.find(b)
        if ra != rb:
            self.p[max(ra, rb)] = min(ra, rb)


def _band_groups(X, S, band_idx, caps: RecurrenceCaps) -> list:
    """Aperiodic tails grouped into bands: shared cells of ``cell`` m, then overlapping hulls (to ``band_gap``)."""
    if band_idx.size == 0:
        return []
    span = int(np.ceil(np.nanmax(np.abs(X[band_idx])) / caps.cell)) + 2
    keys = S[band_idx] * span + np.floor(X[band_idx] / caps.cell).astype(np.int64)
    owner = np.repeat(np.arange(band_idx.size), keys.shape[1])
    kf = keys.ravel()
    order = np.lexsort((owner, kf))
    kf, owner = kf[order], owner[order]
    uf = _UnionFind(band_idx.size)
    same = np.flatnonzero(kf[1:] == kf[:-1])
    for a, b in zip(owner[same], owner[same + 1]):
        if a != b:
            uf.union(int(a), int(b))
    roots: dict[int, list[int]] = {}
    for j in range(band_idx.size):
        roots.setdefault(uf.find(j), []).append(int(band_idx[j]))
    groups = list(roots.values())
    if len(groups) > 1:  # band orbits whose intervals overlap (to band_gap) on some side are one band
        gap = caps.band_gap
        hulls = [merge_intervals({int(k): X[g].ravel()[S[g].ravel() == k] for k in np.unique(S[g])}, gap)
                 for g in groups]
        uf = _UnionFind(len(groups))
        for a in range(len(groups)):
            for b in range(a + 1, len(groups)):
                if any(p[0] == q[0] and p[1] <= q[2] + gap and q[1] <= p[2] + gap for p in hulls[a] for q in hulls[b]):
                    uf.union(a, b)
        joined: dict[int, list[int]] = {}
        for a, g in enumerate(groups):
            joined.setdefault(uf.find(a), []).extend(g)
        groups = list(joined.values())
    return groups


# --- describing an attractor ---------------------------------------------------------------------------------


def _fill(cmap: ConfigMap, xs, ss, caps: RecurrenceCaps) -> tuple:
    """A band's intervals: recorded points merged across ``band_gap``, then gaps filled by images.

    Each round samples the current intervals (``n_fill`` points in all, by length) and
    adds the images that stay on the arm; a gap that no image of the band reaches is real.
    """
    gap = caps.band_gap
    xs = np.asarray(xs, dtype=float)
    ss = np.asarray(ss, dtype=np.int64)
    bands = merge_intervals({int(k): xs[ss == k] for k in np.unique(ss)}, gap)
    for _ in range(caps.fill_rounds):
        if caps.n_fill <= 0:
            break
        lengths = np.array([hi - lo for _, lo, hi in bands])
        share = lengths / lengths.sum() if lengths.sum() > 0 else np.full(len(bands), 1.0 / len(bands))
        px, ps = [], []
        for (k, lo, hi), w in zip(bands, share):
            n = max(2, int(round(w * caps.n_fill)))
            px.append(np.linspace(lo, hi, n))
            ps.append(np.full(n, k, dtype=np.int64))
        xn, sn, st = cmap(np.concatenate(px), np.concatenate(ps))
        ok = st == C.OK
        xs = np.concatenate((xs, xn[ok]))
        ss = np.concatenate((ss, sn[ok]))
        new = merge_intervals({int(k): xs[ss == k] for k in np.unique(ss)}, gap)
        if new == bands:
            break
        bands = new
    return bands


def _slopes(cmap: ConfigMap, x, s, h: float) -> np.ndarray:
    """dT/dx at each configuration by central differences (one-sided across a branch switch; nan if none)."""
    x = np.asarray(x, dtype=float)
    s = np.asarray(s, dtype=np.int64)
    xp, sp, stp = cmap(x + h, s)
    xm, sm, stm = cmap(np.maximum(x - h, np.array([cmap.x_lo[int(k)] for k in s]) + 1e-12), s)
    x0, s0, st0 = cmap(x, s)
    right = (stp == C.OK) & (st0 == C.OK) & (sp == s0)
    left = (stm == C.OK) & (st0 == C.OK) & (sm == s0)
    slope = np.full(x.size, np.nan)
    both = right & left
    slope[both] = (xp[both] - xm[both]) / (2 * h)
    r = right & ~left
    slope[r] = (xp[r] - x0[r]) / h
    lft = left & ~right
    slope[lft] = (x0[lft] - xm[lft]) / h
    return slope


def _describe_cycle(cmap: ConfigMap, pts, members, residual: float, caps: RecurrenceCaps) -> dict:
    """A fixed point or cycle: multiplier Π dT/dx and Lyapunov exponent mean log|dT/dx| along it."""
    p = len(pts)
    xs = np.array([q[1] for q in pts])
    ss = np.array([q[0] for q in pts])
    sl = _slopes(cmap, xs, ss, caps.fd_step)
    finite = np.all(np.isfinite(sl))
    mult = float(np.prod(sl)) if finite else math.nan
    lyap = float(np.mean(np.log(np.abs(sl)))) if finite and np.all(sl != 0) else (-math.inf if finite else math.nan)
    visits = tuple((int(k), float(np.mean(ss == k))) for k in np.unique(ss))
    return dict(kind="fixed_point" if p == 1 else "cycle", period=p, points=pts,
                bands=tuple(sorted((s, x, x) for s, x in pts)), multiplier=mult, lyapunov=lyap,
                members=members, side_visits=visits, key=(0, pts[0][0], pts[0][1]), residual=residual)


def _describe_band(cmap: ConfigMap, X, S, members, caps: RecurrenceCaps) -> dict:
    """A band: its filled intervals and the Lyapunov exponent over up to 200 of its recorded points."""
    xs = X[members].ravel()
    ss = S[members].ravel()
    bands = _fill(cmap, xs, ss, caps)
    pick = np.linspace(0, xs.size - 1, min(200, xs.size)).astype(int)
    sl = _slopes(cmap, xs[pick], ss[pick], caps.fd_step)
    good = np.isfinite(sl) & (sl != 0)
    lyap = float(np.mean(np.log(np.abs(sl[good])))) if np.any(good) else math.nan
    visits = tuple((int(k), float(np.mean(ss == k))) for k in np.unique(ss))
    return dict(kind="band", period=0, points=(), bands=bands, multiplier=math.nan, lyapunov=lyap,
                members=members, side_visits=visits, key=(1, bands[0][0], bands[0][1]), residual=math.nan)


# --- the test ------------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True, eq=False)
class Recurrence:
    """What the recurrence test found from a set of starts.

    ``attractors`` numbered from 1 in (kind, side, x) order, ``fraction`` = share of
    these starts; per start its ``labels`` (−1 for escapes) and ``fates`` (0 attracted,
    else the escape status); the recorded tails ``x_tail`` (m) and ``side_tail``
    (shape (starts, n_record)); ``transient_used``: throws discarded in all.
    """

    attractors: tuple
    labels: np.ndarray
    fates: np.ndarray
    x_tail: np.ndarray
    side_tail: np.ndarray
    transient_used: int

    def __repr__(self) -> str:
        kinds = ", ".join(f"#{a.id} {a.kind}" for a in self.attractors[:4])
        more = " …" if len(self.attractors) > 4 else ""
        return (f"Recurrence({self.labels.size} starts: {kinds or 'no attractor'}{more}; "
                f"-1 {int(np.sum(self.labels == LABEL_ESCAPE))}; {self.transient_used} throws discarded)")


def find_attractors(cmap: ConfigMap, x0, s0, caps: RecurrenceCaps | None = None, progress=None) -> Recurrence:
    """The recurrence test on the orbits of the given starts (see the module docstring).

    ``caps`` is a :class:`~throwmap.analysis.caps.RecurrenceCaps` (or a mapping of
    caps; default: the defaults). Returns a :class:`Recurrence`.
    """
    caps = resolve_caps(caps)
    X, S, fate, per, alive, used, settled = _settle(cmap, x0, s0, caps, progress)
    m = X.shape[0]
    cycles, demoted = verified_cycles(cmap, X, S, alive[per[alive] > 0], per, caps)
    per[demoted] = 0
    wander = alive[per[alive] == 0]
    # a tail that only moves on (a drift) is on no attractor; nor, once max_transient ran
    # out, is a group of tails whose span still moves (not stationary): both are unresolved
    drift = wander[_drifting(X, S, wander)]
    fate[drift] = FATE_UNRESOLVED
    groups = _band_groups(X, S, np.setdiff1d(wander, drift), caps)
    if not settled:
        keep = []
        for g in groups:
            if _stationary(X[g], S[g], caps.band_gap):
                keep.append(g)
            else:
                fate[g] = FATE_UNRESOLVED
        groups = keep
    found = [_describe_cycle(cmap, pts, members, res, caps) for pts, members, res in cycles]
    found += [_describe_band(cmap, X, S, members, caps) for members in groups]
    found.sort(key=lambda d: d["key"])
    labels = np.full(m, LABEL_ESCAPE, dtype=np.int64)
    attractors = []
    for k, d in enumerate(found, start=1):
        labels[d["members"]] = k
        attractors.append(Attractor(id=k, kind=d["kind"], period=d["period"], points=d["points"],
                                    bands=d["bands"], multiplier=d["multiplier"], lyapunov=d["lyapunov"],
                                    fraction=len(d["members"]) / m if m else 0.0, side_visits=d["side_visits"],
                                    residual=d["residual"]))
    return Recurrence(attractors=tuple(attractors), labels=labels, fates=fate, x_tail=X, side_tail=S,
                      transient_used=int(used))


# --- starting configurations ---------------------------------------------------------------------------------


def start_grid(cmap: ConfigMap, n_starts: int, rng) -> tuple[np.ndarray, np.ndarray]:
    """``n_starts`` configurations per side, one drawn uniformly in each of n equal cells of (x_lo, x_hi]."""
    if isinstance(n_starts, bool) or not isinstance(n_starts, (int, np.integer)) or n_starts < 1:
        raise InvalidStateError("n_starts", f"must be a positive integer, got {shown(n_starts)}")
    gen = as_generator(rng)
    xs, ss = [], []
    for s in cmap.sides:
        lo, hi = cmap.x_lo[s], cmap.x_hi[s]
        edges = np.linspace(lo, hi, int(n_starts) + 1)
        u = gen.uniform(0.0, 1.0, int(n_starts))
        x = edges[:-1] + (1.0 - u) * np.diff(edges)  # in (lo, hi]
        xs.append(x)
        ss.append(np.full(int(n_starts), s, dtype=np.int64))
    return np.concatenate(xs), np.concatenate(ss)


def check_starts(cmap: ConfigMap, starts) -> tuple[np.ndarray, np.ndarray]:
    """Validate user-given ``(x, side)`` starts against the map's domain."""
    try:
        x, s = starts
    except (TypeError, ValueError):
        raise InvalidStateError("starts", "must be a pair of arrays (x, side)") from None
    x = np.atleast_1d(np.asarray(x, dtype=float)).ravel()
    s = np.atleast_1d(np.asarray(s)).ravel()
    if s.size == 1 and x.size > 1:
        s = np.full(x.size, s[0])
    if x.size == 0 or x.size != s.size:
        raise InvalidStateError("starts", f"need as many sides as x (got {x.size} x and {s.size} sides)")
    if not np.all(np.isfinite(x)):
        raise InvalidStateError("starts", "x must be finite")
    bad = ~np.isin(s, cmap.sides)
    if np.any(bad):
        raise InvalidStateError("starts", f"side {shown(s[bad][0])} is not a stable side {list(cmap.sides)}")
    s = s.astype(np.int64)
    lo = np.array([cmap.x_lo[int(k)] for k in s])
    if np.any(x <= lo):
        i = int(np.flatnonzero(x <= lo)[0])
        raise InvalidStateError("starts", f"x[{i}] = {x[i]:.6g} m is at or behind the first valid x on side "
                                          f"{s[i]} ({lo[i]:.6g} m)")
    return x, s
