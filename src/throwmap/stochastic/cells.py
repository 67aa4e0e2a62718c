"""Cells on the arm: the finite state space of a stochastic throw map.

A part resting flat is ``(x, side)`` (m, stable side). :class:`Cells` cuts each stable side's
admissible starts ``lo < x ≤ hi`` (:func:`throwmap.system.starts.start_interval`, or a given span)
into intervals of length at most ``size`` (m), with extra cut points ``breaks`` (m) where a
policy's sensors switch (the goal window x_f ± ε, approach rungs), so that a cell never straddles
a sensor threshold. Transient state ``i`` of a chain is cell ``i``; cells are numbered side by side
in the order of ``sides``, in increasing x within a side.

Conventions: a cell is the half-open interval ``(left, right]`` (the admissible interval's rule);
a point outside every cell maps to −1 (:meth:`Cells.index`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, shown

__all__ = ["Cells"]


def _edges(lo: float, hi: float, size: float, breaks) -> np.ndarray:
    """Edges from lo to hi at most ``size`` apart, with the breaks inside; a grid edge closer than 1 % of
    ``size`` to a break is dropped (the break wins, no sliver cell)."""
    n = max(1, int(math.ceil((hi - lo) / size - 1e-9)))
    grid = np.linspace(lo, hi, n + 1)
    inner = np.asarray(sorted({float(b) for b in breaks if lo < float(b) < hi}))
    if inner.size:
        near = np.min(np.abs(grid[1:-1, None] - inner[None, :]), axis=1) < 0.01 * size
        grid = np.concatenate([grid[:1], grid[1:-1][~near], grid[-1:]])
        grid = np.unique(np.concatenate([grid, inner]))
    return grid


@dataclass(frozen=True, slots=True, eq=False)
class Cells:
    """Intervals of rests per stable side (module docstring). ``sides``: the stable sides;
    ``edges``: per side the increasing cell edges (m); ``size``: the requested largest cell (m)."""

    sides: tuple
    edges: tuple
    size: float
    offsets: np.ndarray = field(init=False, repr=False)

    def __post_init__(self):
        if len(self.sides) != len(self.edges) or not self.sides:
            raise InvalidStateError("cells.edges", "need one array of edges per side")
        edges = tuple(np.asarray(e, dtype=float) for e in self.edges)
        for k, e in zip(self.sides, edges):
            if e.ndim != 1 or e.size < 2 or not np.all(np.isfinite(e)) or np.any(np.diff(e) <= 0):
                raise InvalidStateError("cells.edges", f"side {k}: must be ≥ 2 finite increasing edges (m)")
        object.__setattr__(self, "edges", edges)
        object.__setattr__(self, "sides", tuple(int(k) for k in self.sides))
        object.__setattr__(self, "offsets", np.cumsum([0] + [e.size - 1 for e in edges]))

    @classmethod
    def on_arm(cls, part, arm, size: float, *, breaks=(), span=None, sides=None) -> "Cells":
        """Cells of at most ``size`` m over each stable side's admissible starts (or ``span`` = (lo, hi) m,
        clipped to them; needed on an unbounded arm), cut at ``breaks`` (m)."""
        from ..system.starts import start_interval

        if isinstance(size, bool) or not isinstance(size, (int, float)) or not math.isfinite(size) or size <= 0:
            raise InvalidStateError("cell", f"must be a cell size > 0 (m), got {shown(size)}")
        sides = part.stable_sides if sides is None else tuple(part.check_side(k) for k in sides)
        edges = []
        for k in sides:
            lo, hi = start_interval(part, arm, k)
            if span is not None:
                lo, hi = max(lo, float(span[0])), min(hi, float(span[1]))
            if not math.isfinite(hi):
                raise InvalidStateError("span", "the arm is unbounded: give span = (lo, hi) in m")
            if not hi > lo:
                raise InvalidStateError("span", f"side {k} has no admissible rest in the span")
            edges.append(_edges(lo, hi, float(size), breaks))
        return cls(tuple(sides), tuple(edges), float(size))

    @property
    def n(self) -> int:
        """The number of cells (transient states)."""
        return int(self.offsets[-1])

    def side_slice(self, side: int) -> slice:
        j = self.sides.index(int(side))
        return slice(int(self.offsets[j]), int(self.offsets[j + 1]))

    def index(self, x, side) -> np.ndarray:
        """The cell of each rest ``(x, side)`` (arrays broadcast), −1 outside every cell."""
        x, side = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(side))
        out = np.full(x.shape, -1, dtype=np.int64)
        for j, (k, e) in enumerate(zip(self.sides, self.edges)):
            on = (side == k) & (x > e[0]) & (x <= e[-1])
            i = np.searchsorted(e, x[on], side="left") - 1
            out[on] = self.offsets[j] + np.clip(i, 0, e.size - 2)
        return out

    def bounds(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(left, right, side)`` of every cell (m, m, side index)."""
        lefts, rights, sides = [], [], []
        for k, e in zip(self.sides, self.edges):
            lefts.append(e[:-1])
            rights.append(e[1:])
            sides.append(np.full(e.size - 1, k))
        return np.concatenate(lefts), np.concatenate(rights), np.concatenate(sides)

    def centres(self) -> tuple[np.ndarray, np.ndarray]:
        """``(x, side)`` of every cell's midpoint."""
        left, right, side = self.bounds()
        return 0.5 * (left + right), side

    def labels(self) -> tuple:
        left, right, side = self.bounds()
        return tuple(f"side {int(k)} ({100 * a:.4g}, {100 * b:.4g}] cm" for a, b, k in zip(left, right, side))

    def histogram(self, x, side, weights=None) -> np.ndarray:
        """The (unnormalised) mass of the rests ``(x, side)`` per cell; rests outside every cell are dropped."""
        i = self.index(x, side).ravel()
        w = np.ones(i.size) if weights is None else np.asarray(weights, dtype=float).ravel()
        return np.bincount(i[i >= 0], weights=w[i >= 0], minlength=self.n).astype(float)

    def to_dict(self) -> dict:
        return {"size_m": self.size, "sides": list(self.sides), "edges_m": [e.tolist() for e in self.edges]}
