"""The assembly snapshots' caption counts the panels drawn: "0 panels", "1 panel", "2 panels"."""

from types import SimpleNamespace

import numpy as np
import pytest

from throwmap.reproduce import figures


def _episode(labels):
    runs = tuple((label, i) for i, label in enumerate(labels))
    return SimpleNamespace(plot_snapshots=lambda: None, snapshot_runs=lambda: runs, throw_no=np.arange(1, 10) * 3,
                           seed=0, index=0)


@pytest.mark.parametrize("labels,panels", [((), "0 panels"), (("dropped",), "1 panel:"),
                                           (("dropped", "assembled"), "2 panels")], ids=["none", "one", "two"])
def test_the_caption_counts_the_panels(monkeypatch, tmp_path, labels, panels):
    monkeypatch.setattr(figures, "_episode", lambda ctx: _episode(labels))
    monkeypatch.setattr(figures, "_save", lambda fig, path: None)
    caption = figures.assembly_snapshots(tmp_path / "f.png", None, {})["caption"]
    assert f"The same trial, {panels}" in caption
    if not labels:
        assert "no snapshot" in caption
