"""The bifurcation diagram of a continuation: attractors' x against the parameter by side, events marked, above the
basin fractions as stacked areas (:class:`~throwmap.analysis.continuation.Continuation`)."""

from __future__ import annotations

import math

import numpy as np

from .style import ESCAPE_COLOR, _plt, attractor_colors, layout, save_figure, scale, side_colors

__all__ = ["plot_continuation", "EVENT_LABELS"]

EVENT_LABELS = {"appear": "appears", "vanish": "vanishes", "merge": "merge", "split": "splits", "jump": "jumps",
                "period_doubling": "period doubling", "fold": "fold (multiplier +1)",
                "escape_onset": "escape begins", "escape_end": "escape ends"}
"""How each event kind is written on the figure."""
LABEL_PT = 7
"""Font size of the event labels, points."""


def plot_continuation(c, path=None, *, unit: str = "cm", fig=None):
    """Two panels sharing the parameter axis.

    Top: every attractor at every value evaluated — a band as a vertical bar over each of its intervals, a fixed
    point or cycle point as a dot — coloured by the side it rests on; r_i per side as a dashed line when the
    continuation has them; events as vertical lines, labelled. Bottom: the share of the starts ending on each
    attractor (by id, stacked), then those that escape (dark) and those unresolved at the horizon (grey).
    ``unit``: x in ``"cm"`` or ``"m"``. Saved to ``path`` when given; returns the Figure.
    """
    plt = _plt()
    k = scale(unit)
    if fig is None:
        fig = plt.figure(figsize=(9, 6.5))
    ax, ax2 = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 1.6]})
    pts = c.points
    sides = sorted({int(s) for p in pts for a in p.attractors for s in a.sides} | {int(s) for p in pts for s in p.r})
    colors = side_colors(max(sides) + 1 if sides else 1)
    values = np.array([p.value for p in pts])
    step = float(np.min(np.diff(values))) if len(values) > 1 else 1.0
    shown_sides = set()
    span = float(values[-1] - values[0]) or 1.0
    grid_step = float(np.min(np.diff(c.grid))) if len(c.grid) > 1 else span
    n_sides = max(1, len(sides))
    for p in pts:
        lw, alpha = (1.0, 0.45) if p.refined else (2.2, 0.85)  # values added while locating events: lighter
        for a in p.attractors:
            for s, lo, hi in a.bands:  # sides side by side around the value, so overlapping intervals stay visible
                dx = (sides.index(int(s)) - (n_sides - 1) / 2) * 0.22 * grid_step / n_sides if not p.refined else 0.0
                if a.kind == "band":
                    ax.plot([p.value + dx] * 2, [k * lo, k * hi], "-", color=colors[int(s)], lw=lw, alpha=alpha,
                            solid_capstyle="butt")
                else:
                    ax.plot(p.value + dx, k * lo, "o", color=colors[int(s)], ms=3.5 if not p.refined else 2)
                shown_sides.add(int(s))
    for s in sides:
        r = [(p.value, p.r.get(s, math.nan)) for p in pts if p.r]
        if r:
            rv = np.array(r, dtype=float)
            ax.plot(rv[:, 0], k * rv[:, 1], "--", color=colors[s], lw=0.9, label=f"r{s} (jogs end)")
    for s in sorted(shown_sides):
        ax.plot([], [], "-", color=colors[s], lw=3, label=f"rests on side {s}")
    ax.plot([], [], "-", color="0.5", lw=1, alpha=0.5, label="values added to locate events")
    ymax = ax.get_ylim()[1]
    # events closer than a label's line height (at the axes' width on the page) share one label
    width_pt = ax.get_position().width * fig.get_figwidth() * 72.0
    near = 1.6 * LABEL_PT / max(width_pt, 1.0) * span
    groups: list = []
    for e in sorted(c.events, key=lambda e: e.value):
        ax.axvline(e.value, color="0.35", lw=0.8, ls=":")
        ax2.axvline(e.value, color="0.35", lw=0.8, ls=":")
        text = EVENT_LABELS.get(e.kind, e.kind) + (f" #{e.ids[0]}" if e.ids else "")
        if groups and e.value - groups[-1][0] <= near:
            if text not in groups[-1][1]:
                groups[-1][1].append(text)
        else:
            groups.append([e.value, [text]])
    for at, texts in groups:
        ax.text(at, ymax, " " + ", ".join(texts), rotation=90, va="top", ha="right", fontsize=LABEL_PT, color="0.2",
                bbox=dict(facecolor="white", edgecolor="none", alpha=0.8, pad=0.3))  # readable over the bars
    u = f" ({c.unit})" if c.unit else ""
    ax.set_ylabel(f"attractor x ({unit})")
    ax.set_ylim(bottom=0)
    ax.legend(loc="upper right", fontsize=7, framealpha=0.85)
    sys_ = c.system
    if "part" in sys_:
        fixed = ", ".join(t for t in (
            f"h = {100 * sys_['h_m']:.3g} cm" if c.param != "h" else "",
            f"ω = {sys_['omega_rad_s']:g} rad/s" if c.param != "omega" and sys_.get("omega_rad_s") is not None else "",
            f"μ = {sys_['mu']}" if c.param != "mu" else "") if t)
        what = f"{sys_['part']}, {fixed}, model '{c.model}'"
    else:
        what = f"map family {sys_.get('family', '')}"
    r = c.range
    symbol = {"omega": "ω", "alpha": "α", "mu": "μ"}.get(c.param, c.param)
    ax.set_title(f"{what}\nattractors along {symbol}; {r['starts_per_side']} starts per side, {r['horizon_throws']} "
                 "throws each", fontsize=9)

    # basin fractions, stacked: attractors by id, then escapes and unresolved
    ids = c.ids
    acol = attractor_colors(max(ids) if ids else 1)
    layers = [np.array([sum(a.fraction for a in p.attractors if a.id == i) for p in pts]) for i in ids]
    layers.append(np.array([p.escape_fraction for p in pts]))
    layers.append(np.array([p.unresolved_fraction for p in pts]))
    colours = [acol[i - 1] for i in ids] + [ESCAPE_COLOR, (0.75, 0.75, 0.75, 1.0)]
    labels = [f"#{i}" for i in ids] + ["escape (behind the joint, off the end)", "unresolved at the horizon"]
    ax2.stackplot(values, *layers, colors=colours, labels=labels, step=None)
    ax2.set_ylim(0, 1)
    ax2.set_ylabel("share of starts")
    ax2.set_xlabel(f"{symbol}{u}")
    ax2.set_xlim(values[0] - 0.02 * step, values[-1] + 0.02 * step)
    ax2.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=7, framealpha=0.85)
    layout(fig)
    if path is not None:
        save_figure(fig, path)
    return fig
