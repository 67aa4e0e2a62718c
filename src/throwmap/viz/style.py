"""What every figure shares: pyplot imported on first use, colours, axis units, layout and saving.

Importing this module does not load matplotlib; :func:`_plt` does, on first use
(matplotlib falls back to Agg where there is no display). Data are always in SI
units (m); figures label their axes in ``unit`` — ``"cm"`` (the default) or ``"m"``.
"""

from __future__ import annotations

import math

from ..errors import InvalidStateError

__all__ = ["ESCAPE_COLOR", "UNITS", "attractor_colors", "describe_setting", "part_label", "map_title", "save_figure", "scale",
           "side_colors", "wrap_setting", "x_range_text"]

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


def _omegas_text(omegas) -> str:
    om = [float(w) for w in omegas]
    return "ω = " + ", ".join(f"{w:g}" for w in om) + " rad/s" if om else "ω = ?"


def part_label(part) -> str:
    """A part's name for a title: ``part.name``, or for a :class:`~throwmap.system.part.Part` with an
    empty name its descriptive default (:func:`~throwmap.system.part.default_name`:
    ``"polygon(4 vertices, 70 g)+lead(…)"``); a plain string as it is; ``""`` when unknown."""
    name = getattr(part, "name", part)
    if not name and hasattr(part, "point_masses") and hasattr(part, "vertices"):
        from ..system.part import default_name

        added = sum(m for m, _ in part.point_masses)
        return default_name(len(part.vertices), part.mass - added, part.point_masses)
    return "" if name is None else str(name)


def describe_setting(part=None, h=None, omegas=(), model=None, mu=None) -> str:
    """What a figure shows, for its title: ``"<part>, h = -0.01 m, ω = 4 rad/s, model 'paper'"``.

    ``part`` is a name (or a :class:`~throwmap.system.part.Part`), ``h`` the arm height (m),
    ``omegas`` the release rate(s) (rad/s), ``model`` a model name, ``mu`` the arm's
    friction (shown when finite). A piece that is not known is shown as ``?`` rather than
    left out, so a title never silently omits the part, h, ω or the model.
    """
    name = part_label(part)
    if isinstance(omegas, (int, float)):
        omegas = (omegas,)
    bits = [str(name) if name else "part ?", f"h = {h:g} m" if h is not None else "h = ?", _omegas_text(omegas or ())]
    if mu is not None and math.isfinite(mu):
        bits.append(f"μ = {mu:g}")
    bits.append(f"model {model!r}" if model else "model ?")
    return ", ".join(bits)


def map_title(info: dict, fallback: str = "map") -> str:
    """:func:`describe_setting` of a map's ``describe()`` dict (a throw map); ``fallback`` for any other map.

    Also takes a list of such dicts (a funnel graph's maps): parts, h, ω and models merged.
    """
    infos = info if isinstance(info, (list, tuple)) else [info]
    infos = [i for i in infos if isinstance(i, dict) and i.get("kind") == "throw"]
    if not infos:
        return fallback

    def merged(key):
        return list(dict.fromkeys(v for v in (i.get(key) for i in infos) if v is not None))

    omegas = [w for i in infos for w in (i.get("omegas_rad_s") or [i.get("omega_rad_s")]) if w is not None]
    parts, hs, models, mus = merged("part"), merged("h_m"), merged("model"), merged("mu")
    text = describe_setting(" | ".join(parts), hs[0] if len(hs) == 1 else None, list(dict.fromkeys(omegas)),
                            ", ".join(models), mus[0] if len(mus) == 1 else None)
    if len(hs) > 1:
        text = text.replace("h = ?", "h = " + ", ".join(f"{h:g}" for h in hs) + " m")
    return text


def wrap_setting(text: str, width: int) -> str:
    """``text`` from :func:`describe_setting` on lines of about ``width`` characters, broken only
    at the comma before a setting (``h =``, ``ω =``, ``μ =``, ``model``, ``analysed``, ``sampled``, ``x ≤``), never
    inside a list of ω or a part's name."""
    import re

    pieces = re.split(r", (?=h = |ω = |μ = |model |analysed |sampled |x ≤ )", text)
    lines: list[str] = []
    for p in pieces:
        if lines and len(lines[-1]) + 2 + len(p) <= width:
            lines[-1] += ", " + p
        else:
            lines.append(p)
    return ",\n".join(lines)


def x_range_text(info: dict) -> str:
    """``"x ≤ 60 cm"``: the outer end of the analysed domain from a map's ``describe()`` dict, or ``""``."""
    infos = info if isinstance(info, (list, tuple)) else [info]
    xs = [i.get("x_max_m") for i in infos if isinstance(i, dict) and i.get("x_max_m") is not None]
    return f"analysed for x ≤ {100 * max(xs):.4g} cm" if xs else ""


def fmt_share(d: dict) -> str:
    """``{"off_end": 0.25}`` → ``"off_end 25.0 %"`` (shares of starts, comma separated)."""
    return ", ".join(f"{k} {100 * v:.1f} %" for k, v in d.items())


def save_figure(fig, path, dpi: int = 130, tight: bool = False):
    """Save ``fig`` atomically (render to memory, then write-and-rename); returns the path.

    The format follows the suffix of ``path`` (PNG when it has none); ``dpi`` in dots per inch; ``tight``: the
    image is cropped or grown to what is drawn (nothing drawn outside the figure is cut off).
    """
    import io as _io
    from pathlib import Path

    from ..io.files import atomic_write_bytes

    path = Path(path)
    buf = _io.BytesIO()
    fig.savefig(buf, format=path.suffix.lstrip(".") or "png", dpi=dpi,
                **({"bbox_inches": "tight", "pad_inches": 0.1} if tight else {}))
    atomic_write_bytes(path, buf.getvalue())
    return path
