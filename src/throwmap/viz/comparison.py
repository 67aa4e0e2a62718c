"""Model-comparison figure: jog-length error of each approximate model against the reference, per ω.

Draws a :class:`~throwmap.studies.compare.ModelComparison` already computed by
:func:`~throwmap.studies.compare.compare_models`; matplotlib is imported on first use.
"""

from __future__ import annotations

from .style import _plt

__all__ = ["plot_model_comparison"]


def plot_model_comparison(comparison, ax=None):
    """Median relative jog error (%) of each model against ``comparison.reference``, per ω (rad/s); the Figure."""
    plt = _plt()
    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 3.5))
    fig = ax.figure
    for model in comparison.models:
        rows = [r for r in comparison.rows if r["model"] == model]
        ax.plot([r["omega"] for r in rows], [r["jog_rel_err_median"] * 100 for r in rows], "o-", label=model)
    ax.set_xlabel("ω (rad/s)")
    ax.set_ylabel(f"median |Δ jog| / jog vs {comparison.reference!r} (%)")
    ax.set_yscale("log")
    ax.legend()
    ax.set_title(comparison.part_name)
    fig.tight_layout()
    return fig
