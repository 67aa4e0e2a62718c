"""Checks of a run between steps: penetration, clearance (for exact flight), escape, flips and settling.

* penetration: each part vertex is tested against the arm, fixtures and other
  parts; deeper than ``penetration_tol`` means pymunk lost the contact (it can
  lose grazing high-friction contacts: zero impulse, a vertex sinking
  millimetres into the arm) and the run's result is refused.
* clearance: a lower bound of the distance from a part to everything else,
  which bounds how long it may fly on the exact parabola (:mod:`.stepping`).
* escape: a part with a vertex below the surface line beyond either edge of the
  arm (x < −back or x > L), or whose CM drops below the arm's underside, has
  left the arm: ``behind_joint`` behind the joint's half of the arm, else ``off_end``.
* energy: once the arm has stopped, no part may gain mechanical energy (zero
  restitution); a gain beyond what position correction explains (g times twice
  ``penetration_tol``) marks a run that blew up (:func:`.run.simulate` reruns it).
* near: a vertex about to land (no coarse steps then, :mod:`.run`).
* settling: every part slower than ``settle_speed`` and ``settle_spin``.
"""

from __future__ import annotations

import math

from ...records.outcome import Status
from ..rest import EDGE_EPS
from .contacts import nearest_side
from .world import BOX_TOL, World

__all__ = ["BOX_TOL", "GONE", "all_slow", "body_state", "clearance", "energy", "escape", "inspect", "probe",
           "sunk_into"]


def body_state(w: World, i: int) -> tuple:
    """Part i's ``(x, y, angle, vx, vy, spin)`` in the world frame (m, rad, m/s, rad/s), read once for the
    checks of one instant (:func:`inspect`, :func:`energy`, :func:`all_slow` take it instead of reading again)."""
    cp = w.cp
    b = w.bodies_h[i]
    p, v = cp.position(b), cp.velocity(b)
    return p.x, p.y, cp.angle(b), v.x, v.y, cp.spin(b)


def inspect(w: World, i: int, arm_angle: float, ca: float, sa: float, horizon: float = 0.0, state=None):
    """Part i against the arm at ``arm_angle`` (rad; ``ca``, ``sa`` its cos and sin).

    Returns ``(depth, x, y, phi, over, near)``: the deepest penetration (m) of
    part i's vertices into the arm (its solid: −back ≤ x ≤ L, less than its
    thickness below the surface), fixtures or other parts; its CM ``(x, y)`` (m)
    and angle ``phi`` (rad) in the arm frame (``phi`` unwrapped); ``over``: −1 if
    a vertex is below the surface line (by more than :data:`throwmap.engine.rest.EDGE_EPS`) behind the
    arm's back edge x = −back, +1 if beyond its end x = L, else 0 (the part is
    over an edge: it has left the arm); ``near``: a vertex not in contact could
    touch within ``horizon`` (s), i.e. its gap is below ``flight_margin`` plus its
    approach speed times ``horizon`` (a landing is coming: no coarse steps). ``state``: part i's
    :func:`body_state` if already read.
    """
    cp = w.cp
    b = w.bodies_h[i]
    px, py, a, vx, vy, om = body_state(w, i) if state is None else state
    deepest = 0.0
    over = 0
    near = False
    L, h, back, thick, margin = w.L, w.h, w.back, w.thickness, w.margin
    c, s = math.cos(a), math.sin(a)
    if w.plain_arm:
        for wx, wy in w.wlists[i]:
            X = px + c * wx - s * wy
            Y = py + s * wx + c * wy
            xa = ca * X + sa * Y
            ya = -sa * X + ca * Y
            d = h - ya
            if d > EDGE_EPS and (xa < -back or xa > L):
                over = -1 if xa < -back else 1
            # fast path: depth below the flat surface line, in the arm frame
            if -back <= xa <= L and d <= thick:
                if d > deepest:
                    deepest = d
                if horizon > 0.0 and d < -EDGE_EPS:
                    vn = -sa * (vx - om * (Y - py)) + ca * (vy + om * (X - px))
                    if -d < margin + max(0.0, -vn) * horizon:
                        near = True
        return deepest, ca * px + sa * py, -sa * px + ca * py, a - arm_angle, over, near
    lo, hi = -back - EDGE_EPS, L + EDGE_EPS  # fixtures at the ends: see throwmap.engine.rest.edge_status
    distance, NULL, to_world = cp.distance, cp.NULL, cp.to_world
    others = w.others_h[i]
    # a shape whose arm-frame box (inflated by reach) misses the vertex is farther than reach: it can
    # neither hold the vertex (depth) nor be within margin + speed × horizon of it (near); not queried
    if horizon > 0.0:
        reach = margin + (math.hypot(vx, vy) + abs(om) * w.R[i]) * horizon + BOX_TOL
        boxes = [None if bx is None else (bx[0] - reach, bx[1] + reach, bx[2] - reach, bx[3] + reach)
                 for bx in w.boxes[i]]
    else:
        boxes = w.boxes_tol[i]  # inflated by 0.0 + BOX_TOL
    for v in w.wlists[i]:
        wx, wy = v
        X = px + c * wx - s * wy
        Y = py + s * wx + c * wy
        xa = ca * X + sa * Y
        ya = -sa * X + ca * Y
        if h - ya > EDGE_EPS and (xa < lo or xa > hi):
            over = -1 if xa < lo else 1
        q = None
        closest = math.inf
        for sh, bx in zip(others, boxes):
            if bx is not None and (xa < bx[0] or xa > bx[1] or ya < bx[2] or ya > bx[3]):
                continue
            if q is None:
                q = to_world(b, v)
            d = distance(sh, q, NULL)
            if d < -deepest:
                deepest = -d
            if d < closest:
                closest = d
        if q is not None and horizon > 0.0 and EDGE_EPS < closest:
            speed = math.hypot(vx - om * (q.y - py), vy + om * (q.x - px))
            if closest < margin + speed * horizon:
                near = True
    return deepest, ca * px + sa * py, -sa * px + ca * py, a - arm_angle, over, near


GONE = (None, Status.BEHIND_JOINT, Status.OFF_END)
"""The status of each escape code of :func:`probe`."""


def sunk_into(w: World, i: int) -> str:
    """What part i's deepest vertex has sunk into now, for the penetration refusal's message: ``"the arm"``,
    ``"the wall"`` or ``"part j"`` (:attr:`World.names`), ``"a shape"`` where no vertex is inside any (m; the
    same shapes :func:`inspect` measures the depth against). One part on a plain arm: the depth is below the
    arm's surface, so the arm."""
    if w.plain_arm:
        return "the arm"
    cp = w.cp
    b = w.bodies_h[i]
    deepest, name = 0.0, "a shape"
    for v in w.wlists[i]:
        q = cp.to_world(b, v)
        for sh, what in zip(w.others_h[i], w.names[i]):
            d = cp.distance(sh, q, cp.NULL)
            if d < deepest:
                deepest, name = d, what
    return name


def probe(w: World, i: int, horizon: float = 0.0, flips: bool = False):
    """Everything the periodic checks read of part i at one instant (the arm at its angle now), from one reading of
    its state:
    ``(x, y, angle, vx, vy, spin)`` (:func:`body_state`), then :func:`inspect`'s ``(depth, x, y, phi, over, near)``,
    its :func:`energy` (J/kg), whether it is slower than ``settle_speed`` and ``settle_spin`` (:func:`all_slow`),
    with ``flips`` :func:`~.contacts.nearest_side`'s ``(side, tilt)`` of ``phi`` (else ``(0, 0.0)``), and whether it
    has left the arm (:func:`escape`; a vertex beyond the end with a wall there does not count) as a code, ``GONE[code]``
    its status. :meth:`.native.NativeRun.probe` gives the same numbers from the C helper."""
    arm_angle = w.cp.angle(w.arm_h)
    st = body_state(w, i)
    pen, xa, ya, phi, over, near = inspect(w, i, arm_angle, math.cos(arm_angle), math.sin(arm_angle), horizon, st)
    k, tilt = nearest_side(w.betas[i], phi) if flips else (0, 0.0)
    slow = math.hypot(st[3], st[4]) < w.settle[0] and abs(st[5]) < w.settle[1]
    gone = escape(w, i, xa, ya, w.arm_thickness, 0 if w.end_wall and over > 0 else over)
    code = 0 if gone is None else 1 if gone == Status.BEHIND_JOINT else 2
    return (*st, pen, xa, ya, phi, over, near, energy(w, i, st), slow, k, tilt, code)


def clearance(w: World, i: int, enough: float = -math.inf) -> float:
    """Lower bound of the distance (m) from part i to every other shape: the least distance over part i's
    vertices to the other shapes, the arm's corners to part i and the other parts' vertices to part i.

    ``enough`` (m): a caller that only needs to know whether the bound exceeds ``enough`` may get, where it
    does not, the distance of one pair found within ``enough`` (at most ``enough``, not the least): the pair
    that gave the last bound (``w.clear_hint[i]``) is tried first, and where it is still within ``enough``
    the rest is not searched. Where the bound exceeds ``enough`` it is returned exactly as without it.
    """
    if w.native is not None:
        return w.native.clearance(i, enough)
    cp = w.cp
    distance, NULL, to_world = cp.distance, cp.NULL, cp.to_world
    b = w.bodies_h[i]
    shp = w.shapes_h[i]
    hint = w.clear_hint[i]
    if hint is not None:
        kind, j, k = hint
        if kind == 0:  # part i's vertex k to shape j
            d = distance(w.others_h[i][j], to_world(b, w.wlists[i][k]), NULL)
        elif kind == 1:  # arm corner k to part i
            aa = cp.angle(w.arm_h)
            cx, cy = w.corners[k]
            d = distance(shp, (math.cos(aa) * cx - math.sin(aa) * cy, math.sin(aa) * cx + math.cos(aa) * cy), NULL)
        else:  # part j's vertex k to part i
            d = distance(shp, to_world(w.bodies_h[j], w.wlists[j][k]), NULL)
        if d <= enough:
            return d
    best = math.inf
    others = w.others_h[i]
    for k, v in enumerate([to_world(b, v) for v in w.wlists[i]]):
        for j, s in enumerate(others):
            d = distance(s, v, NULL)
            if d < best:
                best, hint = d, (0, j, k)
    aa = cp.angle(w.arm_h)
    ca, sa = math.cos(aa), math.sin(aa)
    for k, (cx, cy) in enumerate(w.corners):
        d = distance(shp, (ca * cx - sa * cy, sa * cx + ca * cy), NULL)
        if d < best:
            best, hint = d, (1, 0, k)
    for j in range(w.n):
        if j != i:
            bj = w.bodies_h[j]
            for k, v in enumerate([to_world(bj, v) for v in w.wlists[j]]):
                d = distance(shp, v, NULL)
                if d < best:
                    best, hint = d, (2, j, k)
    w.clear_hint[i] = hint
    return best


def escape(w: World, i: int, xa: float, ya: float, arm_thickness: float, over: int = 0):
    """Status of part i if it has left the arm, else None.

    Left: a vertex below the surface line beyond either edge (``over`` from
    :func:`inspect`: −1 behind the back edge x = −back, +1 beyond the end), or its
    CM ``(xa, ya)`` (m, arm frame) below the arm's underside (less 3 × the part's
    radius), or below its top beyond either end; ``behind_joint`` on the joint's
    half of the arm, else ``off_end``.
    """
    if over:
        return Status.BEHIND_JOINT if over < 0 else Status.OFF_END
    R, L, h = w.R[i], w.L, w.h
    if ya < h - arm_thickness - 3.0 * R or (ya < h and (xa < -w.back - R or xa > L + R)):
        return Status.BEHIND_JOINT if xa < 0.5 * L else Status.OFF_END
    return None


def energy(w: World, i: int, state=None) -> float:
    """Part i's mechanical energy per unit mass in the world frame, J/kg: ½(v² + ρ²φ̇²) + g y
    (``state``: its :func:`body_state` if already read)."""
    _, y, _, vx, vy, om = body_state(w, i) if state is None else state
    return 0.5 * (vx * vx + vy * vy + w.rho2[i] * om * om) + w.g * y


def all_slow(w: World, tracks, speed: float, spin: float, states=None) -> bool:
    """Every part still on the arm is slower than ``speed`` (m/s) and spins slower than ``spin`` (rad/s)
    (``states``: each part's :func:`body_state` if already read, None where not)."""
    for i, tr in enumerate(tracks):
        if tr.fell is not None:
            continue
        st = states[i] if states is not None and states[i] is not None else body_state(w, i)
        if not (math.hypot(st[3], st[4]) < speed and abs(st[5]) < spin):
            return False
    return True
