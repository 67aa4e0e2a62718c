"""What the Fig. 13 and Fig. 14 analogues show, computed (:mod:`throwmap.viz.statics` draws it).

:func:`lean_data`: the leaning part at one β with its contact forces (LP), and over a (β, μ) grid at the
arm's α the complete lean condition and the draft's printed one (:class:`LeanData`). :func:`partial_data`: the
partial assembly at one γ with its forces, and over a (γ, μ) grid where it rests (LP) with the arm friction each γ
needs (:class:`PartialData`). Both are results with ``table()``, ``to_dict()`` and ``.plot()`` (the figure).
Units: m, rad (γ also in degrees for the axis).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .assembly import partial_assembly, partial_region
from .leaning import drafts_no_lean, edge_frame_cm, lean_possible, leaning_bodies
from .rest import RestAnalysis, analyse_rest

__all__ = ["LeanData", "PartialData", "lean_data", "partial_data"]


def _bodies(bodies) -> list:
    return [{"part": b.part.name, "x_m": b.x, "y_m": b.y, "phi_rad": b.phi} for b in bodies]


@dataclass(frozen=True, slots=True, eq=False)
class LeanData:
    """Fig. 13's data: the part ``part_name`` leaning at ``beta_show`` (rad) with arm μ ``mu_show`` on an arm at
    ``alpha`` (rad), ``length`` and ``h`` (m): its ``bodies`` and their :class:`RestAnalysis`; over ``betas`` ×
    ``mus`` (arrays ``(len(mus), len(betas))``) where a lean can rest (``possible``, the complete condition) and
    where the draft's printed condition says it cannot (``drafts_no_lean``)."""

    part_name: str
    alpha: float
    beta_show: float
    mu_show: float
    length: float
    h: float
    bodies: tuple
    analysis: RestAnalysis
    betas: np.ndarray
    mus: np.ndarray
    possible: np.ndarray
    drafts_no_lean: np.ndarray

    def table(self) -> str:
        """The shown lean's verdict, then the grid's shares: can lean, and where the draft's condition is wrong."""
        a = self.analysis
        state = "can rest" if a.can_rest else f"cannot rest ({a.message})"
        wrong = self.possible & self.drafts_no_lean
        miss = ~self.possible & ~self.drafts_no_lean
        return "\n".join([
            f"{self.part_name} leaning at β = {self.beta_show:.3g} rad, α = {math.degrees(self.alpha):.3g}°, "
            f"μ = {self.mu_show:g}: {state}; needs μ ≥ {a.mu_needed:.4g}",
            f"over β ∈ [{self.betas[0]:.3g}, {self.betas[-1]:.3g}] rad × μ ∈ [{self.mus[0]:g}, {self.mus[-1]:g}] "
            f"({self.possible.size} points): a lean rests at {100 * self.possible.mean():.1f} %; the draft's printed "
            f"condition says 'cannot lean' where it can at {100 * wrong.mean():.1f} % and allows one that cannot at "
            f"{100 * miss.mean():.1f} %"])

    def to_dict(self) -> dict:
        """JSON-ready: the parameters, the bodies' poses, the analysis (:meth:`RestAnalysis.to_dict`) and the grids."""
        from ..serial import json_ready

        return json_ready({"part_name": self.part_name, "alpha": self.alpha, "beta_show": self.beta_show,
                           "mu_show": self.mu_show, "length": self.length, "h": self.h, "bodies": _bodies(self.bodies),
                           "analysis": self.analysis.to_dict(), "betas": self.betas, "mus": self.mus,
                           "possible": self.possible, "drafts_no_lean": self.drafts_no_lean})

    def plot(self):
        """The Fig. 13 analogue (:func:`throwmap.viz.statics.lean_figure`); returns the Figure."""
        from ..viz.statics import lean_figure

        return lean_figure(self)


@dataclass(frozen=True, slots=True, eq=False)
class PartialData:
    """Fig. 14's data: the partial assembly at ``gamma_show`` (rad) with arm μ ``mu_show`` on an arm at ``alpha``
    (rad), ``length`` and ``h`` (m): its ``bodies`` and their :class:`RestAnalysis`; over ``gammas_deg`` × ``mus``
    where it rests (``rests``, LP, ``(len(gammas_deg), len(mus))``) and the arm μ each γ needs (``mu_needed``)."""

    alpha: float
    gamma_show: float
    mu_show: float
    length: float
    h: float
    bodies: tuple
    analysis: RestAnalysis
    gammas_deg: np.ndarray
    mus: np.ndarray
    rests: np.ndarray
    mu_needed: np.ndarray

    def table(self) -> str:
        """The shown assembly's verdict, then per γ the arm μ needed."""
        a = self.analysis
        lines = [f"partial assembly at γ = {math.degrees(self.gamma_show):.3g}°, α = {math.degrees(self.alpha):.3g}°, "
                 f"μ = {self.mu_show:g}: {'rests' if a.can_rest else 'cannot rest'} (needs μ ≥ {a.mu_needed:.4g})",
                 "| γ (deg) | arm μ needed (LP) |", "|---|---|"]
        lines += [f"| {g:g} | {m:.4g} |" for g, m in zip(self.gammas_deg, self.mu_needed)]
        return "\n".join(lines)

    def to_dict(self) -> dict:
        """JSON-ready: the parameters, the bodies' poses, the analysis and the grids (inf μ needed as null)."""
        from ..serial import json_ready

        return json_ready({"alpha": self.alpha, "gamma_show": self.gamma_show, "mu_show": self.mu_show,
                           "length": self.length, "h": self.h, "bodies": _bodies(self.bodies),
                           "analysis": self.analysis.to_dict(), "gammas_deg": self.gammas_deg, "mus": self.mus,
                           "rests": self.rests, "mu_needed": self.mu_needed})

    def plot(self):
        """The Fig. 14 analogue (:func:`throwmap.viz.statics.partial_figure`); returns the Figure."""
        from ..viz.statics import partial_figure

        return partial_figure(self)


def lean_data(part, *, alpha: float, beta_show: float, mu_show: float, length: float = 0.3, h: float = -0.01,
              mu_max: float = 4.0, n_beta: int = 300, n_mu: int = 200) -> LeanData:
    """Fig. 13's data (see the module docstring)."""
    bodies, cs = leaning_bodies(part, beta_show, length=length, h=h, mu_arm=mu_show)
    a, b, _ = edge_frame_cm(part)
    betas = np.linspace(0.005, 1.5, n_beta)
    mus = np.linspace(0.0, mu_max, n_mu)
    B, M = np.meshgrid(betas, mus)
    return LeanData(part.name, alpha, beta_show, mu_show, length, h, tuple(bodies),
                    analyse_rest(bodies, cs, alpha=alpha), betas, mus, np.asarray(lean_possible(a, b, B, alpha, M)),
                    np.asarray(drafts_no_lean(a, b, B, alpha, M)))


def partial_data(part, *, alpha: float, gamma_show: float, mu_show: float = 1.0, length: float = 0.5,
                 h: float = -0.01, gammas_deg=None, mus=None) -> PartialData:
    """Fig. 14's data (see the module docstring)."""
    bodies, cs = partial_assembly(part, gamma_show, length=length, h=h, mu_arm=mu_show)
    g = np.linspace(-29.5, -0.5, 30) if gammas_deg is None else np.asarray(gammas_deg, float)
    m = np.linspace(0.0, 0.6, 25) if mus is None else np.asarray(mus, float)
    reg = partial_region(part, np.radians(g), m, alpha=alpha, length=length)
    return PartialData(alpha, gamma_show, mu_show, length, h, tuple(bodies), analyse_rest(bodies, cs, alpha=alpha), g,
                       m, reg.rests, reg.mu_needed)
