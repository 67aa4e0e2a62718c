"""A feeder for the recoil arm: random search screened by first passage (Sec. V-C, corrected).

The critical-point design (:func:`throwmap.design.design`, the exact impulse map) does not carry over
to the draft's recoiling arm with 3 % ω jitter: there the end stop of the impulse feeder design is
reached first by a wrong side in ≈ 23 % of drops and parts drift behind the joint. This search
draws candidate feeders — a lead weight of mass in ``masses`` (kg) anywhere on the plate at least
``margin`` (m) inside its edges, ω uniform in ``omega_range`` (rad/s), h uniform in ``h_range`` (m)
— tabulates each one's recoil throw map (:func:`~throwmap.design.passage.recoil_table`) and keeps
those with a window of end-stop positions X where at least ``purity`` of the Markov chains first
pass X on one side, none on another, and that side holds there
(:func:`~throwmap.design.passage.first_passage`). Each candidate costs one table (≈ 2,300 engine
throws, ≈ 10 s on 2 cores); a hit is then checked by ``throwmap experiment feed`` (the verdict).

Sampling, per candidate, from ``numpy.random.default_rng(seed)``: the weight's (x, y) uniform on
the plate's bounding box until inside the inset plate, then the mass (``rng.choice(masses)``), ω,
h, in that order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError
from ..system.arm import Arm
from ..system.part import Part
from .passage import Passage, first_passage, recoil_table
from .plate import inset_polygon

__all__ = ["FeedCandidate", "FeederSpace", "search_feeders"]


@dataclass(frozen=True, slots=True, eq=False)
class FeedCandidate:
    """One candidate: the weight (``weight_mass`` kg at ``weight_at`` m, plate frame), ``omega`` (rad/s),
    ``h`` (m), the ``part`` (plate + weight), per target side its :class:`Passage` (``passages``) and its
    window (``windows``: side → (lo, hi) m or None); ``best`` the side with the widest window (or None)."""

    index: int
    weight_mass: float
    weight_at: tuple
    omega: float
    h: float
    part: Part
    passages: dict
    windows: dict

    @property
    def best(self):
        ok = {k: w for k, w in self.windows.items() if w is not None}
        return max(ok, key=lambda k: ok[k][1] - ok[k][0]) if ok else None

    def to_dict(self) -> dict:
        return {"index": self.index, "weight_mass_kg": self.weight_mass, "weight_at_m": list(self.weight_at),
                "omega_rad_s": self.omega, "h_m": self.h, "com_m": list(self.part.com),
                "windows_m": {str(k): (list(w) if w else None) for k, w in self.windows.items()},
                "best_side": self.best}


@dataclass(frozen=True, slots=True)
class FeederSpace:
    """Where the candidates are drawn: a lead weight of one of ``masses`` (kg) anywhere on the plate at least
    ``margin`` (m) inside its edges, ω uniform over ``omega_range`` (rad/s), h uniform over ``h_range`` (m), on an arm
    of friction ``mu``."""

    masses: tuple = (0.03, 0.05, 0.08)
    omega_range: tuple = (3.5, 6.5)
    h_range: tuple = (-0.05, 0.0)
    margin: float = 0.008
    mu: float = 1.0

    def __post_init__(self):
        for name in ("omega_range", "h_range"):
            lo, hi = getattr(self, name)
            if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
                raise InvalidStateError(name, f"must be (low, high) with low ≤ high, got {(lo, hi)!r}")


def search_feeders(plate: Part, *, n: int = 10, seed: int = 0, space: FeederSpace = FeederSpace(),
                   sigma: float = 0.03, purity: float = 0.99, chains: int = 1500, throws: int = 60,
                   step: float = 0.005, workers: int | None = None, progress=None):
    """Yield ``n`` :class:`FeedCandidate` drawn over ``space`` (:class:`FeederSpace`; see the module docstring;
    ``step`` the table's grid, m); ``progress(i, n)`` after each."""
    if isinstance(n, bool) or not (isinstance(n, int) and 1 <= n <= 10_000):
        raise InvalidStateError("n", f"must be an integer in [1, 10000], got {n!r}")
    if isinstance(seed, bool) or not (isinstance(seed, int) and seed >= 0):
        raise InvalidStateError("seed", f"must be an integer ≥ 0, got {seed!r}")
    masses, omega_range, h_range, margin, mu = space.masses, space.omega_range, space.h_range, space.margin, space.mu
    inset = inset_polygon(plate.vertices, margin)
    V = np.asarray(plate.vertices, dtype=float)
    (x0, y0), (x1, y1) = V.min(axis=0), V.max(axis=0)
    rng = np.random.default_rng(seed)
    for i in range(n):
        while True:
            p = (float(rng.uniform(x0, x1)), float(rng.uniform(y0, y1)))
            if inset.contains(p):
                break
        m = float(rng.choice(np.asarray(masses, dtype=float)))
        w = float(rng.uniform(*omega_range))
        h = float(rng.uniform(*h_range))
        part = Part.from_vertices(plate.vertices, mass=plate.mass, point_masses=((m, p),),
                                  name=f"{plate.name}+lead({1000 * m:.4g} g at ({100 * p[0]:.4g}, {100 * p[1]:.4g}) cm)")
        arm = Arm(h=h, mu=mu)
        table = recoil_table(part, arm, w, sigma=sigma, step=step, workers=workers)
        passages: dict[int, Passage] = {}
        windows = {}
        for k in part.stable_sides:
            pas = first_passage(part, table, k, n=chains, throws=throws, seed=0)
            passages[k] = pas
            win = pas.window(purity)
            windows[k] = (min(win), max(win)) if win else None
        if progress is not None:
            progress(i + 1, n)
        yield FeedCandidate(i, m, p, w, h, part, passages, windows)
