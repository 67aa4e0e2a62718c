"""Forward limit sets of a throw map, whatever their kind (paper Sec. III-D, Fig. 5).

:func:`limit_set` iterates a map from many initial configurations and describes
where the orbits end: fixed points and cycles (period, multiplier, stability),
bands (intervals per side, with their Lyapunov exponent), and escapes (label −1,
see :mod:`throwmap.analysis.attractors`). The method is the recurrence test of
:mod:`throwmap.analysis.recurrence`, bounded by the caps of
:class:`~throwmap.analysis.caps.RecurrenceCaps`; the result is a :class:`LimitSet`.

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
from ..system.arm import regime_warnings_once
from .attractors import (Attractor, attractor_counts, attractor_table, check_cycles, domain_of, domain_text,
                         escape_fractions, map_short, range_short)
from .budget import Limits, guard_work
from .caps import DEFAULT_CAPS, RecurrenceCaps, check_caps, resolve_caps, split_options
from .maps import DEFAULT_MODEL, ConfigMap, as_map
from .recurrence import check_starts, find_attractors, start_grid
from .tails import bytes_per_orbit

__all__ = ["LimitSet", "limit_set", "RecurrenceCaps", "DEFAULT_CAPS", "check_caps", "WALL_TOL"]

WALL_TOL = 1e-5
"""A fixed point within this distance (m) below a wall's resting configuration x* = length − u_R rests against it
(10 µm: rigid_body ends a slide into the wall a few µm short of x*, at its contact tolerance)."""


@dataclass(frozen=True, slots=True, eq=False)
class LimitSet:
    """The forward limit sets a map's orbits end on, from many initial configurations.

    ``attractors`` are numbered from 1; ``escapes`` maps each escape fate
    (``"behind_joint"``, ``"off_end"``, ``"no_rest"``, …, ``"unresolved"``) to its share
    of the starts (their label is −1). ``starts_x`` (m) and ``starts_side`` hold the
    initial configurations with each one's ``labels``; ``caps`` records the recurrence
    caps used (:meth:`RecurrenceCaps.to_dict` plus ``transient_used``, the throws
    discarded in all); ``map_info`` describes the map (part, arm, ω, model).
    """

    attractors: tuple
    escapes: dict
    starts_x: np.ndarray
    starts_side: np.ndarray
    labels: np.ndarray
    caps: dict
    map_info: dict

    def __post_init__(self):
        check_cycles(self.attractors, float(self.caps.get("tol", DEFAULT_CAPS["tol"])))

    def __repr__(self) -> str:
        esc = ", ".join(f"{k} {100 * v:.1f} %" for k, v in self.escapes.items()) or "none"
        return (f"LimitSet({map_short(self.map_info)}, {self._range_short()}, {self.n_starts} starts: "
                f"{attractor_counts(self.attractors)}; escapes {esc})")

    def _range_short(self) -> str:
        if self.map_info.get("starts") == "given" and self.starts_x.size:
            return f"starts x∈[{self.starts_x.min():.4g}, {self.starts_x.max():.4g}] m"
        return range_short(self.map_info)

    @property
    def range_text(self) -> str:
        """The starts this result covers, in words (e.g. ``"valid starts with x ≤ 0.600 m"``).

        On an unbounded arm the search stops at ``x_max`` (default 0.6 m); beyond it the
        map may have other attractors, so "unique" and "every orbit escapes" hold for
        this range only.
        """
        if self.map_info.get("starts") == "given":
            return f"{self.n_starts} given starts"
        dom, valid = domain_of(self.map_info)
        return domain_text(dom, valid)

    @property
    def n_starts(self) -> int:
        return int(self.starts_x.size)

    @property
    def recurrence_caps(self) -> RecurrenceCaps:
        """The caps used, as a :class:`RecurrenceCaps`."""
        return RecurrenceCaps.from_dict(self.caps)

    @property
    def transient_used(self) -> int:
        """Throws discarded in all before the recorded tails (≥ ``caps["transient"]``)."""
        return int(self.caps.get("transient_used", self.caps.get("transient", 0)))

    @property
    def wall_points(self) -> dict:
        """``{attractor id: (side, x*)}`` for the fixed points and cycle points that rest against a wall.

        With a :class:`~throwmap.Wall` at the arm's end a part resting against it has
        x* + u_R = length: the last start :func:`throwmap.throw` accepts on that side, the
        domain's upper end. A jog that would carry the part past the wall stops there, so
        T(x) = x* for every x close below x*: a fixed point with multiplier 0
        (superstable: reached in finitely many throws, not asymptotically). The map is
        defined only for x ≤ x*, so that multiplier is the *left* derivative,
        lim_{h→0+} (T(x*) − T(x* − h))/h (the slopes are one-sided where the right
        neighbour is no valid start; :func:`~throwmap.analysis.recurrence.find_attractors`).
        """
        info = self.map_info
        if not any(f.get("kind") == "wall" for f in info.get("fixtures") or ()):
            return {}
        dom, _ = domain_of(info)
        x_max = float(info.get("x_max_m", math.inf))
        out = {}
        for a in self.attractors:
            for side, x in a.points:
                hi = dom.get(int(side), (math.nan, math.nan))[1]  # = length − u_R unless x_max cut it
                if hi < x_max and 0.0 <= hi - x <= WALL_TOL:
                    out[a.id] = (int(side), float(x))
                    break
        return out

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
                 f"attractor(s) from {self.n_starts} starts (searched: {self.range_text}; not beyond)"]
        if not self.attractors and self.escapes:
            lines.append(f"  no orbit from the {self.range_text} ends on an attractor (escapes below); "
                         "attractors beyond this range are not ruled out")
        elif self.unique:
            lines.append(f"  every orbit from the {self.range_text} ends on #1; attractors beyond this range are "
                         "not ruled out")
        wall = self.wall_points
        for a in self.attractors:
            lines.append(f"  {a.describe()}  [{100 * a.fraction:.1f} % of starts]")
            if a.id in wall:
                s, x = wall[a.id]
                gap = dom_hi(self.map_info, s) - x
                lines.append(f"     against the wall: x = {x:.6f} m on side {s}, {1e6 * gap:.3g} µm below length − u_R (the "
                             f"last valid start); multiplier {a.multiplier:+.3g} is the left derivative (T is defined "
                             f"for x ≤ length − u_R only)")
        for k, v in self.escapes.items():
            lines.append(f"  -1 {k}: {100 * v:.1f} % of starts")
        return "\n".join(lines)

    def table(self) -> str:
        """The range searched, then one row per attractor and per escape fate: kind, period,
        multiplier, Lyapunov exponent, share of starts."""
        return (f"searched: {self.range_text} (not beyond)\n"
                + attractor_table(self.attractors, self.escapes, share="starts %"))

    def to_dict(self) -> dict:
        return {
            "kind": self.kind, "unique": self.unique, "range": self.range_text,
            "attractors": [a.to_dict() for a in self.attractors],
            "at_wall": [{"id": i, "side": s, "x_m": x} for i, (s, x) in self.wall_points.items()],
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


def dom_hi(map_info: dict, side: int) -> float:
    """The upper end of the analysed domain on ``side`` (m; nan if not recorded)."""
    dom, _ = domain_of(map_info)
    return dom.get(int(side), (math.nan, math.nan))[1]


@regime_warnings_once()
def limit_set(part, arm=None, omega=None, model: str = DEFAULT_MODEL, *, caps: RecurrenceCaps = RecurrenceCaps(),
              starts=None, n_starts: int = 64, rng=0, x_max=None, progress=None, limits: Limits | None = None,
              **overrides) -> LimitSet:
    """Find and describe every forward limit set reached from many initial configurations.

    Parameters
    ----------
    part, arm, omega, model
        The throw map T^ω (``omega`` may be a sequence: the composed map Π T^{ω_j}
        is then one step), or pass a :class:`~throwmap.analysis.maps.ConfigMap` as
        ``part`` and leave ``arm``/``omega`` out. Default model ``"rigid_body"``.
    caps
        The caps of the recurrence test (:class:`~throwmap.analysis.caps.RecurrenceCaps`):
        throws discarded (``transient`` 200), throws recorded (``n_record`` 400),
        recurrence tolerance (``tol`` 1e-8 m), longest period sought (``max_period`` 32),
        band-merging cell (``cell`` 1 mm), gap that splits a band (``band_gap`` 2 mm),
        finite-difference step for slopes (``fd_step`` 1 µm); while the recorded tails
        are not stationary the orbits go on, up to ``max_transient`` (5000) throws
        discarded in all; a band's sampling gaps are filled by ``fill_rounds`` (2)
        rounds of ``n_fill`` (2000) images of its intervals.
    starts
        ``(x, side)`` arrays of initial configurations; default ``n_starts`` per
        stable side, stratified over (x_lo, x_hi] with generator ``rng`` (seeded: 0).
    x_max
        Outer end of the domain, m (default: the arm length, else 0.6 m).
    progress
        ``progress(done, total)`` after each iteration of the batch.
    limits
        Work guard (:class:`~throwmap.budget.Limits`): the recorded tails (16 bytes per
        start and recorded throw) and ``transient + n_record`` throws per start are
        estimated first; above the limits the call is refused with one line, unless
        ``limits.force``.
    overrides
        Any cap by name (``transient=50``; ``None`` keeps ``caps``' value), merged into
        ``caps``; with a part, other keywords are throw options for
        :func:`throwmap.throw_batch` (``fixtures``, ``settings``…). Anything else is
        refused, naming it.

    Returns
    -------
    LimitSet
        The attractors found, the escapes and every start's label.
    """
    cap_overrides, throw_options = split_options(overrides, not isinstance(part, ConfigMap))
    cmap = as_map(part, arm, omega, model, x_max=x_max, **throw_options)
    rc = resolve_caps(caps, cap_overrides)
    limits = Limits.of(limits)
    if starts is None:
        valid = isinstance(n_starts, (int, np.integer)) and not isinstance(n_starts, bool) and n_starts >= 1
        n_planned = int(n_starts) * len(cmap.sides) if valid else 0  # start_grid refuses the rest
    else:
        n_planned = int(np.size(starts[0])) if isinstance(starts, (tuple, list)) and len(starts) == 2 else 1
    # name the knob that is furthest above its default (a huge record is not the starts' fault)
    field = "n_starts" if starts is None else "starts"
    per_side = n_planned / max(1, len(cmap.sides))
    ratios = {field: per_side / 64, "n_record": rc.n_record / DEFAULT_CAPS["n_record"],
              "transient": rc.transient / max(1, DEFAULT_CAPS["transient"])}
    field = max(ratios, key=lambda k: ratios[k])
    guard_work("limit set", field, n_planned, bytes_per_orbit(rc.n_record), limits,
               throws_per_config=rc.transient + rc.n_record, cmap=cmap, hint="fewer starts or a shorter record")
    if starts is None:
        x0, s0 = start_grid(cmap, n_starts, rng)
    else:
        x0, s0 = check_starts(cmap, starts)
    found = find_attractors(cmap, x0, s0, rc, progress)
    info = cmap.describe()
    info["label"] = cmap.label
    info["starts"] = "grid" if starts is None else "given"
    return LimitSet(attractors=found.attractors, escapes=escape_fractions(found.fates, found.labels), starts_x=x0,
                    starts_side=s0, labels=found.labels, caps={**rc.to_dict(), "transient_used": found.transient_used},
                    map_info=info)
