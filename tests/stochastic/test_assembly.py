"""The self-assembly low-phase chain counted from reduced-state sequences."""

import numpy as np
import pytest

from throwmap.errors import InvalidStateError
from throwmap.stochastic.assembly import low_phase_chain, low_phase_hits


def test_counted_chain_and_hits():
    seqs = [["r1", "r1", "r2", "assembled"], ["r1", "r2", "ended"], ["r2", "assembled"], ["r1", "r1", "ended"]]
    c = low_phase_chain(seqs)
    assert c.labels == ("r1", "r2", "assembled", "ended")
    P = c.P
    # r1: to r1 twice, to r2 twice, to ended once
    assert P[0] == pytest.approx([2 / 5, 2 / 5, 0, 1 / 5])
    # r2: to assembled twice, to ended once
    assert P[1] == pytest.approx([0, 0, 2 / 3, 1 / 3])
    assert c.initial == pytest.approx([3 / 4, 1 / 4, 0, 0])
    assert list(low_phase_hits(seqs)) == [3, -1, 1, -1]
    curve = c.p_goal_by(50, ["assembled"])
    ab = c.absorption().of(c.initial[:2])
    assert curve[-1] == pytest.approx(ab["assembled"], abs=1e-9)
    assert ab["assembled"] + ab["ended"] == pytest.approx(1.0)


def test_no_sequences_is_refused():
    with pytest.raises(InvalidStateError, match="low phase"):
        low_phase_chain([])


def test_a_state_without_data_ends():
    c = low_phase_chain([["r1", "assembled"], ["r2"] + ["ended"]])
    assert c.P[c.labels.index("r2"), c.labels.index("ended")] == 1.0
    assert np.allclose(c.P.sum(axis=1), 1.0)
