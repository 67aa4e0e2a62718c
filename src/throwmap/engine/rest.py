"""How both engine backends (pymunk, MuJoCo) read a part's end state as a status, as the analytic models do.

The arm's surface spans −back ≤ x ≤ L (:attr:`throwmap.Arm.back`, the arm's
length). A part with a vertex below the surface line beyond either edge has left
the arm (``behind_joint`` behind x = −back, ``off_end`` beyond x = L); a part at
rest is ``ok`` only where :func:`throwmap.throw` would accept its rest as a start
(flat on a stable side, both support vertices on the arm), which is where the
analytic models call a landing ``ok``.
"""

from __future__ import annotations

import math

import numpy as np

from ..records.outcome import Status
from ..system.pose import world_vertices

__all__ = ["EDGE_EPS", "FLAT_TILT", "WALL_SLACK", "UNCONVERGED", "clamp_to_arm", "edge_status", "rest_status", "tilted_message"]

UNCONVERGED = Status.UNCONVERGED
"""Status of a run refused as not converged (code 10 of :mod:`throwmap.kernels.codes`)."""

EDGE_EPS = 1e-4
"""m a vertex must be below the arm's surface line, beyond one of its edges, to have left the arm."""

FLAT_TILT = 0.02
"""rad: a settled part within this angle of a side lies flat on it."""

WALL_SLACK = 1e-3
"""m a part at rest may reach past x = L into an end wall (pressed in by another part) and still be on the arm:
the engine's default ``penetration_tol``, deeper than which a run is refused."""


def edge_status(vx, vy, h: float, L: float, back: float, slack: float = 0.0, end_slack: float | None = None):
    """``behind_joint``/``off_end`` if a vertex (arm-frame coordinates ``vx``, ``vy``, m) is below the
    surface line y = h (by more than :data:`EDGE_EPS`) behind x = −back − ``slack`` / beyond
    x = L + ``slack``, else None. ``slack`` (m) is :data:`EDGE_EPS` where fixtures stand at the
    ends: a part pressed into a wall at the arm's end, down in a cavity, sits a collision slop
    (~10 µm) inside the wall, below the surface line and "past" L without having left the arm;
    ``end_slack`` (default ``slack``) replaces it at the end x = L."""
    below = np.asarray(vy) < h - EDGE_EPS
    vx = np.asarray(vx)
    if np.any(below & (vx < -back - slack)):
        return Status.BEHIND_JOINT
    if np.any(below & (vx > L + (slack if end_slack is None else end_slack))):
        return Status.OFF_END
    return None


def rest_status(part, pose_a, x: float, k: int, tilt: float, h: float, L: float, back: float, plain: bool) -> Status:
    """Status of ``part`` at rest at arm-frame pose ``pose_a`` = state ``(x, k, tilt)`` on an arm −back ≤ x ≤ L.

    ``ok`` only flat on a stable side (|tilt| < :data:`FLAT_TILT`) with
    −back < x + u_L and x + u_R ≤ L; ``behind_joint``/``off_end`` past an edge;
    tilted elsewhere on a ``plain`` arm (one part, no fixtures: nothing can hold
    it so) ``unconverged``. With fixtures or other parts a tilted rest (against a
    wall, in a cavity, on another part) is ``ok``, and the edges get :data:`EDGE_EPS` of
    slack (see :func:`edge_status`; :func:`clamp_to_arm` then puts x back on the arm).
    """
    V = world_vertices(part, pose_a)
    slack = 0.0 if plain else EDGE_EPS
    # not plain: a vertex driven into the wall's foot (pymunk lets it sink up to penetration_tol into the corner)
    # reads past L and below the surface; up to WALL_SLACK that is no part off the end
    over = edge_status(V[:, 0], V[:, 1], h, L, back, slack, slack if plain else WALL_SLACK)
    flat = abs(tilt) < FLAT_TILT and bool(part.stable[k])
    if over == Status.BEHIND_JOINT or (flat and x + float(part.uL[k]) <= -back - slack):
        return Status.BEHIND_JOINT
    # with fixtures a part "flat" within FLAT_TILT may be turned about a vertex at the wall's foot (propped on
    # another part): its reach is read off its vertices on the surface (within WALL_SLACK of it), not off the flat
    # side's u_R — a vertex higher up may overhang past L above an end wall's top; and a part pressed into the end
    # wall (by another part) sits up to WALL_SLACK inside it without having left the arm
    if plain:
        reach = x + float(part.uR[k])
    else:
        low = V[:, 1] <= h + WALL_SLACK
        reach = float(V[low, 0].max()) if low.any() else x + float(part.uR[k])
    if over == Status.OFF_END or (flat and reach > L + (slack if plain else WALL_SLACK)) or x > L + slack:
        return Status.OFF_END
    if plain and not flat:
        return UNCONVERGED
    return Status.OK


def clamp_to_arm(part, x: float, k: int, L: float, back: float) -> float:
    """``x`` moved onto the starts :func:`throwmap.throw` accepts on side ``k`` (at most :data:`EDGE_EPS`
    away, see :func:`rest_status`): a part flat against a wall at the arm's end reads a collision
    slop past x = L − u_R and is reported at the last start, so the next throw starts from it."""
    from ..system.starts import _last_at_most  # the start rule's own rounding (throw.start_interval)

    hi = _last_at_most(float(part.uR[k]), float(L))
    lo = _last_at_most(float(part.uL[k]), -float(back))
    if x > hi:
        return hi
    if x <= lo:
        return math.nextafter(lo, math.inf)
    return x


def tilted_message(i: int, tilt: float, side: int) -> str:
    """Why part ``i`` settled tilted by ``tilt`` (rad) from ``side`` on a bare arm is ``unconverged``."""
    return (f"part {i}: came to rest {tilt:.3g} rad off side {side} on the bare arm, where nothing can hold it "
            f"tilted (flat within {FLAT_TILT:g} rad): result refused")
