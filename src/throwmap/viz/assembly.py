"""Self-assembly figures (paper Sec. VI): the Fig. 16 and Fig. 15 analogues of one recorded trial.

* :func:`plot_assembly_episode` — x of both parts' CMs against throw number (triangles and squares as in the
  draft's Fig. 16), filled where a part rests on its assembly side, the phases shaded (randomise, assemble,
  retention), the switch and the assembly marked, the release rate per throw below;
* :func:`plot_assembly_snapshots` — the pair drawn at the switch, in a partial assembly and assembled (Fig. 15),
  on the arm at its rest angle with the wall.

Both take an :class:`throwmap.experiments.assemble_episode.AssemblyEpisode` and compute nothing physical: poses are
drawn as recorded. Matplotlib is imported on first use.
"""

from __future__ import annotations

import math

import numpy as np

from ..system.pose import world_vertices
from .style import _plt, scale

__all__ = ["plot_assembly_episode", "plot_assembly_snapshots", "draw_pair"]

MARKERS = ("^", "s")
COLORS = ("C0", "C3")
PHASE_SHADE = {"high": ("0.92", "randomise (high throws)"), "low": ("#dcebf7", "assemble (low throws)"),
               "hold": ("#e3f3df", "retention")}


def plot_assembly_episode(ep, *, unit: str = "cm", title: str | None = None):
    """x of both parts against throw number (Fig. 16 analogue) with ω per throw below; returns the Figure."""
    plt = _plt()
    s = scale(unit)
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(8, 5.2), sharex=True, height_ratios=(3, 1.1))
    k = np.asarray(ep.throw_no)
    phases = list(ep.phases)
    # shade each phase's span of throw numbers
    seen = set()
    i = 0
    while i < len(phases):
        p, j = phases[i], i
        while j + 1 < len(phases) and phases[j + 1] == p:
            j += 1
        if p in PHASE_SHADE:
            color, label = PHASE_SHADE[p]
            ax.axvspan(k[i] - 0.5, k[j] + 0.5, color=color, zorder=0, label=None if p in seen else label)
            seen.add(p)
        i = j + 1
    keep = np.array([p not in ("tilt", "slide", "escape", "reset") for p in phases])
    roles = ep.roles()
    for p in range(ep.states.shape[1]):
        x = ep.states[:, p, 0] * s
        side = ep.states[:, p, 1]
        ax.plot(k[keep], x[keep], "-", color=COLORS[p], lw=0.7, alpha=0.6, zorder=1)
        name, want = roles[p]
        on = keep & (side == want) & (np.abs(ep.states[:, p, 2]) < 0.05)
        ax.scatter(k[keep], x[keep], marker=MARKERS[p], s=18, facecolors="none", edgecolors=COLORS[p], lw=0.8,
                   zorder=2, label=name)
        ax.scatter(k[on], x[on], marker=MARKERS[p], s=18, color=COLORS[p], zorder=3)
    ax.axhline(ep.length * s, color="k", lw=1.0)
    ax.annotate("wall", (k[0], ep.length * s), fontsize=7, va="bottom")
    for r in ep.switch_runs[:-1]:  # switches whose low phase stalled (tilted back, randomised again)
        ax.axvline(k[r] + 0.5, color="0.5", ls="--", lw=0.8, zorder=1)
    if ep.switch_throw is not None:
        ax.axvline(ep.switch_throw + 0.5, color="k", ls="--", lw=1.0, zorder=1)
        ax.annotate(f"switch after throw {ep.switch_throw}: tilt to α = {math.degrees(ep.alphas[ep.switch_run]):.0f}°",
                    (ep.switch_throw + 0.5, ep.length * s * 0.03), rotation=90, fontsize=7, ha="right", va="bottom")
    if ep.assembled_run is not None:
        ka = int(k[ep.assembled_run])
        ax.axvline(ka, color="C2", ls=":", lw=1.2, zorder=1)
        ax.annotate(f"assembled (throw {ka})", (ka, ep.length * s * 0.03), rotation=90, fontsize=7, ha="right",
                    va="bottom", color="C2")
    ax.set_ylabel(f"x of CM on the arm ({unit})")
    ax.set_ylim(0, ep.length * s * 1.06)
    ax.legend(loc="lower left", fontsize=7, ncol=2, title="filled: flat on its assembly side (a: longer leg, "
                                                          "b: hypotenuse)", title_fontsize=6)
    t = ep.trial
    end = f"assembled after {ep.summary()['assembled_throw']} throws" if t.success else f"failed: {t.failure}"
    ax.set_title(title or f"self-assembly, seed {ep.seed} trial {ep.index}: {end}", fontsize=9)
    thr = np.array([ph not in ("drop", "tilt", "slide", "escape", "reset") for ph in phases])
    ax2.step(k[thr], ep.omegas[thr], where="mid", color="0.3", lw=0.9)
    ax2.set_ylabel("ω (rad/s)")
    ax2.set_xlabel("throw number")
    fig.tight_layout()
    return fig


def _rot(alpha: float, pts: np.ndarray) -> np.ndarray:
    c, s = math.cos(alpha), math.sin(alpha)
    return pts @ np.array([[c, s], [-s, c]])


def draw_pair(ax, part, poses, *, length: float, h: float, wall_height: float, alpha: float, unit: str = "cm",
              show: float = 0.25, labels=None) -> None:
    """Draw the arm (rest angle ``alpha``, joint at the origin), the wall at its end (``show`` m of it) and the parts
    at their arm-frame ``poses`` in world coordinates."""
    s = scale(unit)
    arm = _rot(alpha, np.array([[0.0, h], [length, h]]))
    body = _rot(alpha, np.array([[0.0, h], [length, h], [length, h - 0.02], [0.0, h - 0.02]]))
    ax.fill(body[:, 0] * s, body[:, 1] * s, color="0.75", zorder=1)
    ax.plot(arm[:, 0] * s, arm[:, 1] * s, color="k", lw=1.2, zorder=2)
    wall = _rot(alpha, np.array([[length, h], [length + 0.01, h], [length + 0.01, h + min(show, wall_height)],
                                 [length, h + min(show, wall_height)]]))
    ax.fill(wall[:, 0] * s, wall[:, 1] * s, color="0.45", zorder=2)
    ax.plot([0], [0], "ko", ms=4, zorder=3)
    for p, q in enumerate(poses):
        v = _rot(alpha, world_vertices(part, q))
        if labels is not None:
            c0 = _rot(alpha, np.array([[q[0], q[1]]]))[0]
            ax.annotate(labels[p], (c0[0] * s, c0[1] * s), xytext=(0, 9), textcoords="offset points", fontsize=8,
                        ha="center", color=COLORS[p % 2], zorder=6)
        ax.fill(v[:, 0] * s, v[:, 1] * s, facecolor=COLORS[p % 2], alpha=0.35, edgecolor=COLORS[p % 2], lw=1.2,
                zorder=4)
        c = _rot(alpha, np.array([[q[0], q[1]]]))[0]
        ax.plot(c[0] * s, c[1] * s, marker=MARKERS[p % 2], color=COLORS[p % 2], ms=4, zorder=5)
    ax.set_aspect("equal")


def plot_assembly_snapshots(ep, *, title: str | None = None, unit: str = "cm"):
    """The pair at the switch, partly assembled and assembled (Fig. 15 analogue); returns the Figure."""
    plt = _plt()
    snaps = ep.snapshot_runs() or (("end", ep.n_runs - 1),)
    fig, axes = plt.subplots(len(snaps), 1, figsize=(7.5, 2.5 * len(snaps)), squeeze=False)
    s = scale(unit)
    for ax, (label, r) in zip(axes[:, 0], snaps):
        draw_pair(ax, ep.part, ep.poses[r], length=ep.length, h=ep.h, wall_height=ep.wall_height,
                  alpha=float(ep.alphas[r]), unit=unit, labels=[n for n, _ in ep.roles()])
        ax.set_title(f"{label}: throw {int(ep.throw_no[r])} ({ep.phases[r]}, α = {math.degrees(ep.alphas[r]):.0f}°)",
                     fontsize=8)
        ax.set_xlim(-0.02 * s, (ep.length + 0.04) * s)
        ax.set_ylim(-0.13 * s, 0.13 * s)
        ax.set_ylabel(unit)
    axes[-1, 0].set_xlabel(f"world x ({unit})")
    fig.suptitle(title or f"self-assembly, seed {ep.seed} trial {ep.index}", fontsize=9)
    fig.tight_layout()
    return fig
