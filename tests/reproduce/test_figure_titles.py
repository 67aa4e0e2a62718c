"""Every title of a reproduced figure lies inside the figure: none is cut off at the figure's edge.

The figures are made by ``throwmap reproduce``'s own makers (quick size), kept instead of saved, drawn with Agg
and each title's extent compared with the figure's box.
"""

from pathlib import Path

import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402

from throwmap.reproduce import FIGURES, figures  # noqa: E402
from throwmap.reproduce.plan import SIZES  # noqa: E402

CHEAP = tuple(f.key for f in FIGURES if f.key != "fig02_funnels")
"""The reproduced figures made here in seconds each (the funnels' 400-point grids on a 1 m arm take minutes)."""


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _made(key, tmp_path, monkeypatch):
    """The figure ``key`` as ``throwmap reproduce`` makes it (quick size), kept open."""
    kept = []
    monkeypatch.setattr(figures, "_save", lambda fig, path: kept.append(fig))
    spec = next(f for f in FIGURES if f.key == key)
    figures.MAKERS[spec.maker](Path(tmp_path) / f"{key}.png", SIZES["quick"], {})
    assert len(kept) == 1
    return kept[0]


def _titles(fig):
    texts = [fig._suptitle] if fig._suptitle is not None else []
    for ax in fig.axes:
        texts += [ax.title, ax._left_title, ax._right_title]
    return [t for t in texts if t.get_visible() and t.get_text()]


@pytest.mark.parametrize("key", CHEAP)
def test_reproduced_titles_fit_inside_the_figure(key, tmp_path, monkeypatch):
    fig = _made(key, tmp_path, monkeypatch)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    box = fig.bbox
    titles = _titles(fig)
    assert titles
    for t in titles:
        e = t.get_window_extent(renderer)
        inside = e.x0 >= box.x0 - 0.5 and e.x1 <= box.x1 + 0.5 and e.y0 >= box.y0 - 0.5 and e.y1 <= box.y1 + 0.5
        assert inside, (f"{key}: title {t.get_text()!r} spans x {e.x0:.0f}…{e.x1:.0f}, y {e.y0:.0f}…{e.y1:.0f} px; "
                        f"the figure {box.x0:.0f}…{box.x1:.0f} × {box.y0:.0f}…{box.y1:.0f}")
