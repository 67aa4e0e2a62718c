"""Period doubling of a fixed point, located on its own multiplier.

Past a period doubling the fixed point is unstable and no orbit finds it; it is still a root of T(x) − x. So the
fixed point is solved for directly (:func:`solve_fixed`, a bracketed root near where it was, the map staying on its
side) and its multiplier dT/dx taken by central differences; :func:`locate` bisects the parameter on the sign of
multiplier + 1, and :func:`doublings` pairs a fixed point of one value with the attractor it doubled into at the
next (the period-2 cycle, or a band while orbits still converge slowly) so that both keep one id.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["doublings", "solve_fixed", "locate"]

def doublings(ev, a, b, tol: float, ptol: float) -> list:
    """Fixed points of ``a`` that double between ``a`` and ``b``: the fixed point solved at ``b`` near it has a
    multiplier below −1 and lies in the hull (± ``tol`` m) of an attractor of ``b`` on its side (the period-2 cycle,
    or a band while orbits still converge slowly). ``[(i, j, value, half width)]``, the value located by bisection
    on the multiplier to ``ptol``."""
    out, used = [], set()
    for i, fp in enumerate(a.attractors):
        if fp.kind != "fixed_point" or not (math.isfinite(fp.multiplier) and fp.multiplier > -1):
            continue
        side, x = fp.points[0]
        sol = solve_fixed(ev.cmap(b.value), side, x)
        if sol is None or sol[1] > -1:
            continue
        for j, att in enumerate(b.attractors):
            hull = att.interval(side)
            if j in used or hull is None or not (hull[0] - tol <= sol[0] <= hull[1] + tol):
                continue
            at = locate(ev, a, b, i, ptol)
            if at is not None:
                out.append((i, j, at[0], at[1]))
                used.add(j)
            break
    return out


def solve_fixed(cmap, side: int, x0: float, span: float = 0.01):
    """The fixed point of ``cmap`` on ``side`` near ``x0`` (a root of T(x) − x within ± ``span`` m, the map staying
    on the side) and its multiplier dT/dx (central difference, 1 µm): ``(x, multiplier)`` or None."""
    from scipy.optimize import brentq

    lo_d, hi_d = cmap.domain()[side]
    xs = np.linspace(max(lo_d + 1e-9, x0 - span), min(hi_d, x0 + span), 41)
    tx, ts, st = cmap(xs, np.full(xs.size, side))
    ok = (st == 0) & (ts == side)
    f = np.where(ok, tx - xs, np.nan)
    best = None
    for i in range(xs.size - 1):
        if ok[i] and ok[i + 1] and f[i] * f[i + 1] <= 0:
            if best is None or abs(xs[i] - x0) < abs(best - x0):
                best = xs[i]
    if best is None:
        return None
    i = int(np.searchsorted(xs, best))

    def g(x):
        y, s, c = cmap(np.array([x]), np.array([side]))
        return float(y[0]) - x if int(c[0]) == 0 and int(s[0]) == side else math.nan

    try:
        x = brentq(g, xs[i], xs[i + 1], xtol=1e-10)
    except ValueError:
        return None
    e = 1e-6
    y, s, c = cmap(np.array([x - e, x + e]), np.array([side, side]))
    if not np.all((c == 0) & (s == side)):
        return None
    return x, float((y[1] - y[0]) / (2 * e))


def locate(ev, a, b, i: int, tol: float):
    """Locate where the fixed point ``a.attractors[i]`` doubles in [a.value, b.value] (bisection on the solved
    multiplier's sign of m + 1): ``(value, half width)`` or None when the solved multiplier does not pass −1."""
    side, x = a.attractors[i].points[0]
    lo, hi = a.value, b.value
    m_hi = solve_fixed(ev.cmap(hi), side, x)
    if m_hi is None or m_hi[1] > -1:
        return None
    while hi - lo > 2 * tol:
        mid = 0.5 * (lo + hi)
        sol = solve_fixed(ev.cmap(mid), side, x)
        if sol is None:
            return None
        if sol[1] > -1:
            lo, x = mid, sol[0]
        else:
            hi = mid
    return 0.5 * (lo + hi), 0.5 * (hi - lo)


