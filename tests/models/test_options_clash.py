"""An options instance and a keyword naming the same field must agree; a keyword that
contradicts the instance is refused (it used to win silently)."""

import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError
from throwmap.models.paper import PaperOptions
from throwmap.system.catalogue import triangle_30_60_90


def _args():
    return triangle_30_60_90(), tm.Arm(h=-0.01)


def test_conflicting_keyword_is_refused():
    part, arm = _args()
    with pytest.raises(InvalidStateError) as err:
        tm.throw(part, arm, 0.2, 0, 4.0, model="paper", options=PaperOptions(tol=1e-9), tol=1e-6)
    assert err.value.field == "tol"
    assert "given twice" in str(err.value)


def test_agreeing_keyword_is_accepted_and_same_result():
    part, arm = _args()
    a = tm.throw(part, arm, 0.2, 0, 4.0, model="paper", options=PaperOptions(tol=1e-9), tol=1e-9)
    b = tm.throw(part, arm, 0.2, 0, 4.0, model="paper", options=PaperOptions(tol=1e-9))
    assert a.x == b.x and a.side == b.side


def test_batch_refuses_the_clash_too():
    part, arm = _args()
    with pytest.raises(InvalidStateError) as err:
        tm.throw_batch(part, arm, [0.2, 0.3], 0, 4.0, model="paper", options=PaperOptions(max_iter=50), max_iter=60)
    assert err.value.field == "max_iter"
