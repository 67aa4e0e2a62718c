"""Conventions used everywhere in throwmap: units, frames, numbering, signs.

Units
-----
SI throughout code, files and output: metres, kilograms, seconds, radians.
The paper speaks in centimetres; convert at the edge (:func:`cm`), never inside.
Gravity ``g`` defaults to :data:`G` = 9.81 m/s² and is a parameter of :class:`~throwmap.Arm`.

World frame (paper Sec. III-A, Fig. 6)
--------------------------------------
The joint axis is the origin; x points along the arm (outward), y points up and
gravity acts along −y. The arm surface is the line y = h when the arm is
horizontal (h < 0 puts the surface below the joint axis). The arm occupies
0 ≤ x ≤ length (``length=None``: unbounded). Angles are counter-clockwise
positive; a throw has angular velocity ω = θ̇_r ≥ 0 (the arm's tip goes up).

Parts, vertices and sides
-------------------------
A part is a convex polygon given by its vertices in either orientation, in any
frame (the body frame). Internally the vertices are re-ordered clockwise,
``w_0 … w_{n-1}``, and centred on the centre of mass (CM).

*Side numbering.* Side 0 is the edge joining the first two listed vertices; the
sides are numbered clockwise around the part. With the clockwise list ``w``,
side k is the edge from ``w_k`` to ``w_{k+1}``; when the part rests on side k,
``w_k`` is its right support vertex and ``w_{k+1}`` its left one. A flip — the
part rolling counter-clockwise over its left support vertex — therefore takes
side k to side k+1 (the paper's ``i → i+1 mod n``). Every edge is numbered,
stable or not.

*Per-side quantities* (paper Sec. III-A): resting on side k, ``d_k > 0`` is the
CM height above the surface and ``(u_L, v_L)``, ``(u_R, v_R)`` are the vectors
from the CM to the left and right support vertices (``v_L = v_R = -d_k``).
Side k is *stable* when ``u_L < 0 < u_R`` (strictly).

Configurations
--------------
A resting configuration is ``(x, side)``: x is the CM x-coordinate, in metres
from the joint, when resting on the horizontal arm.

Energies
--------
Potential energy is measured from the arm line: ``U = m g (y_cm - h)``.
"""

from __future__ import annotations

G: float = 9.81
"""Default gravitational acceleration, m/s²."""

CM_PER_M: float = 100.0


def cm(value: float) -> float:
    """Convert a length given in centimetres (as the paper does) to metres."""
    return value / CM_PER_M


def to_cm(value: float) -> float:
    """Convert metres to centimetres (for comparison with the paper's numbers)."""
    return value * CM_PER_M
