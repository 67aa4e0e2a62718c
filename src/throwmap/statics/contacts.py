"""Which point contacts a placement has: parts on the arm, against the end wall and on each other.

:func:`find_contacts` reads them off the geometry (arm frame, m): a vertex within ``tol`` of the arm
surface y = h (on the arm's span) touches the arm (normal +y); a vertex within ``tol`` of the wall's
face x = L (between the surface and the wall's top) touches the wall (normal −x); the wall's top
corner within ``tol`` of a part's edge touches that edge (normal: the edge's inward normal); a vertex
of one part within ``tol`` of another part's edge touches it (force on the vertex's part along the
edge's outward normal). Two parts flat on each other give two vertex contacts (the ends of the
common segment), which spans every force distribution the segment can carry. Parts that overlap by
more than ``tol`` are refused: they are not a placement.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidStateError
from ..system.geometry import edges_outward as _edges, overlap_depth
from .rest import Contact

__all__ = ["find_contacts"]


def _on_segment(pt, p, q, tol):
    """Distance from ``pt`` to segment pq if its projection falls on it (within ``tol``), else inf."""
    d = q - p
    L2 = float(d @ d)
    s = float((pt - p) @ d) / L2
    L = math.sqrt(L2)
    if s * L < -tol or (s - 1.0) * L > tol:
        return math.inf
    s = min(max(s, 0.0), 1.0)
    return float(np.hypot(*(pt - (p + s * d))))


def find_contacts(bodies, *, h: float, mu_arm: float, length=None, back: float = 0.0, wall=None,
                  mu_wall=None, mu_parts: float = 0.0, tol: float = 1e-6) -> tuple:
    """The contacts of ``bodies`` (see the module docstring). ``wall``: a
    :class:`~throwmap.system.fixtures.Wall` at x = ``length`` (needs ``length``); ``mu_wall`` its μ
    (None: the wall's own, else the arm's); ``mu_parts`` part–part μ."""
    bodies = tuple(bodies)
    verts = [b.vertices() for b in bodies]
    out = []
    if wall is not None and length is None:
        raise InvalidStateError("length", "a wall stands at the arm's end: give the arm's length")
    mw = (wall.mu if wall is not None and wall.mu is not None else mu_arm) if mu_wall is None else mu_wall
    for i, v in enumerate(verts):
        for p in v:
            if p[1] < h - tol:
                raise InvalidStateError("bodies", f"part {i} sinks {h - p[1]:.3g} m below the arm surface")
            if abs(p[1] - h) <= tol and p[0] > -back - tol and (length is None or p[0] <= length + tol):
                out.append(Contact(i, None, (p[0], h), (0.0, 1.0), mu_arm, "arm"))
            if wall is not None:
                if p[0] > length + tol and p[1] < h + wall.height - tol:
                    raise InvalidStateError("bodies", f"part {i} overlaps the wall by {p[0] - length:.3g} m")
                if abs(p[0] - length) <= tol and h - tol <= p[1] <= h + wall.height + tol:
                    out.append(Contact(i, None, (length, p[1]), (-1.0, 0.0), mw, "wall"))
        if wall is not None:
            corner = np.array([length, h + wall.height])
            for p, q, n in _edges(v):
                d = _on_segment(corner, p, q, tol)
                near_vertex = min(np.hypot(*(corner - p)), np.hypot(*(corner - q))) <= tol
                if d <= tol and not near_vertex:
                    out.append(Contact(i, None, tuple(corner), tuple(-n), mw, "corner"))
    for i in range(len(bodies)):
        for j in range(len(bodies)):
            if i == j:
                continue
            if i < j:
                depth = overlap_depth(verts[i], verts[j])
                if depth > tol:
                    raise InvalidStateError("bodies", f"parts {i} and {j} overlap by {depth:.3g} m")
            for p in verts[i]:
                for a, bq, n in _edges(verts[j]):
                    if _on_segment(p, a, bq, tol) <= tol:
                        # vertex of i on edge of j: the force on i along j's outward normal; skip vertex-vertex
                        # duplicates seen from the other side
                        if any(np.hypot(*(p - w)) <= tol for w in verts[j]) and i > j:
                            continue
                        out.append(Contact(i, j, tuple(p), tuple(n), mu_parts, "part"))
                        break
    return tuple(out)
