"""Statics as an LP: closed forms (a block on an incline, the leaning triangle of Fig. 13) and invariants."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import throwmap as tm
from throwmap.errors import InvalidStateError
from throwmap.statics import (Body, Contact, analyse_rest, drafts_no_lean, edge_frame_cm, find_contacts,
                              lean_free_beta, lean_possible, leaning_bodies)

SQUARE = tm.rectangle(0.06, 0.06)
TRI = tm.triangle_30_60_90()


def _flat(part=SQUARE, x=0.2):
    body = Body(part, x, 0.03, 0.0)
    return (body,), find_contacts((body,), h=0.0, mu_arm=1.0)


@given(alpha=st.floats(-0.7, 0.7))
@settings(max_examples=30, deadline=None)
def test_block_on_an_incline_needs_tan_alpha(alpha):
    # a square flat on the arm tips only past 45°; below, the friction it needs is |tan α|
    bodies, cs = _flat()
    r = analyse_rest(bodies, cs, alpha=alpha)
    assert r.can_rest == (abs(math.tan(alpha)) <= 1.0)
    assert r.mu_needed == pytest.approx(abs(math.tan(alpha)), abs=1e-6)


def test_flat_part_normal_forces_unique_tangential_not():
    # two supports with friction: torque balance fixes both normal forces, not how friction is shared
    bodies, cs = _flat()
    r = analyse_rest(bodies, cs, alpha=0.1)
    assert len(cs) == 2 and r.can_rest
    assert sum(f[0] for f in r.forces) == pytest.approx(SQUARE.mass * 9.81 * math.cos(0.1), rel=1e-7)
    for (fn_lo, fn_hi), (ft_lo, ft_hi) in r.ranges:
        assert fn_hi - fn_lo < 1e-6 and ft_hi - ft_lo > 1e-3
    assert not any(r.unique)


def test_leaning_triangle_lp_equals_the_closed_form():
    # Fig. 13: the general LP and the complete closed form agree on 400 random (β, α, μ)
    a, b, _ = edge_frame_cm(TRI)
    rng = np.random.default_rng(1)
    for _ in range(400):
        beta, alpha = rng.uniform(0.01, 1.55), rng.uniform(-0.6, 0.3)
        mu = float(rng.choice([0.2, 0.6, 1.0, 2.0, math.inf]))
        bodies, cs = leaning_bodies(TRI, beta, length=0.3, mu_arm=mu)
        assert analyse_rest(bodies, cs, alpha=alpha, detail=False).can_rest == bool(lean_possible(a, b, beta, alpha, mu))


def test_drafts_constants_and_its_condition_is_only_sufficient():
    # the draft's 0.58 / 0.14 are the CM's place along and off the hypotenuse (from the 30° vertex)
    a, b, c = edge_frame_cm(TRI)
    assert (round(a, 2), round(b, 2), c) == (0.58, 0.14, pytest.approx(0.17))
    beta, alpha = np.meshgrid(np.linspace(0.01, 1.5, 120), np.linspace(-0.5, 0.2, 60))
    for mu in (1.0, 2.0):
        drafts = drafts_no_lean(a, b, beta, alpha, mu)
        ours = ~lean_possible(a, b, beta, alpha, mu)
        assert not (drafts & ~ours).any()  # whenever the draft says "cannot lean", it cannot
        assert (ours & ~drafts).any()  # but it misses falls the draft's (ii) alone does not see


def test_lean_free_angle_near_the_drafts_quarter_radian():
    # the draft: at μ = 2 no lean below β ≈ 0.25 rad for reasonable α (here α = −10°)
    a, b, _ = edge_frame_cm(TRI)
    assert lean_free_beta(a, b, math.radians(-10), 2.0) == pytest.approx(0.268, abs=0.005)
    assert lean_free_beta(a, b, math.radians(-10), 1.0) > lean_free_beta(a, b, math.radians(-10), 2.0)


def test_two_parts_stacked_find_their_contacts_and_rest():
    # a square on a square: four arm/part contacts found, it rests, the top one's weight passes through
    low, top = Body(SQUARE, 0.2, 0.03), Body(SQUARE, 0.2, 0.09)
    cs = find_contacts((low, top), h=0.0, mu_arm=0.5, mu_parts=0.0)
    assert sorted(c.label for c in cs) == ["arm", "arm", "part", "part"]
    r = analyse_rest((low, top), cs, alpha=0.0)
    assert r.can_rest
    arm_fn = sum(f[0] for f, c in zip(r.forces, cs) if c.label == "arm")
    assert arm_fn == pytest.approx(2 * SQUARE.mass * 9.81, rel=1e-7)
    with pytest.raises(InvalidStateError, match="overlap"):
        find_contacts((low, Body(SQUARE, 0.21, 0.05)), h=0.0, mu_arm=0.5)


def test_no_contact_and_bad_contacts_are_refused():
    r = analyse_rest((Body(SQUARE, 0.2, 0.5),), (), alpha=0.0)
    assert not r.can_rest and "fall" in r.message
    with pytest.raises(InvalidStateError, match="contact.mu"):
        Contact(0, None, (0, 0), (0, 1), -1.0)
    with pytest.raises(InvalidStateError, match="contact"):
        analyse_rest((Body(SQUARE, 0.2, 0.03),), (Contact(3, None, (0, 0), (0, 1), 1.0),))


def test_partial_assembly_geometry_and_friction_needed():
    # Fig. 14: assembled (γ = −30°) the pair fills the rectangle; partially assembled it rests at α = −10° with
    # far less friction than the draft's measured μ > 1 — and needs more as the arm tilts further
    from throwmap.statics.assembly import assembled_pair, partial_assembly, partial_region

    a, b = assembled_pair(TRI, length=0.5)
    pts = np.vstack([a.vertices(), b.vertices()])
    assert pts[:, 0].min() == pytest.approx(0.5 - 0.17 * math.cos(math.radians(30)))
    assert pts[:, 1].max() == pytest.approx(0.085) and pts[:, 0].max() == pytest.approx(0.5)
    bodies, cs = partial_assembly(TRI, math.radians(-15), length=0.5, mu_arm=1.0)
    assert sorted(c.label for c in cs) == ["arm", "arm", "arm", "part", "wall"]
    reg = partial_region(TRI, np.radians([-25, -15, -5]), [1.0], alpha=math.radians(-10))
    assert reg.rests.all() and (reg.mu_needed < 0.1).all()
    steeper = partial_region(TRI, np.radians([-25, -15, -5]), [1.0], alpha=math.radians(-30)).mu_needed
    assert (steeper > reg.mu_needed).all()
