"""The feeding experiment (issue 11, item 3): seeded trials end to end through the runner, refusals
counted as refusals, the open variant, config errors.

Short runs on the impulse arm (its cavity design uses the exact model: about a second) with few
throws; the full experiment's numbers are in docs/how-to/feeding.md and /tmp evidence, not asserted here.
"""

import math

import pytest

from throwmap.errors import ConfigError
from throwmap.experiments import get_experiment
from throwmap.experiments.base import config_of, trial_generator
from throwmap.experiments.runner import run_experiment

QUICK = {"noise": {"omega_rel": 0.03, "mu_rel": 0.1, "realisation": "impulse"}, "max_throws": 6, "hold_throws": 3}
KINDS = {"wrong_side_captured", "tilted_in_cavity", "ejected", "not_captured", "off_arm"}


@pytest.mark.slow
def test_seeded_trials_run_end_to_end_and_repeat():
    a = run_experiment("feed", QUICK, n=3, seed=11, workers=1)
    b = run_experiment("feed", QUICK, n=3, seed=11, workers=1)
    assert [t.to_json() for t in a.trials] == [t.to_json() for t in b.trials]
    assert a.n == 3 and a.successes == sum(t.success for t in a.trials)
    lo, hi = a.ci95
    assert 0.0 <= lo <= a.success_rate <= hi <= 1.0
    for t in a.trials:
        assert t.success or t.failure in KINDS or t.failure.startswith("refused:")
        v = t.values
        assert 1 <= v["throws"] <= QUICK["max_throws"] + QUICK["hold_throws"]
        if t.success:  # captured within the cap, then held through exactly hold_throws more throws
            assert v["where"] == "target" and v["side"] == 0
            assert v["throws"] == v["throws_to_capture"] + QUICK["hold_throws"]
        elif t.failure == "not_captured":
            assert math.isnan(v["throws_to_capture"]) and v["throws"] == QUICK["max_throws"]
    checks = a.parameters["cavity"]["exact_checks"]  # the design's forecast, not named as the run's success
    assert checks["passed"] in (True, False) and "success" not in a.parameters["cavity"]
    assert a.parameters["hold_throws"] == 3 and a.parameters["noise"]["omega_rel"] == 0.03


@pytest.mark.slow
def test_engine_refusal_is_a_failure_never_a_success():
    # a tiny drop settles within 0.15 s; every throw needs ≈ 0.3 s of flight, so the engine times out
    cfg = dict(QUICK, height=(0.0, 0.001), settings={"t_max": 0.15, "settle_hold": 0.02, "verify": False, "retries": 0})
    res = run_experiment("feed", cfg, n=2, seed=5, workers=1)
    assert res.successes == 0
    assert all(t.failure.startswith("refused:") for t in res.trials)
    assert sum(res.failures.values()) == 2 and all(k.startswith("refused:") for k in res.failures)


@pytest.mark.slow
def test_open_variant_feeds_off_the_end():
    exp = get_experiment("feed")
    cfg = config_of(exp, dict(QUICK, variant="open", max_throws=40))
    t = exp.trial(cfg, 0, trial_generator(2, 0))
    assert t.success or t.failure in {"wrong_side", "behind_joint", "not_fed"} or t.failure.startswith("refused:")
    if t.failure != "not_fed" and not (t.failure or "").startswith("refused:") and t.failure != "behind_joint":
        assert t.values["where"] == "off_end" and t.success == (t.values["side_before"] == 0)
    assert exp.parameters(cfg)["length_m"] > 0


def test_config_errors_name_the_field():
    exp = get_experiment("feed")
    with pytest.raises(ConfigError, match="variant"):
        config_of(exp, {"variant": "ajar"})
    with pytest.raises(ConfigError, match="hold_thorws|allowed"):
        config_of(exp, {"hold_thorws": 5})
    with pytest.raises(ConfigError, match="fixture"):
        config_of(exp, {"fixture": "trough"})
    with pytest.raises(ConfigError, match="clear_every"):
        config_of(exp, {"clear_every": -1})
    cfg = config_of(exp, None)
    assert cfg.hold_throws == 50 and cfg.noise.omega_rel == 0.03 and cfg.noise.realisation == "recoil"


def test_builtin_example_is_the_recoil_feeder_of_examples():
    # no CONFIG runs the >= 99 % recoil feeder: the packaged copy equals examples/feed_recoil.toml and its part
    from pathlib import Path

    from throwmap.experiments.base import read_config

    root = Path(__file__).resolve().parents[2]
    for name in ("feed_recoil.toml", "recoil_feeder.toml"):
        assert (root / "src/throwmap/data" / name).read_bytes() == (root / "examples" / name).read_bytes(), name
    exp = get_experiment("feed")
    builtin, example = config_of(exp, None), read_config(exp, root / "examples/feed_recoil.toml")
    assert builtin.model_dump(exclude={"part"}) == example.model_dump(exclude={"part"})
    assert builtin.part.endswith("recoil_feeder.toml") and builtin.cavity.length == 0.38
    assert builtin.noise.realisation == "recoil" and builtin.noise.omega_rel == 0.03


def test_plain_end_wall_fixture_classifies_rest_poses():
    # fixture "wall": the feeder design's end-wall window, a wall above the energy bound; a part resting
    # flush against it is "target" only on the target side, one far from it is "outside"
    from throwmap.design import feeder_design
    from throwmap.experiments.feed import FeedConfig, build_wall
    from throwmap.system.pose import pose_at_rest

    fd = feeder_design()
    d = build_wall(FeedConfig(fixture="wall"))
    lo, hi = fd.wall_window
    assert lo < d.arm.length < hi and d.fixtures == (d.wall,)
    assert d.wall.height > d.numbers["rise_bound_m"] and d.wall.mu == 0.0
    part, h, L = d.part, d.arm.h, d.arm.length
    assert d.where(pose_at_rest(part, h, L - float(part.uR[0]) - 1e-4, 0)) == "target"
    assert d.where(pose_at_rest(part, h, L - float(part.uR[2]) - 1e-4, 2)) == "other"
    assert d.where(pose_at_rest(part, h, 0.12, 0)) == "outside"
    exp = get_experiment("feed")
    cfg = config_of(exp, {"fixture": "wall", "wall": {"length": 0.31}})
    assert exp.parameters(cfg)["wall"]["length_m"] == 0.31 and "cavity" not in exp.parameters(cfg)


@pytest.mark.slow
def test_clearing_throws_raise_the_wall_and_the_throw_rate():
    from throwmap.experiments.feed import FeedConfig, build_design

    base = {"noise": QUICK["noise"]}
    plain = build_design(FeedConfig.model_validate(base))
    cleared = build_design(FeedConfig.model_validate(dict(base, clear_every=2, clear_factor=1.5)))
    assert FeedConfig().clear_every == 0  # the default protocol has no clearing throws
    rise = plain.numbers["rise_bound_m"]
    assert math.isclose(cleared.wall.height - plain.wall.height, 1.25 * rise, rel_tol=1e-12)
    assert cleared.length == plain.length and cleared.cavity == plain.cavity
    exp = get_experiment("feed")
    cfg = config_of(exp, dict(QUICK, clear_every=2, clear_factor=1.5, max_throws=4, hold_throws=0))
    t = exp.trial(cfg, 0, trial_generator(3, 0))
    if t.values["throws"] >= 2:  # throw 2 was a clearing throw: ω·1.5·(1 + 0.03 N), N > −6
        assert t.values["omega_max"] > 1.5 * 0.82 * exp.setup(cfg)[3]


def test_left_in_the_fixture_is_named_by_side():
    from throwmap.experiments.feed import Feed

    assert Feed._other((0.3, 0, 0.1), 0) == "tilted_in_cavity"
    assert Feed._other((0.3, 2, 0.0), 0) == "wrong_side_captured"
