"""Attractors of a configuration map, and the label −1 (paper Sec. III-D, "forward limit sets").

An :class:`Attractor` is one forward limit set found by iterating a map:

``"fixed_point"``  a configuration T(x, i) = (x, i);
``"cycle"``        a period-p orbit, p ≥ 2 (paper Fig. 2 left: a period-two spout);
``"band"``         an aperiodic set, described by its intervals per side — what the
                   canonical triangle has, since every branch of its map stretches x.

Labels follow Attractors.jl: attractors are numbered 1, 2, …; the label
:data:`LABEL_ESCAPE` = −1 means the orbit **did not end on an attractor on the arm**:
a throw left the arm (behind the joint or past its end), failed to come to rest
(``no_rest``, ``timeout``, ``penetration``, ``inconsistent``), or the orbit reached
no known attractor within the throw cap (``unresolved``). The *fate* code says which.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..throws.outcome import Status

__all__ = ["Attractor", "LABEL_ESCAPE", "FATE_UNRESOLVED", "fate_label", "fate_code", "merge_intervals",
           "escape_fractions", "attractor_table", "nan_to_none", "none_to_nan"]

LABEL_ESCAPE = -1
"""Label of a configuration whose orbit does not end on an attractor on the arm."""

FATE_UNRESOLVED = -1
"""Fate code of an orbit that reached no known attractor within the throw cap."""

KINDS = ("fixed_point", "cycle", "band")


def fate_label(code: int) -> str:
    """``"attracted"`` for OK (0), the status label for an escape, ``"unresolved"`` for −1."""
    code = int(code)
    if code == FATE_UNRESOLVED:
        return "unresolved"
    if code == Status.OK:
        return "attracted"
    return Status(code).label


def fate_code(label: str) -> int:
    if label == "unresolved":
        return FATE_UNRESOLVED
    if label == "attracted":
        return int(Status.OK)
    for s in Status:
        if s.label == label:
            return int(s)
    raise ValueError(f"unknown fate {label!r}")


def escape_fractions(fates, labels) -> dict:
    """``{fate label: share}`` over the starts labelled −1 (shares of all starts)."""
    fates = np.asarray(fates)
    n = max(1, fates.size)
    esc = np.asarray(labels) == LABEL_ESCAPE
    return {fate_label(c): float(np.sum(esc & (fates == c)) / n) for c in np.unique(fates[esc])}


def merge_intervals(side_x: dict, gap: float) -> tuple:
    """Per side, split sorted points where consecutive ones are more than ``gap`` apart.

    ``side_x`` maps side → array of x (m). Returns ``((side, lo, hi), ...)`` sorted.
    """
    out = []
    for s in sorted(side_x):
        xs = np.sort(np.asarray(side_x[s], dtype=float))
        if xs.size == 0:
            continue
        cut = np.flatnonzero(np.diff(xs) > gap)
        starts = np.concatenate(([0], cut + 1))
        ends = np.concatenate((cut, [xs.size - 1]))
        out.extend((int(s), float(xs[a]), float(xs[b])) for a, b in zip(starts, ends))
    return tuple(out)


@dataclass(frozen=True, slots=True)
class Attractor:
    """One forward limit set of a configuration map.

    Attributes
    ----------
    id : int
        1, 2, … (never −1; see :data:`LABEL_ESCAPE`).
    kind : str
        ``"fixed_point"``, ``"cycle"`` or ``"band"``.
    period : int
        Throws (map steps) per cycle; 0 for a band.
    points : tuple of (side, x)
        A cycle's configurations in orbit order, x in m; empty for a band.
    bands : tuple of (side, lo, hi)
        Intervals per side, m, sorted; a cycle point is the interval (x, x).
    multiplier : float
        d(T^p)/dx along a cycle (product of the branch slopes); nan for a band.
        ``|multiplier| < 1``: stable, 0: superstable (e.g. a part held by a wall).
    lyapunov : float
        Mean log|dT/dx| per step along the attractor (> 0: the map stretches, a band).
    fraction : float
        Share of the analysed starting configurations that end on it.
    side_visits : tuple of (side, share)
        Share of the attractor's recorded configurations on each side.
    """

    id: int
    kind: str
    period: int
    points: tuple
    bands: tuple
    multiplier: float
    lyapunov: float
    fraction: float
    side_visits: tuple

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"kind must be one of {KINDS}, got {self.kind!r}")

    @property
    def stable(self) -> bool | None:
        """For a cycle, ``|multiplier| < 1``; None for a band (it attracts as a set)."""
        if self.kind == "band" or not math.isfinite(self.multiplier):
            return None
        return bool(abs(self.multiplier) < 1.0)

    @property
    def sides(self) -> tuple[int, ...]:
        return tuple(sorted({int(b[0]) for b in self.bands}))

    def interval(self, side: int):
        """``(lo, hi)`` hull of the attractor on ``side`` (m), or None if it never rests there."""
        bs = [b for b in self.bands if b[0] == side]
        if not bs:
            return None
        return (min(b[1] for b in bs), max(b[2] for b in bs))

    def contains(self, x, side, tol: float) -> np.ndarray:
        """Whether each configuration lies on the attractor to within ``tol`` m."""
        x = np.asarray(x, dtype=float)
        side = np.asarray(side)
        out = np.zeros(np.broadcast(x, side).shape, dtype=bool)
        for s, lo, hi in self.bands:
            out |= (side == s) & (x >= lo - tol) & (x <= hi + tol)
        return out

    def describe(self) -> str:
        """One line: kind, sides and intervals in metres."""
        if self.kind == "band":
            iv = "; ".join(f"side {s}: [{lo:.4f}, {hi:.4f}]" for s, lo, hi in self.bands)
            return f"#{self.id} band (Lyapunov {self.lyapunov:+.3f}/step) {iv}"
        pts = ", ".join(f"({x:.5f}, {s})" for s, x in self.points)
        st = {True: "stable", False: "unstable", None: "?"}[self.stable]
        name = "fixed point" if self.kind == "fixed_point" else f"period-{self.period} cycle"
        return f"#{self.id} {name}, multiplier {self.multiplier:+.4g} ({st}): {pts}"

    def to_dict(self) -> dict:
        return {
            "id": self.id, "kind": self.kind, "period": self.period,
            "points": [{"side": int(s), "x_m": float(x)} for s, x in self.points],
            "bands": [{"side": int(s), "lo_m": float(lo), "hi_m": float(hi)} for s, lo, hi in self.bands],
            "multiplier": nan_to_none(self.multiplier), "lyapunov": nan_to_none(self.lyapunov),
            "stable": self.stable, "fraction": float(self.fraction),
            "side_visits": [{"side": int(s), "share": float(v)} for s, v in self.side_visits],
        }

    @classmethod
    def from_dict(cls, d: dict) -> "Attractor":
        return cls(
            id=int(d["id"]), kind=str(d["kind"]), period=int(d["period"]),
            points=tuple((int(p["side"]), float(p["x_m"])) for p in d["points"]),
            bands=tuple((int(b["side"]), float(b["lo_m"]), float(b["hi_m"])) for b in d["bands"]),
            multiplier=none_to_nan(d["multiplier"]), lyapunov=none_to_nan(d["lyapunov"]), fraction=float(d["fraction"]),
            side_visits=tuple((int(v["side"]), float(v["share"])) for v in d["side_visits"]),
        )


def attractor_table(attractors, escapes: dict, share: str = "share %") -> str:
    """Attractors and escapes as a plain-text table, one row per label (intervals in cm for reading).

    ``escapes`` maps each escape fate to its share; ``share`` heads the share column.
    """
    rows = [f"{'label':>5}  {'kind':<13}{'period':>6}  {'multiplier':>10}  {'Lyapunov':>8}  {share:>9}  "
            "intervals per side (cm)"]
    for a in attractors:
        iv = "; ".join(f"{s}: {100 * lo:.3f}–{100 * hi:.3f}" if hi > lo else f"{s}: {100 * lo:.4f}"
                       for s, lo, hi in a.bands)
        rows.append(f"{a.id:>5}  {a.kind:<13}{a.period:>6}  {a.multiplier:>10.4g}  {a.lyapunov:>+8.3f}  "
                    f"{100 * a.fraction:>9.2f}  {iv}")
    for k, v in escapes.items():
        rows.append(f"{LABEL_ESCAPE:>5}  {k:<13}{'':>6}  {'':>10}  {'':>8}  {100 * v:>9.2f}")
    return "\n".join(rows)


def nan_to_none(v: float):
    """JSON has no nan: None stands for it."""
    return None if v is None or not math.isfinite(v) else float(v)


def none_to_nan(v) -> float:
    """The inverse of :func:`nan_to_none`."""
    return math.nan if v is None else float(v)
