"""The Fig. 13 and Fig. 14 analogues: placements drawn with contact forces and friction cones, and the
regions where they can rest (paper Sec. VI). Draws the data of :mod:`throwmap.statics.figures`; computes
nothing. Lengths shown in cm, forces scaled to the parts' weight.
"""

from __future__ import annotations

import math

import numpy as np

from .style import _plt, layout

__all__ = ["draw_placement", "lean_figure", "partial_figure", "plot_rest_forces", "plot_engine_rest",
           "plot_partial_region", "plot_lean_table", "plot_partial_table"]


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


def lean_figure(data):
    """Fig. 13 analogue from :func:`throwmap.statics.figures.lean_data` (a ``LeanData``): left, the part leaning
    with its forces; right, where a lean can rest over (β, μ) at that α (complete condition) with the draft's
    printed boundary."""
    plt = _plt()
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.4))
    an, alpha = data.analysis, data.alpha
    draw_placement(ax0, data.bodies, an, length=data.length, h=data.h, wall_height=0.12, alpha=alpha)
    state = "can rest" if an.can_rest else f"cannot rest ({an.message})"
    ax0.set_title(f"leaning at β = {data.beta_show:.2f} rad, α = {math.degrees(alpha):.0f}°, μ = {data.mu_show:g}: "
                  f"{state}", fontsize=9)
    B, M = np.meshgrid(data.betas, data.mus)
    ax1.contourf(B, M, data.possible.astype(float), levels=[-0.5, 0.5, 1.5], colors=["white", "tab:orange"],
                 alpha=0.6)
    ax1.contour(B, M, data.drafts_no_lean.astype(float), levels=[0.5], colors="k", linestyles="--")
    ax1.plot([], [], color="tab:orange", lw=6, alpha=0.6, label="can lean (complete condition)")
    ax1.plot([], [], "k--", label="draft's printed boundary")
    ax1.set_xlabel("lean angle β (rad)")
    ax1.set_ylabel("arm μ")
    ax1.set_title(f"{data.part_name}:\nwhere a lean rests, α = {math.degrees(alpha):.0f}°, frictionless wall",
                  fontsize=9)
    ax1.legend(fontsize=8, loc="upper right")
    layout(fig)
    return fig


def partial_figure(data):
    """Fig. 14 analogue from :func:`throwmap.statics.figures.partial_data` (a ``PartialData``): left, the partial
    assembly with its forces; right, where it rests over (γ, μ) (LP) and the arm friction it needs against γ."""
    plt = _plt()
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.4))
    an, alpha = data.analysis, data.alpha
    draw_placement(ax0, data.bodies, an, length=data.length, h=data.h, wall_height=0.12, alpha=alpha)
    ax0.set_title(f"partial assembly γ = {math.degrees(data.gamma_show):.0f}°, α = {math.degrees(alpha):.0f}°, "
                  f"μ = {data.mu_show:g}: {'rests' if an.can_rest else 'cannot rest'} (needs μ ≥ {an.mu_needed:.3g})",
                  fontsize=9)
    g, m = data.gammas_deg, data.mus
    _region(ax1, g, m, data.mu_needed)
    ax1.set_title(f"where the partial assembly rests, α = {math.degrees(alpha):.0f}° (frictionless wall and parts)",
                  fontsize=9)
    layout(fig)
    return fig


def _region(ax, g, m, mu_needed) -> None:
    """Where the partial assembly rests over (γ deg, μ) and the μ it needs against γ, on ``ax``.

    The region is drawn from ``mu_needed`` itself: it rests where μ ≥ μ needed (the LP is monotone in the arm's μ),
    between the samples on the same straight segments as the line, so its edge is the line. (A contour of the
    rests-grid would put the edge half-way between two grid μ, off the line by up to half a grid step.) A γ that
    no arm μ holds (μ needed ∞) shows no rest."""
    g = np.asarray(g, dtype=float)
    need = np.asarray(mu_needed, dtype=float)
    top = float(np.max(m))
    finite = np.isfinite(need)
    ax.fill_between(g, np.where(finite, np.minimum(need, top), top), top, where=finite, color="tab:green",
                    alpha=0.5, lw=0, label="rests (LP): arm μ ≥ μ needed")
    ax.plot(g, need, "k-", label="arm μ needed (LP)")
    ax.set_xlabel("γ (deg; −30 assembled, 0 flat)")
    ax.set_ylabel("arm μ")
    if g.size > 1:
        ax.set_xlim(float(np.min(g)), float(np.max(g)))
    ax.set_ylim(0, top)
    ax.legend(fontsize=8)


def _axes(ax, size=(5.5, 3.6)):
    plt = _plt()
    if ax is None:
        fig, ax = plt.subplots(figsize=size)
        return fig, ax
    return ax.figure, ax


def plot_partial_region(region, ax=None):
    """A :class:`~throwmap.statics.assembly.PartialRegion`: where it rests over (γ, μ) and the μ it needs.
    Returns the Figure."""
    fig, ax = _axes(ax)
    _region(ax, np.degrees(region.gamma), region.mu, region.mu_needed)
    ax.set_title(f"partial assembly, α = {math.degrees(region.alpha):.0f}°: where it rests (LP)", fontsize=9)
    layout(fig)
    return fig


def plot_rest_forces(analysis, ax=None):
    """A :class:`~throwmap.statics.rest.RestAnalysis`: per contact f_n and f_t (in units of the weight) of one
    solution, with their admissible ranges as error bars. Returns the Figure."""
    fig, ax = _axes(ax)
    W = analysis.weight or 1.0
    k = np.arange(len(analysis.contacts))
    for j, (name, color, off) in enumerate((("f_n", "tab:blue", -0.18), ("f_t", "tab:orange", 0.18))):
        if not analysis.forces:
            break
        f = np.array([fc[j] for fc in analysis.forces]) / W
        lo = np.array([r[j][0] for r in analysis.ranges]) / W
        hi = np.array([r[j][1] for r in analysis.ranges]) / W
        ax.bar(k + off, f, width=0.34, color=color, alpha=0.7, label=f"{name} / weight")
        err = np.vstack([np.clip(f - lo, 0, 1e3), np.clip(hi - f, 0, 1e3)])
        ax.errorbar(k + off, f, yerr=err, fmt="none", ecolor="k", capsize=3, lw=0.8)
    ax.set_xticks(k, [f"{i} {c.label}" for i, c in enumerate(analysis.contacts)], fontsize=8)
    ax.axhline(0, color="0.5", lw=0.6)
    ax.set_ylabel("force / total weight")
    ax.set_title("can rest" if analysis.can_rest else f"cannot rest: {analysis.message}"[:90], fontsize=9)
    if analysis.forces:
        ax.legend(fontsize=7)
    layout(fig)
    return fig


def plot_engine_rest(rest, ax=None, *, threshold: float = 1e-3):
    """An :class:`~throwmap.statics.engine_check.EngineRest`: how far each part moved (mm) against ``threshold``
    (m). Returns the Figure."""
    fig, ax = _axes(ax, (4.5, 3.2))
    ax.bar(range(len(rest.moved)), [1e3 * m for m in rest.moved], color="tab:blue")
    ax.axhline(1e3 * threshold, color="0.4", ls="--", lw=0.9, label="stayed below")
    ax.set_xticks(range(len(rest.moved)), [f"part {i}" for i in range(len(rest.moved))])
    ax.set_ylabel("moved in the engine (mm)")
    ax.set_title(f"engine, {rest.run_for:g} s: {rest.status}, {'stayed' if rest.stayed else 'did not stay'}",
                 fontsize=9)
    ax.legend(fontsize=7)
    layout(fig)
    return fig


def plot_lean_table(table, ax=None):
    """A :class:`~throwmap.statics.tables.LeanTable`: how often the three answers to "can it lean?" agree, and
    how often the draft's printed condition is wrong. Returns the Figure."""
    fig, ax = _axes(ax, (6.5, 3.4))
    d = table.to_dict()
    items = [("closed form = LP", d["closed_vs_lp"], d["n"]),
             ("LP = engine", d["lp_vs_engine"], d["n"] - d["engine_refused"]),
             ("LP = engine, cap-bound out", d["lp_vs_engine_free"], d["n"] - d["engine_refused"] - d["cap_bound"]),
             ("draft: 'cannot' but can", d["draft_wrong_no_lean"], d["n"]),
             ("draft: allows a fall", d["draft_misses_fall"], d["n"])]
    shown = [(label, k, n) for label, k, n in items if n > 0]
    ax.barh(range(len(shown)), [100 * k / n for _, k, n in shown], color="tab:blue")
    for i, (_, k, n) in enumerate(shown):
        ax.annotate(f"{k}/{n}", (100 * k / n, i), xytext=(3, 0), textcoords="offset points", va="center", fontsize=7)
    ax.set_yticks(range(len(shown)), [s[0] for s in shown], fontsize=8)
    ax.invert_yaxis()
    ax.set_xlim(0, 110)
    ax.set_xlabel("% of the random leans")
    ax.set_title(f"random leans (n = {d['n']}, seed {d['seed']})", fontsize=9)
    layout(fig)
    return fig


def plot_partial_table(table, ax=None):
    """A :class:`~throwmap.statics.tables.PartialTable`: the arm μ needed against γ, the chosen μ, and which γ
    stayed in the engine. Returns the Figure."""
    fig, ax = _axes(ax)
    g = [r[0] for r in table.rows]
    ax.plot(g, [r[1] for r in table.rows], "k.-", label="arm μ needed (LP)")
    ax.axhline(table.mu, color="0.4", ls="--", lw=0.9, label=f"arm μ = {table.mu:g}")
    for marker, want, label in (("o", True, "stays in the engine"), ("x", False, "moves in the engine")):
        pts = [(r[0], r[1]) for r in table.rows if r[3] is want]
        if pts:
            ax.plot([p[0] for p in pts], [p[1] for p in pts], marker, ls="none", color="tab:green" if want else
                    "tab:red", label=label)
    ax.set_xlabel("γ (deg; −30 assembled, 0 flat)")
    ax.set_ylabel("arm μ")
    ax.set_title(f"partial assembly at α = {table.alpha_deg:g}°", fontsize=9)
    ax.legend(fontsize=7)
    layout(fig)
    return fig
