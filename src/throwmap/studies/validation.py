"""Validation of the analytic models against full rigid-body simulation (physics report).

:func:`validate` throws random and gridded cases — several parts (offset-CM
lead-weighted ones included), arm heights h, rates ω, and x on every stable
side — through the analytic models and the engine(s), and compares every model
with the reference engine (pymunk): side agreement, |Δx| statistics, status
agreement, and where each model's assumptions failed; and the same comparisons by
the one agreement statistic (:mod:`throwmap.studies.agreement`: refusals counted
apart, Wilson 95 % intervals). The report is a frozen
:class:`~throwmap.studies.validation_report.ValidationReport` with ``.table()``
(Markdown), ``.to_dict()`` (JSON) and ``.plot()``.

The study is declared as a :class:`ValidationConfig` and run on the experiment runner
(:mod:`throwmap.studies.study`, experiment ``"validate"``): trial i throws case i
(the validation cases first, in :func:`make_cases` order, then the realisation cases),
so ``workers``, ``out`` (resume) and interruptions behave as for
:func:`throwmap.experiments.run_experiment`.
"""

from __future__ import annotations

import math
import os
import time
import warnings
from dataclasses import dataclass

import numpy as np
from pydantic import Field

from ..budget import check_count, guard_work
from ..errors import InvalidStateError
from ..experiments.registry import register_experiment
from ..io.config import part_document, part_from_spec
from ..kernels import codes as C
from ..models import DEFAULT_MODEL, get_model
from ..rng import as_generator
from ..system.arm import Arm
from ..system.catalogue import rectangle, regular_polygon, triangle_30_60_90
from ..system.part import Part
from ..throws.throw import throw_batch
from .agreement import AgreementTable, agreement
from .agreement import goals as agreement_goals
from .study import Mu, StudyConfig, StudyRun, answer_values, answers, cached_cases, case_trial, run_study, stored
from .validation_report import ValidationReport, ValidationRow, compare_row

__all__ = ["ValidationCase", "ValidationConfig", "ValidationReport", "ValidationRow", "VALIDATE", "default_parts", "make_cases",
           "realisation_cases", "validate", "validation_report"]

DEFAULT_MU = 1.5
"""Arm friction of the validation set (measured μ > 1 for the paper's arm, Sec. VI)."""
DEFAULT_H = (-0.01, -0.005)
"""Arm heights of the validation set, m."""
DEFAULT_OMEGA = (3.0, 7.0)
"""Range of release rates, rad/s."""
X_MAX = 0.45
"""Largest starting CM abscissa, m."""
MU_ROWS = (0.3, 0.6, 1.0, 2.0, math.inf)
"""Arm frictions of the table's extra rows: rigid_body vs pymunk on the same cases at each μ
(at μ ≤ 0.6 the impact law decides, :mod:`throwmap.kernels.rigid_body.impact`)."""
BYTES_PER_CASE_MODEL = 600
"""Memory a validation holds per case and model (engines included), bytes: x, side, status, μ and the
kernel record (:data:`throwmap.kernels.codes.NREC` floats), ≈ 270 bytes, twice while the pieces are joined."""
TIMED_ENGINE_THROWS = 3
"""Engine throws timed (after one that warms it) to estimate a validation's time."""


def default_parts() -> dict[str, Part]:
    """The validation parts: the canonical triangle, lead-weighted offset-CM parts, a square, a pentagon."""
    return {
        "triangle": triangle_30_60_90(),
        "triangle+lead": triangle_30_60_90(point_masses=[(0.03, (0.10, 0.01))]),
        "rectangle+lead": Part.from_vertices([(0, 0), (0.08, 0), (0.08, 0.04), (0, 0.04)], mass=0.05,
                                             point_masses=[(0.02, (0.065, 0.01))], name="rectangle+lead"),
        "square": rectangle(0.06, 0.06),
        "pentagon": regular_polygon(5, 0.05),
    }


@dataclass(frozen=True, slots=True)
class ValidationCase:
    """The thrown cases of one part: arrays of x (m), side, ω (rad/s), h (m), and ``kind`` (grid/random)."""

    part_name: str
    x: np.ndarray
    side: np.ndarray
    omega: np.ndarray
    h: np.ndarray
    kind: np.ndarray


def make_cases(parts: dict[str, Part], n: int, seed=0, *, grid: bool = True, hs=DEFAULT_H,
               omega_range=DEFAULT_OMEGA, x_max: float = X_MAX) -> list[ValidationCase]:
    """``n`` random cases spread over ``parts`` (exactly ``n``: the first ``n mod len(parts)`` parts take one more)
    plus, with ``grid``, a grid per part
    (x at 4 points on every stable side × ω ∈ {min, mid, max} at h = hs[0]); the random ones drawn from
    ``seed`` (an int or a Generator, :func:`throwmap.rng.as_generator`)."""
    rng = as_generator(seed, "seed")
    out = []
    n_parts = max(len(parts), 1)
    for i, (name, part) in enumerate(parts.items()):
        per_part = n // n_parts + (1 if i < n % n_parts else 0)
        sides = np.flatnonzero(part.stable)
        xs, ss, oms, hh, kind = [], [], [], [], []
        if grid:
            for k in sides:
                lo = -part.uL[k] + 0.01
                for x in np.linspace(lo, x_max, 4):
                    for om in (omega_range[0], 0.5 * sum(omega_range), omega_range[1]):
                        xs.append(x), ss.append(k), oms.append(om), hh.append(hs[0]), kind.append("grid")
        for _ in range(per_part):
            k = int(rng.choice(sides))
            lo = -part.uL[k] + 0.005
            xs.append(float(rng.uniform(lo, x_max)))
            ss.append(k)
            oms.append(float(rng.uniform(*omega_range)))
            hh.append(float(rng.choice(hs)))
            kind.append("random")
        out.append(ValidationCase(name, np.array(xs), np.array(ss, dtype=np.int64), np.array(oms), np.array(hh),
                                  np.array(kind)))
    return out




REALISATIONS = ("finite, Δt = 5 ms", "finite, Δt = 20 ms", "recoil 3°, PD overshoot")
"""The finite arm motions compared with the impulse (:func:`realisation_for`)."""


def realisation_for(label: str, omega: float):
    """The arm motion called ``label`` (:data:`REALISATIONS`) at release rate ``omega`` (rad/s) (Sec. III-B, IV-A):
    :class:`~throwmap.engine.FiniteThrow` with Δt = 5 ms and 20 ms (constant ω, ending at the rest angle), and the
    Flatland recoil-and-overshoot profile :meth:`~throwmap.engine.RecoilThrow.for_release_rate` (3° recoil, ζ = 0.5)."""
    from ..engine import FiniteThrow, RecoilThrow

    makers = {REALISATIONS[0]: lambda w: FiniteThrow(w, 0.005), REALISATIONS[1]: lambda w: FiniteThrow(w, 0.02),
              REALISATIONS[2]: lambda w: RecoilThrow.for_release_rate(w)}
    return makers[label](float(omega))


def realisation_cases(part: Part, n: int, seed=0, *, omega_range=DEFAULT_OMEGA, x_max: float = X_MAX) -> tuple:
    """``(x, side, ω)`` arrays of the ``n`` throws on which finite arm motions are compared with the impulse, drawn
    from ``seed`` (:func:`throwmap.rng.as_generator`): a stable side, x uniform on [left limit + 1 cm, ``x_max``],
    ω uniform over ``omega_range``."""
    rng = as_generator(seed, "seed")
    sides = np.flatnonzero(part.stable)
    k = rng.choice(sides, n)
    x = np.array([rng.uniform(-part.uL[s] + 0.01, x_max) for s in k])
    om = rng.uniform(*omega_range, n)
    return x, k, om


# ------------------------------------------------------------------ the study on the runner
class ValidationConfig(StudyConfig):
    """The validation study, declared (SI units; see :func:`validate` for the meaning of each key).

    ``parts``: name → ``[part]`` table (:func:`throwmap.io.config.part_document`); ``n``: random cases in all;
    ``seed``: of the random cases (and of the realisation cases); μ = ∞ is written ``"inf"``.
    """

    parts: dict[str, dict] = Field(default_factory=lambda: {k: part_document(p)["part"]
                                                            for k, p in default_parts().items()})
    n: int = Field(400, ge=0)
    grid: bool = True
    models: tuple[str, ...] = ("paper", "small_angle", "rigid_body")
    engines: tuple[str, ...] = ("pymunk",)
    mu: Mu = DEFAULT_MU
    hs: tuple[float, ...] = DEFAULT_H
    omega_range: tuple[float, float] = DEFAULT_OMEGA
    x_max: float = X_MAX
    mu_rows: tuple[Mu, ...] = MU_ROWS
    n_realisations: int = Field(0, ge=0)
    engine_settings: dict | None = None
    mujoco_settings: dict | None = None


@dataclass(frozen=True, slots=True)
class _StudyCases:
    """The cases of a config: ``parts`` by name, the validation cases per part and flat (part name, x, side, ω, h),
    and the realisation cases (x, side, ω) on the first part."""

    parts: dict
    cases: list
    part: np.ndarray
    x: np.ndarray
    side: np.ndarray
    omega: np.ndarray
    h: np.ndarray
    real: tuple

    @property
    def n_cases(self) -> int:
        return int(self.x.size)

    @property
    def n_trials(self) -> int:
        return self.n_cases + int(self.real[0].size)


def _study_cases(cfg: ValidationConfig) -> _StudyCases:
    parts = {name: part_from_spec(doc) for name, doc in cfg.parts.items()}
    cases = make_cases(parts, cfg.n, cfg.seed, grid=cfg.grid, hs=cfg.hs, omega_range=cfg.omega_range, x_max=cfg.x_max)
    cat = (lambda key: np.concatenate([getattr(c, key) for c in cases]) if cases else np.zeros(0))
    names = np.concatenate([np.full(c.x.size, c.part_name, dtype=object) for c in cases]) if cases else np.zeros(0, object)
    real = (np.zeros(0), np.zeros(0, np.int64), np.zeros(0))
    if cfg.n_realisations > 0:
        real = realisation_cases(next(iter(parts.values())), cfg.n_realisations, cfg.seed, omega_range=cfg.omega_range)
    return _StudyCases(parts, cases, names, cat("x"), cat("side").astype(np.int64), cat("omega"), cat("h"), real)


REFERENCE = "pymunk"
"""The engine every model is compared with (its label in the tables)."""
ENGINE_ROWS = {"pymunk": "engine", "mujoco": "mujoco"}
"""The engines a validation may throw through: label → the model that runs it."""
VALIDATED = DEFAULT_MODEL
"""The model held to the validation's goals and thrown again at the arm frictions of ``mu_rows``."""


def _engine_keywords(cfg: ValidationConfig) -> dict:
    """Each engine's throw keywords by label (its settings; the pymunk engine in this process)."""
    eng, muj = _settings(cfg)
    return {"pymunk": {"workers": 1, **eng}, "mujoco": muj}


def _settings(cfg: ValidationConfig) -> tuple[dict, dict]:
    """The engine's and MuJoCo's keyword ``settings`` (empty: their defaults)."""
    eng = {}
    if cfg.engine_settings:
        from ..engine.settings import EngineSettings

        eng = {"settings": EngineSettings(**cfg.engine_settings)}
    muj = {"settings": None}
    if cfg.mujoco_settings:
        from ..engine.mujoco.settings import MujocoSettings

        muj = {"settings": MujocoSettings(**cfg.mujoco_settings)}
    return eng, muj


def _one(part, arm, x, side, omega, model, **kw):
    """One throw through ``throw_batch`` (refusals as statuses, warnings quiet): ``(x, side, status, record)``."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        b = throw_batch(part, arm, np.array([x]), np.array([side], dtype=np.int64), np.array([omega]), model=model,
                        **kw)
    return float(b.x[0]), int(b.side[0]), int(b.status[0]), b.records[0]


class ValidationStudy:
    """The ``validate`` study as an experiment: trial i throws case i (module docstring)."""

    name = "validate"
    summary = "validation: analytic models against the pymunk engine, case by case (throwmap validate)"
    config_type = ValidationConfig

    def parameters(self, cfg: ValidationConfig) -> dict:
        import json

        return json.loads(cfg.model_dump_json())

    def trial(self, cfg: ValidationConfig, index: int, rng):
        sc = cached_cases(cfg, _study_cases)
        if index >= sc.n_cases:
            return self._realisation_trial(cfg, sc, index, rng)
        part, h = sc.parts[str(sc.part[index])], float(sc.h[index])
        x, side, omega = float(sc.x[index]), int(sc.side[index]), float(sc.omega[index])
        kw = _engine_keywords(cfg)
        arm = Arm(h=h, mu=cfg.mu)
        values, statuses = {}, []
        for model in cfg.models:
            a = _one(part, arm, x, side, omega, model, on_invalid="status")
            values.update(answer_values(model, *a))
            statuses.append((model, a[2]))
        a = _one(part, arm, x, side, omega, ENGINE_ROWS[REFERENCE], on_invalid="status", **kw[REFERENCE])
        values.update(answer_values(REFERENCE, *a))
        statuses.insert(0, (REFERENCE, a[2]))
        for label in _other_engines(cfg):
            a = _one(part, arm, x, side, omega, ENGINE_ROWS[label], on_invalid="status", **kw[label])
            values.update(answer_values(label, *a[:3]))
        for j, mu in enumerate(cfg.mu_rows):
            arm_j = Arm(h=h, mu=float(mu))
            rb = _one(part, arm_j, x, side, omega, VALIDATED, on_invalid="status")
            values.update(answer_values(f"mu{j}.{VALIDATED}", *rb[:3]))
            values[f"mu{j}.{VALIDATED}.slips"] = stored(rb[3][C.N_SLIPS])
            en = _one(part, arm_j, x, side, omega, ENGINE_ROWS[REFERENCE], on_invalid="status", **kw[REFERENCE])
            values.update(answer_values(f"mu{j}.{REFERENCE}", *en[:3]))
        return case_trial(index, rng, values, statuses)

    def _realisation_trial(self, cfg, sc, index, rng):
        from ..engine import engine_run

        j = index - sc.n_cases
        part = next(iter(sc.parts.values()))
        arm = Arm(h=cfg.hs[0], mu=cfg.mu)
        x, k, om = (float(sc.real[0][j]), int(sc.real[1][j]), float(sc.real[2][j]))
        b = throw_batch(part, arm, np.array([x]), np.array([k]), np.array([om]), model=ENGINE_ROWS[REFERENCE], workers=1)
        values = answer_values("impulse", b.x[0], b.side[0], b.status[0])
        statuses = [("impulse", b.status[0])]
        for r, label in enumerate(REALISATIONS):
            run = engine_run(part, arm, x, k, om, realisation=realisation_for(label, om))
            values.update(answer_values(f"real{r}", run.states[0][0], run.states[0][1], int(run.status)))
            statuses.append((label, int(run.status)))
        return case_trial(index, rng, values, statuses)


VALIDATE = register_experiment(ValidationStudy())
"""The registered ``validate`` study."""


def _assumptions(model: str, res: dict) -> str:
    """The model's own account of its assumptions over these throws (``—`` if it gives none)."""
    report = getattr(get_model(model), "assumptions", None)
    return report(res["recs"], res["mu"], res["status"]) if report is not None else "—"


def validation_report(cfg: ValidationConfig, trials) -> ValidationReport:
    """The report of the study ``cfg`` from its trials (sorted by index, all of them): the validation table's rows
    (the models at ``cfg.mu``, "paper, assumptions hold", "pymunk (self)", one rigid_body row per μ of
    ``cfg.mu_rows``), the goals, the realisation rows, and every comparison's agreement."""
    sc = cached_cases(cfg, _study_cases)
    trials = tuple(trials)
    if len(trials) != sc.n_trials:
        from ..errors import InvalidStateError

        raise InvalidStateError("trials", f"the study has {sc.n_trials} cases, got {len(trials)} trials")
    vt, rt = trials[:sc.n_cases], trials[sc.n_cases:]
    mus = np.full(len(vt), float(cfg.mu))
    results = {m: {**answers(vt, m, record=C.NREC), "mu": mus} for m in cfg.models}
    results[REFERENCE] = {**answers(vt, REFERENCE, record=C.NREC), "mu": mus}
    for label in _other_engines(cfg):
        results[label] = {**answers(vt, label), "recs": np.full((len(vt), C.NREC), np.nan), "mu": mus}
    ref = results[REFERENCE]
    rows, agree = [], []

    def add(name, sub_ref, res, assumptions, at=None):
        row = compare_row(name, sub_ref, res, assumptions)
        ag = agreement(res, sub_ref, label=name)
        rows.insert(at, row) if at is not None else rows.append(row)
        agree.insert(at, ag) if at is not None else agree.append(ag)

    for model in list(cfg.models) + list(_other_engines(cfg)):
        add(model, ref, results[model], _assumptions(ENGINE_ROWS.get(model, model), results[model]))
    add(f"{REFERENCE} (self)", ref, ref, _assumptions(ENGINE_ROWS[REFERENCE], ref))
    for i, model in enumerate(cfg.models):  # a model where its own assumptions hold (the paper's: no lift-off, no slip)
        own = getattr(get_model(model), "assumptions_hold", None)
        holds = own(results[model]["recs"], cfg.mu) if own is not None else None
        if holds is not None and holds.any():
            sub = {k: v[holds] for k, v in results[model].items()}
            subref = {k: v[holds] for k, v in ref.items()}
            at = next(j for j, r in enumerate(rows) if r.model == model) + 1
            add(f"{model}, assumptions hold", subref, sub, f"{100 * holds.mean():.0f} % of throws", at=at)
    goals = {}
    if VALIDATED in results:
        at = next(j for j, r in enumerate(rows) if r.model == VALIDATED)
        goals = agreement_goals(agree[at], f"{VALIDATED} vs {REFERENCE}")
    settings = {"n_random": cfg.n, "grid": cfg.grid, "seed": cfg.seed, "mu": cfg.mu, "h": list(cfg.hs),
                "omega_range": list(cfg.omega_range), "parts": list(cfg.parts), "models": list(cfg.models),
                "engines": list(cfg.engines), "n_throws": int(ref["x"].size)}
    case_info = {c.part_name: int(c.x.size) for c in sc.cases}
    real_rows, real_agree = [], []
    if rt:
        imp = answers(rt, "impulse")
        for r, label in enumerate(REALISATIONS):
            res = answers(rt, f"real{r}")
            real_rows.append(compare_row(label, imp, res, ""))
            real_agree.append(agreement(res, imp, label=f"{label} vs impulse"))
        settings["n_realisations"] = cfg.n_realisations
    for j, mu in enumerate(cfg.mu_rows):
        res = answers(vt, f"mu{j}.{VALIDATED}")
        res["slips"] = np.array([float(t.values[f"mu{j}.{VALIDATED}.slips"]) for t in vt], dtype=float)
        mref = answers(vt, f"mu{j}.{REFERENCE}")
        slip = 100.0 * np.mean(np.nan_to_num(res["slips"]) > 0) if res["slips"].size else math.nan
        add(f"{VALIDATED}, μ = {_mu_label(mu)}", mref, res, f"slip in {slip:.0f} % of throws")
    settings["mu_rows"] = [float(m) for m in cfg.mu_rows]
    return ValidationReport(REFERENCE, case_info, results, tuple(rows), goals, settings, tuple(real_rows),
                            AgreementTable(tuple(agree + real_agree), f"{REFERENCE} engine"))


def _other_engines(cfg: ValidationConfig) -> tuple:
    """The engines of ``cfg`` besides the reference, in order (each one more row)."""
    return tuple(e for e in cfg.engines if e != REFERENCE)


def _mu_label(mu: float) -> str:
    return "∞" if math.isinf(mu) else f"{mu:g}"


def _guard_validation(parts, cfg: "ValidationConfig", workers, limits) -> dict:
    """The work guard of :func:`validate` (:func:`throwmap.budget.guard_work` on ``n``)."""
    hs, omega_range, mu, engine_settings = cfg.hs, cfg.omega_range, cfg.mu, cfg.engine_settings
    n_grid = sum(12 * len(p.stable_sides) for p in parts.values()) if cfg.grid else 0
    n_cases = cfg.n + n_grid
    n_engines = 1 + len(_other_engines(cfg))
    n_models = len(tuple(cfg.models)) + n_engines
    workers_n = (os.cpu_count() or 1) if workers in (0, None) else max(1, int(workers))
    engine_per_case = n_engines / workers_n + 3 * cfg.n_realisations / max(n_cases, 1)

    def seconds_per_engine_throw() -> float:
        case = make_cases(dict([next(iter(parts.items()))]), 0, grid=True, hs=hs, omega_range=omega_range)[0]
        part = parts[case.part_name]
        k = min(1 + TIMED_ENGINE_THROWS, case.x.size)
        kw = {"settings": engine_settings} if engine_settings else {}
        arm = Arm(h=float(case.h[0]), mu=mu)
        throw_batch(part, arm, case.x[:1], case.side[:1], case.omega[:1], model="engine", on_invalid="status", **kw)
        t0 = time.perf_counter()
        throw_batch(part, arm, case.x[1:k], case.side[1:k], case.omega[1:k], model="engine", on_invalid="status",
                    **kw)
        return (time.perf_counter() - t0) / max(k - 1, 1)

    return guard_work("validate", "n", n_cases, BYTES_PER_CASE_MODEL * n_models, limits,
                      throws_per_config=engine_per_case, timer=seconds_per_engine_throw,
                      hint="fewer random throws (--n)", unit="cases")


def validate(parts: dict[str, Part] | None = None, *, run: StudyRun = StudyRun(workers=0),
             **config) -> ValidationReport:
    """Throw the validation set through ``models`` and ``engines``; compare each with pymunk.

    The rows are at arm friction ``mu``; then, for each μ in ``mu_rows`` (default
    :data:`MU_ROWS`, ``()`` for none), one more row: rigid_body against pymunk on
    the same cases at that μ (label ``rigid_body, μ = …``).

    ``config``: the study's keys (:class:`ValidationConfig`): ``n`` random cases (400) and the ``grid`` of each part
    (True), ``seed`` (0), ``models`` (paper, small_angle, rigid_body), ``engines`` ⊆ {"pymunk", "mujoco"} ("pymunk"
    is always run: it is the reference), ``mu`` (1.5), ``hs``, ``omega_range``, ``mu_rows``, ``n_realisations``
    (> 0 also compares finite arm motions with the impulse on that many throws of the first part,
    :data:`REALISATIONS`), ``engine_settings`` / ``mujoco_settings`` (an :class:`~throwmap.engine.EngineSettings` /
    ``MujocoSettings``, or a dict of their fields). An unknown key is refused naming it.

    ``run`` (:class:`~throwmap.studies.study.StudyRun`): on the experiment runner, each case one trial — ``workers``
    processes (0: one per core), ``out`` keeps the trials and resumes an interrupted run (``resume``),
    ``stop_after`` runs at most that many new cases and then raises, ``progress(done, total)`` counts cases, and
    ``limits``, the work guard (:mod:`throwmap.budget`): memory :data:`BYTES_PER_CASE_MODEL` per case and model,
    time from :data:`TIMED_ENGINE_THROWS` engine throws measured now (the engine throws dominate; shared over
    ``workers``); above the limits it is refused with one line on ``n``, unless forced.
    """
    import dataclasses

    parts = default_parts() if parts is None else parts
    unknown = sorted(set(config) - set(ValidationConfig.model_fields) - {"parts"})
    if unknown or "parts" in config:
        key = unknown[0] if unknown else "parts"
        raise InvalidStateError(key, f"unknown key for validate (its keys: "
                                     f"{', '.join(k for k in ValidationConfig.model_fields if k != 'parts')}; the parts "
                                     f"are the first argument)")
    for e in tuple(config.get("engines", ("pymunk",))):
        if e not in ENGINE_ROWS:
            raise InvalidStateError("engines", f"unknown engine {e!r} (choose from {', '.join(ENGINE_ROWS)})")
    check_count("n", config.get("n", 400))
    as_fields = (lambda s: None if s is None else (dict(s) if isinstance(s, dict) else dataclasses.asdict(s)))
    fields = {k: (as_fields(v) if k in ("engine_settings", "mujoco_settings") else
                  tuple(v) if isinstance(v, (list, tuple)) else v) for k, v in config.items()}
    cfg = ValidationConfig(parts={k: part_document(p)["part"] for k, p in parts.items()}, **fields)
    _guard_validation(parts, cfg, run.workers, run.limits)
    sc = cached_cases(cfg, _study_cases)
    res = run_study(VALIDATE, cfg, sc.n_trials, dataclasses.replace(run, workers=run.workers or 0))
    return validation_report(cfg, res.trials)
