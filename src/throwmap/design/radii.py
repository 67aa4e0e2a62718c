"""The critical radii r_i of a design point, per stable side, as a result (paper Sec. III-D, V-B).

r_i is the first start beyond the first jog on side i from which a throw flips (m): the design targets of Sec. V-B.
:class:`SideRadii` carries them with how they were found — the corrected energy test of the small-angle model
(:func:`~throwmap.design.small_angle.energy_critical_points`), an exact model or the engine
(:func:`~throwmap.design.examples.exact_r`, :func:`~throwmap.design.examples.engine_r`) — with ``table()``,
``to_dict()`` (``{side: r}``) and ``.plot()``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["SideRadii"]


@dataclass(frozen=True, slots=True)
class SideRadii:
    """r_i per stable side (``r``: side → m; nan where no flip follows a jog up to the domain's end) of part
    ``part`` (its name) thrown at ``omega`` (rad/s), found by ``method`` (``"energy test"`` or a model's name)."""

    r: dict
    method: str
    part: str = ""
    omega: float = math.nan

    def __post_init__(self):
        object.__setattr__(self, "r", {int(s): float(v) for s, v in dict(self.r).items()})

    def table(self) -> str:
        """One row per side: r_i in m and cm."""
        lines = [f"r_i of {self.part or 'the part'} at ω = {self.omega:g} rad/s ({self.method})",
                 "| side | r_i (m) | r_i (cm) |", "|---|---|---|"]
        for s, v in self.r.items():
            lines.append(f"| {s} | {v:.6f} | {100 * v:.2f} |" if math.isfinite(v) else f"| {s} | — | — |")
        return "\n".join(lines)

    def to_dict(self) -> dict:
        """``{side: r_i}`` (m; nan where none), as the functions returned before they returned this result."""
        return dict(self.r)

    def plot(self, ax=None):
        """r_i per side as bars (:func:`throwmap.viz.design.plot_side_radii`)."""
        from ..viz.design import plot_side_radii

        return plot_side_radii(self, ax=ax)
