"""The feeder search: screened candidates verified in the engine, with an honest verdict.

:func:`design_feeder` screens the candidates (:func:`throwmap.feeder.screen.screen`, exact impulse model),
then takes them widest window first and verifies each in the engine with the feeding experiment
(``feed``, closed variant: drops from random poses, the recoil arm with ω jitter, μ spread; see
:mod:`throwmap.experiments.feed`): first ``n_pre`` trials (a candidate with fewer than 90 % successes
is dropped), then ``n_verify`` trials, and, where those reach ``goal``, an independent rerun of
``n_verify`` trials with another seed that must land inside the first run's Wilson 95 % interval and
reach ``goal`` too. The first candidate that passes is the feeder; none passing within the budget is
``success`` False with the evidence (the screen's reason, or the best rate reached and by whom).

Every candidate tried is kept in ``out``: its files in ``out/candidates/<k>/`` and its trials in the
runs' folders there, so a rerun of the same search resumes (stored trials are not run again).
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

from ..budget import check_count
from ..errors import InvalidStateError, shown
from ..io.files import atomic_write_text
from ..system.part import Part
from .files import feeder_files
from .screen import DEFAULT_DEPTHS, DEFAULT_HS, DEFAULT_OMEGAS, Candidate, Screen, screen

__all__ = ["Tried", "FeederSearch", "VerifyPlan", "design_feeder", "GOAL", "PRE_SHARE"]

GOAL = 0.95
"""The success rate a feeder must reach in the engine (the draft's hardware fed 19 of 20 = 95 %)."""
PRE_SHARE = 0.9
"""The share of the first ``n_pre`` trials a candidate must feed to be verified further."""


@dataclass(frozen=True, slots=True)
class Tried:
    """One candidate verified in the engine: its index ``k`` in the screen's ranking, the ``candidate``, the
    ``runs`` made (each ``{"n", "successes", "ci95", "seed", "failures"}``) and the ``verdict`` (``"fed"``,
    ``"dropped after the first trials"``, ``"below the goal"``, ``"rerun disagrees"``)."""

    k: int
    candidate: Candidate
    runs: tuple
    verdict: str

    def to_dict(self) -> dict:
        return {"k": self.k, "candidate": self.candidate.to_dict(), "runs": list(self.runs), "verdict": self.verdict}


@dataclass(frozen=True, slots=True)
class FeederSearch:
    """The search's result: ``success`` (a verified feeder), its ``side``, ``config`` (path of ``feeder.toml``; None
    without one), ``verified`` and ``rerun`` (the two full runs: ``{"n", "successes", "ci95", "seed", …}``),
    ``predicted`` (the screen's exact-model window of the fed candidate), ``time_s``, ``reason`` (why none,
    when ``success`` is False), ``tried`` (every candidate verified, in order), ``screen`` and every
    ``assumption`` (arm, jitter, materials, goal)."""

    success: bool
    side: int | None
    config: str | None
    verified: dict | None
    rerun: dict | None
    predicted: dict | None
    time_s: float
    reason: str
    tried: tuple
    screen: Screen = field(repr=False)
    assumptions: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        out = {"success": self.success, "side": self.side, "config": self.config, "verified": self.verified,
               "rerun": self.rerun, "predicted": self.predicted, "time_s": self.time_s,
               "assumptions": self.assumptions, "tried": [t.to_dict() for t in self.tried]}
        if not self.success:
            out["reason"] = self.reason
        return out

    def summary(self) -> str:
        if self.success:
            v = self.verified
            return (f"feeder found: side {self.side}, {v['successes']}/{v['n']} fed "
                    f"(Wilson 95 % [{100 * v['ci95'][0]:.1f}, {100 * v['ci95'][1]:.1f}] %), rerun "
                    f"{self.rerun['successes']}/{self.rerun['n']}; config {self.config} ({self.time_s:.0f} s)")
        return f"no feeder: {self.reason} ({self.time_s:.0f} s)"


def _run_doc(res) -> dict:
    return {"n": res.n, "successes": res.successes, "ci95": [float(res.ci95[0]), float(res.ci95[1])],
            "seed": res.seed, "failures": dict(res.failures), "rate": res.success_rate}


def _share(value, name: str, hi: float = 1.0) -> float:
    """A finite number in [0, ``hi``] (``hi`` may be ∞), refused on ``name`` otherwise."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (0.0 <= value <= hi) or math.isnan(value):
        raise InvalidStateError(name, f"must be a number in [0, {hi:g}], got {shown(value)}")
    return float(value)


@dataclass(frozen=True, slots=True)
class VerifyPlan:
    """How candidates are verified in the engine: ``n_pre`` trials first (``pre_share`` of them must be fed),
    then ``n_verify`` trials and a rerun of as many (seeds ``seed`` and ``seed + 1``), ``goal`` the success
    rate both must reach, ``workers`` engine processes (0: all cores), ``budget_s`` the wall time (s) after
    which no further candidate is started."""

    n_pre: int = 20
    n_verify: int = 200
    goal: float = GOAL
    pre_share: float = PRE_SHARE
    seed: int = 0
    workers: int = 0
    budget_s: float = 600.0

    def __post_init__(self):
        for name, minimum in (("n_pre", 1), ("n_verify", 1), ("seed", 0), ("workers", 0)):
            check_count(name, getattr(self, name), minimum=minimum)
        _share(self.budget_s, "budget_s", math.inf)
        _share(self.goal, "goal")
        _share(self.pre_share, "pre_share")


def design_feeder(part: Part, out, *, side: int | None = None, mu: float = 1.0, g: float = 9.81, sigma: float = 0.03,
                  mu_rel: float = 0.1, plan: VerifyPlan | None = None, grid: dict | None = None,
                  progress=None) -> FeederSearch:
    """Search a feeder of ``part`` that feeds one side (or ``side``) into a pocket at the arm's end (module docstring).

    ``out``: the folder for every candidate tried and the feeder's ``feeder.toml`` / ``part.toml``; ``mu`` the arm's
    μ (± ``mu_rel`` per trial), ``sigma`` the relative ω jitter, ``g`` m/s²; ``plan`` the engine verification
    (:class:`VerifyPlan`; None: its defaults); ``grid`` the screen's ``omegas``, ``hs``, ``depths``
    (:func:`~throwmap.feeder.screen.screen`; None: its defaults); ``progress(stage, done, total)``.
    """
    from ..experiments.base import read_config
    from ..experiments.feed import Feed
    from ..experiments.runner import run_experiment

    t0 = time.perf_counter()
    if not isinstance(part, Part):
        raise InvalidStateError("part", f"must be a Part, got {type(part).__name__}")
    plan = VerifyPlan() if plan is None else plan
    if not isinstance(plan, VerifyPlan):
        raise InvalidStateError("plan", f"must be a VerifyPlan, got {type(plan).__name__}")
    grid = {"omegas": DEFAULT_OMEGAS, "hs": DEFAULT_HS, "depths": DEFAULT_DEPTHS, **(grid or {})}
    if set(grid) - {"omegas", "hs", "depths"}:
        raise InvalidStateError("grid", f"takes omegas, hs and depths, got {sorted(grid)}")
    n_pre, n_verify, goal, pre_share = plan.n_pre, plan.n_verify, plan.goal, plan.pre_share
    seed, workers, budget_s = plan.seed, plan.workers, plan.budget_s
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InvalidStateError("out", f"{str(out)!r} is a file, not a folder")
    assumptions = {"arm": {"mu": mu, "mu_rel": mu_rel, "g_m_s2": g}, "omega_jitter_rel": sigma,
                   "realisation": "recoil (3°, ζ = 0.2)", "pocket": "end wall μ 0, floor the arm's μ",
                   "drops": "2–10 cm above the arm, any pose, anywhere over it", "goal": goal,
                   "screen": "exact impulse model (rigid_body), window over ω(1 − σ) … ω(1 + 3σ)"}
    scr = screen(part, mu=mu, g=g, sides=None if side is None else (side,), **grid, sigma=sigma,
                 progress=None if progress is None else (lambda d, t: progress("screen", d, t)))
    ranked = [(k, c) for k, c in enumerate(scr.candidates) if c.window is not None]
    tried: list[Tried] = []

    def result(success, reason="", fed=None, verified=None, rerun=None):
        return FeederSearch(success, fed.side if fed else None, str(out / "feeder.toml") if fed else None,
                            verified, rerun, {"window_m": list(fed.window), "width_m": fed.width} if fed else None,
                            time.perf_counter() - t0, reason, tuple(tried), scr, assumptions)

    if not ranked:
        return result(False, scr.reason())
    out.mkdir(parents=True, exist_ok=True)
    log = out / "candidates.jsonl"
    for k, c in ranked:
        if time.perf_counter() - t0 > budget_s:
            break
        here = out / "candidates" / str(k)
        path = feeder_files(c, scr, here, mu_rel=mu_rel)
        cfg = read_config(Feed(), path)
        runs = []

        def run(n, s, name):
            cb = None if progress is None else (lambda d, t: progress(f"candidate {k}: {name}", d, t))
            res = run_experiment("feed", cfg, n=n, seed=s, workers=workers, out=here / name, progress=cb)
            runs.append(_run_doc(res))
            return res

        pre = run(n_pre, seed, "first")
        verdict = "dropped after the first trials"
        verified = rerun = None
        if pre.successes >= pre_share * n_pre:
            full = run(n_verify, seed, "verify")
            verdict = "below the goal"
            if full.success_rate >= goal:
                again = run(n_verify, seed + 1, "rerun")
                lo, hi = full.ci95
                verdict = ("fed" if again.success_rate >= goal and lo <= again.success_rate <= hi
                           else "rerun disagrees")
                verified, rerun = runs[-2], runs[-1]
        tried.append(Tried(k, c, tuple(runs), verdict))
        with log.open("a", encoding="utf-8") as fh:
            fh.write(json.dumps(tried[-1].to_dict()) + "\n")
        if verdict == "fed":
            for name in ("feeder.toml", "part.toml"):
                atomic_write_text(out / name, (here / name).read_text(encoding="utf-8"))
            return result(True, fed=c, verified=verified, rerun=rerun)
    best = max(tried, key=lambda t: max(r["rate"] for r in t.runs), default=None)
    if best is None:
        why = f"the budget ({budget_s:g} s) ran out before any of {len(ranked)} screened candidates was verified"
    else:
        rate = max(r["rate"] for r in best.runs)
        why = (f"none of the {len(tried)} candidates verified in the engine (of {len(ranked)} screened with a window "
               f"on sides {list(scr.separable())}) fed ≥ {100 * goal:g} %: the best, side {best.candidate.side} at "
               f"ω = {best.candidate.omega:g} rad/s, h = {best.candidate.h:g} m, reached {100 * rate:.1f} % "
               f"({best.verdict})")
    return result(False, why)
