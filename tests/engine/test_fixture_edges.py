"""A part held by fixtures at the arm's end is not "off the end" for a collision slop (engine/rest.py).

Pressed into an end wall, down in a cavity, the pymunk engine leaves a vertex ~10 µm inside
the wall: below the surface line and past x = L. That is a rest, not an escape; on the bare
arm the exact start rule still applies (x + u_R ≤ L).
"""

import math

import numpy as np

import throwmap as tm
from throwmap.engine.rest import EDGE_EPS, clamp_to_arm, edge_status, rest_status
from throwmap.system.starts import start_interval
from throwmap.system.pose import pose_at_rest


def test_edge_status_slack_only_where_asked():
    h, L = -0.01, 0.3
    vx, vy = np.array([L + 1.3e-5]), np.array([h - 0.0175])
    assert edge_status(vx, vy, h, L, 0.0) == tm.Status.OFF_END           # bare arm: exact
    assert edge_status(vx, vy, h, L, 0.0, slack=EDGE_EPS) is None        # fixtures: a slop is no escape
    assert edge_status(vx + 0.01, vy, h, L, 0.0, slack=EDGE_EPS) == tm.Status.OFF_END  # a real escape still is


def test_flat_rest_a_slop_past_the_end_is_ok_with_fixtures_and_clamped_onto_the_arm():
    part = tm.triangle_30_60_90()
    arm = tm.Arm(h=-0.01, length=0.3)
    k = 0
    hi = start_interval(part, arm, k)[1]
    x = hi + 8e-7  # the vertex 0.8 µm past L, as measured against an end wall
    pose = pose_at_rest(part, arm.h, x, k)
    assert rest_status(part, pose, x, k, 0.0, arm.h, arm.length, 0.0, True) == tm.Status.OFF_END
    assert rest_status(part, pose, x, k, 0.0, arm.h, arm.length, 0.0, False) == tm.Status.OK
    xc = clamp_to_arm(part, x, k, arm.length, 0.0)
    assert xc == hi and xc + part.uR[k] <= arm.length
    assert tm.throw(part, arm, xc, k, 0.0, model="paper").status != tm.Status.INVALID_START
    assert clamp_to_arm(part, 0.1, k, arm.length, 0.0) == 0.1  # inside: unchanged
    assert math.isclose(clamp_to_arm(part, -0.5, k, arm.length, 0.0), -part.uL[k], abs_tol=1e-12)
