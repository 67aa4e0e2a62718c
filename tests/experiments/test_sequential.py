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
    from throwmap.statics.contacts import overlap_depth
    from throwmap.throws.trajectory import world_vertices

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
    from throwmap.experiments.noise import NoiseConfig

    cfg = SequentialConfig()
    noise = NoiseConfig(omega_rel=0.03, realisation="recoil", zeta=0.2).noise()
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
