"""Shared data for the viewer's tests: a made-up two-part motion (no engine) with an orbit in its meta."""

from __future__ import annotations

import math

import numpy as np
import pytest

from throwmap.system.catalogue import triangle_30_60_90
from throwmap.system.fixtures import Wall
from throwmap.records.trajectory import Trajectory
from throwmap.system.pose import pose_at_rest


def made_up_trajectory(throws: int = 6, per_throw: float = 1.0, rate: float = 240.0) -> Trajectory:
    """Two triangles on a 0.5 m arm with a 5 cm wall: each 'throw' the arm swings up and back while part 0 hops
    2 cm along it in an arc and part 1 rests; a contact under each part while it rests (SI units)."""
    part = triangle_30_60_90()
    h, length = 0.02, 0.5
    t = np.arange(int(throws * per_throw * rate) + 1) / rate
    k = np.minimum((t // per_throw).astype(int), throws - 1)
    u = (t - k * per_throw) / per_throw  # 0…1 within a throw
    arm = 0.25 * np.sin(math.pi * u) ** 2
    x0 = 0.10 + 0.02 * k + 0.02 * np.clip((u - 0.3) / 0.4, 0, 1)
    lift = 0.04 * np.sin(math.pi * np.clip((u - 0.3) / 0.4, 0, 1))
    poses = np.zeros((t.size, 2, 3))
    for i, (a, x, dy) in enumerate(zip(arm, x0, lift)):
        px, py, phi = pose_at_rest(part, h, x, 1, a)
        poses[i, 0] = (px, py + dy, phi + 3 * dy)
        poses[i, 1] = pose_at_rest(part, h, 0.35, 1, a)
    contacts = tuple(np.array([[poses[i, 1, 0], poses[i, 1, 1] - part.d[1]]]) if lift[i] > 0 else
                     np.array([[poses[i, 0, 0], poses[i, 0, 1] - part.d[1]], [poses[i, 1, 0], poses[i, 1, 1] - part.d[1]]])
                     for i in range(t.size))
    events = tuple(e for j in range(throws) for e in ((j * per_throw + 0.3 * per_throw, "release"),
                                                    (j * per_throw + 0.7 * per_throw, "impact v1"),
                                                    (j * per_throw + 0.9 * per_throw, "rest")))
    orbit = {"throw": list(range(throws + 1)), "x": [[0.10 + 0.02 * j, 0.35] for j in range(throws + 1)],
             "side": [[1, 1]] * (throws + 1), "phase": ["drop"] + ["high"] * throws,
             "t": [None] + [j * per_throw for j in range(throws)]}
    return Trajectory(t, arm, poses, (part, part), h, length, (Wall(0.05, 0.01),), contacts, events, "made-up",
                      {"orbit": orbit})


@pytest.fixture(scope="session")
def two_part_trajectory() -> Trajectory:
    return made_up_trajectory()
