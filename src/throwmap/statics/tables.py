"""The statics tables: closed form against the general LP against the engine (Figs. 13, 14).

:func:`lean_table` draws random leans (β, α, μ) of the draft's triangle against a frictionless wall and
answers "can it lean?" three ways: the complete closed form (:func:`~throwmap.statics.leaning.lean_possible`),
the LP of :func:`~throwmap.statics.rest.analyse_rest`, and the engine (:func:`~throwmap.statics.engine_check.engine_rest`:
placed and left for 1 s); it also counts where the draft's printed condition calls a lean impossible
that is, and the reverse (a :class:`LeanTable`). :func:`partial_table` does the same for Fig. 14's partial
assembly over γ: the arm friction it needs (LP), whether it rests at the chosen μ, and whether it stays in the
engine (a :class:`PartialTable`). Both are results with ``table()``, ``to_dict()`` and ``.plot()``. Units: m, rad.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

from ..budget import Limits, check_count, guard_work
from ..rng import as_generator
from .assembly import _arm_mu_needed, partial_assembly
from .engine_check import engine_rest
from .leaning import drafts_no_lean, edge_frame_cm, lean_possible, leaning_bodies
from .rest import analyse_rest

__all__ = ["LeanTable", "PartialTable", "lean_table", "partial_table"]

H = -0.01
"""Arm surface height of the checks, m (the project's default regime)."""


@dataclass(frozen=True, slots=True)
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

    def table(self) -> str:
        """:meth:`lines` as text."""
        return "\n".join(self.lines())

    def to_dict(self) -> dict:
        """The counts, and per lean ``beta_rad``, ``alpha_rad``, ``mu``, ``closed_form``, ``lp``, ``engine_stayed``,
        ``engine_moved_m``, ``draft_no_lean``, ``engine_status``, ``cap_bound`` (JSON-ready: μ = ∞ as null)."""
        from ..serial import json_ready

        keys = ("beta_rad", "alpha_rad", "mu", "closed_form", "lp", "engine_stayed", "engine_moved_m", "draft_no_lean",
                "engine_status", "cap_bound")
        return json_ready({"n": self.n, "seed": self.seed, "closed_vs_lp": self.closed_vs_lp,
                           "lp_vs_engine": self.lp_vs_engine, "engine_refused": self.engine_refused,
                           "cap_bound": self.cap_bound, "lp_vs_engine_free": self.lp_vs_engine_free,
                           "draft_wrong_no_lean": self.draft_wrong_no_lean, "draft_misses_fall": self.draft_misses_fall,
                           "rows": [dict(zip(keys, r)) for r in self.rows]})

    def plot(self, ax=None):
        """How often the answers agree (:func:`throwmap.viz.statics.plot_lean_table`)."""
        from ..viz.statics import plot_lean_table

        return plot_lean_table(self, ax=ax)


@dataclass(frozen=True, slots=True)
class PartialTable:
    """The partial assembly over γ at arm μ ``mu`` on an arm at ``alpha_deg`` (degrees): ``rows`` of
    ``(γ deg, arm μ needed (LP), rests at μ (LP), engine stayed (None: not checked), engine moved m, status)``."""

    alpha_deg: float
    mu: float
    rows: tuple

    def table(self) -> str:
        """The rows as Markdown (the engine's movement in mm)."""
        lines = ["| γ (deg) | arm μ needed (LP) | rests at μ (LP) | stays in the engine (1 s) | engine moved (mm) |",
                 "|---|---|---|---|---|"]
        for g, need, lp, stayed, moved, status in self.rows:
            st = "—" if stayed is None else ("yes" if stayed else f"no ({status})")
            lines.append(f"| {g} | {need:.4f} | {'yes' if lp else 'no'} | {st} | {moved * 1e3:.3g} |")
        return "\n".join(lines)

    def to_dict(self) -> dict:
        """``alpha_deg``, ``mu`` and per γ ``gamma_deg``, ``mu_needed``, ``rests_lp``, ``engine_stayed``,
        ``engine_moved_m``, ``status`` (JSON-ready)."""
        from ..serial import json_ready

        keys = ("gamma_deg", "mu_needed", "rests_lp", "engine_stayed", "engine_moved_m", "status")
        return json_ready({"alpha_deg": self.alpha_deg, "mu": self.mu, "rows": [dict(zip(keys, r)) for r in self.rows]})

    def plot(self, ax=None):
        """The μ needed against γ with the engine's verdicts (:func:`throwmap.viz.statics.plot_partial_table`)."""
        from ..viz.statics import plot_partial_table

        return plot_partial_table(self, ax=ax)


ROW_BYTES = 400
"""Memory of one lean-table row (bytes, a tuple of ten numbers), for the work guard."""


def lean_table(part, *, n: int = 100, seed: int = 0, length: float = 0.3, engine: bool = True,
               progress=None, limits: Limits | None = None) -> LeanTable:
    """The lean table (see the module docstring).

    Work guard (``limits``, :mod:`throwmap.budget`): ``n`` rows' memory, and their time from the first
    row, timed now; above the limits the table is refused with one line on ``n``."""
    from ..system.fixtures import Wall

    n = check_count("n", n, minimum=1)
    rng = as_generator(seed)
    a, b, c = edge_frame_cm(part)
    rows = []

    def first_row_seconds():
        t0 = time.perf_counter()
        rows.append(_lean_row(part, rng, a, b, c, length, engine, Wall))
        return time.perf_counter() - t0

    guard_work("lean table", "n", n, ROW_BYTES, limits, throws_per_config=1.0, timer=first_row_seconds,
               hint="fewer leans (--n)", unit="leans")
    for i in range(n):
        if i >= len(rows):
            rows.append(_lean_row(part, rng, a, b, c, length, engine, Wall))
        if progress is not None:
            progress(i + 1, n)
    from .engine_check import REFUSED

    ok_engine = [r for r in rows if r[8] not in REFUSED and r[8] != "skipped"]
    free = [r for r in ok_engine if not r[9]]
    return LeanTable(n, seed, sum(r[3] == r[4] for r in rows), sum(r[4] == r[5] for r in ok_engine),
                     n - len(ok_engine) if engine else n, sum(r[9] for r in ok_engine), sum(r[4] == r[5] for r in free),
                     sum(r[7] and r[4] for r in rows),
                     sum((not r[7]) and (not r[4]) for r in rows), tuple(rows))


def _lean_row(part, rng, a, b, c, length, engine, Wall) -> tuple:
    """One random lean (β, α, μ) of the lean table: closed form, LP, engine (see the module docstring)."""
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
    return (beta, alpha, mu, closed, lp, stayed, moved, bool(drafts_no_lean(a, b, beta, alpha, mu)), status, capped)


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
                  length: float = 0.5, engine: bool = True) -> PartialTable:
    """The :class:`PartialTable` of Fig. 14: rows ``(γ deg, arm μ needed, rests at μ (LP), engine stayed, engine
    moved m, status)``."""
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
    return PartialTable(float(alpha_deg), float(mu), tuple(out))
