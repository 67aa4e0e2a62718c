"""Full rigid-body simulation of throws in pymunk (Chipmunk2D): the "engine" model.

The scene (:mod:`.world`): the arm is a kinematic body turning about the joint,
built from convex solids under its surface profile, with the fixtures on it;
parts are convex polygons with their own mass, CM and inertia; restitution is
zero and friction is set per pair of bodies.

Stepping (:mod:`.stepping`)
---------------------------
While any part is in or near contact the space advances by the fixed step
``dt`` (0.125 ms by default, the converged value), or by ``coarse_dt`` in smooth
contact phases (every part touching, arm still, no new contact for
``impact_window``). While every part is clear of everything by more than
``flight_margin``, the parts are advanced by the exact ballistic solution, in
leaps short enough that no vertex can reach any shape; this removes pymunk's
free-flight drift of g·t·dt/2 and most of the steps.

Checks (:mod:`.checks`)
-----------------------
* penetration: every millisecond, each part vertex is tested against the arm,
  fixtures and other parts; deeper than ``penetration_tol`` → status
  ``penetration`` — that result is refused, and the run retried with a finer step.
* escape: a vertex below the surface line past an edge of the arm (x < −back,
  :attr:`throwmap.Arm.back`; x > L), or a CM below the arm's underside: the part
  has left the arm, ``behind_joint`` or ``off_end`` at once (also after every
  exact-flight leap).
* landing ahead: while a vertex not in contact is about to touch, no coarse steps.
* energy: after the arm stops no part may gain mechanical energy (several parts: their total,
  since parts pushing each other trade energy).
* settling: after the arm has stopped, every part slower than ``settle_speed``
  and ``settle_spin`` for ``settle_hold`` → at rest, ``t_max`` → ``timeout``. A
  part at rest is ``ok`` only flat on a stable side with both support vertices
  on the arm (:mod:`throwmap.engine.rest`, as the analytic models).

Verification (:mod:`.verify`)
-----------------------------
Hard runs (deep penetration, repeated side changes, energy gain, timeout) are
rerun at half the step; where the two disagree the run is refused as
``unconverged``, with the reason in its message.

Friction (:mod:`.friction`)
---------------------------
Each contact's friction is set before every solve to the pair's μ, capped where
Chipmunk's solver would diverge (μ |K_nt| > 0.7 K_nn); without the cap μ = ∞
lost contacts in most long throws.

Contacts, impacts, hops and flips are counted in :mod:`.contacts`; the loop is
:func:`.run.simulate`, its result :class:`.result.EngineRun`. pymunk itself is
imported only when a run starts.

The C helper (:mod:`.native`)
-----------------------------
The hot paths — the friction hook and the exact solve (called per contact per
step), blocks of steps with the arm parked, the checks of each round, clearance
and leaps — run in a small C module built with cffi on first use, with the same
arithmetic as their Python versions: a run is the same bit for bit with or
without it. Where it cannot be built (no C compiler) or ``THROWMAP_NATIVE=0``,
the Python versions run (several times slower).
"""

from .result import EngineRun
from .run import simulate

__all__ = ["EngineRun", "simulate"]
