"""Feedback-throwing figures (paper Fig. 7 and Sec. IV-A's precision/time trade-off).

* :func:`plot_episode` — one :class:`~throwmap.control.Episode`: x against throw number, coloured by
  side, the goal band, ω per throw below, the controller's switches marked (Fig. 7 analogue);
* :func:`plot_fan` — many episodes overlaid (the goal band, each trace coloured by its final outcome);
* :func:`plot_tradeoff` — median and 90th-percentile throws against ε with the success rate.

Matplotlib is imported on first use.
"""

from __future__ import annotations

import math

import numpy as np

from .style import _plt, side_colors

__all__ = ["plot_episode", "plot_fan", "plot_tradeoff"]


def _goal_band(ax, goal, scale: float) -> None:
    ax.axhspan((goal.x - goal.eps) * scale, (goal.x + goal.eps) * scale, color="0.85", zorder=0,
               label=f"goal: side {goal.side}, ±{1000 * goal.eps:.3g} mm")


def plot_episode(ep, ax=None, *, title: str | None = None, unit: str = "cm"):
    """x against throw number coloured by side, the goal band, the switches (dotted lines, labelled with
    the new mode) and ω per throw (lower panel); returns the Figure."""
    plt = _plt()
    if ax is None:
        fig, (ax, ax2) = plt.subplots(2, 1, figsize=(7.5, 5), sharex=True, height_ratios=(3, 1.2))
    else:
        fig, ax2 = ax.figure, None
    s = 100.0 if unit == "cm" else 1.0
    xs, ss = np.asarray(ep.x), np.asarray(ep.side)
    k = np.arange(xs.size)
    colors = side_colors(max(int(ss.max()) + 1, ep.goal.side + 1, 3))
    _goal_band(ax, ep.goal, s)
    ax.plot(k, xs * s, "-", color="0.7", lw=0.8, zorder=1)
    for side in np.unique(ss):
        m = ss == side
        ax.scatter(k[m], xs[m] * s, s=14, color=colors[int(side)], label=f"side {int(side)}", zorder=2)
    for st in ep.steps:
        if st.switched and st.action in ("throw", "stop"):
            ax.axvline(st.n_thrown, color="k", ls=":", lw=0.8, zorder=1)
            ax.annotate(st.mode, (st.n_thrown, ax.get_ylim()[1]), fontsize=7, rotation=90, va="top", ha="right")
    end = "success" if ep.success else ep.failure
    ax.set_ylabel(f"x of CM ({unit})")
    ax.legend(loc="lower right", fontsize=7)
    ax.set_title(title or (f"{ep.part}, {ep.model}: {end} after {ep.throws} throws "
                           f"({ep.switches} switches, {ep.looks} looks)"), fontsize=9)
    if ax2 is not None:
        th = ep.throw_steps()
        ax2.step([t.n_thrown + 0.5 for t in th], [t.omega for t in th], where="mid", color="C0", lw=1)
        ax2.set_ylabel("ω (rad/s)")
        ax2.set_xlabel("throw number")
    else:
        ax.set_xlabel("throw number")
    fig.tight_layout()
    return fig


def plot_fan(episodes, ax=None, *, title: str | None = None, unit: str = "cm"):
    """Many episodes' x against throw number (success: blue, failure: red), the goal band; returns the Figure."""
    plt = _plt()
    eps = [e for e in episodes if e is not None]
    if ax is None:
        fig, ax = plt.subplots(figsize=(7.5, 4))
    fig = ax.figure
    s = 100.0 if unit == "cm" else 1.0
    if eps:
        _goal_band(ax, eps[0].goal, s)
    ok = sum(e.success for e in eps)
    for e in eps:
        ax.plot(np.arange(len(e.x)), np.asarray(e.x) * s, "-", lw=0.7, alpha=0.6,
                color="C0" if e.success else "C3")
        goal_side = np.asarray(e.side) == e.goal.side
        ax.scatter(np.flatnonzero(goal_side), np.asarray(e.x)[goal_side] * s, s=3, color="k", alpha=0.4, zorder=2)
    ax.set_xlabel("throw number")
    ax.set_ylabel(f"x of CM ({unit})")
    ax.set_title(title or (f"{len(eps)} episodes ({eps[0].part}, {eps[0].model}): {ok} successes; "
                           f"black dots: on the goal side" if eps else "no episodes"), fontsize=9)
    ax.legend(loc="lower right", fontsize=7)
    fig.tight_layout()
    return fig


def plot_tradeoff(rows, ax=None, *, title: str | None = None):
    """``rows``: dicts with ``eps_m``, ``median``, ``p90`` (throws of the successes), ``success_rate`` and
    ``ci95``; throws against ε (mm, log) with the success rate on a second axis; returns the Figure."""
    plt = _plt()
    if ax is None:
        fig, ax = plt.subplots(figsize=(6.5, 4))
    fig = ax.figure
    e = np.array([1000 * r["eps_m"] for r in rows])
    med = np.array([np.nan if r["median"] is None else r["median"] for r in rows], dtype=float)
    p90 = np.array([np.nan if r["p90"] is None else r["p90"] for r in rows], dtype=float)
    ax.plot(e, med, "o-", color="C0", label="median throws (successes)")
    ax.plot(e, p90, "s--", color="C0", alpha=0.6, label="90th percentile")
    ax.set_xscale("log")
    ax.set_xticks(e, [f"{v:g}" for v in e])
    ax.minorticks_off()
    ax.set_xlabel("goal radius ε (mm)")
    ax.set_ylabel("throws to the goal")
    ax2 = ax.twinx()
    rate = np.array([100 * r["success_rate"] for r in rows])
    lo = np.array([100 * r["ci95"][0] for r in rows])
    hi = np.array([100 * r["ci95"][1] for r in rows])
    ax2.errorbar(e, rate, yerr=[rate - lo, hi - rate], fmt="^", color="C2", capsize=3, label="success % (Wilson 95 %)")
    ax2.set_ylabel("success (%)", color="C2")
    ax2.set_ylim(min(50.0, float(np.nanmin(lo)) - 5 if lo.size else 50.0), 101)
    for r, x in zip(rows, e):
        if r.get("omega_low") is not None and math.isfinite(r["omega_low"]):
            ax.annotate(f"ω_low {r['omega_low']:.2g}", (x, med[list(e).index(x)]), fontsize=7, textcoords="offset points",
                        xytext=(4, 4))
    h1, l1 = ax.get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax.legend(h1 + h2, l1 + l2, fontsize=7, loc="upper right")
    ax.set_title(title or "precision against time (Sec. IV-A)", fontsize=9)
    fig.tight_layout()
    return fig
