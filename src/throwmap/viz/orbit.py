"""Orbit figure: x against throw number, side by colour (paper Figs. 7 and 16).

Draws an :class:`~throwmap.records.orbit.Orbit` that :func:`throwmap.iterate` has
already computed; matplotlib is imported on first use.
"""

from __future__ import annotations

import numpy as np

from ..records.outcome import Status
from .style import _plt, describe_setting, side_colors, wrap_setting

__all__ = ["plot_orbit"]


def plot_orbit(orbit, ax=None, part=None, unit: str = "cm", *, arm=None, title: str | None = None):
    """x against throw number, side by colour (like paper Figs. 7 and 16); returns the Figure.

    ``orbit.x`` is in m and drawn in ``unit`` (``"cm"``, the default, else m);
    ``part`` (optional) fixes the number of side colours and names the part in the
    title, ``arm`` (optional) gives its h (an :class:`~throwmap.Orbit` holds neither:
    pass both, or the title shows ``?`` for what is missing). The title names the
    part, h, ω and the model unless ``title`` is given. An orbit that ended early
    (``status`` not OK) has its last outcome marked ``x`` with the reason.
    """
    plt = _plt()
    if ax is None:
        fig, ax = plt.subplots(figsize=(7, 3.5))
    fig = ax.figure
    scale = 100.0 if unit == "cm" else 1.0
    k = np.arange(len(orbit.x))
    sides = np.asarray(orbit.side)
    n_sides = int(sides.max()) + 1 if part is None else part.n_sides
    colors = side_colors(max(n_sides, 1))
    ax.plot(k, orbit.x * scale, "-", color="0.8", lw=0.8, zorder=1)
    for s in np.unique(sides):
        m = sides == s
        ax.scatter(k[m], orbit.x[m] * scale, s=12, color=colors[int(s)], label=f"side {int(s)}", zorder=2)
    if orbit.status != Status.OK and orbit.outcomes:
        last = orbit.outcomes[-1]
        ax.scatter([len(orbit.x)], [last.x * scale], marker="x", color="k", s=40, zorder=3,
                   label=f"escape: {orbit.status.label}")
    ax.set_xlabel("throw number")
    ax.set_ylabel(f"x of CM on the arm ({unit})")
    if title is None:
        omegas = [float(w) for w in np.unique(np.round(orbit.omegas, 6))]
        setting = describe_setting(part, None if arm is None else arm.h, omegas if len(omegas) <= 4 else (),
                                   orbit.model, None if arm is None else arm.mu)
        if len(omegas) > 4:
            setting = setting.replace("ω = ?", f"{len(omegas)} release rates {min(omegas):g}–{max(omegas):g} rad/s")
        # on lines that fit over the axes (at most 0.6 em a character at 9 pt)
        width_pt = ax.get_position().width * fig.get_figwidth() * 72.0
        title = wrap_setting(f"orbit ({orbit.n_throws} throws): {setting}", int(width_pt / (0.6 * 9)))
    ax.set_title(title, fontsize=9)
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    return fig
