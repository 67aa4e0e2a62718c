"""The statics tables of issue 13: closed form against the general LP against the engine (Figs. 13, 14).

:func:`lean_table` draws random leans (β, α, μ) of the draft's triangle against a frictionless wall and
answers "can it lean?" three ways: the complete closed form (:func:`~throwmap.statics.leaning.lean_possible`),
the LP of :func:`~throwmap.statics.rest.analyse_rest`, and the engine (:func:`~throwmap.statics.engine_check.engine_rest`:
placed and left for 1 s); it also counts where the draft's printed condition calls a lean impossible
that is, and the reverse. :func:`partial_table` does the same for Fig. 14's partial assembly over γ:
the arm friction it needs (LP), whether it rests at the chosen μ, and whether it stays in the engine.
Units: m, rad.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..rng import as_generator
from .assembly import _arm_mu_needed, partial_assembly
from .engine_check import engine_rest
from .leaning import drafts_no_lean, edge_frame_cm, lean_possible, leaning_bodies
from .rest import analyse_rest

__all__ = ["LeanTable", "lean_table", "partial_table"]

H = -0.01
"""Arm surface height of the checks, m (the project's default regime)."""


@dataclass(frozen=True)
class LeanTable:
    """Counts over ``n`` random leans; ``rows`` keep (β, α, μ, closed form, LP, engine stayed, engine moved m,
    draft says no lean, engine status, cap-bound). A lean is *cap-bound* when the LP says it rests but the
    friction it needs exceeds pymunk's per-contact cap 0.7 K_nn/|K_nt| at the arm contact
    (:mod:`throwmap.engine.pymunk.friction`): there the engine cannot hold it, whatever μ."""

    n: int
    seed: int
    closed_vs_lp: int
    lp_vs_engine: int
    engine_refused: int
    cap_bound: int
    lp_vs_engine_free: int
    draft_wrong_no_lean: int
    draft_misses_fall: int
    rows: tuple

    def lines(self) -> list[str]:
        n = self.n
        head = [f"random leans of the draft's triangle against a frictionless wall (n = {n}, seed {self.seed}; "
                f"β ∈ (0.02, 1.5) rad, α ∈ [−30°, 10°], μ ∈ {{0.3, 0.6, 1, 2, ∞}}):",
                f"  closed form (i)-(iii) = LP: {self.closed_vs_lp}/{n}"]
        tail = [f"  the draft's printed condition says 'cannot lean' where it can: {self.draft_wrong_no_lean}/{n}; "
                f"it allows a lean that cannot rest (fall back or foot slides away): {self.draft_misses_fall}/{n}"]
        if self.rows and all(r[8] == "skipped" for r in self.rows):
            return head + ["  LP = engine: not checked (engine off)"] + tail
        return head + [f"  LP = engine (stays put 1 s, < 1 mm and < 0.01 rad): {self.lp_vs_engine}/{n - self.engine_refused}"
                f" (engine runs refused: {self.engine_refused}); cap-bound (the lean needs more friction than the "
                f"engine's cap gives): {self.cap_bound}; LP = engine without them: {self.lp_vs_engine_free}/"
                f"{n - self.engine_refused - self.cap_bound}"] + tail


def lean_table(part, *, n: int = 100, seed: int = 0, length: float = 0.3, engine: bool = True,
               progress=None) -> LeanTable:
    """The lean table (see the module docstring)."""
    from ..system.fixtures import Wall

    rng = as_generator(seed)
    a, b, c = edge_frame_cm(part)
    rows = []
    for i in range(n):
        beta = float(rng.uniform(0.02, 1.5))
        alpha = float(rng.uniform(math.radians(-30), math.radians(10)))
        mu = float(rng.choice([0.3, 0.6, 1.0, 2.0, math.inf]))
        bodies, cs = leaning_bodies(part, beta, length=length, h=H, mu_arm=mu)
        closed = bool(lean_possible(a, b, beta, alpha, mu))
        lp = analyse_rest(bodies, cs, alpha=alpha, detail=False).can_rest
        if engine:
            er = engine_rest(bodies, h=H, mu_arm=mu, length=length, wall=Wall(c, mu=0.0), alpha=alpha)
            stayed, moved, status = er.stayed, max(er.moved), er.status
        else:
            stayed, moved, status = None, math.nan, "skipped"
        capped = lp and _cap_bound(part, bodies, cs, alpha)
        rows.append((beta, alpha, mu, closed, lp, stayed, moved, bool(drafts_no_lean(a, b, beta, alpha, mu)), status,
                     capped))
        if progress is not None:
            progress(i + 1, n)
    from .engine_check import REFUSED

    ok_engine = [r for r in rows if r[8] not in REFUSED and r[8] != "skipped"]
    free = [r for r in ok_engine if not r[9]]
    return LeanTable(n, seed, sum(r[3] == r[4] for r in rows), sum(r[4] == r[5] for r in ok_engine),
                     n - len(ok_engine) if engine else n, sum(r[9] for r in ok_engine), sum(r[4] == r[5] for r in free),
                     sum(r[7] and r[4] for r in rows),
                     sum((not r[7]) and (not r[4]) for r in rows), tuple(rows))


def _cap_bound(part, bodies, contacts, alpha) -> bool:
    """Whether the friction the lean needs at its arm contact exceeds the engine's cap there — only where the engine
    caps (``friction.EXACT`` off): with the exact high-friction solve (one part) no lean is cap-bound."""
    from ..engine.pymunk import friction
    from ..engine.pymunk.friction import CAP

    if friction.EXACT:
        return False

    need = analyse_rest(bodies, contacts, alpha=alpha).mu_needed
    px, py = contacts[0].point
    rx, ry = px - bodies[0].x, py - bodies[0].y
    cap = CAP * (part.radius_of_gyration ** 2 + rx * rx) / abs(rx * ry) if rx * ry != 0 else math.inf
    return need > cap


def partial_table(part, gammas_deg=(-29, -25, -20, -15, -10, -5, -1), *, alpha_deg: float = -10.0, mu: float = 1.0,
                  length: float = 0.5, engine: bool = True) -> list[tuple]:
    """Rows ``(γ deg, arm μ needed, rests at μ (LP), engine stayed, engine moved m, status)`` for Fig. 14."""
    from ..system.fixtures import Wall

    alpha = math.radians(alpha_deg)
    out = []
    for g in gammas_deg:
        gamma = math.radians(g)
        need = _arm_mu_needed(part, gamma, alpha, 0.0, 0.0, length)
        bodies, cs = partial_assembly(part, gamma, length=length, h=H, mu_arm=mu)
        lp = analyse_rest(bodies, cs, alpha=alpha, detail=False).can_rest
        if engine:
            er = engine_rest(bodies, h=H, mu_arm=mu, length=length, wall=Wall(0.2, mu=0.0), alpha=alpha)
            out.append((g, need, lp, er.stayed, max(er.moved), er.status))
        else:
            out.append((g, need, lp, None, math.nan, "skipped"))
    return out
