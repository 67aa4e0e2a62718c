"""Experiments ``assemble-sequential`` / ``assemble-serial`` (paper Sec. V-D) and the stack design behind them."""

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from throwmap.errors import ThrowmapError
from throwmap.experiments.sequential import SequentialConfig, build_stack

# a cheap trial: the drop and at most one throw of each phase, one hold throw
QUICK = {"max_throws": 1, "max_first": 1, "max_second": 1, "hold": 1}


@pytest.fixture(scope="module")
def design():
    return build_stack(SequentialConfig())


def test_the_pair_fills_the_wedge_without_overlap(design):
    from throwmap.system.geometry import overlap_depth
    from throwmap.system.pose import world_vertices

    c = design.checks()
    assert -0.0015 < c["overlap_m"] < 0  # 1 mm apart along the leg, not inside each other
    assert 0 < c["wall_gap_m"] <= 0.0011 and c["floor_gap_m"] > 0
    W = world_vertices(design.wedge, design.wedge_pose)
    T = world_vertices(design.triangle, design.triangle_pose)
    # the wedge lies between the apex and the wall, over the triangle's short leg, inside the cavity's end
    assert W[:, 0].min() == pytest.approx(T[:, 0][np.argmax(T[:, 1])], abs=1e-9)
    assert W[:, 0].max() < design.cavity.length and W[:, 1].min() < design.arm.h  # its tip is down in the pocket
    # the wall (a solid at x >= L) does not overlap it
    wall = np.array([[design.cavity.length, -1], [1, -1], [1, 1], [design.cavity.length, 1]])
    assert overlap_depth(W, wall) < 0
    assert design.wedge.n_sides == 4 and 0.06 < design.wedge.mass < 0.08  # 50 g of lead in the tip
    assert design.assembled(design.poses)
    bad = (design.wedge_pose[0] - 0.02, design.wedge_pose[1], design.wedge_pose[2])
    assert not design.assembled((design.triangle_pose, bad))
    turned = (design.wedge_pose[0], design.wedge_pose[1], design.wedge_pose[2] + 0.2)
    assert not design.assembled((design.triangle_pose, turned))


def test_bad_wedge_is_one_line():
    from throwmap.experiments import run_experiment

    with pytest.raises(ThrowmapError) as e:
        run_experiment("assemble-serial", {"wedge": {"lead_at": [0.5, 0.5]}}, n=1, seed=1, workers=1)
    assert "config.wedge" in e.value.field and "\n" not in str(e.value)


def test_bad_config_is_one_line():
    from throwmap.experiments import run_experiment

    with pytest.raises(ThrowmapError) as e:
        run_experiment("assemble-sequential", {"max_throw": 3}, n=1, seed=1, workers=1)
    assert "max_throw" in str(e.value) and "\n" not in str(e.value)
    with pytest.raises(ThrowmapError) as e:
        run_experiment("assemble-sequential", {"x_range": [0.3, 0.1]}, n=1, seed=1, workers=1)
    assert e.value.field == "config.x_range"


def test_cli_bad_config_exit_2(tmp_path):
    cfg = tmp_path / "bad.toml"
    cfg.write_text("hold = 0\n")
    r = subprocess.run([sys.executable, "-m", "throwmap", "experiment", "assemble-serial", str(cfg), "--n", "1"],
                       capture_output=True, text=True)
    assert r.returncode == 2 and r.stderr.startswith("error: ") and r.stderr.count("\n") == 1


def test_contract_json_keys():
    from throwmap.experiments import experiment_names, run_experiment

    assert {"assemble-sequential", "assemble-serial"} <= set(experiment_names())
    for name in ("assemble-sequential", "assemble-serial"):
        res = run_experiment(name, QUICK, n=1, seed=3, workers=1)
        d = json.loads(json.dumps(res.to_json()))
        for key in ("n", "successes", "success_rate", "ci95", "failures", "seed", "parameters", "config", "values",
                    "version", "elapsed_s", "workers", "resumed"):
            assert key in d
        assert d["n"] == 1 and sum(d["failures"].values()) + d["successes"] == 1
        for key in ("throws", "throws_to_assemble", "triangle_at", "wedge_at", "order", "held_1", "held_k",
                    "mu", "drop_redraws", "lost"):
            assert key in res.trials[0].values
        assert set(d["failures"]) <= {"ejected", "wrong_orientation", "not_assembled"} | {
            f for f in d["failures"] if f.startswith("refused:")}
        p = d["parameters"]
        assert p["variant"] == name.split("-")[1] and p["design"]["wedge"]["mass_kg"] > 0.06


@pytest.mark.slow
def test_the_assembled_pair_rests_and_stays_after_throws(design):
    from throwmap.engine import Friction, ImpulseThrow, Placement, Scene, simulate
    from throwmap.experiments.feed import _settings
    from throwmap.io.spec import NoiseSpec

    cfg = SequentialConfig()
    noise = NoiseSpec(omega_rel=0.03, realisation="recoil", zeta=0.2).noise()
    scene = Scene(design.arm, tuple(Placement(p, pose=q) for p, q in zip(design.parts, design.poses)),
                  design.fixtures, 0.0, Friction(part_part=cfg.mu_parts))
    run = simulate(scene, ImpulseThrow(0.0), _settings(cfg))
    assert int(run.status) == 0 and design.assembled(run.poses)
    rng = np.random.default_rng(0)
    for _ in range(5):
        _, real = noise.throw(4.559824565181344, rng)
        run = simulate(run.next_scene(), real, _settings(cfg))
        assert int(run.status) == 0 and design.assembled(run.poses), run.poses
        assert math.isfinite(design.wedge_error(run.poses[1])[0])


# ------------------------------------------------------------------ the recovery (closed loop)
# a trap as the engine left it (assemble-sequential seed 5 trial 1, open loop): the wedge flat on its leg side on the
# pocket floor at the wall, the triangle leaning 30° on it
TRAP = ((0.3343624150948792, 0.014463550341238179, 9.42497693987172),
        (0.33523915872788546, -0.01853690743802933, 7.330574738872478))

def test_stuck_sensor_reads_the_trap_only(design):
    from throwmap.experiments.sequential import RecoverConfig, _reads_stuck

    rec = RecoverConfig()
    rng = np.random.default_rng(0)
    # the trap: the wedge flat on its leg side at the wall, the triangle leaning 30° on it (measured poses)
    trap = TRAP
    assert not design.assembled(trap)
    assert _reads_stuck(design, trap, trap, rec, rng)
    moved = ((trap[0][0] - 0.02, trap[0][1], trap[0][2]), trap[1])  # the triangle moved 2 cm: not stuck
    assert not _reads_stuck(design, trap, moved, rec, rng)
    turned = (trap[0], (trap[1][0], trap[1][1], trap[1][2] + 0.2))  # the wedge turned 0.2 rad: not stuck
    assert not _reads_stuck(design, trap, turned, rec, rng)
    short = ((0.15, 0.0, 0.0), trap[1])  # the triangle short of the lip: not in the pocket's end
    assert not _reads_stuck(design, short, short, rec, rng)
    # sensor errors: a missed trap and a false alarm, at the configured rates
    always_miss = RecoverConfig(false_negative=1.0)
    assert not _reads_stuck(design, trap, trap, always_miss, rng)
    alarm = RecoverConfig(false_positive=1.0)
    assert _reads_stuck(design, short, short, alarm, rng)
    half = RecoverConfig(false_negative=0.5)
    reads = [_reads_stuck(design, trap, trap, half, rng) for _ in range(2000)]
    assert 0.45 < np.mean(reads) < 0.55


def test_recover_config_is_checked():
    from throwmap.experiments import run_experiment

    for bad in ({"recover": {"alpha": 2.0}}, {"recover": {"confirm": 0}}, {"recover": {"enabled": "yes"}},
                {"recover": {"still": -1}}, {"recover": {"tilt": 0.1}}):
        with pytest.raises(ThrowmapError, match="recover"):
            run_experiment("assemble-sequential", bad, n=1, seed=1, workers=1)


@pytest.mark.slow
def test_the_recovery_moves_a_trap_that_throws_do_not(design):
    """The trap survives throws at the assembly rate (the sensor reads "stuck" once it is at the wall); the recovery (tilt by
    10°, throw there, tilt back: real arm motions) moves it: the sensor no longer reads "stuck"."""
    from throwmap.engine import Friction, Placement, RecoilThrow, Scene, TiltTo, simulate
    from throwmap.experiments.feed import _settings
    from throwmap.experiments.sequential import RecoverConfig, _reads_stuck

    cfg = SequentialConfig()
    rec, settings, rng = RecoverConfig(), _settings(cfg), np.random.default_rng(0)
    omega = 4.5598
    scene = Scene(design.arm, tuple(Placement(p, pose=q) for p, q in zip(design.parts, TRAP)), design.fixtures,
                  friction=Friction(part_part=cfg.mu_parts))
    run = simulate(scene, None, settings)
    assert int(run.status) == 0
    reads = []
    for _ in range(8):  # it jogs outward to the wall, then stays
        before = run.poses
        run = simulate(run.next_scene(), RecoilThrow.for_release_rate(omega, zeta=0.2), settings)
        assert int(run.status) == 0
        reads.append(_reads_stuck(design, before, run.poses, rec, rng))
    assert reads[-3:] == [True, True, True] and not design.assembled(run.poses), reads
    before = run.poses
    run = simulate(run.next_scene(), TiltTo(rec.alpha, rec.rate), settings)
    assert int(run.status) == 0 and run.alpha == pytest.approx(rec.alpha)
    run = simulate(run.next_scene(), RecoilThrow.for_release_rate(rec.omega, zeta=0.2), settings)
    assert int(run.status) == 0
    run = simulate(run.next_scene(), TiltTo(-run.alpha, rec.rate), settings)
    assert int(run.status) == 0 and abs(run.alpha) < 1e-9
    assert not _reads_stuck(design, before, run.poses, rec, rng)


# ------------------------------------------------------------------ two-part engine runs met in these experiments
def _pair_scene(design, mu, poses):
    from throwmap import Arm
    from throwmap.engine import Friction, Placement, Scene

    a = design.arm
    arm = Arm(h=a.h, g=a.g, length=a.length, mu=mu, back=a.back)
    return Scene(arm, tuple(Placement(p, pose=q) for p, q in zip(design.parts, poses)), design.fixtures,
                 friction=Friction(part_part=0.5))


def test_leaping_parts_do_not_pass_through_each_other(design):
    """Both parts in free flight, closing on each other: the exact-flight leaps measure their distance on the
    shapes' cached world vertices, which must follow the leaps (they did not: the parts were measured apart while
    they passed into each other, a vertex 3.65 mm deep, refused at every step down to dt/16)."""
    from throwmap.engine import RecoilThrow, simulate
    from throwmap.experiments.feed import _settings

    scene = _pair_scene(design, 0.9912972669117388, ((0.29575374249708153, 0.05838854934084252, 10.634598923269),
                                                     (0.3371556734103793, 0.022271558052696205, 9.424718648509259)))
    run = simulate(scene, RecoilThrow(omega_n=179.89928681655618, recoil=0.05235987755982989, zeta=0.2),
                   _settings(SequentialConfig()))
    assert int(run.status) == 0, run.message
    assert run.penetration_max < 1e-3 and run.n_leaps > 0


def test_a_blow_up_is_rerun_at_half_the_step(design):
    """Without the half-step rerun (verify off, as these experiments), a run that gains 2 × 10⁵ J/kg (a part
    thrown 1.8 km, reported as a timeout) is rerun at half the step, which does not blow up."""
    from throwmap.engine import RecoilThrow, simulate
    from throwmap.engine.pymunk.run import BLOWUP_RISE
    from throwmap.experiments.feed import _settings

    scene = _pair_scene(design, 0.9981483282708306, ((0.3205842060562813, 0.0860924731392448, 17.52165206967037),
                                                     (0.34193028417507954, 0.022270632221915023, 15.707931140894223)))
    run = simulate(scene, RecoilThrow(omega_n=184.3515173828374, recoil=0.05235987755982989, zeta=0.2),
                   _settings(SequentialConfig()))
    assert int(run.status) == 0 and "a blow-up" in run.message
    assert run.energy_gain < scene.arm.g * BLOWUP_RISE and run.dt == pytest.approx(0.000125 / 2)
    assert all(0 < p[0] < design.arm.length for p in run.poses)


def test_open_loop_example_turns_the_recovery_off():
    from pathlib import Path

    from throwmap.experiments import get_experiment
    from throwmap.experiments.base import read_config

    path = Path(__file__).parent.parent.parent / "examples" / "sequential_open_loop.toml"
    cfg = read_config(get_experiment("assemble-sequential"), path)
    assert cfg.recover.enabled is False and SequentialConfig().recover.enabled is True
