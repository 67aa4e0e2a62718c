"""The impulse throw in MuJoCo, read back in throwmap's terms (see :mod:`throwmap.engine.mujoco`, "Reading the run")."""

from __future__ import annotations

import math

import numpy as np

from ...errors import InvalidStateError, ThrowmapError
from ...kernels import codes as C
from ...system.arm import Arm
from ...system.part import Part
from ...records.outcome import Status, ThrowOutcome
from ...system.starts import check_start
from ...records.trajectory import Trajectory
from ...system.pose import pose_at_rest, state_from_pose
from ..reach import lengths, unbounded_message
from ...system.motion import ImpulseThrow
from ..rest import edge_status, rest_status, tilted_message
from ..scene import Placement, Scene
from .model import mujoco_model_xml
from .settings import (
    MODEL_NAME,
    POST_SPEED_FRACTION,
    POST_WINDOW,
    TOUCH_HYSTERESIS,
    UNBOUNDED_EXTRA,
    MujocoSettings,
)

__all__ = ["mujoco_throw"]


def _mujoco():
    """Import MuJoCo, or say how to install it."""
    try:
        import mujoco
    except ImportError:
        raise ThrowmapError("engine", "MuJoCo is not installed: pip install 'throwmap[mujoco]'") from None
    return mujoco


def _vertices(w: np.ndarray, q) -> tuple[np.ndarray, np.ndarray]:
    c, s = math.cos(q[2]), math.sin(q[2])
    return q[0] + c * w[:, 0] - s * w[:, 1], q[1] + s * w[:, 0] + c * w[:, 1]


def mujoco_throw(part: Part, arm: Arm, x: float, side: int, omega: float,
                 settings: MujocoSettings = MujocoSettings(), *, record: bool = False):
    """The impulse throw of ``part`` resting at ``(x, side)`` with release rate ``omega`` (rad/s), in MuJoCo.

    Returns a :class:`~throwmap.records.outcome.ThrowOutcome` (model ``"engine:mujoco"``);
    with ``record=True`` the pair ``(ThrowOutcome, Trajectory)``, sampled every
    step. Raises :class:`~throwmap.errors.InvalidStateError` for an inadmissible
    start (as :func:`throwmap.throws.throw` does) and :class:`~throwmap.errors.ThrowmapError`
    when MuJoCo is not installed. Deterministic: same inputs, same result.

    An unbounded arm is simulated as long as the throw needs
    (:mod:`throwmap.engine.reach`); a part at the end of the longest simulated arm
    is refused as ``unresolved``, never ``off_end``.
    """
    if not isinstance(part, Part):
        raise InvalidStateError("part", f"must be a Part, got {type(part).__name__}")
    if not isinstance(arm, Arm):
        raise InvalidStateError("arm", f"must be an Arm, got {type(arm).__name__}")
    if not isinstance(settings, MujocoSettings):
        raise InvalidStateError("settings", f"must be MujocoSettings, got {type(settings).__name__}")
    x0, k0, om = check_start(part, arm, x, side, omega)
    mujoco = _mujoco()
    # an unbounded arm is simulated long enough for the throw (:mod:`throwmap.engine.reach`); a part that
    # reaches the simulated end reruns on a longer one, and at the end of the longest is refused (unresolved)
    tried = lengths(Scene(arm, (Placement(part, x=x0, side=k0),)), ImpulseThrow(om), UNBOUNDED_EXTRA, settings.t_max)
    for n, L in enumerate(tried):
        res = _run(mujoco, part, arm, x0, k0, om, settings, record, L)
        out = res[0] if record else res
        if arm.length is None and out.status == Status.OFF_END:
            if n + 1 < len(tried):
                continue
            out = out.replace(status=Status.UNRESOLVED)
            out = out.replace(message=unbounded_message(L, tried))
            return (out, res[1]) if record else out
        return res
    raise AssertionError("unreachable")  # pragma: no cover


def _run(mujoco, part, arm, x0, k0, om, s, record, L):
    """One MuJoCo run of the throw on an arm ``L`` m long (see :func:`mujoco_throw`)."""
    model = mujoco.MjModel.from_xml_string(mujoco_model_xml(part, arm, s, x0, k0, length=L))
    data = mujoco.MjData(model)

    h, g, back = arm.h, arm.g, arm.back
    rho2 = part.radius_of_gyration**2
    w = np.asarray(part.w, dtype=float)
    n = w.shape[0]
    dk = float(part.d[k0])
    pose0 = pose_at_rest(part, h, x0, k0)
    v0 = (-(h + dk) * om, x0 * om, om)  # ω × r of the arm point at the CM, and spin ω (Sec. III-B)
    data.qpos[:] = pose0
    data.qvel[:] = v0
    mujoco.mj_forward(model, data)

    rec = np.full(C.NREC, np.nan)
    rec[C.E_RELEASE] = 0.5 * (v0[0] ** 2 + v0[1] ** 2 + rho2 * om * om) + g * dk
    rec[C.PENETRATION_MAX] = 0.0
    rec[C.N_IMPACTS] = 0.0
    rec[C.N_LIFTOFFS] = 0.0

    dt = s.timestep
    n_max = int(math.ceil(s.t_max / dt))
    n_hold = int(math.ceil(s.settle_hold / dt))
    # ω = 0: no throw, the resting contacts are not touch-downs
    touching = np.zeros(n, dtype=bool) if om > 0 else (part.vertices_at_rest(x0, k0, h)[:, 1] <= h + 1e-12)
    any_touch = False
    jc = -1
    t_c = math.nan
    post_done = False
    grav_int = 0.0  # ∫ (x_cm − x_contact) dt since the first contact, m·s
    vc_pre = 0.0
    gap_prev = math.inf
    calm = 0
    status = None
    message = ""
    t_event = 0.0
    ts, poses, contacts, events = [], [], [], []

    step = 0
    while True:
        t = step * dt
        q = data.qpos.copy()
        v = data.qvel.copy()
        vx_, vy_ = _vertices(w, q)
        over = (vx_ >= -back) & (vx_ <= L)
        gap = np.where(over, vy_ - h, np.inf)
        pen = np.where(over & (vy_ < h), np.minimum(np.minimum(h - vy_, vx_ + back), L - vx_), 0.0)
        pen_now = float(pen.max())
        if pen_now > rec[C.PENETRATION_MAX]:
            rec[C.PENETRATION_MAX] = pen_now
        if record:
            ts.append(t)
            poses.append(q)
            pts = [(data.contact[i].pos[0], data.contact[i].pos[2]) for i in range(data.ncon)]
            contacts.append(np.array(pts, dtype=float).reshape(-1, 2))
        if pen_now > s.penetration_tol:
            status, t_event = Status.PENETRATION, t
            message = (f"a vertex sank {pen_now * 1e3:.2f} mm into the arm at t = {t:.4f} s "
                       f"(> penetration_tol {s.penetration_tol * 1e3:g} mm); result refused")
            events.append((t, "penetration"))
            break
        gmin = float(gap.min())
        if step > 0:
            # vertex touch-downs (impacts) and lift-offs of the whole part
            new = (gap <= 0.0) & ~touching
            touching = (touching | (gap <= 0.0)) & (gap <= TOUCH_HYSTERESIS)
            if np.any(new):
                rec[C.N_IMPACTS] += float(np.count_nonzero(new))
                if jc < 0:  # first contact
                    jc = int(np.argmin(gap))
                    frac = gap_prev / (gap_prev - gmin) if math.isfinite(gap_prev) and gap_prev > gmin else 1.0
                    t_c = t - dt + frac * dt
                    rec[C.T_FLIGHT] = t_c
                    rec[C.CONTACT_VERTEX] = jc
                    rec[C.CONTACT_X] = float(vx_[jc])
                    vyp = v[1] + g * (t - t_c)
                    rec[C.VX_PRE], rec[C.VY_PRE], rec[C.W_PRE] = v[0], vyp, v[2]
                    rec[C.K_PRE] = 0.5 * (v[0] ** 2 + vyp**2 + rho2 * v[2] ** 2)
                    ycm = q[1] - (t - t_c) * 0.5 * (v[1] + vyp)
                    rec[C.U_IMPACT] = g * (ycm - h)
                    rx, ry = vx_[jc] - q[0], vy_[jc] - q[1]
                    vc_pre = math.hypot(v[0] - v[2] * ry, v[1] + v[2] * rx)
                    events.append((t_c, "impact"))
            if any_touch and not np.any(touching):
                rec[C.N_LIFTOFFS] += 1.0
            any_touch = bool(np.any(touching))
        if jc >= 0 and not post_done:
            rx, ry = vx_[jc] - q[0], vy_[jc] - q[1]
            if t > t_c:
                grav_int += (q[0] - vx_[jc]) * dt
            vc = math.hypot(v[0] - v[2] * ry, v[1] + v[2] * rx)
            if t > t_c and (vc <= POST_SPEED_FRACTION * vc_pre or t - t_c >= POST_WINDOW):
                post_done = True
                wp = v[2] + g * grav_int / (rho2 + rx * rx + ry * ry)
                rec[C.VX_POST], rec[C.VY_POST], rec[C.W_POST] = v[0], v[1], wp
                rec[C.JX] = v[0] - rec[C.VX_PRE]
                rec[C.JY] = v[1] - rec[C.VY_PRE] + g * (t - t_c)
                if rec[C.JY] > 0:
                    rec[C.MU_IMPACT] = abs(rec[C.JX]) / rec[C.JY]
                rec[C.K_POST] = 0.5 * (v[0] ** 2 + v[1] ** 2 + rho2 * v[2] ** 2)
                rec[C.K_MAX_IMPACT_GAIN] = rec[C.K_POST] - rec[C.K_PRE]
        gap_prev = gmin
        # settled?
        if math.hypot(v[0], v[1]) < s.settle_speed and abs(v[2]) < s.settle_spin:
            calm += 1
        else:
            calm = 0
        if calm > n_hold:
            rec[C.T_REST] = t - n_hold * dt
            status = Status.OK
            events.append((rec[C.T_REST], "rest"))
            break
        gone = edge_status(vx_, vy_, h, L, back)  # a vertex below the surface past an edge: it left the arm
        if gone is None and np.all(vy_ < h):  # wholly below the arm's top
            gone = Status.BEHIND_JOINT if q[0] <= -back else Status.OFF_END
        if gone is not None:
            status, t_event = gone, t
            events.append((t, "left arm"))
            break
        if step >= n_max:
            status, t_event = Status.TIMEOUT, t
            message = f"not settled after {s.t_max:g} s"
            events.append((t, "timeout"))
            break
        mujoco.mj_step(model, data)
        step += 1

    q = data.qpos.copy()
    xe, ke, tilt = state_from_pose(part, tuple(q))
    rec[C.E_FINAL] = g * (q[1] - h)
    if status == Status.OK:  # ok only as a start throw() accepts, as the analytic models and pymunk
        if q[1] < h:
            status = Status.BEHIND_JOINT if xe <= -back else Status.OFF_END
        else:
            status = rest_status(part, tuple(q), xe, ke, tilt, h, L, back, True)
            if status == Status.UNCONVERGED:
                message = tilted_message(0, tilt, ke)
    out = ThrowOutcome.from_record(part, x0, k0, om, MODEL_NAME, xe, ke, status, rec)
    if message:
        out = out.replace(message=message)  # why the result was refused
    if not record:
        return out
    traj = Trajectory(
        t=np.asarray(ts), arm_angle=np.zeros(len(ts)), poses=np.asarray(poses).reshape(-1, 1, 3),
        parts=(part,), h=h, length=L, contacts=tuple(contacts), events=tuple(events), source=MODEL_NAME,
        meta={"settings": s, "t_end": t_event if status != Status.OK else float(rec[C.T_REST])},
    )
    return out, traj
