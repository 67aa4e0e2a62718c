"""Agreement of models with a reference, drawn (:class:`throwmap.studies.agreement.AgreementTable`).

:func:`plot_agreement` draws, per comparison, the share of compared throws with the same outcome and the share of
same-outcome rests within the position tolerance, each with its Wilson 95 % interval as an error bar; the refusals
(left out of both shares) are written beside each row. Takes the table or its ``to_dict()``; computes nothing.
Matplotlib is imported on first use.
"""

from __future__ import annotations

import math

from .style import _plt, layout

__all__ = ["plot_agreement"]


def plot_agreement(table, ax=None, *, title: str | None = None):
    """Horizontal points: same outcome (%) and |Δx| ≤ tol (%) per row with Wilson 95 % bars; returns the Figure."""
    plt = _plt()
    d = table if isinstance(table, dict) else table.to_dict()
    rows = d["rows"]
    if ax is None:
        fig, ax = plt.subplots(figsize=(7.5, 0.9 + 0.42 * max(len(rows), 1)))
    else:
        fig = ax.figure
    ys = list(range(len(rows)))[::-1]
    for key, ci, off, color, name in (("same_rate", "same_ci95", 0.12, "C0", "same outcome"),
                                      ("within_rate", "within_ci95", -0.12, "C1", "|Δx| ≤ tol, of same-outcome rests")):
        pts = [(y + off, r[key], r[ci]) for y, r in zip(ys, rows) if r[key] is not None and math.isfinite(r[key])]
        if not pts:
            continue
        yy = [p[0] for p in pts]
        xx = [100 * p[1] for p in pts]
        lo = [100 * (p[1] - p[2][0]) for p in pts]
        hi = [100 * (p[2][1] - p[1]) for p in pts]
        ax.errorbar(xx, yy, xerr=[lo, hi], fmt="o", color=color, ecolor=color, capsize=3, ms=4,
                    label=f"{name} (Wilson 95 %)")
    for y, r in zip(ys, rows):
        ax.annotate(f"{r['compared']}/{r['n']} compared; refused {r['refused_model']} / {r['refused_reference']}",
                    (0, y), xytext=(3, -9), textcoords="offset points", fontsize=6, color="0.35")
    ax.set_yticks(ys, [r["label"] for r in rows], fontsize=7)
    ax.set_xlim(-2, 102)
    ax.set_ylim(-0.8, len(rows) - 0.2)
    ax.set_xlabel("agreement (%)")
    ax.set_title(title or f"agreement with the {d.get('reference', 'reference')}", fontsize=9)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7, loc="lower left")
    layout(fig)
    return fig
