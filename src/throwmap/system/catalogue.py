"""Canonical parts, in one place (used by the demo, the CLI and the tests)."""

from __future__ import annotations

import dataclasses
import math

from ..errors import InvalidPartError
from .part import Part

__all__ = ["BUILTIN_PARTS", "builtin_part", "lead_name", "rectangle", "regular_polygon", "triangle_30_60_90"]


def lead_name(name: str, point_masses) -> str:
    """``name`` with its lead weights appended, so a weighted part is never labelled as the plain one.

    ``point_masses`` is a part's validated ``((m, (x, y)), …)`` (kg, m, body frame);
    e.g. ``"triangle_30_60_90(hypotenuse=0.17)+lead(30 g at (10, 1) cm)"``. No weights:
    ``name`` unchanged.
    """
    if not point_masses:
        return name
    items = "; ".join(f"{1000 * m:.4g} g at ({100 * x:.4g}, {100 * y:.4g}) cm" for m, (x, y) in point_masses)
    return f"{name}+lead({items})"


def triangle_30_60_90(hypotenuse: float = 0.17, mass: float = 0.05, mirror: bool = False, point_masses=()) -> Part:
    """The paper's 30-60-90 triangle (Sec. IV-A, V-C, VI), uniform plate.

    Right angle at the body origin, long leg along +x, short leg along +y
    (``mirror=True`` reflects it in the y axis: the paper's part *b* of Sec. VI).
    Vertices are listed so that side 0 is the hypotenuse, side 1 the long leg
    and side 2 the short leg (clockwise, see conventions). The paper's 17 cm
    part has its CM 2.83 cm from the long leg and 4.91 cm from the short leg.
    ``point_masses`` ``[(m, (x, y)), …]`` (kg, m, body frame) are lead weights; the
    name then says so (:func:`lead_name`), e.g. ``triangle_30_60_90(hypotenuse=0.17)+lead(30 g at (10, 1) cm)``.
    """
    if not (math.isfinite(hypotenuse) and hypotenuse > 0):
        raise InvalidPartError("hypotenuse", f"must be a positive finite length, got {hypotenuse}")
    a = 0.5 * hypotenuse  # short leg, opposite 30°
    b = 0.5 * math.sqrt(3.0) * hypotenuse  # long leg, opposite 60°
    sx = -1.0 if mirror else 1.0
    A = (sx * b, 0.0)  # 30° vertex
    B = (0.0, a)  # 60° vertex
    C = (0.0, 0.0)  # right angle
    verts = [A, B, C] if not mirror else [B, A, C]
    name = f"triangle_30_60_90(hypotenuse={hypotenuse:g}{', mirror' if mirror else ''})"
    part = Part.from_vertices(verts, mass=mass, point_masses=point_masses, name=name)
    if part.point_masses:  # validated by from_vertices: name the weights
        part = dataclasses.replace(part, name=lead_name(name, part.point_masses))
    return part


def regular_polygon(n: int, circumradius: float = 0.05, mass: float = 0.05, rotation: float = 0.0) -> Part:
    """A uniform regular n-gon (n ≥ 3) of given circumradius, m."""
    if isinstance(n, bool) or not isinstance(n, int) or n < 3:
        raise InvalidPartError("n", f"a regular polygon needs an integer n ≥ 3, got {n!r}")
    if not (math.isfinite(circumradius) and circumradius > 0):
        raise InvalidPartError("circumradius", f"must be a positive finite length, got {circumradius}")
    verts = [
        (circumradius * math.cos(rotation - 2 * math.pi * k / n), circumradius * math.sin(rotation - 2 * math.pi * k / n))
        for k in range(n)
    ]
    return Part.from_vertices(verts, mass=mass, name=f"regular_polygon(n={n}, circumradius={circumradius:g})")


def rectangle(width: float = 0.08, height: float = 0.04, mass: float = 0.05) -> Part:
    """A uniform rectangle, m. Side 0 is the bottom edge (width), then clockwise."""
    for nm, v in (("width", width), ("height", height)):
        if not (math.isfinite(v) and v > 0):
            raise InvalidPartError(nm, f"must be a positive finite length, got {v}")
    verts = [(width, 0.0), (0.0, 0.0), (0.0, height), (width, height)]
    return Part.from_vertices(verts, mass=mass, name=f"rectangle({width:g}×{height:g})")


BUILTIN_PARTS = {
    "triangle": lambda: triangle_30_60_90(0.17),
    "triangle-mirror": lambda: triangle_30_60_90(0.17, mirror=True),
    "square": lambda: rectangle(0.05, 0.05),
    "rectangle": lambda: rectangle(0.08, 0.04),
    "pentagon": lambda: regular_polygon(5, 0.04),
    "hexagon": lambda: regular_polygon(6, 0.04),
}
"""Built-in parts by name (CLI ``--part NAME``)."""


def builtin_part(name: str) -> Part:
    """A built-in part by name (see :data:`BUILTIN_PARTS`)."""
    try:
        return BUILTIN_PARTS[name]()
    except KeyError:
        raise InvalidPartError("part", f"unknown built-in part {name!r} (choose from {', '.join(BUILTIN_PARTS)})") from None
