"""Composed throws and funnels (paper Sec. I-A, Fig. 2; Burridge, Rizzi & Koditschek's sequential composition).

A *funnel* is one attractor of one throw map T^ω: its **mouth** is the attractor's
basin (the configurations that end on it) and its **spout** is the attractor
itself. Funnel A leads into funnel B when A's spout lies inside B's mouth: a part
that has settled into A's limit set, thrown with B's speed from then on, ends on
B's limit set. Given a goal set of configurations, the funnels whose spouts lie in
the goal have priority 0, and a funnel whose spout lies in the mouth of a priority-k
funnel has priority k + 1 — the paper's partial order of funnel maps, in which a
sensor need only tell which mouth the part is in.

Goals, mouths and spouts are sets of configurations (:class:`~throwmap.analysis.sets.ConfigSet`).
"""

from __future__ import annotations

import inspect
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown
from ..system.arm import regime_warnings_once
from .attractors import Attractor, domain_text, system_short
from .basins import Basins, basins
from .caps import RecurrenceCaps
from .cellmap import map_to_attractors
from .maps import DEFAULT_MODEL, as_map
from .sets import ConfigSet, SetImage, push

__all__ = ["ConfigSet", "Funnel", "FunnelGraph", "SetImage", "funnels", "push", "mouth_of"]


def mouth_of(b: Basins, ident: int) -> ConfigSet:
    """The basin of attractor ``ident`` on the grid, as intervals, never past the searched range.

    Each run of grid points is widened by half a cell, then clipped to the range the
    basins searched (``b.map_info["domain_m"]``, else the grid's own ends): nothing is
    known of configurations beyond it.
    """
    dom = {int(k): (float(v[0]), float(v[1])) for k, v in (b.map_info.get("domain_m") or {}).items()}
    ivs = []
    for s in np.unique(b.side):
        g = np.flatnonzero(b.side == s)
        xs = b.x[g]
        hit = b.labels[g] == ident
        if not np.any(hit):
            continue
        half = 0.5 * float(np.max(np.diff(xs))) if xs.size > 1 else 0.0
        lo_end, hi_end = dom.get(int(s), (float(xs[0]), float(xs[-1])))
        hi_end = min(hi_end, float(xs[-1]) + half)
        edges = np.diff(np.concatenate(([0], hit.astype(np.int8), [0])))
        starts, ends = np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1
        for a, e in zip(starts, ends):
            ivs.append((int(s), max(float(xs[a] - half), lo_end), min(float(xs[e] + half), hi_end)))
    return ConfigSet(tuple(ivs))


@dataclass(frozen=True, slots=True, eq=False)
class Funnel:
    """One attractor of one throw map: ``mouth`` (its basin) and spout (``attractor``).

    ``omegas`` is the throw (or composed sequence) of the map, rad/s; ``mouth_fraction``
    the basin's share of the analysed grid.
    """

    name: str
    omegas: tuple
    attractor: Attractor
    mouth: ConfigSet
    mouth_fraction: float

    def __repr__(self) -> str:
        return (f"Funnel({self.name!r}, mouth {100 * self.mouth_fraction:.1f} % in {len(self.mouth.intervals)} "
                f"interval(s), spout {self.attractor.kind} on sides {self.attractor.sides})")

    @property
    def spout(self) -> ConfigSet:
        return ConfigSet.from_attractor(self.attractor)

    def to_dict(self) -> dict:
        return {"name": self.name, "omegas_rad_s": list(self.omegas), "attractor": self.attractor.to_dict(),
                "mouth": self.mouth.to_dict(), "mouth_fraction": self.mouth_fraction}

    @classmethod
    def from_dict(cls, d: dict) -> "Funnel":
        return cls(name=str(d["name"]), omegas=tuple(float(w) for w in d["omegas_rad_s"]),
                   attractor=Attractor.from_dict(d["attractor"]), mouth=ConfigSet.from_dict(d["mouth"]),
                   mouth_fraction=float(d["mouth_fraction"]))


@dataclass(frozen=True, slots=True, eq=False)
class FunnelGraph:
    """Funnels, which spout lies in which mouth, and the priority order that reaches ``goal``.

    ``edges``: ``(i, j, share)`` — ``share`` of funnel i's sampled spout that lies in
    funnel j's mouth (never past the range j's basins searched) *and* ends on j's
    attractor under j's throw (an edge is listed when share ≥ ``containment``).
    ``rank``: funnel index → priority (0: spout inside the goal) or None (leads
    nowhere near the goal). ``order``: funnel indices by priority, then mouth size.
    """

    funnels: tuple
    edges: tuple
    goal: ConfigSet | None
    rank: dict
    containment: float
    map_info: dict

    def __repr__(self) -> str:
        names = ", ".join(self.funnels[i].name for i in self.order[:4]) + (" …" if len(self.order) > 4 else "")
        return (f"FunnelGraph({self._maps_short()}, {len(self.funnels)} funnels, {len(self.edges)} edges, "
                f"goal {'none' if self.goal is None else f'{len(self.goal.intervals)} interval(s)'}, "
                f"order: {names or '-'})")

    def _maps_short(self) -> str:
        maps = self.map_info.get("maps", [])
        oms = [", ".join(f"{w:g}" for w in m.get("omegas_rad_s", ())) for m in maps if m.get("kind") == "throw"]
        models = sorted({m.get("model") for m in maps if m.get("kind") == "throw"})
        if oms and len(oms) == len(maps):
            xm = max(m.get("x_max_m", 0.0) for m in maps)
            extra = system_short(maps[0])
            return (f"model={', '.join(models)!r}, omegas=[{'; '.join(oms)}] rad/s, "
                    f"{extra + ', ' if extra else ''}x ≤ {xm:.4g} m")
        return f"{len(maps)} maps"

    @property
    def range_text(self) -> str:
        """The range every map's basins (the mouths) were searched over, in words."""
        texts = []
        for m in self.map_info.get("maps", []):
            d = {int(k): tuple(v) for k, v in (m.get("domain_m") or {}).items()}
            t = domain_text(d, m.get("kind") == "throw")
            if t not in texts:
                texts.append(t)
        return "; ".join(texts) or "the analysed grid"

    @property
    def order(self) -> tuple:
        ranked = [i for i, r in self.rank.items() if r is not None]
        return tuple(sorted(ranked, key=lambda i: (self.rank[i], -self.funnels[i].mouth_fraction, i)))

    def policy(self):
        """The controller this graph implies: for a configuration, the ω of the highest-priority funnel whose mouth holds it.

        Returns a function ``policy(x, side) -> omegas or None``.
        """
        order = self.order

        def choose(x, side):
            for i in order:
                if bool(self.funnels[i].mouth.contains(x, side)):
                    return self.funnels[i].omegas
            return None

        return choose

    def table(self) -> str:
        """The funnels, their mouths and spouts, and the edges, as text (cm for reading)."""
        lines = ["goal: " + (self.goal.describe("cm") if self.goal is not None else "none (all funnels listed)"),
                 f"mouths searched over the {self.range_text} (nothing is claimed beyond)"]
        lines.append(f"{'#':>3}  {'funnel':<16} {'priority':>8}  {'mouth %':>8}  spout")
        for i, f in enumerate(self.funnels):
            r = self.rank.get(i)
            lines.append(f"{i:>3}  {f.name:<16} {('-' if r is None else str(r)):>8}  {100 * f.mouth_fraction:>8.2f}  "
                         f"{f.spout.describe('cm')}")
        lines.append("edges (spout of A inside mouth of B):")
        if not self.edges:
            lines.append("  none")
        for i, j, share in self.edges:
            lines.append(f"  {self.funnels[i].name} → {self.funnels[j].name}  ({100 * share:.1f} % of spout)")
        if self.order:
            lines.append("priority order: " + " > ".join(self.funnels[i].name for i in self.order))
        return "\n".join(lines)

    def to_dict(self) -> dict:
        return {"funnels": [f.to_dict() for f in self.funnels],
                "edges": [{"from": i, "to": j, "share": s} for i, j, s in self.edges],
                "goal": None if self.goal is None else self.goal.to_dict(),
                "rank": {str(i): r for i, r in self.rank.items()}, "order": list(self.order),
                "containment": self.containment, "map": dict(self.map_info)}

    @classmethod
    def from_dict(cls, d: dict) -> "FunnelGraph":
        return cls(funnels=tuple(Funnel.from_dict(f) for f in d["funnels"]),
                   edges=tuple((int(e["from"]), int(e["to"]), float(e["share"])) for e in d["edges"]),
                   goal=None if d["goal"] is None else ConfigSet.from_dict(d["goal"]),
                   rank={int(i): (None if r is None else int(r)) for i, r in d["rank"].items()},
                   containment=float(d["containment"]), map_info=dict(d["map"]))

    def plot(self, ax=None, **kwargs):
        """The funnel graph; see :func:`throwmap.viz.funnels.plot_funnel_graph`."""
        from ..viz.funnels import plot_funnel_graph

        return plot_funnel_graph(self, ax=ax, **kwargs)


def _ranks(n: int, edges, rank0: set) -> dict:
    rank = {i: (0 if i in rank0 else None) for i in range(n)}
    k = 0
    while True:
        frontier = {i for i, r in rank.items() if r == k}
        nxt = {i for i, j, _ in edges if rank[i] is None and j in frontier}
        if not nxt:
            break
        k += 1
        for i in nxt:
            rank[i] = k
    return rank


_BASIN_KEYWORDS = frozenset(
    name for name, p in inspect.signature(basins).parameters.items() if p.kind is p.KEYWORD_ONLY
) | frozenset(RecurrenceCaps.names())
"""Keywords that :func:`funnels` hands to :func:`basins` (its own and the recurrence caps); others are throw options."""


@regime_warnings_once()
def funnels(part, arm=None, omegas=None, model: str = DEFAULT_MODEL, *, maps=None, goal=None, grid=400,
            containment: float = 1.0, spout_samples: int = 200, reach_tol: float = 1e-6, max_throws: int = 500,
            rng=0, x_max=None, progress=None, **basin_options) -> FunnelGraph:
    """Funnels of several throw speeds and the priority order that reaches ``goal`` (Sec. I-A).

    Parameters
    ----------
    part, arm, omegas, model
        One throw map per entry of ``omegas`` (an entry may itself be a sequence: a
        composed map). Or give ``maps``: a list of :class:`ConfigMap` (then ``part``
        may be None).
    goal
        A :class:`ConfigSet` (or its text spec); None ranks nothing and lists every
        funnel and edge.
    grid
        Points per side for each map's basins (mouths).
    containment
        Share of a spout's samples that must end on the other funnel's attractor for
        an edge (default 1.0: all of them).
    spout_samples
        Samples per spout interval; cycle points are used exactly.
    reach_tol, max_throws
        As in :func:`~throwmap.analysis.basins.basins`, for mapping spout samples.
    basin_options
        Keywords of :func:`~throwmap.analysis.basins.basins` (caps, ``method``, ``n_check``…)
        go to each map's basins; any other keyword is a throw option of every map
        (model options such as ``options=RigidBodyOptions(...)`` or ``impact_law="velocity"``,
        ``fixtures``…; refused by :func:`throwmap.throw_batch` when the model does not take it).
        With ``maps`` given, only basins keywords are taken.
    progress
        ``progress(stage, done, total)``.
    """
    if maps is None:
        if omegas is None:
            raise InvalidStateError("omegas", "give the throw speeds (or maps)")
        oms = list(omegas) if np.ndim(omegas) else [omegas]
        if not oms:
            raise InvalidStateError("omegas", "needs at least one throw speed")
        throw_options = {k: v for k, v in basin_options.items() if k not in _BASIN_KEYWORDS}
        basin_options = {k: v for k, v in basin_options.items() if k in _BASIN_KEYWORDS}
        maps = [as_map(part, arm, w, model, x_max=x_max, **throw_options) for w in oms]
    else:
        maps = [as_map(m) for m in maps]
        if not maps:
            raise InvalidStateError("maps", "needs at least one map")
    if isinstance(goal, str):
        goal = ConfigSet.parse(goal)
    if goal is not None and not isinstance(goal, ConfigSet):
        raise InvalidStateError("goal", f"must be a ConfigSet or its text spec, got {type(goal).__name__}")
    if goal is not None:
        known = sorted({k for m in maps for k in m.sides})
        bad = [k for k in goal.sides if k not in known]
        if bad:
            raise InvalidStateError("goal", f"side {bad[0]} is not a stable side of the maps {known}")
    if isinstance(containment, bool) or not isinstance(containment, (int, float)) or not 0 < containment <= 1:
        raise InvalidStateError("containment", f"must be in (0, 1], got {shown(containment)}")
    if isinstance(spout_samples, bool) or not isinstance(spout_samples, (int, np.integer)) or spout_samples < 2:
        raise InvalidStateError("spout_samples", f"must be an integer ≥ 2, got {shown(spout_samples)}")
    fs: list[Funnel] = []
    owner: list[int] = []
    found: list[Basins] = []
    for k, cmap in enumerate(maps):
        b = basins(cmap, grid=grid, rng=rng, reach_tol=reach_tol, max_throws=max_throws, **basin_options)
        found.append(b)
        for a in b.attractors:
            if a.fraction <= 0:
                continue
            w = ", ".join(f"{v:g}" for v in getattr(cmap, "omegas", ()))
            name = (f"ω={w} #{a.id}" if w else f"{cmap.label} #{a.id}")
            fs.append(Funnel(name=name, omegas=tuple(getattr(cmap, "omegas", ())), attractor=a,
                             mouth=mouth_of(b, a.id), mouth_fraction=a.fraction))
            owner.append(k)
        if progress is not None:
            progress("basins", k + 1, len(maps))
    edges = []
    for i, f in enumerate(fs):
        xs, ss = f.spout.sample(spout_samples)
        for j, g in enumerate(fs):
            if owner[j] == owner[i]:
                continue
            cmap = maps[owner[j]]
            ok_side = np.isin(ss, cmap.sides)
            lab = np.full(xs.size, -1, dtype=np.int64)
            if np.any(ok_side):
                lab[ok_side], _, _ = map_to_attractors(cmap, xs[ok_side], ss[ok_side], found[owner[j]].attractors,
                                                       reach_tol, max_throws)
            share = float(np.mean((lab == g.attractor.id) & g.mouth.contains(xs, ss)))
            if share >= containment:
                edges.append((i, j, share))
        if progress is not None:
            progress("edges", i + 1, len(fs))
    rank0 = set()
    if goal is not None:
        for i, f in enumerate(fs):
            xs, ss = f.spout.sample(spout_samples)
            if np.all(goal.contains(xs, ss, 1e-12)):
                rank0.add(i)
    rank = _ranks(len(fs), edges, rank0) if goal is not None else {i: None for i in range(len(fs))}
    info = {"maps": [m.describe() for m in maps], "grid": grid if isinstance(grid, int) else "custom"}
    return FunnelGraph(funnels=tuple(fs), edges=tuple(edges), goal=goal, rank=rank, containment=float(containment),
                       map_info=info)
