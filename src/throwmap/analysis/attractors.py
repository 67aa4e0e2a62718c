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

from ..errors import InvalidStateError
from ..records.outcome import Status

__all__ = ["Attractor", "LABEL_ESCAPE", "FATE_UNRESOLVED", "fate_label", "fate_code", "merge_intervals",
           "escape_fractions", "attractor_table", "nan_to_none", "none_to_nan", "check_cycles", "domain_text",
           "domain_of", "range_short", "map_short", "system_short", "attractor_counts"]

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
    residual : float
        For a fixed point or cycle, max |T^k(x_0) − x_k| over k = 1 … p (the last is
        |T^p(x_0) − x_0|), m, measured by applying the map p times from the first point
        (:func:`~throwmap.analysis.cycles.cycle_residual`; inf if an image lands on
        another side or escapes); nan for a band or when not measured.
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
    residual: float = math.nan

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"kind must be one of {KINDS}, got {self.kind!r}")

    def __repr__(self) -> str:
        """``Attractor(#1 band, sides (0, 1, 2), x∈[0.1728, 0.5296] m, Lyapunov +0.200/step, 100.0 %)``."""
        if self.kind == "band":
            lo = min(b[1] for b in self.bands)
            hi = max(b[2] for b in self.bands)
            what = (f"band, sides {self.sides}, x∈[{lo:.4g}, {hi:.4g}] m in {len(self.bands)} interval(s), "
                    f"Lyapunov {self.lyapunov:+.3f}/step")
        else:
            pts = ", ".join(f"({x:.5g} m, side {s})" for s, x in self.points[:3])
            more = f", … {self.period} points" if self.period > 3 else ""
            name = "fixed point" if self.kind == "fixed_point" else f"period-{self.period} cycle"
            what = f"{name} {pts}{more}, multiplier {self.multiplier:+.3g}"
        return f"Attractor(#{self.id} {what}, {100 * self.fraction:.1f} %)"

    def with_fraction(self, fraction: float, ident: int | None = None) -> "Attractor":
        """A copy with another share (and id)."""
        return Attractor(id=self.id if ident is None else ident, kind=self.kind, period=self.period,
                         points=self.points, bands=self.bands, multiplier=self.multiplier, lyapunov=self.lyapunov,
                         fraction=float(fraction), side_visits=self.side_visits, residual=self.residual)

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
            "residual_m": None if math.isnan(self.residual) else (
                float(self.residual) if math.isfinite(self.residual) else "inf"),
        }

    @classmethod
    def from_dict(cls, d: dict) -> "Attractor":
        return cls(
            id=int(d["id"]), kind=str(d["kind"]), period=int(d["period"]),
            points=tuple((int(p["side"]), float(p["x_m"])) for p in d["points"]),
            bands=tuple((int(b["side"]), float(b["lo_m"]), float(b["hi_m"])) for b in d["bands"]),
            multiplier=none_to_nan(d["multiplier"]), lyapunov=none_to_nan(d["lyapunov"]), fraction=float(d["fraction"]),
            side_visits=tuple((int(v["side"]), float(v["share"])) for v in d["side_visits"]),
            residual=none_to_nan(d.get("residual_m")) if d.get("residual_m") != "inf" else math.inf,
        )


def check_cycles(attractors, tol: float) -> None:
    """Refuse a fixed point or cycle whose measured residual |T^p(x) − x| exceeds ``tol`` (m), or was never measured.

    Raises :class:`~throwmap.errors.InvalidStateError` naming the attractor: a result
    never holds a cycle that the map does not close.
    """
    for a in attractors:
        if a.kind != "band" and not a.residual <= tol:
            raise InvalidStateError("attractors", f"#{a.id} {a.kind.replace('_', ' ')}: |T^p(x) − x| = "
                                                  f"{a.residual:.3g} m is not within tol = {tol:.3g} m on the same "
                                                  "side: not a cycle of the map")


def domain_text(domain: dict, valid_from_joint: bool = False) -> str:
    """The range of starts a result covers, e.g. ``"valid starts with x ≤ 0.600 m"``.

    ``domain`` is ``{side: (x_lo, x_hi)}`` (m; x_lo excluded). ``valid_from_joint``: the
    lower ends are the part's first valid x per side, so the range is every valid start
    up to x_hi; otherwise both ends are given.
    """
    if not domain:
        return "the analysed starts"
    his = {round(float(v[1]), 12) for v in domain.values()}
    los = {round(float(v[0]), 12) for v in domain.values()}
    if valid_from_joint and len(his) == 1:
        return f"valid starts with x ≤ {his.pop():.3f} m"
    if len(his) == 1 and len(los) == 1:
        return f"starts with {los.pop():.4g} < x ≤ {his.pop():.4g} m"
    return "starts with " + ", ".join(f"{float(lo):.4g} < x ≤ {float(hi):.4g} m on side {k}"
                                      for k, (lo, hi) in sorted(domain.items(), key=lambda kv: int(kv[0])))


def domain_of(map_info: dict) -> tuple[dict, bool]:
    """``({side: (lo, hi)}, valid_from_joint)`` from a result's ``map_info`` (empty if it does not say)."""
    d = map_info.get("domain_m") or {}
    return ({int(k): (float(v[0]), float(v[1])) for k, v in d.items()}, map_info.get("kind") == "throw")


def range_short(map_info: dict) -> str:
    """``x∈(0, 0.6] m`` for a repr: the lowest x_lo and the highest x_hi."""
    dom, _ = domain_of(map_info)
    if not dom:
        return "x range not recorded"
    return f"x∈({min(v[0] for v in dom.values()):.4g}, {max(v[1] for v in dom.values()):.4g}] m"


def system_short(map_info: dict) -> str:
    """``alpha=5°, wall 5 cm (μ 0)`` from a throw map's ``map_info`` (empty on the paper's plain arm)."""
    bits = []
    alpha = float(map_info.get("alpha_rad") or 0.0)
    if alpha:
        bits.append(f"alpha={math.degrees(alpha):.3g}°")
    for f in map_info.get("fixtures") or ():
        if f.get("kind") == "wall":
            mu = f.get("mu")
            mu = "arm μ" if mu == "arm" else ("μ ∞" if mu is None else f"μ {mu:g}")
            bits.append(f"wall {100 * f['height_m']:.3g} cm ({mu})")
        elif f.get("kind") == "cavity":
            bits.append("cavity")
    return ", ".join(bits)


def map_short(map_info: dict) -> str:
    """``model='paper', omega=4 rad/s`` (a throw map, with ``alpha=…, wall …`` where the arm has them)
    or ``map='name'``, for a repr."""
    if map_info.get("kind") == "throw":
        w = ", ".join(f"{v:g}" for v in map_info.get("omegas_rad_s", ()))
        extra = system_short(map_info)
        return f"model={map_info.get('model')!r}, omega={w} rad/s" + (f", {extra}" if extra else "")
    return f"map={map_info.get('name', map_info.get('label', 'map'))!r}"


def attractor_counts(attractors) -> str:
    """``"1 band, 2 cycles"``; ``"no attractor"`` when empty."""
    names = {"fixed_point": "fixed point", "cycle": "cycle", "band": "band"}
    out = []
    for k in KINDS:
        n = sum(1 for a in attractors if a.kind == k)
        if n:
            out.append(f"{n} {names[k]}{'s' if n > 1 else ''}")
    return ", ".join(out) if out else "no attractor"


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
