"""Status codes and the layout of the per-throw record the kernels fill.

Integers so that batch kernels can return plain arrays; :class:`throwmap.records.outcome.Status`
gives them names.
"""

OK = 0  # came to rest on a stable side, on the arm
BEHIND_JOINT = 1  # a contact or a resting support vertex at x <= -arm.back (x <= 0 by default); on a tilted arm
# also a part that slides down to the joint
OFF_END = 2  # a contact beyond the arm's end, or a resting support vertex beyond it (x + u_R > length)
NO_REST = 3  # the impact cap was reached before rest (paper; rigid_body: UNRESOLVED), or on an unbounded arm the part slides (μ = 0, or tilted with
# μ < |tan α|) or rolls outward for ever
INVALID_START = 4  # the start was not admissible (batch with on_invalid="status"), or on a tilted arm not a rest
NO_CONTACT = 5  # retired: no model returns it (a search that hits its cap is UNRESOLVED with CAP_HIT = 1)
TIMEOUT = 6  # an engine run did not settle within its time limit
PENETRATION = 7  # an engine lost a contact: a vertex sank deeper than the tolerance (result refused)
INCONSISTENT = 8  # rigid-body Coulomb contact has no consistent solution here (Painlevé)
UNRESOLVED = 9  # the model cannot resolve this throw: its flight leaves the range it resolves (result refused)
# (spin angle ω t at first contact beyond kernels.flight.MAX_SPIN_ANGLE, where double precision no
# longer fixes the orientation; for "small_angle2" also g <= d ω², where its expansion has no contact;
# for "paper" and "rigid_body" also a contact search or integration that used its max_iter steps: CAP_HIT = 1)
UNCONVERGED = 10  # an engine run disagreed with its half-step rerun (result refused)

# record layout: one float64 row per throw (energies per unit mass, J/kg; impulses per unit mass, m/s)
T_FLIGHT = 0  # s
CONTACT_VERTEX = 1  # clockwise vertex index w_j of first contact
CONTACT_X = 2  # world x of the first contact point, m
VX_PRE = 3  # CM velocity and spin just before first impact (m/s, m/s, rad/s)
VY_PRE = 4
W_PRE = 5
VX_POST = 6  # just after first impact (paper Eq. 4)
VY_POST = 7
W_POST = 8
JX = 9  # first-impact impulse per unit mass, m/s
JY = 10
MU_IMPACT = 11  # |J_x| / J_y at first impact (friction ratio the no-slip impact needs)
E_RELEASE = 12  # total energy at release (kinetic + g (y_cm - h)), J/kg
K_PRE = 13  # kinetic energy just before the first impact, J/kg
K_POST = 14  # kinetic energy just after it, J/kg
U_IMPACT = 15  # potential energy at first impact, J/kg
E_FINAL = 16  # potential energy at rest, J/kg
N_IMPACTS = 17  # plastic impacts resolved (first contact, side landings, rocking)
N_FLIPS = 18  # side changes: landings on a side other than the last one landed on
MU_MAX = 19  # largest friction ratio needed at any impact or while pivoting
N_MIN = 20  # smallest normal force while pivoting, in units of m g (< 0: lift-off)
N_PULL = 21  # impacts whose normal impulse would have to pull (J_y < 0)
K_MAX_IMPACT_GAIN = 22  # largest (K_after - K_before) at any impact, J/kg (must be <= 0)
N_LIFTOFFS = 23  # contact phases that ended by the normal force reaching zero (the part hops)
N_SLIPS = 24  # sliding impacts and sliding contact phases (impulse or force outside the friction cone)
SLIP_DISTANCE = 25  # total distance contact points slid along the arm, m
T_REST = 26  # time from release until at rest, s (nan where a model does not resolve time)
PENETRATION_MAX = 27  # deepest penetration of any vertex into the arm or a fixture, m (engines; 0 for rigid models)
CAP_HIT = 28  # 1: the throw was refused (UNRESOLVED) because a search or integration used its max_iter steps; else 0
WHY = 29  # reason code of an UNRESOLVED throw a model refused (rigid_body's wall: kernels.rigid_body.wall_contact.WHY_*; 0 or nan: none)
NREC = 30
