"""Sweep results drawn: what a sweep's directory holds, and one design point's outcomes
(:mod:`throwmap.sweeps`). Draws; computes nothing. Matplotlib is imported on first use.
"""

from __future__ import annotations

import json

from .style import _plt, layout

__all__ = ["plot_sweep_status", "plot_point_summary"]


def _axes(ax, size):
    plt = _plt()
    if ax is None:
        return plt.subplots(figsize=size)
    return ax.figure, ax


def plot_sweep_status(status, ax=None):
    """A :class:`~throwmap.sweeps.run.SweepStatus`: the design's points as one bar, stored and missing.
    Returns the Figure."""
    fig, ax = _axes(ax, (6.0, 1.6))
    ax.barh([0], [status.rows], color="tab:green", label=f"stored {status.rows}")
    ax.barh([0], [status.missing], left=[status.rows], color="0.8", label=f"missing {status.missing}")
    ax.set_yticks([])
    ax.set_xlim(0, max(status.n_points, 1))
    ax.set_xlabel("design points")
    ax.set_title(f"sweep {status.sweep_sha256[:12]}: {status.n_points} points in {status.n_chunks} parts "
                 f"({status.chunks_missing} missing)", fontsize=9)
    ax.legend(fontsize=7, loc="lower right")
    layout(fig)
    return fig


def plot_point_summary(point, ax=None):
    """A :class:`~throwmap.sweeps.targets.PointSummary`: the share of trials per outcome, the success bar with its
    Wilson 95 % interval. Returns the Figure."""
    fig, ax = _axes(ax, (5.5, 3.4))
    if point.error is not None:
        ax.set_axis_off()
        ax.set_title(f"refused: {point.error}"[:90], fontsize=9)
        return fig
    n = max(point.n, 1)
    fails = json.loads(point.failures)
    labels = ["success"] + list(fails)
    fracs = [point.successes / n] + [c / n for c in fails.values()]
    ax.bar(range(len(labels)), fracs, color=["tab:green"] + ["tab:red"] * len(fails))
    p = fracs[0]
    ax.errorbar([0], [p], yerr=[[p - point.ci95_low], [point.ci95_high - p]], fmt="none", ecolor="k", capsize=5)
    ax.set_xticks(range(len(labels)), labels, rotation=20, ha="right")
    ax.set_ylim(0, 1.05)
    ax.set_ylabel("fraction of trials")
    ax.set_title(f"{point.successes}/{point.n} succeeded", fontsize=9)
    layout(fig)
    return fig
