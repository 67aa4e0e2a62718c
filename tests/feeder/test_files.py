"""The files a found feeder is written as: its pocket config skips the floor's throw-map window, which changes no
trial."""

from __future__ import annotations

from importlib import resources

from throwmap.experiments.base import read_config
from throwmap.experiments.feed import Feed, build_design
from throwmap.experiments.runner import run_experiment


def test_a_pocket_without_its_window_runs_the_same_trials():
    """``[cavity] window = false`` (what ``feeder.toml`` says: the search placed the wall) leaves out the window on
    the floor's throw map, a report only: the same seed gives the same trials, pocket and wall; only the window's
    checks are gone."""
    with resources.as_file(resources.files("throwmap").joinpath("data/feed_recoil.toml")) as path:
        cfg = read_config(Feed(), path)
    bare = cfg.model_copy(update={"cavity": cfg.cavity.model_copy(update={"window": False})})
    full, quick = build_design(cfg), build_design(bare)
    assert full.jogs is not None and quick.jogs is None
    assert (quick.length, quick.wall.height, quick.cavity.profile) == (full.length, full.wall.height,
                                                                       full.cavity.profile)
    assert {c.name for c in full.checks} - {c.name for c in quick.checks} == {"window", "hold", "release_1",
                                                                              "release_2"}
    a, b = (run_experiment("feed", c, n=2, seed=3, workers=1) for c in (cfg, bare))
    assert [t.to_json() for t in a.trials] == [t.to_json() for t in b.trials]


def test_a_pocket_without_its_window_needs_its_length():
    import pytest
    from pydantic import ValidationError

    from throwmap.design.cavity import Pocket
    from throwmap.errors import InvalidStateError
    from throwmap.experiments.feed import CavityConfig

    with pytest.raises(InvalidStateError) as err:
        Pocket(window=False)
    assert err.value.field == "window"
    with pytest.raises(ValidationError, match="window may be false only with the length given"):
        CavityConfig(window=False)
    assert CavityConfig(window=False, length=0.4).window is False
