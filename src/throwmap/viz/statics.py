"""The Fig. 13 and Fig. 14 analogues: placements drawn with contact forces and friction cones, and the
regions where they can rest (paper Sec. VI). Draws the data of :mod:`throwmap.statics.figures`; computes
nothing. Lengths shown in cm, forces scaled to the parts' weight.
"""

from __future__ import annotations

import math

import numpy as np

from .style import _plt, layout

__all__ = ["draw_placement", "lean_figure", "partial_figure"]


def draw_placement(ax, bodies, analysis, *, length: float, h: float, wall_height: float, alpha: float,
                   force_scale: float = 0.06) -> None:
    """Parts (filled), the arm and wall (grey), each contact force of ``analysis`` (arrows, cm per weight
    ``force_scale`` m/N·W) with its friction cone (dashed) and gravity at each CM (arrow), in cm."""
    s = 100.0
    colors = ["tab:blue", "tab:orange", "tab:green"]
    xmin = min(b.vertices()[:, 0].min() for b in bodies) - 0.03
    ax.plot([xmin * s, length * s], [h * s, h * s], color="0.3", lw=3)
    ax.fill([length * s, (length + 0.01) * s, (length + 0.01) * s, length * s],
            [h * s, h * s, (h + wall_height) * s, (h + wall_height) * s], color="0.7")
    for i, b in enumerate(bodies):
        v = b.vertices() * s
        ax.fill(v[:, 0], v[:, 1], alpha=0.35, color=colors[i % 3], label=f"part {'ab'[i] if i < 2 else i}")
        ax.plot(np.r_[v[:, 0], v[0, 0]], np.r_[v[:, 1], v[0, 1]], color=colors[i % 3])
        gdir = np.array([-math.sin(alpha), -math.cos(alpha)])
        ax.annotate("", xy=(b.x * s + 3 * gdir[0], b.y * s + 3 * gdir[1]), xytext=(b.x * s, b.y * s),
                    arrowprops=dict(arrowstyle="->", color="k"))
    W = analysis.weight
    for j, c in enumerate(analysis.contacts):
        p = np.array(c.point) * s
        n = np.array(c.normal)
        t = np.array(c.tangent)
        if math.isfinite(c.mu) and c.mu > 0:
            for sgn in (1, -1):
                d = n + sgn * c.mu * t
                d = d / np.hypot(*d) * 2.5
                ax.plot([p[0], p[0] + d[0]], [p[1], p[1] + d[1]], ls="--", lw=0.8, color="0.4")
        if analysis.forces:
            fn, ft = analysis.forces[j]
            f = (fn * n + ft * t) / W * force_scale * s
            ax.annotate("", xy=(p[0] + f[0], p[1] + f[1]), xytext=tuple(p),
                        arrowprops=dict(arrowstyle="->", color="tab:red", lw=1.5))
    ax.set_aspect("equal")
    ax.set_xlabel("x along the arm (cm)")
    ax.set_ylabel("y (cm)")


def lean_figure(data: dict):
    """Fig. 13 analogue from :func:`throwmap.statics.figures.lean_data`: left, the part leaning with its
    forces; right, where a lean can rest over (β, μ) at that α (complete condition) with the draft's printed
    boundary."""
    plt = _plt()
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.4))
    an, alpha = data["analysis"], data["alpha"]
    draw_placement(ax0, data["bodies"], an, length=data["length"], h=data["h"], wall_height=0.12, alpha=alpha)
    state = "can rest" if an.can_rest else f"cannot rest ({an.message})"
    ax0.set_title(f"leaning at β = {data['beta_show']:.2f} rad, α = {math.degrees(alpha):.0f}°, μ = {data['mu_show']:g}: "
                  f"{state}", fontsize=9)
    B, M = np.meshgrid(data["betas"], data["mus"])
    ax1.contourf(B, M, data["possible"].astype(float), levels=[-0.5, 0.5, 1.5], colors=["white", "tab:orange"],
                 alpha=0.6)
    ax1.contour(B, M, data["drafts_no_lean"].astype(float), levels=[0.5], colors="k", linestyles="--")
    ax1.plot([], [], color="tab:orange", lw=6, alpha=0.6, label="can lean (complete condition)")
    ax1.plot([], [], "k--", label="draft's printed boundary")
    ax1.set_xlabel("lean angle β (rad)")
    ax1.set_ylabel("arm μ")
    ax1.set_title(f"{data['part_name']}: where a lean rests, α = {math.degrees(alpha):.0f}°, frictionless wall",
                  fontsize=9)
    ax1.legend(fontsize=8, loc="upper right")
    layout(fig)
    return fig


def partial_figure(data: dict):
    """Fig. 14 analogue from :func:`throwmap.statics.figures.partial_data`: left, the partial assembly with its
    forces; right, where it rests over (γ, μ) (LP) and the arm friction it needs against γ."""
    plt = _plt()
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.4))
    an, alpha = data["analysis"], data["alpha"]
    draw_placement(ax0, data["bodies"], an, length=data["length"], h=data["h"], wall_height=0.12, alpha=alpha)
    ax0.set_title(f"partial assembly γ = {math.degrees(data['gamma_show']):.0f}°, α = {math.degrees(alpha):.0f}°, "
                  f"μ = {data['mu_show']:g}: {'rests' if an.can_rest else 'cannot rest'} (needs μ ≥ {an.mu_needed:.3g})",
                  fontsize=9)
    g, m = data["gammas_deg"], data["mus"]
    G, M = np.meshgrid(g, m, indexing="ij")
    ax1.contourf(G, M, data["rests"].astype(float), levels=[-0.5, 0.5, 1.5], colors=["white", "tab:green"], alpha=0.5)
    ax1.plot(g, data["mu_needed"], "k-", label="arm μ needed (LP)")
    ax1.set_xlabel("γ (deg; −30 assembled, 0 flat)")
    ax1.set_ylabel("arm μ")
    ax1.set_ylim(0, float(np.max(m)))
    ax1.set_title(f"where the partial assembly rests, α = {math.degrees(alpha):.0f}° (frictionless wall and parts)",
                  fontsize=9)
    ax1.legend(fontsize=8)
    layout(fig)
    return fig
