"""Optional MuJoCo cross-check of the impulse throw (model string ``"engine:mujoco"``).

Simulates the paper's impulse throw (Sec. III-B) — the part at rest on ``side``
with CM at ``x`` gets the arm's velocity ω × r = ω(−(h + d_k), x) and spin ω at
t = 0, the arm stays still — with MuJoCo's soft-contact solver, and reads the
result back in throwmap's terms (:class:`~throwmap.throws.outcome.ThrowOutcome`).

``mujoco`` is an optional extra (``pip install 'throwmap[mujoco]'``), imported
only when a simulation runs; :func:`mujoco_model_xml` needs nothing beyond the
standard library.

Model
-----
*Planar motion.* MuJoCo's z axis is up, so throwmap's plane (x, y) is MuJoCo's
(x, z). The part body has three joints: a slide along x, a slide along z, and a
hinge about −y. A rotation by θ about +y takes +x toward −z (clockwise in the
(x, z) plane seen with x right and z up), so the hinge axis is (0, −1, 0): a
positive hinge angle is a CCW rotation in (x, y). With the body at the origin
and the part's CM-centred vertices ``w`` as the body-frame geometry, the joint
coordinates are exactly throwmap's pose: ``qpos = (x, y, φ)`` with
``vertex_j = (x, y) + R(φ) w_j`` (:mod:`throwmap.throws.trajectory`), and ``qvel`` is
``(ẋ, ẏ, φ̇)``. ``tests/test_mujoco_backend.py`` checks this against MuJoCo's
own world geometry.

*Part.* A convex prism (mesh geom): the polygon at ±``thickness``/2 along the
out-of-plane axis. Its inertia is explicit (``<inertial>``): mass ``part.mass``,
CM at the body origin, in-plane moment ``mass·ρ²`` (the other two principal
moments are set equal to it; the joints make them irrelevant). The mesh's own
volume never enters.

*Arm.* A static box whose top face is z = h over 0 ≤ x ≤ L (L = ``arm.length``,
or ``x + 2 m`` when the arm is unbounded), friction ``arm.mu`` with condim 3
(μ = 0 becomes condim 1, frictionless). Gravity is −g along z.

*μ = ∞* becomes :data:`NO_SLIP_MU` = 10, not a huge number: MuJoCo needs a
finite μ, and a large one spoils its contact solver. Measured on the triangle
grid of the tests (ω = 3–5 rad/s): with the pyramidal cone μ = 10 already lets
vertices sink > 1 mm (status ``penetration``) and μ ≥ 100 always does; with the
elliptic cone (the default here) μ = 10 keeps the post-impact spin within 4 %
of ω of Eq. (4), μ = 100 is off by 7 % (median) to 46 % and μ = 1000 by up to
68 %. The no-slip impacts and pivots of these throws need μ ≲ 1.3.

*Contact parameters* (the point of this backend). MuJoCo's defaults — solref
(0.02 s, 1), solimp (0.9, 0.95, 1 mm), friction mixed as the larger of the two
geoms' (the part geom's default is 1) — make a soft, springy contact that sinks
and rebounds on impact, so the impact is neither plastic nor no-slip. The tuned
settings (:class:`MujocoSettings`) use a stiff, heavily over-damped contact:
solref ``(2·timestep, 10)`` (time constant 2 Δt, damping ratio 10: the normal
velocity dies at a rate ≈ 1/Δt, the penetration recovers slowly without a
rebound), solimp ``(0.99, 0.999, 0.1 mm)`` (impedance close to 1 within
0.1 mm), multi-point convex collision (``multiccd``: a flat side rests on two
contacts, not one wobbling point), the elliptic friction cone (the pyramidal one
needs μ ≲ 5) and contact priority on the arm (its μ is used exactly, not
max(μ, 1)). With ``defaults=True`` none of this is written and MuJoCo's own
defaults apply (including its default for multiccd, which MuJoCo 4 turned on;
without multiccd a part resting on a side never settles: status ``timeout``).

Reading the run
---------------
Every step the part's vertices are placed from ``qpos``. A vertex's *gap* is its
height above the arm's top (y − h) when it is over the arm (0 ≤ x ≤ L); its
*penetration* is its distance to the nearest arm face (top, joint end, far end)
when inside the box. The record (:mod:`throwmap.kernels.codes`):

* ``T_FLIGHT``: the first step after release at which a vertex over the arm has
  gap ≤ 0, interpolated linearly in the gap between that step and the previous
  one. ``CONTACT_VERTEX``/``CONTACT_X``: the lowest vertex then, and its x.
* ``VX/VY/W_PRE``: the state at that step, which MuJoCo has not yet touched
  (contacts act from the next step), with ẏ moved back to ``T_FLIGHT`` by gravity.
* ``VX/VY/W_POST``: the state once the impact has settled into pivoting — the
  first step at which the contact vertex moves slower than
  :data:`POST_SPEED_FRACTION` (5 %) of its pre-impact speed, or
  :data:`POST_WINDOW` (10 ms) after the contact if that comes first. The spin is
  moved back to ``T_FLIGHT`` by the gravity torque about the contact vertex over
  that window (``(ρ² + |r|²) Δφ̇ = −g ∫ (x − x_c) dt``), so that it compares with
  the instantaneous impact of Eq. (4); the velocities are left as measured.
* ``JX``/``JY``: the contact's impulse per unit mass over that window (Δv with
  gravity's −g Δt removed); ``MU_IMPACT`` = |JX|/JY.
* ``N_IMPACTS``: vertex touch-downs (gap ≤ 0 after being above
  :data:`TOUCH_HYSTERESIS` = 0.1 mm, or never having touched since release);
  ``N_LIFTOFFS``: times the whole part left the arm after the first contact.
* ``E_RELEASE``, ``K_PRE``, ``K_POST``, ``U_IMPACT``, ``E_FINAL``,
  ``K_MAX_IMPACT_GAIN`` (first impact only) per unit mass, as the kernels do.
* ``T_REST``: start of the ``settle_hold`` window in which the CM speed stayed
  below ``settle_speed`` and the spin below ``settle_spin``.
* ``PENETRATION_MAX``: the deepest vertex penetration over the run, m.

Not resolved (left nan): ``N_FLIPS``, ``MU_MAX``, ``N_MIN``, ``N_PULL``,
``N_SLIPS``, ``SLIP_DISTANCE``.

Status: ``PENETRATION`` as soon as a vertex is deeper than ``penetration_tol``
(the run stops; the result is refused); ``BEHIND_JOINT``/``OFF_END`` when every
vertex has dropped below the arm's top (x ≤ 0: behind the joint, else past the
end) or when the settled part has its CM outside [0, L], its CM below the arm's
top, its left support vertex at x ≤ 0 or its CM beyond the end; ``TIMEOUT`` when
it has not settled by ``t_max``; else ``OK`` with ``(x, side)`` from
:func:`~throwmap.throws.trajectory.state_from_pose`. Unlike model ``"paper"``, a part
that comes to rest with its CM on the arm and a support vertex past the end is
``OK`` here (it is supported); the paper model calls any contact beyond the end
``OFF_END``.

Agreement with model "paper"
----------------------------
Measured on the grid of ``tests/test_mujoco_backend.py`` (canonical triangle on
``Arm(h=-0.01, mu=1.5)``, ω = 3, 4, 5 rad/s, x = 0.1–0.4 m, every stable side;
the 22 throws whose paper throw keeps contact): tuned settings — status and side
agree on 100 %, |Δx| median 0.02 mm, max 0.12 mm, first-impact spin
|ω⁺ − ω⁺_Eq.4| median 0.8 %, max 2.3 % of ω. MuJoCo's defaults — every throw
refused (the part sinks > 1 mm); allowed to finish (tolerance 2 cm): 95 %
agree, |Δx| median 1.5 mm, max 3.9 mm, spin error median 29 %, max 63 % of ω
(median 69 % of |ω⁺|). Most of the tuned error is MuJoCo's semi-implicit Euler
flight, whose height lags by g·t·Δt/2 so that the part lands about one step
early; a 0.2 ms step halves it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from ..system.arm import Arm
from ..errors import ThrowmapError
from ..kernels import codes as C
from ..throws.outcome import Status, ThrowOutcome
from ..system.part import Part
from ..throws.throw import check_start
from ..throws.trajectory import Trajectory, pose_at_rest, state_from_pose

__all__ = ["MujocoSettings", "mujoco_model_xml", "mujoco_throw", "MODEL_NAME", "NO_SLIP_MU"]

MODEL_NAME = "engine:mujoco"
NO_SLIP_MU = 10.0
"""Friction coefficient given to MuJoCo for μ = ∞ (MuJoCo needs a finite number)."""
UNBOUNDED_EXTRA = 2.0
"""Arm length simulated beyond the start x when ``Arm.length`` is None, m."""
ARM_DEPTH = 0.05
"""Depth of the arm box below its top face, m."""
POST_SPEED_FRACTION = 0.05
"""The impact has settled into pivoting when the contact vertex is slower than this fraction of its pre-impact speed."""
POST_WINDOW = 0.01
"""Longest wait after the first contact for the post-impact state, s."""
TOUCH_HYSTERESIS = 1e-4
"""A vertex counts as having left the arm once its gap exceeds this, m (impact counting)."""


def _mujoco():
    """Import MuJoCo, or say how to install it."""
    try:
        import mujoco
    except ImportError:
        raise ThrowmapError("engine", "MuJoCo is not installed: pip install 'throwmap[mujoco]'") from None
    return mujoco


def _finite(value, key: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ThrowmapError(key, f"must be a number, got {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise ThrowmapError(key, f"must be finite, got {value!r}")
    return v


@dataclass(frozen=True, slots=True)
class MujocoSettings:
    """Numerical settings of :func:`mujoco_throw` (SI units).

    timestep : MuJoCo's fixed step, s (> 0, ≤ 2 ms).
    solref : contact ``(timeconst s, dampratio)``; ``None``: ``(2·timestep, 10)``,
        a stiff over-damped contact (plastic impact, no rebound). MuJoCo's direct
        form ``(−stiffness, −damping)`` (both < 0) is accepted too.
    solimp : contact impedance ``(dmin, dmax, width m[, midpoint, power])``.
    multiccd : multi-point convex collision (a side rests on two contacts).
    cone : MuJoCo's friction cone, ``"elliptic"`` or ``"pyramidal"``.
    contact_priority : the arm geom has priority, so exactly ``arm.mu`` is used
        (otherwise MuJoCo takes the larger of the arm's and the part's μ, the part
        geom keeping MuJoCo's default 1).
    defaults : write none of solref/solimp/multiccd/cone/priority: MuJoCo's own
        defaults, kept to show how wrong they are for plastic impacts (``timestep``
        is still used).
    settle_speed, settle_spin, settle_hold : settled when the CM is slower than
        ``settle_speed`` (m/s) and the spin below ``settle_spin`` (rad/s) for
        ``settle_hold`` (s).
    t_max : give up after this much simulated time (status ``timeout``), s.
    penetration_tol : a vertex deeper than this in the arm (m) means MuJoCo lost
        the contact: status ``penetration``, result refused.
    thickness : depth of the prism along the out-of-plane axis, m.
    """

    timestep: float = 5e-4
    solref: tuple | None = None
    solimp: tuple = (0.99, 0.999, 1e-4, 0.5, 2)
    multiccd: bool = True
    contact_priority: bool = True
    cone: str = "elliptic"
    defaults: bool = False
    settle_speed: float = 1e-3
    settle_spin: float = 1e-2
    settle_hold: float = 0.05
    t_max: float = 5.0
    penetration_tol: float = 1e-3
    thickness: float = 0.02

    def __post_init__(self):
        for f in fields(self):
            key = f"mujoco.{f.name}"
            v = getattr(self, f.name)
            if f.name in ("multiccd", "contact_priority", "defaults"):
                if not isinstance(v, (bool, np.bool_)):
                    raise ThrowmapError(key, f"must be true or false, got {v!r}")
                object.__setattr__(self, f.name, bool(v))
            elif f.name == "cone":
                if v not in ("elliptic", "pyramidal"):
                    raise ThrowmapError(key, f"must be 'elliptic' or 'pyramidal', got {v!r}")
            elif f.name == "solref":
                if v is None:
                    continue
                vals = self._tuple(v, key, (2,))
                if not ((vals[0] > 0 and vals[1] > 0) or (vals[0] < 0 and vals[1] <= 0)):
                    raise ThrowmapError(
                        key, f"must be (timeconst > 0, dampratio > 0) or (-stiffness < 0, -damping ≤ 0), got {v!r}"
                    )
                object.__setattr__(self, f.name, vals)
            elif f.name == "solimp":
                vals = self._tuple(v, key, (3, 5))
                dmin, dmax, width = vals[:3]
                if not (0 < dmin < 1 and 0 < dmax < 1):
                    raise ThrowmapError(key, f"dmin and dmax must lie in (0, 1), got {v!r}")
                if width <= 0:
                    raise ThrowmapError(key, f"width must be > 0 m, got {v!r}")
                if len(vals) == 5 and not (0 < vals[3] < 1 and vals[4] >= 1):
                    raise ThrowmapError(key, f"midpoint must lie in (0, 1) and power be ≥ 1, got {v!r}")
                object.__setattr__(self, f.name, vals)
            else:
                x = _finite(v, key)
                if x <= 0:
                    raise ThrowmapError(key, f"must be > 0, got {v!r}")
                object.__setattr__(self, f.name, x)
        if self.timestep > 2e-3:
            raise ThrowmapError("mujoco.timestep", f"must be ≤ 2e-3 s to resolve impacts, got {self.timestep!r}")
        if self.settle_hold < 4 * self.timestep:
            raise ThrowmapError(
                "mujoco.settle_hold", f"must cover at least 4 steps ({4 * self.timestep:g} s), got {self.settle_hold!r}"
            )
        if self.t_max < self.settle_hold:
            raise ThrowmapError("mujoco.t_max", f"must be ≥ settle_hold ({self.settle_hold:g} s), got {self.t_max!r}")

    @staticmethod
    def _tuple(v, key, lengths) -> tuple:
        counts = " or ".join(map(str, lengths))
        try:
            vals = tuple(v)
        except TypeError:
            raise ThrowmapError(key, f"must be a sequence of {counts} numbers, got {v!r}") from None
        if len(vals) not in lengths:
            raise ThrowmapError(key, f"must have {counts} numbers, got {v!r}")
        return tuple(_finite(c, key) for c in vals)

    @property
    def contact_solref(self) -> tuple:
        """The solref written to the model: ``solref`` or ``(2·timestep, 10)``."""
        return self.solref if self.solref is not None else (2.0 * self.timestep, 10.0)


def _f(v: float) -> str:
    return repr(float(v))


def _arm_length(arm: Arm, x: float | None) -> float:
    if arm.length is not None:
        return arm.length
    return max(0.0 if x is None else float(x), 0.0) + UNBOUNDED_EXTRA


def mujoco_model_xml(part: Part, arm: Arm, settings: MujocoSettings = MujocoSettings(), x: float | None = None,
                     side: int | None = None) -> str:
    """MJCF text of the part on the arm (see the module docstring).

    ``x`` (m) sets the simulated length of an unbounded arm (``x + 2 m``); with
    ``x`` and ``side`` the model also has a keyframe ``"rest"``: the part at rest
    on ``side`` with its CM at ``x``. Needs no MuJoCo installed.
    """
    if not isinstance(part, Part):
        raise ThrowmapError("part", f"must be a Part, got {type(part).__name__}")
    if not isinstance(arm, Arm):
        raise ThrowmapError("arm", f"must be an Arm, got {type(arm).__name__}")
    if not isinstance(settings, MujocoSettings):
        raise ThrowmapError("settings", f"must be MujocoSettings, got {type(settings).__name__}")
    if x is not None:
        x = _finite(x, "x")
    s = settings
    L = _arm_length(arm, x)
    t2 = 0.5 * s.thickness
    verts = " ".join(f"{_f(wx)} {_f(sy)} {_f(wy)}" for wx, wy in part.w for sy in (-t2, t2))
    inertia = part.moment_of_inertia
    mu = NO_SLIP_MU if math.isinf(arm.mu) else arm.mu
    condim = 1 if mu == 0.0 else 3
    friction = f'friction="{_f(max(mu, 1e-5))} 0 0"'
    if s.defaults:
        option_extra, flags = "", ""
        arm_contact = f'{friction} condim="{condim}"'
        part_contact = f'condim="{condim}"'
    else:
        ref, imp = s.contact_solref, s.solimp
        sol = f'solref="{" ".join(map(_f, ref))}" solimp="{" ".join(map(_f, imp))}"'
        flags = f'\n    <flag multiccd="{"enable" if s.multiccd else "disable"}"/>'
        option_extra = f' cone="{s.cone}"'
        arm_contact = f'{friction} condim="{condim}" {sol}'
        part_contact = f'condim="{condim}" {sol}'
        if s.contact_priority:
            arm_contact += ' priority="1"'
    key = ""
    if x is not None and side is not None:
        px, py, phi = pose_at_rest(part, arm.h, x, side)
        key = f'\n  <keyframe>\n    <key name="rest" qpos="{_f(px)} {_f(py)} {_f(phi)}"/>\n  </keyframe>'
    box = f'size="{_f(0.5 * L)} {_f(s.thickness)} {_f(0.5 * ARM_DEPTH)}"'
    box += f' pos="{_f(0.5 * L)} 0 {_f(arm.h - 0.5 * ARM_DEPTH)}"'
    name = part.name.replace('"', "'").replace("&", "and").replace("<", "(").replace(">", ")")
    return f"""<mujoco model="throwmap {name}">
  <compiler angle="radian"/>
  <option timestep="{_f(s.timestep)}" gravity="0 0 {_f(-arm.g)}"{option_extra}>{flags}
  </option>
  <asset>
    <mesh name="part" vertex="{verts}"/>
  </asset>
  <worldbody>
    <geom name="arm" type="box" {box} {arm_contact}/>
    <body name="part">
      <joint name="x" type="slide" axis="1 0 0"/>
      <joint name="y" type="slide" axis="0 0 1"/>
      <joint name="phi" type="hinge" axis="0 -1 0"/>
      <inertial pos="0 0 0" mass="{_f(part.mass)}" diaginertia="{_f(inertia)} {_f(inertia)} {_f(inertia)}"/>
      <geom name="part" type="mesh" mesh="part" {part_contact}/>
    </body>
  </worldbody>{key}
</mujoco>
"""


def _vertices(w: np.ndarray, q) -> tuple[np.ndarray, np.ndarray]:
    c, s = math.cos(q[2]), math.sin(q[2])
    return q[0] + c * w[:, 0] - s * w[:, 1], q[1] + s * w[:, 0] + c * w[:, 1]


def mujoco_throw(part: Part, arm: Arm, x: float, side: int, omega: float,
                 settings: MujocoSettings = MujocoSettings(), *, record: bool = False):
    """The impulse throw of ``part`` resting at ``(x, side)`` with release rate ``omega`` (rad/s), in MuJoCo.

    Returns a :class:`~throwmap.throws.outcome.ThrowOutcome` (model ``"engine:mujoco"``);
    with ``record=True`` the pair ``(ThrowOutcome, Trajectory)``, sampled every
    step. Raises :class:`~throwmap.errors.InvalidStateError` for an inadmissible
    start (as :func:`throwmap.throws.throw` does) and :class:`~throwmap.errors.ThrowmapError`
    when MuJoCo is not installed. Deterministic: same inputs, same result.
    """
    if not isinstance(part, Part):
        raise ThrowmapError("part", f"must be a Part, got {type(part).__name__}")
    if not isinstance(arm, Arm):
        raise ThrowmapError("arm", f"must be an Arm, got {type(arm).__name__}")
    if not isinstance(settings, MujocoSettings):
        raise ThrowmapError("settings", f"must be MujocoSettings, got {type(settings).__name__}")
    x0, k0, om = check_start(part, arm, x, side, omega)
    mujoco = _mujoco()
    s = settings
    model = mujoco.MjModel.from_xml_string(mujoco_model_xml(part, arm, s, x0, k0))
    data = mujoco.MjData(model)

    h, g, L = arm.h, arm.g, _arm_length(arm, x0)
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
    t_event = 0.0
    ts, poses, contacts, events = [], [], [], []

    step = 0
    while True:
        t = step * dt
        q = data.qpos.copy()
        v = data.qvel.copy()
        vx_, vy_ = _vertices(w, q)
        over = (vx_ >= 0.0) & (vx_ <= L)
        gap = np.where(over, vy_ - h, np.inf)
        pen = np.where(over & (vy_ < h), np.minimum(np.minimum(h - vy_, vx_), L - vx_), 0.0)
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
        if np.all(vy_ < h):  # wholly below the arm's top: it left the arm
            status, t_event = (Status.BEHIND_JOINT if q[0] <= 0.0 else Status.OFF_END), t
            events.append((t, "left arm"))
            break
        if step >= n_max:
            status, t_event = Status.TIMEOUT, t
            events.append((t, "timeout"))
            break
        mujoco.mj_step(model, data)
        step += 1

    q = data.qpos.copy()
    xe, ke, _tilt = state_from_pose(part, tuple(q))
    rec[C.E_FINAL] = g * (q[1] - h)
    if status == Status.OK:
        if q[1] < h or not (0.0 <= xe <= L):
            status = Status.BEHIND_JOINT if xe <= 0.0 else Status.OFF_END
        elif xe + float(part.uL[ke]) <= 0.0:
            status = Status.BEHIND_JOINT
        elif xe > L:
            status = Status.OFF_END
    out = ThrowOutcome.from_record(part, x0, k0, om, MODEL_NAME, xe, ke, status, rec)
    if not record:
        return out
    traj = Trajectory(
        t=np.asarray(ts), arm_angle=np.zeros(len(ts)), poses=np.asarray(poses).reshape(-1, 1, 3),
        parts=(part,), h=h, length=L, contacts=tuple(contacts), events=tuple(events), source=MODEL_NAME,
        meta={"settings": s, "t_end": t_event if status != Status.OK else float(rec[C.T_REST])},
    )
    return out, traj
