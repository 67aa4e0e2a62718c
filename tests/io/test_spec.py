"""One system spec: every config declares part, arm, wall, α and noise with the same schema and the library's rules."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings, strategies as st
from pydantic import BaseModel, ValidationError

import throwmap as tm
from throwmap.errors import InvalidArmError, InvalidStateError
from throwmap.io.spec import Angle, ArmSpec, Friction, NoiseSpec, Omega, SystemSpec, WallSpec
from throwmap.system.arm import check_length, check_mu
from throwmap.system.starts import check_omega
from throwmap.system.system import check_alpha


class Rates(BaseModel):
    omega: Omega = 1.0
    mu: Friction = 1.0
    alpha: Angle = 0.0


def _library_accepts(check, value) -> bool:
    try:
        check(value)
    except (InvalidArmError, InvalidStateError):
        return False
    return True


def _spec_accepts(field: str, value) -> bool:
    try:
        Rates.model_validate({field: value})
    except ValidationError:
        return False
    return True


@settings(max_examples=200, deadline=None)
@given(st.one_of(st.floats(allow_nan=True, allow_infinity=True), st.integers(-10, 10)))
def test_each_rule_is_the_library_s_own(value):
    """The spec accepts exactly what the library's checks accept (one statement of each rule)."""
    assert _spec_accepts("omega", value) == _library_accepts(check_omega, value)
    assert _spec_accepts("mu", value) == _library_accepts(check_mu, value)
    assert _spec_accepts("alpha", value) == _library_accepts(check_alpha, value)


@pytest.mark.parametrize("text", [math.inf, "inf", "Infinity", None])
def test_mu_infinity_has_one_meaning(text):
    assert ArmSpec.model_validate({"h": -0.01, "mu": text}).mu == math.inf


@pytest.mark.parametrize("value", [True, "1.0", "lots", -0.5, math.nan])
def test_bad_mu_is_refused(value):
    with pytest.raises(ValidationError):
        ArmSpec.model_validate({"h": -0.01, "mu": value})


@pytest.mark.parametrize("length", [None, math.inf, "inf"])
def test_an_unbounded_arm_has_one_meaning(length):
    assert ArmSpec.model_validate({"h": -0.01, "length": length}).arm().length is None


def test_lengths_follow_the_arm_s_rule():
    assert _library_accepts(check_length, 0.5) and not _library_accepts(check_length, 0.0)
    with pytest.raises(ValidationError):
        ArmSpec.model_validate({"h": -0.01, "length": 0})


def test_the_spec_builds_the_arm_and_its_defaults():
    a = ArmSpec(h=-0.02, length=0.4, mu=0.7, back=0.01)
    assert a.arm() == tm.Arm(h=-0.02, length=0.4, mu=0.7, back=0.01)
    assert ArmSpec.of(a.arm()) == a
    assert ArmSpec(mu=0.5).arm(h=-0.03) == tm.Arm(h=-0.03, mu=0.5)  # a design's h fills the gap
    with pytest.raises(InvalidArmError, match="h"):
        ArmSpec(mu=0.5).arm()


class Cfg(SystemSpec):
    arm: ArmSpec = ArmSpec(h=-0.01, length=0.5, mu=0.8)


def test_a_table_overrides_only_the_keys_it_names():
    c = Cfg.model_validate({"arm": {"mu": 0.3}})
    assert c.arm == ArmSpec(h=-0.01, length=0.5, mu=0.3)
    assert Cfg.model_validate({}).arm == Cfg().arm


def test_the_system_builds_part_arm_fixtures_noise():
    c = Cfg.model_validate({"part": "pentagon", "alpha": 0.05, "wall": {"height": 0.04, "mu": "inf"},
                            "noise": {"omega_rel": 0.02}})
    assert c.build_part().n_sides == 5
    assert c.build_arm() == tm.Arm(h=-0.01, length=0.5, mu=0.8)
    (wall,) = c.fixtures()
    assert wall == tm.Wall(height=0.04, mu=math.inf)
    assert c.noise_model().omega_rel == 0.02
    with pytest.raises(ValidationError):
        Cfg.model_validate({"alpha": 2.0})  # |α| < π/2
    with pytest.raises(ValidationError):
        Cfg.model_validate({"length": 0.5})  # an arm key goes in [arm]
    with pytest.raises(ValidationError):
        WallSpec.model_validate({"height": 0.0})


def test_noise_is_checked_by_the_noise_s_own_rules():
    with pytest.raises(ValidationError, match="mu_range"):
        NoiseSpec.model_validate({"mu_range": [1.0, 0.5]})
    assert NoiseSpec(realisation="recoil", zeta=0.2).noise().realisation_for(4.0).zeta == 0.2


def test_every_config_with_an_arm_embeds_the_one_arm_schema():
    """The experiments, the sweeps' targets and the part files declare the arm with ArmSpec (no second arm)."""
    from throwmap.experiments import get_experiment, experiment_names
    from throwmap.io.config import FileArmSpec
    from throwmap.sweeps import LimitSetConfig, ThrowConfig

    types = [get_experiment(n).config_type for n in experiment_names()] + [ThrowConfig, LimitSetConfig]
    flat = {"h", "g", "length", "back", "wall_height", "wall_mu"}
    for t in types:
        assert not flat & set(t.model_fields), t.__name__
        arm = t.model_fields.get("arm")
        if arm is not None:
            assert arm.annotation is ArmSpec, t.__name__
    assert issubclass(FileArmSpec, ArmSpec)


@pytest.mark.parametrize("key, value", [("omega", True), ("omega", "4.5"), ("max_throws", "3"), ("side", True)])
def test_an_experiment_config_refuses_texts_and_booleans_for_numbers(key, value):
    from throwmap.errors import ConfigError
    from throwmap.experiments import get_experiment
    from throwmap.experiments.base import config_of

    exp = get_experiment("feed")
    with pytest.raises(ConfigError, match=rf"config\.{key}: must be a number"):
        config_of(exp, {"part": "triangle", key: value})


def test_a_wall_typo_names_the_wall_s_keys():
    from throwmap.errors import ConfigError
    from throwmap.experiments import get_experiment
    from throwmap.experiments.base import config_of

    with pytest.raises(ConfigError, match=r"config\.wall\.heigth: unknown key 'heigth' \(did you mean 'height'\? "
                                          r"allowed: height, mu\)"):
        config_of(get_experiment("settle"), {"part": "triangle", "arm": {"length": 0.4}, "wall": {"heigth": 0.05}})
