"""Where a lead weight may go on a plate, and which CMs a weight can produce (paper Sec. V, reviewer's remark).

A lead weight of mass m_w at w on a plate of mass m_p with centroid c_p moves the part's CM to
``c = (m_p c_p + m_w w) / (m_p + m_w)``: c lies on the segment from c_p to w. So a CM is
realisable with one weight on the plate only inside the plate, and the lightest weight that
puts it at c sits where the ray from c_p through c leaves the allowed region:
``m_w / m_p = |c − c_p| / |w − c|`` (:func:`lightest_weight_for_com`). The allowed region is the
plate shrunk by ``margin`` (m): a disc of lead of radius ``margin`` centred at w stays on the plate.

Lengths in m, masses in kg, points in the frame of the plate's vertices.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidPartError
from ..system.geometry import polygon_mass_properties, signed_area

__all__ = ["InsetPolygon", "inset_polygon", "lightest_weight_for_com", "WeightForCom"]


@dataclass(frozen=True, slots=True)
class InsetPolygon:
    """The convex plate shrunk by ``margin`` (m): where a weight's centre may go.

    ``vertices`` counter-clockwise (m); ``normals`` outward unit normals and ``offsets`` so that
    a point p is allowed iff ``normals @ p <= offsets`` (each row one edge).
    """

    vertices: tuple
    normals: tuple
    offsets: tuple
    margin: float

    def contains(self, p, tol: float = 1e-12) -> bool:
        n, b = np.asarray(self.normals), np.asarray(self.offsets)
        return bool(np.all(n @ np.asarray(p, dtype=float) <= b + tol))

    def distance_inside(self, p) -> float:
        """Smallest distance from p to an edge of the inset polygon (m; negative outside)."""
        n, b = np.asarray(self.normals), np.asarray(self.offsets)
        return float(np.min(b - n @ np.asarray(p, dtype=float)))

    def project(self, p, free=(True, True)) -> tuple:
        """The allowed point nearest to ``p`` moving only the ``free`` coordinates.

        Both free: Euclidean projection onto the polygon. One free: p clipped along that
        axis to the polygon's chord through p (the fixed coordinate must cross the polygon,
        else :class:`~throwmap.errors.InvalidPartError`). None free: p unchanged.
        """
        p = np.asarray(p, dtype=float)
        if not np.all(np.isfinite(p)):
            raise InvalidPartError("weight_at", f"must be finite, got {tuple(p.tolist())}")
        if self.contains(p):
            return (float(p[0]), float(p[1]))
        if free[0] and free[1]:
            V = np.asarray(self.vertices)
            best, dbest = None, math.inf
            for k in range(len(V)):
                a, b = V[k], V[(k + 1) % len(V)]
                e = b - a
                t = min(1.0, max(0.0, float(np.dot(p - a, e) / np.dot(e, e))))
                q = a + t * e
                d = float(np.hypot(*(p - q)))
                if d < dbest:
                    best, dbest = q, d
            return (float(best[0]), float(best[1]))
        if not (free[0] or free[1]):
            return (float(p[0]), float(p[1]))
        j = 0 if free[0] else 1
        lo, hi = self.chord(p, j)
        q = p.copy()
        q[j] = min(hi, max(lo, p[j]))
        return (float(q[0]), float(q[1]))

    def chord(self, p, axis: int) -> tuple:
        """``(lo, hi)`` of coordinate ``axis`` over the polygon with the other coordinate fixed at p's."""
        n, b = np.asarray(self.normals), np.asarray(self.offsets)
        o = 1 - axis
        lo, hi = -math.inf, math.inf
        for nk, bk in zip(n, b):
            rest = bk - nk[o] * p[o]
            if abs(nk[axis]) < 1e-15:
                if rest < 0:
                    lo, hi = math.inf, -math.inf
                continue
            v = rest / nk[axis]
            if nk[axis] > 0:
                hi = min(hi, v)
            else:
                lo = max(lo, v)
        if not lo <= hi:
            raise InvalidPartError("weight_at", f"{'yx'[axis]} = {p[o]:.6g} m leaves no room for the weight inside "
                                                f"the plate (margin {self.margin:g} m)")
        return float(lo), float(hi)


def inset_polygon(vertices, margin: float) -> InsetPolygon:
    """The convex polygon ``vertices`` shrunk by ``margin`` ≥ 0 (m); refused when nothing is left."""
    if not (isinstance(margin, (int, float)) and math.isfinite(margin) and margin >= 0):
        raise InvalidPartError("margin", f"must be a finite length ≥ 0, got {margin!r}")
    V = np.asarray(vertices, dtype=float)
    if signed_area(V) < 0:
        V = V[::-1]
    E = np.roll(V, -1, axis=0) - V
    L = np.hypot(E[:, 0], E[:, 1])
    normals = np.stack([E[:, 1] / L, -E[:, 0] / L], axis=1)  # outward for a counter-clockwise polygon
    offsets = np.einsum("ij,ij->i", normals, V) - margin
    n = len(V)
    out = []
    for k in range(n):  # vertex k of the inset: edges k-1 and k meet
        A = np.array([normals[k - 1], normals[k]])
        out.append(np.linalg.solve(A, [offsets[k - 1], offsets[k]]))
    W = np.array(out)
    ok = signed_area(W) > 0 and all(np.all(normals @ w <= offsets + 1e-12) for w in W)
    if not ok:
        raise InvalidPartError("margin", f"{margin:g} m leaves no room for a weight on the plate")
    return InsetPolygon(tuple(map(tuple, W.tolist())), tuple(map(tuple, normals.tolist())),
                        tuple(float(v) for v in offsets), float(margin))


@dataclass(frozen=True, slots=True)
class WeightForCom:
    """The lightest single weight that puts the CM of plate + weight at ``com`` (m, kg).

    ``realisable`` False means ``com`` is outside the allowed region or on its edge (then no
    finite weight kept ``margin`` inside the plate gives it; outside the plate itself, no mass
    distribution at all); ``at`` is then nan and ``mass`` nan (outside) or inf (on the edge).
    ``ratio`` = mass / plate mass.
    """

    com: tuple
    plate_com: tuple
    realisable: bool
    at: tuple
    mass: float
    ratio: float
    margin: float
    inside_plate: bool


def lightest_weight_for_com(vertices, plate_mass: float, com, margin: float) -> WeightForCom:
    """The lightest weight (kg) and its place (m) putting the CM of plate + weight at ``com``.

    The CM of plate + weight lies on the segment from the plate's centroid c_p to the weight
    w, at ``c = c_p + m_w/(m_p + m_w) (w − c_p)``; for a given c the mass is least when w is
    as far out as allowed on the ray from c_p through c, giving
    ``m_w = m_p |c − c_p| / |w − c|``.
    """
    V = np.asarray(vertices, dtype=float)
    _, cp, _ = polygon_mass_properties(V)
    c = np.asarray(com, dtype=float)
    ins = inset_polygon(V, margin)
    full = inset_polygon(V, 0.0)
    inside_plate = full.contains(c)
    if np.allclose(c, cp):
        return WeightForCom(tuple(c), tuple(cp), True, tuple(cp), 0.0, 0.0, margin, True)
    if not ins.contains(c):
        nan = math.nan
        return WeightForCom(tuple(c), tuple(cp), False, (nan, nan), nan, nan, margin, inside_plate)
    d = (c - cp) / np.linalg.norm(c - cp)
    n, b = np.asarray(ins.normals), np.asarray(ins.offsets)
    # largest s with n·(c + s d) <= b
    nd = n @ d
    s = min(float((bk - nk @ c) / ndk) for nk, bk, ndk in zip(n, b, nd) if ndk > 1e-15)
    if s <= 1e-12:  # c on the allowed region's edge: only an infinitely heavy weight at c itself
        nan = math.nan
        return WeightForCom(tuple(c), tuple(cp), False, (nan, nan), math.inf, math.inf, margin, inside_plate)
    w = c + s * d
    ratio = float(np.linalg.norm(c - cp) / np.linalg.norm(w - c))
    return WeightForCom(tuple(c), tuple(cp), True, (float(w[0]), float(w[1])), ratio * float(plate_mass), ratio,
                        margin, inside_plate)
