"""The feeders the search considers: a lead weight (or none) on the part, and the throw.

A feeder in this family is the user's part, optionally with one lead weight glued to it, thrown
from a plain arm (surface height h, m) at a nominal release rate ω (rad/s) by the recoiling arm
with ω jitter, collected by a shallow lined pocket with an end wall at the arm's end (see
:mod:`throwmap.feeder.arrival`). The weight is what makes a part feedable when it is not: it moves
the centre of mass toward the target side, so that the throws that flip the part tend to end on
that side, and it changes which sides travel outward on the arm.

:func:`weight_variants` proposes the weights for a target side: masses ``ratios`` × the part's own
mass (capped at ``max_kg``), placed on the plate at fractions ``places`` along the side's edge,
``margin`` inside the plate (moved toward the plate's centre where a corner leaves no room), the masses to
:data:`MASS_STEP_KG` and the places to :data:`PLACE_STEP_M` (a weight a workshop can make). The masses and
places are stated, not tuned: the search ranks the variants by how they throw.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError
from ..system.part import Part

__all__ = ["Weight", "Variant", "side_endpoints", "with_weight", "without_last_weight", "weight_variants", "RATIOS", "PLACES", "MARGIN_M"]

RATIOS = (1.0, 1.7)
"""Weight masses proposed, as multiples of the part's own mass."""
PLACES = (0.2, 0.5, 0.8)
"""Places proposed along the target side's inset edge (0: its first vertex, 1: its second)."""
MASS_STEP_KG = 1e-4
"""Weight masses are proposed in steps of this, kg (0.1 g), rounded down (the cap is never passed)."""
PLACE_STEP_M = 1e-4
"""Weight places are proposed on a grid of this, m (0.1 mm)."""
MARGIN_M = 0.008
"""How far inside the plate's edges a weight's centre stays, m (a 1 cm lead disc glued flat)."""


@dataclass(frozen=True, slots=True)
class Weight:
    """A lead weight of ``mass`` kg with its centre at ``at`` (m, the part's frame)."""

    mass: float
    at: tuple

    def to_dict(self) -> dict:
        return {"mass_kg": self.mass, "at_m": list(self.at)}


@dataclass(frozen=True, slots=True, eq=False)
class Variant:
    """The part the feeder throws: ``part`` (the user's part plus ``weight``, or the part alone when ``weight`` is
    None), and the ``side`` the weight was placed for (None without a weight)."""

    part: Part
    weight: Weight | None
    side: int | None

    def label(self) -> str:
        if self.weight is None:
            return "no weight"
        w = self.weight
        return f"{1000 * w.mass:.1f} g at ({100 * w.at[0]:.2f}, {100 * w.at[1]:.2f}) cm"  # as the sheet gives it

    def to_dict(self) -> dict:
        return {"weight": None if self.weight is None else self.weight.to_dict(), "placed_for_side": self.side,
                "mass_kg": self.part.mass, "com_m": list(self.part.com),
                "radius_of_gyration_m": self.part.radius_of_gyration}


def side_endpoints(part: Part, side: int) -> tuple:
    """The end points (m, the part's frame) of side ``side`` in the part's own numbering (:mod:`throwmap.conventions`:
    side 0 is the edge from vertex 0 to vertex 1, then clockwise)."""
    c = np.asarray(part.com, dtype=float)
    w = np.asarray(part.w, dtype=float)
    return c + w[side], c + w[(side + 1) % len(w)]


def with_weight(part: Part, weight: Weight) -> Part:
    """``part`` with ``weight`` added: total mass, CM and radius of gyration (parallel-axis theorem) recomputed."""
    M, m = float(part.mass), float(weight.mass)
    c, p = np.asarray(part.com, dtype=float), np.asarray(weight.at, dtype=float)
    com = (M * c + m * p) / (M + m)
    inertia = M * part.radius_of_gyration**2 + M * float(np.sum((c - com) ** 2)) + m * float(np.sum((p - com) ** 2))
    return dataclasses.replace(part, mass=M + m, com=(float(com[0]), float(com[1])),
                               radius_of_gyration=math.sqrt(inertia / (M + m)),
                               point_masses=tuple(part.point_masses) + ((m, (float(p[0]), float(p[1]))),),
                               name=f"{part.name} + lead {1000 * m:.4g} g")


def without_last_weight(part: Part) -> Part:
    """``part`` without its last point mass (mass, CM and radius of gyration recomputed): the inverse of
    :func:`with_weight`."""
    m, at = part.point_masses[-1]
    M = float(part.mass) - m
    c = (float(part.mass) * np.asarray(part.com) - m * np.asarray(at)) / M
    C = np.asarray(part.com, dtype=float)
    inertia = (float(part.mass) * part.radius_of_gyration**2 - m * float(np.sum((np.asarray(at) - C) ** 2))
               - M * float(np.sum((c - C) ** 2)))  # parallel-axis theorem, backwards
    return dataclasses.replace(part, mass=M, com=(float(c[0]), float(c[1])), radius_of_gyration=math.sqrt(inertia / M),
                               point_masses=part.point_masses[:-1])


def weight_variants(part: Part, side: int, *, max_kg: float, ratios=RATIOS, places=PLACES,
                    margin: float = MARGIN_M) -> list[Variant]:
    """The weighted parts proposed for target ``side`` (see the module docstring); variants whose target side is no
    longer stable are left out. ``max_kg`` caps every mass (0: none proposed)."""
    from ..design.plate import inset_polygon
    from ..errors import ThrowmapError

    if not (isinstance(max_kg, (int, float)) and math.isfinite(max_kg) and max_kg >= 0):
        raise InvalidStateError("max_kg", f"must be a finite mass ≥ 0 kg, got {max_kg!r}")
    if max_kg == 0:
        return []
    try:
        inset = inset_polygon(part.vertices, margin)
    except ThrowmapError:  # a part too small for a weight
        return []
    a, b = side_endpoints(part, side)
    centre = np.asarray(part.vertices, dtype=float).mean(axis=0)
    normal = np.array([a[1] - b[1], b[0] - a[0]]) / float(np.hypot(*(b - a)))
    if float(np.dot(centre - a, normal)) < 0:  # point it into the part, whatever the vertex order
        normal = -normal
    own = float(part.mass)
    # as a workshop cuts and places them: masses to 0.1 g (never above the cap), places to 0.1 mm
    masses = sorted({math.floor(min(float(r) * own, float(max_kg)) / MASS_STEP_KG + 1e-9) * MASS_STEP_KG
                     for r in ratios} - {0.0})
    out = []
    for m in masses:
        for t in places:
            p = a + float(t) * (b - a) + 1.0001 * margin * normal
            for s in np.linspace(0.0, 1.0, 101):  # near a corner: toward the centre until inside the inset
                q = np.round((p + s * (centre - p)) / PLACE_STEP_M) * PLACE_STEP_M
                if inset.contains((float(q[0]), float(q[1]))):
                    p = q
                    break
            else:
                continue
            w = Weight(round(m, 7), (round(float(p[0]), 7), round(float(p[1]), 7)))  # no float noise in the files
            try:
                v = Variant(with_weight(part, w), w, side)
            except ThrowmapError:
                continue
            if side in v.part.stable_sides:
                out.append(v)
    return out
