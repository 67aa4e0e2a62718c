"""The recoil feeder's experiment config (examples/feed_recoil.toml) as a user runs it."""

import os
from pathlib import Path

import pytest

from throwmap.experiments.base import read_config, trial_generator
from throwmap.experiments.feed import FEED

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / "examples" / "feed_recoil.toml"


def test_config_reads_from_any_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the part file is named relative to the config file
    cfg = read_config(FEED, CONFIG)
    assert Path(cfg.part).is_file()
    part, arm, fixtures, omega, side, design = FEED.setup(cfg)
    assert arm.length == pytest.approx(0.38)
    assert design.cavity.depth == pytest.approx(0.01)
    # the pocket's floor and end wall lined (μ 0.2): a lean on the wall slides flat (tests/design/test_cavity_lined.py)
    assert design.cavity.lined and design.wall.mu == pytest.approx(0.2)
    assert any(getattr(f, "lined", False) for f in fixtures)  # what the trials simulate
    # side 0 (17 cm) lies in the pocket: its floor is longer than the side
    assert design.numbers["floor_m"] >= float(part.length[side])
    # the chute drops clear of the end wall: every side's outer vertex short of L from the farthest drop
    assert max(cfg.x_range[1] + float(u) for u in part.uR) < arm.length
    assert cfg.x_range == (0.0, 0.25) and cfg.settings == {"agreement": 0.005, "retries": 4}


def test_config_part_missing_is_named(tmp_path):
    bad = tmp_path / "feed.toml"
    bad.write_text('part = "nowhere.toml"\nside = 0\nomega = 4.5\n[arm]\nh = -0.02\n')
    from throwmap.errors import ThrowmapError

    cfg = read_config(FEED, bad)
    with pytest.raises(ThrowmapError):
        FEED.setup(cfg)


@pytest.mark.slow
def test_one_trial_runs_and_reports(tmp_path):
    cfg = read_config(FEED, CONFIG).model_copy(update={"max_throws": 40, "hold_throws": 3})
    t = FEED.trial(cfg, 0, trial_generator(5, 0))
    assert t.success in (True, False)
    assert t.success == (t.failure is None)
    assert 1 <= t.values["throws"] <= 43
    lo, hi = cfg.x_range
    assert lo - 1e-9 <= t.values["release_x"] <= hi + 1e-9  # drop_x is where it settled, which may lie beyond


@pytest.mark.parametrize("change, field", [
    ({"x_range": (0.25, 0.0)}, "config.x_range"),
    ({"x_range": (-0.1, -0.05)}, "config.x_range"),
    ({"x_range": (0.5, 0.6)}, "config.x_range"),
])
def test_bad_drop_range_is_refused_before_any_trial(change, field):
    from throwmap.errors import InvalidStateError

    cfg = read_config(FEED, CONFIG).model_copy(update=change)
    with pytest.raises(InvalidStateError) as err:
        FEED.setup(cfg)
    assert err.value.field == field


def test_side_must_be_an_integer(tmp_path):
    from throwmap.errors import ConfigError

    bad = tmp_path / "feed.toml"
    bad.write_text(CONFIG.read_text().replace("side = 0", "side = 0.0").replace(
        'part = "recoil_feeder.toml"', f'part = "{ROOT / "examples" / "recoil_feeder.toml"}"'))
    with pytest.raises(ConfigError, match="side"):
        read_config(FEED, bad)


def test_missing_part_file_names_config_part(tmp_path):
    from throwmap.errors import ThrowmapError

    cfg = tmp_path / "feed.toml"
    cfg.write_text('part = "nowhere.toml"\nside = 0\nomega = 4.5\n[arm]\nh = -0.02\n')
    with pytest.raises(ThrowmapError) as err:
        FEED.setup(read_config(FEED, cfg))
    assert err.value.field == "config.part" and "next to the config file" in err.value.reason
