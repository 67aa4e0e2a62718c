"""Limit-set figure: the forward limit set along the arm, one lane per side (paper Fig. 5 analogue).

Draws a :class:`~throwmap.analysis.limitset.LimitSet` (and optionally its
:class:`~throwmap.analysis.critical.CriticalPoints` and an orbit) that the analysis
has already computed; nothing here evaluates a map. The horizontal axis is x along
the arm (joint at 0) in ``unit`` (``"cm"``, the default, or ``"m"``; data in m):
attractors as bars (bands) and dots (cycles), r_i and l_i, and the last throws of
an orbit as arrows. Matplotlib is imported on first use.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidStateError
from .style import _plt, fmt_share, layout, map_title, scale, side_colors, x_range_text

__all__ = ["plot_limit_set", "wall_stops", "system_suffix", "draw_wall_stops"]


def wall_stops(map_info: dict) -> dict:
    """``{side: x*}`` (m): where a wall at the arm's end stops the CM on each side (x* = length − u_R, the
    domain's upper end); empty without a wall, or where ``x_max`` cut the domain short of it."""
    if not any(f.get("kind") == "wall" for f in (map_info or {}).get("fixtures") or ()):
        return {}
    x_max = float(map_info.get("x_max_m", math.inf))
    out = {}
    for s, (lo, hi) in ((map_info.get("domain_m") or {}).items()):
        if float(hi) < x_max:
            out[int(s)] = float(hi)
    return out


def system_suffix(map_info: dict) -> str:
    """``", α = 5°, wall 5 cm (μ 0)"`` for a figure title; empty on the paper's plain arm."""
    info = map_info or {}
    bits = [f"α = {math.degrees(float(info['alpha_rad'])):.3g}°"] if info.get("alpha_rad") else []
    for f in info.get("fixtures") or ():
        if f.get("kind") == "wall":
            mu = f.get("mu")
            bits.append(f"wall {100 * f['height_m']:.3g} cm ("
                        + ("arm μ" if mu == "arm" else "μ ∞" if mu is None else f"μ {mu:g}") + ")")
        elif f.get("kind") == "cavity":
            bits.append("cavity")
    return ", " + ", ".join(bits) if bits else ""


def draw_wall_stops(ax, map_info: dict, k: float, where, handles=None, *, horizontal: bool = False):
    """The wall, drawn where the arm is: a thick grey bar at each side's stop x* (``where(side)`` gives the
    lane's y, or None to draw across the axes; ``horizontal``: a line T = x* in a T(x) panel)."""
    from matplotlib.lines import Line2D

    stops = wall_stops(map_info)
    for s, x in stops.items():
        y = where(s)
        if y is None:
            continue
        if horizontal:
            ax.axhline(x * k, color="0.25", lw=2.5, alpha=0.5, zorder=0, gid="wall")
        elif y == "all":
            ax.axvline(x * k, color="0.25", lw=3, alpha=0.6, zorder=1, gid="wall")
        else:
            ax.vlines(x * k, y - 0.38, y + 0.38, color="0.25", lw=3.5, alpha=0.75, zorder=1, gid="wall")
    if stops and handles is not None:
        handles.append(Line2D([], [], color="0.25", lw=3.5, alpha=0.75, label="wall: the CM stops at length − u_R"))
    return stops


def _attractor_line(a) -> str:
    """A short legend line for an attractor (no coordinates)."""
    if a.kind == "band":
        return f"#{a.id} band, λ = {a.lyapunov:+.3f}/throw"
    st = {True: "stable", False: "unstable", None: "?"}[a.stable]
    name = "fixed point" if a.kind == "fixed_point" else f"period-{a.period} cycle"
    return f"#{a.id} {name}, multiplier {a.multiplier:+.3g} ({st})"


def _arc_arrow(ax, p0, p1, *, rad, color, alpha, lw=1.0, gid=None, zorder=4):
    """One arrow from p0 to p1 (data coordinates), bent by ``rad`` (matplotlib's arc3)."""
    from matplotlib.patches import FancyArrowPatch

    arr = FancyArrowPatch(p0, p1, connectionstyle=f"arc3,rad={rad}", arrowstyle="-|>", mutation_scale=9,
                          color=color, alpha=alpha, lw=lw, shrinkA=2, shrinkB=2, zorder=zorder)
    if gid is not None:
        arr.set_gid(gid)
    ax.add_patch(arr)
    return arr


def _throw_arrow(ax, x0, y0, x1, y1, *, color_jog, color_flip, alpha, gid):
    """A jog as an arc above its lane, a flip as a slightly bent arrow between lanes."""
    if y0 == y1:
        rad = -0.45 if x1 >= x0 else 0.45  # arc3 bends to the left of travel: keep every jog arc above the lane
        dark = tuple(0.55 * c for c in color_jog[:3])  # darker than the lane's bars, which it crosses
        return _arc_arrow(ax, (x0, y0), (x1, y1), rad=rad, color=dark, alpha=alpha, gid=gid)
    return _arc_arrow(ax, (x0, y0), (x1, y1), rad=0.08, color=color_flip, alpha=alpha, gid=gid)


def plot_limit_set(limit, ax=None, *, critical=None, orbit=None, unit: str = "cm", n_arrows: int = 30):
    """The forward limit set along the arm, one lane per side (paper Fig. 5 analogue).

    The horizontal axis is x along the arm (joint at 0, ``unit``); each stable side
    has a horizontal lane. Band attractors are thick bars in the side's colour (an
    interval of zero width as a short tick), cycle and fixed points are large dots,
    and a cycle's throws are drawn as arrows (jogs arc along the lane, flips cross
    lanes). Several attractors are offset slightly within a lane and labelled ``#id``.

    Parameters
    ----------
    limit : LimitSet
        From :func:`~throwmap.analysis.limitset.limit_set`.
    ax : matplotlib Axes, optional
        Drawn into if given, else a new figure.
    critical : CriticalPoints, optional
        Marks r_i (red ▼, where jogs end) and l_i (blue ▲, inf S) on each lane.
    orbit : Orbit, optional
        Its last ``n_arrows`` throws as arrows (older ones fainter); an escape as ``x``.
    unit : str
        ``"cm"`` (default) or ``"m"`` for the axis; the data are in m.
    n_arrows : int
        Throws of ``orbit`` drawn (≥ 0).

    Returns
    -------
    Figure
        A limit set with no attractor (every orbit escapes) still draws its lanes, with a note
        saying where the orbits went.
    """
    from matplotlib.lines import Line2D

    plt = _plt()
    k = scale(unit)
    if isinstance(n_arrows, bool) or not isinstance(n_arrows, (int, np.integer)) or n_arrows < 0:
        raise InvalidStateError("n_arrows", f"must be a non-negative integer, got {n_arrows!r}")
    sides = {int(s) for s in np.asarray(limit.starts_side).ravel()}
    for a in limit.attractors:
        sides.update(int(b[0]) for b in a.bands)
    if critical is not None:
        sides.update(int(s) for s in critical.sides)
    if orbit is not None:
        sides.update(int(s) for s in np.asarray(orbit.side).ravel())
    sides = sorted(sides)
    lane = {s: i for i, s in enumerate(sides)}
    colors = side_colors(max(sides) + 1 if sides else 1)
    if ax is None:
        fig, ax = plt.subplots(figsize=(10, 1.3 * max(len(sides), 1) + 1.9), layout="constrained")
    fig = ax.figure

    # extent of the arm shown: the starts span the analysed domain
    xs = [0.0]
    if np.size(limit.starts_x):
        xs.append(float(np.max(limit.starts_x)))
    xs += [b[2] for a in limit.attractors for b in a.bands]
    if critical is not None:
        xs += [v for d in (critical.r, critical.l) for v in d.values() if math.isfinite(v)]
    xs += list(wall_stops(limit.map_info).values())
    if orbit is not None and np.size(orbit.x):
        xs += [float(v) for v in np.asarray(orbit.x) if math.isfinite(v)]
    x_hi = max(xs)
    handles = []

    # lanes: the arm from the joint to the end of the domain
    for s in sides:
        ax.hlines(lane[s], 0.0, x_hi * k, color="0.82", lw=1.0, zorder=0)
    ax.axvline(0.0, color="0.3", lw=1.2, zorder=0)
    draw_wall_stops(ax, limit.map_info, k, lambda s: lane.get(s), handles)
    ax.annotate(" joint", (0.0, 1.0), xycoords=ax.get_xaxis_transform(), xytext=(0, -3), textcoords="offset points",
                va="top", ha="left", fontsize=7, color="0.3")

    # attractors
    n_att = len(limit.attractors)
    point_w = 0.004 * x_hi  # intervals narrower than this are drawn as ticks
    for j, a in enumerate(limit.attractors):
        dy = 0.0 if n_att == 1 else 0.24 * (j / (n_att - 1) - 0.5)  # spread within ±0.12 of the lane
        if a.kind == "band":
            wide = [b for b in a.bands if b[2] - b[1] >= point_w and b[0] in lane]
            thin = [b for b in a.bands if b[2] - b[1] < point_w and b[0] in lane]
            if wide:
                ax.hlines([lane[b[0]] + dy for b in wide], [b[1] * k for b in wide], [b[2] * k for b in wide],
                          colors=[colors[b[0]] for b in wide], lw=9, alpha=0.85, zorder=2, gid=f"attractor-{a.id}")
            if thin:
                ax.scatter([0.5 * (b[1] + b[2]) * k for b in thin], [lane[b[0]] + dy for b in thin], marker="|",
                           s=110, linewidths=2.5, color=[colors[b[0]] for b in thin], zorder=2,
                           gid=f"attractor-{a.id}")
            handles.append(Line2D([], [], color="0.45", lw=7, label=_attractor_line(a)
                                  + f"\n{100 * a.fraction:.0f} % of starts"))
        else:
            pts = [(int(s), float(x)) for s, x in a.points if int(s) in lane]
            ax.scatter([x * k for _, x in pts], [lane[s] + dy for s, _ in pts], s=90,
                       color=[colors[s] for s, _ in pts], edgecolors="k", linewidths=1.0, zorder=5,
                       gid=f"attractor-{a.id}")
            if len(pts) > 1 and orbit is None:
                for q in range(len(pts)):
                    (s0, x0), (s1, x1) = pts[q], pts[(q + 1) % len(pts)]
                    _throw_arrow(ax, x0 * k, lane[s0] + dy, x1 * k, lane[s1] + dy, color_jog=colors[s0],
                                 color_flip="0.25", alpha=0.9, gid="cycle")
            handles.append(Line2D([], [], ls="none", marker="o", ms=8, mfc="0.6", mec="k",
                                  label=_attractor_line(a) + f"\n{100 * a.fraction:.0f} % of starts"))
        if n_att > 1:
            s0 = a.bands[0][0] if a.bands else None
            if s0 in lane:
                ax.text(a.bands[0][1] * k, lane[s0] + dy + 0.1, f"#{a.id}", fontsize=7, ha="right", va="bottom")

    # critical points
    if critical is not None:
        rx, ry, lx, ly = [], [], [], []
        for s in critical.sides:
            s = int(s)
            r, l = critical.r.get(s, math.nan), critical.l.get(s, math.nan)
            if math.isfinite(r):
                rx.append(r * k)
                ry.append(lane[s])
                ax.vlines(r * k, lane[s] - 0.22, lane[s] + 0.22, color="tab:red", lw=1.2, zorder=3)
                ax.text(r * k, lane[s] + 0.3, f"$r_{{{s}}}$", color="tab:red", ha="center", va="bottom",
                        fontsize=9)
            if math.isfinite(l):
                lx.append(l * k)
                ly.append(lane[s])
                ax.vlines(l * k, lane[s] - 0.22, lane[s] + 0.22, color="tab:blue", lw=1.2, zorder=3)
                ax.text(l * k, lane[s] - 0.3, f"$l_{{{s}}}$", color="tab:blue", ha="center", va="top",
                        fontsize=9)
        if rx:
            ax.scatter(rx, np.asarray(ry) + 0.22, marker="v", s=40, color="tab:red", zorder=6, gid="critical-r",
                       label="$r_i$: jogs end")
            handles.append(Line2D([], [], ls="none", marker="v", color="tab:red", label="$r_i$: jogs end"))
        if lx:
            ax.scatter(lx, np.asarray(ly) - 0.22, marker="^", s=40, color="tab:blue", zorder=6, gid="critical-l",
                       label="$l_i$: where S begins (inf S)")
            handles.append(Line2D([], [], ls="none", marker="^", color="tab:blue",
                                  label="$l_i$: where S begins (inf S)"))

    # orbit
    if orbit is not None and n_arrows > 0:
        ox = np.asarray(orbit.x, dtype=float)
        osd = np.asarray(orbit.side).astype(int)
        n_ok = ox.size - 1  # completed throws
        first = max(0, n_ok - int(n_arrows))
        steps = range(first, n_ok)
        for q, t in enumerate(steps):
            alpha = 0.25 + 0.75 * (q + 1) / max(1, len(steps))
            _throw_arrow(ax, ox[t] * k, lane[osd[t]], ox[t + 1] * k, lane[osd[t + 1]], color_jog=colors[osd[t]],
                         color_flip="0.25", alpha=alpha, gid="orbit")
        if len(steps):
            handles.append(Line2D([], [], color="0.25", marker=">", ms=5,
                                  label=f"orbit: last {len(steps)} throws (jog arcs, flips across)"))
        if getattr(orbit, "escaped", False) or int(getattr(orbit, "status", 0)) != 0:
            last = orbit.outcomes[-1] if getattr(orbit, "outcomes", ()) else None
            xe = float(getattr(last, "x", math.nan)) if last is not None else math.nan
            xe = xe if math.isfinite(xe) else float(ox[-1])
            what = getattr(getattr(orbit, "status", None), "label", "escape")
            ax.scatter([xe * k], [lane[osd[-1]]], marker="x", s=80, color="k", linewidths=2, zorder=7, gid="escape")
            handles.append(Line2D([], [], ls="none", marker="x", color="k", mew=2, label=f"orbit escapes: {what}"))

    # escapes of the limit set
    if limit.escapes:
        handles.append(Line2D([], [], ls="none", marker="x", color="0.4",
                              label="−1 (escaped): " + fmt_share(limit.escapes) + "\nof starts"))
    if not limit.attractors:
        msg = "no attractor on the arm: every orbit escapes"
        if limit.escapes:
            msg += "\n(" + fmt_share(limit.escapes) + " of starts)"
        ax.text(0.5, 0.5, msg, transform=ax.transAxes, ha="center", va="center", fontsize=10,
                bbox=dict(boxstyle="round", fc="white", ec="0.5"), zorder=8)

    ax.set_yticks(range(len(sides)))
    ax.set_yticklabels([f"side {s}" for s in sides])
    for lab, s in zip(ax.get_yticklabels(), sides):
        lab.set_color(colors[s])
    ax.set_ylim(-0.75, len(sides) - 0.25)
    lo = min(xs + [0.0])
    ax.set_xlim(lo * k - 0.02 * x_hi * k, 1.03 * x_hi * k)
    ax.set_xlabel(f"x of CM along the arm ({unit}; joint at 0)")
    label = map_title(limit.map_info, limit.map_info.get("label", "map")) + system_suffix(limit.map_info)
    rng = x_range_text(limit.map_info)
    n_att_txt = f"{len(limit.attractors)} attractor{'s' if len(limit.attractors) != 1 else ''}"
    ax.set_title(f"{label}\nlimit set: {limit.kind}, {n_att_txt} from {limit.n_starts} starts"
                 + (f", {rng}" if rng else ""), fontsize=10)
    if handles:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=False)
    layout(fig)
    return fig
