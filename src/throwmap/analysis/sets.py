"""Sets of resting configurations and their images under a sequence of throws (paper Sec. I-A).

:class:`ConfigSet` is a union of intervals ``(side, lo, hi)`` (m) — goals, mouths and
spouts of funnels; :func:`push` applies a sequence of different throws Π T^{ω_j} to a
set of configurations and returns a :class:`SetImage`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown
from ..kernels import codes as C
from ..system.arm import regime_warnings_once
from .attractors import Attractor, fate_label, merge_intervals
from .budget import Limits, guard_work
from .maps import DEFAULT_MODEL, ConfigMap, ThrowMap, as_map
from .recurrence import check_starts

__all__ = ["ConfigSet", "SetImage", "push"]


@dataclass(frozen=True, slots=True)
class ConfigSet:
    """A set of resting configurations: a union of intervals ``(side, lo, hi)`` (m, lo ≤ hi).

    Build from intervals, or from a text spec with :meth:`parse`
    (``"0:0.20-0.30, 1:0.10-0.15"``, metres).
    """

    intervals: tuple

    def __post_init__(self):
        out = []
        for iv in self.intervals:
            try:
                s, lo, hi = iv
            except (TypeError, ValueError):
                raise InvalidStateError("goal", f"an interval must be (side, lo, hi), got {shown(iv)}") from None
            if isinstance(s, bool) or not isinstance(s, (int, np.integer)) or s < 0:
                raise InvalidStateError("goal", f"side must be a non-negative integer, got {shown(s)}")
            lo, hi = float(lo), float(hi)
            if not (math.isfinite(lo) and math.isfinite(hi)) or hi < lo:
                raise InvalidStateError("goal", f"side {s}: need finite lo ≤ hi, got [{lo}, {hi}]")
            out.append((int(s), lo, hi))
        object.__setattr__(self, "intervals", tuple(sorted(out)))

    def __repr__(self) -> str:
        shown = ", ".join(f"({s}, {lo:.4g}–{hi:.4g} m)" if hi > lo else f"({s}, {lo:.4g} m)"
                          for s, lo, hi in self.intervals[:3])
        more = f", … {len(self.intervals)} intervals" if len(self.intervals) > 3 else ""
        return f"ConfigSet({shown}{more}; sides {self.sides}, {self.measure():.4g} m in all)"

    @classmethod
    def parse(cls, spec: str) -> "ConfigSet":
        """``"side:lo-hi, side:lo-hi, …"`` in metres (``lo`` may equal ``hi``: one configuration)."""
        ivs = []
        for piece in str(spec).split(","):
            piece = piece.strip()
            if not piece:
                continue
            try:
                s, rng = piece.split(":")
                lo, hi = rng.split("-") if "-" in rng.strip()[1:] else (rng, rng)
                ivs.append((int(s), float(lo), float(hi)))
            except ValueError:
                raise InvalidStateError("goal", f"expected side:lo-hi in metres (e.g. 0:0.20-0.30), got {shown(piece)}") from None
        if not ivs:
            raise InvalidStateError("goal", "is empty")
        return cls(tuple(ivs))

    @classmethod
    def from_attractor(cls, a: Attractor) -> "ConfigSet":
        return cls(tuple(a.bands))

    @property
    def sides(self) -> tuple:
        return tuple(sorted({s for s, _, _ in self.intervals}))

    def contains(self, x, side, tol: float = 0.0) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        side = np.asarray(side)
        out = np.zeros(np.broadcast(x, side).shape, dtype=bool)
        for s, lo, hi in self.intervals:
            out |= (side == s) & (x >= lo - tol) & (x <= hi + tol)
        return out

    def sample(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """``n`` evenly spaced configurations per interval (one for a point), ends included."""
        xs, ss = [], []
        for s, lo, hi in self.intervals:
            v = np.linspace(lo, hi, n) if hi > lo else np.array([lo])
            xs.append(v)
            ss.append(np.full(v.size, s, dtype=np.int64))
        if not xs:
            return np.zeros(0), np.zeros(0, dtype=np.int64)
        return np.concatenate(xs), np.concatenate(ss)

    def measure(self) -> float:
        """Total length of the intervals, m."""
        return float(sum(hi - lo for _, lo, hi in self.intervals))

    def describe(self, unit: str = "m") -> str:
        k = 100.0 if unit == "cm" else 1.0
        if not self.intervals:
            return "∅"
        return " ∪ ".join(f"side {s}: [{k * lo:.4g}, {k * hi:.4g}] {unit}" if hi > lo else f"({k * lo:.4g} {unit}, {s})"
                          for s, lo, hi in self.intervals)

    def table(self) -> str:
        """One row per interval: side, ends and length, in cm for reading (the data stay in m)."""
        rows = [f"{'side':>4}  {'lo (cm)':>10}  {'hi (cm)':>10}  {'length (cm)':>11}"]
        for s, lo, hi in self.intervals:
            rows.append(f"{s:>4}  {100 * lo:>10.4f}  {100 * hi:>10.4f}  {100 * (hi - lo):>11.4f}")
        rows.append(f"total length {100 * self.measure():.4f} cm")
        return "\n".join(rows)

    def to_dict(self) -> list:
        """The intervals as ``[{"side", "lo_m", "hi_m"}, ...]`` (a list: the set is its intervals)."""
        return [{"side": s, "lo_m": lo, "hi_m": hi} for s, lo, hi in self.intervals]

    @classmethod
    def from_dict(cls, d) -> "ConfigSet":
        return cls(tuple((int(v["side"]), float(v["lo_m"]), float(v["hi_m"])) for v in d))


@dataclass(frozen=True, slots=True, eq=False)
class SetImage:
    """A set of configurations pushed through a sequence of throws Π T^{ω_j}.

    ``x``, ``side``, ``status`` (arrays, shape (n_steps + 1, n)): each configuration
    after each throw (status 0 = on the arm; escaped ones keep their last state).
    ``hulls``: the image after each throw as a :class:`ConfigSet` (points merged
    into intervals across gaps ≤ ``gap``).
    """

    omegas: tuple
    x: np.ndarray
    side: np.ndarray
    status: np.ndarray
    hulls: tuple
    gap: float

    def __repr__(self) -> str:
        w = ", ".join(f"{v:g}" for v in self.omegas[:6]) + (", …" if len(self.omegas) > 6 else "")
        fin = self.final
        return (f"SetImage(omegas=[{w}] rad/s, {self.x.shape[1]} configs, {100 * self.escaped:.1f} % escaped, "
                f"final: {len(fin.intervals)} interval(s) on sides {fin.sides}, {fin.measure():.4g} m)")

    @property
    def final(self) -> ConfigSet:
        return self.hulls[-1]

    @property
    def escaped(self) -> float:
        """Share of the configurations that left the arm (or failed a throw) along the sequence."""
        return float(np.mean(self.status[-1] != C.OK)) if self.status.size else 0.0

    def escapes(self) -> dict:
        st = self.status[-1]
        return {fate_label(int(c)): float(np.mean(st == c)) for c in np.unique(st) if c != C.OK}

    def summary(self) -> str:
        lines = [f"{self.x.shape[1]} configurations through {len(self.omegas)} throws"]
        for k, w in enumerate(self.omegas, start=1):
            lost = float(np.mean(self.status[k] != C.OK))
            lines.append(f"  after throw {k} (ω = {w:g} rad/s): {self.hulls[k].describe('cm')}"
                         + (f"; {100 * lost:.1f} % off the arm" if lost else ""))
        return "\n".join(lines)

    def table(self) -> str:
        """One row per throw: ω, share still on the arm, and the image's intervals (cm)."""
        rows = [f"{'throw':>5}  {'ω (rad/s)':>9}  {'on arm %':>8}  image (cm)"]
        for k in range(len(self.hulls)):
            w = f"{self.omegas[k - 1]:g}" if k else "-"
            on = 100 * float(np.mean(self.status[k] == C.OK)) if self.status.size else 0.0
            rows.append(f"{k:>5}  {w:>9}  {on:>8.1f}  {self.hulls[k].describe('cm')}")
        return "\n".join(rows)

    def to_dict(self, arrays: bool = True) -> dict:
        """JSON-ready; ``arrays`` adds every configuration after every throw (needed by :meth:`from_dict`)."""
        d = {"omegas_rad_s": list(self.omegas), "hulls": [h.to_dict() for h in self.hulls],
             "escapes": self.escapes(), "gap_m": self.gap, "n": int(self.x.shape[1])}
        if arrays:
            d["configs"] = {"x_m": self.x.tolist(), "side": self.side.tolist(), "status": self.status.tolist()}
        return d

    @classmethod
    def from_dict(cls, d: dict) -> "SetImage":
        if "configs" not in d:
            raise InvalidStateError("configs", "this set image was written without its arrays")
        c = d["configs"]
        n = int(d["n"])
        shape = (len(d["omegas_rad_s"]) + 1, n)
        return cls(omegas=tuple(float(w) for w in d["omegas_rad_s"]),
                   x=np.asarray(c["x_m"], dtype=float).reshape(shape),
                   side=np.asarray(c["side"], dtype=np.int64).reshape(shape),
                   status=np.asarray(c["status"], dtype=np.int64).reshape(shape),
                   hulls=tuple(ConfigSet.from_dict(h) for h in d["hulls"]), gap=float(d["gap_m"]))


@regime_warnings_once()
def push(part, arm=None, omegas=None, configs=None, model: str = DEFAULT_MODEL, *, n: int = 200, gap: float = 2e-3,
         x_max=None, limits: Limits | None = None, **throw_options) -> SetImage:
    """Apply a sequence of throws Π T^{ω_j} (ω_1 first) to a set of configurations.

    ``configs`` is a :class:`ConfigSet` (sampled with ``n`` points per interval) or
    ``(x, side)`` arrays. With a :class:`ThrowMap` as ``part``, its part, arm and
    model are used and ``omegas`` gives the sequence. The work guard
    (:class:`~throwmap.budget.Limits`) refuses above ``limits.max_memory`` bytes (24 bytes per
    configuration and throw are kept) or ``limits.max_seconds``, unless ``limits.force``.
    """
    limits = Limits.of(limits)
    if isinstance(part, ThrowMap):
        base = part
    elif isinstance(part, ConfigMap):
        raise InvalidStateError("part", "push needs a part (or ThrowMap), not a function map")
    else:
        base = as_map(part, arm, 1.0, model, x_max=x_max, **throw_options)
    if not isinstance(base, ThrowMap):
        raise InvalidStateError("part", "push needs a part (or ThrowMap), not a function map")
    oms = np.atleast_1d(np.asarray(omegas, dtype=float)) if omegas is not None else np.zeros(0)
    if oms.ndim != 1 or oms.size == 0:
        raise InvalidStateError("omegas", "must be a non-empty sequence of release rates")
    if isinstance(configs, str):
        configs = ConfigSet.parse(configs)
    if isinstance(configs, ConfigSet):
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
            raise InvalidStateError("n", f"must be an integer ≥ 2 (samples per interval), got {shown(n)}")
        n_planned = int(n) * max(1, len(configs.intervals))
        guard_work("push", "n", n_planned, 24 * (oms.size + 1), limits,
                   throws_per_config=float(oms.size), cmap=base,
                   hint="fewer samples per interval")
        configs = configs.sample(n)
    try:
        x0, s0 = check_starts(base, configs)
    except InvalidStateError as err:
        raise InvalidStateError("configs", err.reason) from None
    maps = {float(w): base.with_omegas(float(w)) for w in np.unique(oms)}
    X = np.empty((oms.size + 1, x0.size))
    S = np.empty((oms.size + 1, x0.size), dtype=np.int64)
    ST = np.zeros((oms.size + 1, x0.size), dtype=np.int64)
    X[0], S[0] = x0, s0
    hulls = [merge_intervals({int(k): x0[s0 == k] for k in np.unique(s0)}, gap)]
    for k, w in enumerate(oms, start=1):
        X[k], S[k], ST[k] = X[k - 1], S[k - 1], ST[k - 1]
        alive = np.flatnonzero(ST[k] == C.OK)
        if alive.size:
            xn, sn, st = maps[float(w)](X[k, alive], S[k, alive])
            ok = st == C.OK
            X[k, alive[ok]] = xn[ok]
            S[k, alive[ok]] = sn[ok]
            ST[k, alive] = st
        on = ST[k] == C.OK
        hulls.append(merge_intervals({int(s): X[k][on & (S[k] == s)] for s in np.unique(S[k][on])}, gap))
    return SetImage(omegas=tuple(float(w) for w in oms), x=X, side=S, status=ST,
                    hulls=tuple(ConfigSet(h) for h in hulls), gap=float(gap))
