"""Figures of a stochastic throw map's chain: arrays in, figures out.

* :func:`plot_goal_curve` — P(goal by throw k): the chain's curve over the Monte Carlo's points and their
  pointwise Wilson 95 % band, with the fraction of k inside the band in the legend;
* :func:`plot_stationary` — the long-run mass per cell against x, one panel per side, and the mass absorbed
  (off the end, behind the joint…) in the title.

Matplotlib is imported on first use. Nothing here computes a throw.
"""

from __future__ import annotations

import numpy as np

from .style import _plt

__all__ = ["plot_goal_curve", "plot_stationary", "plot_comparisons"]


def plot_goal_curve(k, chain, mc, low, high, *, n: int | None = None, label: str = "", fraction=None, ax=None,
                    title: str | None = None):
    """The chain's P(goal by k) (line) and the Monte Carlo's (points, shaded Wilson 95 % band); returns the Figure."""
    plt = _plt()
    if ax is None:
        fig, ax = plt.subplots(figsize=(6.0, 3.8))
    else:
        fig = ax.figure
    k = np.asarray(k)
    ax.fill_between(k, 100 * np.asarray(low), 100 * np.asarray(high), step="mid", color="C0", alpha=0.2,
                    lw=0, label="Monte Carlo, Wilson 95 % band")
    step = max(1, k.size // 60)
    ax.plot(k[::step], 100 * np.asarray(mc)[::step], "o", color="C0", ms=3,
            label=f"Monte Carlo ({n} trials)" if n else "Monte Carlo")
    frac = "" if fraction is None else f": {100 * fraction:.1f} % of k inside the band"
    ax.plot(k, 100 * np.asarray(chain), "-", color="C3", lw=1.6, label=f"Markov chain{frac}")
    ax.set_xlabel("throw k")
    ax.set_ylabel("P(goal reached by throw k) (%)")
    ax.set_ylim(-2, 102)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    ax.set_title(title or (label or "P(goal by throw k)"), fontsize=10)
    fig.tight_layout()
    return fig


def plot_comparisons(comparisons: list, *, title: str | None = None):
    """Several :func:`plot_goal_curve` panels side by side (``comparisons``: objects with ``.plot(ax=)``)."""
    plt = _plt()
    fig, axes = plt.subplots(1, len(comparisons), figsize=(5.5 * len(comparisons), 3.8), squeeze=False)
    for ax, c in zip(axes[0], comparisons):
        c.plot(ax=ax)
    if title:
        fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    return fig


def plot_stationary(per_side: dict, absorbed: dict | None = None, *, ax=None, unit: str = "cm",
                    title: str | None = None):
    """Mass per cell (as a density per cm) against the CM abscissa, one row per side; ``per_side`` is
    {side: (left m, right m, mass)}; ``absorbed`` {label: mass} goes in the title. Returns the Figure."""
    plt = _plt()
    sides = sorted(per_side)
    scale = 100.0 if unit == "cm" else 1.0
    if ax is None:
        fig, axes = plt.subplots(len(sides), 1, figsize=(6.0, 1.6 + 1.3 * len(sides)), sharex=True, squeeze=False)
        axes = axes[:, 0]
    else:
        axes = np.atleast_1d(ax)
        fig = axes[0].figure
    for a, k in zip(axes, sides):
        left, right, mass = (np.asarray(v, dtype=float) for v in per_side[k])
        width = (right - left) * scale
        a.bar(left * scale, mass / np.where(width > 0, width, 1.0), width=width, align="edge", color=f"C{k % 10}",
              alpha=0.8, lw=0)
        a.set_ylabel(f"side {k}\nmass / {unit}", fontsize=8)
        a.text(0.99, 0.85, f"{100 * mass.sum():.1f} % on side {k}", transform=a.transAxes, ha="right", fontsize=8)
        a.grid(alpha=0.3)
    axes[-1].set_xlabel(f"CM abscissa x ({unit})")
    gone = {lab: v for lab, v in (absorbed or {}).items() if v > 5e-4}
    head = title or "long-run distribution over the arm"
    if gone:
        head += "\n" + ", ".join(f"{lab} {100 * v:.1f} %" for lab, v in gone.items())
    axes[0].set_title(head, fontsize=9)
    fig.tight_layout()
    return fig
