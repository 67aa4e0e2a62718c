"""Optional MuJoCo cross-check of the impulse throw (model string ``"engine:mujoco"``).

Simulates the paper's impulse throw (Sec. III-B) — the part at rest on ``side``
with CM at ``x`` gets the arm's velocity ω × r = ω(−(h + d_k), x) and spin ω at
t = 0, the arm stays still — with MuJoCo's soft-contact solver, and reads the
result back in throwmap's terms (:class:`~throwmap.records.outcome.ThrowOutcome`).

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
``vertex_j = (x, y) + R(φ) w_j`` (:mod:`throwmap.records.trajectory`), and ``qvel`` is
``(ẋ, ẏ, φ̇)``. ``tests/engine/test_mujoco_backend.py`` checks this against MuJoCo's
own world geometry.

*Part.* A convex prism (mesh geom): the polygon at ±``thickness``/2 along the
out-of-plane axis. Its inertia is explicit (``<inertial>``): mass ``part.mass``,
CM at the body origin, in-plane moment ``mass·ρ²`` (the other two principal
moments are set equal to it; the joints make them irrelevant). The mesh's own
volume never enters.

*Arm.* A static box whose top face is z = h over 0 ≤ x ≤ L (L = ``arm.length``,
or, when the arm is unbounded, the bound on the flight plus 2 m, longer on
reruns: :mod:`throwmap.engine.reach`), friction ``arm.mu`` with condim 3
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
(the run stops; the result is refused); ``BEHIND_JOINT``/``OFF_END`` as soon as
a vertex is below the surface line past an edge of the arm (x < −back, the arm's
extent behind the joint, :attr:`throwmap.Arm.back`; x > L) or every vertex is
below the arm's top (on an unbounded arm a part past the simulated end reruns on
a longer arm and, past the longest, is ``UNRESOLVED``); ``TIMEOUT`` when it has not settled by ``t_max``. A settled
part is ``OK`` only as :func:`throwmap.engine.rest.rest_status` reads it, the same
rule as the pymunk engine and the analytic models: flat on a stable side with
both support vertices on the arm (else ``BEHIND_JOINT``/``OFF_END``, or
``UNCONVERGED`` tilted on the bare arm), with ``(x, side)`` from
:func:`~throwmap.system.pose.state_from_pose`.

Agreement with model "paper"
----------------------------
Measured on the grid of ``tests/engine/test_mujoco_backend.py`` (canonical triangle on
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

from .model import mujoco_model_xml
from .settings import MODEL_NAME, NO_SLIP_MU, MujocoSettings
from .throw import mujoco_throw

__all__ = ["MujocoSettings", "mujoco_model_xml", "mujoco_throw", "MODEL_NAME", "NO_SLIP_MU"]
