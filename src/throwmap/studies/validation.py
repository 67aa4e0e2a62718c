"""Validation of the analytic models against full rigid-body simulation (issue: physics report).

:func:`validate` throws random and gridded cases — several parts (offset-CM
lead-weighted ones included), arm heights h, rates ω, and x on every stable
side — through the analytic models and the engine(s), and compares every model
with the reference engine (pymunk): side agreement, |Δx| statistics, status
agreement, and where each model's assumptions failed. The report is a frozen
:class:`ValidationReport` with ``.table()`` (Markdown) and ``.to_dict()`` (JSON).
"""

from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass, field

import numpy as np

from ..budget import Limits, DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, check_count, check_limits, guard_work
from ..system.arm import Arm
from ..kernels import codes as C
from ..records.outcome import Status
from ..system.part import Part
from ..system.catalogue import rectangle, regular_polygon, triangle_30_60_90
from ..models import get_model
from ..throws.throw import throw_batch

__all__ = ["ValidationCase", "ValidationReport", "default_parts", "make_cases", "validate"]

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


def make_cases(parts: dict[str, Part], n: int, seed: int = 0, *, grid: bool = True, hs=DEFAULT_H,
               omega_range=DEFAULT_OMEGA, x_max: float = X_MAX) -> list[ValidationCase]:
    """``n`` random cases spread over ``parts`` plus, with ``grid``, a grid per part
    (x at 4 points on every stable side × ω ∈ {min, mid, max} at h = hs[0])."""
    rng = np.random.default_rng(seed)
    out = []
    per_part = max(1, n // max(len(parts), 1))
    for name, part in parts.items():
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


@dataclass(frozen=True, slots=True)
class ValidationReport:
    """Results of :func:`validate`.

    ``results[model]`` holds flat arrays over all cases: ``x``, ``side``,
    ``status`` and, for analytic models, the per-throw record flags. ``rows`` is
    the comparison table (one dict per model vs ``reference``), ``goals`` the
    rigid_body-vs-pymunk goals with pass/fail, ``settings`` what was run.
    """

    reference: str
    cases: dict
    results: dict
    rows: tuple
    goals: dict
    settings: dict = field(default_factory=dict)
    realisation_rows: tuple = ()

    def table(self) -> str:
        """The comparison table in Markdown (distances in mm)."""
        head = ("| model vs " + self.reference + " | throws | same status % | same side % | |Δx| median (mm) "
                "| |Δx| p90 (mm) | |Δx| max (mm) | |Δx| ≤ 0.5 mm % | assumptions failed |")
        lines = [head, "|" + "---|" * 9]
        for r in self.rows:
            lines.append(
                f"| {r['model']} | {r['n']} | {r['same_status_pct']:.1f} | {r['same_side_pct']:.1f} | "
                f"{_f(r['dx_median_mm'])} | {_f(r['dx_p90_mm'])} | {_f(r['dx_max_mm'])} | "
                f"{_f(r['within_0p5mm_pct'], '.1f')} | {r['assumptions']} |"
            )
        return "\n".join(lines)

    def realisation_table(self) -> str:
        """How far finite arm motions land from the impulse idealisation (engine vs engine, mm)."""
        if not self.realisation_rows:
            return ""
        lines = ["| realisation vs impulse (pymunk) | throws | same status % | same side % | |Δx| median (mm) "
                 "| |Δx| p90 (mm) | |Δx| max (mm) |", "|" + "---|" * 7]
        for r in self.realisation_rows:
            lines.append(f"| {r['model']} | {r['n']} | {r['same_status_pct']:.1f} | {r['same_side_pct']:.1f} | "
                         f"{_f(r['dx_median_mm'], '.2f')} | {_f(r['dx_p90_mm'], '.2f')} | {_f(r['dx_max_mm'], '.2f')} |")
        return "\n".join(lines)

    def goal_lines(self) -> list[str]:
        return [f"{name}: {g['value']:.2f} % (goal ≥ {g['goal']:g} %) — {'met' if g['met'] else 'NOT met'}"
                for name, g in self.goals.items()]

    def to_dict(self) -> dict:
        from ..serial import json_ready

        return json_ready({"reference": self.reference, "rows": list(self.rows), "goals": self.goals,
                           "settings": self.settings, "table_markdown": self.table(),
                           "realisations": list(self.realisation_rows)})

    @classmethod
    def from_dict(cls, d: dict) -> "ValidationReport":
        """The report's summary back from :meth:`to_dict` (rows, goals, settings, realisations);
        the per-throw arrays (``cases``, ``results``) are not written and come back empty."""
        return cls(d["reference"], {}, {}, tuple(d["rows"]), dict(d["goals"]), dict(d.get("settings", {})),
                   tuple(d.get("realisations", ())))


def _f(v, spec=".3f"):
    return "—" if v is None or not math.isfinite(v) else format(v, spec)


def _compare(name, ref, res, assumptions: str) -> dict:
    both_ok = (ref["status"] == Status.OK) & (res["status"] == Status.OK)
    same_status = ref["status"] == res["status"]
    same_side = both_ok & (ref["side"] == res["side"])
    n = int(ref["status"].size)
    dx = np.abs(res["x"][same_side] - ref["x"][same_side]) * 1e3
    # a throw counts as within 0.5 mm when both end ok on the same side that close, or both escape alike
    within = np.zeros(n, dtype=bool)
    within[same_side] = np.abs(res["x"][same_side] - ref["x"][same_side]) <= 0.5e-3
    within |= same_status & ~both_ok
    return {
        "model": name,
        "n": n,
        "n_both_ok": int(both_ok.sum()),
        "same_status_pct": 100.0 * same_status.mean() if n else math.nan,
        "same_side_pct": 100.0 * (same_side.sum() + (same_status & ~both_ok).sum()) / n if n else math.nan,
        "dx_median_mm": float(np.median(dx)) if dx.size else math.nan,
        "dx_p90_mm": float(np.percentile(dx, 90)) if dx.size else math.nan,
        "dx_max_mm": float(dx.max()) if dx.size else math.nan,
        "within_0p5mm_pct": 100.0 * within.mean() if n else math.nan,
        "assumptions": assumptions,
    }


def _assumptions(model: str, res: dict) -> str:
    """The model's own account of its assumptions over these throws (``—`` if it gives none)."""
    report = getattr(get_model(model), "assumptions", None)
    return report(res["recs"], res["mu"], res["status"]) if report is not None else "—"


def realisation_departures(part: Part, arm: Arm, n: int = 40, seed: int = 0, *, workers: int | None = 0,
                           omega_range=DEFAULT_OMEGA, x_max: float = X_MAX) -> tuple:
    """Engine throws by finite arm motions compared with the impulse idealisation (Sec. III-B, IV-A).

    Realisations: :class:`~throwmap.engine.FiniteThrow` with Δt = 5 ms and 20 ms
    (constant ω, ending at the rest angle) and the Flatland recoil-and-overshoot
    profile :meth:`~throwmap.engine.RecoilThrow.for_release_rate` (3° recoil, ζ = 0.5).
    Returns one comparison row per realisation.
    """
    from ..engine import FiniteThrow, RecoilThrow

    rng = np.random.default_rng(seed)
    sides = np.flatnonzero(part.stable)
    k = rng.choice(sides, n)
    x = np.array([rng.uniform(-part.uL[s] + 0.01, x_max) for s in k])
    om = rng.uniform(*omega_range, n)
    imp = throw_batch(part, arm, x, k, om, model="engine", workers=workers)
    ref = {"x": imp.x, "side": imp.side, "status": imp.status}
    rows = []
    for label, make in (("finite, Δt = 5 ms", lambda w: FiniteThrow(w, 0.005)),
                        ("finite, Δt = 20 ms", lambda w: FiniteThrow(w, 0.02)),
                        ("recoil 3°, PD overshoot", lambda w: RecoilThrow.for_release_rate(w))):
        xs, ss, st = np.empty(n), np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64)
        for i in range(n):
            from ..engine import engine_run

            r = engine_run(part, arm, float(x[i]), int(k[i]), float(om[i]), realisation=make(float(om[i])))
            xs[i], ss[i], st[i] = r.states[0][0], r.states[0][1], int(r.status)
        rows.append(_compare(label, ref, {"x": xs, "side": ss, "status": st}, ""))
    return tuple(rows)


def _guard_validation(parts, n, grid, models, engines, mu, hs, omega_range, workers, engine_settings,
                      n_realisations, mu_rows, max_memory, max_seconds, force) -> dict:
    """The work guard of :func:`validate` (:func:`throwmap.budget.guard_work` on ``n``)."""
    n_grid = sum(12 * len(p.stable_sides) for p in parts.values()) if grid else 0
    n_cases = n + n_grid
    n_models = len(tuple(models)) + 1 + ("mujoco" in engines)
    workers_n = (os.cpu_count() or 1) if workers in (0, None) else max(1, int(workers))
    engine_per_case = (1 + ("mujoco" in engines)) / workers_n + 3 * n_realisations / max(n_cases, 1)

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

    return guard_work("validate", "n", n_cases, BYTES_PER_CASE_MODEL * n_models, Limits(max_memory, max_seconds, force),
                      throws_per_config=engine_per_case, timer=seconds_per_engine_throw,
                      hint="fewer random throws (--n)", unit="cases")


def validate(parts: dict[str, Part] | None = None, *, n: int = 400, seed: int = 0, grid: bool = True,
             models=("paper", "small_angle", "rigid_body"), engines=("pymunk",), mu: float = DEFAULT_MU,
             hs=DEFAULT_H, omega_range=DEFAULT_OMEGA, workers: int | None = 0, engine_settings=None,
             mujoco_settings=None, progress=None, n_realisations: int = 0,
             mu_rows=MU_ROWS, max_memory: float = DEFAULT_MAX_MEMORY, max_seconds: float = DEFAULT_MAX_SECONDS,
             force: bool = False) -> ValidationReport:
    """Throw the validation set through ``models`` and ``engines``; compare each with pymunk.

    The rows are at arm friction ``mu``; then, for each μ in ``mu_rows`` (default
    :data:`MU_ROWS`, ``()`` for none), one more row: rigid_body against pymunk on
    the same cases at that μ (label ``rigid_body, μ = …``).

    ``engines`` ⊆ {"pymunk", "mujoco"} ("pymunk" is always run: it is the
    reference). ``workers`` processes run the engine (0: one per core).
    ``n_realisations`` > 0 also compares finite arm motions with the impulse on
    that many throws of the first part (:func:`realisation_departures`).
    ``progress(done, total)`` is called as engine throws finish.

    Work guard (:mod:`throwmap.budget`): memory :data:`BYTES_PER_CASE_MODEL` per case
    and model, time from :data:`TIMED_ENGINE_THROWS` engine throws measured now (the
    engine throws dominate; shared over ``workers``); above ``max_memory`` (bytes) or
    ``max_seconds`` (s) it is refused with one line on ``n``, unless ``force``.
    """
    parts = default_parts() if parts is None else parts
    engines = tuple(engines)
    for e in engines:
        if e not in ("pymunk", "mujoco"):
            from ..errors import ThrowmapError

            raise ThrowmapError("engines", f"unknown engine {e!r} (choose from pymunk, mujoco)")
    _guard_validation(parts, check_count("n", n), grid, models, engines, mu, hs, omega_range, workers,
                      engine_settings, n_realisations, mu_rows, max_memory, max_seconds, force)
    cases = make_cases(parts, n, seed, grid=grid, hs=hs, omega_range=omega_range)
    total = sum(c.x.size for c in cases) * (1 + ("mujoco" in engines))
    done = [0]
    acc: dict[str, dict[str, list]] = {}

    def add(model, x, side, status, recs, mus):
        d = acc.setdefault(model, {"x": [], "side": [], "status": [], "recs": [], "mu": []})
        d["x"].append(x), d["side"].append(side), d["status"].append(status), d["recs"].append(recs)
        d["mu"].append(mus)

    for case in cases:
        part = parts[case.part_name]
        for hv in np.unique(case.h):
            sel = case.h == hv
            arm = Arm(h=float(hv), mu=mu)
            xs, ss, oms = case.x[sel], case.side[sel], case.omega[sel]
            mus = np.full(xs.size, mu)
            for model in models:
                import warnings

                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    b = throw_batch(part, arm, xs, ss, oms, model=model, on_invalid="status")
                add(model, b.x, b.side, b.status, b.records, mus)

            def tick(k, tot, base=done[0]):
                if progress is not None:
                    progress(base + k, total)

            def tick2(k, tot, base=done[0] + xs.size):
                if progress is not None:
                    progress(base + k, total)

            b = throw_batch(part, arm, xs, ss, oms, model="engine", on_invalid="status", workers=workers,
                            progress=tick, **({"settings": engine_settings} if engine_settings else {}))
            done[0] += xs.size
            add("pymunk", b.x, b.side, b.status, b.records, mus)
            if "mujoco" in engines:
                b = throw_batch(part, arm, xs, ss, oms, model="mujoco", on_invalid="status", progress=tick2,
                                settings=mujoco_settings)
                done[0] += xs.size
                add("mujoco", b.x, b.side, b.status, np.full_like(b.records, np.nan), mus)
    results = {}
    for model, d in acc.items():
        results[model] = {"x": np.concatenate(d["x"]), "side": np.concatenate(d["side"]),
                          "status": np.concatenate(d["status"]), "recs": np.concatenate(d["recs"]),
                          "mu": np.concatenate(d["mu"])}
    ref = results["pymunk"]
    rows = []
    for model in list(models) + (["mujoco"] if "mujoco" in engines else []):
        res = results[model]
        rows.append(_compare(model, ref, res, _assumptions(model, res)))
    rows.append(_compare("pymunk (self)", ref, ref, _assumptions("engine", ref)))
    # the paper model where its own assumptions hold
    if "paper" in results:
        pr = results["paper"]["recs"]
        holds = (np.nan_to_num(pr[:, C.N_MIN], nan=1.0) >= 0) & (np.nan_to_num(pr[:, C.MU_MAX], nan=0.0) <= mu)
        if holds.any():
            sub = {k: v[holds] for k, v in results["paper"].items()}
            subref = {k: v[holds] for k, v in ref.items()}
            r = _compare("paper, assumptions hold", subref, sub, f"{100 * holds.mean():.0f} % of throws")
            rows.insert(1, r)
    goals = {}
    if "rigid_body" in results:
        r = next(r for r in rows if r["model"] == "rigid_body")
        goals["rigid_body vs pymunk: same side"] = {"value": r["same_side_pct"], "goal": 99.0,
                                                     "met": bool(r["same_side_pct"] >= 99.0)}
        goals["rigid_body vs pymunk: |Δx| ≤ 0.5 mm"] = {"value": r["within_0p5mm_pct"], "goal": 95.0,
                                                         "met": bool(r["within_0p5mm_pct"] >= 95.0)}
    settings = {"n_random": n, "grid": grid, "seed": seed, "mu": mu, "h": list(hs), "omega_range": list(omega_range),
                "parts": list(parts), "models": list(models), "engines": list(engines),
                "n_throws": int(ref["x"].size)}
    case_info = {c.part_name: int(c.x.size) for c in cases}
    real_rows = ()
    if n_realisations > 0:
        first = next(iter(parts.values()))
        real_rows = realisation_departures(first, Arm(h=hs[0], mu=mu), n_realisations, seed, workers=workers,
                                           omega_range=omega_range)
        settings["n_realisations"] = n_realisations
    rows.extend(_mu_rows(parts, cases, mu_rows, workers, engine_settings))
    settings["mu_rows"] = [float(m) for m in mu_rows]
    return ValidationReport("pymunk", case_info, results, tuple(rows), goals, settings, real_rows)


def _mu_label(mu: float) -> str:
    return "∞" if math.isinf(mu) else f"{mu:g}"


def _mu_rows(parts: dict, cases: list, mu_values, workers, engine_settings) -> list[dict]:
    """One row per μ: model rigid_body against pymunk on the same cases, both at that arm friction.

    The row's assumptions column says how many throws had an impact or contact phase
    outside the friction cone (N_SLIPS > 0): where such a slip stops and reverses, the
    two impact laws differ (:mod:`throwmap.kernels.rigid_body.impact`).
    """
    out = []
    for mu in mu_values:
        acc = {m: {"x": [], "side": [], "status": [], "slips": []} for m in ("rigid_body", "pymunk")}
        for case in cases:
            part = parts[case.part_name]
            for hv in np.unique(case.h):
                sel = case.h == hv
                arm = Arm(h=float(hv), mu=float(mu))
                args = (part, arm, case.x[sel], case.side[sel], case.omega[sel])
                import warnings

                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    rb = throw_batch(*args, model="rigid_body", on_invalid="status")
                en = throw_batch(*args, model="engine", on_invalid="status", workers=workers,
                                 **({"settings": engine_settings} if engine_settings else {}))
                for key, b in (("rigid_body", rb), ("pymunk", en)):
                    acc[key]["x"].append(b.x), acc[key]["side"].append(b.side), acc[key]["status"].append(b.status)
                acc["rigid_body"]["slips"].append(rb.records[:, C.N_SLIPS])
        ref = {k: np.concatenate(v) for k, v in acc["pymunk"].items() if v}
        res = {k: np.concatenate(v) for k, v in acc["rigid_body"].items()}
        slip = 100.0 * np.mean(np.nan_to_num(res["slips"]) > 0) if res["slips"].size else math.nan
        out.append(_compare(f"rigid_body, μ = {_mu_label(mu)}", ref, res, f"slip in {slip:.0f} % of throws"))
    return out
