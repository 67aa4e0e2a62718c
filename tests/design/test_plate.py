"""Where the weight may go, the lightest weight for a CM, and the mass properties of plate + weight."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from throwmap.design.examples import draft_cm_readings, plexiglas_triangle
from throwmap.design.plate import inset_polygon, lightest_weight_for_com
from throwmap.errors import InvalidPartError
from throwmap.system.part import Part

PLATE = plexiglas_triangle()
V = np.asarray(PLATE.vertices)


def edge_distances(p):
    out = []
    for k in range(len(V)):
        a, b = V[k], V[(k + 1) % len(V)]
        e = b - a
        out.append(abs(e[0] * (p[1] - a[1]) - e[1] * (p[0] - a[0])) / np.hypot(*e))
    return np.array(out)


def test_inset_vertices_are_margin_from_their_edges():
    ins = inset_polygon(V, 0.008)
    for w in ins.vertices:
        d = edge_distances(np.asarray(w))
        assert np.sum(np.isclose(d, 0.008, atol=1e-12)) == 2  # on two offset edges
        assert np.all(d >= 0.008 - 1e-12)


def test_margin_larger_than_the_inradius_is_refused():
    with pytest.raises(InvalidPartError, match="margin"):
        inset_polygon(V, 0.05)


@settings(max_examples=60, deadline=None)
@given(st.floats(-0.1, 0.25), st.floats(-0.1, 0.2))
def test_projection_is_inside_idempotent_and_nearest(x, y):
    ins = inset_polygon(V, 0.008)
    q = np.asarray(ins.project((x, y)))
    assert ins.contains(q, tol=1e-12)
    assert np.allclose(ins.project(q), q)
    # nearest: no allowed point on a fine boundary sample is closer
    W = np.asarray(ins.vertices)
    t = np.linspace(0, 1, 400)
    pts = np.concatenate([W[k] + t[:, None] * (W[(k + 1) % 3] - W[k]) for k in range(3)])
    if not ins.contains((x, y)):
        assert np.hypot(*(q - (x, y))) <= np.min(np.hypot(*(pts - (x, y)).T)) + 1e-12


def test_projection_along_one_axis_keeps_the_other():
    ins = inset_polygon(V, 0.008)
    q = ins.project((0.2, 0.03), free=(True, False))
    assert q[1] == 0.03 and ins.contains(q)


def grid_mass_properties(vertices, mass, n=1200):
    """CM and polar moment of a uniform polygon by midpoint sampling on an n × n grid (independent of the
    library's triangulation formulas)."""
    from matplotlib.path import Path

    lo, hi = vertices.min(axis=0), vertices.max(axis=0)
    xs = lo[0] + (np.arange(n) + 0.5) * (hi[0] - lo[0]) / n
    ys = lo[1] + (np.arange(n) + 0.5) * (hi[1] - lo[1]) / n
    X, Y = np.meshgrid(xs, ys)
    P = np.stack([X.ravel(), Y.ravel()], axis=1)
    inside = Path(vertices).contains_points(P)
    P = P[inside]
    dm = mass / len(P)
    return P, dm


@pytest.mark.parametrize("m_w, at", [(0.03, (0.012, 0.021)), (0.115, (0.008, 0.0378)), (0.05, (0.09, 0.01))])
def test_cm_and_inertia_of_plate_plus_weight_match_an_independent_computation(m_w, at):
    """The reviewer's concern (Sec. V): CM and inertia come from one mass distribution."""
    part = Part.from_vertices(V, mass=PLATE.mass, point_masses=((m_w, at),))
    P, dm = grid_mass_properties(V, PLATE.mass)
    M = PLATE.mass + m_w
    com = (dm * P.sum(axis=0) + m_w * np.asarray(at)) / M
    inertia = dm * np.sum((P - com) ** 2) + m_w * np.sum((np.asarray(at) - com) ** 2)
    assert part.mass == pytest.approx(M)
    assert np.allclose(part.com, com, atol=2e-5)
    assert part.moment_of_inertia == pytest.approx(inertia, rel=2e-3)


@settings(max_examples=40, deadline=None)
@given(st.floats(0.01, 0.98), st.floats(0.01, 0.98))
def test_lightest_weight_puts_the_cm_where_asked(a, b):
    ins = inset_polygon(V, 0.008)
    W = np.asarray(ins.vertices)
    c = W[0] + a * (W[1] - W[0]) + b * (1 - a) * (W[2] - W[0])  # barycentric: a point of the inset triangle
    w = lightest_weight_for_com(V, PLATE.mass, c, 0.008)
    assert w.realisable
    if w.mass > 1e-9:
        part = Part.from_vertices(V, mass=PLATE.mass, point_masses=((w.mass, w.at),))
        assert np.allclose(part.com, c, atol=1e-9)
        assert ins.contains(w.at, tol=1e-10)
        # any lighter weight on the same ray cannot reach: the weight sits on the allowed region's edge
        assert ins.distance_inside(w.at) == pytest.approx(0.0, abs=1e-10)


def test_the_drafts_cm_readings():
    """Sec. V-B: (u_L, v_L) = (−2, −3.5) cm lies outside the plate in both Sec. III-A readings; as the vector to
    the right-angle corner it needs more than twice the plate's mass of lead."""
    rs = {r.name: r for r in draft_cm_readings((-0.02, -0.035))}
    assert not rs["A"].inside_plate and not rs["B"].inside_plate
    assert rs["C"].weight.realisable and rs["C"].weight.ratio > 2.0
    assert np.allclose(rs["C"].com, (0.02, 0.035))
    rd = {r.name: r for r in draft_cm_readings((-0.028, -0.038))}
    assert not rd["A"].inside_plate
    assert rd["C"].weight.realisable and 0.9 < rd["C"].weight.ratio < 1.2


def test_plate_mass_from_density_and_thickness():
    a, b = 0.085, 0.085 * math.sqrt(3)
    assert PLATE.mass == pytest.approx(1190 * 0.00635 * 0.5 * a * b)
