"""The feeder search: the exact-model screen, the first trials, engine verification, an honest verdict.

:func:`design_feeder` searches the family of :mod:`throwmap.feeder.family` (the part alone, or with a
lead weight placed for a target side) over a grid of release rates ω and arm heights h, in stages of rising cost:

1. **exact screen** — every (variant, ω, h) on the exact impulse model (:func:`~throwmap.feeder.arrival.arrival`
   with ``model="rigid_body"``, ≈ 0.1 s each): which side arrives first at an end stop, and how often — counted
   where the part reaches the end wall and, separately, where it reaches the pocket's lip (a pocket that sorts by
   releasing wrong sides is caught at the wall, one that jams them at its lip). A candidate's share is its
   *predicted* feed rate;
2. **first trials** — candidates predicted ≥ ``min_predicted`` (then any ≥ :data:`TRY_SHARE`), the best of every
   (variant, side) before any second one, run as the feeding experiment in the engine (``feed``: drops from random
   poses, the recoil arm with ω jitter, μ spread, the pocket itself; see :mod:`throwmap.experiments.feed`):
   ``n_pre`` trials, 5 at a time, stopped as soon as more fail than ``pre_share`` allows (≈ 3 s a candidate
   dropped). The pocket decides which side it holds, which no screen of the plain arm sees (measured: candidates
   the engine's own first-arrival table put at 97–99 % fed 0–73 % in the pocket), so the trials are the screen
   that ranks. ``engine_screen=True`` puts the engine's first-arrival table (5–30 s a candidate,
   :func:`~throwmap.feeder.arrival.screen_table`) between the two, as a filter at ``min_predicted``;
3. **verification** — ``n_verify`` trials, and where those reach ``goal`` an independent rerun of ``n_verify`` trials
   with another seed that must reach ``goal`` too and not fall below the range a new run lands in after the first
   (:func:`~throwmap.experiments.stats.rerun_range`, 95 %; above it only confirms the feed: 200/200 after 199/200);
   then
   ``omega_check`` trials at ω(1 ± :data:`OMEGA_DRIFT`): a feeder clearly below the goal there (Wilson upper end under
   it) is *fragile*, not fed, and the same feeder with ω moved :data:`OMEGA_SHIFT` away from the drift it failed is
   tried next; then, for a part with a lead weight, ``weight_check`` trials with the weight moved
   :data:`WEIGHT_DRIFT_M` each way in x and y: one clearly below the goal is *fragile in the weight's place*, not
   fed. A candidate that passes its first trials but falls short is **refined**: its neighbours (end wall
   ± 1 cm, ω ± 0.25 rad/s, h ± 5 mm) are run next.

The budget is a hard limit: no candidate is started after :data:`START_BY` of it and no trial after its end, or
after ``VerifyPlan.finish_s`` more seconds for a verification or rerun under way (a
candidate whose trials it cuts short gets the verdict "the budget ran out in the …", never "fed"). The first candidate
that passes is the feeder; none passing within the budget is ``success`` False with the evidence (each side's best
share on the screens, the best verified rate and by whom).

Every screened and verified candidate is kept in ``out``: the engine screen (when asked for) in ``out/screen.jsonl``,
each candidate's files and trials in ``out/candidates/<k>-<tag>/`` (``k`` its rank, ``tag`` a hash of the candidate);
a rerun of the same search reads them back instead of computing them again (Ctrl-C loses nothing already written).
"""

from __future__ import annotations

import dataclasses
import itertools
import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..budget import check_count
from ..errors import InvalidStateError, shown
from ..experiments.stats import rerun_range, wilson_interval
from ..io.files import atomic_write_text, make_directory
from ..system.arm import Arm
from ..system.part import Part
from .checks import OMEGA_DRIFT, WEIGHT_DRIFT_M, omega_check, stage_label, weight_check
from .arrival import DROP_X, WALL_X_MAX, Arrival, arrival, arrivals, lip_offset, screen_table
from .family import Variant, weight_variants
from .files import LINING_MU, POCKET_DEPTH_M, feeder_files

__all__ = ["Tried", "FeederSearch", "VerifyPlan", "design_feeder", "evidence", "GOAL", "PRE_SHARE", "OMEGAS", "HS"]

GOAL = 0.95
"""The success rate a feeder must reach in the engine (the draft's hardware fed 19 of 20 = 95 %)."""
PRE_SHARE = 0.9
"""The share of the first ``n_pre`` trials a candidate must feed to be verified further."""
OMEGAS = (3.5, 4.0, 4.5, 5.0, 5.5, 6.0)
"""Release rates searched, rad/s (the draft's arm throws at 3.5–6 rad/s)."""
HS = (-0.03, -0.02, -0.01, 0.0)
"""Arm surface heights searched, m (below or through the joint)."""
TRY_SHARE = 0.5
"""Without the engine screen, exact-screen candidates below ``min_predicted`` but at least this share are run too
(after every one above it): the pocket, not the plain arm's first arrival, decides which side is held."""
FEW_TRIALS_WIDTH = 0.10
"""A verified feeder whose pooled Wilson 95 % interval is wider than this (a quick search's few trials: 5/5 spans
[56.6, 100] %, 366/380 [93.9, 97.8] %) says so in its ``feeder.toml`` and summary."""
START_BY = 0.75
"""No candidate is started after this share of the budget (a verification and its rerun, 2 × 200 trials, take 1–5
minutes on 2 cores). No trial is started after the budget itself: a verification it cuts short is no verdict."""


@dataclass(frozen=True, slots=True)
class Tried:
    """One candidate run in the engine: its index ``k`` in the screen's ranking (``FeederSearch.screened``), the
    screened ``candidate``, the ``runs`` made (each ``{"n", "successes", "ci95", "seed", "failures", "rate",
    "throws_to_capture", "time_s", "new_trials"}``: ``new_trials`` those this search ran, the rest read back — the
    first trials a verification extends, or an earlier run's) and the ``verdict`` (``"fed"``, ``"dropped after the first trials"``,
    ``"below the goal"``, ``"rerun below the goal"``, ``"rerun disagrees"`` (at the goal but below the range a new run
    lands in after the verification), ``"the budget ran out in the …"``) and the drift ``checks`` run
    (each ``{"check": "omega" | "weight_x" | "weight_y", "step", "n", "successes", "ci95"}``; ω steps relative, weight
    steps in m); ``read_back``: every trial was read back from an earlier run of the search (its runs then keep that
    run's ``time_s``)."""

    k: int
    candidate: Arrival
    runs: tuple
    verdict: str
    checks: tuple = ()
    read_back: bool = False

    @property
    def folder(self) -> str:
        """The candidate's folder under ``out/candidates``."""
        return f"{self.k}-{_tag(self.candidate)}"

    def to_dict(self) -> dict:
        return {"k": self.k, "folder": self.folder, "candidate": self.candidate.to_dict(), "runs": list(self.runs),
                "verdict": self.verdict, "checks": list(self.checks), "read_back": self.read_back}


@dataclass(frozen=True, slots=True)
class FeederSearch:
    """The search's result: ``success`` (a verified feeder), its ``side``, ``config`` (path of ``feeder.toml``; None
    without one), ``feeder`` (the screened candidate fed, or None), ``verified`` and ``rerun`` (the two full runs;
    :attr:`evidence` pools them),
    ``predicted`` (the screen's share for the fed candidate), ``time_s``, ``reason`` (why none, when
    ``success`` is False), ``tried`` (every candidate run in the engine, in order), ``screened`` (the screen's
    candidates, best first), ``exact`` (the exact screen's count and best per side), every ``assumption``
    (arm, jitter, materials, drops, goal) and the seconds each stage took (``stages_s``: ``exact_screen``,
    ``engine_screen`` when asked for, ``engine_trials``: first trials, drift checks, verifications; ``sheet``)."""

    success: bool
    side: int | None
    config: str | None
    feeder: Arrival | None
    verified: dict | None
    rerun: dict | None
    predicted: float | None
    time_s: float
    reason: str
    tried: tuple
    screened: tuple = field(repr=False)
    exact: dict = field(default_factory=dict)
    assumptions: dict = field(default_factory=dict)
    sheet: dict = field(default_factory=dict)
    stages_s: dict = field(default_factory=dict)

    @property
    def evidence(self) -> dict | None:
        """The verified feeder's engine trials that did not choose it, pooled (None without a verified feeder): the
        verification less its first trials (``verified["chose"]``: they passed the candidate, so they lean its way)
        and the rerun — ``n``, ``successes``, ``ci95`` (Wilson, of the feed rate), ``runs`` (each run's seed, n and
        successes counted), ``left_out`` (the choosing trials) and ``rerun95``: where a new run of as many trials as
        one verification, with another seed, lands with 95 % probability (``{"n", "successes": [low, high], "rate":
        [low, high]}``, :func:`rerun_range`). Compare an independent check with ``rerun95``: ``ci95`` bounds the
        rate, not a new sample of it."""
        return evidence(self.verified, self.rerun)

    def to_dict(self) -> dict:
        f = self.feeder
        out = {"success": self.success, "side": self.side, "config": self.config, "verified": self.evidence,
               "predicted": self.predicted, "time_s": self.time_s,
               "feeder": None if f is None else f.to_dict(), "verification": self.verified, "rerun": self.rerun,
               "sheet": self.sheet, "assumptions": self.assumptions, "exact_screen": self.exact,
               "screened": [a.to_dict() for a in self.screened], "tried": [t.to_dict() for t in self.tried],
               "stages_s": self.stages_s}
        if not self.success:
            out["reason"] = self.reason
        return out

    def table(self, n: int = 5) -> str:
        """The screen's ``n`` best candidates and every one run in the engine, one line each (``#`` the candidate's
        number, as verdicts and folders name it; cm for lengths)."""
        rows = [f"{'#':>4}  {'side':>4}  {'weight':>30}  {'ω rad/s':>7}  {'h cm':>5}  {'wall cm':>7}  {'predicted':>9}  "
                "engine trials: verdict ('-': not run; # past the screen's: refinements)"]
        runs = {t.k: t for t in self.tried}
        for k, a in enumerate(self.screened):
            if k >= n and k not in runs:
                continue
            t = runs.get(k)
            v = ((", ".join(f"{r['successes']}/{r['n']}" for r in t.runs) + f": {t.verdict}"
                  + (" (read back)" if t.read_back else "")) if t else "-")
            rows.append(f"{k:>4}  {a.side:>4}  {a.variant.label():>30}  {a.omega:>7.4g}  {100 * a.h:>5.3g}  {100 * a.X:>7.3g}  "
                        f"{100 * a.predicted:>8.1f}%  {v}")
        return "\n".join(rows)

    def summary(self) -> str:
        if self.success:
            e, f = self.evidence, self.feeder
            runs = " + ".join(f"{r['successes']}/{r['n']}" for r in e["runs"])
            r95 = e["rerun95"]
            return (f"feeder found: side {self.side}, {f.variant.label()}, ω = {f.omega:.4g} rad/s, h = {100 * f.h:.3g} "
                    f"cm, end wall at {100 * f.X:.3g} cm; fed {e['successes']}/{e['n']} ({runs}, two seeds, less the "
                    f"{e['left_out']['n']} trials that chose it; Wilson 95 % [{100 * e['ci95'][0]:.1f}, "
                    f"{100 * e['ci95'][1]:.1f}] %); a new run of {r95['n']} lands in {r95['successes'][0]}–"
                    f"{r95['successes'][1]} fed (95 %); config {self.config} ({self.time_s:.0f} s{self._read_back()})"
                    + ("; few trials: check it with throwmap experiment feed CONFIG --n 200"
                       if e["ci95"][1] - e["ci95"][0] > FEW_TRIALS_WIDTH else ""))
        return f"no feeder: {self.reason} ({self.time_s:.0f} s{self._read_back()})"

    def _read_back(self) -> str:
        n = sum(t.read_back for t in self.tried)
        return f"; {n} of the {len(self.tried)} candidates read back from an earlier run" if n else ""


def evidence(verified: dict | None, rerun: dict | None) -> dict | None:
    """The engine trials of a verification (``verified``, with ``"chose"``: its first trials, which passed the
    candidate) and its ``rerun`` (run docs: ``n``, ``successes``, ``seed``), pooled less the choosing trials; see
    :attr:`FeederSearch.evidence`. None without a verification."""
    if not verified:
        return None
    v, r = verified, rerun  # the verification and its rerun
    chose = v.get("chose") or {"n": 0, "successes": 0}
    runs = [{"seed": v["seed"], "n": v["n"] - chose["n"], "successes": v["successes"] - chose["successes"]}]
    if r:
        runs.append({"seed": r["seed"], "n": r["n"], "successes": r["successes"]})
    runs = [x for x in runs if x["n"] > 0]  # a verification no longer than the first trials adds none
    n, k = sum(x["n"] for x in runs), sum(x["successes"] for x in runs)
    m = int(v["n"])
    lo, hi = rerun_range(k, n, m)
    return {"n": n, "successes": k, "ci95": list(wilson_interval(k, n)), "runs": runs,
            "left_out": {"n": chose["n"], "successes": chose["successes"],
                         "why": "the verification's first trials, which chose the candidate"},
            "rerun95": {"n": m, "successes": [lo, hi], "rate": [lo / m, hi / m]}}


def _run_doc(res) -> dict:
    ttc = [t.values.get("throws_to_capture") for t in res.trials]
    ttc = np.array([v for v in ttc if v is not None and math.isfinite(v)], dtype=float)
    return {"n": res.n, "successes": res.successes, "ci95": [float(res.ci95[0]), float(res.ci95[1])],
            "seed": res.seed, "failures": dict(res.failures), "rate": res.success_rate,
            "first_success": next((int(t.index) for t in res.trials if t.success), None),
            "throws_to_capture": ({"median": float(np.median(ttc)), "p90": float(np.percentile(ttc, 90)),
                                   "max": float(ttc.max())} if ttc.size else None)}


def _share(value, name: str, hi: float = 1.0) -> float:
    """A finite number in [0, ``hi``] (``hi`` may be ∞), refused on ``name`` otherwise."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (0.0 <= value <= hi) or math.isnan(value):
        raise InvalidStateError(name, f"must be a number in [0, {hi:g}], got {shown(value)}")
    return float(value)


@dataclass(frozen=True, slots=True)
class VerifyPlan:
    """How candidates are screened and verified: ``n_pre`` engine trials first (``pre_share`` of them must be fed),
    then ``n_verify`` trials and a rerun of as many (seeds ``seed`` and ``seed + 1``), ``goal`` the success rate
    both must reach, then ``omega_check`` trials at each of ω(1 ± :data:`OMEGA_DRIFT`) (0: no check) and
    ``weight_check`` trials at each of the lead weight's places ± :data:`WEIGHT_DRIFT_M` (0: no check);
    ``min_predicted`` the screen's share run first (the engine screen's share needed, with ``engine_screen``);
    ``screen_share`` the share of the budget the engine screen may use; ``engine_candidates`` the most candidates
    run (or engine-screened); ``omegas`` (rad/s) and ``hs`` (m) the grid searched; ``workers`` engine processes
    (0: all cores); ``budget_s`` the wall time (s) of the search: no candidate is started after :data:`START_BY` of
    it, no trial after it — but for ``finish_s`` more seconds in which a verification or rerun under way may go on
    (the CLI lends them from the design sheet's share: a feeder cut 47 trials short of its rerun is no feeder)."""

    n_pre: int = 20
    n_verify: int = 200
    goal: float = GOAL
    pre_share: float = PRE_SHARE
    min_predicted: float = 0.9
    screen_share: float = 0.35
    engine_candidates: int = 120
    omegas: tuple = OMEGAS
    hs: tuple = HS
    seed: int = 0
    workers: int = 0
    budget_s: float = 600.0
    engine_screen: bool = False
    omega_check: int = 30
    weight_check: int = 30
    finish_s: float = 0.0

    def __post_init__(self):
        for name, minimum in (("n_pre", 1), ("n_verify", 1), ("seed", 0), ("workers", 0), ("engine_candidates", 1),
                              ("omega_check", 0), ("weight_check", 0)):
            check_count(name, getattr(self, name), minimum=minimum)
        _share(self.budget_s, "budget_s", math.inf)
        _share(self.finish_s, "finish_s", math.inf)
        if not isinstance(self.engine_screen, bool):
            raise InvalidStateError("engine_screen", f"must be true or false, got {shown(self.engine_screen)}")
        for name in ("goal", "pre_share", "min_predicted", "screen_share"):
            _share(getattr(self, name), name)
        for name in ("omegas", "hs"):
            grid = getattr(self, name)
            if (not isinstance(grid, (tuple, list)) or not grid
                    or not all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in grid)):
                raise InvalidStateError(name, f"must be a non-empty sequence of finite numbers, got {shown(grid)}")
        if any(w <= 0 for w in self.omegas):
            raise InvalidStateError("omegas", f"must be rates > 0 rad/s, got {list(self.omegas)}")


def _weight_cap(part: Part, weight) -> float:
    """The heaviest lead weight allowed, kg: ``"none"`` 0, ``"auto"`` 1.7 × the part's mass, or a number ≥ 0."""
    if weight == "none":
        return 0.0
    if weight == "auto":
        return 1.7 * float(part.mass)
    if isinstance(weight, bool) or not isinstance(weight, (int, float)) or not math.isfinite(weight) or weight < 0:
        raise InvalidStateError("weight", f"must be 'auto', 'none' or a mass ≥ 0 kg, got {shown(weight)}")
    return float(weight)


def _tag(c: Arrival) -> str:
    """A short name of a screened candidate (weight, ω, h, side, end wall) for its folder."""
    import hashlib

    doc = [c.variant.weight.to_dict() if c.variant.weight else None, round(c.omega, 9), round(c.h, 9), c.side,
           round(c.X, 9)] + (["lip"] if c.lip else [])
    return hashlib.sha1(json.dumps(doc).encode()).hexdigest()[:8]


def _key(v: Variant, w: float, h: float, **screen) -> str:
    """A stored engine screen's key: the variant, ω, h and everything else the screen depends on (``screen``)."""
    return json.dumps([v.weight.to_dict() if v.weight else None, round(w, 9), round(h, 9),
                       {k: screen[k] for k in sorted(screen)}])


def design_feeder(part: Part, out, *, side: int | None = None, weight="auto", arm_length: float | None = None,
                  mu: float = 1.0, g: float = 9.81, sigma: float = 0.03, mu_rel: float = 0.1,
                  plan: VerifyPlan | None = None, progress=None) -> FeederSearch:
    """Search a feeder that feeds one side of ``part`` (or ``side``) into a pocket at the arm's end (module docstring).

    ``out``: the folder for the screens, every candidate verified and the feeder's ``feeder.toml`` / ``part.toml``;
    ``weight``: ``"auto"`` (the part alone and with a lead weight up to 1.7 × its mass), ``"none"`` or the heaviest
    weight in kg; ``arm_length``: the longest arm allowed, m (the end wall is at most there; None: the screen's reach,
    0.6 m); ``mu`` the arm's μ (± ``mu_rel`` per trial), ``sigma`` the relative ω jitter, ``g`` m/s²; ``plan``
    (:class:`VerifyPlan`, with the grid of ω and h searched; None: its defaults); ``progress(stage, done, total)``.
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
    cap = _weight_cap(part, weight)
    # a side the bare part cannot rest on may be made stable by a lead weight: refused only when none is allowed
    sides = tuple(part.stable_sides) if side is None else (part.check_side(side, require_stable=cap == 0),)
    if arm_length is not None and not (isinstance(arm_length, (int, float)) and math.isfinite(arm_length)
                                       and arm_length > 0):
        raise InvalidStateError("arm_length", f"must be a length > 0 m, got {shown(arm_length)}")
    omegas, hs = plan.omegas, plan.hs
    _share(mu, "mu", math.inf)
    _share(sigma, "sigma", 0.3)
    _share(mu_rel, "mu_rel", 0.99)
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InvalidStateError("out", f"{str(out)!r} is a file, not a folder")
    if not out.exists() and not (out.parent if str(out.parent) else Path(".")).is_dir():
        raise InvalidStateError("out", f"folder {str(out.parent)!r} does not exist")  # only DIR itself is made
    budget_s, workers = plan.budget_s, plan.workers
    assumptions = {
        "arm": {"mu": mu, "mu_rel": mu_rel, "g_m_s2": g, "motion": "recoil arm (Flatland 3°, ζ = 0.2)",
                "max_length_m": WALL_X_MAX if arm_length is None else arm_length,
                "max_length_note": "the end wall is screened at most this far from the joint" + (
                    " (the screen's reach: no --arm-length given)" if arm_length is None else "")},
        "omega_jitter_rel": sigma, "pocket": {"depth_m": POCKET_DEPTH_M, "lining_mu": LINING_MU,
                                              "clearance_m": 0.005, "lip_deg": 60.0},
        "drops": f"2–10 cm above the arm, any pose, CM x in {list(DROP_X)} m", "goal": plan.goal,
        "weight": {"max_kg": cap, "places": "0.2, 0.5, 0.8 along each target side, 8 mm inside (toward the centre near a corner); "
                                                 "a weight placed for one side may feed another",
                   "masses": "1 and 1.7 × the part's mass, capped"},
        "grid": {"omegas_rad_s": list(omegas), "hs_m": list(hs)},
        "engine": "pymunk; a half-step rerun must agree to 5 mm, a lost contact retried 4 times"}

    def tick(stage, done, total):
        if progress is not None:
            progress(stage, done, total)

    variants = [Variant(part, None, None)]
    for k in sides:
        variants += weight_variants(part, k, max_kg=cap)
    variants = [v for v in variants if any(k in v.part.stable_sides for k in sides)]
    if not variants:  # only with a side given that the bare part cannot rest on
        return FeederSearch(False, None, None, None, None, None, None, time.perf_counter() - t0,
                            f"side {sides[0]} is unstable on the bare part (it cannot rest on it) and none of the lead "
                            f"weights tried (1 and 1.7 × the part's mass, at most {1000 * cap:.1f} g, at 0.2, 0.5 and 0.8 "
                            f"along it) makes it stable; stable sides: {list(part.stable_sides)}",
                            (), (), {}, assumptions, stages_s={})
    make_directory(out, "out")
    store = out / "screen.jsonl"
    seen = _stored_lines(store, "key")  # a line cut by an interrupted write is screened again

    def fits(a: Arrival) -> bool:
        return a.predicted > 0 and (arm_length is None or a.X <= arm_length + 1e-9)

    # 1. the exact screen: every variant × ω × h
    exact = []
    total = len(variants) * len(omegas) * len(hs)
    for v in variants:
        for w in omegas:
            for h in hs:
                arm = Arm(h=h, g=g, mu=mu)
                table = screen_table(v.part, w, arm, sigma=sigma, exact=True)
                exact += arrivals(v, w, arm, sides=sides, sigma=sigma, chains=400, table=table,
                                  depths=(0.0, POCKET_DEPTH_M))  # arrival at the end wall, and at the pocket's lip
                tick("exact screen", len(exact), total)
    stages = {"exact_screen": time.perf_counter() - t0}
    exact_best = {str(k): max((a.best[k][1] for a in exact if k in a.best), default=0.0) for k in sides}
    weighted = sum(v.weight is not None for v in variants)
    exact_doc = {"candidates": len(exact), "variants": len(variants), "weights_tried": weighted,
                 "bare_part": len(variants) > weighted, "best_share_per_side": exact_best,
                 "what": "variants: the part bare (unless a side only a weight makes stable is asked for) and with each "
                         "lead weight tried (mass × place); candidates: variant × ω × h × end stop (the end wall, the "
                         "pocket's lip); 'screened' lists those that reach a stop first on a target side in some "
                         "chains (share > 0) within the arm's length, in the order the search takes them (by share, "
                         "in turn over side and weight, then the refinements it added; a share ≥ 90 % is run first, "
                         "then ≥ 50 %)"}
    ranked = sorted((a for a in exact if fits(a)), key=lambda a: (-a.predicted, a.wrong, a.variant.weight is not None))
    ranked = [ranked[i] for i in _diverse(list(range(len(ranked))), ranked)]  # every variant and side gets a turn

    # 2. the engine screen, best exact share first, within the screen's share of the budget — or, while no
    #    candidate reaches the share needed for verification, until 60 % of it; resumed below when every candidate
    #    verified so far has failed and time is left
    screened: list[Arrival] = []
    engined: list[Arrival] = []  # the candidates the engine's table screened (read back or computed)
    tables: dict = {}
    n_screen = min(len(ranked), plan.engine_candidates)

    def engine(a: Arrival) -> Arrival:
        """``a`` on the engine's table (read back from ``store`` when screened before)."""
        depth = POCKET_DEPTH_M if a.lip else 0.0
        key = _key(a.variant, a.omega, a.h, sides=list(sides), mu=mu, g=g, sigma=sigma, pocket_depth=depth)
        if key in seen:
            d = seen[key]
            best = {int(k): tuple(v) for k, v in d["best"].items()}
            engined.append(Arrival(a.variant, a.omega, a.h, d["side"], d["X"], d["predicted"], d["wrong"], best,
                                   d["chains"], d["time_s"], "engine", a.lip))
            return engined[-1]
        arm = Arm(h=a.h, g=g, mu=mu)
        tkey = _key(a.variant, a.omega, a.h)
        if tkey not in tables:  # one engine table serves both places of arrival
            tables[tkey] = screen_table(a.variant.part, a.omega, arm, sigma=sigma, workers=workers or None)
        e = arrival(a.variant, a.omega, arm, sides=sides, sigma=sigma, table=tables[tkey], pocket_depth=depth)
        engined.append(e)
        doc = {"key": key, "side": e.side, "X": e.X, "predicted": e.predicted, "wrong": e.wrong,
               "best": {str(k): list(v) for k, v in e.best.items()}, "chains": e.chains, "time_s": e.time_s,
               "exact_predicted": a.predicted, "exact_side": a.side, "label": a.variant.label(),
               "omega": a.omega, "h": a.h}
        with store.open("a", encoding="utf-8") as fh:
            fh.write(json.dumps(doc) + "\n")
        return e

    for a in (ranked[:n_screen] if plan.engine_screen else ()):
        spent = time.perf_counter() - t0
        hopeful = any(e.predicted >= plan.min_predicted for e in screened)
        if screened and (spent > 0.6 * budget_s or (hopeful and spent > plan.screen_share * budget_s)):
            break
        screened.append(engine(a))
        tick("engine screen", len(screened), n_screen)
    pos = len(screened)  # exact candidates screened in the engine
    screened.sort(key=lambda a: (-a.predicted, a.wrong))
    if plan.engine_screen:  # off by default: the first trials screen instead
        stages["engine_screen"] = time.perf_counter() - t0 - stages["exact_screen"]
    tried: list[Tried] = []

    def result(success, reason="", fed=None, verified=None, rerun=None):
        return FeederSearch(success, fed.side if fed else None, str(out / "feeder.toml") if fed else None, fed,
                            verified, rerun, fed.predicted if fed else None, time.perf_counter() - t0, reason,
                            tuple(tried), tuple(screened), exact_doc, assumptions,
                            stages_s={**stages, "engine_trials": time.perf_counter() - t0 - sum(stages.values())})

    # 3. verification in the feeding experiment; a candidate that passes its first trials but falls short is refined
    log = out / "candidates.jsonl"
    before = _stored_lines(log, "folder")  # an earlier run's candidates: read back, they keep its timings
    if plan.engine_screen:
        queue = _diverse([k for k, c in enumerate(screened) if c.predicted >= plan.min_predicted and fits(c)], screened)
    else:  # the first trials screen: the exact screen's candidates, those ≥ min_predicted first, then any ≥ 1/2
        screened[:] = ranked
        good = [k for k, c in enumerate(ranked) if c.predicted >= plan.min_predicted]
        queue = (good + [k for k, c in enumerate(ranked) if TRY_SHARE <= c.predicted < plan.min_predicted])[:n_screen]
        pos = n_screen
    refined_from: dict[int, int] = {}
    shifted: dict[int, tuple] = {}  # a candidate's ω moves away from drifts it could not hold: (count, last direction)
    while True:
        while not queue and pos < n_screen and time.perf_counter() - t0 < 0.75 * budget_s:
            screened.append(engine(ranked[pos]))  # every candidate so far failed: screen the next
            pos += 1
            tick("engine screen", pos, n_screen)
            if screened[-1].predicted >= plan.min_predicted and fits(screened[-1]):
                queue.append(len(screened) - 1)
        if not queue:
            break
        k = queue.pop(0)
        c = screened[k]
        if time.perf_counter() - t0 > START_BY * budget_s:  # leave the last quarter to a verification under way
            break
        here = out / "candidates" / f"{k}-{_tag(c)}"  # the tag: a folder never holds two candidates' trials
        path = feeder_files(c, here, mu=mu, g=g, sigma=sigma, mu_rel=mu_rel)
        cfg = read_config(Feed(), path.resolve())  # the runs store the part's absolute path: resumable from any cwd
        runs, checks = [], []  # the engine runs of the candidate; its drift checks

        def run(n, s, name, finish=False):
            label = stage_label(f"candidate {k}: {name}", here / name, n)
            cb = None if progress is None else (lambda d, t: progress(label, d, t))
            t = time.perf_counter()
            end = t0 + budget_s + (plan.finish_s if finish else 0.0)  # a verification or rerun may finish
            res = run_experiment("feed", cfg, n=n, seed=s, workers=workers, out=here / name, progress=cb,
                                 stop_by=end)  # no trial is started past the budget
            runs.append({**_run_doc(res), "time_s": time.perf_counter() - t, "new_trials": res.n - res.resumed})
            return res

        allowed = plan.n_pre - math.ceil(plan.pre_share * plan.n_pre - 1e-9)  # failures the first trials may have
        for n in sorted({min(plan.n_pre, m) for m in range(5, plan.n_pre + 5, 5)}):  # 5, 10, …: stop once lost
            pre = run(n, plan.seed, "verify")  # the verification extends these trials (same seed, same folder)
            if pre.n - pre.successes > allowed or pre.n < n:
                break
        if len(runs) > 1:  # the first trials are one run, stored in one folder
            runs[:] = [{**runs[-1], "time_s": sum(r["time_s"] for r in runs),
                        "new_trials": sum(r["new_trials"] for r in runs)}]
        verdict = "dropped after the first trials"
        verified = rerun = None
        short = "the budget ran out in the {} ({}/{} trials run)"
        if pre.n < plan.n_pre and pre.n - pre.successes <= allowed:
            verdict = short.format("first trials", pre.n, plan.n_pre)
        elif pre.n == plan.n_pre and pre.successes >= plan.pre_share * plan.n_pre:
            verdict, shift = "fed", 0.0
            if plan.omega_check:  # cheaper than the verification, and it stops the fragile ones before it
                verdict, shift = omega_check(cfg, here, plan, workers=workers, stop_by=t0 + budget_s,
                                              progress=progress, label=f"candidate {k}", record=checks)
                count, last = shifted.get(k, (0, 0.0))
                back = last and math.copysign(1.0, shift) != math.copysign(1.0, last)  # toward where it came from
                if shift and count < 2 and not back:  # centre ω in its window: away from the drift it cannot take
                    refined_from[len(screened)] = k  # (not back: its window is narrower than the move, ± 3 % + 5 %)
                    shifted[len(screened)] = (count + 1, shift)
                    screened.append(dataclasses.replace(c, omega=round(c.omega * (1.0 + shift), 6)))
                    queue.insert(0, len(screened) - 1)
            if verdict == "fed" and plan.weight_check and c.variant.weight is not None:
                verdict = weight_check(cfg, here, plan, workers=workers, stop_by=t0 + budget_s, progress=progress,
                                        label=f"candidate {k}", record=checks)
            if verdict.startswith("fragile"):  # beside it, the undrifted trials: a drift clearly below the goal may
                verdict += f"; undrifted, its first trials fed {pre.successes}/{pre.n}"  # be a feeder below it anyway
            if verdict == "fed":
                full = run(plan.n_verify, plan.seed, "verify", finish=True)
                verdict = "below the goal"
                if full.n < plan.n_verify:  # an unfinished verification is no verdict either way
                    verdict = short.format("verification", full.n, plan.n_verify)
                elif full.success_rate >= plan.goal:
                    again = run(plan.n_verify, plan.seed + 1, "rerun", finish=True)
                    # the rerun must reach the goal and not fall below the range a new run lands in after the
                    # first (rerun_range); above it (200/200 after 199/200) it only confirms the feed
                    lo = rerun_range(full.successes, full.n, plan.n_verify)[0] / plan.n_verify
                    verdict = ("fed" if again.success_rate >= max(plan.goal, lo) else "rerun below the goal"
                               if again.success_rate < plan.goal else "rerun disagrees")  # below the range a new run
                    # lands in after the verification, though at the goal
                    if again.n < plan.n_verify:
                        verdict = short.format("rerun", again.n, plan.n_verify)
                    verified, rerun = {**runs[-2], "chose": {"n": pre.n, "successes": pre.successes}}, runs[-1]
        if k in refined_from:
            verdict += f" (refined from candidate {refined_from[k]})"
        old = before.get(here.name)
        read_back = bool(runs) and not any(r["new_trials"] for r in runs) and old is not None and [
            (r["n"], r["successes"]) for r in old["runs"]] == [(r["n"], r["successes"]) for r in runs]
        if read_back:  # nothing run now: the earlier run's timings stand
            runs[:] = [{**r, "new_trials": 0} for r in old["runs"]]
            if verified:
                verified, rerun = {**runs[-2], "chose": verified["chose"]}, runs[-1]
        tried.append(Tried(k, c, tuple(runs), verdict, tuple(checks), read_back))
        tick(f"→ candidate {k}: " + ", ".join(f"{r['successes']}/{r['n']}" for r in runs) + f" fed: {verdict}"
             + (" (read back)" if read_back else ""), 1, 1)
        atomic_write_text(log, "".join(json.dumps(t.to_dict()) + "\n" for t in tried))  # this search's candidates
        if verdict.startswith("fed"):
            found = result(True, fed=c, verified=verified, rerun=rerun)
            e = found.evidence
            seeds, (lo, hi) = ", ".join(str(r["seed"]) for r in e["runs"]), e["rerun95"]["successes"]
            ci = e["ci95"]
            head = (f"# Verified: {e['successes']}/{e['n']} fed over seed{'s' if len(e['runs']) > 1 else ''} {seeds} (the {e['left_out']['n']} trials "
                    f"that chose it left out; Wilson 95 % [{100 * ci[0]:.1f}, {100 * ci[1]:.1f}] %); a run of "
                    f"{e['rerun95']['n']} trials with another seed lands in {lo}–{hi} fed with 95 % probability.\n")
            if ci[1] - ci[0] > FEW_TRIALS_WIDTH:  # a quick search's handful of trials: its rate is barely known
                head += (f"# Few trials: the feed rate is known only to within [{100 * ci[0]:.1f}, {100 * ci[1]:.1f}] %. "
                         f"Check it with: throwmap experiment feed feeder.toml --n 200 --seed 7\n")
            atomic_write_text(out / "feeder.toml", head + (here / "feeder.toml").read_text(encoding="utf-8"))
            atomic_write_text(out / "part.toml", (here / "part.toml").read_text(encoding="utf-8"))
            return found
        if verdict.startswith(("below the goal", "rerun below the goal", "rerun disagrees")) and k not in refined_from:
            near = _neighbours(c, g=g, mu=mu, sigma=sigma, workers=workers, engine=plan.engine_screen,
                               budget_left=budget_s - (time.perf_counter() - t0))
            fresh = [a for a in near if a.predicted >= plan.min_predicted and fits(a)]
            for a in fresh:
                refined_from[len(screened)] = k
                screened.append(a)
            queue[:0] = list(range(len(screened) - len(fresh), len(screened)))  # the neighbours first
    return result(False, _reason(sides, exact_best, screened, engined, tried, plan, budget_s, unrun=len(queue)))


def _stored_lines(path: Path, key: str) -> dict:
    """The JSON lines an earlier run of the search stored in ``path`` (``screen.jsonl``, ``candidates.jsonl``), by
    their ``key``; a line cut short or of an older format is skipped (its work is done again)."""
    out = {}
    if path.exists():
        for line in path.read_text(encoding="utf-8").splitlines():
            try:
                doc = json.loads(line)
                out[doc[key]] = doc
            except (ValueError, KeyError, TypeError):
                continue
    return out


def _diverse(order: list, screened: list) -> list:
    """``order`` (indices into ``screened``, best first) taken round-robin over the target side, and within a side
    over the variant: the best candidate of every side before any second one, and of every variant of a side
    before a second of any (candidates of one side tend to fail alike — the pocket keeps the same wrong side —
    and those of one variant and side more so)."""
    def by(ks: list, key) -> list:  # ks in groups of one key, each in the order given
        groups: dict = {}
        for k in ks:
            groups.setdefault(key(screened[k]), []).append(k)
        return list(groups.values())

    def round_robin(lists: list) -> list:
        return [k for layer in itertools.zip_longest(*lists) for k in layer if k is not None]

    return round_robin([round_robin(by(ks, lambda c: c.variant.label())) for ks in by(order, lambda c: c.side)])


def _neighbours(c: Arrival, *, g: float, mu: float, sigma: float, workers: int, budget_left: float,
                engine: bool = True) -> list:
    """The refinement of a candidate that passed its first trials but fell short: its end wall 1 cm nearer and farther
    (carrying the share of the stop they moved from: the engine screen keeps each side's best stop only), and
    ω ± 0.25 rad/s, h ± 5 mm on the engine screen (while half of ``budget_left`` s allows, 5–30 s each)."""
    import dataclasses

    out = []
    part = c.variant.part
    depth = POCKET_DEPTH_M if c.lip else 0.0
    for dX in (-0.01, 0.01):
        X = round(c.X + dX, 6)
        lip = X - lip_offset(part, c.side, depth)
        if DROP_X[1] + float(np.max(part.uR)) + 0.01 - 1e-9 <= lip and X <= WALL_X_MAX + 1e-9:
            out.append(dataclasses.replace(c, X=X))
    t0 = time.perf_counter()
    for w, h in ((c.omega - 0.25, c.h), (c.omega + 0.25, c.h), (c.omega, c.h - 0.005), (c.omega, c.h + 0.005)):
        if w <= 0 or time.perf_counter() - t0 > budget_left / 2:
            continue
        if not engine:  # the first trials judge them: they carry the candidate's share
            out.append(dataclasses.replace(c, omega=w, h=h))
            continue
        arm = Arm(h=h, g=g, mu=mu)
        out.append(arrival(c.variant, w, arm, sides=(c.side,), sigma=sigma, pocket_depth=depth,
                           table=screen_table(part, w, arm, sigma=sigma, workers=workers or None)))
    return out


def _time(budget_s: float) -> str:
    """The search's time as the reason gives it: its share of ``--budget`` and when the last candidate may start."""
    return (f"{budget_s:.0f} s of the budget, the rest kept for the design sheet; no candidate starts after "
            f"{START_BY:.0%} of it, {START_BY * budget_s:.0f} s")


def _pct(share: float) -> str:
    """A share as a percentage that never rounds to 0 or 100 unless it is: 0.9975 → "99.8 %", 1 → "100 %"."""
    if share in (0.0, 1.0):
        return f"{100 * share:.0f} %"
    return f"{min(max(100 * share, 0.1), 99.9):.1f} %"


def _reason(sides, exact_best, screened, engined, tried, plan: VerifyPlan, budget_s: float, unrun: int = 0) -> str:
    """Why no feeder: each side's best first-arrival share on the exact screen and on the engine's (``engined``: the
    candidates it screened), and what the engine runs reached."""
    eng = {k: max((a.best[k][1] for a in engined if k in a.best), default=None) for k in sides}
    never = [k for k in sides if exact_best[str(k)] == 0 and not eng[k]]
    parts = []
    if never:
        parts.append(f"side(s) {never} never arrive first at a stop they hold on the exact screen")
    shares = ", ".join(f"side {k}: exact {_pct(exact_best[str(k)])}"
                       + (f", engine {_pct(eng[k])}" if eng[k] is not None else "") for k in sides)
    parts.append(f"best first-arrival shares ({shares})")
    if tried:
        def final(t):  # a candidate's verdict rests on its largest run (its first trials are the start of it)
            return max(t.runs, key=lambda r: r["n"]) if t.runs else {"n": 0, "successes": 0, "rate": 0.0}

        best = max(tried, key=lambda t: (final(t)["n"], final(t)["rate"]))  # the one that went furthest
        last = final(best)
        c = best.candidate
        parts.append(f"{len(tried)} candidate(s) run in the engine, none fed ≥ {100 * plan.goal:g} % in its verification and its rerun, ω ± {100 * OMEGA_DRIFT:g} % and the weight's place ± {1000 * WEIGHT_DRIFT_M:g} mm held: the best, side "
                     f"{c.side} ({c.variant.label()}, ω = {c.omega:g} rad/s, h = {c.h:g} m, wall at {c.X:g} m) reached "
                     f"{last['successes']}/{last['n']} = {100 * last['rate']:.1f} % ({best.verdict})")
    elif screened and max(a.predicted for a in screened) >= plan.min_predicted:
        parts.insert(0, f"the search's time ({_time(budget_s)}) ran out before a candidate was run")  # the cause
    else:
        need = plan.min_predicted if plan.engine_screen else TRY_SHARE
        parts.append(f"no candidate reached the {100 * need:g} % share needed to be run in the engine")
    if unrun and tried:  # the cause, first: the search did not run out of candidates
        parts.insert(0, f"the search's time ({_time(budget_s)}) ran out with {unrun} candidate(s) queued for the "
                        "engine not run")
    return "; ".join(parts)
