"""Locating a guard inside one integration step, shared by the integrated contact modes of model "rigid_body"
(PIVOT_SLIDE, WALL_CONTACT, CORNER, LADDER).

Each mode integrates with classical RK4 and checks its guards at the step's end; where the least
guard G (a smooth function of the state along the RK4 polynomial, which is the interpolant) is ≤ 0
there, the first τ ∈ (0, dt] with G ≤ 0 is bracketed and narrowed (:func:`locate_guard`): false
position on the guard that fired, kept inside the bracket (:func:`falsi_point`), else bisection.
"""

from numba import njit

from .modes import N_BISECT


@njit(cache=True, inline="always")
def falsi_point(lo, hi, tol, c_lo, c_hi):
    """Where to try next in the bracket [lo, hi] (s) with the guard's values c_lo > 0 ≥ c_hi at its ends: the
    false-position root kept half of ``tol`` inside the bracket; its middle when the values do not bracket a root."""
    width = hi - lo
    if c_lo > 0.0 and c_hi <= 0.0:
        mid = lo + width * c_lo / (c_lo - c_hi)
        return min(max(mid, lo + 0.5 * tol), hi - 0.5 * tol)
    return lo + 0.5 * width


@njit(cache=True, inline="always")
def locate_guard(advance, guards, value, s0, s_hi, dt, which, k, t, p):
    """Smallest step length τ ∈ (0, dt] (s) at which the least guard of a mode is ≤ 0, from state ``s0`` at time t.

    The mode supplies ``advance(s0, τ, p)`` (its RK4 step of length τ, the state's interpolant),
    ``guards(s, p)`` → ``(least value, which, k)`` (k a vertex, or −1) and ``value(which, k, s, p)``
    (one guard's value; the least one where the mode has no smooth per-guard values), with ``p``
    the mode's parameters; ``s_hi`` = advance(s0, dt, p), where guard ``which`` (vertex ``k``) fired.

    Bracket [lo, hi] with G(lo) > 0 ≥ G(hi). Each trial point is a false-position step on the
    guard that fired at hi (its own values at both ends: one smooth function), kept at least half
    the tolerance inside the bracket, while the previous step halved the bracket; bisection
    otherwise (a stiff step: μ ≫ 1, or the step's RK4 polynomial far from linear). The sign of the
    least guard itself decides each step, so the result is the bisection's bracket limit; stops
    when the bracket is below 1e-16 (t + τ), as bisection would, at most 4 × N_BISECT trials.
    Returns ``(τ, which, k, s)``: the bracket's upper end, the guard that fired there and the state.
    """
    lo = 0.0
    hi = dt
    s_lo = s0
    falsi = True
    for _ in range(4 * N_BISECT):
        width = hi - lo
        tol = 1e-16 * (t + hi)
        if width <= tol:
            break
        mid = lo + 0.5 * width
        if falsi:
            c_lo = value(which, k, s_lo, p)
            c_hi = value(which, k, s_hi, p)
            mid = falsi_point(lo, hi, tol, c_lo, c_hi)
        sm = advance(s0, mid, p)
        gm, wh, km = guards(sm, p)
        if gm <= 0.0:
            hi = mid
            which = wh
            k = km
            s_hi = sm
        else:
            lo = mid
            s_lo = sm
        falsi = hi - lo <= 0.5 * width
    return hi, which, k, s_hi
