"""The feeder screen: candidates ranked by their exact-model end-wall windows, checked by throwing the part.

Independent check of a window's claim: on the pocket's floor (the arm lowered by the depth), the target side
resting against the end wall (CM at L − u_R) jogs at ω(1 − σ) and ω(1 + 3σ), and every other side resting there
flips — thrown one at a time with ``throwmap.throw``, not through the cavity design's jog map.
"""

from __future__ import annotations

import math

import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError
from throwmap.feeder import feeder_files, screen
from throwmap.records.outcome import Status

SMALL = dict(omegas=(4.0, 4.75), hs=(0.0, -0.01), depths=(0.01,))


@pytest.fixture(scope="module")
def tri_screen():
    return screen(tm.triangle_30_60_90(0.17), **SMALL)


def test_candidates_are_ranked_by_window_width(tri_screen):
    s = tri_screen
    assert len(s.candidates) == 3 * 2 * 2 * 1
    widths = [c.width for c in s.candidates]
    assert widths == sorted(widths, reverse=True)
    assert all((c.window is None) == (c.width == 0.0) for c in s.candidates)
    assert s.best() is s.candidates[0] and s.best().window is not None
    assert s.separable() and s.reason() == ""


@pytest.mark.filterwarnings("ignore::throwmap.errors.RegimeWarning")
def test_the_best_window_holds_its_side_and_releases_the_others(tri_screen):
    s = tri_screen
    part = s.part
    for c in [c for c in s.candidates if c.window][:2]:
        floor = tm.Arm(h=c.h - c.depth, mu=s.mu)
        for L in (c.window[0], c.length, c.window[1]):
            for w in (c.omega * (1 - s.sigma), c.omega * (1 + 3 * s.sigma)):
                for k in part.stable_sides:
                    x = L - float(part.uR[k])
                    if x + float(part.uL[k]) <= 0:
                        continue
                    out = tm.throw(part, floor, x, k, w, "rigid_body")
                    jog = out.status == Status.OK and out.side == k
                    assert jog == (k == c.side), (c, L, w, k, out.status, out.side)


def test_a_part_whose_sides_are_alike_cannot_be_separated():
    s = screen(tm.rectangle(0.06, 0.06), omegas=(3.0, 4.0), hs=(-0.01,), depths=(0.01,))
    assert s.separable() == () and s.best() is None
    assert "no end-wall pocket holds one side alone" in s.reason() and "3–4 rad/s" in s.reason()


def test_the_files_run_as_the_feed_experiment_reads_them(tri_screen, tmp_path):
    from throwmap.experiments.base import read_config
    from throwmap.experiments.feed import Feed

    c = tri_screen.best()
    path = feeder_files(c, tri_screen, tmp_path / "fd")
    cfg = read_config(Feed(), path)
    part, arm, fixtures, omega, side, design = Feed().setup(cfg)
    assert (side, omega, cfg.arm.h, cfg.cavity.depth) == (c.side, c.omega, c.h, c.depth)
    assert arm.length == pytest.approx(c.length) and math.isclose(arm.mu, tri_screen.mu)
    assert [c for v in part.vertices for c in v] == pytest.approx([c for v in tri_screen.part.vertices for c in v])
    assert cfg.noise.realisation == "recoil" and cfg.noise.omega_rel == tri_screen.sigma


@pytest.mark.parametrize("kw, field", [({"omegas": ()}, "omegas"), ({"depths": (-0.01,)}, "depths"),
                                       ({"hs": (math.nan,)}, "hs"), ({"sigma": -0.1}, "sigma"), ({"sides": (7,)}, "side")])
def test_bad_input_names_its_field(kw, field):
    with pytest.raises(InvalidStateError) as err:
        screen(tm.triangle_30_60_90(0.17), **{**SMALL, **kw})
    assert err.value.field == field


def test_a_candidate_without_a_window_writes_no_files(tri_screen, tmp_path):
    bare = next(c for c in tri_screen.candidates if c.window is None)
    with pytest.raises(InvalidStateError) as err:
        feeder_files(bare, tri_screen, tmp_path / "x")
    assert err.value.field == "candidate" and not (tmp_path / "x" / "feeder.toml").exists()
