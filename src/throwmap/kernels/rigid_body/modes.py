"""Modes, guard/event codes, reason codes and numerical constants of the "rigid_body" hybrid automaton.

Integer codes so that the Numba kernels can pass them around; the automaton is
described in :mod:`throwmap.kernels.rigid_body`. A throw the automaton cannot follow ends as
status UNRESOLVED with a reason code (``WHY_*``, :data:`WHY_MESSAGES`) in its record (:func:`refuse`).
"""

import math

from numba import njit

from .. import codes as C

HALF_PI = 0.5 * math.pi
TWO_PI = 2.0 * math.pi

DTH = 0.03
"""Largest pivot-angle change of one RK4 step, rad (sets the integration accuracy of PIVOT_SLIDE)."""
N_BISECT = 56
"""Bisection steps locating a guard inside an RK4 step (≈ 1e-17 of the step)."""
N_ARC = 16
"""Points per arc at which the Zeno rule checks the friction demand, and the sticking phase samples |F|/N."""
SINK_TOL = 1e-9
"""How far (relative to the part's size) a vertex that just left the arm may sink below where it started while
the part moves on the wall before its arm guard fires: rounding, not motion (:func:`~.wall.sink_slack`)."""
MU_SKID = 1e6
"""Friction coefficient standing in for μ = ∞ in PIVOT_SLIDE (the μ → ∞ limit)."""

# modes
MODE_FLIGHT = 0
MODE_STICK = 1  # PIVOT_STICK
MODE_SLIDE = 2  # PIVOT_SLIDE
MODE_SELECT = 3  # a contact just began: choose stick / slide / flight (select_contact_mode)
MODE_REST = 4  # terminal: the throw's status is decided
MODE_LEAN = 6  # on the arm and the wall at once: the multi-contact impact and what follows (wall_lean.py)

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
EV_WALL = 10  # wall_reach: a vertex is on the wall and the pivoting part turns into it

# kinds of the impact reset (coulomb_impact)
IMP_STICK = 0
IMP_SLIDE = 1
IMP_SEPARATE = 2
IMP_INCONSISTENT = -1

# outcomes of the wall-contact modes WALL_CONTACT and CORNER (wall_slide.wall_contact, wall_corner.corner_contact)
WC_FLIGHT = 0
WC_ARM = 1
WC_REFUSE = 2
WC_INCONSISTENT = 3
WC_CAP = 4
WC_FACE = 5
"""Outcomes of :func:`~.wall_slide.wall_contact` and :func:`~.wall_corner.corner_contact` (WC_FACE: a vertex
reached the face, corner only)."""

# reasons of an UNRESOLVED throw (record WHY)
WHY_NONE = 0
WHY_WALL_TOP = 1
WHY_WALL_SLIDE = 2
WHY_TWO_CONTACT = 3
WHY_LADDER = 4
WHY_CORNER = 5
WHY_SLIDE_WALL = 6
WHY_WALL_EDGE = 7
WHY_CORNER_VERTEX = 8
WHY_EVENT_CAP = 9
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
    WHY_EVENT_CAP: ("the part had not come to rest after max_impacts mode changes (its contacts chatter, e.g. an "
                    "edge rocking on the wall's top corner while a vertex slides on the arm): not resolved by "
                    "rigid_body (raise the model option max_impacts, or use model 'engine')"),
    # the moving-arm phase (moving/phase.py: WHY_EVENTS, WHY_STEPS, WHY_NO_MODE, WHY_LAND)
    101: "more events than the cap while the arm moves (e.g. rocking on the moving arm): not resolved by rigid_body",
    102: "more integration steps than the cap while the arm moves: not resolved by rigid_body",
    103: ("no consistent contact mode (stick, slide, lift) after an event while the arm moves: not resolved by "
          "rigid_body"),
    104: "a vertex not adjacent to the pivot touched the moving arm (a degenerate polygon): not modelled by rigid_body",
}
"""Why a throw was refused (status UNRESOLVED), by reason code: the wall's (1–8), the event cap (9) and the moving
arm's (101–104)."""
WHY_COL = getattr(C, "WHY", -1)
"""Record column receiving the reason code of a refusal (``kernels.codes.WHY``), if the record has one."""


@njit(cache=True)
def refuse(rec, why):
    """Status UNRESOLVED for a walled throw the automaton cannot follow; the reason ``why`` goes to the record."""
    if WHY_COL >= 0:
        rec[WHY_COL] = why
    return C.UNRESOLVED
