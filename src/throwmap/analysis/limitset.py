"""Forward limit sets of a throw map, whatever their kind (paper Sec. III-D, Fig. 5).

:func:`limit_set` iterates a map from many initial configurations and describes
where the orbits end: fixed points and cycles (period, multiplier, stability),
bands (intervals per side, with their Lyapunov exponent), and escapes (label −1,
see :mod:`throwmap.analysis.attractors`).

Method (a recurrence test in the manner of Attractors.jl): each orbit is thrown
``transient`` times, then ``n_record`` more throws are recorded.

* An orbit that fails a throw is an escape, with that throw's status as its fate.
* An orbit whose recorded tail repeats with period p ≤ ``max_period`` — every
  recorded state equals the one p throws later on the same side to within ``tol`` —
  is a cycle (p = 1: a fixed point). Cycles with the same points are one attractor.
* Any other orbit is a band. Band orbits that share a cell of ``cell`` metres on a
  side are one attractor (union–find); its intervals are the recorded x per side,
  split where consecutive points are more than ``band_gap`` apart.

Notes
-----
The paper (Sec. III-D) speaks of a *unique* limit set S with ``sup S = {r_i}`` and
``inf S = {l_i}`` and draws it as a cycle of jogs and flips (Fig. 5). For the
canonical triangle every branch of the map stretches x (slopes 1.04–1.33), so S is
a union of bands with a positive Lyapunov exponent, not a finite cycle; here the
kind is found, not assumed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError
from ..kernels import codes as C
from .attractors import LABEL_ESCAPE, Attractor, fate_label, merge_intervals
from .maps import DEFAULT_MODEL, ConfigMap, as_map

__all__ = ["LimitSet", "limit_set", "find_attractors", "DEFAULT_CAPS", "check_caps"]

DEFAULT_CAPS = {
    "transient": 200,  # throws discarded before recording (and per extension block)
    "max_transient": 5000,  # most throws discarded while the recorded tails are not yet stationary
    "n_record": 400,  # throws recorded per orbit
    "tol": 1e-8,  # m: a recurrence / cycle-identity tolerance
    "max_period": 32,  # longest cycle looked for
    "cell": 1e-3,  # m: band orbits sharing a cell of this size belong to one attractor
    "band_gap": 2e-3,  # m: a band's recorded points further apart than this start a new interval
    "fd_step": 1e-6,  # m: finite-difference step for slopes (multipliers, Lyapunov exponents)
    "n_fill": 2000,  # throws per round that fill a band's sampling gaps with images of its intervals
    "fill_rounds": 2,  # such rounds
}
"""Every cap of the recurrence test, with its default (documented in :func:`limit_set`)."""


def _int_cap(name, v, lo):
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < lo:
        raise InvalidStateError(name, f"must be an integer ≥ {lo}, got {v!r}")
    return int(v)


def _pos_cap(name, v):
    if isinstance(v, bool) or not isinstance(v, (int, float, np.floating, np.integer)) or not (
        math.isfinite(float(v)) and float(v) > 0
    ):
        raise InvalidStateError(name, f"must be a positive finite length in m, got {v!r}")
    return float(v)


def check_caps(**caps) -> dict:
    """Validate the recurrence caps (defaults from :data:`DEFAULT_CAPS`); one-line errors name the cap."""
    out = dict(DEFAULT_CAPS)
    caps.pop("transient_used", None)  # a record of a past run, not a cap
    for k, v in caps.items():
        if k not in DEFAULT_CAPS:
            raise InvalidStateError(k, f"unknown cap (caps: {', '.join(DEFAULT_CAPS)})")
        if v is not None:
            out[k] = v
    out["transient"] = _int_cap("transient", out["transient"], 0)
    out["n_record"] = _int_cap("n_record", out["n_record"], 2)
    out["max_period"] = _int_cap("max_period", out["max_period"], 1)
    out["max_transient"] = _int_cap("max_transient", out["max_transient"], out["transient"])
    out["n_fill"] = _int_cap("n_fill", out["n_fill"], 0)
    out["fill_rounds"] = _int_cap("fill_rounds", out["fill_rounds"], 0)
    if out["n_record"] < 2 * out["max_period"]:
        raise InvalidStateError("n_record", f"must be at least 2 × max_period = {2 * out['max_period']}, "
                                            f"got {out['n_record']}")
    for k in ("tol", "cell", "band_gap", "fd_step"):
        out[k] = _pos_cap(k, out[k])
    return out


def run_orbits(cmap: ConfigMap, x0, s0, n_skip: int, n_record: int, progress=None):
    """Iterate ``cmap`` ``n_skip + n_record`` times from every start; record the last ``n_record``.

    Returns ``(X, S, fate, fate_step)``: recorded x (m) and sides, shape (M, n_record),
    nan / −1 after an escape; ``fate`` the escape status (0 if none) and ``fate_step``
    the step at which it happened (−1 if none). ``progress(done, total)`` after each step.
    """
    x = np.array(x0, dtype=float).ravel()
    s = np.array(s0).ravel().astype(np.int64)
    m = x.size
    X = np.full((m, n_record), np.nan)
    S = np.full((m, n_record), -1, dtype=np.int64)
    fate = np.zeros(m, dtype=np.int64)
    fate_step = np.full(m, -1, dtype=np.int64)
    total = n_skip + n_record
    for t in range(total):
        alive = np.flatnonzero(fate == C.OK)
        if alive.size == 0:
            if progress is not None:
                progress(total, total)
            break
        xn, sn, st = cmap(x[alive], s[alive])
        bad = st != C.OK
        fate[alive[bad]] = st[bad]
        fate_step[alive[bad]] = t + 1
        x[alive] = np.where(bad, x[alive], xn)
        s[alive] = np.where(bad, s[alive], sn)
        if t >= n_skip:
            ok = alive[~bad]
            X[ok, t - n_skip] = x[ok]
            S[ok, t - n_skip] = s[ok]
        if progress is not None:
            progress(t + 1, total)
    return X, S, fate, fate_step


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


def _fill(cmap: ConfigMap, xs, ss, caps: dict) -> tuple:
    """A band's intervals: recorded points merged across ``band_gap``, then gaps filled by images.

    Each round samples the current intervals (``n_fill`` points in all, by length) and
    adds the images that stay on the arm; a gap that no image of the band reaches is real.
    """
    gap = caps["band_gap"]
    xs = np.asarray(xs, dtype=float)
    ss = np.asarray(ss, dtype=np.int64)
    bands = merge_intervals({int(k): xs[ss == k] for k in np.unique(ss)}, gap)
    for _ in range(caps["fill_rounds"]):
        if caps["n_fill"] <= 0:
            break
        lengths = np.array([hi - lo for _, lo, hi in bands])
        share = lengths / lengths.sum() if lengths.sum() > 0 else np.full(len(bands), 1.0 / len(bands))
        px, ps = [], []
        for (k, lo, hi), w in zip(bands, share):
            n = max(2, int(round(w * caps["n_fill"])))
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


def _canonical_cycle(xs, ss):
    """Rotate a cycle to start at its smallest (side, x)."""
    k = min(range(len(xs)), key=lambda i: (ss[i], xs[i]))
    return tuple((int(ss[(k + i) % len(xs)]), float(xs[(k + i) % len(xs)])) for i in range(len(xs)))


def find_attractors(cmap: ConfigMap, x0, s0, caps: dict, progress=None):
    """The recurrence test on the orbits of the given starts (see the module docstring).

    Returns ``(attractors, labels, fates, X, S)``: attractors numbered from 1 with
    ``fraction`` = share of these starts; per start its label (−1 for escapes) and
    fate code (0 attracted, else the escape status); the recorded tails.
    """
    X, S, fate, fstep = run_orbits(cmap, x0, s0, caps["transient"], caps["n_record"], progress)
    m = X.shape[0]
    used = caps["transient"]
    late = bool(np.any(fstep > caps["transient"]))  # orbits escaped while being recorded
    while True:
        alive = np.flatnonzero(fate == C.OK)
        per = np.zeros(m, dtype=np.int64)
        if alive.size:
            per[alive] = _periods(X[alive], S[alive], caps["max_period"], caps["tol"])
        wander = alive[per[alive] == 0]
        if wander.size == 0 or (not late and _stationary(X[wander], S[wander], caps["band_gap"])
                                and not _converging(X[wander], caps["tol"])
                                and not _leaky(cmap, X[wander], S[wander], caps["band_gap"])):
            break
        if used + caps["n_record"] + caps["transient"] > caps["max_transient"]:
            break
        # not yet stationary, still converging, or leaking orbits (a chaotic saddle, not an
        # attractor): go on from where the orbits are, discarding what was recorded
        Xn, Sn, fn, fs = run_orbits(cmap, X[alive, -1], S[alive, -1], caps["transient"], caps["n_record"])
        X[alive], S[alive], fate[alive] = Xn, Sn, fn
        late = bool(np.any(fs > caps["transient"]))
        used += caps["n_record"] + caps["transient"]
    caps["transient_used"] = used
    labels = np.full(m, LABEL_ESCAPE, dtype=np.int64)
    tol = caps["tol"]
    # cycles
    cycles: list[tuple] = []  # (canonical points, member starts)
    for i in alive[per[alive] > 0]:
        p = per[i]
        pts = _canonical_cycle(X[i, -p:], S[i, -p:])
        for c in cycles:
            if len(c[0]) == p and all(a[0] == b[0] and abs(a[1] - b[1]) <= 10 * tol for a, b in zip(c[0], pts)):
                c[1].append(i)
                break
        else:
            cycles.append((pts, [i]))
    # bands: union-find over shared cells
    band_idx = alive[per[alive] == 0]
    groups: list[list[int]] = []
    if band_idx.size:
        span = int(np.ceil(np.nanmax(np.abs(X[band_idx])) / caps["cell"])) + 2
        keys = S[band_idx] * span + np.floor(X[band_idx] / caps["cell"]).astype(np.int64)
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
    found = []
    merged: list[tuple] = []
    for pts, members in cycles:
        if len({q[0] for q in pts}) == 1 and max(q[1] for q in pts) - min(q[1] for q in pts) <= 10 * tol:
            pts = (pts[0],)  # a "cycle" whose points coincide is a fixed point not yet settled to tol
        for c in merged:
            if len(c[0]) == len(pts) and all(a[0] == b[0] and abs(a[1] - b[1]) <= 10 * tol for a, b in zip(c[0], pts)):
                c[1].extend(members)
                break
        else:
            merged.append((pts, list(members)))
    cycles = merged
    # band orbits whose intervals overlap (to band_gap) on some side are one band
    if len(groups) > 1:
        hulls = [merge_intervals({int(k): X[g].ravel()[S[g].ravel() == k] for k in np.unique(S[g])}, caps["band_gap"])
                 for g in groups]
        uf = _UnionFind(len(groups))
        for a in range(len(groups)):
            for b in range(a + 1, len(groups)):
                if any(p[0] == q[0] and p[1] <= q[2] + caps["band_gap"] and q[1] <= p[2] + caps["band_gap"]
                       for p in hulls[a] for q in hulls[b]):
                    uf.union(a, b)
        joined: dict[int, list[int]] = {}
        for a, g in enumerate(groups):
            joined.setdefault(uf.find(a), []).extend(g)
        groups = list(joined.values())
    for pts, members in cycles:
        p = len(pts)
        xs = np.array([q[1] for q in pts])
        ss = np.array([q[0] for q in pts])
        sl = _slopes(cmap, xs, ss, caps["fd_step"])
        mult = float(np.prod(sl)) if np.all(np.isfinite(sl)) else math.nan
        lyap = float(np.mean(np.log(np.abs(sl)))) if np.all(np.isfinite(sl)) and np.all(sl != 0) else (
            -math.inf if np.all(np.isfinite(sl)) else math.nan)
        visits = tuple((int(k), float(np.mean(ss == k))) for k in np.unique(ss))
        found.append(dict(kind="fixed_point" if p == 1 else "cycle", period=p, points=pts,
                          bands=tuple(sorted((s, x, x) for s, x in pts)), multiplier=mult, lyapunov=lyap,
                          members=members, side_visits=visits, key=(0, pts[0][0], pts[0][1])))
    for members in groups:
        xs = X[members].ravel()
        ss = S[members].ravel()
        bands = _fill(cmap, xs, ss, caps)
        pick = np.linspace(0, xs.size - 1, min(200, xs.size)).astype(int)
        sl = _slopes(cmap, xs[pick], ss[pick], caps["fd_step"])
        good = np.isfinite(sl) & (sl != 0)
        lyap = float(np.mean(np.log(np.abs(sl[good])))) if np.any(good) else math.nan
        visits = tuple((int(k), float(np.mean(ss == k))) for k in np.unique(ss))
        found.append(dict(kind="band", period=0, points=(), bands=bands, multiplier=math.nan, lyapunov=lyap,
                          members=members, side_visits=visits, key=(1, bands[0][0], bands[0][1])))
    found.sort(key=lambda d: d["key"])
    attractors = []
    for k, d in enumerate(found, start=1):
        labels[d["members"]] = k
        attractors.append(Attractor(id=k, kind=d["kind"], period=d["period"], points=d["points"],
                                    bands=d["bands"], multiplier=d["multiplier"], lyapunov=d["lyapunov"],
                                    fraction=len(d["members"]) / m if m else 0.0, side_visits=d["side_visits"]))
    return tuple(attractors), labels, fate, X, S


def escape_fractions(fates, labels) -> dict:
    """``{fate label: share}`` over the starts labelled −1."""
    fates = np.asarray(fates)
    n = max(1, fates.size)
    esc = np.asarray(labels) == LABEL_ESCAPE
    return {fate_label(c): float(np.sum(esc & (fates == c)) / n) for c in np.unique(fates[esc])}


@dataclass(frozen=True, eq=False)
class LimitSet:
    """The forward limit sets a map's orbits end on, from many initial configurations.

    ``attractors`` are numbered from 1; ``escapes`` maps each escape fate
    (``"behind_joint"``, ``"off_end"``, ``"no_rest"``, …, ``"unresolved"``) to its share
    of the starts (their label is −1). ``starts`` holds the initial configurations
    ``(x, side)`` with each one's ``labels``; ``caps`` the recurrence caps used;
    ``map_info`` describes the map (part, arm, ω, model).
    """

    attractors: tuple
    escapes: dict
    starts_x: np.ndarray
    starts_side: np.ndarray
    labels: np.ndarray
    caps: dict
    map_info: dict

    @property
    def n_starts(self) -> int:
        return int(self.starts_x.size)

    @property
    def unique(self) -> bool:
        """One attractor reached from every start, no escapes."""
        return len(self.attractors) == 1 and not self.escapes

    @property
    def kind(self) -> str:
        """``"fixed_point"``, ``"cycle"``, ``"band"``, ``"escape"`` (all orbits leave) or ``"several"``."""
        if not self.attractors:
            return "escape"
        kinds = {a.kind for a in self.attractors}
        return kinds.pop() if len(kinds) == 1 and len(self.attractors) == 1 else "several"

    def l(self, side: int) -> float:
        """inf S on ``side`` (m): the lowest configuration of any attractor there; nan if none rests there."""
        v = [a.interval(side)[0] for a in self.attractors if a.interval(side) is not None]
        return min(v) if v else math.nan

    def u(self, side: int) -> float:
        """The highest configuration of any attractor on ``side`` (m); nan if none."""
        v = [a.interval(side)[1] for a in self.attractors if a.interval(side) is not None]
        return max(v) if v else math.nan

    def attractor(self, ident: int) -> Attractor:
        for a in self.attractors:
            if a.id == ident:
                return a
        raise InvalidStateError("attractor", f"no attractor {ident} (have {[a.id for a in self.attractors]})")

    def summary(self) -> str:
        """A few lines: kind, each attractor, escapes."""
        lines = [f"limit set of {self.map_info.get('label', 'map')}: {self.kind}, {len(self.attractors)} "
                 f"attractor(s) from {self.n_starts} starts"]
        for a in self.attractors:
            lines.append(f"  {a.describe()}  [{100 * a.fraction:.1f} % of starts]")
        for k, v in self.escapes.items():
            lines.append(f"  -1 {k}: {100 * v:.1f} % of starts")
        return "\n".join(lines)

    def to_dict(self) -> dict:
        return {
            "kind": self.kind, "unique": self.unique,
            "attractors": [a.to_dict() for a in self.attractors],
            "escapes": dict(self.escapes),
            "starts": {"x_m": self.starts_x.tolist(), "side": self.starts_side.tolist(),
                       "label": self.labels.tolist()},
            "caps": dict(self.caps), "map": dict(self.map_info),
            "label_meaning": {"-1": "the orbit did not end on an attractor on the arm (see escapes)"},
        }

    @classmethod
    def from_dict(cls, d: dict) -> "LimitSet":
        return cls(
            attractors=tuple(Attractor.from_dict(a) for a in d["attractors"]),
            escapes={str(k): float(v) for k, v in d["escapes"].items()},
            starts_x=np.asarray(d["starts"]["x_m"], dtype=float),
            starts_side=np.asarray(d["starts"]["side"], dtype=np.int64),
            labels=np.asarray(d["starts"]["label"], dtype=np.int64),
            caps=dict(d["caps"]), map_info=dict(d["map"]),
        )

    def plot(self, ax=None, **kwargs):
        """The Fig. 5 analogue; see :func:`throwmap.viz.limit_set.plot_limit_set`."""
        from ..viz.limit_set import plot_limit_set

        return plot_limit_set(self, ax=ax, **kwargs)


def start_grid(cmap: ConfigMap, n_starts: int, rng) -> tuple[np.ndarray, np.ndarray]:
    """``n_starts`` configurations per side, one drawn uniformly in each of n equal cells of (x_lo, x_hi]."""
    from ..rng import as_generator

    if isinstance(n_starts, bool) or not isinstance(n_starts, (int, np.integer)) or n_starts < 1:
        raise InvalidStateError("n_starts", f"must be a positive integer, got {n_starts!r}")
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


def limit_set(part, arm=None, omega=None, model: str = DEFAULT_MODEL, *, starts=None, n_starts: int = 64,
              rng=0, x_max=None, transient: int | None = None, n_record: int | None = None,
              tol: float | None = None, max_period: int | None = None, cell: float | None = None,
              band_gap: float | None = None, fd_step: float | None = None, max_transient: int | None = None,
              n_fill: int | None = None, fill_rounds: int | None = None, progress=None,
              **throw_options) -> LimitSet:
    """Find and describe every forward limit set reached from many initial configurations.

    Parameters
    ----------
    part, arm, omega, model
        The throw map T^ω (``omega`` may be a sequence: the composed map Π T^{ω_j}
        is then one step), or pass a :class:`~throwmap.analysis.maps.ConfigMap` as
        ``part`` and leave ``arm``/``omega`` out. Default model ``"rigid_body"``.
    starts
        ``(x, side)`` arrays of initial configurations; default ``n_starts`` per
        stable side, stratified over (x_lo, x_hi] with generator ``rng`` (seeded: 0).
    x_max
        Outer end of the domain, m (default: the arm length, else 0.6 m).
    transient, n_record, tol, max_period, cell, band_gap, fd_step, max_transient, n_fill, fill_rounds
        The caps of the recurrence test; defaults in :data:`DEFAULT_CAPS`:
        throws discarded (200), throws recorded (400), recurrence tolerance
        (1e-8 m), longest period sought (32), band-merging cell (1 mm), gap that
        splits a band (2 mm), finite-difference step for slopes (1 µm); while the
        recorded tails are not stationary (a side's span differs between their
        halves by more than ``band_gap``) the orbits go on, up to ``max_transient``
        (5000) throws discarded in all; a band's sampling gaps are filled by
        ``fill_rounds`` (2) rounds of ``n_fill`` (2000) images of its intervals.
    progress
        ``progress(done, total)`` after each iteration of the batch.

    Returns a :class:`LimitSet`.
    """
    cmap = as_map(part, arm, omega, model, x_max=x_max, **throw_options)
    caps = check_caps(transient=transient, n_record=n_record, tol=tol, max_period=max_period, cell=cell,
                      band_gap=band_gap, fd_step=fd_step, max_transient=max_transient, n_fill=n_fill,
                      fill_rounds=fill_rounds)
    if starts is None:
        x0, s0 = start_grid(cmap, n_starts, rng)
    else:
        x0, s0 = check_starts(cmap, starts)
    attractors, labels, fates, _, _ = find_attractors(cmap, x0, s0, caps, progress)
    info = cmap.describe()
    info["label"] = cmap.label
    return LimitSet(attractors=attractors, escapes=escape_fractions(fates, labels), starts_x=x0, starts_side=s0,
                    labels=labels, caps=caps, map_info=info)


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
        raise InvalidStateError("starts", f"side {s[bad][0]!r} is not a stable side {list(cmap.sides)}")
    s = s.astype(np.int64)
    lo = np.array([cmap.x_lo[int(k)] for k in s])
    if np.any(x <= lo):
        i = int(np.flatnonzero(x <= lo)[0])
        raise InvalidStateError("starts", f"x[{i}] = {x[i]:.6g} m is at or behind the first valid x on side "
                                          f"{s[i]} ({lo[i]:.6g} m)")
    return x, s

