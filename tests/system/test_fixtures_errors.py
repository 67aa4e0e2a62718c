"""Bad fixture input is refused as InvalidStateError (a ValueError) naming the field,
with values shown plainly (never ``np.float64(…)``); NumPy numbers are accepted."""

import numpy as np
import pytest

from throwmap.errors import InvalidStateError
from throwmap.system.fixtures import Cavity, Wall


@pytest.mark.parametrize("kwargs, field", [
    (dict(height=-0.01), "wall.height"),
    (dict(height=np.float64(-0.02)), "wall.height"),
    (dict(height=0.02, mu=-1.0), "wall.mu"),
    (dict(height="2"), "wall.height"),
])
def test_wall_errors_name_field(kwargs, field):
    with pytest.raises(InvalidStateError) as err:
        Wall(**kwargs)
    assert err.value.field == field
    assert "np.float64" not in str(err.value) and "numpy" not in str(err.value)


def test_wall_accepts_numpy_numbers():
    w = Wall(height=np.float32(0.02), mu=np.int64(1))
    assert isinstance(w.height, float) and w.height == pytest.approx(0.02)


def test_cavity_errors_name_the_point():
    with pytest.raises(InvalidStateError) as err:
        Cavity(profile=[(0.05, 0.0), (0.02, 0.01), (0.0, -0.01)])
    assert err.value.field == "cavity.profile[1]"
    assert isinstance(err.value, ValueError)
