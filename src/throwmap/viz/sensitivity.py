"""Success rate against one parameter, with Wilson 95 % intervals: the sensitivity figures.

:func:`plot_sensitivity` draws a :class:`throwmap.experiments.sensitivity.Sensitivity` (or its ``to_dict()``):
the success rate of each run as a point with its interval as an error bar, the runs joined by a line, an optional
goal line, and the trial count under each point. Matplotlib is imported on first use.
"""

from __future__ import annotations

from .style import _plt

__all__ = ["plot_sensitivity"]

AXIS_NAMES = {"tilt_rate": "tilt rate (rad/s)", "mu": "arm μ (nominal)", "noise.omega_rel": "ω jitter (relative, 1σ)",
              "sensor.false_positive": "sensor error rate (per read)", "omega_low": "assembling rate ω_low (rad/s)",
              "alpha": "assembly rest angle α (rad)", "noise.mu_rel": "μ spread (relative)"}
"""Axis labels of the usual parameters (others are labelled with their dotted path)."""


def plot_sensitivity(sens, ax=None, *, goal: float | None = None, title: str | None = None):
    """Success (%) against the parameter's value, Wilson 95 % bars, ``goal`` (a rate in [0, 1]) as a dashed line;
    returns the Figure."""
    plt = _plt()
    d = sens if isinstance(sens, dict) else sens.to_dict()
    rows = d["rows"]
    if ax is None:
        fig, ax = plt.subplots(figsize=(5.5, 3.6))
    else:
        fig = ax.figure
    xs = [r["value"] for r in rows]
    ys = [100 * (r["successes"] / r["n"]) if r["n"] else float("nan") for r in rows]
    lo = [y - 100 * r["ci95"][0] for y, r in zip(ys, rows)]
    hi = [100 * r["ci95"][1] - y for y, r in zip(ys, rows)]
    ax.errorbar(xs, ys, yerr=[lo, hi], fmt="o-", color="C0", ecolor="C0", capsize=3, lw=1.2, ms=5,
                label="success (Wilson 95 %)")
    span = (max(xs) - min(xs)) or 1.0
    for k, (x, y, r) in enumerate(zip(xs, ys, rows)):
        # beside the point (clear of its error bar); neighbours within 10 % of the axis alternate above and below
        crowded = any(abs(x - xo) < 0.1 * span for j, xo in enumerate(xs) if j != k)
        dy, va = (-4, "top") if crowded and k % 2 == 1 else (3, "bottom")
        ax.annotate(f"{r['successes']}/{r['n']}", (x, y), textcoords="offset points", xytext=(5, dy), ha="left",
                    va=va, fontsize=7, color="0.3")
    ax.margins(x=0.1)
    if goal is not None:
        ax.axhline(100 * goal, color="0.4", ls="--", lw=0.9, label=f"goal {100 * goal:g} %")
    fields = d["fields"]
    ax.set_xlabel(AXIS_NAMES.get(fields[0], " = ".join(fields)))
    ax.set_ylabel("success (%)")
    ax.set_ylim(-3, 103)
    ax.legend(fontsize=7, loc="lower left")
    ax.set_title(title or f"{d['experiment']}: success against {' = '.join(fields)} (seed {d['seed']})", fontsize=9)
    fig.tight_layout()
    return fig
