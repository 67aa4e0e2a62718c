"""Experiment ``assemble`` (paper Sec. VI): the engine with two parts, the pair sensor, the assembled predicate,
the contract and a resumed run."""

import dataclasses
import json
import math

import numpy as np
import pytest

import throwmap as tm
from throwmap.control.pair_sensors import PairSensor, assembled_error, is_assembled, pair_ready
from throwmap.engine import Placement, Scene
from throwmap.errors import InvalidStateError
from throwmap.statics.assembly import assembled_pair
from throwmap.system.fixtures import Wall

PART = tm.triangle_30_60_90()
H, L = -0.01, 0.5
ARM = tm.Arm(h=H, length=L, mu=1.0)
# cheap configs: no randomising throw (a drop, one look), or a sure-to-fire sensor
QUICK = {"max_high": 0}


def _poses(*placements):
    return tuple(Placement(PART, x=x, side=k).arm_pose(H) for x, k in placements)


# -------------------------------------------------------------------------------- the engine with two parts

def test_overlapping_parts_are_one_line_naming_the_placements():
    with pytest.raises(InvalidStateError) as e:
        Scene(ARM, (Placement(PART, x=0.20, side=1), Placement(PART, x=0.25, side=1)), (Wall(0.3),))
    assert e.value.field == "placements"
    assert "placements 0 and 1 overlap by" in str(e.value) and "\n" not in str(e.value)
    Scene(ARM, (Placement(PART, x=0.20, side=1), Placement(PART, x=0.40, side=0)), (Wall(0.3),))  # apart: fine


def test_touching_parts_are_not_refused():
    a, b = assembled_pair(PART, length=L, h=H)  # flush along the hypotenuse: overlap 0
    Scene(ARM, (Placement(PART, pose=(a.x, a.y, a.phi)), Placement(PART, pose=(b.x, b.y, b.phi))), (Wall(0.3),))


def test_a_refused_run_is_counted_never_dropped(monkeypatch):
    import throwmap.engine as engine
    from throwmap.experiments.assemble import Assemble, AssembleConfig
    from throwmap.experiments.base import trial_generator
    from throwmap.records.outcome import Status

    real = engine.simulate
    calls = []

    def fake(scene, realisation=None, settings=None, **kw):
        run = real(scene, realisation, settings, **kw)
        calls.append(1)
        if len(calls) == 2:  # the first randomising throw is refused
            n = len(run.statuses)
            return dataclasses.replace(run, status=Status.PENETRATION, statuses=(Status.PENETRATION,) * n,
                                       message="part 0: a vertex sank 3 mm; result refused")
        return run

    import throwmap.engine.session as engine_session

    monkeypatch.setattr(engine, "simulate", fake)  # the drop
    monkeypatch.setattr(engine_session, "simulate", fake)  # the session's runs
    cfg = AssembleConfig(max_high=3, sensor={"false_negative": 0.99})  # the sensor (almost) never fires
    tr = Assemble().trial(cfg, 0, trial_generator(1, 0))
    assert not tr.success and tr.failure == "refused:penetration" and tr.values["throws_high"] == 1


def test_parts_at_the_wall_are_not_read_off_the_end():
    """Two rests the first engine runs read as off_end: b propped on a's tip at the wall's foot (flat within
    FLAT_TILT, x + u_R past L but no vertex past it), and a part pressed 0.3 mm into the wall by the other."""
    from throwmap.engine.rest import rest_status
    from throwmap.records.outcome import Status
    from throwmap.system.pose import state_from_pose

    propped = (0.4296, 0.0158, 3.6473)  # read off an engine run (the wall's foot vertex at x = 0.5000 m)
    x, k, tilt = state_from_pose(PART, propped)
    assert k == 0 and abs(tilt) < 0.02 and x + PART.uR[0] > L + 1e-4
    assert rest_status(PART, propped, x, k, tilt, H, L, 0.0, False) == Status.OK
    pressed = Placement(PART, x=L - float(PART.uR[2]) + 3e-4, side=2).arm_pose(H)
    assert rest_status(PART, pressed, pressed[0], 2, 0.0, H, L, 0.0, False) == Status.OK
    deep = Placement(PART, x=L - float(PART.uR[2]) + 3e-3, side=2).arm_pose(H)
    assert rest_status(PART, deep, deep[0], 2, 0.0, H, L, 0.0, False) == Status.OFF_END
    assert rest_status(PART, pressed, pressed[0], 2, 0.0, H, L, 0.0, True) == Status.OFF_END  # bare arm: off


# -------------------------------------------------------------------------------- the pair sensor

def test_pair_ready_on_hand_placed_pairs():
    assert pair_ready(PART, _poses((0.20, 1), (0.40, 0))) == (0, 1)
    assert pair_ready(PART, _poses((0.40, 0), (0.20, 1))) == (1, 0)  # either part may play a
    assert pair_ready(PART, _poses((0.40, 1), (0.15, 0))) is None  # a right of b
    assert pair_ready(PART, _poses((0.20, 1), (0.40, 1))) is None  # b not on its hypotenuse
    assert pair_ready(PART, _poses((0.20, 2), (0.40, 0))) is None  # a on its shorter leg
    # a wholly left of b: a's right vertex (x + 0.098) must be left of b's left vertex (x − 0.099)
    assert pair_ready(PART, _poses((0.20, 1), (0.20 + 0.0982 + 0.0992 + 0.001, 0))) == (0, 1)
    assert pair_ready(PART, _poses((0.20, 1), (0.20 + 0.0982 + 0.0992 - 0.001, 0))) is None
    x, y, phi = _poses((0.40, 0))[0]
    assert pair_ready(PART, (_poses((0.20, 1))[0], (x, y, phi + 0.03))) is None  # b tilted 0.03 rad


def test_pair_sensor_error_rates():
    ready, apart = _poses((0.20, 1), (0.40, 0)), _poses((0.20, 1), (0.40, 1))
    rng = np.random.default_rng(3)
    exact = PairSensor()
    assert exact.read(PART, ready, rng) and not exact.read(PART, apart, rng)
    noisy = PairSensor(false_positive=0.2, false_negative=0.1)
    fp = np.mean([noisy.read(PART, apart, rng) for _ in range(4000)])
    fn = 1 - np.mean([noisy.read(PART, ready, rng) for _ in range(4000)])
    assert abs(fp - 0.2) < 0.03 and abs(fn - 0.1) < 0.03
    with pytest.raises(InvalidStateError, match="sensor.false_positive"):
        PairSensor(false_positive=1.0)


# -------------------------------------------------------------------------------- the assembled predicate

def test_assembled_pair_is_assembled_in_either_labelling():
    a, b = assembled_pair(PART, length=L, h=H)
    poses = ((a.x, a.y, a.phi), (b.x, b.y, b.phi))
    assert assembled_error(PART, poses, length=L, h=H) == pytest.approx((0.0, 0.0), abs=1e-12)
    assert is_assembled(PART, poses, length=L, h=H) and is_assembled(PART, poses[::-1], length=L, h=H)
    assert is_assembled(PART, ((a.x - 0.004, a.y, a.phi), poses[1]), length=L, h=H)
    assert not is_assembled(PART, ((a.x - 0.006, a.y, a.phi), poses[1]), length=L, h=H)  # 6 mm > 5 mm
    assert not is_assembled(PART, (poses[0], (b.x, b.y, b.phi + 0.06)), length=L, h=H)  # 0.06 rad > 0.05
    assert not is_assembled(PART, _poses((0.20, 1), (0.40, 0)), length=L, h=H)  # ready, not assembled


# -------------------------------------------------------------------------------- contract and resume

def test_contract_json_keys(tmp_path):
    from throwmap.experiments import experiment_names, run_experiment

    assert "assemble" in experiment_names()
    res = run_experiment("assemble", QUICK, n=2, seed=1, workers=1)
    d = json.loads(json.dumps(res.to_json()))
    for key in ("n", "successes", "success_rate", "ci95", "failures", "seed", "parameters", "config", "values",
                "version", "elapsed_s", "workers", "resumed"):
        assert key in d
    assert d["n"] == 2 and sum(d["failures"].values()) + d["successes"] == 2
    for key in ("throws_high", "throws_low", "throws", "looks", "held_1", "held_hold", "pos_err_m", "mu", "escapes",
                "slides", "resets", "phase"):
        assert key in res.trials[0].values
    assert "throws_high" in d["values"] and "mu" in d["values"]
    p = d["parameters"]
    assert p["alpha_rad"] == pytest.approx(math.radians(-10)) and p["lean_bound"]["beta_star_rad"] > 0.25
    assert p["escape"]["alpha_rad"] > 0 > p["slide"]["alpha_rad"] and p["switch"]["rectangle"] is True
    assert set(d["failures"]) <= {"no_switch", "wrong_switch", "refused:drop"}


def test_bad_config_is_one_line():
    from throwmap.experiments import run_experiment

    from throwmap.errors import ThrowmapError

    with pytest.raises(ThrowmapError) as e:
        run_experiment("assemble", {"omega_lo": 2.0}, n=1, seed=1, workers=1)
    assert "omega_lo" in str(e.value) and "\n" not in str(e.value)


def test_resumed_run(tmp_path):
    from throwmap.experiments import run_experiment

    out = tmp_path / "run"
    first = run_experiment("assemble", QUICK, n=2, seed=4, workers=1, out=out)
    again = run_experiment("assemble", QUICK, n=3, seed=4, workers=1, out=out)
    assert again.resumed == 2 and again.n == 3 and again.trials[:2] == first.trials
    fresh = run_experiment("assemble", QUICK, n=3, seed=4, workers=1)
    assert fresh.trials == again.trials


# -------------------------------------------------------------------------------- engine-heavy

@pytest.mark.slow
def test_a_ready_pair_assembles_and_stays():
    """Hand-placed ready pair: tilt to −10° at 0.1 rad/s, low throws at 2.4 rad/s: assembled, then held."""
    from throwmap.engine import RecoilThrow, TiltTo, simulate
    from throwmap.records.outcome import Status

    scene = Scene(ARM, (Placement(PART, x=0.17, side=1), Placement(PART, x=0.40, side=0)), (Wall(0.7, mu=0.0),))
    run = simulate(scene, TiltTo(math.radians(-10), 0.1))
    assert run.status == Status.OK and pair_ready(PART, run.poses) is not None
    for k in range(60):
        run = simulate(run.next_scene(), RecoilThrow.for_release_rate(2.4))
        assert run.status == Status.OK, run.message  # two parts: no energy-gain or wall-foot off_end refusal
        if is_assembled(PART, run.poses, length=L, h=H):
            break
    assert is_assembled(PART, run.poses, length=L, h=H)
    run = simulate(run.next_scene(), RecoilThrow.for_release_rate(2.4))
    assert run.status == Status.OK and is_assembled(PART, run.poses, length=L, h=H)


# -------------------------------------------------------------------------------- the wider switch and the randomiser's rules

def test_rectangle_anywhere_on_the_arm():
    """The assembled pair shifted along the arm is a rectangle (the low throws carry it to the wall); the ready
    pair, a flipped b, or a rectangle with a near the joint are not."""
    from throwmap.control.pair_sensors import is_rectangle, rectangle_error

    a, b = assembled_pair(PART, length=L, h=H)
    for dx in (0.0, -0.1, -0.25):
        poses = ((a.x + dx, a.y, a.phi), (b.x + dx, b.y, b.phi))
        d, e, xa = rectangle_error(PART, poses[::-1], h=H)
        assert d == pytest.approx(0.0, abs=1e-12) and e == pytest.approx(0.0, abs=1e-12) and xa == pytest.approx(a.x + dx)
        assert is_rectangle(PART, poses, h=H)
    shifted = ((a.x - 0.30, a.y, a.phi), (b.x - 0.30, b.y, b.phi))
    assert not is_rectangle(PART, shifted, h=H, a_min_x=0.15)  # a's CM at 0.10 m
    assert not is_rectangle(PART, _poses((0.20, 1), (0.40, 0)), h=H)
    assert not is_rectangle(PART, ((a.x - 0.1, a.y, a.phi), (b.x - 0.1, b.y, b.phi + 0.06)), h=H)


def test_sensor_reads_the_rectangle_and_a_min_x():
    a, b = assembled_pair(PART, length=L, h=H)
    rect = ((a.x - 0.1, a.y, a.phi), (b.x - 0.1, b.y, b.phi))
    assert not PairSensor().truth(PART, rect) and PairSensor(rectangle_h=H).truth(PART, rect)
    near = _poses((0.12, 1), (0.40, 0))
    assert pair_ready(PART, near) == (0, 1) and pair_ready(PART, near, a_min_x=0.15) is None
    assert PairSensor().truth(PART, near) and not PairSensor(a_min_x=0.15).truth(PART, near)
    with pytest.raises(InvalidStateError, match="sensor.a_min_x"):
        PairSensor(a_min_x=-0.1)


class _Run:
    def __init__(self, *states):
        self.states = states


def test_randomising_rate_rules():
    """Uniform over omega_high; capped near the joint; the kick only for a flat hypotenuse near the joint with the
    other part well clear and no shorter leg near the joint; the wall sink read from the states."""
    from throwmap.experiments.assemble import AssembleConfig, _stuck_at_wall, _uniform_rate

    cfg, rng = AssembleConfig(), np.random.default_rng(0)
    far = [_uniform_rate(cfg, _Run((0.30, 1, 0.0), (0.42, 0, 0.0)), rng) for _ in range(200)]
    assert min(far) >= 3.0 and max(far) <= 6.0 and max(far) > 5.0
    near = [_uniform_rate(cfg, _Run((0.20, 1, 0.0), (0.42, 0, 0.0)), rng) for _ in range(200)]
    assert max(near) <= cfg.near_cap
    tilted = [_uniform_rate(cfg, _Run((0.30, 1, 0.3), (0.42, 0, 0.0)), rng) for _ in range(200)]
    assert max(tilted) <= cfg.tilted_cap < cfg.omega_high[1]  # a leaning part thrown fast lands behind the joint
    assert _uniform_rate(cfg, _Run((0.15, 0, 0.0), (0.40, 1, 0.0)), rng) == cfg.kick
    assert _uniform_rate(cfg, _Run((0.10, 0, 0.0), (0.40, 1, 0.0)), rng) <= cfg.near_cap  # < slide_x: no kick
    assert _uniform_rate(cfg, _Run((0.15, 0, 0.5), (0.40, 1, 0.0)), rng) <= cfg.near_cap  # tilted: no kick
    assert _uniform_rate(cfg, _Run((0.15, 0, 0.0), (0.22, 1, 0.0)), rng) <= cfg.near_cap  # other part too close
    assert _uniform_rate(cfg, _Run((0.15, 0, 0.0), (0.21, 2, 0.0)), rng) <= cfg.near_cap  # a shorter leg near
    assert _stuck_at_wall(cfg, _Run((0.20, 1, 0.0), (0.47, 2, 0.0)))
    assert not _stuck_at_wall(cfg, _Run((0.20, 1, 0.0), (0.30, 2, 0.0)))
    assert not _stuck_at_wall(cfg, _Run((0.20, 1, 0.0), (0.47, 2, 0.3)))


def test_a_vertex_in_the_walls_foot_is_not_off_the_end():
    """Read off trial 87 (seed 1) of a randomising run: a part landing with a vertex 0.2 mm into the wall and 0.5 mm
    into the arm at the wall's foot was refused as off_end (an ejection); with a wall it is on the arm."""
    from throwmap.engine.rest import rest_status
    from throwmap.records.outcome import Status
    from throwmap.system.pose import state_from_pose, world_vertices

    pose = (0.4105744680510525, 0.038499723036507894, 6.064353778742166)
    V = world_vertices(PART, pose)
    assert V[:, 0].max() > L + 1e-4 and V[np.argmax(V[:, 0]), 1] < H - 1e-4
    x, k, tilt = state_from_pose(PART, pose)
    assert rest_status(PART, pose, x, k, tilt, H, L, 0.0, False) == Status.OK
    assert rest_status(PART, pose, x, k, tilt, H, L, 0.0, True) == Status.OFF_END  # bare arm: it is over the end
