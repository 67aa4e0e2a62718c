"""A design says success only when its part is fed: targets hit and a limit set on the arm; bad input is refused
with one line naming the field, not returned as a failed design."""

import pytest

import throwmap as tm
from throwmap.design import design_critical_points
from throwmap.design.api import MAX_ESCAPE, SolveOptions, SpaceOptions, design
from throwmap.errors import InvalidStateError

PLATE = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01, length=0.6)


def test_targets_hit_where_every_orbit_escapes_is_not_a_success():
    res = design_critical_points(PLATE, ARM, 5.0, weight_mass=0.03, weight_at=(0.03, 0.03),
                                 target={0: 0.30, 1: 0.15, 2: 0.15})
    # the critical points are hit …
    assert all(abs(res.achieved[k] - v) <= 1e-4 for k, v in {0: 0.30, 1: 0.15, 2: 0.15}.items())
    # … but the designed part has no limit set on the arm: it feeds nothing
    assert not res.success
    assert "feeds nothing" in res.message and "every orbit escapes" in res.message
    ls = tm.limit_set(res.part, res.arm, res.omega, "rigid_body", n_starts=32, x_max=0.6)
    assert not ls.attractors


def test_a_design_that_keeps_a_limit_set_succeeds():
    res = design_critical_points(PLATE, ARM, 4.0, weight_mass=0.03, weight_at=(0.03, 0.03),
                                 target={0: 0.40, 1: 0.25, 2: 0.25})
    assert res.success, res.message
    ls = tm.limit_set(res.part, res.arm, res.omega, "rigid_body", n_starts=32, x_max=0.6)
    assert ls.attractors and sum(ls.escapes.values()) <= MAX_ESCAPE


@pytest.mark.parametrize("kw,field", [
    (dict(solve=SolveOptions(n_grid=1)), "n_grid"),
    (dict(solve=SolveOptions(n_grid=10**7)), "n_grid"),
    (dict(solve=SolveOptions(x_max=2.0)), "x_max"),
    (dict(space=SpaceOptions(bounds={"omgea": (1.0, 9.0)})), "bounds"),
    (dict(weight_mass=1e6), "weight_mass"),
])
def test_bad_design_input_is_an_error_not_a_failed_design(kw, field):
    args = dict(weight_mass=0.03, weight_at=(0.03, 0.03)) | kw
    with pytest.raises(InvalidStateError, match=rf"^{field}: "):
        design(PLATE, ARM, 4.0, {0: 0.40, 1: 0.25, 2: 0.25}, **args)
