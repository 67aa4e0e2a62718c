"""A unit slip is warned about whatever its sign: a negative angle, vertices far out at negative x and y."""

import pytest

import throwmap as tm
from throwmap.errors import ScaleWarning
from throwmap.system.system import check_alpha


def test_a_large_negative_angle_is_warned():
    with pytest.warns(ScaleWarning, match="alpha = -1.2 rad"):
        check_alpha(-1.2)


def test_vertices_far_out_at_negative_coordinates_are_warned():
    with pytest.warns(ScaleWarning, match="part.vertices = 17 m"):
        tm.Part.from_vertices([(0, 0), (0, -8.5), (-17, 0)], mass=0.05)
