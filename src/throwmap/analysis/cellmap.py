"""Assigning configurations to attractors: exact orbits and cell-to-cell mapping (paper Sec. III-D).

The algorithms under :func:`~throwmap.analysis.basins.basins`, free of its result types:

:func:`map_to_attractors`     exact orbits until each lies on a known attractor (within
                              ``reach_tol``), escapes, or ``max_throws`` pass;
:func:`exact_with_discovery`  the same, then one round of the recurrence test on the
                              orbits left unresolved, looking for attractors not yet known;
:func:`cell_map`              Hsu's cell-to-cell mapping: every grid configuration is
                              thrown once, its image replaced by the nearest grid
                              configuration on its side, labels propagated back along
                              that graph;
:func:`trap_excursion`        how far sampled images of an attractor's region leave it;
:func:`basin_grid`            a grid spec (points per side, or x values per side).

Labels follow :mod:`throwmap.analysis.attractors` (1, 2, … or −1) and fate codes
(0 attracted, a status code, −1 unresolved).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidStateError, shown
from ..kernels import codes as C
from .attractors import FATE_UNRESOLVED, LABEL_ESCAPE, Attractor
from .caps import RecurrenceCaps
from .maps import ConfigMap, config_grid
from .recurrence import find_attractors

__all__ = ["map_to_attractors", "exact_with_discovery", "cell_map", "trap_excursion", "basin_grid", "grid_size",
           "CHUNK"]


def _membership(attractors, x, s, tol) -> np.ndarray:
    lab = np.zeros(x.size, dtype=np.int64)
    for a in attractors:
        hit = (lab == 0) & a.contains(x, s, tol)
        lab[hit] = a.id
    return lab


def _map_chunk(cmap: ConfigMap, x0, s0, attractors, reach_tol: float, max_throws: int, progress=None):
    """Exact orbits until each lies on an attractor (within ``reach_tol``), escapes, or ``max_throws`` pass.

    Returns ``(labels, fates, throws)``; unresolved orbits get label −1, fate −1 and
    ``throws = max_throws``.
    """
    x = np.array(x0, dtype=float).ravel()
    s = np.array(s0).ravel().astype(np.int64)
    n = x.size
    labels = np.zeros(n, dtype=np.int64)
    fates = np.zeros(n, dtype=np.int64)
    throws = np.zeros(n, dtype=np.int64)
    active = np.arange(n)
    for t in range(max_throws + 1):
        if active.size == 0:
            break
        lab = _membership(attractors, x[active], s[active], reach_tol)
        hit = lab > 0
        labels[active[hit]] = lab[hit]
        throws[active[hit]] = t
        active = active[~hit]
        if t == max_throws or active.size == 0:
            break
        xn, sn, st = cmap(x[active], s[active])
        bad = st != C.OK
        labels[active[bad]] = LABEL_ESCAPE
        fates[active[bad]] = st[bad]
        throws[active[bad]] = t + 1
        x[active], s[active] = xn, sn
        active = active[~bad]
        if progress is not None:
            progress(t + 1, max_throws)
    labels[active] = LABEL_ESCAPE
    fates[active] = FATE_UNRESOLVED
    throws[active] = max_throws
    return labels, fates, throws


CHUNK = 200_000
"""Configurations handled at once by the exact orbits and the cell mapping (bounds their working memory)."""


def map_to_attractors(cmap: ConfigMap, x0, s0, attractors, reach_tol: float, max_throws: int, progress=None):
    """Exact orbits until each lies on an attractor (within ``reach_tol``), escapes, or ``max_throws`` pass.

    Returns ``(labels, fates, throws)``; unresolved orbits get label −1, fate −1 and
    ``throws = max_throws``. Large inputs go through in chunks of :data:`CHUNK`
    configurations, so the working arrays stay that size.
    """
    x0 = np.asarray(x0, dtype=float).ravel()
    s0 = np.broadcast_to(np.asarray(s0).ravel(), x0.shape) if np.size(s0) == 1 else np.asarray(s0).ravel()
    if x0.size <= CHUNK:
        return _map_chunk(cmap, x0, s0, attractors, reach_tol, max_throws, progress)
    labels = np.empty(x0.size, dtype=np.int64)
    fates = np.empty(x0.size, dtype=np.int64)
    throws = np.empty(x0.size, dtype=np.int64)
    for a in range(0, x0.size, CHUNK):
        b = min(a + CHUNK, x0.size)
        labels[a:b], fates[a:b], throws[a:b] = _map_chunk(cmap, x0[a:b], s0[a:b], attractors, reach_tol, max_throws)
        if progress is not None:
            progress(b, x0.size)
    return labels, fates, throws


def _same_attractor(a: Attractor, b: Attractor, tol: float) -> bool:
    if a.kind != b.kind or a.period != b.period:
        return False
    if a.kind != "band":
        return all(p[0] == q[0] and abs(p[1] - q[1]) <= tol for p, q in zip(a.points, b.points))
    return any(pa[0] == pb[0] and pa[1] <= pb[2] + tol and pb[1] <= pa[2] + tol for pa in a.bands for pb in b.bands)


def exact_with_discovery(cmap, x0, s0, attractors, caps: RecurrenceCaps, reach_tol: float, max_throws: int,
                         max_discover: int, progress=None):
    """:func:`map_to_attractors`, then one round of attractor discovery on what stayed unresolved.

    Up to ``max_discover`` unresolved starts go through the recurrence test with ``caps``;
    attractors not yet known (compared to ``caps.band_gap``) are appended with the next
    ids, and the unresolved starts are mapped again. Returns
    ``(attractors, labels, fates, throws)``.
    """
    labels, fates, throws = map_to_attractors(cmap, x0, s0, attractors, reach_tol, max_throws, progress)
    unres = np.flatnonzero(fates == FATE_UNRESOLVED)
    if unres.size:
        pick = unres[np.linspace(0, unres.size - 1, min(unres.size, max_discover)).astype(int)]
        new = find_attractors(cmap, np.asarray(x0)[pick], np.asarray(s0)[pick], caps).attractors
        added = list(attractors)
        for a in new:
            if not any(_same_attractor(a, b, caps.band_gap) for b in added):
                added.append(a.with_fraction(0.0, ident=len(added) + 1))
        if len(added) > len(attractors):
            attractors = tuple(added)
            l2, f2, t2 = map_to_attractors(cmap, np.asarray(x0)[unres], np.asarray(s0)[unres], attractors,
                                           reach_tol, max_throws)
            labels[unres], fates[unres], throws[unres] = l2, f2, t2
    return tuple(attractors), labels, fates, throws


def grid_size(cmap: ConfigMap, grid) -> int:
    """Configurations a grid spec will hold, without building it (refuses what :func:`basin_grid` refuses)."""
    if isinstance(grid, (int, np.integer)) and not isinstance(grid, bool):
        if grid < 2:
            raise InvalidStateError("grid", f"must be an integer ≥ 2 (points per side), got {shown(grid)}")
        return int(grid) * len(cmap.sides)
    if isinstance(grid, dict):
        return int(sum(np.size(v) for v in grid.values()))
    raise InvalidStateError("grid", f"must be points per side (int ≥ 2) or {{side: x values}}, got {shown(grid)}")


def basin_grid(cmap: ConfigMap, grid):
    """Grid spec → flat (x, side) sorted by side then x, and the spacing per side."""
    if isinstance(grid, (int, np.integer)) and not isinstance(grid, bool):
        x, s = config_grid(cmap, int(grid))
    elif isinstance(grid, dict):
        xs, ss = [], []
        for k in sorted(grid):
            side = cmap.check_side(k)
            v = np.sort(np.asarray(grid[k], dtype=float).ravel())
            if v.size < 2 or not np.all(np.isfinite(v)):
                raise InvalidStateError("grid", f"side {side}: need at least 2 finite x values")
            if v[0] <= cmap.x_lo[side]:
                raise InvalidStateError("grid", f"side {side}: x = {v[0]:.6g} m is at or behind the first valid x "
                                                f"({cmap.x_lo[side]:.6g} m)")
            xs.append(v)
            ss.append(np.full(v.size, side, dtype=np.int64))
        x, s = np.concatenate(xs), np.concatenate(ss)
    else:
        raise InvalidStateError("grid", f"must be points per side (int ≥ 2) or {{side: x values}}, got {shown(grid)}")
    spacing = {}
    for k in np.unique(s):
        v = x[s == k]
        spacing[int(k)] = float(np.max(np.diff(v)))
    return x, s, spacing


def cell_map(cmap, x, s, spacing, attractors, reach_tol: float, max_throws: int, progress=None):
    """Cell-to-cell mapping: one exact throw per configuration, then propagation on the grid graph.

    ``(x, side)`` is the grid from :func:`basin_grid` with its ``spacing`` per side (m).
    A configuration within ``max(reach_tol, half a cell)`` of an attractor is on it.
    The grid is thrown in chunks of :data:`CHUNK`; of each chunk's images only the
    successor cell is kept. Returns ``(labels, fates, throws, rest)``: label 0 and the
    indices ``rest`` where the graph ended on no attractor (to be finished by exact orbits).
    """
    n = x.size
    labels = np.zeros(n, dtype=np.int64)
    for k, v in spacing.items():
        on = np.flatnonzero(s == k)
        tol = max(reach_tol, 0.5 * v)
        for a in attractors:
            hit = (labels[on] == 0) & _near(a, x[on], s[on], tol)
            labels[on[hit]] = a.id
    fates = np.zeros(n, dtype=np.int64)
    throws = np.zeros(n, dtype=np.int64)
    succ = np.full(n, -1, dtype=np.int64)
    todo = np.flatnonzero(labels == 0)
    side_idx = {int(k): np.flatnonzero(s == k) for k in np.unique(s)}
    for a in range(0, todo.size, CHUNK):
        idx = todo[a:a + CHUNK]
        xn, sn, st = cmap(x[idx], s[idx])
        bad = st != C.OK
        labels[idx[bad]] = LABEL_ESCAPE
        fates[idx[bad]] = st[bad]
        throws[idx[bad]] = 1
        ok, xo, so = idx[~bad], xn[~bad], sn[~bad]
        for k in np.unique(so):
            g = side_idx.get(int(k))
            m = so == k
            if g is None or g.size < 2:
                continue
            xs = x[g]
            j = np.clip(np.searchsorted(xs, xo[m]), 1, xs.size - 1)
            j = np.where(np.abs(xs[j - 1] - xo[m]) <= np.abs(xs[j] - xo[m]), j - 1, j)
            inside = (xo[m] >= xs[0] - spacing[int(k)]) & (xo[m] <= xs[-1] + spacing[int(k)])
            succ[ok[m]] = np.where(inside, g[j], -1)
        if progress is not None:
            progress(min(a + CHUNK, todo.size), todo.size)
    for _ in range(max_throws):
        open_ = np.flatnonzero((labels == 0) & (succ >= 0))
        if open_.size == 0:
            break
        nxt = succ[open_]
        take = labels[nxt] != 0
        if not np.any(take):
            break
        i, j = open_[take], nxt[take]
        labels[i] = labels[j]
        fates[i] = fates[j]
        throws[i] = throws[j] + 1
    rest = np.flatnonzero(labels == 0)
    return labels, fates, throws, rest


def _near(a: Attractor, x, s, tol):
    out = np.zeros(x.size, dtype=bool)
    for side, lo, hi in a.bands:
        out |= (s == side) & (x >= lo - tol) & (x <= hi + tol)
    return out


def trap_excursion(cmap, attractor: Attractor, n: int, tol: float) -> float:
    """Largest distance (m) by which sampled images of the attractor's region fall outside it (inf: escapes)."""
    xs, ss = [], []
    for side, lo, hi in attractor.bands:
        v = np.linspace(lo, hi, n) if hi > lo else np.array([lo])
        xs.append(v)
        ss.append(np.full(v.size, side, dtype=np.int64))
    x, s = np.concatenate(xs), np.concatenate(ss)
    xn, sn, st = cmap(x, s)
    if np.any(st != C.OK):
        return math.inf
    worst = 0.0
    for i in range(x.size):
        d = math.inf
        for side, lo, hi in attractor.bands:
            if side == sn[i]:
                d = min(d, max(lo - xn[i], xn[i] - hi, 0.0))
        worst = max(worst, d)
    return float(worst)
