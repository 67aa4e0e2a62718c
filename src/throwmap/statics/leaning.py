"""Leaning against the end wall (paper Sec. VI, Figs. 12(a) and 13): closed form, corrected, and the LP.

A part leans at angle β when one edge (length c) rises from its lower vertex P on the arm to its upper
vertex Q on the wall's face, the rest of the part above that edge. With the wall frictionless
(Sec. VI's assumption), the arm's μ at P and gravity g(−sin α, −cos α) in the arm frame, statics
about P give the wall's force (per unit weight)

    n_w = (r_x cos α − r_y sin α) / (c sin β),      r = G − P in the arm frame,

and the arm's tangential force per unit weight f_t = n_w + sin α against its normal force cos α. The
part can lean iff

    (i) n_w ≥ 0,   (ii) n_w + sin α ≤ μ cos α,   (iii) n_w + sin α ≥ −μ cos α.

With G at (a c, b c) in the edge's frame (a along P→Q, b towards the part), condition (ii) fails
exactly when the draft's printed inequality holds (for its 30-60-90 triangle a = 0.583, b = 0.144,
1 − a = 0.417):

    −cos α ((b + μ) sin β − a cos β) + sin α ((1 − a) sin β − b cos β) > 0.

So the draft's condition is (ii) alone: sufficient for "cannot lean", but it ignores (i) (the part
falls back onto the arm) and (iii) (its foot slides away from the wall). :func:`lean_possible`
is the complete condition; :func:`drafts_no_lean` the printed one; :func:`leaning_bodies` builds the
configuration for the general solver of :mod:`throwmap.statics.rest`, which the tests compare with
both. Units: m, rad.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidStateError, shown
from ..models._checks import finite_float
from ..system.system import check_alpha
from .rest import Body, Contact

__all__ = ["edge_frame_cm", "lean_possible", "drafts_no_lean", "leaning_bodies", "lean_free_beta"]


def _hypotenuse(part):
    """Indices (i, j) of the part's longest edge, ordered so that the rest of the part lies to the left of
    i → j (above it when i → j points along +x)."""
    w = np.asarray(part.w, dtype=float)
    n = len(w)
    best = max(range(n), key=lambda k: np.hypot(*(w[(k + 1) % n] - w[k])))
    i, j = best, (best + 1) % n
    d = w[j] - w[i]
    others = [k for k in range(n) if k not in (i, j)]
    cross = d[0] * (w[others[0]][1] - w[i][1]) - d[1] * (w[others[0]][0] - w[i][0])
    return (i, j) if cross > 0 else (j, i)


def edge_frame_cm(part, edge=None) -> tuple[float, float, float]:
    """``(a, b, c)``: the CM at (a c, b c) in the frame of edge P → Q (``edge``: vertex indices into
    ``part.w``; default the longest edge, P the end that puts the part above it), c its length (m)."""
    i, j = _hypotenuse(part) if edge is None else edge
    w = np.asarray(part.w, dtype=float)
    P, Q = w[i], w[j]
    d = Q - P
    c = float(np.hypot(*d))
    e = d / c
    nrm = np.array([-e[1], e[0]])
    r = -P  # the CM is the body frame's origin
    return float(r @ e) / c, float(r @ nrm) / c, c


def lean_possible(a: float, b: float, beta, alpha, mu) -> np.ndarray:
    """The complete lean condition (i)–(iii) of the module docstring, elementwise over β, α (rad), μ."""
    beta, alpha, mu = np.broadcast_arrays(np.asarray(beta, float), np.asarray(alpha, float), np.asarray(mu, float))
    cb, sb, ca, sa = np.cos(beta), np.sin(beta), np.cos(alpha), np.sin(alpha)
    rx = a * cb - b * sb
    ry = a * sb + b * cb
    with np.errstate(divide="ignore", invalid="ignore"):
        nw = (rx * ca - ry * sa) / sb
        ft = nw + sa
        fric = np.where(np.isinf(mu), True, np.abs(ft) <= mu * ca + 1e-12)
    return (sb > 0) & (nw >= -1e-12) & fric


def drafts_no_lean(a: float, b: float, beta, alpha, mu) -> np.ndarray:
    """The draft's printed "cannot lean" inequality (Sec. VI), with its constants 0.58/0.14/0.42 as a, b, 1 − a."""
    beta, alpha, mu = (np.asarray(v, float) for v in (beta, alpha, mu))
    return (-np.cos(alpha) * ((b + mu) * np.sin(beta) - a * np.cos(beta))
            + np.sin(alpha) * ((1 - a) * np.sin(beta) - b * np.cos(beta))) > 0


BETA_TOL = 1e-12
"""Bisection tolerance of :func:`lean_free_beta` (rad)."""


def lean_free_beta(a: float, b: float, alpha: float, mu: float, n: int = 20001) -> float:
    """The largest β* (rad) such that no lean angle in (0, β*] is possible (π/2 if none is): the part
    given less than β* of lean falls back (the draft's "β < 0.25 rad").

    ``a``, ``b`` the CM in the edge frame (:func:`edge_frame_cm`), ``alpha`` the arm's angle (rad), ``mu``
    the arm's friction (≥ 0, inf: no slip). A grid of ``n`` (≥ 3) angles over (0, π/2] finds the first
    lean; the boundary below it is then bisected to :data:`BETA_TOL` (a lean window narrower than the
    grid's step π/(2(n − 1)) below it is not seen)."""
    a, b = finite_float(a, "a"), finite_float(b, "b")
    alpha = check_alpha(alpha, "alpha")
    if isinstance(mu, bool) or not isinstance(mu, (int, float, np.floating)) or math.isnan(mu) or mu < 0:
        raise InvalidStateError("mu", f"must be a number ≥ 0 (inf: no slip), got {shown(mu)}")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 3:
        raise InvalidStateError("n", f"must be an integer ≥ 3 (grid angles), got {shown(n)}")
    betas = np.linspace(0.0, math.pi / 2, n)[1:]
    ok = lean_possible(a, b, betas, alpha, mu)
    if not ok.any():
        return math.pi / 2
    k = int(np.argmax(ok))
    lo, hi = (float(betas[k - 1]) if k > 0 else 0.0), float(betas[k])  # no lean at lo (or lo = 0), a lean at hi
    while hi - lo > BETA_TOL:
        mid = 0.5 * (lo + hi)
        if bool(lean_possible(a, b, mid, alpha, mu)):
            hi = mid
        else:
            lo = mid
    return lo


def leaning_bodies(part, beta: float, *, length: float, h: float = 0.0, mu_arm: float, mu_wall: float = 0.0,
                   edge=None) -> tuple[tuple, tuple]:
    """``(bodies, contacts)`` of ``part`` leaning at ``beta`` (rad, 0 < β < π/2) against a wall at x = ``length``:
    edge P → Q (default the longest) from P on the arm (μ_arm) to Q on the wall (μ_wall)."""
    if not 0 < beta < math.pi / 2:
        raise InvalidStateError("beta", f"must be in (0, π/2) rad, got {beta!r}")
    if not (isinstance(length, (int, float)) and math.isfinite(length) and length > 0):
        raise InvalidStateError("length", f"the wall's place must be a positive finite x (m), got {shown(length)}")
    n = len(part.w)
    if edge is not None:
        try:
            i, j = (int(edge[0]), int(edge[1]))
        except (TypeError, ValueError, IndexError):
            raise InvalidStateError("edge", f"must be a pair of vertex indices (i, j), got {shown(edge)}") from None
        if not (0 <= i < n and 0 <= j < n) or (j - i) % n not in (1, n - 1):
            raise InvalidStateError("edge", f"must be two adjacent vertices of the {n}-gon (0 … {n - 1}), got {shown(edge)}")
    i, j = _hypotenuse(part) if edge is None else (i, j)
    w = np.asarray(part.w, dtype=float)
    d = w[j] - w[i]
    phi = beta - math.atan2(d[1], d[0])
    c = float(np.hypot(*d))
    P = np.array([length - c * math.cos(beta), h])
    rot = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
    com = P - rot @ w[i]
    body = Body(part, float(com[0]), float(com[1]), phi)
    Q = body.vertices()[j]
    contacts = (Contact(0, None, (float(P[0]), h), (0.0, 1.0), mu_arm, "arm"),
                Contact(0, None, (length, float(Q[1])), (-1.0, 0.0), mu_wall, "wall"))
    return (body,), contacts
