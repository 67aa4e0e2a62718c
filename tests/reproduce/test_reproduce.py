"""``throwmap reproduce``: the plan covers the draft's figures, the report says what ran and what failed, the HTML is
self-contained, the errata stay in step with the documentation's errata page, a kept experiment resumes."""

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from throwmap.cli import app
from throwmap.errors import InvalidStateError
from throwmap.reproduce import EXPERIMENTS, FIGURES, reproduce
from throwmap.reproduce import run as run_mod
from throwmap.reproduce.figures import MAKERS
from throwmap.reproduce.plan import ExperimentSpec

ROOT = Path(__file__).resolve().parents[2]


def test_the_plan_covers_the_drafts_figures_and_experiments():
    drafts = {f.draft for f in FIGURES}
    assert {f"Fig. {k}" for k in (2, 5, 7, 8, 9, 13, 14, 15, 16)} <= drafts
    assert all(f.maker in MAKERS for f in FIGURES)
    assert len({f.key for f in FIGURES}) == len(FIGURES)
    assert [(e.draft_successes, e.draft_n) for e in EXPERIMENTS] == [(20, 20), (19, 20), (11, 20), (14, 20)]


def test_errata_in_step_with_the_docs():
    page = (ROOT / "docs" / "explanation" / "errata.md").read_text(encoding="utf-8")
    section = page.split("\n## The errata\n", 1)[1].split("\n## ", 1)[0]
    packaged = (ROOT / "src" / "throwmap" / "data" / "errata.md").read_text(encoding="utf-8")
    body = "\n".join(line for line in packaged.splitlines() if not line.startswith("<!--"))
    assert section.strip() == body.strip()
    assert re.findall(r"^(\d+)\. ", body, re.M) == [str(k) for k in range(1, len(re.findall(r"^\d+\. ", body,
                                                                                                re.M)) + 1)]


@pytest.fixture
def tiny(monkeypatch):
    """The plan cut to one cheap figure (a maker that draws a line) and the ``settle`` experiment."""
    def line(path, size, ctx):
        import matplotlib.pyplot as plt

        from throwmap.viz.style import save_figure

        fig, ax = plt.subplots()
        ax.plot([0, 1], [0, 1])
        save_figure(fig, path)
        plt.close(fig)
        return {"numbers": {"r_m": [0.1], "l_m": float("nan"), "xs": list(range(40))},
                "parameters": {"omega_rad_s": 4.123456789, "arm": {"h_m": -0.01}}}

    def broken(path, size, ctx):
        raise RuntimeError("no attractor within x <= 0.6 m\nsecond line")

    monkeypatch.setitem(MAKERS, "throw_map", line)
    monkeypatch.setitem(MAKERS, "funnels", broken)
    monkeypatch.setattr(run_mod, "FIGURES", FIGURES[:2])
    monkeypatch.setattr(run_mod, "EXPERIMENTS", (
        ExperimentSpec("settling", "Settling", "Sec. III", 20, 20, "settle", config={"arm": {"length": 0.4}}, goal=0.9),
        ExperimentSpec("missing", "Not built", "Sec. IX", 3, 20, "no-such-experiment")))


def test_report_says_what_ran_and_what_failed(tiny, tmp_path):
    rep = reproduce(tmp_path, size="quick", workers=1)
    assert rep.failed == ["fig02_funnels", "missing"]
    f0, f1 = rep.figures
    assert f0["error"] is None and (tmp_path / f0["file"]).stat().st_size > 1000
    assert f1["error"] == "RuntimeError: no attractor within x <= 0.6 m" and f1["file"] is None
    settle, missing = rep.experiments
    assert settle["ours"]["n"] == 3 and settle["ours"]["ci95"][0] <= settle["ours"]["success_rate"]
    assert settle["draft"]["ci95"][0] == pytest.approx(0.8389, abs=1e-4)  # Wilson of 20/20
    assert "'no-such-experiment' is not registered" in missing["error"]
    md = (tmp_path / "report.md").read_text()
    assert "| Settling (Sec. III; `experiment settle`) | 20/20 = 100.0 % [83.9, 100.0] % | 3/3" in md or \
        "| Settling (Sec. III; `experiment settle`) | 20/20 = 100.0 % [83.9, 100.0] % |" in md
    assert "**Failed pieces:** fig02_funnels, missing" in md and "## Errata" in md and "Lemma 4.1" in md
    page = (tmp_path / "report.html").read_text()
    assert "data:image/png;base64," in page and not re.search(r"(src|href)=[\"']https?:", page)
    assert "<ol>" in page and "Lemma 4.1" in page
    # the Markdown rendered: no literal emphasis or code marks outside code blocks; tables are tables
    text = re.sub(r"<(pre|code)>.*?</\1>", "", page, flags=re.S)
    assert "**" not in text and "`" not in text and "<table>" in page and "<strong>Failed pieces:</strong>" in page
    # the JSON blocks are valid JSON with no NaN; long lists are cut and say so; parameters are tables of 4 digits
    blocks = re.findall(r"```json\n(.*?)```", md, flags=re.S)
    assert blocks and all("NaN" not in b for b in blocks)
    numbers = json.loads(blocks[0])
    assert numbers["l_m"] is None and numbers["xs"][-1] == "… 28 more" and len(numbers["xs"]) == 13
    assert "| `omega_rad_s` | 4.123 |" in md and "| `arm.h_m` | -0.01 |" in md
    doc = json.loads((tmp_path / "report.json").read_text())
    assert doc["failed"] == rep.failed and doc["size"] == "quick"
    again = reproduce(tmp_path, size="quick", workers=1)  # the kept trials are read back
    assert again.experiments[0]["ours"]["resumed"] == 3


def test_cli_exit_codes(tiny, tmp_path):
    r = CliRunner().invoke(app, ["reproduce", "--quick", "--out", str(tmp_path), "--workers", "1"])
    assert r.exit_code == 1 and "failed: fig02_funnels, missing" in r.output
    assert "wrote " + str(tmp_path / "report.html") in r.output
    r = CliRunner().invoke(app, ["reproduce", "--quick", "--out", str(tmp_path), "--only", "fig99"])
    assert r.exit_code == 2 and "error: only: unknown keys ['fig99']" in r.output


def test_bad_size_and_workers():
    with pytest.raises(InvalidStateError, match="^size: must be one of"):
        reproduce("x", size="medium")
    with pytest.raises(InvalidStateError, match="^workers: must be an integer"):
        reproduce("x", workers=-1)
