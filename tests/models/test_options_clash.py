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


def test_a_misspelt_keyword_names_the_nearest_one():
    import throwmap as tm

    part, arm = tm.triangle_30_60_90(), tm.Arm(h=-0.01)
    with pytest.raises(tm.InvalidStateError, match=r"n_start: unknown keyword .*did you mean 'n_starts'\?"):
        tm.limit_set(part, arm, 4.5, "paper", n_start=10)
    with pytest.raises(tm.InvalidStateError, match=r"did you mean 'tol'\?"):
        tm.throw(part, arm, 0.2, 0, 4.0, "paper", tole=1e-9)
    with pytest.raises(tm.InvalidStateError) as err:
        tm.throw(part, arm, 0.2, 0, 4.0, "paper", zzzz=1)
    assert "did you mean" not in str(err.value)
