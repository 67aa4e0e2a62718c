"""The feeder tutorial (docs/tutorials/feeder.md) as a new user runs it: the commands of its tested block, in order,
in a fresh folder, each exiting 0 with the output it describes."""

from __future__ import annotations

import json
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "tutorials" / "feeder.md"


def _tested_commands() -> list[str]:
    text = DOC.read_text(encoding="utf-8")
    m = re.search(r"<!-- tutorial: the tests run the commands of this block in order -->\s*```bash\n(.*?)```", text,
                  re.S)
    assert m, "the tutorial has no tested block"
    block = m.group(1).replace("\\\n", " ")  # a command continued on the next line, as a shell reads it
    return [ln for ln in block.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]


@pytest.mark.slow
def test_the_feeder_tutorial_runs_as_written(tmp_path):
    (tmp_path / "examples").mkdir()
    (tmp_path / "examples" / "triangle_plate.toml").write_text((ROOT / "examples" / "triangle_plate.toml").read_text())
    docs = []
    for line in _tested_commands():
        args = shlex.split(line)
        assert args[0] == "throwmap"
        res = subprocess.run([sys.executable, "-m", "throwmap", *args[1:], "--workers", "1"], cwd=tmp_path,
                             capture_output=True, text=True, timeout=600)
        assert res.returncode == 0, (line, res.stdout[-2000:], res.stderr[-2000:])
        docs.append(json.loads(res.stdout))
    design, feed = docs
    assert design["success"] is True and design["side"] == 0 and design["config"].endswith("feeder.toml")
    v = design["verified"]
    # the verification is the 5 first trials that chose the candidate: only the rerun's 5 count
    assert v["n"] == 5 and v["successes"] >= 5 and v["ci95"][0] <= v["successes"] / v["n"] <= v["ci95"][1]
    assert [r["n"] for r in v["runs"]] == [5] and v["left_out"]["n"] == 5 and v["rerun95"]["n"] == 5
    # the time covers every stage, the design sheet's included
    assert "sheet" in design["stages_s"] and design["time_s"] == pytest.approx(sum(design["stages_s"].values()))
    assert design["assumptions"]["omega_jitter_rel"] == 0.03 and design["feeder"]["variant"]["weight"]["mass_kg"] <= 0.05
    for name in ("feeder.toml", "part.toml", "sheet.md", "sheet.html", "drawing.svg", "drawing.png", "fed_trial.html"):
        assert (tmp_path / "quick" / name).is_file(), name
    sheet = (tmp_path / "quick" / "sheet.md").read_text()
    assert f"{v['successes']}/{v['n']}" in sheet and "throws to capture" in sheet
    assert feed["n"] == 3 and feed["successes"] >= 2
