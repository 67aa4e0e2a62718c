"""A map sampled on a grid: T(x) for evenly spaced x on each side (the data of paper Fig. 2).

The throw map T^ω sends a resting configuration (x, side) to the next one
(paper Sec. III-D). :class:`MapSamples` holds one application of a map to ``n``
evenly spaced x per side, ``x_k = x_lo + k (x_hi − x_lo) / n`` for ``k = 1 … n``
(the open end ``x_lo`` excluded): the start, its image and the image's status.
Figures draw it (:meth:`MapSamples.plot`) without evaluating anything.

:func:`throw_map_samples`  the throw map of a part on an arm at one release rate;
:func:`sample_map`         any configuration map (:mod:`throwmap.analysis.maps`:
                           a ``ThrowMap``, a composed sequence, a ``FunctionMap``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, shown
from ..system.arm import Arm
from ..system.part import Part
from ..records.outcome import Status
from ..models import DEFAULT_MODEL
from .throw import throw_batch

__all__ = ["MapSamples", "sample_map", "throw_map_samples"]

DEFAULT_N = 1500
"""Samples per side of a throw-map figure."""

DEFAULT_X_MAX = 0.5
"""Outer end of the sampled x on an unbounded arm, m, for :func:`throw_map_samples`."""


def _frozen(a, dtype) -> np.ndarray:
    a = np.array(a, dtype=dtype).ravel()
    a.setflags(write=False)
    return a


@dataclass(frozen=True, slots=True)
class MapSamples:
    """One step of a map from ``n`` evenly spaced x on each side; flat arrays, side by side in :attr:`sides` order.

    Attributes
    ----------
    x, side : ndarray
        Starts: x of the CM along the arm (m) and the side resting on the arm.
    x_next, side_next : ndarray
        Their images (m, side index); meaningful where ``status == 0``.
    status : ndarray
        :class:`~throwmap.records.outcome.Status` code of each image (0 = rests on
        the arm; otherwise the orbit ends there — off the arm, no rest, …).
    sides : tuple of int
        The sampled sides, in order; entries ``[i n, (i + 1) n)`` belong to ``sides[i]``.
    x_lo, x_hi : tuple of float
        Each side's domain ``(x_lo, x_hi]`` (m), in :attr:`sides` order.
    label : str
        What map this is (part, ω in rad/s, model), the figure's title.
    info : dict
        The map's description (model, ω, h …), JSON-ready.
    """

    x: np.ndarray
    side: np.ndarray
    x_next: np.ndarray
    side_next: np.ndarray
    status: np.ndarray
    sides: tuple
    x_lo: tuple
    x_hi: tuple
    label: str = "map"
    info: dict = field(default_factory=dict)

    def __post_init__(self):
        for name, dtype in (("x", float), ("side", np.int64), ("x_next", float), ("side_next", np.int64),
                            ("status", np.int64)):
            object.__setattr__(self, name, _frozen(getattr(self, name), dtype))
        object.__setattr__(self, "sides", tuple(int(s) for s in self.sides))
        object.__setattr__(self, "x_lo", tuple(float(v) for v in self.x_lo))
        object.__setattr__(self, "x_hi", tuple(float(v) for v in self.x_hi))
        n_all = self.x.size
        if not (self.side.size == self.x_next.size == self.side_next.size == self.status.size == n_all):
            raise InvalidStateError("samples", "x, side, x_next, side_next and status must have one length")
        if not self.sides or len(self.x_lo) != len(self.sides) or len(self.x_hi) != len(self.sides):
            raise InvalidStateError("sides", "need one (x_lo, x_hi) per sampled side, and at least one side")
        if n_all % len(self.sides):
            raise InvalidStateError("samples", f"{n_all} samples do not split evenly over {len(self.sides)} sides")
        n = self.n
        for i, s in enumerate(self.sides):
            if np.any(self.side[i * n:(i + 1) * n] != s):
                raise InvalidStateError("side", f"samples {i * n}…{(i + 1) * n - 1} must all start on side {s}")

    def __repr__(self) -> str:
        info = self.info
        if "model" in info and "omega_rad_s" in info:
            what = f"model={info['model']!r}, omega={info['omega_rad_s']:g} rad/s"
        else:
            what = f"map={(self.label if len(self.label) <= 60 else self.label[:59] + '…')!r}"
        ok = 100.0 * float(np.mean(self.ok)) if self.status.size else 0.0
        return (f"MapSamples({what}, sides {', '.join(map(str, self.sides))}, {self.n} per side, "
                f"x∈({min(self.x_lo):.4g}, {max(self.x_hi):.4g}] m, {ok:.1f} % rest on the arm)")

    @property
    def n(self) -> int:
        """Samples per side."""
        return self.x.size // len(self.sides)

    @property
    def ok(self) -> np.ndarray:
        """Where the image rests on the arm (``status == 0``)."""
        return self.status == Status.OK

    def kinds(self) -> np.ndarray:
        """What each throw does, as text: ``"jog"`` (lands on its own side before any flip from that side),
        ``"flip"`` (lands on another side), ``"tumble"`` (lands on its own side beyond a flip: it tumbled over and
        back, paper Sec. III-D — beyond r_i no throw jogs) or ``"escape"`` (no rest on the arm). Samples are in x
        order per side, as :func:`throw_map_samples` makes them."""
        out = np.full(self.x.size, "escape", dtype=object)
        ok = self.ok
        for s in self.sides:
            sl = self.panel(s)
            same, good = self.side_next[sl] == s, ok[sl]
            flips = np.flatnonzero(good & ~same)
            first = flips[0] if flips.size else self.n
            kind = np.where(same, np.where(np.arange(self.n) < first, "jog", "tumble"), "flip")
            out[sl] = np.where(good, kind, "escape")
        return out

    def panel(self, side: int) -> slice:
        """The slice of the flat arrays that starts on ``side``."""
        if side not in self.sides:
            raise InvalidStateError("side", f"must be one of the sampled sides {list(self.sides)}, got {shown(side)}")
        i = self.sides.index(side)
        return slice(i * self.n, (i + 1) * self.n)

    def to_dict(self) -> dict:
        """Plain lists and numbers (m, side indices, status codes); :meth:`from_dict` reads it back."""
        return {"x_m": self.x.tolist(), "side": self.side.tolist(), "x_next_m": self.x_next.tolist(),
                "side_next": self.side_next.tolist(), "status": self.status.tolist(), "sides": list(self.sides),
                "x_lo_m": list(self.x_lo), "x_hi_m": list(self.x_hi), "label": self.label, "info": dict(self.info)}

    @classmethod
    def from_dict(cls, d: dict) -> "MapSamples":
        return cls(x=d["x_m"], side=d["side"], x_next=d["x_next_m"], side_next=d["side_next"], status=d["status"],
                   sides=d["sides"], x_lo=d["x_lo_m"], x_hi=d["x_hi_m"], label=d.get("label", "map"),
                   info=dict(d.get("info", {})))

    def plot(self, axes=None, **kwargs):
        """T(x) against x per side (paper Fig. 2); see :func:`throwmap.viz.throw_map.plot_map`."""
        from ..viz.throw_map import plot_map

        return plot_map(self, axes=axes, **kwargs)


def _check_n(n, least: int) -> int:
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < least:
        raise InvalidStateError("n", f"must be an integer ≥ {least}, got {shown(n)}")
    return int(n)


def _grid(sides, x_lo, x_hi, n: int) -> tuple[np.ndarray, np.ndarray]:
    """``n`` evenly spaced x per side over ``(x_lo, x_hi]``; flat ``(x, side)``."""
    xs = [np.linspace(lo, hi, n + 1)[1:] for lo, hi in zip(x_lo, x_hi)]
    ss = [np.full(n, s, dtype=np.int64) for s in sides]
    return np.concatenate(xs), np.concatenate(ss)


def sample_map(cmap, n: int = DEFAULT_N) -> MapSamples:
    """Apply a configuration map once to ``n`` evenly spaced x on each of its sides (one batch).

    ``cmap`` is any configuration map (:class:`~throwmap.analysis.maps.ConfigMap`:
    ``sides``, ``x_lo``/``x_hi`` in m, ``label``, and a vectorised call
    ``cmap(x, side) -> (x', side', status)``); ``n ≥ 2`` points per side over
    ``(x_lo, x_hi]``. The label and ``describe()`` of the map go with the samples.
    """
    n = _check_n(n, 2)
    sides = [int(s) for s in cmap.sides]
    x_lo = [float(cmap.x_lo[s]) for s in sides]
    x_hi = [float(cmap.x_hi[s]) for s in sides]
    x, side = _grid(sides, x_lo, x_hi, n)
    xn, sn, st = cmap(x, side)
    info = cmap.describe() if hasattr(cmap, "describe") else {}
    return MapSamples(x=x, side=side, x_next=xn, side_next=sn, status=st, sides=sides, x_lo=x_lo, x_hi=x_hi,
                      label=str(cmap.label), info=info)


def throw_map_samples(part: Part, arm: Arm, omega: float, *, model: str = DEFAULT_MODEL, sides=None, x_max=None,
                      n: int = DEFAULT_N, **throw_options) -> MapSamples:
    """The throw map T^ω of ``part`` on ``arm`` (paper Sec. III-D, Fig. 2) at ``n`` x per side.

    ``omega`` is the release rate (rad/s); ``sides`` the starting sides (default:
    every stable side); each side is sampled over ``(part.x_min(side), x_max]``
    (m), ``x_max`` defaulting to the arm length, or :data:`DEFAULT_X_MAX` for an
    unbounded arm; with a :class:`~throwmap.Wall` in ``fixtures`` and ``x_max`` not given,
    each side stops where its outer vertex meets the wall (x + u_R = L). Inadmissible starts get status ``INVALID_START`` rather than an
    error; ``throw_options`` go to :func:`throwmap.throw_batch`.
    """
    n = _check_n(n, 1)
    sides = list(part.stable_sides) if sides is None else [part.check_side(s) for s in sides]
    from ..system.fixtures import Wall

    fx = throw_options.get("fixtures") or ()
    walled = x_max is None and arm.length is not None and any(isinstance(f, Wall) for f in (
        fx if isinstance(fx, (tuple, list)) else (fx,)))
    if x_max is None:
        x_max = arm.length if arm.length is not None else DEFAULT_X_MAX
    x_max = float(x_max)
    if not math.isfinite(x_max):
        raise InvalidStateError("x_max", f"must be finite, got {x_max}")
    x_lo = [part.x_min(s) for s in sides]
    if x_max <= max(x_lo):  # a side with no start below x_max: nothing to sample there, say so
        raise InvalidStateError("x_max", f"must exceed the first valid x on every side ({max(x_lo):.6g} m), got "
                                         f"{x_max:.6g}")
    x_hi = [x_max] * len(sides)
    if walled:  # stop each side where its outer vertex meets the wall (beyond, no rest exists)
        from ..system.starts import start_interval

        x_hi = [min(x_max, start_interval(part, arm, s)[1]) for s in sides]
        x_hi = [hi if hi > lo else x_max for hi, lo in zip(x_hi, x_lo)]
    x, side = _grid(sides, x_lo, x_hi, n)
    res = throw_batch(part, arm, x, side, omega, model=model, on_invalid="status", **throw_options)
    label = f"throw map, model {model!r}, ω = {omega:g} rad/s, h = {arm.h:g} m"
    info = {"kind": "throw", "part": part.name, "h_m": arm.h, "g_m_s2": arm.g, "arm_length_m": arm.length,
            "omega_rad_s": float(omega), "model": model, "x_max_m": x_max}
    return MapSamples(x=x, side=side, x_next=res.x, side_next=res.side, status=res.status, sides=sides, x_lo=x_lo,
                      x_hi=x_hi, label=label, info=info)
