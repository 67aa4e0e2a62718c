"""The feeder family: weights added by the parallel-axis theorem agree with the part built with them; proposed
places lie inside the plate near the target side; random plates are convex with the drawn size and mass."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import throwmap as tm
from throwmap.feeder import Weight, random_plate, weight_variants, with_weight
from throwmap.feeder.family import side_endpoints
from throwmap.system.geometry import point_in_convex_polygon
from throwmap.system.part import Part


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 10_000), m=st.floats(0.005, 0.2), s=st.floats(0.05, 0.95), t=st.floats(0.05, 0.95))
def test_a_weight_added_equals_the_part_built_with_it(seed, m, s, t):
    plate = random_plate(np.random.default_rng(seed))
    V = np.asarray(plate.vertices)
    c = V.mean(axis=0)
    p = c + s * (V[int(t * len(V))] - c)  # inside: between the vertex mean and a vertex
    a = with_weight(plate, Weight(m, tuple(p)))
    b = Part.from_vertices(plate.vertices, mass=plate.mass, point_masses=((m, tuple(p)),))
    assert a.mass == pytest.approx(b.mass, rel=1e-12)
    assert a.com == pytest.approx(b.com, abs=1e-12)
    assert a.radius_of_gyration == pytest.approx(b.radius_of_gyration, rel=1e-9)


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 10_000))
def test_random_plates_have_the_drawn_vertices_size_and_mass(seed):
    p = random_plate(np.random.default_rng(seed))
    V = np.asarray(p.vertices)
    diameter = max(np.linalg.norm(a - b) for a in V for b in V)
    assert 4 <= len(V) <= 6 and 0.06 - 1e-5 <= diameter <= 0.15 + 1e-5 and 0.02 <= p.mass <= 0.08
    assert p.stable_sides  # a part (Part checks convexity and the CM)
    assert random_plate(np.random.default_rng(seed)).vertices == p.vertices  # seeded


def test_side_endpoints_follow_the_parts_own_numbering():
    tri = tm.triangle_30_60_90(0.17)
    for k in range(3):
        a, b = side_endpoints(tri, k)
        assert np.hypot(*(b - a)) == pytest.approx(tri.length[k])
    a, b = side_endpoints(tri, 0)  # side 0 is the hypotenuse, from vertex 0 to vertex 1
    assert {tuple(np.round(a, 9)), tuple(np.round(b, 9))} == {tuple(np.round(v, 9)) for v in tri.vertices[:2]}


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 10_000))
def test_proposed_weights_sit_inside_the_plate_near_the_target_side(seed):
    plate = random_plate(np.random.default_rng(seed))
    V = np.asarray(plate.vertices)
    for k in plate.stable_sides:
        a, b = side_endpoints(plate, k)
        n = np.array([a[1] - b[1], b[0] - a[0]]) / np.hypot(*(b - a))
        for v in weight_variants(plate, k, max_kg=0.05):
            p = np.asarray(v.weight.at)
            assert point_in_convex_polygon(V, p, strict=True) and v.weight.mass <= 0.05
            dist = abs(float(np.dot(p - a, n)))
            assert dist >= 0.008 - 1e-9  # the margin
            centre = abs(float(np.dot(V.mean(axis=0) - a, n)))
            assert dist < centre  # on the target side's half of the plate (a corner may push it toward the centre)
            assert k in v.part.stable_sides


def test_no_weight_when_the_cap_is_zero():
    assert weight_variants(tm.triangle_30_60_90(0.17), 0, max_kg=0.0) == []
