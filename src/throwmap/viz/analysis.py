"""Figures of the analysis objects: limit sets (paper Fig. 5), maps (Fig. 2), basins, funnel graphs.

Matplotlib is imported on first use (through :func:`throwmap.viz.plotting._plt`), so
importing this module does not load it. Every function takes an optional
``ax``/``axes`` and returns the matplotlib Figure. Data are in metres; axes are
labelled in ``unit`` (``"cm"``, the default, or ``"m"``). Nothing here computes
physics: the objects carry their results, and :func:`plot_map` only evaluates the
map it is given.

``plot_limit_set``    one horizontal lane per side along the arm (joint at 0): the
                      attractors as bars (bands) and dots (cycles), r_i and l_i,
                      and the last throws of an orbit as arrows (paper Fig. 5).
``plot_map``          T(x) against x, one panel per side, coloured by landing side,
                      with the diagonal, r_i, l_i and the limit set (paper Fig. 2).
``plot_basins``       the basin map: attractor label by colour, throws to reach it
                      by shade, binned so that 10⁶ configurations draw quickly.
``plot_funnel_graph`` funnels in layers by priority under the goal, arrows from each
                      spout to the mouths it lies in (paper Sec. I-A).
"""

from __future__ import annotations

import math
import textwrap

import numpy as np

from ..errors import InvalidStateError
from .plotting import _plt, side_colors

__all__ = ["plot_limit_set", "plot_map", "plot_basins", "plot_funnel_graph", "attractor_colors"]

ESCAPE_COLOR = (0.15, 0.15, 0.15, 1.0)
"""Colour of label −1 (no attractor on the arm) in basin maps."""

_UNITS = {"cm": 100.0, "m": 1.0}


def _scale(unit: str) -> float:
    """Axis units per metre."""
    if unit not in _UNITS:
        raise InvalidStateError("unit", f"must be one of {sorted(_UNITS)}, got {unit!r}")
    return _UNITS[unit]


def _layout(fig):
    """tight_layout unless the figure already has a layout engine (e.g. constrained)."""
    if fig.get_layout_engine() is None:
        fig.tight_layout()


def attractor_colors(n: int) -> list:
    """One colour per attractor id 1…n (Set1 without its grey, then Dark2), distinct from :data:`ESCAPE_COLOR`."""
    plt = _plt()
    base = [plt.get_cmap("Set1")(k) for k in (0, 1, 2, 3, 4, 6, 7)] + [plt.get_cmap("Dark2")(k) for k in range(8)]
    return [base[k % len(base)] for k in range(n)]


def _fmt_share(d: dict) -> str:
    return ", ".join(f"{k} {100 * v:.1f} %" for k, v in d.items())


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


# --------------------------------------------------------------------------------------------
# Fig. 5 analogue
# --------------------------------------------------------------------------------------------


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

    Returns the Figure. A limit set with no attractor (every orbit escapes) still
    draws its lanes, with a note saying where the orbits went.
    """
    from matplotlib.lines import Line2D

    plt = _plt()
    k = _scale(unit)
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
    if orbit is not None and np.size(orbit.x):
        xs += [float(v) for v in np.asarray(orbit.x) if math.isfinite(v)]
    x_hi = max(xs)
    handles = []

    # lanes: the arm from the joint to the end of the domain
    for s in sides:
        ax.hlines(lane[s], 0.0, x_hi * k, color="0.82", lw=1.0, zorder=0)
    ax.axvline(0.0, color="0.3", lw=1.2, zorder=0)
    ax.text(0.0, 1.0, " joint", transform=ax.get_xaxis_transform(), va="top", ha="left", fontsize=7, color="0.3")

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
                       label="$l_i$ = inf S")
            handles.append(Line2D([], [], ls="none", marker="^", color="tab:blue", label="$l_i$ = inf S"))

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
                              label="−1 (escaped): " + _fmt_share(limit.escapes) + "\nof starts"))
    if not limit.attractors:
        msg = "no attractor on the arm: every orbit escapes"
        if limit.escapes:
            msg += "\n(" + _fmt_share(limit.escapes) + " of starts)"
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
    label = limit.map_info.get("label", "map")
    n_att_txt = f"{len(limit.attractors)} attractor{'s' if len(limit.attractors) != 1 else ''}"
    ax.set_title(f"{label}\nlimit set: {limit.kind}, {n_att_txt} from {limit.n_starts} starts", fontsize=10)
    if handles:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=7, frameon=False)
    _layout(fig)
    return fig


# --------------------------------------------------------------------------------------------
# Fig. 2 analogue
# --------------------------------------------------------------------------------------------


def plot_map(cmap, axes=None, *, critical=None, limit=None, n: int = 1500, unit: str = "cm"):
    """T(x) against x for any configuration map, one panel per side (paper Fig. 2 analogue).

    Each panel evaluates ``cmap`` at ``n`` points of its side's domain
    ``(x_lo, x_hi]``; images are coloured by the side they land on, escapes are
    ``x`` on the horizontal axis, and the diagonal T(x) = x is dashed.

    Parameters
    ----------
    cmap : ConfigMap
        Any configuration map (:class:`~throwmap.analysis.maps.ThrowMap`,
        :class:`~throwmap.analysis.maps.FunctionMap`, …).
    axes : sequence of Axes, optional
        One per side of ``cmap.sides``; else a new row of panels.
    critical : CriticalPoints, optional
        Vertical lines at r_i (red, dashed) and l_i (blue, dotted) on each side.
    limit : LimitSet, optional
        Its configurations on the panel's side shaded along the x axis, and those on
        every side as bars in that side's colour just inside the T(x) axis (a point
        lands in S when its colour meets a bar of the same colour at its height);
        cycle and fixed points as large dots at (x, next x).
    n : int
        Points per side (≥ 2).
    unit : str
        ``"cm"`` (default) or ``"m"``; the map's data are in m.

    Returns the Figure.
    """
    from matplotlib.lines import Line2D

    plt = _plt()
    k = _scale(unit)
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
        raise InvalidStateError("n", f"must be an integer ≥ 2, got {n!r}")
    sides = [int(s) for s in cmap.sides]
    if axes is None:
        fig, axes = plt.subplots(1, len(sides), figsize=(4.3 * len(sides), 5.2), squeeze=False,
                                 layout="constrained")
        axes = axes[0]
    axes = list(np.atleast_1d(axes).ravel())
    if len(axes) < len(sides):
        raise InvalidStateError("axes", f"need one Axes per side ({len(sides)}), got {len(axes)}")
    fig = axes[0].figure
    # evaluate every side in one batch
    xs = {s: np.linspace(cmap.x_lo[s], cmap.x_hi[s], int(n) + 1)[1:] for s in sides}
    X = np.concatenate([xs[s] for s in sides])
    S = np.concatenate([np.full(int(n), s, dtype=np.int64) for s in sides])
    xn, sn, st = cmap(X, S)
    ok_all = st == 0
    n_col = max(sides + [int(v) for v in np.unique(sn[ok_all])]) + 1
    colors = side_colors(n_col)
    lo_all = min(0.0, min(cmap.x_lo[s] for s in sides))
    hi_all = max(cmap.x_hi[s] for s in sides)
    if np.any(ok_all):
        hi_all = max(hi_all, float(np.max(xn[ok_all])))
        lo_all = min(lo_all, float(np.min(xn[ok_all])))
    lim = (lo_all * k, hi_all * k)
    legend: dict = {}  # label -> handle, first panel that draws it

    def key(label, **kw):
        legend.setdefault(label, Line2D([], [], **kw, label=label))

    for idx, (ax, s) in enumerate(zip(axes, sides)):
        sl = slice(idx * int(n), (idx + 1) * int(n))
        x, y, d, ok = xs[s], xn[sl], sn[sl], ok_all[sl]
        if limit is not None:
            for a in limit.attractors:
                for bs, blo, bhi in a.bands:
                    bs = int(bs)
                    if bs == s and bhi > blo:
                        ax.axvspan(blo * k, bhi * k, color=colors[s], alpha=0.12, lw=0, zorder=0)
                    if bs < n_col:  # S on side bs, as a bar just inside the T(x) axis
                        xa = 0.012 + 0.014 * bs
                        if bhi > blo:
                            ax.vlines(xa, blo * k, bhi * k, transform=ax.get_yaxis_transform(), color=colors[bs],
                                      lw=3, alpha=0.8, zorder=1)
                        else:
                            ax.plot([xa], [blo * k], transform=ax.get_yaxis_transform(), marker="_", ms=7,
                                    mew=2, color=colors[bs], zorder=1)
                if a.kind != "band":
                    p = len(a.points)
                    for q, (ps, px) in enumerate(a.points):
                        if int(ps) != s:
                            continue
                        nx = a.points[(q + 1) % p][1]
                        nside = int(a.points[(q + 1) % p][0])
                        ax.scatter([px * k], [nx * k], s=80, color=colors[nside], edgecolors="k", linewidths=1.2,
                                   zorder=5, gid=f"attractor-{a.id}")
                        key(f"#{a.id} {'fixed point' if p == 1 else f'period-{p} cycle'}: (x, next x)",
                            ls="none", marker="o", ms=7, mfc="0.6", mec="k")
            if limit.attractors:
                key("limit set S (shaded: on this side; bars: on each side)", color="0.6", lw=4)
        for dest in np.unique(d[ok]):
            m = ok & (d == dest)
            ax.scatter(x[m] * k, y[m] * k, s=3, color=colors[int(dest)], zorder=3, rasterized=True,
                       gid=f"branch-{int(dest)}")
            key(f"lands on side {int(dest)}", ls="none", marker="o", ms=4, color=colors[int(dest)])
        if np.any(~ok):
            ax.scatter(x[~ok] * k, np.full(int(np.sum(~ok)), lim[0]), marker="x", s=8, color="k", zorder=3,
                       clip_on=False, gid="escapes")
            key("escapes (off the arm / no rest)", ls="none", marker="x", ms=5, color="k")
        ax.plot(lim, lim, "--", color="0.5", lw=0.8, zorder=2)
        key("T(x) = x", ls="--", color="0.5", lw=0.8)
        if critical is not None:
            r, l = critical.r.get(s, math.nan), critical.l.get(s, math.nan)
            if math.isfinite(r):
                ax.axvline(r * k, color="tab:red", ls="--", lw=1.0, gid="critical-r")
                ax.annotate(f"$r_{{{s}}}$", (r * k, 1.0), xycoords=ax.get_xaxis_transform(), xytext=(2, -2),
                            textcoords="offset points", color="tab:red", ha="left", va="top", fontsize=9)
                key("$r_i$: jogs end", ls="--", color="tab:red", lw=1.0)
            if math.isfinite(l):
                ax.axvline(l * k, color="tab:blue", ls=":", lw=1.2, gid="critical-l")
                ax.annotate(f"$l_{{{s}}}$", (l * k, 1.0), xycoords=ax.get_xaxis_transform(), xytext=(2, -14),
                            textcoords="offset points", color="tab:blue", ha="left", va="top", fontsize=9)
                key("$l_i$ = inf S", ls=":", color="tab:blue", lw=1.2)
        ax.set_xlim(lim)
        ax.set_ylim(lim)
        ax.set_aspect("equal")
        ax.set_xlabel(f"x on side {s} ({unit})")
        ax.set_ylabel(f"T(x) ({unit})")
        ax.set_title(f"side {s}")
    fig.suptitle(cmap.label, fontsize=10)
    handles = sorted(legend.values(), key=lambda h: not h.get_label().startswith("lands on"))  # stable
    if fig.get_layout_engine() is not None and type(fig.get_layout_engine()).__name__ == "ConstrainedLayoutEngine":
        fig.legend(handles=handles, loc="outside lower center", ncol=min(4, len(handles)), fontsize=7,
                   frameon=False)
    else:
        axes[len(sides) - 1].legend(handles=handles, loc="upper left", fontsize=7, framealpha=0.85)
    _layout(fig)
    return fig


# --------------------------------------------------------------------------------------------
# basins
# --------------------------------------------------------------------------------------------


def _bin_lane(x, labels, throws, edges, label_values):
    """Mode label index and mean throws per column; ``count`` 0 marks an empty column."""
    n_col = edges.size - 1
    col = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, n_col - 1)
    li = np.searchsorted(label_values, labels)
    n_lab = label_values.size
    counts = np.bincount(col * n_lab + li, minlength=n_col * n_lab).reshape(n_col, n_lab)
    total = counts.sum(axis=1)
    mode = np.argmax(counts, axis=1)
    mean_t = np.bincount(col, weights=throws.astype(float), minlength=n_col) / np.maximum(total, 1)
    return mode, mean_t, total


def plot_basins(basins, ax=None, *, unit: str = "cm", max_columns: int = 2000):
    """The basin map: one lane per side, x along the arm, colour = attractor, shade = throws to reach it.

    Each lane is binned into at most ``max_columns`` columns of equal width in x;
    a column shows its most common label (attractor ``#id`` in its own colour,
    −1 — no attractor on the arm — in near-black) and is blended with white by
    log(1 + mean throws to reach it) relative to the largest, so the attractor
    itself (0 throws) is fully saturated and the slowest configurations palest.
    Drawn as one image per lane, so 10⁶ configurations draw in well under a second.

    Parameters
    ----------
    basins : Basins
        From :func:`~throwmap.analysis.basins.basins` (flat arrays, m).
    ax : Axes, optional
    unit : str
        ``"cm"`` (default) or ``"m"`` for the x axis.
    max_columns : int
        Most columns per lane (≥ 1).

    Returns the Figure (with a colour bar for the shade; the title carries the
    certificate's statement, shortened).
    """
    from matplotlib.colors import LinearSegmentedColormap, Normalize
    from matplotlib.cm import ScalarMappable
    from matplotlib.patches import Patch

    plt = _plt()
    k = _scale(unit)
    if isinstance(max_columns, bool) or not isinstance(max_columns, (int, np.integer)) or max_columns < 1:
        raise InvalidStateError("max_columns", f"must be a positive integer, got {max_columns!r}")
    x = np.asarray(basins.x, dtype=float)
    side = np.asarray(basins.side)
    labels = np.asarray(basins.labels)
    throws = np.asarray(basins.throws)
    sides = [int(s) for s in np.unique(side)] if side.size else []
    if ax is None:
        fig, ax = plt.subplots(figsize=(10, 1.0 * max(len(sides), 1) + 2.2))
    fig = ax.figure
    label_values = np.unique(labels) if labels.size else np.zeros(0, dtype=np.int64)
    ids = [a.id for a in basins.attractors]
    palette = dict(zip(ids, attractor_colors(len(ids))))
    extra = [int(v) for v in label_values if int(v) not in palette and int(v) != -1]
    palette.update(zip(extra, attractor_colors(len(ids) + len(extra))[len(ids):]))
    palette[-1] = ESCAPE_COLOR
    lut = np.array([palette[int(v)] for v in label_values]).reshape(-1, 4)
    t_max = float(throws.max()) if throws.size else 0.0
    t_norm = math.log1p(t_max) if t_max > 0 else 1.0
    fade = 0.8  # share of white at the largest throw count

    x_lo = float(x.min()) if x.size else 0.0
    x_hi = float(x.max()) if x.size else 1.0
    span = max(x_hi - x_lo, 1e-12)
    # columns no narrower than the coarsest lane's spacing, so no column inside a lane is empty
    n_col = int(max_columns)
    for s in sides:
        xs = x[side == s]
        if xs.size > 1:
            lane_span = float(xs.max() - xs.min())
            step = lane_span / (xs.size - 1)
            if step > 0:  # 1 % wider than the spacing: no column inside the lane falls between two points
                n_col = min(n_col, max(1, int(span / (1.01 * step))))
    edges = np.linspace(x_lo, x_hi, n_col + 1)
    edges[-1] = np.nextafter(x_hi, np.inf)
    for i, s in enumerate(sides):
        m = side == s
        mode, mean_t, total = _bin_lane(x[m], labels[m], throws[m], edges, label_values)
        rgba = lut[mode].copy()
        w = fade * np.log1p(mean_t) / t_norm
        rgba[:, :3] = rgba[:, :3] * (1 - w[:, None]) + w[:, None]
        rgba[:, 3] = np.where(total > 0, 1.0, 0.0)
        img = ax.imshow(rgba[None, :, :], extent=(edges[0] * k, edges[-1] * k, i - 0.38, i + 0.38),
                        origin="lower", aspect="auto", interpolation="nearest", zorder=2)
        img.set_gid(f"basin-side-{s}")
    ax.set_yticks(range(len(sides)))
    ax.set_yticklabels([f"side {s}" for s in sides])
    scol = side_colors(max(sides) + 1 if sides else 1)
    for lab, s in zip(ax.get_yticklabels(), sides):
        lab.set_color(scol[s])
    ax.set_ylim(-0.6, len(sides) - 0.4)
    ax.set_xlim(edges[0] * k, edges[-1] * k)
    ax.set_xlabel(f"x of CM along the arm ({unit})")

    frac = basins.fractions if hasattr(basins, "fractions") else {}
    handles = []
    for a in basins.attractors:
        handles.append(Patch(color=palette[a.id], label=f"#{a.id} {a.kind} ({100 * frac.get(a.id, 0.0):.1f} %)"))
    for v in extra:
        handles.append(Patch(color=palette[v], label=f"#{v} ({100 * frac.get(v, 0.0):.1f} %)"))
    if np.any(label_values == -1):
        esc = getattr(basins, "escapes", {}) or {}
        detail = f" ({_fmt_share(esc)})" if esc else f" ({100 * frac.get(-1, 0.0):.1f} %)"
        handles.append(Patch(color=ESCAPE_COLOR, label="−1: escapes" + detail))
    if handles:
        ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(0.0, -0.2 if len(sides) < 3 else -0.15),
                  ncol=min(3, len(handles)), fontsize=7, frameon=False)
    # the shade scale, on a neutral grey
    grey = np.array([0.35, 0.35, 0.35])
    shade = LinearSegmentedColormap.from_list("throws", [tuple(grey), tuple(grey * (1 - fade) + fade)])
    sm = ScalarMappable(norm=Normalize(0.0, t_norm), cmap=shade)
    cb = fig.colorbar(sm, ax=ax, pad=0.01, fraction=0.04)
    ticks = [v for v in (0, 1, 3, 10, 30, 100, 300, 1000, 3000, 10000) if v <= max(t_max, 1)]
    cb.set_ticks([math.log1p(v) for v in ticks])
    cb.set_ticklabels([str(v) for v in ticks])
    cb.set_label("throws to reach", fontsize=8)
    cb.ax.tick_params(labelsize=7)

    label = basins.map_info.get("label", "map")
    statement = textwrap.shorten(str(basins.certificate.statement), width=120, placeholder=" …")
    ax.set_title(f"basins: {label} — {x.size} configurations\n{statement}", fontsize=9)
    _layout(fig)
    return fig


# --------------------------------------------------------------------------------------------
# funnel graph
# --------------------------------------------------------------------------------------------


def _omega_text(omegas) -> str:
    om = tuple(omegas or ())
    if not om:
        return ""
    return "ω = " + ", ".join(f"{w:g}" for w in om) + " rad/s"


def _goal_text(goal) -> str:
    try:
        d = goal.describe("cm")
    except TypeError:
        d = goal.describe()
    return "goal\n" + "\n".join(textwrap.wrap(str(d), 40))


def plot_funnel_graph(graph, ax=None):
    """Funnels in layers by priority, with arrows from each spout to the mouths it lies in (paper Sec. I-A).

    The goal (if any) is the box at the top; priority-0 funnels (spout inside the
    goal) sit below it with a dashed arrow up to it, priority-1 funnels below them,
    and so on; funnels that do not lead to the goal are the bottom row (grey). Each
    box names the funnel, its ω (rad/s), its attractor's kind and its mouth's share
    of the grid. An arrow i → j means funnel i's spout lies in funnel j's mouth and
    is labelled with the share of spout samples inside.

    Parameters
    ----------
    graph : FunnelGraph
        From :func:`~throwmap.analysis.funnels.funnels` (any object with ``funnels``,
        ``edges``, ``goal`` and ``rank`` as there).
    ax : Axes, optional

    Returns the Figure.
    """
    from matplotlib.patches import FancyArrowPatch, FancyBboxPatch

    plt = _plt()
    fs = tuple(graph.funnels)
    rank = {int(i): (None if r is None else int(r)) for i, r in dict(graph.rank).items()}
    goal = graph.goal
    ranked = sorted({r for r in rank.values() if r is not None})
    max_rank = max(ranked) if ranked else -1
    layers: dict[int, list[int]] = {}
    for i in range(len(fs)):
        r = rank.get(i)
        level = (r + 1) if r is not None else (max_rank + 2)
        layers.setdefault(level, []).append(i)
    for level in layers:
        layers[level].sort(key=lambda i: (-fs[i].mouth_fraction, i))
    if goal is not None:
        layers[0] = []
    levels = sorted(layers)
    widest = max([len(v) for v in layers.values()] + [1])
    if ax is None:
        fig, ax = plt.subplots(figsize=(max(5.0, 2.9 * widest + 0.6), 1.6 * max(len(levels), 1) + 1.2))
    fig = ax.figure
    bw, bh, sx = 0.86, 0.62, 1.3  # box size and spacing of neighbours in a layer, data units (layers 1 apart)
    pos: dict = {}
    boxes: dict = {}
    row = {lv: n for n, lv in enumerate(levels)}
    for lv in levels:
        members = layers[lv]
        for q, i in enumerate(members):
            pos[i] = (sx * (q - (len(members) - 1) / 2), -float(row[lv]))
    # the goal
    if goal is not None:
        gx, gy = 0.0, -float(row[0])
        gw = min(max(bw, sx * 0.8 * widest), 2.6)
        box = FancyBboxPatch((gx - gw / 2, gy - bh / 2), gw, bh, boxstyle="round,pad=0.02,rounding_size=0.08",
                             fc="#fff2b3", ec="#b38f00", lw=1.5, zorder=2, gid="goal")
        ax.add_patch(box)
        boxes["goal"] = box
        ax.text(gx, gy, _goal_text(goal), ha="center", va="center", fontsize=8, zorder=3)
    blues = plt.get_cmap("Blues")
    for i, f in enumerate(fs):
        x, y = pos[i]
        r = rank.get(i)
        fc = "0.92" if r is None else blues(0.45 - 0.3 * (r / max(1, max_rank)))
        box = FancyBboxPatch((x - bw / 2, y - bh / 2), bw, bh, boxstyle="round,pad=0.02,rounding_size=0.08",
                             fc=fc, ec="0.3" if r is not None else "0.6", lw=1.2, zorder=2, gid=f"funnel-{i}")
        ax.add_patch(box)
        boxes[i] = box
        kind = getattr(f.attractor, "kind", "?")
        lines = [str(f.name), ", ".join(v for v in (_omega_text(f.omegas), kind.replace("_", " ")) if v),
                 f"mouth {100 * f.mouth_fraction:.1f} %" + ("" if r is None else f" · priority {r}")]
        ax.text(x, y, "\n".join(lines), ha="center", va="center", fontsize=7.5, zorder=3)

    def arrow(a, b, label, *, style, color, rad):
        pa, pb = boxes[a].get_x() + boxes[a].get_width() / 2, boxes[b].get_x() + boxes[b].get_width() / 2
        ya, yb = boxes[a].get_y() + bh / 2, boxes[b].get_y() + bh / 2
        arr = FancyArrowPatch((pa, ya), (pb, yb), patchA=boxes[a], patchB=boxes[b], arrowstyle="-|>",
                              mutation_scale=12, connectionstyle=f"arc3,rad={rad}", color=color, ls=style, lw=1.2,
                              zorder=1, gid="edge")
        ax.add_patch(arr)
        # label at the middle of the bent path
        mx, my = (pa + pb) / 2, (ya + yb) / 2
        dx, dy = pb - pa, yb - ya
        lx, ly = mx + rad * dy / 2, my - rad * dx / 2
        ax.text(lx, ly, label, fontsize=7, ha="center", va="center", color=color, zorder=4,
                bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.9))

    for i, j, share in graph.edges:
        i, j = int(i), int(j)
        same = pos[i][1] == pos[j][1]
        rad = 0.35 if same else 0.12
        arrow(i, j, f"{100 * share:.0f} %", style="-", color="0.2", rad=rad)
    if goal is not None:
        for i, r in rank.items():
            if r == 0:
                arrow(i, "goal", "in goal", style="--", color="#8a6d00", rad=0.0)
    if not fs:
        ax.text(0.5, 0.5, "no funnels", transform=ax.transAxes, ha="center", va="center")
    half = max([abs(p[0]) for p in pos.values()] + [0.0]) + bw / 2 + 0.15
    if goal is not None:
        half = max(half, boxes["goal"].get_width() / 2 + 0.15)
    ax.set_xlim(-half, half)
    ax.set_ylim(-(len(levels) - 1) - bh / 2 - 0.25, bh / 2 + 0.25)
    ax.set_axis_off()
    order = [fs[i].name for i in sorted((i for i, r in rank.items() if r is not None),
                                         key=lambda i: (rank[i], -fs[i].mouth_fraction, i))]
    title = f"funnel graph: {len(fs)} funnel{'s' if len(fs) != 1 else ''}, {len(graph.edges)} edge" \
            f"{'s' if len(graph.edges) != 1 else ''} (spout → mouth)"
    if order:
        title += "\npriority: " + " > ".join(order)
    elif goal is not None:
        title += "\nno funnel leads to the goal"
    ax.set_title(title, fontsize=9)
    _layout(fig)
    return fig
