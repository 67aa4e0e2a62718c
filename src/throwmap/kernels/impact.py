"""Perfectly plastic, no-slip impact about a contact vertex (paper Sec. III-C, Eq. 4)."""

from numba import njit


@njit(cache=True)
def plastic_impact(vx, vy, w, rx, ry, rho2):
    """Post-impact CM velocity and spin, paper Eq. (4).

    Angular momentum about the contact point is conserved and the contact point
    stops (no slip, no rebound). ``(rx, ry)`` is the vector from the CM to the
    contact vertex *at the impact orientation* (m), ``rho2`` = ρ² (m²),
    ``(vx, vy, w)`` the pre-impact CM velocity (m/s) and spin (rad/s).
    Returns ``(vx⁺, vy⁺, w⁺)``.
    """
    H = rho2 * w + ry * vx - rx * vy  # angular momentum about the contact, per unit mass
    wp = H / (rho2 + rx * rx + ry * ry)
    return ry * wp, -rx * wp, wp
