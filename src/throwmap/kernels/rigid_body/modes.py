"""Modes, guard/event codes and numerical constants of the "rigid_body" hybrid automaton.

Integer codes so that the Numba kernels can pass them around; the automaton is
described in :mod:`throwmap.kernels.rigid_body`.
"""

import math

HALF_PI = 0.5 * math.pi
TWO_PI = 2.0 * math.pi

DTH = 0.03
"""Largest pivot-angle change of one RK4 step, rad (sets the integration accuracy of PIVOT_SLIDE)."""
N_BISECT = 56
"""Bisection steps locating a guard inside an RK4 step (≈ 1e-17 of the step)."""
N_ARC = 16
"""Points per arc at which the Zeno rule checks the friction demand, and the sticking phase samples |F|/N."""
MU_SKID = 1e6
"""Friction coefficient standing in for μ = ∞ in PIVOT_SLIDE (the μ → ∞ limit)."""

# modes
MODE_FLIGHT = 0
MODE_STICK = 1  # PIVOT_STICK
MODE_SLIDE = 2  # PIVOT_SLIDE
MODE_SELECT = 3  # a contact just began: choose stick / slide / flight (select_contact_mode)

# guard / event codes returned by the contact phases
EV_NONE = 0
EV_LAND_A = 1  # land: θ reached θa, side j−1 flat
EV_LAND_B = 2  # land: θ reached θb, side j flat
EV_LIFT_OFF = 3  # lift_off: the normal force reached 0
EV_SLIP = 4  # slip: |F| reached μN while sticking
EV_STICK = 5  # stick: the slip velocity reached 0 while sliding
EV_BEHIND_JOINT = 6  # leave_arm: a sliding contact reached x ≤ 0
EV_OFF_END = 7  # leave_arm: a sliding contact passed x = length
EV_INCONSISTENT = 8  # painleve: effective mass D ≤ 0 while sliding
EV_STEP_CAP = 9  # max_iter integration steps without an event

# kinds of the impact reset (coulomb_impact)
IMP_STICK = 0
IMP_SLIDE = 1
IMP_SEPARATE = 2
IMP_INCONSISTENT = -1
MODE_REST = 4  # terminal: the throw's status is decided
MODE_LEAN = 6  # on the arm and the wall at once: the multi-contact impact and what follows (wall_lean.py)
