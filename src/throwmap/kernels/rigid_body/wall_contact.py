"""The wall's contacts for model "rigid_body": reason codes, the impact along any normal, departure windows.

Part of :mod:`.wall` (see there for the wall, its guards and resets): the plastic Coulomb
impact at a contact with any unit normal (the arm's law, :func:`~.impact.coulomb_impact`, in a
turned frame), and the exact windows for which a contact that just closed stays open.
"""

import math

from numba import njit

from .. import codes as C
from .impact import coulomb_impact

WHY_NONE = 0
WHY_WALL_TOP = 1
WHY_WALL_SLIDE = 2
WHY_TWO_CONTACT = 3
WHY_LADDER = 4
WHY_CORNER = 5
WHY_SLIDE_WALL = 6
WHY_WALL_EDGE = 7
WHY_CORNER_VERTEX = 8
WHY_MESSAGES = {
    WHY_WALL_TOP: ("a vertex reached the wall's plane above its top while the part slid on the arm (a sliding "
                   "pivot) or along the wall: not modelled by rigid_body"),
    WHY_WALL_SLIDE: ("an edge on the wall's top corner moves together with another contact, or a contact with the "
                     "wall lets go of it tangentially (no departure window): not modelled by rigid_body (use model "
                     "'engine')"),
    WHY_TWO_CONTACT: ("two contacts on the arm, or two on the wall, move at once (an edge sliding flat while the part "
                      "touches the other surface), or a contact can neither stay closed nor open: not modelled by "
                      "rigid_body"),
    WHY_LADDER: ("the part stopped against the arm and the wall is not held there and none of the motions "
                 "rigid_body models (a ladder slide, a swing back about its arm contact) can start"),
    WHY_CORNER: ("a vertex at the wall's foot (on the arm and the face at once) moves, or the pivot there is "
                 "driven into the wall: not modelled by rigid_body"),
    WHY_SLIDE_WALL: ("a pivot sliding along the arm brought the part to the wall: this contact is not located "
                     "by rigid_body's sliding phase"),
    WHY_WALL_EDGE: ("while a vertex slides on the wall's face, a second vertex reaches the wall's plane (an edge "
                    "flush on the face or across its top corner): not modelled by rigid_body"),
    WHY_CORNER_VERTEX: ("an edge on the wall's top corner brought a vertex onto the corner or onto the wall's top "
                        "beyond its face, or the part tips over the wall (its top and thickness are not modelled): "
                        "not modelled by rigid_body"),
    # the moving-arm phase (moving/phase.py: WHY_EVENTS, WHY_STEPS, WHY_NO_MODE, WHY_LAND)
    101: "more events than the cap while the arm moves (e.g. rocking on the moving arm): not resolved by rigid_body",
    102: "more integration steps than the cap while the arm moves: not resolved by rigid_body",
    103: ("no consistent contact mode (stick, slide, lift) after an event while the arm moves: not resolved by "
          "rigid_body"),
    104: "a vertex not adjacent to the pivot touched the moving arm (a degenerate polygon): not modelled by rigid_body",
}
"""Why a throw was refused (status UNRESOLVED), by reason code: the wall's (1–8) and the moving arm's (101–104)."""

EV_WALL = 10
"""Event code of guard ``wall_reach`` (after the codes of :mod:`.modes`): a vertex is on the wall and the part turns into it."""
WHY_COL = getattr(C, "WHY", -1)
"""Record column receiving the reason code of a refusal (``kernels.codes.WHY``), if the record has one."""

CONE_TOL = 1e-11
"""Relative tolerance of :func:`cone_contains` (residual and negative coefficients, relative to |b|)."""




@njit(cache=True)
def refuse(rec, why):
    """Status UNRESOLVED for a walled throw the automaton cannot follow; the reason ``why`` goes to the record."""
    if WHY_COL >= 0:
        rec[WHY_COL] = why
    return C.UNRESOLVED


@njit(cache=True)
def wall_impact(vx, vy, om, rx, ry, rho2, mu_w, law):
    """Reset ``wall_impact``: plastic Coulomb impact of the vertex at (r_x, r_y) from the CM (m) on the wall x = L.

    The arm's law :func:`~.impact.coulomb_impact` in the frame (x', y') = (y, −x), a proper
    rotation by −90° in which the wall's inward normal −x̂ is ŷ' and its tangent ŷ is x̂';
    ω is unchanged. ``mu_w`` is the wall's μ (``inf``: no slip), ``law`` the impact law.
    Returns ``(vx⁺, vy⁺, ω⁺, P_t, P_n, kind, jt0, jn0)``: P_n (m/s, ≥ 0) the impulse along −x̂,
    P_t along +ŷ, kind as :func:`~.impact.coulomb_impact` (IMP_SEPARATE if the vertex is not
    moving into the wall).
    """
    vxp, vyp, wp, pt, pn, kind, jt0, jn0 = coulomb_impact(vy, -vx, om, ry, -rx, rho2, mu_w, law)
    return -vyp, vxp, wp, pt, pn, kind, jt0, jn0


@njit(cache=True)
def contact_impact(vx, vy, om, rx, ry, nx, ny, rho2, mu_c, law):
    """Reset ``impact`` at a contact with unit normal (n_x, n_y) into the part: the arm's law in the frame (t, n),
    t = n turned by −90° (a proper rotation). Returns as :func:`wall_impact`, with P_n along n and P_t along t."""
    tx = ny
    ty = -nx
    vxp, vyp, wp, pt, pn, kind, jt0, jn0 = coulomb_impact(vx * tx + vy * ty, vx * nx + vy * ny, om,
                                                          rx * tx + ry * ty, rx * nx + ry * ny, rho2, mu_c, law)
    return vxp * tx + vyp * nx, vxp * ty + vyp * ny, wp, pt, pn, kind, jt0, jn0


@njit(cache=True, inline="always")
def _step_lb(gj, dg, M):
    """Smallest positive root of gj + dg s − ½ M s² (gj clipped at 0; M ≥ 0): a step that cannot pass a root."""
    gp = gj if gj > 0.0 else 0.0
    if M <= 0.0:
        if dg >= 0.0:
            return math.inf
        return gp / (-dg)
    disc = math.sqrt(dg * dg + 2.0 * M * gp)
    if dg >= 0.0:
        return (dg + disc) / M
    return 2.0 * gp / (disc - dg)


@njit(cache=True)
def separating_window(un, acc):
    """Time (s) for which a contact that leaves at normal rate ``un`` > 0 (m/s) stays open when its gap's second
    derivative is bounded by ``acc`` (m/s²): 0.9 × 2 un/acc (at most 1 s), from gap(s) ≥ un s − ½ acc s²."""
    if acc <= 0.0:
        return 1.0
    return min(1.8 * un / acc, 1.0)


@njit(cache=True)
def wall_departure(un, rx, ry, om, gx, gy, lj):
    """Time (s) for which a vertex that just left the wall (gap 0, outward rate ``un`` ≥ 0) stays off it.

    Exact Taylor bound of its gap W(s) ≥ W' s + ½W'' s² + W''' s³/6 − ω⁴ℓ s⁴/24 with
    W'' = −g_x + ω² r_x and W''' = −ω³ r_y ((r_x, r_y): CM → vertex, m): returns 0.9 × the
    positive root of ½W'' + W''' s/6 − ω⁴ℓ s²/24, or 0 if W'' < 0 (the vertex is pressed
    against the wall: it cannot leave). ``gy`` does not enter (the wall is vertical).
    """
    g2 = -gx + om * om * rx
    g3 = -om * om * om * ry
    if g2 < 0.0 and g2 > -1e-9 * (abs(gx) + abs(gy) + 1e-300):
        g2 = 0.0
    if g2 < 0.0:
        return 0.0
    a = om * om * om * om * lj / 24.0
    bb = g3 / 6.0
    cc = 0.5 * g2
    if a <= 0.0:
        if bb > 0.0 or cc > 0.0:
            return 1.0
        return 0.0
    root = (bb + math.sqrt(bb * bb + 4.0 * a * cc)) / (2.0 * a)
    if root <= 0.0:
        return 0.0
    return 0.9 * root


@njit(cache=True)
def corner_bounds(qx, qy, vx, vy, om, gx, gn, t_max):
    """Bounds (M2, M3) on the second and third time derivatives of every edge's corner distance f_e
    (:func:`corner_touch_time`) over a flight of ``t_max`` s from Q − CM = (q_x, q_y) (m) and CM velocity (v_x, v_y)."""
    ga = math.hypot(gx, gn)
    v0 = math.hypot(vx, vy)
    D = math.hypot(qx, qy) + v0 * t_max + 0.5 * ga * t_max * t_max
    vm = v0 + ga * t_max
    aw = abs(om)
    return om * om * D + 2.0 * aw * vm + ga, aw * aw * aw * D + 3.0 * om * om * vm + 3.0 * aw * ga


@njit(cache=True)
def corner_departure(qx, qy, vx, vy, om, gx, gn, nx, ny, t_max):
    """Time (s) for which an edge that just stopped on the wall's top corner (normal velocity 0) stays off it.

    With Q − CM = (q_x, q_y) (m), CM velocity V, gravity g = (g_x, −g_n) and the edge's outward normal n
    (J: turn by +90°), the gap's Taylor bound f(s) ≥ ½ f2 s² + f3 s³/6 − M4 s⁴/24 holds for s ≤ ``t_max`` with
    f2 = −ω² n·(Q − X) − 2ω (Jn)·V − n·g, f3 = −ω³ (Jn)·(Q − X) + 3ω² n·V − 3ω (Jn)·g and
    M4 = ω⁴ D + 4|ω|³ v + 6ω² |g| (D, v: bounds on |Q − X| and |V| over ``t_max``). Returns 0.9 × the positive
    root of ½ f2 + f3 s/6 − M4 s²/24 (at most ``t_max``), or 0 if f2 < 0 (the edge is pressed on the corner) or
    f2 = 0 with f3 ≤ 0 (a tangency that does not open). f3 matters where the edge just let go of the corner
    (CORNER's lift-off, λ = 0: f2 = 0).
    """
    jx = -ny
    jy = nx
    ga = math.hypot(gx, gn)
    f2 = -om * om * (nx * qx + ny * qy) - 2.0 * om * (jx * vx + jy * vy) - (nx * gx - ny * gn)
    if f2 < 0.0 and f2 > -1e-9 * ga:
        f2 = 0.0
    if f2 < 0.0:
        return 0.0
    f3 = -om * om * om * (jx * qx + jy * qy) + 3.0 * om * om * (nx * vx + ny * vy) - 3.0 * om * (jx * gx - jy * gn)
    if f2 == 0.0 and f3 <= 0.0:
        return 0.0
    v0 = math.hypot(vx, vy)
    D = math.hypot(qx, qy) + v0 * t_max + 0.5 * ga * t_max * t_max
    vm = v0 + ga * t_max
    aw = abs(om)
    M4 = om * om * om * om * D + 4.0 * aw * aw * aw * vm + 6.0 * om * om * ga
    if M4 <= 0.0:
        return t_max
    a = M4 / 24.0
    b = f3 / 6.0
    c = 0.5 * f2
    root = (b + math.sqrt(b * b + 4.0 * a * c)) / (2.0 * a)
    return min(0.9 * root, t_max) if root > 0.0 else 0.0
