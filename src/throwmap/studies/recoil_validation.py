"""Validation of "rigid_body" on the moving arm (RecoilThrow) against the pymunk engine.

Random throws as the impulse validation (:mod:`.validation`): a part of the validation set, a stable
side, x uniform on [the part's left limit + 5 mm, 0.45 m], ω ∈ [3, 7] rad/s, μ from
{0.3, 0.6, 1, 2, ∞}, h ∈ {−1, −0.5} cm, ζ ∈ {0.2, 0.5}, recoil 3°; the arm moves as
:meth:`~throwmap.engine.RecoilThrow.for_release_rate` (ω) and both models take the same realisation.

The reference is the engine with its steps divided by 16 (:func:`validate_recoil`), rigid_body takes the
velocity-level impact law of the engine by default. Compared (as :mod:`.tilt_wall`): throws that neither refused (UNRESOLVED, INCONSISTENT, the engine's
TIMEOUT / PENETRATION / UNCONVERGED); a throw agrees on the side when both rest on the same side or
both leave the arm the same way, and within when also |Δx| ≤ 0.5 mm. Wilson 95 % intervals.
Rows also without the throws whose engine answer is bound to pymunk's friction cap (:mod:`.engine_cap`:
the engine again with the cap relaxed 0.7 → 0.9 moves by > 0.25 mm), and split at μ finite / μ = ∞ (where
docs/explanation/validation.md reads the engine as ±2 mm). Also: how often the recoil's answer differs in side (or status)
from the impulse's at the same ω, in rigid_body and in the engine. Every comparison is also given by the one
agreement statistic (:mod:`throwmap.studies.agreement`: refusals apart, same-outcome rests within 0.5 mm).

The study is declared as a :class:`RecoilConfig` and run on the experiment runner (experiment
``"validate-recoil"``, :mod:`throwmap.studies.study`): trial i throws case i of :func:`recoil_cases` (drawn from
the config's seed through :func:`throwmap.rng.as_generator`) in every model and realisation; the result is a
:class:`RecoilValidation` with ``table()``, ``to_dict()`` and ``.plot()``.
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass

import numpy as np
from pydantic import Field

from ..experiments.registry import register_experiment
from ..io.config import part_document, part_from_spec
from ..kernels import codes as C
from ..records.outcome import Status
from ..rng import as_generator
from ..system.arm import Arm
from ..throws.throw import throw
from .agreement import REFUSED, WITHIN, AgreementTable, agreement
from .engine_cap import CAP_ALT, cap_sensitive, friction_cap
from .study import StudyRun, StudyConfig, case_trial, cached_cases, run_study, stored
from .validation import default_parts

__all__ = ["recoil_cases", "validate_recoil", "recoil_table", "RecoilConfig", "RecoilValidation", "RECOIL", "MUS",
           "ZETAS", "WITHIN"]

MUS = (0.3, 0.6, 1.0, 2.0, math.inf)
ZETAS = (0.2, 0.5)
HS = (-0.01, -0.005)
KEYS = ("rb", "engine", "engine_default", "rb_impulse", "engine_impulse", "engine_cap_alt")
"""The answers of each case: rigid_body and the engine (steps / engine_refine) on the recoil, the engine at its
default step on the recoil, both on the impulse, and the fine engine on the recoil with its friction cap relaxed."""


def recoil_cases(n: int, seed=0, parts=None, *, x_max: float = 0.45, recoil: float = math.radians(3.0)):
    """``n`` random throws: a list of dicts (part name, side, x m, ω rad/s, μ, h m, ζ, recoil rad), drawn from
    ``seed`` (an int or a Generator, :func:`throwmap.rng.as_generator`)."""
    parts = default_parts() if parts is None else parts
    names = list(parts)
    rng = as_generator(seed, "seed")
    out = []
    for _ in range(n):
        name = names[int(rng.integers(len(names)))]
        part = parts[name]
        k = int(rng.choice(np.flatnonzero(part.stable)))
        x = float(rng.uniform(-part.uL[k] + 0.005, x_max))
        out.append({"part": name, "side": k, "x": x, "omega": float(rng.uniform(3.0, 7.0)),
                    "mu": float(MUS[int(rng.integers(len(MUS)))]), "h": float(HS[int(rng.integers(len(HS)))]),
                    "zeta": float(ZETAS[int(rng.integers(len(ZETAS)))]), "recoil": recoil})
    return out


def _one(part, c, model, realisation, **opts):
    arm = Arm(h=c["h"], mu=c["mu"])
    o = throw(part, arm, c["x"], c["side"], c["omega"], model=model, realisation=realisation, **opts)
    return o.x, o.side, int(o.status), (o.message or "")


class RecoilConfig(StudyConfig):
    """The recoil study, declared (SI units, rad): ``n`` cases drawn from ``seed`` over ``parts`` (name →
    ``[part]`` table), rigid_body's ``impact_law``, the reference engine's steps divided by ``engine_refine``."""

    parts: dict[str, dict] = Field(default_factory=lambda: {k: part_document(p)["part"]
                                                            for k, p in default_parts().items()})
    n: int = Field(200, ge=1)
    impact_law: str = "velocity"
    engine_refine: int = Field(16, ge=1)


def _recoil_cases(cfg: RecoilConfig):
    parts = {name: part_from_spec(doc) for name, doc in cfg.parts.items()}
    return parts, recoil_cases(cfg.n, cfg.seed, parts)


class RecoilStudy:
    """The ``validate-recoil`` study as an experiment: trial i throws case i (module docstring)."""

    name = "validate-recoil"
    summary = "rigid_body on the moving arm against the pymunk engine, case by case (throwmap validate-recoil)"
    config_type = RecoilConfig

    def parameters(self, cfg: RecoilConfig) -> dict:
        return json.loads(cfg.model_dump_json())

    def trial(self, cfg: RecoilConfig, index: int, rng):
        from ..engine.settings import EngineSettings
        from ..system.motion import RecoilThrow

        parts, cases = cached_cases(cfg, _recoil_cases)
        base = EngineSettings()
        fine = EngineSettings(dt=base.dt / cfg.engine_refine, coarse_dt=base.coarse_dt / cfg.engine_refine)
        c = cases[index]
        part = parts[c["part"]]
        r = RecoilThrow.for_release_rate(c["omega"], c["recoil"], c["zeta"])
        values, statuses = {}, []
        for key, model, real, opts in (("rb", "rigid_body", r, {"impact_law": cfg.impact_law}),
                                       ("engine", "engine", r, {"settings": fine}),
                                       ("engine_default", "engine", r, {}),
                                       ("rb_impulse", "rigid_body", None, {"impact_law": cfg.impact_law}),
                                       ("engine_impulse", "engine", None, {"settings": fine})):
            t0 = time.perf_counter()
            a = _one(part, c, model, real, **opts)
            values.update(_values(key, a, time.perf_counter() - t0))
            statuses.append((key, a[2]))
        # where the engine's answer rests on its friction cap (studies/engine_cap.py): the recoil throw again with
        # the cap relaxed from 0.7 to 0.9; one that moves by > 0.25 mm (or changes side/status) is cap-bound
        t0 = time.perf_counter()
        with friction_cap(CAP_ALT):
            a = _one(part, c, "engine", RecoilThrow.for_release_rate(c["omega"], c["recoil"], c["zeta"]),
                     settings=fine)
        values.update(_values("engine_cap_alt", a, time.perf_counter() - t0))
        return case_trial(index, rng, values, statuses)


def _values(key: str, a: tuple, seconds: float) -> dict:
    return {f"{key}.x": stored(a[0]), f"{key}.side": int(a[1]), f"{key}.status": int(a[2]), f"{key}.message": a[3],
            f"{key}.seconds": float(seconds)}


RECOIL = register_experiment(RecoilStudy())
"""The registered ``validate-recoil`` study."""


@dataclass(frozen=True, slots=True)
class RecoilValidation:
    """The result of :func:`validate_recoil`.

    ``cases`` (dicts, :func:`recoil_cases`), ``results`` (per :data:`KEYS`, one ``(x, side, status, message)``
    per case), ``seconds`` per key (summed over the cases, s), ``impact_law``, ``engine_refine``, ``cap_bound``
    (indices of the cases whose engine answer is bound to its friction cap), ``summary`` (label → the comparison's
    dict, :func:`_summary`) and ``agreement`` (the same comparisons by the one agreement statistic).
    """

    cases: list
    results: dict
    seconds: dict
    impact_law: str
    engine_refine: int
    cap_bound: list
    summary: dict
    agreement: AgreementTable | None = None

    def table(self) -> str:
        """The summary as a Markdown table, then the refusals by reason and the seconds per throw."""
        return recoil_table(self)

    def agreement_table(self) -> str:
        """The comparisons by the one agreement statistic (:meth:`AgreementTable.table`); empty without one."""
        return self.agreement.table() if self.agreement is not None else ""

    def to_dict(self) -> dict:
        """``cases``, ``results``, ``seconds``, ``impact_law``, ``engine_refine``, ``cap_bound``, ``summary`` and
        ``agreement`` (:meth:`AgreementTable.to_dict`)."""
        doc = {"cases": self.cases, "results": self.results, "seconds": self.seconds, "impact_law": self.impact_law,
               "engine_refine": self.engine_refine, "cap_bound": self.cap_bound, "summary": self.summary}
        if self.agreement is not None:
            doc["agreement"] = self.agreement.to_dict()
        return doc

    @classmethod
    def from_dict(cls, d: dict) -> "RecoilValidation":
        """The inverse of :meth:`to_dict` (as read back from JSON: tuples come back as lists, nan as None)."""
        agree = AgreementTable.from_dict(d["agreement"]) if d.get("agreement") else None
        return cls(list(d["cases"]), dict(d["results"]), dict(d["seconds"]), d["impact_law"], int(d["engine_refine"]),
                   list(d["cap_bound"]), dict(d["summary"]), agree)

    def plot(self, ax=None):
        """Every comparison's agreement with its Wilson intervals (:func:`throwmap.viz.agreement.plot_agreement`)."""
        from ..viz.agreement import plot_agreement

        table = self.agreement if self.agreement is not None else AgreementTable((), "engine")
        return plot_agreement(table, ax=ax, title="recoil: rigid_body and the engine on the moving arm")


def recoil_report(cfg: RecoilConfig, trials) -> RecoilValidation:
    """The :class:`RecoilValidation` of the study ``cfg`` from its trials (sorted by index, all of them)."""
    _, cases = cached_cases(cfg, _recoil_cases)
    trials = tuple(trials)
    n = len(cases)
    if len(trials) != n:
        from ..errors import InvalidStateError

        raise InvalidStateError("trials", f"the study has {n} cases, got {len(trials)} trials")
    res = {key: [(float(t.values[f"{key}.x"]), t.values[f"{key}.side"], t.values[f"{key}.status"],
                  t.values[f"{key}.message"]) for t in trials] for key in KEYS}
    secs = {key: float(sum(t.values[f"{key}.seconds"] for t in trials)) for key in KEYS}
    arr = {key: {"x": np.array([v[0] for v in res[key]]), "side": np.array([v[1] for v in res[key]]),
                 "status": np.array([v[2] for v in res[key]])} for key in ("engine", "engine_cap_alt")}
    bound = cap_sensitive(arr["engine"], arr["engine_cap_alt"])
    free = [i for i in range(n) if not bound[i]]
    mus = np.array([c["mu"] for c in cases])
    finite = [i for i in range(n) if math.isfinite(mus[i])]
    k = cfg.engine_refine
    infinite = [i for i in range(n) if i not in set(finite)]
    pairs = {f"rb vs engine/{k} (recoil)": ("rb", "engine", None),
             "rb vs engine (recoil, default dt)": ("rb", "engine_default", None),
             f"engine vs engine/{k} (recoil)": ("engine_default", "engine", None),
             f"rb vs engine/{k} (recoil), cap-bound left out": ("rb", "engine", free),
             f"rb vs engine/{k} (recoil), μ finite": ("rb", "engine", finite),
             f"rb vs engine/{k} (recoil), μ = ∞": ("rb", "engine", infinite),
             f"rb vs engine/{k} (impulse)": ("rb_impulse", "engine_impulse", None),
             "recoil vs impulse (rigid_body)": ("rb", "rb_impulse", None),
             f"recoil vs impulse (engine/{k})": ("engine", "engine_impulse", None)}
    summary, agree = {}, []
    for label, (a, b, keep) in pairs.items():
        ra = res[a] if keep is None else [res[a][i] for i in keep]
        rb = res[b] if keep is None else [res[b][i] for i in keep]
        summary[label] = _summary(ra, rb)
        agree.append(agreement(_arrays(ra), _arrays(rb), label=label, tol=WITHIN))
    # the old results' keys, in their order (engine_cap_alt last)
    return RecoilValidation(cases, res, secs, cfg.impact_law, k, [int(i) for i in np.flatnonzero(bound)], summary,
                            AgreementTable(tuple(agree), "second of each pair"))


def _arrays(rows) -> dict:
    return {"x": np.array([r[0] for r in rows], dtype=float), "side": np.array([r[1] for r in rows], dtype=np.int64),
            "status": np.array([r[2] for r in rows], dtype=np.int64)}


def validate_recoil(n: int = 200, seed: int = 0, parts=None, impact_law: str = "velocity", engine_refine: int = 16, *,
                    run: StudyRun = StudyRun()) -> RecoilValidation:
    """Throw ``n`` random recoil cases with rigid_body (moving arm) and the engine, and both with the impulse.

    The reference is the engine at its step (``dt``, ``coarse_dt``) divided by ``engine_refine``: at its
    default 0.125 ms the engine is not converged on impacts against the fast-moving arm (its own row,
    "engine vs engine/k", shows by how much). ``impact_law`` is rigid_body's (default "velocity", the
    one-step law of time-stepping engines such as pymunk; "routh" differs from it at μ = 0.3). Returns a
    :class:`RecoilValidation` (``to_dict()``: ``cases``, per-throw ``results`` (``rb``, ``engine``,
    ``engine_default``, ``rb_impulse``, ``engine_impulse``, ``engine_cap_alt``: lists of (x, side, status,
    message)), ``summary`` (:func:`_summary`), ``seconds`` per model, ``agreement``).

    ``run`` (:class:`~throwmap.studies.study.StudyRun`): on the experiment runner, one case per trial — ``workers``
    processes (0: one per core), ``out`` keeps the trials and resumes (``resume``), ``stop_after`` runs at most that
    many new cases and then raises; ``progress(done, total)`` counts cases; ``limits``: the runner's work guard.
    """
    from ..budget import check_count

    parts = default_parts() if parts is None else parts
    cfg = RecoilConfig(parts={k: part_document(p)["part"] for k, p in parts.items()}, n=check_count("n", n, minimum=1),
                       seed=seed, impact_law=impact_law, engine_refine=engine_refine)
    res = run_study(RECOIL, cfg, cfg.n, run)
    return recoil_report(cfg, res.trials)


def _wilson(k: int, m: int) -> list:
    from ..experiments.stats import wilson_interval

    lo, hi = wilson_interval(int(k), int(m))
    return [100.0 * lo, 100.0 * hi]


def _summary(a, b) -> dict:
    """``a`` against ``b`` (lists of (x, side, status, message)): module docstring."""
    xa, sa, ta = (np.array([r[q] for r in a]) for q in range(3))
    xb, sb, tb = (np.array([r[q] for r in b]) for q in range(3))
    cmp = ~np.isin(ta, REFUSED) & ~np.isin(tb, REFUSED)
    both_ok = cmp & (ta == C.OK) & (tb == C.OK)
    same_side = both_ok & (sa == sb)
    same_escape = cmp & (ta == tb) & (ta != C.OK)
    dx = np.full(len(a), np.nan)
    dx[same_side] = np.abs(xa[same_side] - xb[same_side])
    same = same_side | same_escape
    within = same_escape | (same_side & (dx <= WITHIN))
    m = int(cmp.sum())
    d = dx[same_side] * 1e3
    why_a: dict = {}
    for (x, s, st, msg), refused in zip(a, np.isin(ta, REFUSED)):
        if refused:
            key = f"{Status(int(st)).label}: {msg}" if msg else Status(int(st)).label
            why_a[key] = why_a.get(key, 0) + 1
    why_b: dict = {}
    for st in tb[np.isin(tb, REFUSED)]:
        why_b[Status(int(st)).label] = why_b.get(Status(int(st)).label, 0) + 1
    return {"n": len(a), "n_compared": m,
            "same_pct": 100.0 * same.sum() / m if m else math.nan, "same_ci95": _wilson(same.sum(), m),
            "within_pct": 100.0 * within.sum() / m if m else math.nan, "within_ci95": _wilson(within.sum(), m),
            "dx_median_mm": float(np.median(d)) if d.size else math.nan,
            "dx_p95_mm": float(np.percentile(d, 95)) if d.size else math.nan,
            "dx_max_mm": float(d.max()) if d.size else math.nan,
            "refused_first": why_a, "refused_second": why_b}


def recoil_table(report) -> str:
    """The summary as a Markdown table, then the refusals by reason and the seconds per throw (``report``: a
    :class:`RecoilValidation` or its ``to_dict()``)."""
    if not isinstance(report, dict):
        report = report.to_dict()
    lines = ["| comparison | compared | same side % (95 % CI) | \\|Δx\\| ≤ 0.5 mm % (95 % CI) | median \\|Δx\\| mm "
             "| p95 \\|Δx\\| mm | max \\|Δx\\| mm |", "|---|---|---|---|---|---|---|"]
    def pct(v, ci):
        return "—" if v is None or not math.isfinite(v) else f"{v:.1f} ({ci[0]:.1f}–{ci[1]:.1f})"

    def mm(v):
        return "—" if v is None or not math.isfinite(v) else f"{v:.3f}"

    for label, s in report["summary"].items():
        lines.append(f"| {label} | {s['n_compared']}/{s['n']} | {pct(s['same_pct'], s['same_ci95'])} | "
                     f"{pct(s['within_pct'], s['within_ci95'])} | {mm(s['dx_median_mm'])} | {mm(s['dx_p95_mm'])} | "
                     f"{mm(s['dx_max_mm'])} |")
    lines.append("")
    for label, s in report["summary"].items():
        for side, key in (("first", "refused_first"), ("second", "refused_second")):
            for why, k in s[key].items():
                lines.append(f"- {label}, refused by the {side}: {k} × {why}")
    secs = report["seconds"]
    n = max(len(report["cases"]), 1)
    lines.append("- seconds per throw: " + ", ".join(f"{k} {v / n:.3f}" for k, v in secs.items()))
    return "\n".join(lines)
