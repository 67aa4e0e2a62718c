"""Model "rigid_body" on a moving arm: the arm's motion θ(t) of a throw realisation instead of the impulse.

The paper's release (Sec. III-B, Eq. 1) gives the resting part the arm point's velocity ω × r and
spin ω at t = 0 and never moves the arm. Here the arm follows θ(t) of any realisation
(:class:`~throwmap.system.motion.FiniteThrow`, :class:`~throwmap.system.motion.RecoilThrow`,
:class:`~throwmap.system.motion.SampledThrow`): the part rides it (sticking or sliding, flat or on one
vertex), separates where its contact forces vanish, flies, and lands on the arm wherever the arm is.

Architecture: everything is written in the ARM FRAME, where the arm is the fixed line y = h. Impacts
are instantaneous, so the static automaton's impact laws apply unchanged to arm-frame velocities; the
arm's motion enters only as smooth body forces (gravity turned by α + θ, centrifugal, Euler, Coriolis;
:mod:`.dynamics`) and as velocity jumps where θ̇ jumps. Once the arm has stopped, the state is handed
to the validated static automaton, so the landing and settling after the arm stops are its code.

Modules
-------
``profile``   θ, θ̇, θ̈ of a realisation and the times where they are not smooth
``dynamics``  the applied field and the constrained Newton–Euler solve of a contact mode
``phase``     the moving-arm phase: RK4 per mode, guards located by bisection, resets, mode selection
``handover``  one throw: the moving phase, then the static automaton
"""

from .handover import throw_moving
from .profile import ArmMotion, arm_motion

__all__ = ["ArmMotion", "arm_motion", "throw_moving"]
