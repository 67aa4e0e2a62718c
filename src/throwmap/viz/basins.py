"""Basin figure: attractor label by colour, throws to reach it by shade, one lane per side.

Draws a :class:`~throwmap.analysis.basins.Basins` already computed by
:func:`~throwmap.analysis.basins.basins`; the configurations are binned into
columns so that 10⁶ of them draw quickly. Matplotlib is imported on first use.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InvalidStateError
from .limit_set import draw_wall_stops, system_suffix
from .style import (
    ESCAPE_COLOR,
    _plt,
    attractor_colors,
    fmt_share,
    layout,
    map_title,
    scale,
    side_colors,
)

__all__ = ["basins_title", "plot_basins", "shade"]

FADE = 0.8
"""Share of white blended into a label's colour at the largest throw count."""


def shade(rgba, mean_throws, t_norm: float, fade: float = FADE) -> np.ndarray:
    """Colours of columns of one label: ``rgba`` blended with white by ``fade · log(1 + throws) / t_norm``.

    ``rgba`` is one colour ``(4,)`` or one per column ``(N, 4)``; ``mean_throws`` the
    throws to reach the attractor (one per column); ``t_norm = log(1 + largest throws)``.
    The lanes and the colour key both use this, so the key shows the lanes' colours.
    """
    base = np.broadcast_to(np.asarray(rgba, dtype=float), (np.size(mean_throws), 4)).copy()
    w = fade * np.log1p(np.asarray(mean_throws, dtype=float).ravel()) / t_norm
    base[:, :3] = base[:, :3] * (1 - w[:, None]) + w[:, None]
    return base


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

    Returns
    -------
    Figure
        The x axis starts at the joint (x = 0); a colour key beside it has one column per label
        drawn, faded by throws exactly as the lanes are (:func:`shade`), ticked in throws; the title
        names the part, h, ω, the model and the analysed range, and carries the certificate's
        statement, shortened.
    """
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import LinearSegmentedColormap, Normalize
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
        fig, ax = plt.subplots(figsize=(10, 1.0 * max(len(sides), 1) + 2.6))  # + room for a 4-line title
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
        rgba = shade(lut[mode], mean_t, t_norm)
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
    ax.set_xlim(min(0.0, edges[0]) * k, edges[-1] * k)  # from the joint, x = 0
    ax.axvline(0.0, color="0.3", lw=1.2, zorder=1, gid="joint")
    ax.set_xlabel(f"x of CM along the arm ({unit}; joint at 0)")

    frac = basins.fractions if hasattr(basins, "fractions") else {}
    handles = []
    row = {s: i for i, s in enumerate(sides)}
    draw_wall_stops(ax, basins.map_info, k, lambda s: row.get(s), handles)
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
    # the colour key: one column per label drawn, its colour faded exactly as in the lanes
    key_labels = [int(v) for v in label_values]
    key_rows = 256
    t_rows = np.expm1(np.linspace(0.0, t_norm, key_rows))  # throws at each row (log1p-spaced)
    key = np.stack([shade(palette[v], t_rows, t_norm) for v in key_labels], axis=1) if key_labels else \
        np.ones((key_rows, 1, 4))
    sm = ScalarMappable(norm=Normalize(0.0, t_norm), cmap=LinearSegmentedColormap.from_list("w", ["w", "w"]))
    cb = fig.colorbar(sm, ax=ax, pad=0.01, fraction=0.025 * max(1, len(key_labels)) + 0.015)
    cb.solids.set_visible(False)
    cb.ax.imshow(key, extent=(0.0, 1.0, 0.0, t_norm), origin="lower", aspect="auto", interpolation="nearest",
                 zorder=1).set_gid("basin-key")
    cb.ax.set_xlim(0.0, 1.0)
    n_key = max(1, len(key_labels))
    cb.ax.xaxis.set_visible(True)
    cb.ax.set_xticks([(j + 0.5) / n_key for j in range(len(key_labels))])
    cb.ax.set_xticklabels([f"#{v}" if v != -1 else "−1" for v in key_labels], fontsize=6)
    ticks = [v for v in (0, 1, 3, 10, 30, 100, 300, 1000, 3000, 10000) if v <= max(t_max, 1)]
    cb.set_ticks([math.log1p(v) for v in ticks])
    cb.set_ticklabels([str(v) for v in ticks])
    cb.set_label("throws to reach (colour: attractor)", fontsize=8)
    cb.ax.tick_params(labelsize=7)

    label = map_title(basins.map_info, basins.map_info.get("label", "map")) + system_suffix(basins.map_info)
    info = basins.map_info if isinstance(basins.map_info, dict) else {}
    ax.set_title(basins_title(label, x.size, info.get("x_max_m"), basins.certificate, unit), fontsize=8)
    layout(fig)
    return fig


def basins_title(label: str, n_configs: int, x_max_m, certificate, unit: str = "cm") -> str:
    """The basin map's title, two lines: ``basins: <setting>`` (as every figure names it, SI), then — in the axis'
    ``unit`` — the starts, the range analysed and what the certificate says in short — unique and globally attractive (all starts reach attractor #k
    within T throws), one attractor reached but not certified, or the attractors and escapes that share the grid
    (the whole statement is ``basins.certificate.statement``)."""
    k = scale(unit)
    where = f"{n_configs} starts" + ("" if x_max_m is None else f", x ≤ {float(x_max_m) * k:.4g} {unit}")
    c = certificate
    if not hasattr(c, "attractor"):  # a certificate known by its statement only
        say = str(getattr(c, "statement", c))
    elif c.attractor is not None and c.unique:
        say = f"unique and globally attractive at grid resolution: all reach #{c.attractor} within {c.max_throws_to_reach} throws"
    elif c.attractor is not None:
        say = f"all reach #{c.attractor} within {c.max_throws_to_reach} throws, not certified (see the certificate)"
    else:
        say = "not unique: " + str(c.statement).split("share the grid: ", 1)[-1]
    return f"basins: {label}\n{where}: {say}"