"""The experiment command's table names what it is about: the part, the side wanted, ω, the arm and the fixtures."""

from __future__ import annotations

import math

from typer.testing import CliRunner

from throwmap.cli.app import app
from throwmap.cli.experiment import _setting


def test_the_setting_line_names_part_omega_arm_and_fixtures():
    p = {"part": "plate + lead 49 g", "target_side": 1, "omega_rad_s": 4.0, "h_m": -0.03, "length_m": 0.48, "mu": 1.0,
         "noise": {"realisation": "recoil", "omega_rel": 0.03},
         "cavity": {"numbers": {"L_m": 0.48, "depth_m": 0.01}}, "wall": {"height_m": 0.05}}
    assert _setting(p) == ("part plate + lead 49 g; side 1 wanted; ω = 4 rad/s; arm h = -0.03 m, length 0.48 m, μ = 1; "
                           "recoil throw, ω jitter 3 %; fixtures: cavity (end wall at 0.48 m, 1 cm deep), "
                           "end wall 0.05 m high")
    # only what is stated, and never a number that is not one
    assert _setting({"omega_rad_s": math.inf, "h_m": True, "part": 3}) == "" and _setting({}) == ""


def test_the_table_is_headed_by_the_setting():
    res = CliRunner().invoke(app, ["experiment", "settle", "--n", "1", "--workers", "1"])
    assert res.exit_code == 0, res.output
    first = res.stdout.splitlines()[0]
    assert first.startswith("part triangle_30_60_90(hypotenuse=0.17); arm h = -0.01 m"), first
    assert "throw" not in first and first.endswith("fixtures: none")  # settle drops the part, it throws nothing
