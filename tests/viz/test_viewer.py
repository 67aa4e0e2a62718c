"""The viewer's page without a browser (throwmap.viz.viewer, ``throwmap view``): the data it stores, that it is
self-contained, the CLI's sources and its one-line errors. The browser test is test_viewer_browser.py."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from throwmap.errors import RegimeWarning
from typer.testing import CliRunner

from throwmap.cli.app import app
from throwmap.errors import InvalidStateError
from throwmap.io.trajectory_file import save_trajectory
from throwmap.viz.viewer import QUANTUM, orbit_steps, player_data, table_html, viewer_html, write_viewer

runner = CliRunner()


def _data(page: str):
    m = re.search(r'<script id="viewer-data" type="application/json">(.*?)</script>', page, re.S)
    return json.loads(m.group(1))


def test_frames_are_resampled_and_quantised(two_part_trajectory):
    tr = two_part_trajectory
    d = player_data(tr, fps=30)
    span = tr.t[-1] - tr.t[0]
    assert d["n"] == int(span * 30) + 1 and d["fps"] == 30
    assert len(d["arm"]) == d["n"] and all(len(p) == 3 * d["n"] for p in d["poses"])
    assert isinstance(d["poses"][0][0], int)  # units of QUANTUM (0.1 mm, 0.1 mrad)
    np.testing.assert_allclose(np.array(d["poses"][1][0::3]) * QUANTUM, np.interp(
        tr.t[0] + np.arange(d["n"]) / 30, tr.t, tr.poses[:, 1, 0]), atol=QUANTUM)
    assert sum(d["cc"]) * 2 == len(d["cp"])
    assert {d["labels"][i] for i in d["label"]} >= {"release", "flight", "rest (jog)"}
    assert len(d["parts"]) == 2 and d["parts"][0]["color"] != d["parts"][1]["color"]
    assert d["fixture_pieces"]  # the wall


def test_each_frame_knows_the_step_it_plays(two_part_trajectory):
    d = player_data(two_part_trajectory, fps=10)
    o = d["orbit"]
    assert o["throw"] == list(range(7)) and o["t"][0] is None
    steps = d["step"]
    assert steps[0] == 1 and steps[-1] == 6 and all(b >= a for a, b in zip(steps, steps[1:]))
    assert steps[10] == 2  # t = 1.0 s: the second throw starts
    assert o["x"][3] == [round(0.16 / QUANTUM), round(0.35 / QUANTUM)]


def test_a_long_motion_is_capped(two_part_trajectory):
    d = player_data(two_part_trajectory, fps=240, max_frames=100)
    assert d["n"] <= 100 and d["fps"] < 240


def test_an_orbit_of_throws_gives_its_steps():
    from throwmap.system.arm import Arm
    from throwmap.system.catalogue import triangle_30_60_90
    from throwmap.throws.orbit_trajectory import orbit_trajectory

    with pytest.warns(RegimeWarning):  # h ≥ 0: as every throw on such an arm warns
        tr = orbit_trajectory(triangle_30_60_90(), Arm(0.02), 0.1, 0, 3.0, 3, model="paper")
    o = orbit_steps(tr)
    assert o["throw"] == [0, 1, 2, 3] and o["x"][0] == [0.1] and o["t"][0] is None
    assert o["x"][1:] == [[out.x] for out in tr.meta["outcomes"]]
    d = player_data(tr)
    assert max(d["step"]) == 3


def test_the_page_is_self_contained_and_small(tmp_path, two_part_trajectory):
    page = viewer_html(title="a </script> title", subtitle="s & t", player=player_data(two_part_trajectory),
                       sections=table_html(("a", "b"), [(1, 2.5), ("x<y", None)], caption="T"))
    assert not re.search(r"""(src|href)\s*=\s*["'](https?:)?//""", page)  # nothing fetched
    assert "<script src" not in page and "@import" not in page and "http://" not in page.replace(
        "http://www.w3.org", "")
    assert "a &lt;/script&gt; title" in page and "x&lt;y" in page
    assert page.count("</script>") == 2  # the data block and the script: the data never closes it early
    assert _data(page)["n"] > 100
    out = write_viewer(tmp_path / "v.html", page)
    assert out.stat().st_size < 150_000
    with pytest.raises(InvalidStateError, match="out"):
        write_viewer(tmp_path / "v.png", page)


def test_a_page_without_a_player_has_the_tables():
    page = viewer_html(title="t", player=None, sections=table_html(("k",), [(i,) for i in range(5)], max_rows=3,
                                                                   highlight=1))
    assert '<section id="player" data-frame="0" data-step="-1" data-playing="false" hidden>' in page
    assert "first 3 of 5 shown" in page and page.count('class="hl"') == 1 and _data(page) is None


def test_bad_inputs_are_named(two_part_trajectory):
    with pytest.raises(InvalidStateError, match="fps"):
        player_data(two_part_trajectory, fps=0)
    with pytest.raises(InvalidStateError, match="max_frames"):
        player_data(two_part_trajectory, max_frames=1)
    with pytest.raises(InvalidStateError, match="trajectory"):
        player_data("nope")


# ------------------------------------------------------------------ the command
def _one_error(result, field):
    assert result.exit_code == 2, result.output
    lines = result.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(f"error: {field}: "), result.stderr


def test_view_plays_a_trajectory_file(tmp_path, two_part_trajectory):
    src = save_trajectory(two_part_trajectory, tmp_path / "t.npz")
    res = runner.invoke(app, ["view", str(src), "--out", str(tmp_path / "v.html"), "--fps", "20"])
    assert res.exit_code == 0, res.output
    assert "wrote" in res.stdout and "2 parts, 7 orbit steps" in res.stdout
    d = _data((tmp_path / "v.html").read_text())
    assert d["fps"] == 20 and len(d["orbit"]["throw"]) == 7


def test_view_an_orbit_and_save_it(tmp_path):
    res = runner.invoke(app, ["view", "--part", "triangle", "--h", "0.02", "--omega", "3", "--x", "0.1", "--side",
                              "0", "-n", "2", "--model", "paper", "--out", str(tmp_path / "o.html"),
                              "--save-trajectory", str(tmp_path / "o.npz")])
    assert res.exit_code == 0, res.output
    assert (tmp_path / "o.npz").exists() and "3 orbit steps" in res.stdout
    again = runner.invoke(app, ["view", str(tmp_path / "o.npz"), "--out", str(tmp_path / "again.html")])
    assert again.exit_code == 0 and "3 orbit steps" in again.stdout


def _experiment_dir(path, name="settle", n=4):
    path.mkdir()
    cfg = {"mu": 0.8}
    (path / "run.json").write_text(json.dumps({"experiment": name, "version": "x", "config": cfg, "seed": 3}))
    trials = [{"index": i, "seed": 10 + i, "success": i != 2, "failure": None if i != 2 else "tilted",
               "values": {"x": 0.1 * i, "side": i % 3}} for i in range(n)]
    (path / "trials.jsonl").write_text("".join(json.dumps(t) + "\n" for t in trials) + '{"index": 9, "cut')
    return path


def test_view_an_experiment_directory(tmp_path):
    d = _experiment_dir(tmp_path / "run")
    res = runner.invoke(app, ["view", str(d), "--out", str(tmp_path / "e.html")])
    assert res.exit_code == 0, res.output
    page = (tmp_path / "e.html").read_text()
    assert "tables only" in res.stdout and _data(page) is None
    assert "3/4 succeeded" in page and "<td>tilted</td>" in page and 'id="trials"' in page
    assert "interrupted run" in page  # no result.json
    res = runner.invoke(app, ["view", str(d), "--trial", "1", "--out", str(tmp_path / "e.html")])
    _one_error(res, "trial")  # settle records no motion


@pytest.mark.parametrize("args, field", [
    ([], "result"),
    (["--assemble", "--part", "triangle"], "result"),
    (["x.npz", "--out", "v.png"], "out"),
    (["missing.npz"], "path"),
    (["--assemble", "--start", "middle"], "start"),
    (["--part", "triangle", "--h", "0.02", "--x", "0.1", "--side", "0"], "omega"),
    (["--part", "triangle", "--omega", "3", "--x", "0.1", "--side", "0", "--model", "nope"], "model"),
    (["x.npz", "--trial", "1"], "trial"),
    (["--assemble", "--save-trajectory", "a.json"], "save_trajectory"),
])
def test_view_errors_are_one_line(tmp_path, args, field, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _one_error(runner.invoke(app, ["view", *args]), field)


@pytest.mark.slow
def test_view_an_assembly_episode(tmp_path):
    """One engine trial (seconds): the page plays it with both parts' orbit and the switch."""
    res = runner.invoke(app, ["view", "--assemble", "--seed", "0", "--index", "0", "--first-success",
                              "--out", str(tmp_path / "a.html"), "--save-trajectory", str(tmp_path / "a.npz")])
    assert res.exit_code == 0, res.output
    page = (tmp_path / "a.html").read_text()
    d = _data(page)
    assert len(d["parts"]) == 2 and "tilt" in d["orbit"]["phase"] and d["orbit"]["t"][0] is None
    assert len(page.encode()) < 400_000
    again = runner.invoke(app, ["view", str(tmp_path / "a.npz"), "--out", str(tmp_path / "b.html")])
    assert again.exit_code == 0 and "self-assembly, seed 0 trial " in (tmp_path / "b.html").read_text()
