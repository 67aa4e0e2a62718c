"""The feeder search's first stage: candidate feeders screened on the exact model (cheap).

A candidate is a target side k, a nominal release rate ω (rad/s), the arm's surface height h (m) and a
pocket depth (m). Each is scored by the cavity design of :func:`throwmap.design.cavity.design_cavity`
on the exact impulse model ("rigid_body"): the window of arm-end positions L (m) where, on the pocket's
floor, side k jogs into the end wall for every ω from ω(1 − ``z_release``·σ) to ω(1 + ``z_hold``·σ)
and every other side flips there. The window's width is the candidate's score: the wider, the more
the arm's end, its ω and the part may drift before another side is held. A side with no window at any
candidate cannot be separated by an end-wall pocket in this family; the screen says so.

The screen is a proxy: the feeding experiment throws with the recoil arm in the engine, where
windows shift by millimetres; the candidates it ranks first are the ones to verify there.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, ThrowmapError, shown
from ..system.arm import Arm
from ..system.noise import Noise
from ..system.part import Part

__all__ = ["Candidate", "Screen", "screen", "DEFAULT_OMEGAS", "DEFAULT_HS", "DEFAULT_DEPTHS"]

DEFAULT_OMEGAS = tuple(float(w) for w in np.round(np.arange(3.0, 6.51, 0.25), 2))
"""Release rates screened by default, rad/s (the draft's arm throws at 3.5–6 rad/s)."""
DEFAULT_HS = (-0.03, -0.02, -0.01, 0.0)
"""Arm surface heights screened by default, m (below or through the joint)."""
DEFAULT_DEPTHS = (0.01, 0.02)
"""Pocket depths screened by default, m."""


@dataclass(frozen=True, slots=True)
class Candidate:
    """One screened feeder: ``side``, ``omega`` (rad/s), ``h`` (m), ``depth`` (m); ``window`` the widest interval
    (lo, hi) of the arm's end L (m) where only ``side`` is held at the end wall (None: none), ``width`` its width
    (m; 0 without one), ``length`` the L the design chose (m; nan without a window), ``message`` the design's
    verdict on its exact-model checks."""

    side: int
    omega: float
    h: float
    depth: float
    window: tuple | None
    width: float
    length: float
    message: str

    def to_dict(self) -> dict:
        return {"side": self.side, "omega_rad_s": self.omega, "h_m": self.h, "depth_m": self.depth,
                "window_m": list(self.window) if self.window else None, "width_m": self.width,
                "length_m": None if math.isnan(self.length) else self.length, "message": self.message}


@dataclass(frozen=True, slots=True)
class Screen:
    """Every screened :class:`Candidate` (``candidates``, widest window first), the ``part``, the arm's ``mu`` and
    ``g``, the jitter ``sigma`` designed for, and ``sides`` screened."""

    part: Part
    mu: float
    g: float
    sigma: float
    sides: tuple
    candidates: tuple = field(repr=False)

    def best(self, side: int | None = None) -> Candidate | None:
        """The widest-window candidate (of ``side``, or of any side), or None when none has a window."""
        for c in self.candidates:
            if c.window is not None and (side is None or c.side == side):
                return c
        return None

    def separable(self) -> tuple:
        """The sides some candidate holds alone at the end wall, widest window first."""
        out = []
        for c in self.candidates:
            if c.window is not None and c.side not in out:
                out.append(c.side)
        return tuple(out)

    def reason(self) -> str:
        """Why no side is separable (empty when one is): the sides screened and the ranges searched."""
        if self.separable():
            return ""
        om = sorted({c.omega for c in self.candidates})
        hs = sorted({c.h for c in self.candidates})
        return (f"no end-wall pocket holds one side alone: for sides {list(self.sides)}, ω {om[0]:g}–{om[-1]:g} "
                f"rad/s, h {hs[0]:g}–{hs[-1]:g} m and ±{100 * self.sigma:g} % jitter, every arm-end position "
                "that holds the side also holds another (or holds none)") if om else "nothing was screened"

    def table(self, n: int = 10) -> str:
        """The ``n`` best candidates, one line each (cm for lengths)."""
        rows = [f"{'side':>4}  {'ω rad/s':>8}  {'h cm':>6}  {'depth cm':>8}  {'window cm':>17}  {'width cm':>8}"]
        for c in self.candidates[:n]:
            win = f"[{100 * c.window[0]:.1f}, {100 * c.window[1]:.1f}]" if c.window else "none"
            rows.append(f"{c.side:>4}  {c.omega:>8.3f}  {100 * c.h:>6.1f}  {100 * c.depth:>8.1f}  {win:>17}  "
                        f"{100 * c.width:>8.2f}")
        return "\n".join(rows)

    def to_dict(self) -> dict:
        return {"part": self.part.name, "mu": self.mu if math.isfinite(self.mu) else None, "g_m_s2": self.g,
                "sigma": self.sigma, "sides": list(self.sides), "separable": list(self.separable()),
                "reason": self.reason(), "candidates": [c.to_dict() for c in self.candidates]}


def _grid(values, name: str, *, lo: float = -math.inf, positive: bool = False) -> tuple:
    try:
        out = tuple(float(v) for v in values)
    except (TypeError, ValueError):
        raise InvalidStateError(name, f"must be a sequence of numbers, got {shown(values)}") from None
    if not out:
        raise InvalidStateError(name, "must not be empty")
    for v in out:
        if not math.isfinite(v) or v < lo or (positive and v <= 0):
            raise InvalidStateError(name, f"must hold finite numbers{' > 0' if positive else ''}"
                                          f"{f' ≥ {lo:g}' if math.isfinite(lo) else ''}, got {v!r}")
    return out


def _fits(design) -> bool:
    """Whether the designed pocket (lip ramp and floor, m back from the end wall) is shorter than the arm."""
    return float(design.cavity.span) < float(design.arm.length)


def screen(part: Part, *, mu: float = 1.0, g: float = 9.81, sides=None, omegas=DEFAULT_OMEGAS, hs=DEFAULT_HS,
           depths=DEFAULT_DEPTHS, sigma: float = 0.03, z_hold: float = 3.0, z_release: float = 1.0,
           progress=None) -> Screen:
    """Score every candidate (side × ω × h × depth) by its exact-model end-wall window (see the module docstring).

    ``mu`` is the arm's (and the pocket floor's) friction, ``g`` m/s², ``sigma`` the relative ω jitter the
    window must cover (−``z_release``·σ … +``z_hold``·σ). ``progress(done, total)`` after each candidate.
    Returns a :class:`Screen`, candidates widest window first (ties: slower ω, then shallower h).
    """
    from ..design.cavity import Pocket, design_cavity
    from ..errors import RegimeWarning

    if not isinstance(part, Part):
        raise InvalidStateError("part", f"must be a Part, got {type(part).__name__}")
    sides = tuple(part.stable_sides) if sides is None else tuple(part.check_side(s) for s in sides)
    omegas = _grid(omegas, "omegas", positive=True)
    hs = _grid(hs, "hs")
    depths = _grid(depths, "depths", positive=True)
    sigma = _grid([sigma], "sigma", lo=0.0)[0]
    total = len(sides) * len(omegas) * len(hs) * len(depths)
    noise = Noise(omega_rel=sigma, realisation="impulse")
    out, done = [], 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RegimeWarning)
        for side in sides:
            for h in hs:
                arm = Arm(h=h, g=g, mu=mu)
                for depth in depths:
                    for w in omegas:
                        try:
                            d = design_cavity(part, arm, w, side, pocket=Pocket(depth=depth), noise=noise,
                                              z_hold=z_hold, z_release=z_release, verify=False)
                            lo, hi = d.numbers.get("L_lo_m", math.nan), d.numbers.get("L_hi_m", math.nan)
                            fits = _fits(d)
                            window = ((float(lo), float(hi)) if d.success and fits and math.isfinite(lo)
                                      and math.isfinite(hi) else None)
                            message = d.message if fits else "failed: the pocket is longer than the arm"
                            out.append(Candidate(side, w, h, depth, window, (window[1] - window[0]) if window else 0.0,
                                                 float(d.arm.length) if window else math.nan, message))
                        except ThrowmapError as err:  # e.g. the side never jogs on this floor
                            out.append(Candidate(side, w, h, depth, None, 0.0, math.nan, f"{err.field}: {err.reason}"))
                        done += 1
                        if progress is not None:
                            progress(done, total)
    out.sort(key=lambda c: (-c.width, c.omega, -c.h))
    return Screen(part, float(mu), float(g), float(sigma), sides, tuple(out))
