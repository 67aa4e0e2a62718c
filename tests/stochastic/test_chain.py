"""MarkovChain on small chains with closed forms (Kemeny & Snell 1960, Ch. III)."""

import numpy as np
import pytest

from throwmap.errors import InvalidStateError
from throwmap.stochastic import ChainMixture, MarkovChain


def ruin(p: float) -> MarkovChain:
    """Gambler's ruin on {1, 2, 3} with absorbing 0 ('lost') and 4 ('won'): up with p, down with q."""
    q = 1 - p
    P = np.zeros((5, 5))
    P[0, 1], P[0, 3] = p, q          # cell 1 -> 2 or lost
    P[1, 2], P[1, 0] = p, q          # cell 2 -> 3 or 1
    P[2, 4], P[2, 1] = p, q          # cell 3 -> won or 2
    P[3, 3] = P[4, 4] = 1.0
    return MarkovChain(P, ("c1", "c2", "c3", "lost", "won"), 3)


@pytest.mark.parametrize("p", [0.5, 0.3, 0.8])
def test_gamblers_ruin_absorption_is_the_closed_form(p):
    q, n = 1 - p, 4
    r = q / p
    want = [(i / n) if p == 0.5 else (1 - r**i) / (1 - r**n) for i in (1, 2, 3)]
    ab = ruin(p).absorption()
    won = ab.B[:, ab.labels.index("won")]
    assert won == pytest.approx(want, abs=1e-12)
    assert ab.B.sum(axis=1) + ab.escape == pytest.approx(1.0, abs=1e-12)


def test_expected_throws_of_the_fair_ruin_is_i_times_n_minus_i():
    t = ruin(0.5).expected_throws()
    assert t == pytest.approx([1 * 3, 2 * 2, 3 * 1], abs=1e-12)


def test_p_goal_by_k_is_the_first_hitting_distribution():
    # from cell 3, won at throw 1 with p; at throw 3 via 3->2->3->won with p q p ...
    p = 0.3
    c = ruin(p)
    curve = c.p_goal_by(3, ["won"], [0, 0, 1.0])
    assert curve[:2] == pytest.approx([0.0, p])
    assert curve[2] == pytest.approx(p)             # no way to win in exactly 2
    assert curve[3] == pytest.approx(p + (1 - p) * p * p)
    assert np.all(np.diff(curve) >= -1e-15)


def test_a_stop_is_not_a_throw():
    # one cell; the policy stops there (free absorbing 'stop:goal'): reached after 0 throws
    P = np.array([[0.0, 1.0], [0.0, 1.0]])
    c = MarkovChain(P, ("c", "stop:goal"), 1, free=("stop:goal",))
    assert c.p_goal_by(2, ["stop:goal"], [1.0]) == pytest.approx([1.0, 1.0, 1.0])
    assert c.expected_throws(["stop:goal"])[0] == pytest.approx(0.0)


def test_a_closed_class_of_cells_is_escape_and_stationary_averages_a_cycle():
    # cells a <-> b (a 2-cycle), cell c -> a or off with 1/2 each
    P = np.zeros((4, 4))
    P[0, 1] = P[1, 0] = 1.0
    P[2, 0] = P[2, 3] = 0.5
    P[3, 3] = 1.0
    c = MarkovChain(P, ("a", "b", "c", "off"), 3)
    ab = c.absorption()
    assert ab.escape == pytest.approx([1.0, 1.0, 0.5])
    assert ab.B[:, 0] + ab.escape == pytest.approx(1.0)
    st = c.stationary([0, 0, 1.0])
    assert st.converged
    assert st.pi == pytest.approx([0.25, 0.25, 0.0, 0.5], abs=1e-9)
    assert st.on_arm == pytest.approx(0.5)
    assert np.isinf(c.expected_throws()[2])


def test_rows_must_sum_to_one_and_labels_match():
    with pytest.raises(InvalidStateError, match="row 0 sums"):
        MarkovChain(np.array([[0.5, 0.4], [0, 1.0]]), ("a", "b"), 1)
    with pytest.raises(InvalidStateError, match="labels"):
        MarkovChain(np.eye(2), ("a",), 1)


def test_a_mixture_averages_the_curves():
    a, b = ruin(0.3), ruin(0.7)
    m = ChainMixture((a, b), [1, 3])
    want = 0.25 * a.p_goal_by(5, ["won"], [1, 0, 0]) + 0.75 * b.p_goal_by(5, ["won"], [1, 0, 0])
    assert m.p_goal_by(5, ["won"], [1, 0, 0]) == pytest.approx(want)


def test_reach_gives_the_probability_and_the_conditional_mean_throws():
    p, mean = ruin(0.5).reach(["won"], [0, 0, 1.0])
    assert p == pytest.approx(0.75)
    # from 3 (fair ruin, n = 4): E[T | won] = (n² − i²)/3 = (16 − 9)/3
    assert mean == pytest.approx(7 / 3)


def test_quasi_stationary_of_a_symmetric_leaky_pair():
    # a <-> b with probability 0.5, off with 0.5: conditioned on staying, half and half; survival 0.5 a throw
    P = np.array([[0, 0.5, 0.5], [0.5, 0, 0.5], [0, 0, 1.0]])
    q = MarkovChain(P, ("a", "b", "off"), 2).quasi_stationary()
    assert q.pi == pytest.approx([0.5, 0.5, 0.0])
    assert q.rate == pytest.approx(0.5)
