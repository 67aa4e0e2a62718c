"""Statics refuses bad input with one line naming the field, before any LP; its searches end."""

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError, ThrowmapError
from throwmap.statics import (Body, Contact, analyse_rest, edge_frame_cm, find_contacts, lean_free_beta,
                              lean_possible, leaning_bodies)
from throwmap.statics.assembly import partial_region
from throwmap.statics.rest import least_mu

SQUARE = tm.rectangle(0.06, 0.06)
TRI = tm.triangle_30_60_90()


def _flat():
    body = Body(SQUARE, 0.2, 0.03, 0.0)
    return (body,), find_contacts((body,), h=0.0, mu_arm=1.0)


@pytest.mark.parametrize("alpha", [math.nan, math.inf, "0.1", 100.0, True])
def test_analyse_rest_refuses_a_bad_alpha(alpha):
    bodies, cs = _flat()
    with pytest.raises(InvalidStateError, match=r"^alpha: "):
        analyse_rest(bodies, cs, alpha=alpha)


@pytest.mark.parametrize("g", [math.nan, 0.0, -9.81, math.inf])
def test_analyse_rest_refuses_a_bad_g(g):
    bodies, cs = _flat()
    with pytest.raises(InvalidStateError, match=r"^g: "):
        analyse_rest(bodies, cs, g=g)


@pytest.mark.parametrize("field,kw", [("body.x", dict(x=math.nan)), ("body.y", dict(y=math.inf)),
                                      ("body.phi", dict(phi="0"))])
def test_a_body_at_nan_is_refused(field, kw):
    args = dict(part=SQUARE, x=0.2, y=0.03, phi=0.0) | kw
    with pytest.raises(InvalidStateError, match=rf"^{field}: "):
        Body(**args)


def test_a_contact_at_nan_or_with_itself_is_refused():
    with pytest.raises(InvalidStateError, match=r"^contact.point: "):
        Contact(0, None, (math.nan, 0.0), (0.0, 1.0), 1.0)
    with pytest.raises(InvalidStateError, match=r"^contact.b: "):
        Contact(0, 0, (0.0, 0.0), (0.0, 1.0), 1.0)


def test_partial_region_refuses_a_nan_alpha():
    with pytest.raises(InvalidStateError, match=r"^alpha: "):
        partial_region(TRI, [0.1], [1.0], alpha=math.nan)


def test_leaning_bodies_refuses_a_non_edge_and_a_wall_behind_the_joint():
    with pytest.raises(InvalidStateError, match=r"^edge: "):
        leaning_bodies(TRI, 0.3, length=0.3, mu_arm=1.0, edge=(0, 7))
    with pytest.raises(InvalidStateError, match=r"^edge: "):
        leaning_bodies(tm.rectangle(0.06, 0.04), 0.3, length=0.3, mu_arm=1.0, edge=(0, 2))
    with pytest.raises(InvalidStateError, match=r"^length: "):
        leaning_bodies(TRI, 0.3, length=-0.1, mu_arm=1.0)


@pytest.mark.parametrize("kw,field", [(dict(mu=math.nan), "mu"), (dict(mu=-1.0), "mu"), (dict(n=2), "n"),
                                      (dict(alpha=math.nan), "alpha")])
def test_lean_free_beta_refuses_bad_input(kw, field):
    a, b, _ = edge_frame_cm(TRI)
    args = dict(alpha=math.radians(-10), mu=2.0) | kw
    with pytest.raises(InvalidStateError, match=rf"^{field}: "):
        lean_free_beta(a, b, **args)


@pytest.mark.parametrize("alpha,mu", [(math.radians(-10), 1.0), (math.radians(-10), 2.0), (-0.3, 0.5), (0.0, 1.0)])
def test_lean_free_beta_is_the_boundary_not_a_grid_step_below(alpha, mu):
    a, b, _ = edge_frame_cm(TRI)
    beta = lean_free_beta(a, b, alpha, mu)
    if beta == math.pi / 2:
        assert not lean_possible(a, b, np.linspace(1e-6, math.pi / 2, 4001), alpha, mu).any()
        return
    # no lean just below β*, a lean just above it: β* is the boundary to 1e-9 rad, not a grid step (7.9e-5) short
    assert not lean_possible(a, b, beta - 1e-9, alpha, mu)
    assert lean_possible(a, b, beta + 1e-9, alpha, mu)
    assert not lean_possible(a, b, np.linspace(1e-9, beta, 2001), alpha, mu).any()


def test_least_mu_refuses_a_predicate_that_never_settles():
    calls = []

    def never_settles(mu):  # false at 0, true at every μ > 0: no least μ, the bisection would halve to 1e-323
        calls.append(mu)
        return mu > 0.0

    with pytest.raises(ThrowmapError, match=r"^least_mu: "):
        least_mu(never_settles)
    assert len(calls) < 250


def test_least_mu_still_finds_a_monotone_threshold():
    assert least_mu(lambda mu: mu >= 0.37) == pytest.approx(0.37, rel=1e-9)
    assert least_mu(lambda mu: mu >= 1e-20) == pytest.approx(1e-20, rel=1e-9)
