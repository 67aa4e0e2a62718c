"""Poses at rest (:mod:`throwmap.system.pose`): a part pushed against a wall touches it and never passes it."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from throwmap.feeder import random_plate
from throwmap.system.pose import pose_against_wall, pose_at_rest, world_vertices


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 10_000), wall=st.floats(0.2, 0.6), h=st.floats(-0.03, 0.0))
def test_a_part_against_a_wall_touches_it_on_every_stable_side(seed, wall, h):
    part = random_plate(np.random.default_rng(seed))
    for k in part.stable_sides:
        pose = pose_against_wall(part, h, wall, k)
        v = world_vertices(part, pose)
        assert v[:, 0].max() == pytest.approx(wall, abs=1e-12)  # touches, never passes
        # flat on side k: the same orientation and height as resting there, only moved along the arm
        rest = pose_at_rest(part, h, pose[0], k)
        assert pose == pytest.approx(rest, abs=1e-12)
        assert v[:, 1].min() == pytest.approx(h, abs=1e-12)


def test_an_overhanging_neighbour_keeps_the_side_off_the_wall():
    """A parallelogram resting on its 10 cm base, its top shifted 3 cm along it: at one end the top overhangs the base
    by 3 cm, at the other it leans back. Against a wall the base's end touches it in one orientation and stops 3 cm
    short of it in the mirror image."""
    from throwmap.system.part import Part

    gaps = []
    for sign in (1.0, -1.0):
        verts = [(sign * x, y) for x, y in ((0.0, 0.0), (0.10, 0.0), (0.13, 0.04), (0.03, 0.04))]
        part = Part.from_vertices(verts if sign > 0 else verts[::-1], mass=0.05)
        k = int(np.argmin(part.d))  # the base: the side nearest the CM (2 cm below it)
        assert part.d[k] == pytest.approx(0.02) and k in part.stable_sides
        v = world_vertices(part, pose_against_wall(part, 0.0, 0.5, k))
        assert v[:, 0].max() == pytest.approx(0.5, abs=1e-12)
        gaps.append(0.5 - v[np.abs(v[:, 1]) < 1e-9][:, 0].max())
    assert sorted(gaps) == pytest.approx([0.0, 0.03], abs=1e-12)
