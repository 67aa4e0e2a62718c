"""Values far outside a hand-sized part on a one-joint arm (a unit slip) are warned about, naming the field;
ordinary values are not."""

import math
import warnings

import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError, ScaleWarning
from throwmap.system.system import check_alpha

TRI = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01)


def test_ordinary_values_raise_no_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error", ScaleWarning)
        tm.throw(TRI, ARM, 0.2, 0, 4.0, "paper")
        tm.throw(TRI, ARM, 0.2, 0, 4.0, "rigid_body", alpha=math.radians(-10.0))


@pytest.mark.parametrize("call,field", [
    (lambda: tm.throw(TRI, ARM, 0.2, 0, 229.0, "paper"), "omega = 229 rad/s"),
    (lambda: tm.throw(TRI, ARM, 20.0, 0, 4.0, "paper"), "x = 20 m"),
    (lambda: tm.Part.from_vertices([(0, 0), (17, 0), (0, 8.5)], mass=0.05), "part.vertices = 17 m"),
    (lambda: tm.Part.from_vertices([(0, 0), (0.17, 0), (0, 0.085)], mass=50.0), "part.mass = 50 kg"),
    (lambda: check_alpha(1.2), "alpha = 1.2 rad"),
])
def test_a_unit_slip_is_warned_with_its_field(call, field):
    with pytest.warns(ScaleWarning, match=field):
        call()


def test_an_alpha_beyond_vertical_suggests_degrees():
    with pytest.raises(InvalidStateError, match=r"for degrees write e.g. 10deg"):
        check_alpha(10.0)


def test_alpha_at_vertical_gets_no_degree_hint():
    """90° typed as 90deg is π/2 rad: refused (the arm vertical) without suggesting '1.5708deg' (= 1.57°)."""
    import math

    with pytest.raises(InvalidStateError) as err:
        check_alpha(math.pi / 2)
    assert "= 90°" in str(err.value) and "deg)" not in str(err.value) and "write" not in str(err.value)
