"""Basin figure: attractor label by colour, throws to reach it by shade, one lane per side.

Draws a :class:`~throwmap.analysis.basins.Basins` already computed by
:func:`~throwmap.analysis.basins.basins`; the configurations are binned into
columns so that 10⁶ of them draw quickly. Matplotlib is imported on first use.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np

from ..errors import InvalidStateError
from .style import ESCAPE_COLOR, _plt, attractor_colors, fmt_share, layout, scale, side_colors

__all__ = ["plot_basins"]


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
    k = scale(unit)
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
        detail = f" ({fmt_share(esc)})" if esc else f" ({100 * frac.get(-1, 0.0):.1f} %)"
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
    layout(fig)
    return fig
