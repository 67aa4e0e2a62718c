"""Critical points r_i = sup S and l_i = inf S of a throw map (paper Sec. III-D, Sec. V).

For every stable side i:

``r_i``  where jogs end: every x in [jog_start_i, r_i) is thrown back onto side i
         (a jog) and the throw from r_i is not. The paper defines sup S this way and
         assumes every x ≥ r_i flips to side i+1; :attr:`CriticalPoints.flips_beyond`
         says whether that holds on the sampled arm (a very hard throw can tumble and
         rock back onto side i, or leave the arm), and ``next_kind`` what happens at r_i.
``l_i``  the lowest configuration of the forward limit set on side i (inf S).

Method
------
r_i: the map is evaluated on ``n_grid`` points per side in one batch; the first
non-jog above the first jog brackets r_i, and multisection (``n_split`` points per
round, all sides in one batch) shrinks the bracket to ``xtol`` (default 1 µm).
"Every x below r_i jogs" holds at the grid's resolution.

l_i: the per-side hull of the forward-invariant set, by iterating interval hulls
I_j ← hull{T(x, i) landing on j : x ∈ I_i} from the whole domain with
``hull_samples`` points per interval, until the hulls move less than ``xtol``; then
each lower end is polished by a bounded scalar minimisation of the landing x near
the sample that attains it. When the converged hulls are not trapping (a sampled
configuration in them leaves the arm), the limit set is found from orbits
(:func:`~throwmap.analysis.limitset.limit_set`) and l_i is its lowest point.

Notes
-----
The paper computes r_i from the small-angle energy test F^i = K + U − U_crit = 0
(Sec. V); that test is blind to the sense of rotation and misplaces the switch by
centimetres. Here r_i is the switch of the chosen model's own map.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..kernels import codes as C
from ..serial import fields_equal
from ..system.arm import regime_warnings_once
from .attractors import fate_label, map_short, nan_to_none, none_to_nan
from .budget import Limits, guard_work
from .caps import check_int, check_length
from .maps import DEFAULT_MODEL, ConfigMap, as_map

__all__ = ["CriticalPoints", "critical_points"]


@dataclass(frozen=True, slots=True, eq=False)
class CriticalPoints:
    """r_i, l_i and what happens beyond r_i, per stable side (dicts keyed by side; metres).

    Attributes
    ----------
    r : dict
        r_i (m): the first x above ``jog_start`` whose throw is not a jog; nan when
        every sampled x up to ``x_max`` jogs.
    l : dict
        l_i = inf S (m); nan when the limit set never rests on the side or no limit
        set stays on the arm.
    jog_start : dict
        The lowest sampled x that jogs (m); nan if no x on the side jogs.
    next_kind : dict
        What the throw from just above r_i does: ``"flip to side j"`` or an escape
        (``"behind_joint"``, ``"off_end"``, …).
    flips_beyond : dict
        True when every sampled x in [r_i, x_max] flips (lands on another side).
    non_flips : dict
        Sampled x ≥ r_i that do not flip, as runs ``(x_from, x_to, what)`` (m; ``what``
        is ``"jog"`` — a tumble that rocks back onto the side — or an escape).
    r_bracket : dict
        ``(lo, hi)`` with lo jogging and hi not, hi − lo ≤ ``xtol``.
    l_method : str
        ``"hull"`` (trapping interval hulls) or ``"orbits"`` (from :func:`limit_set`).
    x_max, xtol : float
        Domain end and tolerance, m.
    n_throws : int
        Map evaluations used.
    map_info : dict
    """

    r: dict
    l: dict
    jog_start: dict
    next_kind: dict
    flips_beyond: dict
    non_flips: dict
    r_bracket: dict
    l_method: str
    x_max: float
    xtol: float
    n_throws: int
    map_info: dict

    def __eq__(self, other):
        """Equal when every field holds the same values (NaN equal to NaN, arrays element-wise)."""
        return fields_equal(self, other)

    __hash__ = None

    def __repr__(self) -> str:
        def cm(d):
            return "{" + ", ".join(f"{s}: {v:.4g}" for s, v in sorted(d.items())) + "}"
        return (f"CriticalPoints({map_short(self.map_info)}, x ≤ {self.x_max:.4g} m, r={cm(self.r)} m, "
                f"l={cm(self.l)} m, l by {self.l_method})")

    @property
    def sides(self) -> tuple:
        return tuple(sorted(self.r))

    def table(self) -> str:
        """A plain-text table, cm for reading (the data stay in m)."""
        rows = [f"searched: x ≤ {100 * self.x_max:.1f} cm on every side (r_i, l_i and flips beyond r_i hold "
                "in this range only)",
                "side   jog from (cm)   r_i (cm)      l_i (cm)    at r_i            every x ≥ r_i flips"]
        for s in self.sides:
            rows.append(f"{s:>4}   {100 * self.jog_start[s]:>12.4f}   {100 * self.r[s]:>10.4f}   "
                        f"{100 * self.l[s]:>10.4f}    {self.next_kind[s]:<16}  {self._beyond(s)}")
        return "\n".join(rows)

    def _beyond(self, s) -> str:
        if self.flips_beyond[s]:
            return "yes"
        runs = self.non_flips.get(s, ())
        if not runs:
            return "no"
        return "no: " + ", ".join(f"{w} {100 * a:.2f}–{100 * b:.2f} cm" for a, b, w in runs[:3])

    def plot(self, ax=None, *, unit: str = "cm"):
        """Per side: the jogs up to r_i, l_i, the non-flips beyond r_i (:func:`throwmap.viz.critical.plot_critical`);
        returns the Figure."""
        from ..viz.critical import plot_critical

        return plot_critical(self, ax, unit=unit)

    def to_dict(self) -> dict:
        f = nan_to_none
        return {
            "r_m": {str(s): f(v) for s, v in self.r.items()},
            "l_m": {str(s): f(v) for s, v in self.l.items()},
            "jog_start_m": {str(s): f(v) for s, v in self.jog_start.items()},
            "next_kind": {str(s): v for s, v in self.next_kind.items()},
            "flips_beyond": {str(s): bool(v) for s, v in self.flips_beyond.items()},
            "non_flips": {str(s): [[float(a), float(b), w] for a, b, w in v] for s, v in self.non_flips.items()},
            "r_bracket_m": {str(s): [f(a), f(b)] for s, (a, b) in self.r_bracket.items()},
            "l_method": self.l_method, "x_max_m": self.x_max, "xtol_m": self.xtol, "n_throws": self.n_throws,
            "map": dict(self.map_info),
        }

    @classmethod
    def from_dict(cls, d: dict) -> "CriticalPoints":
        u = none_to_nan
        return cls(
            r={int(s): u(v) for s, v in d["r_m"].items()},
            l={int(s): u(v) for s, v in d["l_m"].items()},
            jog_start={int(s): u(v) for s, v in d["jog_start_m"].items()},
            next_kind={int(s): str(v) for s, v in d["next_kind"].items()},
            flips_beyond={int(s): bool(v) for s, v in d["flips_beyond"].items()},
            non_flips={int(s): tuple((float(a), float(b), str(w)) for a, b, w in v) for s, v in d["non_flips"].items()},
            r_bracket={int(s): (u(v[0]), u(v[1])) for s, v in d["r_bracket_m"].items()},
            l_method=str(d["l_method"]), x_max=float(d["x_max_m"]), xtol=float(d["xtol_m"]),
            n_throws=int(d["n_throws"]), map_info=dict(d["map"]),
        )


def _what(side0, side1, status) -> str:
    if status != C.OK:
        return fate_label(status)
    return "jog" if side1 == side0 else f"flip to side {int(side1)}"


class _Counter:
    """Wraps a map, counting evaluations."""

    def __init__(self, cmap):
        self.cmap = cmap
        self.n = 0

    def __call__(self, x, s):
        x = np.asarray(x, dtype=float).ravel()
        self.n += x.size
        return self.cmap(x, s)


def _runs(xs, idx, what) -> tuple:
    """Consecutive grid indices with the same outcome, as ``(x_from, x_to, what)`` runs."""
    out = []
    for i in idx:
        if out and out[-1][3] == i - 1 and out[-1][2] == what[i]:
            out[-1] = (out[-1][0], float(xs[i]), what[i], i)
        else:
            out.append((float(xs[i]), float(xs[i]), what[i], i))
    return tuple((a, b, w) for a, b, w, _ in out)


def _r_points(T, cmap, n_grid, n_split, xtol):
    sides = cmap.sides
    xs = {s: np.linspace(cmap.x_lo[s], cmap.x_hi[s], n_grid + 1)[1:] for s in sides}
    X = np.concatenate([xs[s] for s in sides])
    Sd = np.concatenate([np.full(n_grid, s, dtype=np.int64) for s in sides])
    xn, sn, st = T(X, Sd)
    r, jog_start, bracket, nxt, flips_beyond, non_flips = {}, {}, {}, {}, {}, {}
    todo = {}
    for k, s in enumerate(sides):
        sl = slice(k * n_grid, (k + 1) * n_grid)
        jog = (st[sl] == C.OK) & (sn[sl] == s)
        if not np.any(jog):
            r[s] = jog_start[s] = math.nan
            bracket[s] = (math.nan, math.nan)
            nxt[s] = "no jog"
            flips_beyond[s] = False
            non_flips[s] = ()
            continue
        i0 = int(np.argmax(jog))
        jog_start[s] = float(xs[s][i0])
        stop = np.flatnonzero(~jog[i0:])
        if stop.size == 0:
            r[s] = math.nan
            bracket[s] = (float(xs[s][-1]), math.nan)
            nxt[s] = "jogs to x_max"
            flips_beyond[s] = False
            non_flips[s] = ()
            continue
        ir = i0 + int(stop[0])
        flip = (st[sl] == C.OK) & (sn[sl] != s)
        bad = np.flatnonzero(~flip[ir:]) + ir
        flips_beyond[s] = bad.size == 0
        non_flips[s] = _runs(xs[s], bad, [_what(s, sn[sl][i], st[sl][i]) for i in range(n_grid)])
        todo[s] = [float(xs[s][ir - 1]), float(xs[s][ir]), (int(sn[sl][ir]), int(st[sl][ir]))]
    # multisection on all open brackets at once
    while todo:
        open_ = [s for s in todo if todo[s][1] - todo[s][0] > xtol]
        if not open_:
            break
        pts = {s: np.linspace(todo[s][0], todo[s][1], n_split + 2)[1:-1] for s in open_}
        X = np.concatenate([pts[s] for s in open_])
        Sd = np.concatenate([np.full(n_split, s, dtype=np.int64) for s in open_])
        xn, sn, st = T(X, Sd)
        for k, s in enumerate(open_):
            sl = slice(k * n_split, (k + 1) * n_split)
            jog = (st[sl] == C.OK) & (sn[sl] == s)
            lo, hi, what = todo[s]
            nj = np.flatnonzero(~jog)
            if nj.size == 0:
                todo[s] = [float(pts[s][-1]), hi, what]
            else:
                j = int(nj[0])
                todo[s] = [float(pts[s][j - 1]) if j > 0 else lo, float(pts[s][j]),
                           (int(sn[sl][j]), int(st[sl][j]))]
    for s, (lo, hi, (side1, status)) in todo.items():
        r[s] = hi
        bracket[s] = (lo, hi)
        nxt[s] = _what(s, side1, status)
    return r, jog_start, bracket, nxt, flips_beyond, non_flips


def _l_hull(T, cmap, m, max_iter, xtol, r):
    """Lower ends of the forward-invariant interval hulls; None if they are not trapping.

    Lower ends skip the slow creep of outward jogs: where every sampled jog on side j
    moves outward (T(x) > x), the lower end of the hull is the lowest *flip* landing on
    j (jogs only raise it), and a side no flip lands on is transient (empty). Each
    source interval is sampled at ``m`` points plus the r_i found before.
    """
    sides = cmap.sides
    iv = {s: (cmap.x_lo[s] + 1e-12, cmap.x_hi[s]) for s in sides}
    src: dict = {}
    for _ in range(max_iter):
        live = [s for s in sides if iv[s] is not None]
        if not live:
            return {s: math.nan for s in sides}
        pts = {}
        for s in live:
            extra = [r[s], r[s] + xtol] if math.isfinite(r.get(s, math.nan)) else []
            p = np.concatenate((np.linspace(iv[s][0], iv[s][1], m), [v for v in extra if iv[s][0] < v < iv[s][1]]))
            pts[s] = np.sort(p)
        X = np.concatenate([pts[s] for s in live])
        Sd = np.concatenate([np.full(pts[s].size, s, dtype=np.int64) for s in live])
        xn, sn, st = T(X, Sd)
        if np.any(st != C.OK):
            return None
        new, src = {}, {}
        for j in sides:
            jog = (Sd == j) & (sn == j)
            flip = (Sd != j) & (sn == j)
            if not np.any(jog | flip):
                new[j] = None
                continue
            outward = np.all(xn[jog] > X[jog])
            lows = flip if outward else (jog | flip)
            if not np.any(lows):
                new[j] = None  # only outward jogs land here: a transient side
                continue
            i_lo = int(np.flatnonzero(lows)[np.argmin(xn[lows])])
            new[j] = (float(xn[lows].min()), float(xn[jog | flip].max()))
            src[j] = (int(Sd[i_lo]), float(X[i_lo]), pts[int(Sd[i_lo])])
        spacing = max((iv[s][1] - iv[s][0]) / (m - 1) for s in live)
        settled = all((new[s] is None) == (iv[s] is None) for s in sides) and all(
            abs(new[s][0] - iv[s][0]) <= xtol and abs(new[s][1] - iv[s][1]) <= 2 * spacing
            for s in sides if new[s] is not None and iv[s] is not None)
        iv = new
        if settled:
            break
    # polish every lower end at once: multisection of the landing x around the sample that attains it
    l = {j: (math.nan if iv[j] is None else iv[j][0]) for j in sides}
    box = {}
    for j in sides:
        if iv[j] is not None:
            i_src, x_src, grid = src[j]
            k = int(np.searchsorted(grid, x_src))
            box[j] = [i_src, float(grid[max(k - 1, 0)]), float(grid[min(k + 1, grid.size - 1)])]
    n_split = 16
    for _ in range(60):
        open_ = [j for j in box if box[j][2] - box[j][1] > xtol]
        if not open_:
            break
        pts = {j: np.linspace(box[j][1], box[j][2], n_split + 1) for j in open_}
        X = np.concatenate([pts[j] for j in open_])
        Sd = np.concatenate([np.full(n_split + 1, box[j][0], dtype=np.int64) for j in open_])
        xn, sn, st = T(X, Sd)
        for k, j in enumerate(open_):
            sl = slice(k * (n_split + 1), (k + 1) * (n_split + 1))
            f = np.where((st[sl] == C.OK) & (sn[sl] == j), xn[sl], np.inf)
            if not np.any(np.isfinite(f)):
                box[j][2] = box[j][1]
                continue
            i = int(np.argmin(f))
            l[j] = min(l[j], float(f[i]))
            box[j][1] = float(pts[j][max(i - 1, 0)])
            box[j][2] = float(pts[j][min(i + 1, n_split)])
    return l


@regime_warnings_once()
def critical_points(part, arm=None, omega=None, model: str = DEFAULT_MODEL, *, x_max=None, n_grid: int = 128,
                    n_split: int = 15, xtol: float = 1e-6, hull_samples: int = 64, hull_max_iter: int = 200,
                    limit=None, limits: Limits | None = None, **throw_options) -> CriticalPoints:
    """r_i and l_i of every stable side (paper Sec. III-D), r_i to ``xtol``.

    Parameters
    ----------
    part, arm, omega, model
        The throw map (default model ``"rigid_body"``), or a
        :class:`~throwmap.analysis.maps.ConfigMap` as ``part``.
    x_max
        Outer end of the searched domain, m (default: arm length, else 0.6 m).
    n_grid
        Points per side of the bracketing grid (its spacing is the resolution of
        "every x below r_i jogs" and of ``flips_beyond``).
    n_split
        Points per multisection round.
    xtol
        Width of the final r_i bracket and the hull tolerance, m (default 1 µm).
    hull_samples, hull_max_iter
        Points per interval and iteration cap of the hull iteration for l_i.
    limit
        A :class:`~throwmap.analysis.limitset.LimitSet` to take l_i from instead.
    limits
        Work guard (:class:`~throwmap.budget.Limits`) on the bracketing grid (``n_grid``
        per side, ≈ 100 bytes and one throw each): refused above the limits unless ``limits.force``.
    """
    cmap: ConfigMap = as_map(part, arm, omega, model, x_max=x_max, **throw_options)
    for name, v, lo in (("n_grid", n_grid, 2), ("n_split", n_split, 1), ("hull_samples", hull_samples, 2),
                        ("hull_max_iter", hull_max_iter, 1)):
        check_int(name, v, lo)
    check_length("xtol", xtol)
    limits = Limits.of(limits)
    n_planned = int(n_grid) * len(cmap.sides)
    guard_work("critical points", "n_grid", n_planned, 100, limits, throws_per_config=1.0,
               cmap=cmap, timed_above=10**5, hint="a smaller n_grid")
    T = _Counter(cmap)
    r, jog_start, bracket, nxt, flips_beyond, non_flips = _r_points(T, cmap, int(n_grid), int(n_split), float(xtol))
    if limit is not None:
        l = {s: limit.l(s) for s in cmap.sides}
        method = "orbits"
    else:
        l = _l_hull(T, cmap, int(hull_samples), int(hull_max_iter), float(xtol), r)
        method = "hull"
        if l is None:
            from .limitset import limit_set

            ls = limit_set(T.cmap)
            T.n += ls.n_starts * (ls.caps["transient"] + ls.caps["n_record"])
            l = {s: ls.l(s) for s in cmap.sides}
            method = "orbits"
    info = cmap.describe()
    info["label"] = cmap.label
    return CriticalPoints(r=r, l=l, jog_start=jog_start, next_kind=nxt, flips_beyond=flips_beyond,
                          non_flips=non_flips, r_bracket=bracket, l_method=method, x_max=float(max(cmap.x_hi.values())),
                          xtol=float(xtol), n_throws=T.n, map_info=info)
