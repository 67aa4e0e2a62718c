"""The analysis covers what it says it covers: its domain, its options, its caps, its tables.

1. The analysed domain is the set of starts ``throw()`` accepts (``Arm.back`` and the arm's end
   included), so a certificate never claims uniqueness over starts it did not look at.
2. ``funnels`` passes model options on to every throw map.
3. Raising ``transient`` raises ``max_transient`` with it; a huge record is refused naming ``n_record``.
4. ``LimitSet.table()`` and ``Basins.table()`` state the x range they cover.

Independent checks: every domain end is tested against ``throw()`` itself, and the fixed point
found behind the old domain is re-thrown by hand.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.analysis import RecurrenceCaps, ThrowMap, basins, funnels, limit_set
from throwmap.errors import InvalidStateError
from throwmap.models.rigid_body import RigidBodyOptions

TRI = tm.triangle_30_60_90(0.17)
BACK = tm.Arm(h=-0.01, back=0.05)


def _accepts(arm, x, side):
    try:
        tm.throw(TRI, arm, x, side, 4.0)
    except InvalidStateError:
        return False
    return True


# ---------------------------------------------------------------- 1. domain = throw()'s starts
@pytest.mark.parametrize("arm", [tm.Arm(h=-0.01), BACK, tm.Arm(h=-0.01, back=0.02, length=0.3)])
def test_domain_is_exactly_the_starts_throw_accepts(arm):
    cmap = ThrowMap(TRI, arm, 4.0)
    assert cmap.sides == TRI.stable_sides
    for s in cmap.sides:
        lo, hi = cmap.x_lo[s], cmap.x_hi[s]
        assert not _accepts(arm, lo, s)  # x_lo is excluded: the first start is just above it
        assert _accepts(arm, math.nextafter(lo, math.inf), s)
        assert _accepts(arm, hi, s)
        if arm.length is not None:
            assert hi < arm.length  # the right support vertex, not the CM, ends at the arm's end
            assert not _accepts(arm, math.nextafter(hi, math.inf), s)


def test_back_widens_the_domain_behind_the_joint():
    plain, back = ThrowMap(TRI, tm.Arm(h=-0.01), 4.0), ThrowMap(TRI, BACK, 4.0)
    for s in TRI.stable_sides:
        assert back.x_lo[s] == pytest.approx(plain.x_lo[s] - 0.05, abs=1e-12)


def test_basins_with_back_find_the_fixed_point_near_the_joint_and_claim_no_uniqueness():
    """The tester's case: x = 0.03 m on side 1 is an accepted start and stays put; it was outside the domain."""
    o = tm.iterate(TRI, BACK, (0.03, 1), 4.0, n=50)
    assert o.x[-1] == pytest.approx(0.03, abs=1e-6) and set(np.asarray(o.side).tolist()) == {1}
    b = basins(TRI, BACK, 4.0, grid=60)
    assert not b.certificate.unique
    assert b.x[b.side == 1].min() < TRI.x_min(1)  # the grid reaches behind the old domain
    near = [a for a in b.attractors if a.kind == "fixed_point" and any(
        s == 1 and 0.0 < lo < TRI.x_min(1) for s, lo, _ in a.bands)]
    assert near, [a.bands for a in b.attractors]
    for a in near[:3]:  # each is a fixed point when re-thrown by hand
        s, x, _ = a.bands[0]
        out = tm.throw(TRI, BACK, x, s, 4.0)
        assert out.status == tm.Status.OK and out.side == s and abs(out.x - x) <= 1e-6


def test_limit_set_with_back_has_fixed_points_behind_the_old_domain():
    ls = limit_set(TRI, BACK, 4.0, n_starts=16, transient=50, n_record=64)
    assert ls.starts_x[ls.starts_side == 1].min() < TRI.x_min(1)
    assert any(a.kind == "fixed_point" and any(s == 1 and lo < TRI.x_min(1) for s, lo, _ in a.bands)
               for a in ls.attractors)
    assert not ls.unique


def test_finite_arm_domain_is_cut_by_the_right_vertex():
    arm = tm.Arm(h=-0.01, length=0.3)
    ls = limit_set(TRI, arm, 4.0, n_starts=8, transient=20, n_record=64)
    for s in TRI.stable_sides:
        xs = ls.starts_x[ls.starts_side == s]
        assert np.all(xs + TRI.uR[s] <= 0.3)


# ---------------------------------------------------------------- 2. funnels take model options
def test_funnels_pass_model_options_to_every_map():
    arm = tm.Arm(h=-0.01, mu=0.3)
    kw = dict(grid=40, n_seeds=8, transient=50, n_record=64)
    by_kw = funnels(TRI, arm, [3.0, 4.0], impact_law="velocity", **kw)
    by_opts = funnels(TRI, arm, [3.0, 4.0], options=RigidBodyOptions(impact_law="velocity"), **kw)
    ref = basins(TRI, arm, 4.0, impact_law="velocity", grid=40, n_seeds=8, transient=50, n_record=64)
    for g in (by_kw, by_opts):
        spouts = [f.attractor.bands for f in g.funnels if f.omegas == (4.0,)]
        assert spouts == [a.bands for a in ref.attractors if a.fraction > 0]


def test_funnels_still_refuse_unknown_keywords():
    with pytest.raises(InvalidStateError) as err:
        funnels(TRI, tm.Arm(h=-0.01), [4.0], bogus=1, grid=20)
    assert err.value.field == "bogus"
    with pytest.raises(InvalidStateError) as err:  # an option of another model names the models that take it
        funnels(TRI, tm.Arm(h=-0.01), [4.0], model="paper", impact_law="velocity", grid=20)
    assert err.value.field == "impact_law"


# ---------------------------------------------------------------- 3. transient and its ceiling
def test_raising_transient_raises_max_transient():
    caps = RecurrenceCaps().replace(transient=6000)
    assert caps.max_transient >= 6000 + 2 * (6000 + caps.n_record)
    assert RecurrenceCaps().replace(transient=10).max_transient == RecurrenceCaps().max_transient
    assert RecurrenceCaps().replace(transient=6000, max_transient=7000).max_transient == 7000
    with pytest.raises(InvalidStateError) as err:  # given both, the user's ceiling is checked as before
        RecurrenceCaps().replace(transient=6000, max_transient=5000)
    assert err.value.field == "max_transient"


def test_limit_set_runs_with_a_long_transient():
    ls = limit_set(TRI, tm.Arm(h=-0.01), 4.0, n_starts=2, transient=6000)
    assert [a.kind for a in ls.attractors] == ["band"] and not ls.escapes


def test_a_huge_record_is_refused_naming_the_record():
    with pytest.raises(InvalidStateError) as err:
        limit_set(TRI, tm.Arm(h=-0.01), 4.0, n_record=100_000_000)
    assert err.value.field == "n_record"
    with pytest.raises(InvalidStateError) as err:
        limit_set(TRI, tm.Arm(h=-0.01), 4.0, n_starts=10_000_000)
    assert err.value.field == "n_starts"


# ---------------------------------------------------------------- 4. tables state the range
def test_tables_state_the_range():
    arm = tm.Arm(h=-0.01)
    ls = limit_set(TRI, arm, 4.0, n_starts=4, transient=50, n_record=64, x_max=0.5)
    assert "valid starts with x ≤ 0.500 m" in ls.table().splitlines()[0]
    b = basins(TRI, arm, 4.0, grid=30, x_max=0.5)
    assert "valid starts with x ≤ 0.500 m" in b.table().splitlines()[0]
    assert b.range_text == ls.range_text
