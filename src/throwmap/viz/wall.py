"""The fixed point a wall makes, checked: left difference quotients of the map against the step
(:class:`throwmap.analysis.wall.WallFixedPoint`). Draws; computes nothing. Matplotlib is imported on first use.
"""

from __future__ import annotations

import math

from .style import _plt, layout

__all__ = ["plot_wall_fixed_point"]


def plot_wall_fixed_point(fp, ax=None):
    """|(T(x*) − T(x* − h))/h| against h (log–log; a zero quotient drawn at the axis floor) and limit_set's
    multiplier as a dashed line; a fixed point not found is a titled empty axes. Returns the Figure."""
    plt = _plt()
    if ax is None:
        fig, ax = plt.subplots(figsize=(5.5, 3.6))
    else:
        fig = ax.figure
    if not fp.found:
        ax.set_axis_off()
        ax.set_title(f"wall fixed point ({fp.model}, {fp.part}, side {fp.side}): not found", fontsize=9)
        return fig
    floor = 1e-12
    hs = [float(h) for h in fp.fd_steps_m]
    qs = [abs(float(q)) if q is not None and math.isfinite(q) else math.nan for q in fp.fd_left]
    ax.loglog(hs, [max(q, floor) if math.isfinite(q) else math.nan for q in qs], "o-", color="C0",
              label="|T(x*) − T(x* − h)| / h")
    if math.isfinite(fp.multiplier):
        ax.axhline(max(abs(fp.multiplier), floor), color="0.4", ls="--", lw=0.9,
                   label=f"limit_set's multiplier {fp.multiplier:+.3g}")
    ax.set_xlabel("step h (m)")
    ax.set_ylabel("left difference quotient")
    ax.set_title(f"wall fixed point x* = {fp.x_star_m:.6f} m ({fp.model}, {fp.part}, side {fp.side})", fontsize=9)
    ax.legend(fontsize=7)
    layout(fig)
    return fig
