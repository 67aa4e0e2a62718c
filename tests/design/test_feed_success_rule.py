"""The success rule of a design: at most MAX_ESCAPE (10 %) of the starts may escape, all kinds of escape together,
exactly 10 % included; a lead weight up to MAX_WEIGHT (10 kg, that included) is taken."""

from types import SimpleNamespace

import pytest

import throwmap as tm
import throwmap.analysis.limitset as limitset
from throwmap.design.api import MAX_ESCAPE, MAX_WEIGHT, SpaceOptions, _holds_on_arm, design
from throwmap.errors import InvalidStateError

PLATE = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01, length=0.6)
DESIGNED = SimpleNamespace(part=PLATE, arm=ARM, omega=4.0)


def _holds(monkeypatch, escapes):
    monkeypatch.setattr(limitset, "limit_set", lambda *a, **kw: SimpleNamespace(attractors=("one",), escapes=escapes))
    return _holds_on_arm(DESIGNED, "rigid_body", 0.6, None)


def test_exactly_the_allowed_share_escaping_still_holds(monkeypatch):
    assert MAX_ESCAPE == 0.10
    holds, what = _holds(monkeypatch, {"off_end": 0.10})
    assert holds, what


def test_escapes_of_both_kinds_are_counted_together(monkeypatch):
    holds, what = _holds(monkeypatch, {"off_end": 0.06, "behind_joint": 0.06})
    assert not holds and "12.0 % of the starts escape" in what
    assert _holds(monkeypatch, {"off_end": 0.04, "behind_joint": 0.05})[0]


def test_the_heaviest_allowed_weight_passes_its_check():
    assert MAX_WEIGHT == 10.0
    # 10 kg passes the weight check: the next check (an unknown bound) is the one that refuses
    with pytest.raises(InvalidStateError, match=r"^bounds: "):
        design(PLATE, ARM, 4.0, {0: 0.40, 1: 0.25, 2: 0.25}, weight_mass=MAX_WEIGHT, weight_at=(0.03, 0.03),
               space=SpaceOptions(bounds={"omgea": (1.0, 9.0)}))
