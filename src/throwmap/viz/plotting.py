"""Figures (matplotlib, imported lazily): orbits (Figs. 7, 16), throw maps (Fig. 2), model errors.

Every function takes an optional ``ax``/``axes`` and returns the matplotlib Figure.
"""

from __future__ import annotations

import numpy as np

from ..throws.outcome import Status

__all__ = ["plot_orbit", "plot_throw_map", "plot_model_comparison", "save_figure", "side_colors"]


def save_figure(fig, path, dpi: int = 130):
    """Save ``fig`` atomically (render to memory, then write-and-rename); returns the path."""
    import io as _io
    from pathlib import Path

    from ..io.files import atomic_write_bytes

    path = Path(path)
    buf = _io.BytesIO()
    fig.savefig(buf, format=path.suffix.lstrip(".") or "png", dpi=dpi)
    atomic_write_bytes(path, buf.getvalue())
    return path


def _plt():
    """pyplot, imported on first use (matplotlib falls back to Agg where there is no display)."""
    import matplotlib.pyplot as plt

    return plt


def side_colors(n: int) -> list:
    """One colour per side index (tab10 cycle)."""
    plt = _plt()
    cmap = plt.get_cmap("tab10")
    return [cmap(k % 10) for k in range(n)]


def plot_orbit(orbit, ax=None, part=None, unit: str = "cm"):
    """x against throw number, side by colour (like paper Figs. 7 and 16)."""
    plt = _plt()
    if ax is None:
        fig, ax = plt.subplots(figsize=(7, 3.5))
    fig = ax.figure
    scale = 100.0 if unit == "cm" else 1.0
    k = np.arange(len(orbit.x))
    sides = np.asarray(orbit.side)
    n_sides = int(sides.max()) + 1 if part is None else part.n_sides
    colors = side_colors(max(n_sides, 1))
    ax.plot(k, orbit.x * scale, "-", color="0.8", lw=0.8, zorder=1)
    for s in np.unique(sides):
        m = sides == s
        ax.scatter(k[m], orbit.x[m] * scale, s=12, color=colors[int(s)], label=f"side {int(s)}", zorder=2)
    if orbit.status != Status.OK and orbit.outcomes:
        last = orbit.outcomes[-1]
        ax.scatter([len(orbit.x)], [last.x * scale], marker="x", color="k", s=40, zorder=3,
                   label=f"escape: {orbit.status.label}")
    ax.set_xlabel("throw number")
    ax.set_ylabel(f"x of CM on the arm ({unit})")
    omegas = np.unique(np.round(orbit.omegas, 6))
    om = f"ω = {omegas[0]:g} rad/s" if len(omegas) == 1 else f"{len(omegas)} release rates"
    ax.set_title(f"orbit, model {orbit.model!r}, {om}")
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    return fig


def plot_throw_map(part, arm, omega, *, model: str = "paper", sides=None, x_max=None, n: int = 1500, axes=None,
                   unit: str = "cm"):
    """T(x) against x, one panel per starting side, with the diagonal (paper Fig. 2).

    Points are coloured by the side the part lands on; escapes (off the arm) are
    marked ``x`` at the start x on the axis. ``x_max`` defaults to the arm length,
    or 0.5 m for an unbounded arm.
    """
    from ..throws.throw import throw_batch

    plt = _plt()
    sides = list(part.stable_sides) if sides is None else [part.check_side(s) for s in sides]
    if x_max is None:
        x_max = arm.length if arm.length is not None else 0.5
    if axes is None:
        fig, axes = plt.subplots(1, len(sides), figsize=(4.2 * len(sides), 4), squeeze=False)
        axes = axes[0]
    axes = np.atleast_1d(axes)
    fig = axes[0].figure
    scale = 100.0 if unit == "cm" else 1.0
    colors = side_colors(part.n_sides)
    for ax, s in zip(axes, sides):
        x_lo = part.x_min(s)
        xs = np.linspace(x_lo, x_max, n + 1)[1:]
        res = throw_batch(part, arm, xs, s, omega, model=model, on_invalid="status")
        ok = res.status == Status.OK
        for dest in np.unique(res.side[ok]):
            m = ok & (res.side == dest)
            kind = "jog" if dest == s else "flip"
            ax.scatter(xs[m] * scale, res.x[m] * scale, s=3, color=colors[int(dest)],
                       label=f"→ side {int(dest)} ({kind})")
        if np.any(~ok):
            ax.scatter(xs[~ok] * scale, np.zeros(np.sum(~ok)), marker="x", s=8, color="k", label="escapes")
        lim = (0, x_max * scale)
        ax.plot(lim, lim, "--", color="0.5", lw=0.8, label="T(x) = x")
        ax.set_xlim(lim)
        ax.set_ylim(lim)
        ax.set_aspect("equal")
        ax.set_xlabel(f"x on side {s} ({unit})")
        ax.set_ylabel(f"T(x) ({unit})")
        ax.set_title(f"side {s}")
        ax.legend(loc="upper left", fontsize=7, markerscale=3)
    fig.suptitle(f"throw map, model {model!r}, ω = {omega:g} rad/s, h = {arm.h:g} m")
    fig.tight_layout()
    return fig


def plot_model_comparison(comparison, ax=None):
    """Jog-length error of each approximate model against the reference, per ω."""
    plt = _plt()
    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 3.5))
    fig = ax.figure
    for model in comparison.models:
        rows = [r for r in comparison.rows if r["model"] == model]
        ax.plot([r["omega"] for r in rows], [r["jog_rel_err_median"] * 100 for r in rows], "o-", label=model)
    ax.set_xlabel("ω (rad/s)")
    ax.set_ylabel(f"median |Δ jog| / jog vs {comparison.reference!r} (%)")
    ax.set_yscale("log")
    ax.legend()
    ax.set_title(comparison.part_name)
    fig.tight_layout()
    return fig
