"""Tilted and walled throws: the exact models against the engine.

:func:`validate_tilt_wall` throws random cases on a tilted arm (rest angle α) and on
an arm with a :class:`~throwmap.Wall` at its end through the exact models and through
the pymunk engine (the reference), as :mod:`throwmap.studies.validation` does for the
plain arm, and compares them throw by throw. Four conditions, ``n`` throws each:

=====================  ==========================================================
``tilt, μ = ∞``        α ∈ [−15°, 15°], no slip; models ``paper`` and ``rigid_body``
``tilt``               α as above, μ random in [0.3, ∞]; ``rigid_body``
``wall, μ_w = 0``      α and μ as above, a frictionless wall; ``rigid_body``
``wall, μ_w = μ``      the wall as rough as the arm; ``rigid_body``
=====================  ==========================================================

The paper model assumes a pivot that never slips (Sec. III), so it is compared at μ = ∞ only. Every throw
draws a part from the validation set (:func:`~throwmap.studies.validation.default_parts`), a side, x uniform
over the starts :func:`throwmap.throw` accepts (with a wall: the outer quarter of those clear of it), ω ∈ [3, 7]
rad/s, h ∈ {−1, −0.5} cm (the paper's regime 0 > h > −min d), the arm length in [0.25, 0.40] m. Per row: throws compared, same outcome % (same side at rest, or the same escape) and
"same escape or |Δx| ≤ 0.5 mm" %, each with its Wilson 95 % interval, median and 95th percentile |Δx|, and the throws each
side refused (``unresolved``, ``timeout``, …) with their reasons, and the worst misses as reproducers.
:func:`~throwmap.analysis.wall.wall_fixed_point` finds, with :func:`throwmap.limit_set`, the fixed point a
wall makes where jogs saturate (x* = length − u_R) and checks its multiplier by finite differences. Every row
is also given by the one agreement statistic (:mod:`throwmap.studies.agreement`), and the goals are read from it
(:func:`~throwmap.studies.agreement.goals`: the position among same-outcome rests only; no goal is met on
nothing compared).

The study is declared as a :class:`TiltWallConfig` and run on the experiment runner (experiment
``"validate-fixtures"``, :mod:`throwmap.studies.study`): trial i throws one case (condition by condition, in
:data:`CONDITIONS` order, ``n`` each) through the engine (also with its friction cap relaxed, without the wall
and at α = 0) and the models; each condition's cases are drawn from child ``c`` of the seed
(:func:`throwmap.experiments.base.trial_generator`, c the condition's place in :data:`CONDITIONS`).
"""

from __future__ import annotations

import json
import math
import time
import warnings
from dataclasses import dataclass

import numpy as np
from pydantic import Field

from ..analysis.wall import WallFixedPoint, wall_fixed_point
from ..budget import check_count, guard_work
from ..errors import InvalidStateError, ThrowmapError
from ..experiments.base import trial_generator
from ..experiments.registry import register_experiment
from ..io.config import part_document, part_from_spec
from ..kernels import codes as C
from ..models import DEFAULT_MODEL, get_model
from ..records.outcome import Status
from ..rng import as_generator
from ..system.arm import Arm
from ..system.fixtures import Wall
from ..system.part import Part
from ..system.starts import start_interval, tilted_rest_reason, wall_reach
from ..throws.throw import throw, throw_batch
from .agreement import goals as agreement_goals
from .agreement import REFUSED, AgreementTable, agreement, refusal_counts
from .agreement import WITHIN as AGREEMENT_WITHIN
from .engine_cap import CAP_ALT, cap_sensitive, friction_cap
from .study import StudyRun, StudyConfig, answer_values, answers, cached_cases, case_trial, run_study, stored
from .tilt_wall_report import MU_BANDS, TiltWallReport, TiltWallRow, _band
from .validation import default_parts

__all__ = ["CONDITIONS", "REFUSED", "TILT_WALL", "TiltWallCases", "TiltWallConfig", "TiltWallReport", "TiltWallRow",
           "WallFixedPoint", "compare_rows", "make_cases", "tilt_wall_report", "validate_tilt_wall",
           "wall_fixed_point"]

ALPHA_RANGE = (-math.radians(15.0), math.radians(15.0))
"""Arm rest angles α, rad (±15°)."""
MU_RANGE = (0.3, 3.0)
"""Finite arm frictions, drawn log-uniformly; with probability :data:`P_MU_INF` μ = ∞ instead."""
P_MU_INF = 0.2
"""Share of the throws at μ = ∞ (no slip) in the conditions with random μ."""
OMEGA_RANGE = (3.0, 7.0)
"""Release rates, rad/s (the validation set's)."""
H_VALUES = (-0.01, -0.005)
"""Arm heights, m (0 > h > −min d for every part of the set: the paper's regime)."""
LENGTH_RANGE = (0.25, 0.40)
"""Arm lengths, m: short enough that many jogs reach the wall."""
WALL_X_SHARE = 0.25
"""With a wall, x is drawn over this outer share of the starts on the side (where jogs reach the wall)."""
WALL_HEIGHT = 0.05
"""Wall height above the arm surface, m (taller than every part of the set lying on a side)."""
WITHIN = AGREEMENT_WITHIN
"""|Δx| counted as agreement, m (the 0.5 mm of the validation goals, :data:`throwmap.studies.agreement.WITHIN`)."""
GOALS = {"same_pct": 99.0, "within_pct": 95.0}
"""Targets per row: same outcome ≥ 99 % of the compared throws, |Δx| ≤ 0.5 mm in ≥ 95 % of the same-outcome rests."""
VALIDATED = DEFAULT_MODEL
"""The model whose options ``rigid_body_options`` are and against which the other exact models are compared."""

CONDITIONS = {
    "tilt, μ = ∞": {"wall": None, "mu": "inf", "models": ("paper", "rigid_body")},
    "tilt": {"wall": None, "mu": "random", "models": ("rigid_body",)},
    "wall, μ_w = 0": {"wall": "zero", "mu": "random", "models": ("rigid_body",)},
    "wall, μ_w = μ": {"wall": "arm", "mu": "random", "models": ("rigid_body",)},
}
"""The conditions thrown, ``n`` throws each: the wall's μ (None: no wall), how μ is drawn, the models compared."""
N_WORST = 8
"""Misses kept per row as reproducers: side or status disagreements first, then the largest |Δx|."""


@dataclass(frozen=True, slots=True)
class TiltWallCases:
    """The throws of one condition, as arrays of equal length (SI units; ``wall_mu`` nan: no wall,
    ``inf``: as rough as an arm at μ = ∞)."""

    condition: str
    part: np.ndarray
    x: np.ndarray
    side: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray
    mu: np.ndarray
    h: np.ndarray
    length: np.ndarray
    wall_mu: np.ndarray

    @property
    def n(self) -> int:
        return int(self.x.size)

    def subset(self, keep) -> "TiltWallCases":
        """The throws where ``keep`` (a boolean array) holds."""
        return TiltWallCases(self.condition, *(getattr(self, f)[keep] for f in
                                               ("part", "x", "side", "omega", "alpha", "mu", "h", "length", "wall_mu")))

    def case(self, i: int) -> dict:
        """Throw ``i`` as plain values (its reproducer)."""
        wm = float(self.wall_mu[i])
        return {"part": str(self.part[i]), "x_m": float(self.x[i]), "side": int(self.side[i]),
                "omega_rad_s": float(self.omega[i]), "alpha_rad": float(self.alpha[i]),
                "alpha_deg": math.degrees(float(self.alpha[i])), "mu": float(self.mu[i]), "h_m": float(self.h[i]),
                "length_m": float(self.length[i]), "wall": None if math.isnan(wm) else {"height_m": WALL_HEIGHT,
                                                                                      "mu": wm}}

    def system(self, i: int, parts: dict) -> tuple:
        """``(part, arm, fixtures, alpha)`` of throw ``i``."""
        arm = Arm(h=float(self.h[i]), mu=float(self.mu[i]), length=float(self.length[i]))
        wm = float(self.wall_mu[i])
        fixtures = () if math.isnan(wm) else (Wall(WALL_HEIGHT, mu=wm),)
        return parts[str(self.part[i])], arm, fixtures, float(self.alpha[i])


def make_cases(parts: dict[str, Part], condition: str, n: int, rng: np.random.Generator,
               alpha_range=ALPHA_RANGE) -> TiltWallCases:
    """``n`` random throws of ``condition`` (a key of :data:`CONDITIONS`) drawn with ``rng``; α uniform
    over ``alpha_range`` (rad; ``(0, 0)``: the plain arm's baseline on the same draws). The side is
    drawn among those the part rests on at that α (:func:`throwmap.system.starts.tilted_rest_reason`:
    it neither tips nor slides); a draw where every side tips is drawn again. ``rng``: a Generator or an int seed
    (:func:`throwmap.rng.as_generator`)."""
    rng = as_generator(rng)
    spec = CONDITIONS[condition]
    names = list(parts)
    cols: dict[str, list] = {k: [] for k in ("part", "x", "side", "omega", "alpha", "mu", "h", "length", "wall_mu")}
    while len(cols["x"]) < n:
        name = names[int(rng.integers(len(names)))]
        part = parts[name]
        alpha = float(rng.uniform(*alpha_range))
        length = float(rng.uniform(*LENGTH_RANGE))
        h = float(rng.choice(H_VALUES))
        if spec["mu"] == "inf" or rng.uniform() < P_MU_INF:
            mu = math.inf
        else:
            mu = float(math.exp(rng.uniform(math.log(MU_RANGE[0]), math.log(MU_RANGE[1]))))
        arm = Arm(h=h, mu=mu, length=length)
        at_rest = [k for k in part.stable_sides if not tilted_rest_reason(part, arm, k, alpha)]
        if not at_rest:  # every side tips at this α: draw again
            continue
        k = int(rng.choice(at_rest))
        lo, hi = start_interval(part, arm, k)
        if spec["wall"] is not None:  # starts clear of the wall (wall_reach), their outer quarter
            hi = min(hi, length - wall_reach(part, k, WALL_HEIGHT))
            lo = hi - WALL_X_SHARE * (hi - lo)
        x = float(rng.uniform(lo, hi))
        x = min(max(x, math.nextafter(lo, math.inf)), hi)
        wall_mu = {None: math.nan, "zero": 0.0, "arm": mu}[spec["wall"]]
        for key, v in (("part", name), ("x", x), ("side", k), ("omega", float(rng.uniform(*OMEGA_RANGE))),
                       ("alpha", alpha), ("mu", mu), ("h", h), ("length", length), ("wall_mu", wall_mu)):
            cols[key].append(v)
    return TiltWallCases(condition, np.array(cols["part"], dtype=object),
                         *(np.array(cols[k], dtype=np.int64 if k == "side" else float)
                           for k in ("x", "side", "omega", "alpha", "mu", "h", "length", "wall_mu")))


def _throw_one(cases: TiltWallCases, i: int, parts: dict, model: str, options: dict, walls: bool = True,
               level: bool = False) -> dict:
    """Throw ``i`` of ``cases`` through ``model`` (``walls`` False: without the wall; ``level``: at α = 0):
    ``{"x", "side", "status", "n_min", "why", "message"}``; refused keywords (a model without tilt or fixtures) give
    ``message`` (the refusal's) and no answer (x nan, side and status −1)."""
    part, arm, fixtures, alpha = cases.system(i, parts)
    fixtures = fixtures if walls else ()
    alpha = 0.0 if level else alpha
    out = {"x": math.nan, "side": -1, "status": -1, "n_min": math.nan, "why": "", "message": None}
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            b = throw_batch(part, arm, cases.x[i:i + 1], cases.side[i:i + 1], cases.omega[i:i + 1], model=model,
                            on_invalid="status", fixtures=fixtures, alpha=alpha, **options)
    except ThrowmapError as err:
        out["message"] = str(err)
        return out
    out.update(x=float(b.x[0]), side=int(b.side[0]), status=int(b.status[0]))
    out["n_min"] = float(b.records[0, C.N_MIN])  # < 0: the pivot lifts off (paper assumes it does not)
    if int(b.status[0]) in REFUSED:  # the model's reason, from the one-throw call
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            o = throw(part, arm, float(cases.x[i]), int(cases.side[i]), float(cases.omega[i]), model,
                      fixtures=fixtures, alpha=alpha, **options)
        out["why"] = o.message or o.status.label
    return out


def _throw_all(cases: TiltWallCases, parts: dict, model: str, options: dict, tick, walls: bool = True,
               level: bool = False) -> dict:
    """Every throw of ``cases`` through ``model`` (:func:`_throw_one`) as arrays; refused keywords end the run
    with the refusal's message."""
    n = cases.n
    out = {"x": np.full(n, np.nan), "side": np.full(n, -1, dtype=np.int64), "status": np.full(n, -1, dtype=np.int64),
           "n_min": np.full(n, np.nan), "why": np.full(n, "", dtype=object), "message": None}
    for i in range(n):
        one = _throw_one(cases, i, parts, model, options, walls, level)
        if one["message"]:
            out["message"] = one["message"]
            return out
        for k in ("x", "side", "status", "n_min", "why"):
            out[k][i] = one[k]
        if tick is not None:
            tick()
    return out


def _take(res: dict, keep) -> dict:
    return {k: (v[keep] if isinstance(v, np.ndarray) else v) for k, v in res.items()}


def _wilson(k: int, n: int) -> list:
    from ..experiments.stats import wilson_interval

    lo, hi = wilson_interval(int(k), int(n))
    return [100.0 * lo, 100.0 * hi]


def _reasons(res: dict) -> dict:
    """``{reason: count}`` over refused throws (numbers as ``#``: like reasons group; cut at a word), most first."""
    import re
    from collections import Counter
    why = [re.sub(r"[-+]?\d[\d.e+-]*", "#", str(w)).split(": not modelled")[0] for w in res.get("why", ()) if w]
    why = [w if len(w) <= 110 else w[:w.rfind(" ", 0, 110)] + " …" for w in why]
    return dict(Counter(why).most_common())


def _agree(a: dict, b: dict) -> np.ndarray:
    """Throw by throw: the same escape, or at rest on the same side within :data:`WITHIN`."""
    same_st = a["status"] == b["status"]
    return same_st & ((a["status"] != C.OK) | ((a["side"] == b["side"]) & (np.abs(a["x"] - b["x"]) <= WITHIN)))


def compare_rows(label: str, cases: TiltWallCases, parts: dict, res: dict, ref: dict, free: dict | None = None,
                 level: tuple | None = None, sensitive=None) -> TiltWallRow:
    """One row (a :class:`TiltWallRow`): ``res`` (a model) against ``ref`` (the engine) on ``cases``; see the
    module docstring. ``res``, ``ref``: dicts of arrays ``x``, ``side``, ``status`` (and ``why``, ``message``).

    ``free`` (the engine without the wall, same throws) gives ``wall_changed_pct``: the share of
    throws whose engine outcome the wall changed (beyond 0.5 mm, or side, or status). ``level``
    (``(res, ref)`` of the same throws at α = 0) gives the row's ``baseline``. ``sensitive`` (booleans,
    :func:`~throwmap.studies.engine_cap.cap_sensitive`) marks throws whose engine answer depends on its friction cap:
    the row then also gives its agreement without them (``cap``). The row's ``agreement`` is the one agreement
    statistic of ``res`` against ``ref`` (:func:`~throwmap.studies.agreement.agreement`)."""
    n = cases.n
    if res.get("message"):
        return TiltWallRow(label, n, 0, False, res["message"])
    refused_m = np.isin(res["status"], REFUSED)
    refused_e = np.isin(ref["status"], REFUSED)
    cmp = ~refused_m & ~refused_e
    both_ok = cmp & (res["status"] == C.OK) & (ref["status"] == C.OK)
    same_side = both_ok & (res["side"] == ref["side"])
    same_escape = cmp & (res["status"] == ref["status"]) & (res["status"] != C.OK)
    dx = np.full(n, np.nan)
    dx[same_side] = np.abs(res["x"][same_side] - ref["x"][same_side])
    same = same_side | same_escape
    within = same_escape | (same_side & (dx <= WITHIN))
    m = int(cmp.sum())
    d = dx[same_side] * 1e3
    # engine rests that lean on the wall (tilted, right support vertex past the arm's end)
    uR = np.array([parts[str(p)].uR[int(k)] for p, k in zip(cases.part, np.maximum(ref["side"], 0))])
    leaning = (ref["status"] == C.OK) & (ref["x"] + uR > cases.length + 1e-4)
    by_mu = {}
    for lo, hi in MU_BANDS:
        sel = cmp & ((cases.mu == lo) if math.isinf(lo) else ((cases.mu >= lo) & (cases.mu < hi)))
        if sel.any():
            by_mu[_band(lo, hi)] = {"n": int(sel.sum()), "within_pct": 100.0 * float(within[sel].mean()),
                                    "same_pct": 100.0 * float(same[sel].mean())}
    base = None
    if level is not None and not level[0].get("message") and not level[1].get("message"):
        b = compare_rows(label, cases, parts, level[0], level[1])
        base = {k: getattr(b, k) for k in ("n_compared", "same_pct", "within_pct", "dx_median_mm", "dx_p95_mm", "by_mu")}
    miss = np.flatnonzero(cmp & ~within)
    order = miss[np.argsort(-np.nan_to_num(dx[miss], nan=np.inf), kind="stable")][:N_WORST]
    worst = [{**cases.case(int(i)), "model": {"x_m": float(res["x"][i]), "side": int(res["side"][i]),
                                              "status": Status(int(res["status"][i])).label},
              "engine": {"x_m": float(ref["x"][i]), "side": int(ref["side"][i]),
                         "status": Status(int(ref["status"][i])).label},
              "dx_mm": float(dx[i] * 1e3) if math.isfinite(dx[i]) else None} for i in order]
    return TiltWallRow(
        label, n, m, True, None,
        same_pct=100.0 * same.sum() / m if m else math.nan, same_ci95=_wilson(same.sum(), m),
        within_pct=100.0 * within.sum() / m if m else math.nan, within_ci95=_wilson(within.sum(), m),
        dx_median_mm=float(np.median(d)) if d.size else math.nan,
        dx_p95_mm=float(np.percentile(d, 95)) if d.size else math.nan,
        dx_max_mm=float(d.max()) if d.size else math.nan,
        model_refused=refusal_counts(res["status"]), engine_refused=refusal_counts(ref["status"]),
        model_refused_why=_reasons(res), engine_refused_why=_reasons(ref),
        engine_leaning=int(leaning.sum()),
        at_wall_pct=(100.0 * float(np.mean((ref["status"] == C.OK) & (np.abs(ref["x"] + uR - cases.length) < 1e-3)))
                     if not np.all(np.isnan(cases.wall_mu)) else 0.0),
        wall_changed_pct=100.0 * float(np.mean(~_agree(free, ref))) if free is not None else None,
        by_mu=by_mu, baseline=base, cap=_cap_split(cmp, same, within, sensitive),
        worst=worst, agreement=agreement(res, ref, label=label, tol=WITHIN),
    )


def _cap_split(cmp, same, within, sensitive) -> dict | None:
    """Agreement without the throws whose engine answer moves with its friction cap (None: not measured)."""
    if sensitive is None:
        return None
    keep = cmp & ~sensitive
    k = int(keep.sum())
    return {"n_sensitive": int((cmp & sensitive).sum()), "n_kept": k,
            "same_pct": 100.0 * float(same[keep].mean()) if k else float("nan"), "same_ci95": _wilson(same[keep].sum(), k),
            "within_pct": 100.0 * float(within[keep].mean()) if k else float("nan"),
            "within_ci95": _wilson(within[keep].sum(), k)}


def _timer(parts: dict) -> float:
    """Seconds per engine throw, measured on three tilted throws against a wall (after one that warms the engine)."""
    first = dict([next(iter(parts.items()))])
    _throw_all(make_cases(first, "wall, μ_w = 0", 1, as_generator(1)), parts, "engine", {}, None)
    cases = make_cases(first, "wall, μ_w = 0", 3, as_generator(2))
    t0 = time.perf_counter()
    _throw_all(cases, parts, "engine", {}, None)
    return (time.perf_counter() - t0) / cases.n


# ------------------------------------------------------------------ the study on the runner
class TiltWallConfig(StudyConfig):
    """The tilt/wall study, declared (SI units, rad; see :func:`validate_tilt_wall` for each key). ``parts``:
    name → ``[part]`` table (:func:`throwmap.io.config.part_document`); ``models`` None: each condition's own."""

    parts: dict[str, dict] = Field(default_factory=lambda: {k: part_document(p)["part"]
                                                            for k, p in default_parts().items()})
    n: int = Field(500, ge=1)
    conditions: tuple[str, ...] = tuple(CONDITIONS)
    models: tuple[str, ...] | None = None
    alpha_range: tuple[float, float] = ALPHA_RANGE
    baseline: bool = True
    rigid_body_options: dict = Field(default_factory=dict)


def _tilt_cases(cfg: TiltWallConfig) -> tuple[dict, dict]:
    """``(parts, {condition: TiltWallCases})`` of ``cfg`` (condition c drawn from child c of the seed)."""
    parts = {name: part_from_spec(doc) for name, doc in cfg.parts.items()}
    names = list(CONDITIONS)
    return parts, {c: make_cases(parts, c, cfg.n, trial_generator(cfg.seed, names.index(c)), cfg.alpha_range)
                   for c in cfg.conditions}


def _models(cfg: TiltWallConfig, condition: str) -> tuple:
    return CONDITIONS[condition]["models"] if cfg.models is None else tuple(cfg.models)


def _answer(key: str, one: dict) -> dict:
    values = answer_values(key, one["x"], one["side"], one["status"])
    values[f"{key}.n_min"] = stored(one["n_min"])
    values[f"{key}.why"] = one["why"]
    if one["message"]:
        values[f"{key}.message"] = one["message"]
    return values


class TiltWallStudy:
    """The ``validate-fixtures`` study as an experiment: trial i throws one case (module docstring)."""

    name = "validate-fixtures"
    summary = "tilted arms and walls: the exact models against the pymunk engine, case by case (throwmap validate-fixtures)"
    config_type = TiltWallConfig

    def parameters(self, cfg: TiltWallConfig) -> dict:
        return json.loads(cfg.model_dump_json())

    def trial(self, cfg: TiltWallConfig, index: int, rng):
        parts, by_condition = cached_cases(cfg, _tilt_cases)
        c = cfg.conditions[index // cfg.n]
        cases, i = by_condition[c], index % cfg.n
        values, statuses = {}, []
        ref = _throw_one(cases, i, parts, "engine", {})
        values.update(_answer("engine", ref))
        statuses.append(("engine", ref["status"]))
        with friction_cap(CAP_ALT):  # the same throw with the engine's friction cap relaxed: where it matters
            values.update(_answer("engine, cap relaxed", _throw_one(cases, i, parts, "engine", {})))
        if CONDITIONS[c]["wall"]:
            values.update(_answer("engine, no wall", _throw_one(cases, i, parts, "engine", {}, walls=False)))
        if cfg.baseline:
            values.update(_answer("engine, α = 0", _throw_one(cases, i, parts, "engine", {}, level=True)))
        for m in _models(cfg, c):
            opts = dict(cfg.rigid_body_options) if m == VALIDATED else {}
            one = _throw_one(cases, i, parts, m, opts)
            values.update(_answer(m, one))
            statuses.append((m, one["status"]))
            if cfg.baseline:
                values.update(_answer(f"{m}, α = 0", _throw_one(cases, i, parts, m, opts, level=True)))
        return case_trial(index, rng, values, statuses)


TILT_WALL = register_experiment(TiltWallStudy())
"""The registered ``validate-fixtures`` study."""


def _results(trials, key: str) -> dict:
    """The answers stored under ``key`` as :func:`_throw_all` gives them (arrays, ``why``, ``message``)."""
    out = {**answers(trials, key), "n_min": np.array([float(t.values[f"{key}.n_min"]) for t in trials], dtype=float),
           "why": np.array([t.values[f"{key}.why"] for t in trials], dtype=object), "message": None}
    msgs = [t.values[f"{key}.message"] for t in trials if f"{key}.message" in t.values]
    if msgs:  # a model that refuses the condition's keywords: the first refusal, no answers (as _throw_all)
        first = next(j for j, t in enumerate(trials) if f"{key}.message" in t.values)
        out = {"x": np.full(len(trials), np.nan), "side": np.full(len(trials), -1, dtype=np.int64),
               "status": np.full(len(trials), -1, dtype=np.int64), "n_min": np.full(len(trials), np.nan),
               "why": np.full(len(trials), "", dtype=object), "message": msgs[0]}
        for k, read in (("x", float), ("side", int), ("status", int), ("n_min", float), ("why", str)):
            out[k][:first] = [read(t.values[f"{key}.{k}"]) for t in trials[:first]]
    return out


def tilt_wall_report(cfg: TiltWallConfig, trials, *, fixed_point: WallFixedPoint | None = None) -> TiltWallReport:
    """The report of the study ``cfg`` from its trials (sorted by index, all of them); see :func:`validate_tilt_wall`."""
    parts, by_condition = cached_cases(cfg, _tilt_cases)
    trials = tuple(trials)
    if len(trials) != cfg.n * len(cfg.conditions):
        raise InvalidStateError("trials", f"the study has {cfg.n * len(cfg.conditions)} cases, got {len(trials)} trials")
    rows, cases_out, results = [], {}, {}
    for j, c in enumerate(cfg.conditions):
        cases, tr = by_condition[c], trials[j * cfg.n:(j + 1) * cfg.n]
        ref = _results(tr, "engine")
        sens = cap_sensitive(ref, _results(tr, "engine, cap relaxed"))
        free = _results(tr, "engine, no wall") if CONDITIONS[c]["wall"] else None
        ref0 = _results(tr, "engine, α = 0") if cfg.baseline else None
        names = _models(cfg, c)
        res = {m: _results(tr, m) for m in names}
        res0 = {m: _results(tr, f"{m}, α = 0") for m in names} if cfg.baseline else {}
        cases_out[c] = cases
        results[c] = {"engine": ref, **res, **({"engine, no wall": free} if free else {}),
                      **({"engine, α = 0": ref0} if ref0 else {}), **{f"{m}, α = 0": r for m, r in res0.items()}}
        for m, r in res.items():
            rows.append(compare_rows(f"{c}: {m} vs engine", cases, parts, r, ref, free,
                                     (res0[m], ref0) if cfg.baseline else None, sens))
        others = [m for m in res if m != VALIDATED]
        if VALIDATED in res:  # two exact models: no engine between them
            for m in others:
                rows.append(compare_rows(f"{c}: {m} vs {VALIDATED}", cases, parts, res[m], res[VALIDATED], None,
                                         (res0[m], res0[VALIDATED]) if cfg.baseline else None))
        for m in others:  # where a model's no-lift-off assumption holds
            if "no lift-off" not in getattr(get_model(m), "assumes", ()) or res[m]["message"]:
                continue
            holds = np.nan_to_num(res[m]["n_min"], nan=1.0) >= 0
            sub = cases.subset(holds)
            for name, other in (("engine", ref), (VALIDATED, res.get(VALIDATED))):
                if other is not None and holds.any():
                    row = compare_rows(f"{c}: {m} vs {name}, no lift-off ({100 * holds.mean():.0f} %)", sub, parts,
                                       _take(res[m], holds), _take(other, holds))
                    rows.append(row)
    goals = {}
    for r in rows:
        if r.available and r.agreement is not None:
            goals.update(agreement_goals(r.agreement, r.row, GOALS["same_pct"], GOALS["within_pct"]))
    settings = {"n_per_condition": cfg.n, "seed": cfg.seed, "conditions": {c: {**CONDITIONS[c], "models": list(
        _models(cfg, c))} for c in cfg.conditions}, "parts": list(cfg.parts),
        "alpha_range_deg": [round(math.degrees(float(a)), 9) for a in cfg.alpha_range], "mu_range": list(MU_RANGE),
        "p_mu_inf": P_MU_INF, "omega_range_rad_s": list(OMEGA_RANGE), "h_m": list(H_VALUES),
        "length_range_m": list(LENGTH_RANGE), "wall_height_m": WALL_HEIGHT, "within_m": WITHIN,
        "rigid_body_options": dict(cfg.rigid_body_options), "baseline_alpha_0": bool(cfg.baseline),
        "mu_bands": [_band(*b) for b in MU_BANDS], "reference": "engine (pymunk, default EngineSettings)",
        "refused_statuses": [Status(c).label for c in REFUSED]}
    agree = AgreementTable(tuple(r.agreement for r in rows if r.agreement is not None), "pymunk engine")
    return TiltWallReport(tuple(rows), goals, fixed_point, settings, cases_out, results, agree)


def validate_tilt_wall(parts: dict[str, Part] | None = None, *, n: int = 500, seed: int = 0, conditions=None,
                       models=None, alpha_range=ALPHA_RANGE, baseline: bool = True,
                       rigid_body_options: dict | None = None, fixed_point: bool = True,
                       run: StudyRun = StudyRun()) -> TiltWallReport:
    """Throw ``n`` random cases per condition (:data:`CONDITIONS`) through the models and the engine; compare.

    ``models`` (a sequence of model names) replaces every condition's models (e.g.
    ``("engine",)``: the engine against itself, a check of the comparison: 100 %).
    ``baseline`` also throws every case at α = 0 (model and engine), so that each row
    says how the same draws agree on the level arm (the known plain-arm gaps: μ ≤ 0.6,
    μ = ∞). ``alpha_range`` (rad) is where α is drawn (``(0.0, 0.0)``: the same throws on the
    level arm, a baseline). ``seed`` seeds one child generator per condition (``SeedSequence(seed).spawn``), so a
    condition's throws do not depend on which others run. ``rigid_body_options`` (e.g.
    ``{"impact_law": "velocity"}``) go to every rigid_body throw. ``fixed_point`` also runs
    :func:`wall_fixed_point` on a 6 cm square (side 0, ω = 3 rad/s: jogs of ≈ 5 mm, L = 0.30 m,
    μ = 1, frictionless wall), with the engine's images of x*, x* − 1 mm, x* − 5 mm.

    ``run`` (:class:`~throwmap.studies.study.StudyRun`): on the experiment runner, one case per trial — ``workers``
    processes (0: one per core); ``out`` (a directory) keeps the cases' trials and resumes an interrupted run
    (``resume``); ``stop_after`` runs at most that many new cases and then raises; ``progress(done, total)`` counts
    cases; ``limits``: the work guard (:mod:`throwmap.budget`) on ``n``, the engine time per throw measured first.
    """
    parts = default_parts() if parts is None else parts
    conditions = tuple(CONDITIONS) if conditions is None else tuple(conditions)
    alpha_range = tuple(float(a) for a in alpha_range)
    if len(alpha_range) != 2 or not all(math.isfinite(a) for a in alpha_range) or alpha_range[1] < alpha_range[0]:
        raise InvalidStateError("alpha_range", f"must be (low, high) in rad with low ≤ high, got {alpha_range}")
    for c in conditions:
        if c not in CONDITIONS:
            raise InvalidStateError("conditions", f"unknown condition {c!r} (choose from {', '.join(CONDITIONS)})")
    n = check_count("n", n, minimum=1)
    n_engine = n * sum(2 + bool(CONDITIONS[c]["wall"]) + bool(baseline) for c in conditions)  # (+ the relaxed cap)
    guard_work("validate-fixtures", "n", n_engine, 400.0, run.limits, throws_per_config=1.0,
               timer=lambda: _timer(parts), hint="fewer throws per condition (--n)", unit="engine throws")
    rb = dict(rigid_body_options or {})
    if models is not None:
        from ..models import check_model

        models = tuple(check_model(m) for m in ([models] if isinstance(models, str) else models))
    cfg = TiltWallConfig(parts={k: part_document(p)["part"] for k, p in parts.items()}, n=n, seed=seed,
                         conditions=conditions, models=models, alpha_range=alpha_range, baseline=baseline,
                         rigid_body_options=rb)
    res = run_study(TILT_WALL, cfg, n * len(conditions), run)
    fp = None
    if fixed_point:
        from ..system.catalogue import rectangle

        fp = wall_fixed_point(rectangle(0.06, 0.06), Arm(h=-0.01, mu=1.0, length=0.30), 3.0, 0,
                              wall=Wall(WALL_HEIGHT, mu=0.0), reference="engine", **rb)
    return tilt_wall_report(cfg, res.trials, fixed_point=fp)
