"""Fixtures on the arm as geometry (paper Sec. V–VI, Figs. 9(b), 11–13): a wall, a cavity.

A fixture is described in the *arm frame* (x along the arm from the joint, y up,
the arm surface at y = h, see :mod:`throwmap.conventions`); it turns with the arm.
Engines build solid convex pieces from it (:meth:`solids`); animations draw its
:meth:`outline`. The arm's rest angle α is not a fixture but part of the engine
scene (:class:`throwmap.engine.Scene`), since it may change between throws.

* :class:`Wall` — a vertical wall at the arm's end (Sec. VI: assembly against a wall).
* :class:`Cavity` — a polygonal depression of the surface ending at the arm's end
  (Sec. V-B, Fig. 9(b): captures the part in one configuration).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown

__all__ = ["Wall", "Cavity", "arm_solids", "surface_profile", "fixture_to_dict", "fixture_from_dict"]


def _num(value, field: str, *, positive=False, nonneg=False) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real) or not math.isfinite(value):
        raise InvalidStateError(field, f"must be a finite number, got {shown(value)}")
    if positive and value <= 0:
        raise InvalidStateError(field, f"must be > 0, got {shown(value)}")
    if nonneg and value < 0:
        raise InvalidStateError(field, f"must be ≥ 0, got {shown(value)}")
    return float(value)


@dataclass(frozen=True, slots=True)
class Wall:
    """A vertical wall standing at the arm's end, x ∈ [length, length + thickness].

    ``height`` (m) is measured above the arm surface y = h; ``mu`` is the
    wall–part Coulomb friction (``None``: the arm's μ; the paper's leaning
    analysis, Fig. 13, assumes 0).
    """

    height: float = 0.05
    thickness: float = 0.01
    mu: float | None = None

    def __post_init__(self):
        object.__setattr__(self, "height", _num(self.height, "wall.height", positive=True))
        object.__setattr__(self, "thickness", _num(self.thickness, "wall.thickness", positive=True))
        if self.mu is not None:
            mu = self.mu
            if isinstance(mu, (bool, np.bool_)) or not isinstance(mu, numbers.Real) or math.isnan(mu) or mu < 0:
                raise InvalidStateError("wall.mu", f"must be a number ≥ 0, got {shown(mu)}")
            object.__setattr__(self, "mu", float(mu))

    def solids(self, h: float, length: float, depth: float) -> list[np.ndarray]:
        """Convex pieces (arm frame, counter-clockwise) reaching ``depth`` below the surface."""
        x0, x1 = length, length + self.thickness
        y0, y1 = h - depth, h + self.height
        return [np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])]

    def outline(self, h: float, length: float) -> np.ndarray:
        x0, x1 = length, length + self.thickness
        return np.array([[x0, h], [x1, h], [x1, h + self.height], [x0, h + self.height]])


@dataclass(frozen=True, slots=True)
class Cavity:
    """A polygonal depression of the arm surface that ends at the arm's end.

    ``profile`` lists points ``(s, y)``: s ≥ 0 is the distance *back from the
    arm's end* (m) and y ≤ 0 the surface height relative to the plain surface
    (m). Points go from the cavity's lip (largest s, y = 0) to the arm's end
    (s = 0), with s non-increasing; equal s gives a vertical step. Example: a
    rectangular pocket 6 cm long and 2 cm deep is
    ``Cavity(((0.06, 0), (0.06, -0.02), (0, -0.02)))``.

    ``lined``: the floor (the segments at the full depth) is faced with the end wall's material, so
    part contacts there have the wall's μ (:attr:`Wall.mu`) instead of the arm's (e.g. a PTFE insert:
    a part leaning on the end wall then slides flat; docs/how-to/feeding.md, the recoil feeder).
    """

    profile: tuple
    lined: bool = False

    def __post_init__(self):
        try:
            pts = tuple((float(s), float(y)) for s, y in self.profile)
        except (TypeError, ValueError):
            raise InvalidStateError("cavity.profile", "must be a sequence of (s, y) pairs in metres") from None
        if len(pts) < 2:
            raise InvalidStateError("cavity.profile", f"needs at least 2 points, got {len(pts)}")
        for i, (s, y) in enumerate(pts):
            if not (math.isfinite(s) and math.isfinite(y)):
                raise InvalidStateError(f"cavity.profile[{i}]", f"must be finite, got {(s, y)}")
            if s < 0:
                raise InvalidStateError(f"cavity.profile[{i}]", f"s (distance back from the arm's end) must be ≥ 0, got {s}")
            if y > 0:
                raise InvalidStateError(f"cavity.profile[{i}]", f"y must be ≤ 0 (a depression), got {y}")
            if i and s > pts[i - 1][0]:
                raise InvalidStateError(f"cavity.profile[{i}]", "s must not increase from the lip to the arm's end")
        if pts[0][1] != 0.0:
            raise InvalidStateError("cavity.profile[0]", f"the lip must be at y = 0, got {pts[0][1]}")
        if pts[-1][0] != 0.0:
            raise InvalidStateError(f"cavity.profile[{len(pts) - 1}]", f"must end at the arm's end (s = 0), got s = {pts[-1][0]}")
        if pts[0][0] <= 0.0:
            raise InvalidStateError("cavity.profile[0]", "the cavity must have a positive length")
        object.__setattr__(self, "profile", pts)
        if not isinstance(self.lined, (bool, np.bool_)):
            raise InvalidStateError("cavity.lined", f"must be true or false, got {shown(self.lined)}")
        object.__setattr__(self, "lined", bool(self.lined))

    @property
    def depth(self) -> float:
        return -min(y for _, y in self.profile)

    @property
    def span(self) -> float:
        """Length of the cavity along the arm, m."""
        return self.profile[0][0]

    def points(self, h: float, length: float) -> np.ndarray:
        """The cavity's surface polyline in the arm frame, from the lip to the arm's end."""
        return np.array([[length - s, h + y] for s, y in self.profile])


def surface_profile(h: float, length: float, fixtures=()) -> np.ndarray:
    """The arm's top surface as a polyline (arm frame) from the joint to the arm's end."""
    cav = [f for f in fixtures if isinstance(f, Cavity)]
    if len(cav) > 1:
        raise InvalidStateError("fixtures", "at most one cavity")
    if cav:
        c = cav[0]
        if c.span >= length:
            raise InvalidStateError("cavity.profile", f"the cavity ({c.span:g} m) must be shorter than the arm ({length:g} m)")
        return np.vstack(([[0.0, h]], c.points(h, length)))
    return np.array([[0.0, h], [length, h]])


def arm_solids(h: float, length: float, thickness: float, fixtures=()) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """Convex solid pieces of the arm and of its fixtures, arm frame, counter-clockwise.

    Returns ``(arm_pieces, fixture_pieces)``. The arm is the region between the
    surface profile and ``h - thickness`` (thickness is enlarged to clear a cavity's
    floor by at least ``thickness / 2``), cut into one quadrilateral per profile
    segment so each piece is convex.
    """
    walls = [f for f in fixtures if isinstance(f, Wall)]
    unknown = [f for f in fixtures if not isinstance(f, (Wall, Cavity))]
    if unknown:
        raise InvalidStateError("fixtures", f"unknown fixture {unknown[0]!r} (use Wall or Cavity)")
    if len(walls) > 1:
        raise InvalidStateError("fixtures", "at most one wall")
    prof = surface_profile(h, length, fixtures)
    depth = max(thickness, float(h - prof[:, 1].min()) + 0.5 * thickness)
    bottom = h - depth
    pieces = []
    for (xa, ya), (xb, yb) in zip(prof[:-1], prof[1:]):
        if xb - xa <= 1e-12:
            continue
        pieces.append(np.array([[xa, bottom], [xb, bottom], [xb, yb], [xa, ya]]))
    fixture_pieces = []
    for w in walls:
        fixture_pieces += w.solids(h, length, depth)
    return pieces, fixture_pieces


def fixture_to_dict(f) -> dict:
    """A fixture as a JSON-ready dict: ``{"kind": "wall", "height": …, "thickness": …, "mu": …}`` or
    ``{"kind": "cavity", "profile": [[s, y], …]}`` (m; ``mu`` None: the arm's; a lined cavity adds ``"lined": true``)."""
    if isinstance(f, Wall):
        return {"kind": "wall", "height": f.height, "thickness": f.thickness, "mu": f.mu}
    if isinstance(f, Cavity):
        return {"kind": "cavity", "profile": [list(p) for p in f.profile], **({"lined": True} if f.lined else {})}
    raise InvalidStateError("fixtures", f"unknown fixture {f!r} (use Wall or Cavity)")


def fixture_from_dict(d: dict):
    """Inverse of :func:`fixture_to_dict`."""
    kind = d.get("kind") if isinstance(d, dict) else None
    if kind == "wall":
        return Wall(d["height"], d["thickness"], d.get("mu"))
    if kind == "cavity":
        return Cavity(tuple(tuple(p) for p in d["profile"]), bool(d.get("lined", False)))
    raise InvalidStateError("fixtures", f"unknown fixture record {d!r} (kind must be 'wall' or 'cavity')")
