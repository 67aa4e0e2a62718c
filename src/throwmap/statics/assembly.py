"""Two same-handed right triangles assembling into a rectangle at the wall (paper Sec. VI, Figs. 12(b), 14).

Placement (arm frame, wall face at x = L, arm surface y = h). Part *a* rests on its longer leg (length
ℓ, the "intermediate-length edge") with its right angle towards the joint; part *b* is *a* turned by
180° (same-handed, not mirrored). Assembled, they fill the rectangle [L − ℓ, L] × [h, h + s] (s the
shorter leg) and share the hypotenuse as its diagonal. A partial assembly (Fig. 14) has *b* turned
by γ ∈ (−θ, 0) about its lower vertex at the wall's foot (θ = atan(s/ℓ), 30° for the draft's
triangle; γ = −θ is assembled, γ = 0 is *b* flat on its hypotenuse), its far vertex resting on *a*'s
hypotenuse, and *a* slid under it as far as that contact puts it. :func:`partial_assembly` builds
the two :class:`~throwmap.statics.rest.Body` and their contacts (arm, wall, part–part) for
:func:`~throwmap.statics.rest.analyse_rest`; :func:`partial_region` maps where the partial assembly
can rest over (γ, μ) and the friction it needs. Units: m, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError
from ..system.system import check_alpha
from .contacts import find_contacts
from .rest import Body, analyse_rest, least_mu

__all__ = ["legs", "assembled_pair", "partial_assembly", "partial_region", "PartialRegion"]


def legs(part) -> tuple[float, float]:
    """``(ℓ, s)``: the longer and shorter leg (m) of a right triangle given with its right angle at the
    origin and its legs along +x (the longer) and +y, as :func:`throwmap.triangle_30_60_90` builds it."""
    v = np.asarray(part.vertices, dtype=float)
    if len(v) != 3 or len(part.point_masses) or not any(np.allclose(p, 0) for p in v):
        raise InvalidStateError("part", "must be a uniform right triangle with its right angle at (0, 0)")
    xs = [p for p in v if abs(p[1]) < 1e-12 and p[0] > 0]
    ys = [p for p in v if abs(p[0]) < 1e-12 and p[1] > 0]
    if not xs or not ys or xs[0][0] < ys[0][1]:
        raise InvalidStateError("part", "must have its longer leg along +x and its shorter along +y")
    return float(xs[0][0]), float(ys[0][1])


def assembled_pair(part, *, length: float, h: float = 0.0) -> tuple[Body, Body]:
    """Parts *a* and *b* assembled into the rectangle [L − ℓ, L] × [h, h + s]."""
    ell, s = legs(part)
    cx, cy = part.com
    a = Body(part, length - ell + cx, h + cy, 0.0)
    centre = np.array([length - ell / 2, h + s / 2])
    cb = 2 * centre - a.com
    return a, Body(part, float(cb[0]), float(cb[1]), math.pi)


def partial_assembly(part, gamma: float, *, length: float, h: float = 0.0, mu_arm: float, mu_wall: float = 0.0,
                     mu_parts: float = 0.0, tol: float = 1e-9):
    """``(bodies, contacts)`` of the partial assembly at ``gamma`` (rad, −θ ≤ γ ≤ 0; see the module docstring)."""
    ell, s = legs(part)
    theta = math.atan2(s, ell)
    if not -theta - 1e-12 <= gamma <= 1e-12:
        raise InvalidStateError("gamma", f"must be in [−{theta:.6g}, 0] rad (−θ assembled, 0 flat), got {gamma!r}")
    a0, b0 = assembled_pair(part, length=length, h=h)
    d = gamma + theta  # b turned about the wall's foot (L, h) from its assembled pose
    c, sn = math.cos(d), math.sin(d)
    pivot = np.array([length, h])
    rb = b0.com - pivot
    cb = pivot + np.array([c * rb[0] - sn * rb[1], sn * rb[0] + c * rb[1]])
    b = Body(part, float(cb[0]), float(cb[1]), math.pi + d)
    far = np.array([-ell, s])  # b's far hypotenuse vertex relative to the pivot, assembled
    T = pivot + np.array([c * far[0] - sn * far[1], sn * far[0] + c * far[1]])
    xa = T[0] - ell * (1.0 - (T[1] - h) / s)  # a's right angle, so that its hypotenuse passes through T
    a = Body(part, float(xa + part.com[0]), float(h + part.com[1]), 0.0)
    from ..system.fixtures import Wall

    contacts = find_contacts((a, b), h=h, mu_arm=mu_arm, length=length, wall=Wall(height=2 * s, mu=mu_wall),
                             mu_wall=mu_wall, mu_parts=mu_parts, tol=max(tol, 1e-9 * ell))
    return (a, b), contacts


@dataclass(frozen=True, slots=True, eq=False)
class PartialRegion:
    """Where the partial assembly rests (Fig. 14): ``gamma`` (rad) × ``mu`` (arm μ) → ``rests`` (bool,
    ``(len(gamma), len(mu))``, LP), and ``mu_needed`` per γ (the least arm μ that holds it; inf: none), with the
    arm's rest angle ``alpha`` (rad), the wall's and the parts' μ."""

    gamma: np.ndarray
    mu: np.ndarray
    rests: np.ndarray
    mu_needed: np.ndarray
    alpha: float = 0.0
    mu_wall: float = 0.0
    mu_parts: float = 0.0

    def table(self) -> str:
        """Per γ (degrees): the arm μ needed and the share of the μ grid where it rests."""
        lines = ["| γ (deg) | arm μ needed (LP) | rests at μ of the grid |", "|---|---|---|"]
        for i, g in enumerate(self.gamma):
            ok = ", ".join(f"{m:g}" for m in self.mu[self.rests[i]]) or "none"
            lines.append(f"| {math.degrees(float(g)):.4g} | {float(self.mu_needed[i]):.4g} | {ok} |")
        return "\n".join(lines)

    def to_dict(self) -> dict:
        """``{"gamma", "mu", "rests", "mu_needed"}`` as lists (rad; inf μ needed as null), with ``alpha``,
        ``mu_wall``, ``mu_parts``."""
        from ..serial import json_ready

        return json_ready({"gamma": self.gamma, "mu": self.mu, "rests": self.rests, "mu_needed": self.mu_needed,
                           "alpha": self.alpha, "mu_wall": self.mu_wall, "mu_parts": self.mu_parts})

    def plot(self, ax=None):
        """The region over (γ, μ) and the μ needed against γ (:func:`throwmap.viz.statics.plot_partial_region`)."""
        from ..viz.statics import plot_partial_region

        return plot_partial_region(self, ax=ax)


def partial_region(part, gammas, mus, *, alpha: float, mu_wall: float = 0.0, mu_parts: float = 0.0,
                   length: float = 0.5) -> PartialRegion:
    """Where the partial assembly rests over ``gammas`` (rad) × ``mus`` (arm μ), and the least arm μ that holds it at
    each γ (with the wall and part–part μ as given): a :class:`PartialRegion`."""
    alpha = check_alpha(alpha, "alpha")
    gammas = np.asarray(gammas, dtype=float)
    mus = np.asarray(mus, dtype=float)
    if not np.all(np.isfinite(gammas)):
        raise InvalidStateError("gammas", "must be finite angles (rad)")
    if np.any(np.isnan(mus)) or np.any(mus < 0):
        raise InvalidStateError("mus", "must be friction coefficients ≥ 0 (inf: no slip)")
    rests = np.zeros((len(gammas), len(mus)), dtype=bool)
    need = np.zeros(len(gammas))
    for i, gmm in enumerate(gammas):
        for j, mu in enumerate(mus):
            bodies, cs = partial_assembly(part, float(gmm), length=length, mu_arm=float(mu), mu_wall=mu_wall,
                                          mu_parts=mu_parts)
            rests[i, j] = analyse_rest(bodies, cs, alpha=alpha, detail=False).can_rest
        need[i] = _arm_mu_needed(part, float(gmm), alpha, mu_wall, mu_parts, length)
    return PartialRegion(gammas, mus, rests, need, float(alpha), float(mu_wall), float(mu_parts))


def _arm_mu_needed(part, gamma, alpha, mu_wall, mu_parts, length) -> float:
    """The least arm μ (others fixed) that holds the partial assembly at ``gamma`` (:func:`least_mu`; inf if none)."""

    def ok(mu):
        bodies, cs = partial_assembly(part, gamma, length=length, mu_arm=mu, mu_wall=mu_wall, mu_parts=mu_parts)
        return analyse_rest(bodies, cs, alpha=alpha, detail=False).can_rest

    return least_mu(ok, rel=1e-6, cap=1e6)
