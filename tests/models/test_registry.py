"""The model layer: registry, System, options dataclasses, features, the single default model."""

from dataclasses import FrozenInstanceError, dataclass

import numpy as np
import pytest

import throwmap as tm
from throwmap.errors import InvalidStateError
from throwmap.models import DEFAULT_MODEL, BatchArrays, Features, ThrowModel, get_model, model_names, register
from throwmap.models.paper import PaperOptions
from throwmap.models.registry import unregister
from throwmap.models.rigid_body import RigidBodyOptions
from throwmap.system.fixtures import Cavity, Wall
from throwmap.system.system import System

TRI = tm.triangle_30_60_90(0.17)
ARM = tm.Arm(h=-0.01, mu=1.5)
BUILTINS = ("paper", "small_angle", "small_angle2", "rigid_body", "engine", "mujoco")


def test_builtins_registered_in_order_and_implement_the_protocol():
    assert model_names()[: len(BUILTINS)] == BUILTINS
    assert tm.MODELS == BUILTINS
    for name in BUILTINS:
        m = get_model(name)
        assert isinstance(m, ThrowModel) and m.name == name and m.summary
        opts = m.options_type()
        with pytest.raises((FrozenInstanceError, AttributeError, TypeError)):
            opts.__setattr__("nonexistent_field", 1)


def test_one_default_model_everywhere():
    assert DEFAULT_MODEL == tm.DEFAULT_MODEL == "rigid_body"
    slippery = tm.Arm(h=-0.01, mu=0.5)
    rb = tm.throw(TRI, slippery, 0.2, 0, 4.0, model="rigid_body")
    d = tm.throw(TRI, slippery, 0.2, 0, 4.0)
    assert d.model == "rigid_body" and (d.x, d.side, d.status) == (rb.x, rb.side, rb.status)
    assert tm.throw_batch(TRI, slippery, [0.2], 0, 4.0).x[0] == rb.x
    assert tm.iterate(TRI, slippery, (0.2, 0), 4.0, n=3).x[1] == rb.x
    assert tm.ThrowMap(TRI, slippery, 4.0).model == "rigid_body"
    # the part slips at μ = 0.5, so "paper" lands elsewhere: the default really is rigid_body
    assert abs(tm.throw(TRI, slippery, 0.2, 0, 4.0, model="paper").x - d.x) > 1e-3


def test_unknown_model_is_one_line_naming_the_field():
    with pytest.raises(InvalidStateError) as err:
        tm.throw(TRI, ARM, 0.2, 0, 4.0, model="exact")
    assert str(err.value).startswith("model: unknown model 'exact'") and "\n" not in str(err.value)


@pytest.mark.parametrize("model, kw, field", [
    ("paper", {"fixtures": (Wall(),)}, "fixtures"),
    ("rigid_body", {"fixtures": (Cavity(((0.05, 0.0), (0.05, -0.01), (0.0, -0.01))),)}, "fixtures"),
    ("small_angle", {"alpha": 0.1}, "alpha"),
    ("small_angle2", {"alpha": -0.17}, "alpha"),
    ("rigid_body", {"alpha": 2.0}, "alpha"),  # |α| < π/2
    ("paper", {"alpha": -1.6}, "alpha"),
    ("paper", {"settings": None}, "settings"),
    ("paper", {"realisation": None}, "realisation"),
    ("rigid_body", {"n_samples": 8}, "n_samples"),
    ("engine", {"colour": "red"}, "colour"),
    ("paper", {"tol": -1.0}, "tol"),
    ("paper", {"max_impacts": 0}, "max_impacts"),
    ("rigid_body", {"max_iter": 2.5}, "max_iter"),
    ("engine", {"workers": -2}, "workers"),
    ("paper", {"options": RigidBodyOptions()}, "options"),
    ("paper", {"fixtures": (1,)}, "fixtures[0]"),
    ("engine", {"alpha": float("nan")}, "alpha"),
])
def test_unsupported_features_and_bad_options_are_refused(model, kw, field):
    for call in (lambda: tm.throw(TRI, ARM, 0.2, 0, 4.0, model=model, **kw),
                 lambda: tm.throw_batch(TRI, ARM, [0.2], 0, 4.0, model=model, **kw)):
        with pytest.raises(InvalidStateError) as err:
            call()
        assert err.value.field == field, str(err.value)
        assert "\n" not in str(err.value)


def test_feature_refusal_names_the_models_that_support_it():
    with pytest.raises(InvalidStateError, match=r"only the 'rigid_body', 'engine' models take 'fixtures' \(model is 'paper'\)"):
        tm.throw(TRI, ARM, 0.2, 0, 4.0, model="paper", fixtures=(Wall(),))
    with pytest.raises(InvalidStateError, match=r"only the 'engine', 'mujoco' models take 'settings'"):
        tm.throw(TRI, ARM, 0.2, 0, 4.0, model="rigid_body", settings=None)


def test_options_instance_equals_keywords():
    a = tm.throw(TRI, ARM, 0.4, 1, 10.0, model="paper", options=PaperOptions(max_impacts=2))
    b = tm.throw(TRI, ARM, 0.4, 1, 10.0, model="paper", max_impacts=2)
    c = tm.throw(TRI, ARM, 0.4, 1, 10.0, model="paper", options=PaperOptions(max_impacts=2), max_impacts=2)
    assert a.to_dict() == b.to_dict() == c.to_dict()
    with pytest.raises(InvalidStateError, match="^max_impacts: given twice"):  # a contradiction is refused
        tm.throw(TRI, ARM, 0.4, 1, 10.0, model="paper", options=PaperOptions(max_impacts=50), max_impacts=2)
    assert a.status == tm.Status.NO_REST  # the cap really reached the kernel
    assert tm.throw(TRI, ARM, 0.4, 1, 10.0, model="paper").status != tm.Status.NO_REST


def test_system_value():
    s = System(ARM)
    assert s.plain and s.fixtures == () and s.alpha == 0.0
    s2 = System(ARM, Wall(), 0.1)
    assert s2.fixtures == (Wall(),) and not s2.plain
    with pytest.raises(InvalidStateError, match="^arm:"):
        System("arm")
    with pytest.raises(InvalidStateError, match="^fixtures:"):
        System(ARM, 3)
    with pytest.raises(FrozenInstanceError):
        s.alpha = 1.0


def test_features_are_declared():
    assert get_model("engine").features.fixtures and get_model("engine").features.tilt
    for name in ("paper", "small_angle", "small_angle2", "rigid_body"):
        f = get_model(name).features
        # rigid_body: a Wall (not a Cavity), and a moving arm (realisation=, kernels/rigid_body/moving)
        assert f.fixtures == (name == "rigid_body") and f.realisation == (name == "rigid_body")
        assert f.tilt == (name in ("paper", "rigid_body"))
    assert get_model("rigid_body").features.friction and not get_model("paper").features.friction
    assert set(get_model("engine").features.supported()) >= {"fixtures", "tilt", "realisation", "trajectory"}


@pytest.mark.parametrize("model", ["paper", "small_angle", "small_angle2", "rigid_body"])
def test_batch_equals_single_through_the_registry(model):
    rng = np.random.default_rng(3)
    k = rng.choice(TRI.stable_sides, 40)
    x = np.array([rng.uniform(TRI.x_min(s) + 1e-3, 0.5) for s in k])
    om = rng.uniform(0.5, 7.0, 40)
    b = tm.throw_batch(TRI, ARM, x, k, om, model=model)
    for i in range(40):
        o = tm.throw(TRI, ARM, x[i], int(k[i]), om[i], model=model)
        assert (o.x, o.side, int(o.status)) == (b.x[i], b.side[i], b.status[i])
        same = tm.ThrowOutcome.from_record(TRI, x[i], int(k[i]), om[i], model, b.x[i], b.side[i], b.status[i],
                                           b.records[i])
        assert same.to_dict() == o.to_dict()


@pytest.mark.parametrize("model", ["paper", "rigid_body"])
def test_outcome_record_round_trip(model):
    for x, s, om in [(0.2, 0, 4.0), (0.34, 1, 4.0), (0.5, 2, 6.0), (0.12, 0, 0.0)]:
        o = tm.throw(TRI, ARM, x, s, om, model=model)
        row = o.to_record(TRI)
        b = tm.throw_batch(TRI, ARM, [x], s, om, model=model).records[0]
        keep = ~np.isnan(b)
        np.testing.assert_allclose(row[keep], b[keep], rtol=1e-12, atol=0)
        back = tm.ThrowOutcome.from_record(TRI, x, s, om, model, o.x, o.side, int(o.status), row)
        assert back == o or (np.isnan(o.t_rest) and back.x == o.x and back.side == o.side)


@dataclass(frozen=True, slots=True)
class PullOptions:
    x_star: float = 0.3
    k: float = 0.5


class Pull:
    """A toy model: x' = x* + k (x − x*), same side (a contraction, to test registration only)."""

    name = "test_pull"
    summary = "pulls every part toward x_star"
    options_type = PullOptions
    features = Features()

    def throw_one(self, part, system, x, side, omega, o):
        return o.x_star + o.k * (x - o.x_star), side, 0, np.zeros(tm.kernels.codes.NREC)

    def throw_batch(self, part, system, x, side, omega, valid, o, progress=None):
        return BatchArrays(o.x_star + o.k * (x - o.x_star), side.copy(), np.where(valid, 0, 4).astype(np.int64),
                           np.zeros((x.size, tm.kernels.codes.NREC)))

    def trajectory(self, part, system, x, side, omega, o, dt):
        raise NotImplementedError


def test_a_registered_model_works_everywhere_by_name():
    register(Pull())
    try:
        assert "test_pull" in model_names()
        assert tm.throw(TRI, ARM, 0.2, 0, 4.0, model="test_pull", k=0.0).x == pytest.approx(0.3)
        b = tm.throw_batch(TRI, ARM, [0.2, 0.4], 1, 4.0, model="test_pull")
        np.testing.assert_allclose(b.x, [0.25, 0.35])
        orbit = tm.iterate(TRI, ARM, (0.1, 0), 4.0, n=5, model="test_pull")
        np.testing.assert_allclose(orbit.x, 0.3 - 0.2 * 0.5 ** np.arange(6))
        ls = tm.limit_set(TRI, ARM, 4.0, model="test_pull", n_starts=8)
        assert ls.attractors and all(a.kind == "fixed_point" for a in ls.attractors)
        assert sorted(a.bands[0][1] for a in ls.attractors) == pytest.approx([0.3] * len(TRI.stable_sides), abs=1e-6)
        with pytest.raises(InvalidStateError, match="already registered"):
            register(Pull())
    finally:
        unregister("test_pull")
    with pytest.raises(InvalidStateError, match="^model:"):
        tm.throw(TRI, ARM, 0.2, 0, 4.0, model="test_pull")


def test_register_refuses_non_models():
    with pytest.raises(InvalidStateError, match="^model:"):
        register(object())


def test_mujoco_model_matches_the_backend():
    pytest.importorskip("mujoco")
    from throwmap.engine import mujoco as mb

    direct = mb.mujoco_throw(TRI, ARM, 0.25, 0, 4.0)
    o = tm.throw(TRI, ARM, 0.25, 0, 4.0, model="mujoco")
    assert (o.x, o.side, o.status) == (direct.x, direct.side, direct.status)
    b = tm.throw_batch(TRI, ARM, [0.25, 0.0], 0, 4.0, model="mujoco", on_invalid="status")
    assert b.x[0] == direct.x and b.status[1] == tm.Status.INVALID_START


def test_the_readme_example_model_reproduces_paper_at_zero_jitter(tmp_path):
    import importlib.util
    import sys
    from pathlib import Path

    path = Path(__file__).parents[2] / "examples" / "custom_model.py"
    spec = importlib.util.spec_from_file_location("custom_model", path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # dataclasses look their module up
    spec.loader.exec_module(mod)
    res = mod.main(tmp_path)
    assert res["sigma0_equals_paper"]
    assert 0 < res["jitter_x_std_m"] < 0.01  # the jitter really spreads the landings, by millimetres
    assert "paper_jitter" not in model_names()  # main() unregisters it
