"""Parts: mass properties, side tables, numbering conventions, bad input."""

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.errors import InvalidPartError, InvalidStateError


def test_triangle_side_table_matches_geometry(triangle):
    """Sec. IV-A: 17 cm hypotenuse, CM ~3 cm from the long leg and ~5 cm from the short leg."""
    a, b, c = 0.085, 0.085 * math.sqrt(3), 0.17
    assert triangle.n_sides == 3 and triangle.stable_sides == (0, 1, 2)
    assert triangle.d[0] == pytest.approx(a * b / c / 3)  # CM height over the hypotenuse
    assert triangle.d[1] == pytest.approx(a / 3)  # over the long leg (2.83 cm)
    assert triangle.d[2] == pytest.approx(b / 3)  # over the short leg (4.91 cm)
    assert triangle.length[0] == pytest.approx(c)
    assert triangle.length[1] == pytest.approx(b)
    assert triangle.length[2] == pytest.approx(a)
    for k in range(3):
        assert triangle.uR[k] - triangle.uL[k] == pytest.approx(triangle.length[k])


def test_uniform_plate_inertia_closed_forms():
    r = tm.rectangle(0.08, 0.04, mass=0.2)
    assert r.radius_of_gyration**2 == pytest.approx((0.08**2 + 0.04**2) / 12)
    assert r.com == pytest.approx((0.04, 0.02))
    n, R = 6, 0.05
    hexa = tm.regular_polygon(n, R)
    # regular n-gon: J/A = R²/6 (2 + cos(2π/n))... use the standard I = m R² (1 + 2cos²(π/n)) / 6
    assert hexa.radius_of_gyration**2 == pytest.approx(R**2 * (1 + 2 * math.cos(math.pi / n) ** 2) / 6)


def test_point_masses_move_cm_and_inertia_consistently(triangle):
    pm = (0.03, (0.10, 0.01))
    p = tm.triangle_30_60_90(0.17, point_masses=[pm])
    m0 = triangle.mass
    assert p.mass == pytest.approx(m0 + 0.03)
    c_expected = (m0 * np.array(triangle.com) + 0.03 * np.array(pm[1])) / (m0 + 0.03)
    assert np.allclose(p.com, c_expected)
    # inertia about the new CM: plate (parallel axis) + point mass
    i_expected = (m0 * triangle.radius_of_gyration**2 + m0 * np.sum((np.array(triangle.com) - c_expected) ** 2)
                  + 0.03 * np.sum((np.array(pm[1]) - c_expected) ** 2))
    assert p.moment_of_inertia == pytest.approx(i_expected)
    # independent check: dense sampling of the plate
    rng = np.random.default_rng(0)
    v = np.array(triangle.vertices)
    u = rng.random((400_000, 2))
    u[u.sum(1) > 1] = 1 - u[u.sum(1) > 1]
    pts = v[2] + u[:, :1] * (v[0] - v[2]) + u[:, 1:] * (v[1] - v[2])
    i_mc = m0 * np.mean(np.sum((pts - c_expected) ** 2, axis=1)) + 0.03 * np.sum((np.array(pm[1]) - c_expected) ** 2)
    assert p.moment_of_inertia == pytest.approx(i_mc, rel=5e-3)


def test_explicit_com_and_radius_override(triangle):
    p = tm.Part.from_vertices(triangle.vertices, 0.05, com=(0.05, 0.02), radius_of_gyration=0.03)
    assert p.com == (0.05, 0.02) and p.radius_of_gyration == 0.03


@pytest.mark.parametrize("ccw", [True, False])
def test_side_zero_is_first_edge_and_flips_go_to_next_side(ccw):
    v = [(0.0, 0.0), (0.1, 0.0), (0.12, 0.05), (0.03, 0.07)]
    if not ccw:
        v = [v[1], v[0], v[3], v[2]]  # clockwise, still starting with the same first edge (reversed)
    p = tm.Part.from_vertices(v, 0.05)
    assert p.length[0] == pytest.approx(0.1)
    # the vertices of side 0 are the first two listed
    assert {p.user_vertex(0), p.user_vertex(1)} == {0, 1}
    # clockwise numbering: side k+1 starts at side k's left support vertex w_{k+1}
    for k in range(p.n_sides):
        assert np.allclose(p.vertices_at_rest(0.2, k, 0.0)[(k + 1) % p.n_sides],
                           [0.2 + p.uL[k], 0.0])
        assert np.allclose(p.vertices_at_rest(0.2, k, 0.0)[k], [0.2 + p.uR[k], 0.0])


def test_relabelling_vertices_shifts_sides_only(triangle):
    v = list(triangle.vertices)
    for shift in range(1, 3):
        q = tm.Part.from_vertices(v[shift:] + v[:shift], 0.05)
        # same geometry, rotated labels: find the offset
        offs = [o for o in range(3) if np.allclose(np.roll(triangle.d, -o), q.d)]
        assert len(offs) == 1
        o = offs[0]
        assert np.allclose(np.roll(triangle.uL, -o), q.uL) and np.allclose(np.roll(triangle.uR, -o), q.uR)
    # reversing the orientation keeps the clockwise numbering from the first edge
    r = tm.Part.from_vertices([v[1], v[0], v[2]], 0.05)
    assert np.allclose(r.d, triangle.d) and np.allclose(r.uL, triangle.uL)


@pytest.mark.parametrize(
    "kwargs, field, words",
    [
        (dict(vertices=[(0, 0), (1, 0)], mass=1), "part.vertices", "at least 3"),
        (dict(vertices=[(0, 0), (0.1, 0), (0.1, 0), (0, 0.1)], mass=1), "part.vertices", "coincide"),
        (dict(vertices=[(0, 0), (0.1, 0), (0.2, 0), (0, 0.1)], mass=1), "part.vertices", "collinear"),
        (dict(vertices=[(0, 0), (0.1, 0), (0.05, 0.02), (0.1, 0.1), (0, 0.1)], mass=1), "part.vertices", "not convex"),
        (dict(vertices=[(math.cos(a), math.sin(a)) for a in np.arange(5) * 4 * math.pi / 5], mass=1),
         "part.vertices", "self-intersecting"),
        (dict(vertices=[(0, 0), (0.1, 0), (float("nan"), 0.1)], mass=1), "part.vertices", "finite"),
        (dict(vertices=[(0, 0), (0.1, 0), (0, float("inf"))], mass=1), "part.vertices", "finite"),
        (dict(vertices=[(0, 0), (0.1, 0), (0, 0.1)], mass=0), "part.mass", "positive"),
        (dict(vertices=[(0, 0), (0.1, 0), (0, 0.1)], mass=-1), "part.mass", "positive"),
        (dict(vertices=[(0, 0), (0.1, 0), (0, 0.1)], mass=1, com=(0.2, 0.2)), "part.com", "not strictly inside"),
        (dict(vertices=[(0, 0), (0.1, 0), (0, 0.1)], mass=1, radius_of_gyration=0), "part.radius_of_gyration",
         "positive"),
        (dict(vertices=[(0, 0), (0.1, 0), (0, 0.1)], mass=1, point_masses=[(0.1, (0.2, 0.2))]),
         "part.point_masses[0].at", "outside"),
        (dict(vertices=[(0, 0), (0.1, 0), (0, 0.1)], mass=1, point_masses=[(-0.1, (0.01, 0.01))]),
         "part.point_masses[0].mass", "positive"),
    ],
)
def test_bad_parts_are_refused_naming_the_field(kwargs, field, words):
    with pytest.raises(InvalidPartError) as err:
        tm.Part.from_vertices(**kwargs)
    assert err.value.field == field
    assert words in str(err.value)
    assert str(err.value).startswith(field + ": ")


def test_unstable_sides_are_numbered_and_refused_as_start():
    # heavy weight near one end of a long, slanted quadrilateral makes some sides unstable
    p = tm.Part.from_vertices([(0, 0), (0.2, 0), (0.21, 0.02), (0.0, 0.03)], 0.01, point_masses=[(0.2, (0.19, 0.005))])
    assert not p.stable.all() and p.stable.any()
    k = int(np.flatnonzero(~p.stable)[0])
    with pytest.raises(InvalidStateError, match=f"side {k} is unstable"):
        tm.throw(p, tm.Arm(h=-0.001), 0.3, k, 1.0, model="paper")
    with pytest.raises(InvalidStateError, match="does not exist"):
        tm.throw(p, tm.Arm(h=-0.001), 0.3, 7, 1.0, model="paper")


def test_inertia_of_a_part_far_from_the_origin_keeps_its_precision():
    """Regression (found by Hypothesis): triangulating from the origin lost ρ to cancellation
    for a thin part 1 m away (5e-9 relative); the mass properties must not depend on where
    the vertices are given."""
    v = np.array([(0.03125, 0.0), (0.016884447058379368, 0.026295968275246766),
                  (0.030005321457823936, -0.008731734318716433)])
    near = tm.Part.from_vertices(v, mass=0.05)
    for shift in ((1.0, 1.0), (10.0, -7.0), (100.0, 100.0)):
        far = tm.Part.from_vertices(v + np.array(shift), mass=0.05)
        assert far.radius_of_gyration == pytest.approx(near.radius_of_gyration, rel=1e-11)
        np.testing.assert_allclose(np.array(far.com) - shift, near.com, rtol=0, atol=1e-12)
