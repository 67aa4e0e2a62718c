"""What every figure shares: pyplot imported on first use, colours, axis units, layout and saving.

Importing this module does not load matplotlib; :func:`_plt` does, on first use
(matplotlib falls back to Agg where there is no display). Data are always in SI
units (m); figures label their axes in ``unit`` — ``"cm"`` (the default) or ``"m"``.
"""

from __future__ import annotations

from ..errors import InvalidStateError

__all__ = ["ESCAPE_COLOR", "UNITS", "attractor_colors", "save_figure", "scale", "side_colors"]

UNITS = {"cm": 100.0, "m": 1.0}
"""Axis units per metre, by name."""

ESCAPE_COLOR = (0.15, 0.15, 0.15, 1.0)
"""Colour of label −1 (no attractor on the arm) in basin maps."""


def _plt():
    """pyplot, imported on first use (matplotlib falls back to Agg where there is no display)."""
    import matplotlib.pyplot as plt

    return plt


def scale(unit: str) -> float:
    """Axis units per metre for ``unit`` (``"cm"`` or ``"m"``); any other name is refused."""
    if unit not in UNITS:
        raise InvalidStateError("unit", f"must be one of {sorted(UNITS)}, got {unit!r}")
    return UNITS[unit]


def layout(fig) -> None:
    """tight_layout unless the figure already has a layout engine (e.g. constrained)."""
    if fig.get_layout_engine() is None:
        fig.tight_layout()


def side_colors(n: int) -> list:
    """One colour per side index 0…n−1 (tab10 cycle), the same in every figure."""
    plt = _plt()
    cmap = plt.get_cmap("tab10")
    return [cmap(k % 10) for k in range(n)]


def attractor_colors(n: int) -> list:
    """One colour per attractor id 1…n (Set1 without its grey, then Dark2), distinct from :data:`ESCAPE_COLOR`."""
    plt = _plt()
    base = [plt.get_cmap("Set1")(k) for k in (0, 1, 2, 3, 4, 6, 7)] + [plt.get_cmap("Dark2")(k) for k in range(8)]
    return [base[k % len(base)] for k in range(n)]


def fmt_share(d: dict) -> str:
    """``{"off_end": 0.25}`` → ``"off_end 25.0 %"`` (shares of starts, comma separated)."""
    return ", ".join(f"{k} {100 * v:.1f} %" for k, v in d.items())


def save_figure(fig, path, dpi: int = 130):
    """Save ``fig`` atomically (render to memory, then write-and-rename); returns the path.

    The format follows the suffix of ``path`` (PNG when it has none); ``dpi`` in dots per inch.
    """
    import io as _io
    from pathlib import Path

    from ..io.files import atomic_write_bytes

    path = Path(path)
    buf = _io.BytesIO()
    fig.savefig(buf, format=path.suffix.lstrip(".") or "png", dpi=dpi)
    atomic_write_bytes(path, buf.getvalue())
    return path
