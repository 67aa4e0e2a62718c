"""Drawing an :class:`~throwmap.experiments.runner.ExperimentResult` (matplotlib imported lazily)."""

from __future__ import annotations

__all__ = ["plot_result"]


def plot_result(result, ax=None):
    """Bars: the fraction of trials per outcome (success, then each failure kind); the success bar
    carries its Wilson 95 % interval as an error bar. Returns the axes."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6.5, 4), layout="constrained")
    n = max(result.n, 1)
    labels = ["success"] + list(result.failures)
    fracs = [result.successes / n] + [c / n for c in result.failures.values()]
    colors = ["tab:green"] + ["tab:red"] * len(result.failures)
    bars = ax.bar(range(len(labels)), fracs, color=colors)
    lo, hi = result.ci95
    p = fracs[0]
    ax.errorbar([0], [p], yerr=[[p - lo], [hi - p]], fmt="none", ecolor="black", capsize=6, label="Wilson 95 %")
    for i, (b, f) in enumerate(zip(bars, fracs)):
        top = hi if i == 0 else f  # above the interval's cap on the success bar
        ax.annotate(f"{100 * f:.1f} %", (b.get_x() + b.get_width() / 2, top), xytext=(0, 3),
                    textcoords="offset points", ha="center", va="bottom", fontsize=8)
    ax.set_xticks(range(len(labels)), labels, rotation=20, ha="right")
    ax.set_ylim(0, 1.12)
    ax.set_ylabel("fraction of trials")
    ax.set_title(f"experiment {result.name}: n = {result.n}, seed {result.seed}")
    ax.legend(loc="upper right", fontsize=8)
    return ax
