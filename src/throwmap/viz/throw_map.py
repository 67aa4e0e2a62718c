"""The throw-map figure: T(x) against x, one panel per side (paper Fig. 2 and its analogue for any map).

One plotter, :func:`plot_map`, draws :class:`~throwmap.throws.samples.MapSamples`
that the library has already computed (:func:`~throwmap.throws.samples.throw_map_samples`
for a part on an arm, :func:`~throwmap.throws.samples.sample_map` for any
configuration map); nothing here evaluates a map. Images are coloured by the side
they land on, escapes are ``x`` on the horizontal axis, the diagonal T(x) = x is
dashed, and r_i, l_i and the limit set S are marked when given. Matplotlib is
imported on first use; data are in m, axes in ``unit`` (``"cm"`` or ``"m"``).
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidStateError
from .limit_set import draw_wall_stops, system_suffix
from .style import _plt, layout, map_title, scale, side_colors, wrap_setting

__all__ = ["plot_map", "sampled_range"]


def sampled_range(samples, unit: str = "cm") -> str:
    """``"sampled for x ≤ 60 cm"``: the outer end of the x range a map was sampled (and, for
    the demo's limits, analysed) over, in ``unit``; each side starts at its own ``x_lo`` (its panel)."""
    hi = [float(v) for v in samples.x_hi if math.isfinite(float(v))]
    return f"sampled for x ≤ {scale(unit) * max(hi):.4g} {unit}" if hi else "x range ?"


def _draw_limit_set(ax, limit, s: int, k: float, colors, n_col: int, key) -> None:
    """S on side ``s`` shaded along x, S on every side as bars inside the T(x) axis, cycle points as dots."""
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


def _draw_critical(ax, critical, s: int, k: float, key) -> None:
    """r_i (red, dashed) and l_i (blue, dotted) as vertical lines, labelled at the top."""
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
        key("$l_i$: where S begins (inf S)", ls=":", color="tab:blue", lw=1.2)


def plot_map(samples, axes=None, *, critical=None, limit=None, unit: str = "cm", compact: bool = False,
             title: str | None = None):
    """T(x) against x, one panel per sampled side (paper Fig. 2; its analogue for any map).

    Parameters
    ----------
    samples : MapSamples
        From :func:`~throwmap.throws.samples.throw_map_samples` or
        :func:`~throwmap.throws.samples.sample_map` (x in m).
    axes : sequence of Axes, optional
        One per side of ``samples.sides``; else a new row of panels.
    critical : CriticalPoints, optional
        Vertical lines at r_i (red, dashed) and l_i (blue, dotted) on each side.
    limit : LimitSet, optional
        Its configurations on the panel's side shaded along the x axis, and those on
        every side as bars in that side's colour just inside the T(x) axis (a point
        lands in S when its colour meets a bar of the same colour at its height);
        cycle and fixed points as large dots at (x, next x).
    unit : str
        ``"cm"`` (default) or ``"m"``; the data are in m.
    compact : bool
        The paper's Fig. 2 look (:func:`throwmap.plot_throw_map`): 4.2 × 4 in panels and a
        legend in each panel naming each branch a jog, a flip or a tumble over and back (a landing on the
        panel's side beyond a flip from it, hollow). Otherwise
        (default) one legend sits below the panels (or in the last panel of a figure without constrained
        layout). Both span the sampled domain and every image.
    title : str, optional
        The figure's title; default names the part, h, ω and the model for a throw
        map (from ``samples.info``), else ``samples.label``.

    Returns
    -------
    Figure
    """
    from matplotlib.lines import Line2D

    plt = _plt()
    k = scale(unit)
    sides = list(samples.sides)
    if axes is None:
        if compact:
            fig, axes = plt.subplots(1, len(sides), figsize=(4.2 * len(sides), 4), squeeze=False)
        else:
            fig, axes = plt.subplots(1, len(sides), figsize=(4.3 * len(sides), 5.2), squeeze=False,
                                     layout="constrained")
        axes = axes[0]
    axes = list(np.atleast_1d(axes).ravel())
    if len(axes) < len(sides):
        raise InvalidStateError("axes", f"need one Axes per side ({len(sides)}), got {len(axes)}")
    fig = axes[0].figure
    xn, sn, ok_all = samples.x_next, samples.side_next, samples.ok
    n_col = max(sides + [int(v) for v in np.unique(sn[ok_all])]) + 1
    colors = side_colors(n_col)
    kinds = samples.kinds()
    lo_all = min([0.0] + list(samples.x_lo))
    hi_all = max(samples.x_hi)
    if np.any(ok_all):  # every image inside the axes
        hi_all = max(hi_all, float(np.max(xn[ok_all])))
        lo_all = min(lo_all, float(np.min(xn[ok_all])))
    lim = (lo_all * k, hi_all * k)
    legend: dict = {}  # label -> handle, first panel that draws it

    for ax, s in zip(axes, sides):
        panel: dict = {}  # this panel's legend

        def key(label, **kw):
            h = legend.setdefault(label, Line2D([], [], **kw, label=label))
            panel.setdefault(label, h)

        sl = samples.panel(s)
        x, y, d, ok = samples.x[sl], xn[sl], sn[sl], ok_all[sl]
        kind = kinds[sl]
        if limit is not None:
            _draw_limit_set(ax, limit, s, k, colors, n_col, key)
        for dest in np.unique(d[ok]):
            m = ok & (d == dest)
            tumble = m & (kind == "tumble")  # on its own side again, beyond a flip: over and back, not a jog
            m = m & ~tumble
            ax.scatter(x[m] * k, y[m] * k, s=3, color=colors[int(dest)], zorder=1 if compact else 3,
                       rasterized=not compact, gid=f"branch-{int(dest)}")
            what = f"→ side {int(dest)} ({'jog' if dest == s else 'flip'})" if compact else f"lands on side {int(dest)}"
            if np.any(m):
                key(what, ls="none", marker="o", ms=5 if compact else 4, color=colors[int(dest)])
            if np.any(tumble):
                ax.scatter(x[tumble] * k, y[tumble] * k, s=10, marker="o", facecolors="none",
                           edgecolors=colors[int(dest)], linewidths=0.8, zorder=1 if compact else 3,
                           rasterized=not compact, gid=f"tumble-{int(dest)}")
                key(f"→ side {int(dest)}, tumbled over and back", ls="none", marker="o", ms=5, mfc="none",
                    color=colors[int(dest)])
        if np.any(~ok):
            ax.scatter(x[~ok] * k, np.full(int(np.sum(~ok)), lim[0]), marker="x", s=8, color="k",
                       zorder=1 if compact else 3, clip_on=compact, gid="escapes")  # compact: the Fig. 2 look
            key("escapes (off the arm / no rest)", ls="none", marker="x", ms=5, color="k")
        ax.plot(lim, lim, "--", color="0.5", lw=0.8, zorder=2)
        key("T(x) = x", ls="--", color="0.5", lw=0.8)
        if draw_wall_stops(ax, samples.info, k, lambda side, s=s: 0.0 if side == s else None, horizontal=True):
            key("wall: a jog stops at length − u_R", color="0.25", lw=2.5, alpha=0.5)
        if critical is not None:
            _draw_critical(ax, critical, s, k, key)
        ax.set_xlim(lim)
        ax.set_ylim(lim)
        ax.set_aspect("equal")
        ax.set_xlabel(f"x on side {s} ({unit})")
        ax.set_ylabel(f"T(x) ({unit})")
        ax.set_title(f"side {s}")
        if compact:
            ax.legend(handles=list(panel.values()), loc="upper left", fontsize=7)
    if title is None:
        setting = map_title(samples.info, "")
        setting += system_suffix(samples.info) if setting else ""
        title = f"throw map T(x): {setting}" if setting else str(samples.label)
        title = wrap_setting(f"{title}, {sampled_range(samples, unit)}", 150 if compact else 120)
    fig.suptitle(title, **({} if compact else {"fontsize": 10}))
    if not compact:
        handles = sorted(legend.values(), key=lambda h: not h.get_label().startswith("lands on"))  # stable
        engine = fig.get_layout_engine()
        if engine is not None and type(engine).__name__ == "ConstrainedLayoutEngine":
            fig.legend(handles=handles, loc="outside lower center", ncol=min(4, len(handles)), fontsize=7,
                       frameon=False)
        else:
            axes[len(sides) - 1].legend(handles=handles, loc="upper left", fontsize=7, framealpha=0.85)
    layout(fig)
    return fig
