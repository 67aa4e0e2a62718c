"""Funnel-graph figure: funnels in layers by priority, arrows from each spout to the mouths it lies in.

Draws a :class:`~throwmap.analysis.funnels.FunnelGraph` already computed by
:func:`~throwmap.analysis.funnels.funnels` (paper Sec. I-A); matplotlib is
imported on first use.
"""

from __future__ import annotations

from .style import _plt, layout, map_title, wrap_setting, x_range_text

__all__ = ["plot_funnel_graph"]


FUNNEL_KEY = ("key — mouth: the starts a funnel collects (its basin, % of the grid); spout: where it delivers "
              "them (its attractor); arrow i → j: i's spout lies in j's mouth (share of spout samples); priority k: "
              "its spout lies in the mouth of a priority k − 1 funnel (0: in the goal), so k switches of ω reach the goal")
"""The funnel graph's key, under the figure."""


def _omega_text(omegas) -> str:
    om = tuple(omegas or ())
    if not om:
        return ""
    return "ω = " + ", ".join(f"{w:g}" for w in om) + " rad/s"


def wrap_intervals(text: str, width: int = 40, sep: str = " ∪ ") -> list[str]:
    """Lines of at most ``width`` characters, broken only between the ``sep``-joined items.

    An item (e.g. ``"side 0: [50, 90] cm"``) is never split, so no line ends inside an
    interval; an item longer than ``width`` gets a line of its own.
    """
    lines: list[str] = []
    for item in str(text).split(sep):
        if lines and len(lines[-1]) + len(sep) + len(item) <= width:
            lines[-1] += sep + item
        else:
            lines.append(item)
    return lines


def _goal_text(goal) -> str:
    try:
        d = goal.describe("cm")
    except TypeError:
        d = goal.describe()
    return "goal\n" + "\n".join(wrap_intervals(str(d), 40))


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

    Returns
    -------
    Figure
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
        fig, ax = plt.subplots(figsize=(max(5.0, 2.9 * widest + 0.6), 1.6 * max(len(levels), 1) + 1.7))
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
    if fs:  # the key: the words of the draft's Sec. I-A, said once under the graph
        import textwrap

        key = FUNNEL_KEY + ("; dashed: spout inside the goal" if goal is not None else "")
        ax.text(0.5, -0.01, textwrap.fill(key, max(50, int(13 * fig.get_figwidth()))), transform=ax.transAxes,
                ha="center", va="top", fontsize=7, color="0.25", gid="key")
    order = [fs[i].name for i in sorted((i for i, r in rank.items() if r is not None),
                                         key=lambda i: (rank[i], -fs[i].mouth_fraction, i))]
    title = f"funnel graph: {len(fs)} funnel{'s' if len(fs) != 1 else ''}, {len(graph.edges)} edge" \
            f"{'s' if len(graph.edges) != 1 else ''} (spout → mouth)"
    if order:
        title += "\npriority: " + " > ".join(order)
    elif goal is not None:
        title += "\nno funnel leads to the goal"
    maps = dict(getattr(graph, "map_info", {}) or {}).get("maps", [])
    setting = map_title(maps, "")
    if setting:
        rng = x_range_text(maps)
        width = max(40, int(11 * fig.get_figwidth()))  # characters that fit at fontsize 9
        title = wrap_setting(f"{setting}{', ' + rng if rng else ''}", width) + "\n" + title
    ax.set_title(title, fontsize=9)
    layout(fig)
    return fig
