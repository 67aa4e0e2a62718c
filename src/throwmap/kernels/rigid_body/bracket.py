"""The trial point of the guard location shared by the integrated contact modes (PIVOT_SLIDE, WALL_CONTACT,
CORNER, LADDER): false position on the guard that fired, kept inside the bracket, else bisection."""

from numba import njit


@njit(cache=True, inline="always")
def falsi_point(lo, hi, tol, c_lo, c_hi):
    """Where to try next in the bracket [lo, hi] (s) with the guard's values c_lo > 0 ≥ c_hi at its ends: the
    false-position root kept half of ``tol`` inside the bracket; its middle when the values do not bracket a root."""
    width = hi - lo
    if c_lo > 0.0 and c_hi <= 0.0:
        mid = lo + width * c_lo / (c_lo - c_hi)
        return min(max(mid, lo + 0.5 * tol), hi - 0.5 * tol)
    return lo + 0.5 * width
