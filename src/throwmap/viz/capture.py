"""The captured part: a frame of the part at rest in the cavity at the arm's end (paper Fig. 9(b)).

Draws, in the arm frame (cm): the arm's surface from the joint to its end with the cavity
(:func:`throwmap.system.fixtures.surface_profile`) and the arm's body under it, the end wall,
the part at its pose — filled, each side in its colour with its number, the CM as a dot —
and the design's numbers (L, lip, depth, floor, wall height) as labels. matplotlib is imported
on call.
"""

from __future__ import annotations

import numpy as np

__all__ = ["plot_capture"]


def plot_capture(design, ax=None, path=None, pose=None, title: str | None = None):
    """Draw ``design`` (a :class:`~throwmap.design.cavity.CavityDesign`) with its part at ``pose``
    (arm frame (x, y, φ), m, rad; default the engine's ``captured_pose``, else the part resting
    on the target side against the end wall). Returns the Figure (saved to ``path`` if given)."""
    import matplotlib

    if ax is None and path is not None:
        matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon

    from ..system.fixtures import surface_profile
    from ..system.pose import pose_against_wall, world_vertices
    from .style import side_colors

    d, part, k = design, design.part, design.side
    what = "at rest on side" if pose is not None else "captured on side"
    if pose is None:
        pose = d.captured_pose
    if pose is None:
        what = "designed rest (no engine capture) on side"
        gap = d.numbers.get("end_gap_m", 0.0)
        pose = pose_against_wall(part, d.floor_y, d.length - gap, k)
    fig = None
    if ax is None:
        fig, ax = plt.subplots(figsize=(8.0, 4.2))
    else:
        fig = ax.figure
    cm = 100.0
    h, L = d.arm.h, d.length
    prof = surface_profile(h, L, d.fixtures)
    bottom = min(prof[:, 1].min(), h) - 0.02
    body = np.vstack((prof, [[L, bottom], [0.0, bottom]]))
    ax.add_patch(Polygon(body * cm, closed=True, facecolor="0.85", edgecolor="0.3", lw=1.0))
    w = d.wall
    ax.add_patch(Polygon(np.array([[L, bottom], [L + w.thickness, bottom], [L + w.thickness, h + w.height],
                                   [L, h + w.height]]) * cm, closed=True, facecolor="0.6", edgecolor="0.2", lw=1.0))
    V = world_vertices(part, pose)
    ax.add_patch(Polygon(V * cm, closed=True, facecolor="#cfe3f7", edgecolor="none", alpha=0.9))
    colors = side_colors(part.n_sides)
    for s in range(part.n_sides):
        a, b = V[s], V[(s + 1) % part.n_sides]
        ax.plot([a[0] * cm, b[0] * cm], [a[1] * cm, b[1] * cm], color=colors[s], lw=2.5)
        mid = 0.5 * (a + b)
        c = V.mean(axis=0)
        lab = mid + 0.012 * (mid - c) / max(np.linalg.norm(mid - c), 1e-9)
        ax.text(lab[0] * cm, lab[1] * cm, str(s), color=colors[s], ha="center", va="center", fontsize=9,
                fontweight="bold")
    ax.plot([pose[0] * cm], [pose[1] * cm], "ko", ms=4)
    n = d.numbers
    y_ann = (h + w.height) * cm + 1.0
    ax.annotate("", xy=(d.lip_x * cm, y_ann), xytext=(L * cm, y_ann),
                arrowprops={"arrowstyle": "<->", "color": "0.3", "lw": 0.8})
    ax.plot([d.lip_x * cm] * 2, [h * cm, y_ann], ":", color="0.5", lw=0.8)
    ax.text(0.5 * (d.lip_x + L) * cm, y_ann + 0.3, f"cavity {100 * d.cavity.span:.1f} cm: floor {100 * n['floor_m']:.1f} cm, "
            f"depth {100 * d.cavity.depth:.1f} cm", ha="center", va="bottom", fontsize=8, color="0.25")
    ax.text(L * cm + 1.3, (h + w.height) * cm, f"end wall\n{100 * w.height:.1f} cm\nabove arm\nμ = {w.mu:g}", fontsize=8,
            va="top", color="0.25")
    lo = max(0.0, d.lip_x - 0.08)
    ax.set_xlim(lo * cm, (L + 0.09) * cm)
    ax.set_ylim(bottom * cm, (h + w.height + 0.035) * cm)
    ax.set_aspect("equal")
    ax.set_xlabel("x along the arm (cm)")
    ax.set_ylabel("y (cm)")
    real = d.realisation
    ax.set_title(title or (f"{part.name or 'part'}\n{what} {k}: arm end L = {100 * L:.1f} cm, "
                           f"ω = {d.omega:.3g} rad/s ({real['kind']})"), fontsize=9)
    fig.tight_layout()
    if path is not None:
        fig.savefig(path, dpi=130)
    return fig
