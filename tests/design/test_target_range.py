"""A target position the searched range cannot hold is refused as input (one line naming ``target``)."""

import pytest

import throwmap as tm
from throwmap.design import design_critical_points
from throwmap.errors import InvalidStateError


@pytest.mark.parametrize("value", [5.0, -0.1, 0.0, 0.61])
def test_a_target_outside_the_arm_is_bad_input(value):
    plate, arm = tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01, length=0.6)
    with pytest.raises(InvalidStateError, match=r"^target: r_0 = .* outside the searched range"):
        design_critical_points(plate, arm, 5.0, weight_mass=0.03, weight_at=(0.03, 0.03), target={0: value})
