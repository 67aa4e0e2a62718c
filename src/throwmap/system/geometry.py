"""Plane-polygon geometry: validation, orientation, area moments, side tables.

Plain functions of NumPy arrays in metres; no classes, no I/O. The side table
implements the per-side quantities of paper Sec. III-A (d, u_L, v_L, u_R, v_R)
under the numbering of :mod:`throwmap.conventions`.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidPartError, shown

__all__ = [
    "as_finite_array",
    "check_convex_polygon",
    "signed_area",
    "clockwise_order",
    "polygon_mass_properties",
    "point_in_convex_polygon",
    "side_table",
    "edges_outward",
    "overlap_depth",
]

_REL_EPS = 1e-9  # relative tolerance for collinearity / degeneracy tests


def as_finite_array(value, field: str, shape: tuple | None = None) -> np.ndarray:
    """Return ``value`` as a float array, refusing NaN/inf and wrong shapes."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InvalidPartError(field, f"must be numbers, got {shown(value)}") from None
    if shape is not None:
        ok = arr.ndim == len(shape) and all(s is None or s == a for s, a in zip(shape, arr.shape))
        if not ok:
            want = "×".join("n" if s is None else str(s) for s in shape)
            raise InvalidPartError(field, f"must have shape {want}, got {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise InvalidPartError(field, "must be finite (got NaN or infinity)")
    return arr


def signed_area(vertices: np.ndarray) -> float:
    """Shoelace signed area (m²): positive for counter-clockwise vertex order."""
    x, y = vertices[:, 0], vertices[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def check_convex_polygon(vertices: np.ndarray, field: str = "part.vertices") -> None:
    """Raise :class:`InvalidPartError` unless ``vertices`` is a strictly convex simple polygon.

    Refused: fewer than 3 vertices, repeated vertices, zero-length edges, three
    consecutive collinear vertices, a reflex vertex (non-convex), and polygons
    whose turns all agree but wind more than once (self-intersecting stars).
    """
    n = len(vertices)
    if n < 3:
        raise InvalidPartError(field, f"a polygon needs at least 3 vertices, got {n}")
    edges = np.roll(vertices, -1, axis=0) - vertices
    lengths = np.hypot(edges[:, 0], edges[:, 1])
    scale = float(np.max(lengths)) if n else 0.0
    if scale <= 0.0:
        raise InvalidPartError(field, "degenerate polygon (all vertices coincide)")
    for k in range(n):
        if lengths[k] <= _REL_EPS * scale:
            raise InvalidPartError(field, f"degenerate polygon: vertices {k} and {(k + 1) % n} coincide")
    nxt = np.roll(edges, -1, axis=0)
    cross = edges[:, 0] * nxt[:, 1] - edges[:, 1] * nxt[:, 0]
    sin_turn = cross / (lengths * np.roll(lengths, -1))
    for k in range(n):
        if abs(sin_turn[k]) <= _REL_EPS:
            v = (k + 1) % n
            dot = float(np.dot(edges[k], nxt[k]))
            if dot < 0:
                raise InvalidPartError(field, f"degenerate polygon: the edges at vertex {v} fold back on each other")
            raise InvalidPartError(field, f"degenerate polygon: vertex {v} is collinear with its neighbours")
    sign = np.sign(sin_turn)
    if not (np.all(sign > 0) or np.all(sign < 0)):
        k = int(np.argmax(sign != sign[0])) if sign[0] != 0 else 0
        raise InvalidPartError(field, f"polygon is not convex (reflex or inconsistent turn at vertex {(k + 1) % n})")
    turn = np.arctan2(cross, np.einsum("ij,ij->i", edges, nxt))
    total = float(np.sum(turn))
    if abs(abs(total) - 2.0 * math.pi) > 1e-6:
        raise InvalidPartError(field, f"polygon is self-intersecting (it winds {abs(total) / (2 * math.pi):.0f} times)")
    if abs(signed_area(vertices)) <= _REL_EPS * scale * scale:
        raise InvalidPartError(field, "degenerate polygon (zero area)")


def clockwise_order(vertices: np.ndarray) -> np.ndarray:
    """Index array ``idx`` so that ``vertices[idx]`` is clockwise with side 0 = edge (v0, v1).

    Implements the numbering of :mod:`throwmap.conventions`: with ``w = vertices[idx]``,
    side k is the edge (w_k, w_{k+1}) and it is the same edge as the user's side k
    (edge v0–v1 for k = 0, then clockwise).
    """
    n = len(vertices)
    if signed_area(vertices) < 0:  # already clockwise
        return np.arange(n)
    # counter-clockwise: w_k = v_{(1-k) mod n} makes (w0, w1) = (v1, v0)
    return np.array([(1 - k) % n for k in range(n)])


def polygon_mass_properties(vertices: np.ndarray) -> tuple[float, np.ndarray, float]:
    """Area (m²), centroid (m) and polar second moment of area about the centroid (m⁴).

    Uniform-plate formulas by triangulation from the vertices' mean point (any
    orientation): triangulating from a far-away origin would lose the second moment
    to cancellation in the parallel-axis shift.
    """
    ref = vertices.mean(axis=0)
    local = vertices - ref
    x0, y0 = local[:, 0], local[:, 1]
    x1, y1 = np.roll(x0, -1), np.roll(y0, -1)
    c = x0 * y1 - x1 * y0
    a = 0.5 * float(np.sum(c))
    cx = float(np.sum((x0 + x1) * c)) / (6.0 * a)
    cy = float(np.sum((y0 + y1) * c)) / (6.0 * a)
    ixx = float(np.sum((y0 * y0 + y0 * y1 + y1 * y1) * c)) / 12.0
    iyy = float(np.sum((x0 * x0 + x0 * x1 + x1 * x1) * c)) / 12.0
    j_origin = ixx + iyy
    if a < 0:
        a, j_origin = -a, -j_origin
    j_c = j_origin - a * (cx * cx + cy * cy)
    return a, np.array([cx, cy]) + ref, j_c


def point_in_convex_polygon(vertices: np.ndarray, p, strict: bool = False, tol: float = 1e-12) -> bool:
    """Whether point ``p`` lies in the convex polygon (on the boundary counts unless ``strict``)."""
    p = np.asarray(p, dtype=float)
    orient = 1.0 if signed_area(vertices) > 0 else -1.0
    e = np.roll(vertices, -1, axis=0) - vertices
    rel = p[None, :] - vertices
    cross = orient * (e[:, 0] * rel[:, 1] - e[:, 1] * rel[:, 0])
    scale = float(np.max(np.hypot(e[:, 0], e[:, 1])))
    if strict:
        return bool(np.all(cross > tol * scale))
    return bool(np.all(cross >= -tol * scale * scale - tol))


def side_table(w: np.ndarray) -> dict[str, np.ndarray]:
    """Per-side rest geometry of a clockwise, CM-centred vertex list ``w`` (paper Sec. III-A).

    Returns arrays indexed by side k (edge w_k → w_{k+1}):

    ``beta``   body rotation (rad) that puts side k flat at the bottom;
    ``d``      CM height above side k when resting on it (m);
    ``uL``     x of the vector CM → left support vertex w_{k+1} at rest (m; its y is −d);
    ``uR``     x of the vector CM → right support vertex w_k at rest (m; its y is −d);
    ``length`` edge length (m); ``stable`` u_L < 0 < u_R.

    and per vertex j: ``ell`` |w_j| (m), the CM height when balanced on vertex j.
    """
    nxt = np.roll(w, -1, axis=0)
    e = nxt - w
    beta = np.mod(math.pi - np.arctan2(e[:, 1], e[:, 0]), 2.0 * math.pi)
    c, s = np.cos(beta), np.sin(beta)
    uR = c * w[:, 0] - s * w[:, 1]
    vR = s * w[:, 0] + c * w[:, 1]
    uL = c * nxt[:, 0] - s * nxt[:, 1]
    vL = s * nxt[:, 0] + c * nxt[:, 1]
    d = -0.5 * (vR + vL)
    return {
        "beta": beta,
        "d": d,
        "uL": uL,
        "uR": uR,
        "length": np.hypot(e[:, 0], e[:, 1]),
        "stable": (uL < 0.0) & (uR > 0.0),
        "ell": np.hypot(w[:, 0], w[:, 1]),
    }


def edges_outward(v: np.ndarray):
    """(start, end, outward unit normal) of a convex polygon's edges, either orientation."""
    n = len(v)
    area2 = sum(v[i, 0] * v[(i + 1) % n, 1] - v[(i + 1) % n, 0] * v[i, 1] for i in range(n))
    sign = 1.0 if area2 > 0 else -1.0  # CCW: outward normal = (dy, −dx)
    for i in range(n):
        p, q = v[i], v[(i + 1) % n]
        d = q - p
        L = float(np.hypot(*d))
        yield p, q, sign * np.array([d[1], -d[0]]) / L


def overlap_depth(va: np.ndarray, vb: np.ndarray) -> float:
    """Penetration depth (m) of two convex polygons by separating axes: > 0 when they overlap."""
    best = math.inf
    for poly in (va, vb):
        for p, q, n in edges_outward(poly):
            pa = va @ n
            pb = vb @ n
            best = min(best, min(pa.max(), pb.max()) - max(pa.min(), pb.min()))
    return best
