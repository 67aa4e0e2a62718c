"""The critical points of a throw map drawn per side: where jogs start and end (r_i), where the limit set
begins (l_i), and what throws beyond r_i do (paper Sec. III-D).

One row per stable side on a common x axis (``unit``, data in m): a bar from ``jog_start`` to r_i (the
jogs), a marker at l_i = inf S, the runs beyond r_i that do not flip (tumbles back, escapes), and the
domain's end ``x_max``. Draws a :class:`~throwmap.analysis.critical.CriticalPoints`; computes nothing.
"""

from __future__ import annotations

import math

from .style import _plt, map_title, scale, side_colors

__all__ = ["plot_critical"]


def plot_critical(cp, ax=None, *, unit: str = "cm"):
    """Draw ``cp`` (a :class:`~throwmap.analysis.critical.CriticalPoints`) on ``ax`` (a new figure when None);
    returns the Figure."""
    plt = _plt()
    k = scale(unit)
    if ax is None:
        fig, ax = plt.subplots(figsize=(7.0, 1.0 + 0.6 * max(1, len(cp.sides))))
    else:
        fig = ax.figure
    colors = side_colors(1 + max(cp.sides, default=0))
    for row, s in enumerate(cp.sides):
        lo, r, l = cp.jog_start.get(s, math.nan), cp.r.get(s, math.nan), cp.l.get(s, math.nan)
        end = r if math.isfinite(r) else cp.x_max
        if math.isfinite(lo):
            ax.plot([lo * k, end * k], [row, row], color=colors[s], lw=6, solid_capstyle="butt",
                    label="jogs (jog_start → r_i)" if row == 0 else None)
        if math.isfinite(r):
            ax.plot([r * k], [row], marker="|", ms=16, color="tab:red", label="r_i: where jogs end" if row == 0 else None)
        if math.isfinite(l):
            ax.plot([l * k], [row], marker="v", ms=9, color="tab:blue",
                    label="l_i: where S begins (inf S)" if row == 0 else None)
        for x0, x1, what in cp.non_flips.get(s, ()):
            ax.plot([x0 * k, x1 * k], [row - 0.25, row - 0.25], color="0.4", lw=2,
                    label="beyond r_i, not a flip" if row == 0 else None)
            ax.annotate(str(what), (x0 * k, row - 0.25), xytext=(0, -9), textcoords="offset points", fontsize=7)
    ax.axvline(cp.x_max * k, color="0.6", ls=":", lw=1, label=f"x_max = {cp.x_max * k:.4g} {unit}")
    ax.set_yticks(range(len(cp.sides)), [f"side {s}" for s in cp.sides])
    ax.set_ylim(-0.8, len(cp.sides) - 0.4)
    ax.set_xlabel(f"x ({unit})")
    ax.set_title(f"critical points — {map_title(cp.map_info)}", fontsize=9)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    return fig
