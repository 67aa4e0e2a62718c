"""After an impulse elsewhere (the wall's on the arm, the arm's on the wall) a vertex on a line is excluded from that
line's guard only while it leaves it: its velocity away from the line decides, spin included. A vertex pressed back
gets −1 (a second contact); a vertex that has sunk below the arm gets its depth as slack in the wall modes; a
contact leaving the wall's top corner gets the separating window of its opening rate."""

import math

import numpy as np
import pytest

from throwmap.kernels.flight import separating_window
from throwmap.kernels.rigid_body.flight import rearm_window
from throwmap.kernels.rigid_body.impact import C_OPEN
from throwmap.kernels.rigid_body.modes import SINK_TOL
from throwmap.kernels.rigid_body.wall import corner_bounds, rearm_wall_window, sink_slack
from throwmap.kernels.rigid_body.wall_lean import LN_FLIGHT, _dispatch

G = 9.81
H = -0.01
# a square's corners (m) about its CM: vertex 0 at (+0.02, −0.02), lower right
W = np.array([[0.02, -0.02], [-0.02, -0.02], [-0.02, 0.02], [0.02, 0.02]])
LJ = math.hypot(0.02, 0.02)


@pytest.mark.parametrize("om", [2.0, -2.0])
def test_an_arm_vertex_leaves_the_line_only_if_its_spin_lifts_it(om):
    y = H + 0.02  # vertex 0 on the arm's line, the CM at rest: the spin alone moves the vertex (v_n = ω r_x)
    win = rearm_window(y, 0.0, 0.0, 0.0, om, W, 0, H, G, 0.0, 1e-9)
    if om > 0:  # r_x > 0: ω > 0 lifts it
        assert win == pytest.approx(separating_window(om * 0.02, G + om * om * LJ), rel=1e-12) and win > 0
    else:  # pressed into the arm: a second contact
        assert win == -1.0


@pytest.mark.parametrize("vx", [-0.1, 0.1])
def test_a_face_vertex_leaves_the_wall_only_moving_away_from_it(vx):
    L = 0.3
    x = L - 0.02  # vertex 0 on the wall's face x = L
    win = rearm_wall_window(False, x, H + 0.05, vx, 0.0, 0.0, 0.0, W, 0, L, H, 0.05, 0.0, G, 1e-9)
    if vx < 0:  # moving away from the face (−x)
        assert win == pytest.approx(separating_window(0.1, G), rel=1e-12) and win > 0
    else:
        assert win == -1.0


def test_the_sink_slack_is_the_depth_below_the_arm():
    size = LJ
    assert sink_slack(0.2, H + 0.02 - 1e-4, 0.0, W, 0, H) == pytest.approx(1e-4 + SINK_TOL * size, rel=1e-9)
    assert sink_slack(0.2, H + 0.03, 0.0, W, 0, H) == pytest.approx(SINK_TOL * size, rel=1e-9)  # above: none
    assert sink_slack(0.2, H + 0.02 - 1e-4, 0.0, W, -1, H) == 0.0


def test_a_contact_leaving_the_walls_top_corner_gets_its_opening_window():
    # one contact, on the corner, opened by the impact: the corner at (0.02, 0) from the CM touches the part's
    # edge x = 0.02 whose normal into the part is nrm = (−1, 0); the part moving along nrm (−x) opens it
    pts = np.array([[0.02, 0.0]])
    nrm = np.array([[-1.0, 0.0]])
    out = _dispatch(0.28, H + 0.06, -0.05, 0.0, 0.0, 0.0, W, 3e-4, 0.5, 0.0, 0.0, G, LJ, 1, pts, nrm,
                    np.array([0.0]), np.array([0]), np.array([2]), np.array([C_OPEN]))
    code, kc, win_c = out[0], out[6], out[7]
    m2 = corner_bounds(0.02, 0.0, -0.05, 0.0, 0.0, 0.0, G, 1.0)[0]
    assert code == LN_FLIGHT and kc == 0
    assert win_c == pytest.approx(separating_window(0.05, m2), rel=1e-12) and win_c > 0.0
