"""The Fig. 14 analogue's region: the shaded "rests" area over (γ, μ) is exactly where the arm μ is at least the μ
the black line says the partial assembly needs (the same LP), at every γ between the samples too, and the legend
names it.

The drawn objects are inspected (the filled paths in data coordinates), not the pixels of a saved image.
"""

import math

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import to_rgb  # noqa: E402

import throwmap as tm  # noqa: E402
from throwmap.statics.assembly import PartialRegion  # noqa: E402
from throwmap.statics.figures import partial_data  # noqa: E402

TRI = tm.triangle_30_60_90(0.17)
ALPHA = math.radians(-10.0)
TOL = 1e-3
"""Arm μ this close to the μ needed (or to the axes' edges) is not judged: the region's edge lies there."""


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


@pytest.fixture(scope="module")
def data():
    """Fig. 14's data on the reproduced figure's μ grid (0 … 0.6 in steps of 0.025), at the γ where the assembly
    needs μ between two grid values (−29.5 … −23.5°)."""
    return partial_data(TRI, alpha=ALPHA, gamma_show=math.radians(-15), gammas_deg=np.arange(-29.5, -23.0, 1.0))


def _green(ax):
    """The paths (data coordinates) painted in tab:green on ``ax``: the "rests" region."""
    green = np.array(to_rgb("tab:green"))
    paths = []
    for c in ax.collections:
        faces = c.get_facecolors()
        for k, p in enumerate(c.get_paths()):
            if len(faces) and np.allclose(faces[k % len(faces)][:3], green, atol=0.02):
                paths.append(p)
    return paths


def _says_rests(paths, g, mu) -> bool:
    return any(p.contains_point((g, mu)) for p in paths)


def _check_region(ax, g, need, top):
    """At γ across ``g`` (the samples and between them, the line's interpolation) the region holds (γ, μ) iff
    μ ≥ μ needed; returns how many points were judged."""
    paths = _green(ax)
    assert paths, "no region drawn"
    gs = np.linspace(g[0], g[-1], 8 * (len(g) - 1) + 1)[1:-1]
    bad, n = [], 0
    for gg in gs:
        nd = float(np.interp(gg, g, need))
        for mu in np.linspace(0.0, top, 241):
            if abs(mu - nd) < TOL or mu < TOL or mu > top - TOL:
                continue
            n += 1
            if _says_rests(paths, gg, mu) != (mu >= nd):
                bad.append((round(float(gg), 3), round(float(mu), 4), round(nd, 4)))
    assert not bad, f"region disagrees with the μ-needed line at (γ deg, μ, μ needed): {bad[:6]}"
    return n


def test_fig14_region_is_where_mu_reaches_the_mu_needed(data):
    fig = data.plot()
    ax = fig.axes[1]
    assert _check_region(ax, data.gammas_deg, data.mu_needed, float(np.max(data.mus))) > 1000
    # the line drawn is the data's μ needed
    line = next(ln for ln in ax.get_lines() if ln.get_label().startswith("arm μ needed"))
    assert np.allclose(line.get_xdata(), data.gammas_deg) and np.allclose(line.get_ydata(), data.mu_needed)


def test_fig14_region_is_named_in_the_legend(data):
    ax = data.plot().axes[1]
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    handles, names = ax.get_legend_handles_labels()
    named = [h for h, n in zip(handles, names) if n.startswith("rests")]
    assert named and any(t.startswith("rests") for t in labels), labels
    assert all(p in _green(ax) for h in named for p in h.get_paths())


def test_partial_region_plot_leaves_out_a_gamma_that_cannot_rest():
    """A made-up region: μ needed 0.03 … 0.05, and ∞ (no arm μ holds it) at one γ: no rest is shown there."""
    g = np.radians([-29.5, -28.5, -27.5, -26.5, -25.5])
    need = np.array([0.0497, 0.0467, np.inf, 0.0407, 0.0378])
    mus = np.linspace(0.0, 0.6, 25)
    reg = PartialRegion(g, mus, mus[None, :] >= need[:, None], need, ALPHA)
    ax = reg.plot().axes[0]
    gd = np.degrees(g)
    paths = _green(ax)
    assert not any(_says_rests(paths, gd[2], mu) for mu in np.linspace(0.01, 0.59, 59))
    _check_region(ax, gd[:2], need[:2], 0.6)
    _check_region(ax, gd[3:], need[3:], 0.6)
    assert any(t.get_text().startswith("rests") for t in ax.get_legend().get_texts())
