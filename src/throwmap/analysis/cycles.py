"""Cycles of a configuration map, confirmed by the map itself (paper Sec. III-D).

The recurrence test (:mod:`throwmap.analysis.recurrence`) calls a recorded tail
periodic when every state equals the one p throws later to within ``tol``. Here
that is confirmed by throwing again: :func:`closing` throws each tail's last state
once more, and :func:`verified_cycles` applies the map p times from every cycle's
first point (:func:`cycle_residual`). A reported cycle therefore satisfies
|T^p(x) − x| ≤ ``tol`` with matching sides; tails that only looked periodic (a
drift whose steps were compared without their sign, say) go back to the wandering
ones.
"""

from __future__ import annotations

import math

import numpy as np

from ..kernels import codes as C
from .caps import RecurrenceCaps
from .maps import ConfigMap

__all__ = ["closing", "cycle_residual", "verified_cycles", "canonical_cycle"]


def closing(cmap: ConfigMap, X, S, idx, per, tol: float) -> np.ndarray:
    """Whether each periodic tail closes under the map: |T(x_last) − x_{−p}| ≤ ``tol`` on the same side.

    One more throw of each tail's last configuration must land on the configuration
    ``p`` throws before it; a tail that only *looked* periodic (e.g. a drift compared
    without its sign) does not close.
    """
    if idx.size == 0:
        return np.zeros(0, dtype=bool)
    p = per[idx]
    xn, sn, st = cmap(X[idx, -1], S[idx, -1])
    back_x = X[idx, X.shape[1] - p]
    back_s = S[idx, X.shape[1] - p]
    return (st == C.OK) & (sn == back_s) & (np.abs(xn - back_x) <= tol)


def canonical_cycle(xs, ss):
    """Rotate a cycle to start at its smallest (side, x)."""
    k = min(range(len(xs)), key=lambda i: (ss[i], xs[i]))
    return tuple((int(ss[(k + i) % len(xs)]), float(xs[(k + i) % len(xs)])) for i in range(len(xs)))


def _same_points(c, pts, tol: float) -> bool:
    return len(c) == len(pts) and all(a[0] == b[0] and abs(a[1] - b[1]) <= 10 * tol for a, b in zip(c, pts))


def _group_cycles(X, S, idx, per, tol: float) -> list:
    """Periodic tails grouped by their points: ``[(canonical points, member starts), ...]``."""
    cycles: list[tuple] = []
    for i in idx:
        p = per[i]
        pts = canonical_cycle(X[i, -p:], S[i, -p:])
        for c in cycles:
            if _same_points(c[0], pts, tol):
                c[1].append(i)
                break
        else:
            cycles.append((pts, [i]))
    return cycles


def cycle_residual(cmap: ConfigMap, pts) -> float:
    """max over a cycle's points of the distance to where the map takes the one before, m.

    ``pts`` is ``((side, x), ...)`` in orbit order (period p = its length). The map is
    applied p times from the first point; each image must rest on the arm, on the next
    point's side. Returns the largest |x_k − T^k(x_0)| (k = 1 … p, the last being
    |T^p(x_0) − x_0|), or inf if an image escapes or lands on another side.
    """
    x = np.array([pts[0][1]])
    s = np.array([pts[0][0]], dtype=np.int64)
    worst = 0.0
    for k in range(1, len(pts) + 1):
        x, s, st = cmap(x, s)
        want_s, want_x = pts[k % len(pts)]
        if int(st[0]) != C.OK or int(s[0]) != int(want_s):
            return math.inf
        worst = max(worst, abs(float(x[0]) - float(want_x)))
    return worst


def _fixed_point_near(cmap: ConfigMap, side: int, x: float, tol: float, max_steps: int):
    """Iterate from (x, side) until |T(x) − x| ≤ ``tol`` on the same side; the point, or None."""
    xa = np.array([x])
    sa = np.array([side], dtype=np.int64)
    for _ in range(max_steps):
        xn, sn, st = cmap(xa, sa)
        if int(st[0]) != C.OK or int(sn[0]) != side:
            return None
        if abs(float(xn[0]) - float(xa[0])) <= tol:
            return (side, float(xa[0]))
        xa = xn
    return None


def verified_cycles(cmap: ConfigMap, X, S, idx, per, caps: RecurrenceCaps) -> tuple[list, list]:
    """Periodic tails as verified cycles: ``([(points, members, residual), ...], [demoted starts])``.

    A "cycle" whose points coincide (to 10 ``tol``, one side) is a fixed point not yet
    settled: it is iterated on (up to ``transient`` throws) until |T(x) − x| ≤ ``tol``.
    Every cycle is then checked by applying the map p times from its first point
    (:func:`cycle_residual` ≤ ``tol``); a group that fails is no cycle and its tails go
    back to the wandering ones. Cycles that coincide after this are one.
    """
    tol = caps.tol
    merged: list[tuple] = []
    demoted: list[int] = []
    for pts, members in _group_cycles(X, S, idx, per, tol):
        if len(pts) > 1 and len({q[0] for q in pts}) == 1 and max(q[1] for q in pts) - min(q[1] for q in pts) <= 10 * tol:
            fp = _fixed_point_near(cmap, pts[0][0], pts[0][1], tol, max(caps.transient, 1))
            if fp is not None:
                pts = (fp,)
        res = cycle_residual(cmap, pts)
        if not res <= tol:
            demoted.extend(members)
            continue
        for c in merged:
            if _same_points(c[0], pts, tol):
                c[1].extend(members)
                c[2] = max(c[2], res)
                break
        else:
            merged.append([pts, list(members), res])
    return [tuple(c) for c in merged], demoted
