"""Random convex plates: parts nobody tuned a feeder for, drawn reproducibly.

:func:`random_plate` draws a uniform plate with a given number of vertices: the vertices lie on an
ellipse of random aspect ratio and orientation at sorted random angles (no two closer than a
third of an even share of the turn, so no side is a sliver), the polygon is scaled so its
diameter (the largest vertex-to-vertex distance) is the drawn size and moved so its lowest-left
vertex is at the origin. Points on an ellipse are always in convex position, so the plate is
convex by construction. SI units: m, kg.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidStateError
from ..system.part import Part

__all__ = ["random_plate", "PLATE_VERTICES", "PLATE_SIZE_M", "PLATE_MASS_KG"]

PLATE_VERTICES = (4, 6)
"""Vertex counts drawn by default (inclusive)."""
PLATE_SIZE_M = (0.06, 0.15)
"""Diameters drawn by default, m."""
PLATE_MASS_KG = (0.02, 0.08)
"""Masses drawn by default, kg."""


def random_plate(rng: np.random.Generator, *, vertices=PLATE_VERTICES, size=PLATE_SIZE_M, mass=PLATE_MASS_KG,
                 name: str | None = None) -> Part:
    """A uniform convex plate drawn from ``rng`` (see the module docstring): vertex count uniform over
    ``vertices`` (inclusive), diameter uniform over ``size`` (m), mass uniform over ``mass`` (kg)."""
    lo_n, hi_n = (int(v) for v in vertices)
    if not 3 <= lo_n <= hi_n <= 12:
        raise InvalidStateError("vertices", f"must be (low, high) with 3 ≤ low ≤ high ≤ 12, got {vertices!r}")
    for field, (lo, hi) in (("size", size), ("mass", mass)):
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo <= hi):
            raise InvalidStateError(field, f"must be (low, high) with 0 < low ≤ high, got {(lo, hi)!r}")
    n = int(rng.integers(lo_n, hi_n + 1))
    gap = 2 * math.pi / n / 3  # the least angle between neighbours on the ellipse
    while True:
        t = np.sort(rng.uniform(0.0, 2 * math.pi, n))
        if np.all(np.diff(np.r_[t, t[0] + 2 * math.pi]) >= gap):
            break
    aspect = float(rng.uniform(0.45, 1.0))
    turn = float(rng.uniform(0.0, math.pi))
    p = np.c_[np.cos(t), aspect * np.sin(t)]
    c, s = math.cos(turn), math.sin(turn)
    p = p @ np.array([[c, s], [-s, c]])
    diameter = max(float(np.linalg.norm(a - b)) for a in p for b in p)
    p *= float(rng.uniform(*size)) / diameter
    p -= p.min(axis=0)
    m = float(rng.uniform(*mass))
    label = name or f"random plate ({n} vertices, {100 * float(np.ptp(p[:, 0])):.1f} × {100 * float(np.ptp(p[:, 1])):.1f} cm, {1000 * m:.1f} g)"
    return Part.from_vertices(np.round(p, 6), mass=m, name=label)
