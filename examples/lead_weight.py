"""How a lead weight reshapes the orbit of the paper's triangle (Sec. V-C, in miniature).

Throws the uniform 30-60-90 triangle and the same triangle with a 30 g weight near its
30° corner, 400 times each at ω = 4 rad/s on an arm with h = −1 cm, and prints the band
of x each side occupies after the transient. Writes ``lead_weight.png`` into ``out_dir``.

Run: ``python examples/lead_weight.py [OUT_DIR]``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import throwmap as tm


def bands(orbit, part, skip=100):
    out = {}
    for s in part.stable_sides:
        xs = orbit.x[skip:][orbit.side[skip:] == s]
        out[s] = (xs.min(), xs.max(), xs.size) if xs.size else None
    return out


def main(out_dir: str | Path = "out") -> dict:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from throwmap.viz.style import save_figure

    arm = tm.Arm(h=-0.01)
    parts = {
        "uniform": tm.triangle_30_60_90(0.17),
        "lead weight at (10, 1) cm": tm.triangle_30_60_90(0.17, point_masses=[(0.03, (0.10, 0.01))]),
    }
    fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    result = {}
    for ax, (label, part) in zip(axes, parts.items()):
        orbit = tm.iterate(part, arm, (part.x_min(0) + 0.01, 0), 4.0, n=400, model="paper")
        orbit.plot(ax=ax, part=part, arm=arm)  # titled with the part (its lead included), h, ω and the model
        ax.set_title(ax.get_title() + f"\n{label}: CM at ({100 * part.com[0]:.1f}, {100 * part.com[1]:.1f}) cm, "
                     f"{orbit.status.label}", fontsize=8)
        result[label] = bands(orbit, part)
        print(f"{label}:")
        for s, b in result[label].items():
            print(f"  side {s}: " + ("never visited" if b is None else f"{100 * b[0]:6.2f} … {100 * b[1]:6.2f} cm, "
                                      f"{b[2]} visits"))
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    save_figure(fig, out / "lead_weight.png")
    return result


if __name__ == "__main__":
    main(*sys.argv[1:])
