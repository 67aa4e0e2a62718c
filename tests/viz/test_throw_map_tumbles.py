"""The throw map names a throw that lands on its own side beyond a flip a tumble over and back (not a jog), and
keeps every image inside its axes."""

from __future__ import annotations

import numpy as np
import pytest

import throwmap as tm
from throwmap.throws.samples import throw_map_samples


@pytest.fixture(scope="module")
def samples():
    return throw_map_samples(tm.triangle_30_60_90(0.17), tm.Arm(h=-0.01), 4.0, model="paper", x_max=0.6, n=300)


def test_kinds_jog_before_the_first_flip_and_tumble_after_it(samples):
    kinds = samples.kinds()
    assert set(kinds) <= {"jog", "flip", "tumble", "escape"}
    for s in samples.sides:
        sl = samples.panel(s)
        k, same, ok = kinds[sl], samples.side_next[sl] == s, samples.ok[sl]
        assert np.array_equal(k == "escape", ~ok) and np.array_equal(k == "flip", ok & ~same)
        flips = np.flatnonzero(k == "flip")
        first = flips[0] if flips.size else len(k)
        assert np.all(np.flatnonzero(k == "jog") < first) and np.all(np.flatnonzero(k == "tumble") > first)
    # the draft's triangle at ω = 4 rad/s: side 1 tumbles over and back beyond its flips (the map command says so too)
    assert np.any(kinds[samples.panel(1)] == "tumble")


def test_the_figure_labels_tumbles_and_keeps_every_image_inside(samples):
    import matplotlib

    matplotlib.use("Agg")
    fig = samples.plot(compact=True)
    ax1 = fig.axes[samples.sides.index(1)]
    assert any(c.get_gid() == "tumble-1" for c in ax1.collections)
    labels = [t.get_text() for t in ax1.get_legend().get_texts()]
    assert "→ side 1, tumbled over and back" in labels and "→ side 1 (jog)" in labels
    ok = samples.ok
    top = 100 * float(np.max(samples.x_next[ok]))
    for ax in fig.axes:
        assert ax.get_ylim()[1] >= top - 1e-9 and ax.get_xlim()[1] >= top - 1e-9
