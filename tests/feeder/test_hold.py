"""The in-pocket hold check on the examples' recoil feeder (fed 99.5 % in the engine): it keeps its side through
every throw of the check. (A pocket that lets its side go is dropped by the search: tests/feeder/test_search.py.)"""

from __future__ import annotations

from pathlib import Path

import pytest

from throwmap.experiments.base import read_config
from throwmap.experiments.feed import Feed
from throwmap.feeder.hold import HOLD_THROWS, HOLD_Z, pocket_hold

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
def test_the_examples_recoil_feeder_holds_its_side_in_its_pocket():
    h = pocket_hold(read_config(Feed(), ROOT / "examples" / "feed_recoil.toml"))
    assert h.held and h.throws == len(HOLD_Z) * HOLD_THROWS and h.z is None and h.ended == "target"
