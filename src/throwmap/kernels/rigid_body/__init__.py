"""Model "rigid_body": exact planar rigid-body dynamics of one polygon on the arm line.

Extends model "paper" (Sec. III, Eqs. 1–4; :mod:`~throwmap.kernels.paper`,
:mod:`~throwmap.kernels.roll`) by dropping its two contact assumptions: the
contact vertex may *lift off* (the normal force reaches zero, Sec. III-C's
"the part does not bounce" is no longer imposed) and it may *slip* (Coulomb
friction μ, Sec. III-C's "friction is high enough" is no longer imposed).
Unit mass, inertia ρ² about the CM, gravity −g ŷ, arm line y = h for
0 ≤ x ≤ length, plastic impacts (zero restitution).

Pose convention (as :mod:`throwmap.records.trajectory`): world vertex_j = (x, y) + R(φ) w_j;
flat on side k, φ = β_k (mod 2π) and y = h + d_k.

Hybrid system
-------------
Modes

``FLIGHT``       ballistic motion (Eq. 1 from an arbitrary state).
``PIVOT_STICK``  one vertex A fixed on the line: compound pendulum
                 I_A θ̈ = −g ℓ_A cos θ (θ = angle of A→CM, I_A = ρ² + ℓ_A²), as roll.py.
``PIVOT_SLIDE``  one vertex A on the line, sliding with slip velocity v_A ≠ 0:
                 2 DOF (x_A, θ), friction −μ N sgn(v_A).
``FLAT_SLIDE``   a side flat on the line, sliding at deceleration μ g (closed form); with
                 μ = 0 it never stops (to the arm's edge: BEHIND_JOINT / OFF_END, or
                 NO_REST outward on an unbounded arm).
``REST``         terminal.

Guards (named as in the code, ``EV_*``)

``touch``        FLIGHT: the earliest time any vertex reaches y = h moving down
                 (:func:`throwmap.kernels.flight.first_contact`: safe lower-bound
                 stepping from any flight state, shared with model "paper").
``leave_arm``    a contact point at x ≤ −back (BEHIND_JOINT; ``Arm.back``, default 0)
                 or x > length (OFF_END).
``land``         PIVOT_*: θ reaches θa (side j−1 flat) or θb (side j flat): the
                 second vertex B of that side touches (``EV_LAND_A``/``EV_LAND_B``).
``lift_off``     PIVOT_*: the normal force N reaches 0 (``EV_LIFT_OFF``). While
                 sticking, N/(m g) = 1 − k + 3k s² − 2k e s (s = sin θ, k = ℓ²/I,
                 e = E/(g ℓ)); the crossing is solved analytically in s.
``slip``         PIVOT_STICK: |F| = μ N, F/(m g) = k cos θ (3s − 2e) (``EV_SLIP``).
``stick``        PIVOT_SLIDE: the slip velocity reaches 0 (``EV_STICK``).
``painleve``     PIVOT_SLIDE: the normal-force equation's effective mass
                 D = 1 + ℓ² cos θ (cos θ + μσ sin θ)/ρ² reaches 0: no consistent
                 Coulomb solution (status INCONSISTENT).

Resets

``release``      rest on ``side`` at x0; CM velocity ω(−(h+d), x0), spin ω (Eq. 1).
``impact``       one vertex, plastic, Coulomb (:func:`.impact.coulomb_impact`): the no-slip
                 impulse of Eq. 4 if it lies in the friction cone (|J_t| ≤ μ J_n);
                 otherwise Routh's compression-only process in impulse space
                 (slide, slip may stop and stick or reverse, ends when the normal
                 velocity is 0). A no-slip impulse with J_n < 0 is counted in N_PULL.
``land_side``    B touches while A is on the line: first the impulse at B alone
                 (A free); accepted if A then moves up (lifts); otherwise both
                 vertices stop normal motion (v_y = ω = 0) and a friction impulse
                 ≤ μ J_n removes horizontal velocity; what remains slides the part
                 flat (FLAT_SLIDE) to rest. Then rest (stable side) or tip from rest
                 about the vertex the CM overhangs (unstable side), as roll.py.
``lift``         PIVOT_* → FLIGHT with the contact's velocity; the departed vertex is
                 excluded from ``touch`` for a window in which its exact 4th-order
                 Taylor lower bound (|G''''| ≤ ω⁴ℓ) stays positive.
``slip_start``   PIVOT_STICK → PIVOT_SLIDE; the sense σ is the one for which the
                 sliding dynamics is consistent (σ ẍ_A > 0, D > 0).
``stick_start``  PIVOT_SLIDE → PIVOT_STICK when static friction suffices, else
                 slide the other way.
``rocking_rest`` (Zeno, decided on purpose as roll.py): after a sticking landing on a
                 stable side with kinetic energy below both topple barriers, rest —
                 only if the next swings at that energy about both support vertices
                 keep N > 0 and |F| ≤ μN (checked at 16 points per arc).

A wall at the arm's end (``wall_h`` > 0; :mod:`.wall`)
-----------------------------------------------------
Guards ``wall_touch`` (FLIGHT: a vertex reaches the face x = length below the top),
``corner_touch`` (FLIGHT: the top corner enters the part through an edge), ``wall_reach``
(PIVOT_*: a closed-form lower bound on θ, face or corner; PIVOT_SLIDE: a guard of the RK4
phase) and ``slide_hit`` (FLAT_SLIDE, closed form). Resets: ``wall_impact`` (the impact law
above along the contact's normal, μ_w), the flat slide's impact (stop dead, turn about the corner
vertex, or refuse), and every contact with the arm and the wall at once (a pivot that meets the
wall, a landing while on the wall, a third vertex): one velocity-level plastic impact at all
touching contacts (:mod:`.wall_lean`, the law of the engines). Modes on the wall:
WALL_CONTACT (a vertex pressed on the face, sliding or sticking: :mod:`.wall_slide`), CORNER (an
edge pressed on the top corner: :mod:`.wall_corner`), LADDER (a vertex on the arm and one on the
face sliding at both: :mod:`.wall_lean`); rests against the wall by exact cone statics, and
the Zeno limit of ever smaller impacts (speeds below ``V_STOP`` √(gℓ)) is a stop. What it cannot
follow ends as UNRESOLVED (reason codes ``WHY_*`` of :mod:`.modes`): an edge on the corner
moving with another contact, an edge flat on the arm or the face sliding while the part touches
the other surface, a vertex onto the corner or the wall's foot, a flat slide into the wall above
its top. A rest leaning on arm and wall reports the nearest side and the CM's x, as the engines do.

Numerics and accuracy (plainly)
-------------------------------
* FLIGHT is closed form; ``touch`` cannot miss a crossing (lower-bound stepping)
  and is Newton-polished, as in model "paper".
* PIVOT_STICK is closed form (:mod:`.stick_exact`, :mod:`.swing`): the energy is
  conserved, so the swing's path (reach the end ahead, or turn back where
  sin θ = e) follows from E and the sense of θ̇ as in roll.py; ``lift_off`` is the
  first root of N(s), a quadratic in s = sin θ, and ``slip`` the first root of
  μ²N² − F², a quartic in s isolated exactly through its critical points, so
  no excursion of |F|/N above μ is missed; θ̇ at the event comes from E and the
  time from an incomplete elliptic integral (Carlson's R_F), exact to rounding.
  The former RK4 phase (:func:`.stick.pivot_stick`, step Δθ ≤ DTH) is kept as
  the reference (:func:`throw_one_rigid_body_rk4`); it samples the slip guard at
  step ends only.
* PIVOT_SLIDE is integrated with classical RK4, step Δt = DTH/(|θ̇| + Ω)
  (Ω = √(g/ℓ), DTH = 0.03 rad), global θ error ~1e-8 rad; guards are checked at
  step ends and located on the RK4 step length (the RK4 step is the
  interpolant) by false position on the guard that fired, safeguarded by
  bisection, to a bracket of 1e-16 (t + τ) (:func:`.slide._locate_guard`).
* T_REST: when the Zeno rule decides rest, the (finite) remaining rocking time is
  not added: T_REST is the time of the deciding landing.
* Frictionless arm (μ = 0): every contact force is vertical, so the CM's
  horizontal velocity stays −(h + d) ω from the release (tested on whole
  trajectories); the Zeno rule then compares the kinetic energy relative to that
  horizontal motion with the topple barriers, and an unstable side landed on
  while sliding tips over its overhung vertex as a sliding pivot.
* FLAT_SLIDE assumes the part does not tip over its leading edge while it
  decelerates (not checked).

Trajectory output
-----------------
``traj`` (M, 4) receives rows (t, x_cm, y_cm, φ) every ``traj_dt`` s and at every
event; φ is continuous (not wrapped), the last row is the rest pose with
φ = β_k + 2π m. Rows not written are NaN: the number of samples is the number
of leading non-NaN rows (:func:`count_samples`). When M is too small, periodic
samples stop at M − 1 rows and the last row still receives the final pose.
M = 0 records nothing.

Modules (the automaton's pieces)
--------------------------------
``modes``        mode, guard/event and impact codes, numerical constants
``flight``       FLIGHT: guards touch (shared first contact) and leave_arm, reset lift
``impact``       the impact laws: one vertex (Coulomb/Routh or velocity-level), any normal, several
                 contacts at once; the impact records
``coulomb``      the guards of a Coulomb contact (lift_off, slip, stick), shared by the integrated modes
``bracket``      locating a guard inside an integration step, shared by the integrated modes
``stick``        PIVOT_STICK forces, and the RK4 sticking phase (reference)
``swing``        the closed-form swing: path, guard roots, elapsed time
``stick_exact``  PIVOT_STICK in closed form (the default)
``slide``        PIVOT_SLIDE, and the contact-mode selection (slip_start, stick_start)
``landing``      reset land_side and rocking_rest
``flat``         FLAT_SLIDE and REST (a side flat on the arm)
``trajectory``   trajectory rows
``automaton``    one throw: the loop over modes
``batch``        many throws: parallel kernels and their serial twins, chosen by batch size
``inputs``       the records the kernels take: the part, the arm (with its wall) and the run's limits
``tilt``         an arm at rest angle α: tilted sticking phase, flat slides and rests
``wall``         a wall at the arm's end: its geometry, the guards wall_touch and corner_touch,
                 the departure windows, the pivot's wall reset
``wall_statics`` rests against the wall by exact cone statics
``wall_slide``   WALL_CONTACT (a vertex pressed on the face)
``wall_corner``  CORNER (an edge pressed on the top corner)
``wall_lean``    LEAN and its LADDER (a vertex on the arm and one on the face)
"""

from .automaton import run_throw, throw_one_rigid_body, throw_one_rigid_body_rk4
from .batch import (PARALLEL_MIN, pick, throw_many_rigid_body, throw_many_rigid_body_rk4,
                    throw_many_rigid_body_rk4_serial, throw_many_rigid_body_serial)
from ..flight import departure_window
from .inputs import ArmArrays, PartArrays, RunLimits, arm_arrays, arm_record, part_arrays, run_limits
from .impact import LAW_ROUTH, LAW_VELOCITY, coulomb_impact
from .modes import (DTH, EV_BEHIND_JOINT, EV_INCONSISTENT, EV_LAND_A, EV_LAND_B, EV_LIFT_OFF, EV_NONE,
                    EV_OFF_END, EV_SLIP, EV_STEP_CAP, EV_STICK, IMP_INCONSISTENT, IMP_SEPARATE, IMP_SLIDE, IMP_STICK,
                    MODE_FLIGHT, MODE_REST, MODE_SELECT, MODE_SLIDE, MODE_STICK, MU_SKID, N_ARC, N_BISECT)
from .slide import pivot_slide, select_contact_mode, slide_rhs, slide_sense
from .stick import pivot_stick, stick_forces
from .stick_exact import pivot_stick_exact
from .swing import swing_time
from .trajectory import count_samples

__all__ = ["ArmArrays", "PartArrays", "RunLimits", "arm_arrays", "arm_record", "part_arrays", "run_limits",
           "LAW_ROUTH", "LAW_VELOCITY", "PARALLEL_MIN", "pick", "throw_many_rigid_body_serial",
           "throw_many_rigid_body_rk4_serial",
           "count_samples", "coulomb_impact", "departure_window", "pivot_slide", "pivot_stick",
           "pivot_stick_exact", "run_throw", "select_contact_mode", "slide_rhs", "slide_sense",
           "stick_forces", "swing_time", "throw_many_rigid_body", "throw_many_rigid_body_rk4",
           "throw_one_rigid_body", "throw_one_rigid_body_rk4"]
