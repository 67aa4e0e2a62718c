"""The analysis commands (throwmap.cli.analysis): limitset, basins, funnels.

Happy paths on the canonical triangle (h = −0.01 m) with the exact 'paper' model and
small caps/grids; JSON that round-trips through the library's ``from_dict``; figures
and result files; and one-line errors with exit status 2.
"""

from __future__ import annotations

import dataclasses
import io
import json
import subprocess
import sys

import numpy as np
import pytest
from typer.testing import CliRunner

import throwmap as tm
from throwmap.cli import analysis as cli_analysis
from throwmap.analysis import Basins, CriticalPoints, FunnelGraph, LimitSet, critical_points
from throwmap.cli.app import app
from throwmap.cli.options import to_json

runner = CliRunner()

TRIANGLE = ["--part", "triangle", "--h", "-0.01", "--model", "paper"]
CAPS = ["--starts", "8", "--record", "64", "--transient", "50"]
PNG = b"\x89PNG\r\n\x1a\n"
SPOUT_4 = "0:0.17-0.53, 1:0.33-0.44, 2:0.28-0.40"
"""A goal holding the ω = 4 rad/s limit set of the triangle (and none of the ω = 3 ones)."""


def invoke(*args):
    return runner.invoke(app, [str(a) for a in args])


def ok(result):
    assert result.exit_code == 0, (result.exit_code, result.output)
    assert "Traceback" not in result.output
    return result


def strict_json(text):
    def refuse(token):
        raise ValueError(f"non-standard JSON token {token}")

    return json.loads(text, parse_constant=refuse)


def normalised(d):
    """``d`` as the CLI writes it: strict JSON and back."""
    return strict_json(to_json(d))


def assert_round_trip(cls, doc):
    """``cls.from_dict(doc).to_dict()`` gives back every library key of ``doc`` unchanged."""
    again = normalised(cls.from_dict(doc).to_dict())
    assert set(again) <= set(doc)
    assert again == {k: doc[k] for k in again}


def assert_one_error(result, field):
    """Exit 2, exactly one stderr line ``error: <field>: …``, nothing on stdout, no traceback."""
    assert result.exit_code == 2, (result.exit_code, result.output)
    lines = result.stderr.splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {field}: "), lines[0]
    assert result.stdout == ""
    assert "Traceback" not in result.output
    assert result.exception is None or isinstance(result.exception, SystemExit)


# ---------------------------------------------------------------- limitset
def test_limitset_text():
    result = ok(invoke("limitset", *TRIANGLE, "--omega", "4", *CAPS))
    out = result.stdout
    assert "critical points" in out and "r_i (cm)" in out and "l_i (cm)" in out
    assert "limit set of triangle_30_60_90" in out
    assert "band, 1 attractor(s) from 24 starts" in out
    assert result.stderr == ""  # no progress bar off a terminal


def test_limitset_json_one_band_and_round_trip():
    doc = strict_json(ok(invoke("limitset", *TRIANGLE, "--omega", "4", *CAPS, "--json")).stdout)
    assert {"limit_set", "critical_points", "part", "arm", "omega", "model", "seed", "version"} <= set(doc)
    assert doc["version"] == tm.__version__ and doc["seed"] == 0 and doc["model"] == "paper"
    assert {k: doc["arm"][k] for k in ("h", "g", "length", "mu")} == {"h": -0.01, "g": 9.81, "length": None,
                                                                       "mu": None}
    assert set(doc["arm"]) == {f.name for f in dataclasses.fields(tm.Arm)}  # every field of the arm
    ls = doc["limit_set"]
    assert ls["kind"] == "band" and ls["unique"] is True
    assert len(ls["attractors"]) == 1 and ls["attractors"][0]["kind"] == "band"
    assert ls["escapes"] == {}
    assert len(ls["starts"]["x_m"]) == 24  # 8 per stable side
    assert ls["caps"]["n_record"] == 64 and ls["caps"]["transient"] == 50
    # the critical points are the library's
    direct = critical_points(tm.triangle_30_60_90(0.17), tm.Arm(-0.01), 4.0, "paper")
    assert doc["critical_points"]["r_m"] == normalised(direct.to_dict())["r_m"]
    assert set(doc["critical_points"]["r_m"]) == {"0", "1", "2"}
    assert_round_trip(LimitSet, ls)
    assert_round_trip(CriticalPoints, doc["critical_points"])


def test_limitset_everything_escapes_at_5_6(tmp_path):
    fig = tmp_path / "ls.png"
    doc = strict_json(ok(invoke("limitset", *TRIANGLE, "--omega", "5.6", *CAPS, "--json", "--plot", fig)).stdout)
    ls = doc["limit_set"]
    assert ls["kind"] == "escape" and ls["attractors"] == []
    assert ls["escapes"] == {"behind_joint": 1.0}
    assert set(ls["starts"]["label"]) == {-1}
    assert fig.read_bytes()[:8] == PNG  # an orbit that escapes still draws


def test_limitset_plots_and_out(tmp_path):
    fig, fig_map, out = tmp_path / "ls.png", tmp_path / "map.png", tmp_path / "res"
    result = ok(invoke("limitset", *TRIANGLE, "--omega", "4", *CAPS, "--plot", fig, "--plot-map", fig_map,
                       "--out", out))
    assert fig.read_bytes()[:8] == PNG and fig_map.read_bytes()[:8] == PNG
    for p in (fig, fig_map, out / "limit_set.json"):
        assert f"wrote {p}" in result.stdout
    doc = strict_json((out / "limit_set.json").read_text())
    assert doc["plot"] == str(fig) and doc["plot_map"] == str(fig_map)
    assert doc["limit_set"]["kind"] == "band"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["ls.png", "map.png", "res"]  # no temp files left
    assert [p.name for p in out.iterdir()] == ["limit_set.json"]


def test_limitset_same_seed_same_result():
    a = strict_json(ok(invoke("limitset", *TRIANGLE, "--omega", "4", *CAPS, "--seed", "3", "--json")).stdout)
    b = strict_json(ok(invoke("limitset", *TRIANGLE, "--omega", "4", *CAPS, "--seed", "3", "--json")).stdout)
    c = strict_json(ok(invoke("limitset", *TRIANGLE, "--omega", "4", *CAPS, "--seed", "4", "--json")).stdout)
    assert a["limit_set"] == b["limit_set"]
    assert a["limit_set"]["starts"]["x_m"] != c["limit_set"]["starts"]["x_m"]


# ---------------------------------------------------------------- basins
def test_basins_text():
    result = ok(invoke("basins", *TRIANGLE, "--omega", "4", "--grid", "200"))
    out = result.stdout
    assert "basins of triangle_30_60_90" in out and "600 configurations" in out
    assert "certificate: unique and globally attractive" in out
    assert result.stderr == ""


def test_basins_json_unique_band_without_arrays():
    doc = strict_json(ok(invoke("basins", *TRIANGLE, "--omega", "4", "--grid", "200", "--json")).stdout)
    assert "grid" not in doc  # the summary only
    assert {"n_configs", "method", "attractors", "fractions", "escapes", "certificate", "caps", "map", "part",
            "arm", "seed", "version"} <= set(doc)
    assert doc["n_configs"] == 600 and doc["method"] == "orbits"
    assert [a["kind"] for a in doc["attractors"]] == ["band"]
    assert doc["fractions"] == {"1": 1.0}
    assert doc["certificate"]["unique"] is True and doc["certificate"]["attractor"] == 1
    assert doc["certificate"]["statement"].startswith("unique and globally attractive")


def test_basins_everything_escapes_behind_the_joint_at_5_6():
    doc = strict_json(ok(invoke("basins", *TRIANGLE, "--omega", "5.6", "--grid", "200", "--json")).stdout)
    assert doc["attractors"] == []
    assert doc["fractions"] == {"-1": 1.0}
    assert doc["escapes"] == {"behind_joint": 1.0}
    assert doc["certificate"]["unique"] is False


def test_basins_out_and_plot(tmp_path):
    fig, out = tmp_path / "b.png", tmp_path / "res"
    result = ok(invoke("basins", *TRIANGLE, "--omega", "4", "--grid", "200", "--plot", fig, "--out", out))
    assert fig.read_bytes()[:8] == PNG
    assert sorted(p.name for p in out.iterdir()) == ["basins.json", "basins.npz"]
    for p in (fig, out / "basins.json", out / "basins.npz"):
        assert f"wrote {p}" in result.stdout
    doc = strict_json((out / "basins.json").read_text())
    assert len(doc["grid"]["x_m"]) == 600
    assert_round_trip(Basins, doc)
    back = Basins.from_dict(doc)
    with np.load(out / "basins.npz") as npz:
        assert sorted(npz.files) == ["fates", "labels", "side", "throws", "x"]
        for name in npz.files:
            np.testing.assert_array_equal(npz[name], getattr(back, name))
    assert set(np.unique(back.labels)) == {1}


def test_basins_out_large_grid_keeps_arrays_out_of_json(tmp_path, monkeypatch):
    monkeypatch.setattr(cli_analysis, "JSON_ARRAYS_MAX", 100)
    ok(invoke("basins", *TRIANGLE, "--omega", "4", "--grid", "50", "--out", tmp_path))
    doc = strict_json((tmp_path / "basins.json").read_text())
    assert "grid" not in doc and doc["arrays"] == "basins.npz"
    with np.load(tmp_path / "basins.npz") as npz:
        assert npz["x"].size == 150


def test_basins_cells_method_reports_check():
    doc = strict_json(ok(invoke("basins", *TRIANGLE, "--omega", "4", "--grid", "200", "--method", "cells",
                                "--check", "50", "--json")).stdout)
    assert doc["method"] == "cells"
    assert doc["check"]["n"] == 50


def test_progress_bar_on_a_terminal_changes_nothing(monkeypatch):
    """On a terminal the commands draw Rich bars on stderr; the results are the same."""
    from rich.console import Console

    plain = strict_json(ok(invoke("basins", *TRIANGLE, "--omega", "4", "--grid", "100", "--json")).stdout)
    sink = io.StringIO()
    monkeypatch.setattr(cli_analysis, "_stderr_console", lambda: Console(file=sink, force_terminal=True))
    barred = strict_json(ok(invoke("basins", *TRIANGLE, "--omega", "4", "--grid", "100", "--json")).stdout)
    assert barred == plain
    assert "limit set" in sink.getvalue()


# ---------------------------------------------------------------- funnels
def test_funnels_text_with_priority_order():
    result = ok(invoke("funnels", *TRIANGLE, "--omega", "3,4", "--grid", "100", "--x-max", "1.0",
                       "--goal", SPOUT_4))
    out = result.stdout
    assert out.startswith("goal: ")
    assert "ω=4 #1" in out and "ω=3 #1" in out
    assert "priority order: ω=4 #1 > " in out


def test_funnels_json_and_round_trip():
    doc = strict_json(ok(invoke("funnels", *TRIANGLE, "--omega", "3", "--omega", "4", "--grid", "100",
                                "--x-max", "1.0", "--goal", SPOUT_4, "--json")).stdout)
    assert {"funnels", "edges", "goal", "rank", "order", "containment", "map", "part", "omegas", "version"} <= set(doc)
    assert doc["omegas"] == [3.0, 4.0]
    names = [f["name"] for f in doc["funnels"]]
    assert names[doc["order"][0]] == "ω=4 #1"
    assert doc["rank"][str(names.index("ω=4 #1"))] == 0
    assert any(n.startswith("ω=3") for n in names)
    for i, f in enumerate(doc["funnels"]):
        if not f["name"].startswith("ω=3"):
            continue
        beyond = all(b["lo_m"] > 1.0 for b in f["attractor"]["bands"])
        # a spout inside the searched range leads into ω=4's mouth; one beyond x_max = 1.0 m leads nowhere
        assert doc["rank"][str(i)] == (None if beyond else 1), (f["name"], f["attractor"]["bands"])
    assert all(f["mouth"] == [] or max(iv["hi_m"] for iv in f["mouth"]) <= 1.0 for f in doc["funnels"])
    assert_round_trip(FunnelGraph, doc)


def test_funnels_paper_goal_plot_and_out(tmp_path):
    fig, out = tmp_path / "f.png", tmp_path / "res"
    result = ok(invoke("funnels", *TRIANGLE, "--omega", "3,4", "--grid", "100", "--x-max", "1.0",
                       "--goal", "0:0.50-0.90", "--plot", fig, "--out", out))
    assert "goal: side 0: [50, 90] cm" in result.stdout
    assert fig.read_bytes()[:8] == PNG
    doc = strict_json((out / "funnels.json").read_text())
    assert doc["goal"] == [{"side": 0, "lo_m": 0.5, "hi_m": 0.9}]
    assert doc["plot"] == str(fig)


# ---------------------------------------------------------------- one-line errors
@pytest.mark.parametrize(
    "args, field",
    [
        pytest.param(["funnels", "--omega", "3,4", "--goal", "7:0.5-0.9"], "goal", id="goal-unknown-side"),
        pytest.param(["funnels", "--omega", "3,4", "--goal", "0-0.5"], "goal", id="goal-malformed"),
        pytest.param(["funnels", "--omega", "3,4", "--goal", "0:0.9-0.5"], "goal", id="goal-reversed"),
        pytest.param(["funnels", "--omega", "3,4", "--goal=-1:0.5-0.6"], "goal", id="goal-negative-side"),
        pytest.param(["funnels", "--omega", "3,-4"], "omega", id="funnels-negative-omega"),
        pytest.param(["funnels", "--omega", "3,x"], "omega", id="funnels-omega-not-a-number"),
        pytest.param(["funnels", "--omega", "3,4", "--containment", "2"], "containment", id="containment"),
        pytest.param(["limitset", "--omega", "-1"], "omega", id="limitset-negative-omega"),
        pytest.param(["limitset", "--omega", "nan"], "omega", id="limitset-nan-omega"),
        pytest.param(["limitset", "--omega", "4", "--starts", "0"], "starts", id="starts"),
        pytest.param(["limitset", "--omega", "4", "--record", "3"], "record", id="record"),
        pytest.param(["limitset", "--omega", "4", "--model", "exact"], "model", id="unknown-model"),
        pytest.param(["basins", "--omega", "4", "--grid", "1"], "grid", id="grid-below-2"),
        pytest.param(["basins", "--omega", "4", "--length", "0.4", "--x-max", "0.5"], "x_max",
                     id="x-max-beyond-arm"),
        pytest.param(["basins", "--omega", "4", "--method", "magic"], "method", id="unknown-method"),
        pytest.param(["basins", "--omega", "4", "--check", "-1"], "check", id="negative-check"),
        pytest.param(["basins", "--omega", "4", "--max-throws", "0"], "max_throws", id="max-throws"),
    ],
)
def test_bad_input_is_one_line(args, field):
    cmd, rest = args[0], args[1:]
    assert_one_error(invoke(cmd, *TRIANGLE, *rest), field)


@pytest.mark.parametrize("cmd", ["limitset", "basins", "funnels"])
def test_bad_plot_paths(tmp_path, cmd):
    base = [cmd, *TRIANGLE, "--omega", "4"]
    assert_one_error(invoke(*base, "--plot", tmp_path / "fig.xyz"), "plot")
    (tmp_path / "file").write_text("x")
    assert_one_error(invoke(*base, "--plot", tmp_path / "file" / "fig.png"), "plot")  # its folder is a file
    assert_one_error(invoke(*base, "--out", tmp_path / "file"), "out")
    assert list(tmp_path.iterdir()) == [tmp_path / "file"]  # nothing written


def test_bad_plot_map_path(tmp_path):
    assert_one_error(invoke("limitset", *TRIANGLE, "--omega", "4", "--plot-map", tmp_path / "map.txt"), "plot_map")


def test_subprocess_error_is_one_line():
    proc = subprocess.run([sys.executable, "-m", "throwmap", "funnels", "--part", "triangle", "--h", "-0.01",
                           "--omega", "3,4", "--goal", "5:0.5-0.9"], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2
    assert proc.stderr.splitlines() == [
        "error: goal: side 5 is not a stable side of triangle_30_60_90(hypotenuse=0.17) (stable sides: [0, 1, 2])"]
    assert proc.stdout == ""


# ---------------------------------------------------------------- demo
def test_demo_analysis_figures_and_summary(tmp_path, monkeypatch):
    """The demo's analysis step (small grids here; the demo itself runs in test_cli.py::test_demo)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from throwmap.studies import demo

    monkeypatch.setitem(demo.ANALYSIS, "model", "paper")
    monkeypatch.setitem(demo.ANALYSIS, "basin_grid", 200)
    monkeypatch.setitem(demo.ANALYSIS, "funnel_grid", 100)
    part, arm = tm.triangle_30_60_90(demo.DEMO["hypotenuse"]), tm.Arm(demo.DEMO["h"])
    summary, files = demo._analysis(part, arm, demo.DEMO["omega"], tmp_path, lambda msg: None, plt)
    assert [f.name for f in files] == ["limit_set.png", "throw_map_limits.png", "basins.png", "funnels.png"]
    assert all(f.read_bytes()[:8] == PNG for f in files)
    assert set(summary["critical_points"]["r_m"]) == {"0", "1", "2"}
    assert summary["limit_set"]["kind"] == "band"
    assert summary["basins"]["fractions"] == {"1": 1.0} and summary["basins"]["certificate"]["unique"] is True
    assert summary["funnels"]["goal"] == demo.ANALYSIS["goal"]
    # the omega = 3 band lies in x in [0.5, 0.9] on every side: it is the top funnel, omega = 4 leads into it
    assert summary["funnels"]["order"][:2] == ["ω=3 #1", "ω=4 #1"]
    json.dumps(normalised(summary), allow_nan=False)


# ---------------------------------------------------------------- issue 10: guarded work, stated ranges
def test_a_huge_basin_grid_is_refused_up_front_in_one_line():
    """``basins --grid 100000000`` once ran 17 min and took 12 GB; now it is refused before any throw."""
    result = invoke("basins", *TRIANGLE, "--omega", "4", "--grid", "100000000")
    assert_one_error(result, "grid")
    line = result.stderr
    assert "300,000,000 configurations" in line and "GB of memory" in line
    assert "--max-memory" in line and "--force" in line


def test_a_long_limit_set_is_refused_by_its_time_estimate():
    result = invoke("limitset", *TRIANGLE, "--omega", "4", "--starts", "80000", "--max-time", "1")
    assert_one_error(result, "starts")
    assert "measured now" in result.stderr and "--max-time" in result.stderr


@pytest.mark.parametrize("args, field", [(["--max-memory", "0"], "max_memory"), (["--max-time", "-1"], "max_time")])
def test_bad_limits_are_one_line(args, field):
    assert_one_error(invoke("basins", *TRIANGLE, "--omega", "4", "--grid", "20", *args), field)


def test_limitset_and_basins_state_the_range_they_searched():
    out = ok(invoke("limitset", *TRIANGLE, "--omega", "5.6", *CAPS)).stdout
    assert "valid starts with x ≤ 0.600 m" in out and "not ruled out" in out
    assert "searched: x ≤ 60.0 cm" in out
    out = ok(invoke("basins", *TRIANGLE, "--omega", "4", "--grid", "100", "--x-max", "0.5")).stdout
    assert "unique and globally attractive for the valid starts with x ≤ 0.500 m" in out


@pytest.mark.parametrize("cmd, opt", [("basins", "--grid"), ("limitset", "--starts"), ("limitset", "--seed"),
                                      ("basins", "--max-throws")])
def test_integer_options_take_whole_numbers_only(cmd, opt):
    """One rule with the library: ``basins(grid=3.0)`` is refused, so is ``--grid 3.0``."""
    result = invoke(cmd, *TRIANGLE, "--omega", "4", opt, "3.0")
    assert result.exit_code == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ") and "integer" in lines[0]


# ---------------------------------------------------------------- round 2 (outside tester)
RB = ["--part", "triangle", "--h", "-0.01"]  # the default model, rigid_body


@pytest.mark.parametrize("cmd, extra", [("limitset", CAPS), ("basins", ["--grid", "30"]),
                                        ("funnels", ["--grid", "30", "--starts", "8"])])
def test_back_option_reaches_the_analysed_domain(cmd, extra):
    """``--back`` (as on throw/iterate) widens the domain behind the joint to the starts throw() accepts."""
    doc = strict_json(ok(invoke(cmd, *RB, "--omega", "4", "--back", "0.05", *extra, "--json")).stdout)
    assert doc["arm"]["back"] == 0.05
    maps = doc["map"]["maps"] if cmd == "funnels" else [doc["limit_set"]["map"] if cmd == "limitset" else doc["map"]]
    lo, _ = tm.system.starts.start_interval(tm.triangle_30_60_90(), tm.Arm(h=-0.01, back=0.05), 1)
    for m in maps:
        assert m["domain_m"]["1"][0] == lo < tm.triangle_30_60_90().x_min(1)


def test_basins_certificate_with_back_in_the_part_file(tmp_path):
    """The tester's file with ``[arm] back = 0.05``: the fixed points near the joint break uniqueness."""
    path = tmp_path / "backf.toml"
    path.write_text("[part]\nvertices = [[0.1472, 0.0], [0.0, 0.085], [0.0, 0.0]]\nmass = 0.05\n"
                    "[arm]\nh = -0.01\nback = 0.05\n")
    doc = strict_json(ok(invoke("basins", "--part", path, "--omega", "4", "--grid", "60", "--json")).stdout)
    assert doc["arm"]["back"] == 0.05
    assert doc["certificate"]["unique"] is False
    plain = strict_json(ok(invoke("basins", "--part", path, "--back", "0", "--omega", "4", "--grid", "60",
                                  "--json")).stdout)
    old_lo = {k: v[0] for k, v in plain["map"]["domain_m"].items()}
    assert any(a["kind"] == "fixed_point" and any(b["lo_m"] < old_lo[str(b["side"])] for b in a["bands"])
               for a in doc["attractors"])


def test_funnels_take_model_options():
    doc = strict_json(ok(invoke("funnels", *RB, "--omega", "3,4", "--mu", "0.3", "-O", "impact_law=velocity",
                                "--grid", "30", "--starts", "8", "--json")).stdout)
    assert doc["model_options"]["impact_law"] == "velocity"


def test_long_transient_and_max_transient_options():
    doc = strict_json(ok(invoke("limitset", *RB, "--omega", "4", "--starts", "2", "--transient", "6000",
                                "--json")).stdout)
    assert doc["limit_set"]["caps"]["max_transient"] >= 6000
    doc = strict_json(ok(invoke("limitset", *RB, "--omega", "4", "--starts", "2", "--transient", "100",
                                "--max-transient", "900", "--json")).stdout)
    assert doc["limit_set"]["caps"]["max_transient"] == 900
    assert_one_error(invoke("limitset", *RB, "--omega", "4", "--transient", "300", "--max-transient", "200"),
                     "max_transient")


def test_a_huge_record_names_the_record():
    assert_one_error(invoke("limitset", *RB, "--omega", "4", "--record", "100000000"), "record")
