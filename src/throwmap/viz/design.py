"""Design figure: the paper's Fig. 8 analogue — iterates of a limit-set design, each part beside its limit set.

One row per chosen iterate: on the left the part (the plate, its lead weight as a disc to
scale of the weight's margin, the CM, each side labelled by its number), on the right its
forward limit set along the arm (:func:`throwmap.viz.limit_set.plot_limit_set`) with the
achieved r_i (red ▼) and the targets (green ◆ and a dashed line). Nothing here evaluates a
map: :meth:`throwmap.design.result.DesignResult.plot` computes the limit sets and passes them
in. Matplotlib is imported on first use.
"""

from __future__ import annotations

import math

import numpy as np

from .style import _plt, layout, scale, side_colors

__all__ = ["plot_design", "draw_part", "plot_side_radii"]


def draw_part(ax, part, *, weight_radius: float = 0.008, unit: str = "cm", title: str | None = None):
    """The part in its body frame: plate outline, side numbers, lead weights (discs), CM (+)."""
    from matplotlib.patches import Circle, Polygon

    k = scale(unit)
    V = np.asarray(part.vertices, dtype=float)
    ax.add_patch(Polygon(V * k, closed=True, fc="0.9", ec="0.2", lw=1.2, zorder=1))
    n = len(V)
    colors = side_colors(n)
    # side k joins clockwise w_k, w_{k+1}; user vertices via part.user_vertex
    c = np.asarray(part.com) * k
    for s in range(n):
        a = V[part.user_vertex(s)] * k
        b = V[part.user_vertex(s + 1)] * k
        mid = 0.5 * (a + b)
        out = mid - c
        out = out / (np.linalg.norm(out) or 1.0)
        ax.plot([a[0], b[0]], [a[1], b[1]], color=colors[s], lw=3, zorder=2, solid_capstyle="round")
        ax.text(*(mid + 0.9 * out * (1.0 if unit == "cm" else 0.01)), f"{s}", color=colors[s], ha="center",
                va="center", fontsize=9, fontweight="bold")
    for m, (x, y) in part.point_masses:
        ax.add_patch(Circle((x * k, y * k), weight_radius * k, fc="0.35", ec="k", zorder=3))
        ax.text(x * k, y * k, f"{1000 * m:.3g} g", color="w", ha="center", va="center", fontsize=6, zorder=4)
    ax.plot(*c, marker="+", color="tab:red", ms=10, mew=2, zorder=5)
    ax.set_aspect("equal")
    pad = 0.15 * float(np.ptp(V, axis=0).max()) * k
    ax.set_xlim(V[:, 0].min() * k - pad, V[:, 0].max() * k + pad)
    ax.set_ylim(V[:, 1].min() * k - pad, V[:, 1].max() * k + pad)
    ax.set_xlabel(unit, fontsize=8)
    ax.tick_params(labelsize=7)
    if title:
        ax.set_title(title, fontsize=8)
    return ax


def plot_design(result, ax=None, *, steps=None, limit_sets=None, unit: str = "cm", separation=None):
    """The Fig. 8 analogue of a :class:`~throwmap.design.result.DesignResult`.

    Parameters
    ----------
    result : DesignResult
    ax : sequence of Axes pairs, optional
        ``[(ax_part, ax_limit), …]``, one pair per drawn step; default a new figure.
    steps : sequence of int, optional
        Iterates to draw (default: the start, up to two in between, the last).
    limit_sets : dict or bool
        ``{step: LimitSet}`` to draw beside each part (True: :meth:`DesignResult.limit_sets`
        computes them; False/None: only r_i and the targets on empty lanes).
    unit : str
        ``"cm"`` or ``"m"`` for the axes (data in m).
    separation : Separation, optional
        Draws X (solid) and X ± margin (shaded) on every row; default the result's own
        separation target, if any.

    Returns
    -------
    Figure
    """
    from matplotlib.lines import Line2D

    plt = _plt()
    k = scale(unit)
    n_hist = len(result.history)
    if steps is None:
        steps = sorted({0, n_hist - 1, *([n_hist // 3, (2 * n_hist) // 3] if n_hist > 3 else range(n_hist))})
    steps = [int(s) for s in steps]
    if limit_sets is True:
        limit_sets = result.limit_sets(steps)
    limit_sets = limit_sets or {}
    if ax is None:
        fig, axes = plt.subplots(len(steps), 2, figsize=(12, 2.6 * len(steps) + 0.8),
                                 gridspec_kw={"width_ratios": [1, 3.2]}, layout="constrained", squeeze=False)
    else:
        axes = np.asarray(ax, dtype=object).reshape(-1, 2)
        fig = axes[0, 0].figure
    targets = result.target_values()
    if separation is None:
        separation = next((t for t in result.targets if type(t).__name__ == "Separation"), None)
    sides = sorted({t.side for t in result.targets} | set(result.part.stable_sides))
    colors = side_colors(max(sides) + 1)
    x_top = max([v for st in result.history for v in st.r.values() if math.isfinite(v)] + list(targets.values())
                + [0.1])
    for row, i in enumerate(steps):
        st = result.history[i]
        axp, axl = axes[row]
        vals = ", ".join(_fmt(k_, st.values[k_]) for k_ in result.vary)
        draw_part(axp, st.part, weight_radius=result.margin, unit=unit,
                  title=f"step {i}" + (" (start)" if i == 0 else " (solution)" if i == n_hist - 1 else "")
                  + f"\n{vals}")
        ls = limit_sets.get(i)
        lane = {s: j for j, s in enumerate(sides)}
        if ls is not None:
            from .limit_set import plot_limit_set

            plot_limit_set(ls, ax=axl, unit=unit)
            leg = axl.get_legend()
            if leg is not None and row != len(steps) - 1:
                leg.remove()
            present = [int(t.get_text().split()[-1]) for t in axl.get_yticklabels() if t.get_text()]
            lane = {s: j for j, s in enumerate(present)} or lane
        else:
            for s in sides:
                axl.hlines(lane[s], 0, x_top * 1.1 * k, color="0.82", lw=1.0)
            axl.set_yticks(range(len(sides)))
            axl.set_yticklabels([f"side {s}" for s in sides])
            axl.set_xlabel(f"x of CM along the arm ({unit}; joint at 0)")
        for s, r in st.r.items():
            if s in lane and math.isfinite(r):
                axl.scatter([r * k], [lane[s] + 0.25], marker="v", s=45, color="tab:red", zorder=7)
        for lbl, v in targets.items():
            _, s = lbl.split("_")
            s = int(s)
            if s in lane:
                axl.vlines(v * k, lane[s] - 0.35, lane[s] + 0.35, color="tab:green", ls="--", lw=1.3, zorder=6)
                axl.scatter([v * k], [lane[s] + 0.35], marker="D", s=28, color="tab:green", zorder=7)
        if separation is not None:
            axl.axvspan((separation.x - separation.margin) * k, (separation.x + separation.margin) * k,
                        color="tab:purple", alpha=0.08, zorder=0)
            axl.axvline(separation.x * k, color="tab:purple", lw=1.0, zorder=1)
            axl.text(separation.x * k, 1.0, f" X: only side {separation.side} beyond", color="tab:purple", fontsize=7,
                     va="top", transform=axl.get_xaxis_transform())
        ach = ", ".join(f"{lbl} {100 * v:.2f}" for lbl, v in st.achieved.items())
        axl.set_title(f"step {i}: {ach} cm, |achieved − target| = {1000 * st.norm:.2f} mm", fontsize=9)
        axl.set_xlim(0, max(axl.get_xlim()[1], 1.08 * x_top * k))
    handles = [Line2D([], [], ls="none", marker="v", color="tab:red", label="$r_i$ achieved (exact map)"),
               Line2D([], [], ls="--", marker="D", color="tab:green", label="target")]
    axes[0, 1].legend(handles=handles, loc="lower right", fontsize=7, framealpha=0.8)
    fig.suptitle(f"limit-set design (paper Fig. 8 analogue): {result.part.name}, model {result.model}\n"
                 f"{'' if result.success else 'NOT REACHED: '}{result.message}", fontsize=9)
    del colors
    layout(fig)
    return fig


_SHORT = {"weight_x": "x_w", "weight_y": "y_w", "com_x": "x_CM", "com_y": "y_CM", "h": "h", "weight_mass": "m_w"}


def _fmt(name: str, v) -> str:
    if v is None:
        return f"{name} —"
    if name in ("weight_x", "weight_y", "com_x", "com_y", "h"):
        return f"{_SHORT[name]} {100 * v:.2f} cm"
    if name == "weight_mass":
        return f"{_SHORT[name]} {1000 * v:.1f} g"
    if name == "alpha":
        return f"α {math.degrees(v):.2f}°"
    return f"ω {v:.3f} rad/s"


def plot_side_radii(radii, ax=None):
    """A :class:`~throwmap.design.radii.SideRadii`: r_i per side as bars (cm; sides without one left empty).
    Returns the Figure."""
    plt = _plt()
    if ax is None:
        fig, ax = plt.subplots(figsize=(4.5, 3.2))
    else:
        fig = ax.figure
    sides = list(radii.r)
    vals = [100 * v if math.isfinite(v) else 0.0 for v in radii.r.values()]
    colors = side_colors(max(sides) + 1 if sides else 1)
    ax.bar(range(len(sides)), vals, color=[colors[s] for s in sides])
    for i, v in enumerate(radii.r.values()):
        ax.annotate(f"{100 * v:.2f}" if math.isfinite(v) else "none", (i, vals[i]), xytext=(0, 3),
                    textcoords="offset points", ha="center", fontsize=7)
    ax.set_xticks(range(len(sides)), [f"side {s}" for s in sides])
    ax.set_ylabel("r_i (cm)")
    ax.set_title(f"r_i at ω = {radii.omega:g} rad/s ({radii.method})", fontsize=9)
    layout(fig)
    return fig
