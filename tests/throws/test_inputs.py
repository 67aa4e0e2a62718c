"""Bad input to throw/throw_batch: one line naming the field, never a deep traceback or a coerced value."""

import numpy as np
import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError

TRI = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01)


@pytest.mark.parametrize("call, field", [
    (lambda: tm.throw("triangle", ARM, 0.2, 0, 4.0), "part"),
    (lambda: tm.throw(TRI, -0.01, 0.2, 0, 4.0), "arm"),
    (lambda: tm.throw(TRI, ARM, 0.2, 0, "4"), "omega"),
    (lambda: tm.throw(TRI, ARM, "0.2", 0, 4.0), "x"),
    (lambda: tm.throw_batch("triangle", ARM, [0.2], 0, 4.0), "part"),
    (lambda: tm.throw_batch(TRI, ARM, np.array([0.2, 0.3]), np.array([0, 1, 2]), 4.0), "x"),
    (lambda: tm.throw_batch(TRI, ARM, ["0.2"], 0, 4.0), "x"),
    (lambda: tm.throw_batch(TRI, ARM, [0.2], 0, ["4"]), "omega"),
])
def test_one_line_naming_the_field(call, field):
    with pytest.raises(InvalidStateError) as err:
        call()
    assert err.value.field == field and "\n" not in str(err.value)


def test_mujoco_outcomes_carry_the_registry_name():
    pytest.importorskip("mujoco")
    assert tm.throw(TRI, ARM, 0.25, 0, 4.0, model="mujoco").model == "mujoco"
