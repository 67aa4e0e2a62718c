"""Model-comparison figure: jog-length error of each approximate model against the reference, per ω.

Draws a :class:`~throwmap.studies.compare.ModelComparison` already computed by
:func:`~throwmap.studies.compare.compare_models`; matplotlib is imported on first use.
"""

from __future__ import annotations

import math

from .style import _plt, describe_setting, wrap_setting

__all__ = ["plot_model_comparison"]


def plot_model_comparison(comparison, ax=None):
    """Median relative jog error (%) of each model against ``comparison.reference``, per ω (rad/s); the Figure.

    The title names the part, h, the ω compared, the models and the reference model.
    """
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
    omegas = sorted({float(r["omega"]) for r in comparison.rows})
    models = ", ".join(comparison.models)
    setting = describe_setting(comparison.part_name, comparison.h, omegas, comparison.reference)
    x_max = getattr(comparison, "x_max", None)
    rng = f", x ≤ {100 * x_max:.4g} cm" if isinstance(x_max, (int, float)) and math.isfinite(x_max) else ""
    width = max(40, int(12 * fig.get_figwidth()))  # characters that fit at fontsize 8
    ax.set_title(wrap_setting(setting + rng, width) + f"\njog error of {models} against {comparison.reference!r}",
                 fontsize=8)
    fig.tight_layout()
    return fig
