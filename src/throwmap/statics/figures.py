"""What the Fig. 13 and Fig. 14 analogues show, computed (:mod:`throwmap.viz.statics` draws it).

:func:`lean_data`: the leaning part at one β with its contact forces (LP), and over a (β, μ) grid at the
arm's α the complete lean condition and the draft's printed one. :func:`partial_data`: the partial assembly at
one γ with its forces, and over a (γ, μ) grid where it rests (LP) with the arm friction each γ needs.
Units: m, rad (γ also in degrees for the axis).
"""

from __future__ import annotations

import numpy as np

from .assembly import partial_assembly, partial_region
from .leaning import drafts_no_lean, edge_frame_cm, lean_possible, leaning_bodies
from .rest import analyse_rest

__all__ = ["lean_data", "partial_data"]


def lean_data(part, *, alpha: float, beta_show: float, mu_show: float, length: float = 0.3, h: float = -0.01,
              mu_max: float = 4.0, n_beta: int = 300, n_mu: int = 200) -> dict:
    """Fig. 13's data (see the module docstring)."""
    bodies, cs = leaning_bodies(part, beta_show, length=length, h=h, mu_arm=mu_show)
    a, b, _ = edge_frame_cm(part)
    betas = np.linspace(0.005, 1.5, n_beta)
    mus = np.linspace(0.0, mu_max, n_mu)
    B, M = np.meshgrid(betas, mus)
    return {"part_name": part.name, "alpha": alpha, "beta_show": beta_show, "mu_show": mu_show, "length": length,
            "h": h, "bodies": bodies, "analysis": analyse_rest(bodies, cs, alpha=alpha), "betas": betas, "mus": mus,
            "possible": lean_possible(a, b, B, alpha, M), "drafts_no_lean": drafts_no_lean(a, b, B, alpha, M)}


def partial_data(part, *, alpha: float, gamma_show: float, mu_show: float = 1.0, length: float = 0.5,
                 h: float = -0.01, gammas_deg=None, mus=None) -> dict:
    """Fig. 14's data (see the module docstring)."""
    bodies, cs = partial_assembly(part, gamma_show, length=length, h=h, mu_arm=mu_show)
    g = np.linspace(-29.5, -0.5, 30) if gammas_deg is None else np.asarray(gammas_deg, float)
    m = np.linspace(0.0, 0.6, 25) if mus is None else np.asarray(mus, float)
    reg = partial_region(part, np.radians(g), m, alpha=alpha, length=length)
    return {"alpha": alpha, "gamma_show": gamma_show, "mu_show": mu_show, "length": length, "h": h, "bodies": bodies,
            "analysis": analyse_rest(bodies, cs, alpha=alpha), "gammas_deg": g, "mus": m, "rests": reg["rests"],
            "mu_needed": reg["mu_needed"]}
