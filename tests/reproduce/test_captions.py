"""A figure whose result failed is a failed piece of the reproduction, and captions come from results."""

from pathlib import Path

from throwmap.reproduce import figures
from throwmap.reproduce.plan import FigureSpec
from throwmap.reproduce.run import _figure

SPEC = FigureSpec("figX", "Fig. X", "The designed part captured in its cavity.", "fake")


def test_a_failed_result_fails_the_figure_and_its_caption_says_so(monkeypatch, tmp_path):
    monkeypatch.setitem(figures.MAKERS, "fake", lambda path, size, ctx: {"numbers": {"success": False},
                                                                        "failure": "failed: engine capture"})
    row = _figure(SPEC, Path(tmp_path), None, {})
    assert row["error"] == "its result failed (success: false): failed: engine capture"
    assert row["caption"].startswith("Not reproduced — the result failed.")


def test_a_successful_result_keeps_its_caption(monkeypatch, tmp_path):
    monkeypatch.setitem(figures.MAKERS, "fake", lambda path, size, ctx: {"numbers": {"success": True}})
    row = _figure(SPEC, Path(tmp_path), None, {})
    assert row["error"] is None and row["caption"] == SPEC.caption


def test_a_caption_from_the_result_replaces_the_planned_one(monkeypatch, tmp_path):
    monkeypatch.setitem(figures.MAKERS, "fake", lambda path, size, ctx: {"numbers": {}, "caption": "2 panels: a, b."})
    assert _figure(SPEC, Path(tmp_path), None, {})["caption"] == "2 panels: a, b."
