"""Discrete maps on resting configurations (x, side): the one interface the analysis uses.

A *configuration map* takes arrays ``x`` (m) and ``side`` (int) and returns
``(x', side', status)``: where each configuration rests after one application of
the map, and a :class:`~throwmap.records.outcome.Status` code (``OK`` = 0 means it rests
on the arm; anything else means the orbit ends there — it left the arm, or the
throw did not come to rest). This is Attractors.jl's ``mapper`` idea for the
paper's configuration space ℝ⁺ × ℕ mod n (Sec. III-D).

Two kinds are provided:

:class:`ThrowMap`     the physical throw map T^ω of a part on an arm under one model,
                      or a composed sequence Π T^{ω_j} (Sec. I-A) applied as one step;
:class:`FunctionMap`  any vectorised Python function — synthetic maps with known
                      attractors (tests, teaching) or a user's own model.

Both carry the domain on which "all initial configurations" are drawn: for every
side in :attr:`sides` the interval ``(x_lo[side], x_hi[side]]``. For a throw map it is
exactly the starts :func:`throwmap.throw` accepts on that side
(:func:`throwmap.system.starts.start_interval`, the start check's own rule:
the left support vertex ahead of the arm's edge behind the joint, ``x + u_L > −arm.back``,
and the right one on the arm, ``x + u_R ≤ arm.length``), cut at ``x_max``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, ClassVar

import numpy as np

from ..system.arm import Arm
from ..errors import InvalidStateError, shown
from ..kernels import codes as C
from ..models import DEFAULT_MODEL, check_model  # DEFAULT_MODEL re-exported here for the analysis modules
from ..system.part import Part
from ..throws.throw import prepare, throw_batch
from ..system.starts import check_omega, start_interval

__all__ = ["ConfigMap", "ThrowMap", "FunctionMap", "DEFAULT_X_MAX", "DEFAULT_MODEL", "as_map", "config_grid",
           "fixtures_doc", "plot_throw_map", "system_text"]

DEFAULT_X_MAX = 0.6
"""Outer end of the analysed domain on an unbounded arm, m (the paper's arms span ≈ 60 cm).

Every result says the range it covers (certificates, summaries, reprs): beyond it a
map can have other attractors (the canonical triangle at ω = 5.6 rad/s, μ = 1 has a
fixed point near 1.17 m although every orbit from x ≤ 0.6 m leaves behind the joint)."""


class ConfigMap:
    """Interface: ``step(x, side) -> (x', side', status)`` on flat arrays, plus the domain.

    Subclasses set ``sides`` (tuple of ints), ``x_lo``/``x_hi`` (dicts side → m),
    ``throws_per_step`` (physical throws in one step) and ``label`` (str).
    """

    sides: tuple
    x_lo: dict
    x_hi: dict
    throws_per_step: int
    label: str
    deterministic: bool = False
    """Whether one state always maps to the same image, whatever else is in the batch (bit for bit):
    the recurrence test then stops throwing an orbit once it repeats exactly."""

    def step(self, x, side):  # pragma: no cover - interface
        raise NotImplementedError

    def __call__(self, x, side):
        """Vectorised step on anything array-like; returns ``(x', side', status)`` arrays."""
        x = np.ascontiguousarray(np.asarray(x, dtype=float).ravel())
        side = np.ascontiguousarray(np.asarray(side).ravel().astype(np.int64))
        if side.size == 1 and x.size > 1:
            side = np.full(x.size, int(side[0]), dtype=np.int64)
        if x.size == 0:
            return x.copy(), side.copy(), np.zeros(0, dtype=np.int64)
        return self.step(x, side)

    def check_side(self, side) -> int:
        if isinstance(side, bool) or not isinstance(side, (int, np.integer)) or int(side) not in self.sides:
            raise InvalidStateError("side", f"must be one of the stable sides {list(self.sides)}, got {shown(side)}")
        return int(side)

    def domain(self) -> dict:
        """``{side: (x_lo, x_hi)}`` in metres."""
        return {s: (float(self.x_lo[s]), float(self.x_hi[s])) for s in self.sides}


def _check_x_max(x_max, lo_max: float, arm_length) -> float:
    if x_max is None:
        x_max = arm_length if arm_length is not None else DEFAULT_X_MAX
    if isinstance(x_max, bool):
        raise InvalidStateError("x_max", f"must be a number, got {shown(x_max)}")
    try:
        v = float(x_max)
    except (TypeError, ValueError):
        raise InvalidStateError("x_max", f"must be a number, got {shown(x_max)}") from None
    if not math.isfinite(v):
        raise InvalidStateError("x_max", f"must be finite, got {v}")
    if v <= lo_max:
        raise InvalidStateError("x_max", f"must exceed the first valid x on every side ({lo_max:.6g} m), got {v:.6g}")
    if arm_length is not None and v > arm_length:
        raise InvalidStateError("x_max", f"is beyond the arm's end ({arm_length:g} m), got {v:.6g}")
    return v


def fixtures_doc(fixtures) -> list:
    """Fixtures for JSON output: ``[{"kind": "wall", "height_m", "thickness_m", "mu"}, {"kind": "cavity",
    "profile_m": [[s, y], …]}]``. A wall's ``"mu"`` is ``"arm"`` where it takes the arm's μ
    (``Wall.mu`` None) and ``null`` for μ = ∞ (no slip), as everywhere in the JSON output."""
    from ..system.fixtures import Cavity, Wall

    out = []
    for f in fixtures or ():
        if isinstance(f, Wall):
            out.append({"kind": "wall", "height_m": f.height, "thickness_m": f.thickness,
                        "mu": "arm" if f.mu is None else (f.mu if math.isfinite(f.mu) else None)})
        elif isinstance(f, Cavity):
            out.append({"kind": "cavity", "profile_m": [[s, y] for s, y in f.profile]})
        else:  # pragma: no cover - System refuses anything else
            out.append({"kind": type(f).__name__})
    return out


def system_text(fixtures, alpha: float) -> str:
    """``"α = 5°, wall 5 cm (μ 0)"`` for labels and reprs; empty for the paper's plain arm."""
    from ..system.fixtures import Cavity, Wall

    bits = []
    if alpha:
        bits.append(f"α = {math.degrees(alpha):.3g}°")
    for f in fixtures or ():
        if isinstance(f, Wall):
            mu = "arm μ" if f.mu is None else f"μ {f.mu:g}"
            bits.append(f"wall {100 * f.height:.3g} cm ({mu})")
        elif isinstance(f, Cavity):
            bits.append(f"cavity {100 * f.span:.3g} × {100 * f.depth:.3g} cm")
    return ", ".join(bits)


@dataclass(frozen=True, eq=False)
class ThrowMap(ConfigMap):
    """The throw map T^ω of ``part`` on ``arm`` (paper Sec. III-D), or a composed sequence.

    ``omegas`` is one release rate (rad/s) or a sequence; one :meth:`step` applies
    T^{ω_k} ∘ … ∘ T^{ω_1} (``throws_per_step = k``) and stops a configuration at
    its first failed throw (its status is that throw's). ``model`` is any of
    the registered models (:func:`throwmap.models.model_names`; default
    :data:`throwmap.models.DEFAULT_MODEL`, ``"rigid_body"``); ``throw_options`` go
    to :func:`throwmap.throw_batch` (e.g. ``fixtures``, ``settings`` for the engine).
    The domain is every stable side with valid starts, from
    :func:`throwmap.system.starts.start_interval`
    (the starts ``throw()`` accepts, ``arm.back`` included): ``x_lo`` (exclusive) to
    ``min(x_max, arm.length − u_R)`` (``x_max`` default: the arm length, else
    :data:`DEFAULT_X_MAX`). With a :class:`~throwmap.Wall` at the arm's end the
    part resting against it has x + u_R = length, so ``x_hi`` = length − u_R is
    exactly that resting configuration (a fixed point where jogs saturate).

    ``throw_options`` are checked at construction as :func:`throwmap.throw` checks them
    (:func:`throwmap.throws.throw.prepare`): ``fixtures=`` and ``alpha=`` (rad) are
    refused, naming the keyword and the models that take them, by a model whose
    :class:`~throwmap.models.Features` lacks them. The map keeps them as
    :attr:`fixtures` (a tuple) and :attr:`alpha` (rad), and :meth:`describe`
    (every result's ``map_info``) records them.
    """

    part: Part
    arm: Arm
    omegas: tuple
    model: str = DEFAULT_MODEL
    x_max: float | None = None
    throw_options: dict = field(default_factory=dict)
    deterministic: ClassVar[bool] = True  # every model is: a throw depends on its own start only

    def __post_init__(self):
        check_model(self.model)
        om = np.atleast_1d(np.asarray(self.omegas, dtype=float))
        if om.ndim != 1 or om.size == 0:
            raise InvalidStateError("omega", "must be a release rate or a non-empty sequence of them")
        object.__setattr__(self, "omegas", tuple(check_omega(float(w)) for w in om))
        opts = dict(self.throw_options)
        kw = {k: opts.pop(k) for k in ("fixtures", "alpha", "options") if k in opts}
        for k in ("progress", "on_invalid"):
            opts.pop(k, None)
        _, system, _ = prepare(self.model, self.arm, kw.get("fixtures", ()), kw.get("alpha", 0.0),
                               kw.get("options"), opts)
        if system.fixtures and self.arm.length is None:
            raise InvalidStateError("arm.length", "a wall or cavity sits at the arm's end: give the arm a length")
        object.__setattr__(self, "fixtures", system.fixtures)
        object.__setattr__(self, "alpha", system.alpha)
        iv = {s: start_interval(self.part, self.arm, s) for s in self.part.stable_sides}
        x_hi = _check_x_max(self.x_max, max(lo for lo, _ in iv.values()), self.arm.length)
        sides = tuple(s for s in self.part.stable_sides if min(x_hi, iv[s][1]) > iv[s][0])
        if not sides:
            raise InvalidStateError("arm", "no stable side has a valid start up to "
                                             f"x_max = {x_hi:.6g} m (arm length {shown(self.arm.length)} m)")
        object.__setattr__(self, "x_max", x_hi)
        object.__setattr__(self, "sides", sides)
        object.__setattr__(self, "x_lo", {s: iv[s][0] for s in sides})
        object.__setattr__(self, "x_hi", {s: min(x_hi, iv[s][1]) for s in sides})
        object.__setattr__(self, "throws_per_step", len(self.omegas))
        w = ", ".join(f"{v:g}" for v in self.omegas)
        extra = system_text(self.fixtures, self.alpha)
        object.__setattr__(self, "label", f"{self.part.name or 'part'}, ω = {w} rad/s, model {self.model}"
                                          + (f", {extra}" if extra else ""))

    def step(self, x, side):
        x = x.copy()
        side = side.copy()
        status = np.zeros(x.size, dtype=np.int64)
        for w in self.omegas:
            alive = np.flatnonzero(status == C.OK)
            if alive.size == 0:
                break
            res = throw_batch(self.part, self.arm, x[alive], side[alive], w, model=self.model,
                              on_invalid="status", **self.throw_options)
            x[alive] = res.x
            side[alive] = res.side
            status[alive] = res.status
        return x, side, status

    def with_omegas(self, omegas) -> "ThrowMap":
        return ThrowMap(self.part, self.arm, omegas, self.model, self.x_max, dict(self.throw_options))

    def describe(self) -> dict:
        return {"kind": "throw", "part": self.part.name, "h_m": self.arm.h, "g_m_s2": self.arm.g,
                "arm_length_m": self.arm.length, "mu": self.arm.mu if math.isfinite(self.arm.mu) else None, "omegas_rad_s": list(self.omegas),
                "model": self.model, "x_max_m": self.x_max, "alpha_rad": self.alpha,
                "fixtures": fixtures_doc(self.fixtures),
                "domain_m": {str(s): [self.x_lo[s], self.x_hi[s]] for s in self.sides}}

    def __repr__(self) -> str:
        w = ", ".join(f"{v:g}" for v in self.omegas)
        extra = system_text(self.fixtures, self.alpha)
        return (f"ThrowMap(part={self.part.name or 'part'!r}, h={self.arm.h:g} m, model={self.model!r}, "
                f"omega={w} rad/s, {extra + ', ' if extra else ''}sides {self.sides}, x ≤ {self.x_max:.4g} m)")


@dataclass(frozen=True, eq=False)
class FunctionMap(ConfigMap):
    """A map given as a vectorised function ``f(x, side) -> (x', side', status)``.

    ``domain`` is ``{side: (x_lo, x_hi)}`` (m); ``f`` receives float and int64 arrays
    of equal length and must return three arrays of that length (``status`` 0 where
    the image rests on the arm, a :class:`~throwmap.records.outcome.Status` code otherwise).
    ``deterministic=True`` says that ``f`` maps each state to the same image whatever
    else is in the arrays (no randomness, no coupling), so orbits may stop early once
    they repeat exactly. Used for synthetic maps with known attractors and for users' own models.
    """

    f: Callable
    domain_: dict
    name: str = "function map"
    deterministic: bool = False

    def __post_init__(self):
        if not callable(self.f):
            raise InvalidStateError("f", "must be callable")
        if not self.domain_:
            raise InvalidStateError("domain", "needs at least one side")
        lo, hi = {}, {}
        for s, iv in self.domain_.items():
            a, b = (float(v) for v in iv)
            if not (math.isfinite(a) and math.isfinite(b) and b > a):
                raise InvalidStateError("domain", f"side {s}: need finite x_lo < x_hi, got {shown(iv)}")
            lo[int(s)], hi[int(s)] = a, b
        object.__setattr__(self, "sides", tuple(sorted(lo)))
        object.__setattr__(self, "x_lo", lo)
        object.__setattr__(self, "x_hi", hi)
        object.__setattr__(self, "throws_per_step", 1)
        object.__setattr__(self, "label", self.name)

    def step(self, x, side):
        xn, sn, st = self.f(x, side)
        xn = np.asarray(xn, dtype=float).reshape(x.shape).copy()
        sn = np.asarray(sn).reshape(x.shape)
        st = np.asarray(st).reshape(x.shape)
        for name, a in (("side", sn), ("status", st)):
            if not (np.issubdtype(a.dtype, np.integer) or np.issubdtype(a.dtype, np.bool_)):
                raise InvalidStateError(name, f"f must return integer {name} codes (status: 0 at rest on the arm, else a "
                                              f"throwmap.records.outcome.Status code), got dtype {a.dtype}")
        return xn, sn.astype(np.int64), st.astype(np.int64)

    def describe(self) -> dict:
        return {"kind": "function", "name": self.name,
                "domain_m": {str(s): [self.x_lo[s], self.x_hi[s]] for s in self.sides}}

    def __repr__(self) -> str:
        dom = ", ".join(f"side {s}: ({self.x_lo[s]:.4g}, {self.x_hi[s]:.4g}] m" for s in self.sides[:4])
        return f"FunctionMap({self.name!r}, {dom}{', …' if len(self.sides) > 4 else ''})"


def as_map(part_or_map, arm: Arm | None = None, omega=None, model: str = DEFAULT_MODEL, *, x_max=None,
           **throw_options) -> ConfigMap:
    """A :class:`ConfigMap` from ``(part, arm, omega, model)`` or an existing map (returned as is)."""
    if isinstance(part_or_map, ConfigMap):
        if arm is not None or omega is not None:
            raise InvalidStateError("arm", "give either a map or (part, arm, omega), not both")
        return part_or_map
    if not isinstance(part_or_map, Part):
        raise InvalidStateError("part", f"must be a Part or a configuration map, got {type(part_or_map).__name__}")
    if not isinstance(arm, Arm):
        raise InvalidStateError("arm", f"must be an Arm, got {type(arm).__name__}")
    if omega is None:
        raise InvalidStateError("omega", "a release rate is required")
    return ThrowMap(part_or_map, arm, omega, model, x_max, dict(throw_options))


def config_grid(cmap: ConfigMap, n: int, *, field_name: str = "grid") -> tuple[np.ndarray, np.ndarray]:
    """``n`` evenly spaced x per side over ``(x_lo, x_hi]`` (the open end excluded); flat ``(x, side)``."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
        raise InvalidStateError(field_name, f"must be an integer ≥ 2 (points per side), got {shown(n)}")
    xs, ss = [], []
    for s in cmap.sides:
        xs.append(np.linspace(cmap.x_lo[s], cmap.x_hi[s], int(n) + 1)[1:])
        ss.append(np.full(int(n), s, dtype=np.int64))
    return np.concatenate(xs), np.concatenate(ss)


def plot_throw_map(part, arm, omega, *, model: str = DEFAULT_MODEL, sides=None, x_max=None, n: int = 1500, axes=None,
                   unit: str = "cm", **throw_options):
    """T(x) against x, one panel per starting side, with the diagonal (paper Fig. 2); returns the Figure.

    Samples the throw map at ``n`` x per side over ``(x_min(side), x_max]`` (m;
    ``x_max`` defaults to the arm length, or 0.5 m for an unbounded arm) with
    :func:`throwmap.throws.samples.throw_map_samples` (with ``fixtures`` and every side: over each
    side's starts up to the wall, x + u_R ≤ length, by :func:`~throwmap.throws.samples.sample_map`
    of a :class:`~throwmap.analysis.ThrowMap`) and draws it with
    :func:`throwmap.viz.throw_map.plot_map` (``compact`` look): points coloured
    by the side the part lands on, escapes marked ``x`` on the axis. ``omega`` in
    rad/s; ``unit`` ``"cm"`` or ``"m"``; ``throw_options`` go to :func:`throw_batch`.
    """
    from ..throws.samples import sample_map, throw_map_samples
    from ..viz.throw_map import plot_map

    if throw_options.get("fixtures") and sides is None:  # sampled up to the wall: x + u_R ≤ length per side
        samples = sample_map(ThrowMap(part, arm, omega, model, x_max, dict(throw_options)), n)
    else:
        samples = throw_map_samples(part, arm, omega, model=model, sides=sides, x_max=x_max, n=n, **throw_options)
    return plot_map(samples, axes=axes, unit=unit, compact=True)
