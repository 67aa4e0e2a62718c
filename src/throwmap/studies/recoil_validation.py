"""Validation of "rigid_body" on the moving arm (RecoilThrow) against the pymunk engine (issue 12 item 2).

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
the README reads the engine as ±2 mm). Also: how often the recoil's answer differs in side (or status)
from the impulse's at the same ω, in rigid_body and in the engine.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..kernels import codes as C
from ..system.arm import Arm
from ..records.outcome import Status
from ..throws.throw import throw
from .engine_cap import CAP_ALT, cap_sensitive, friction_cap
from .validation import default_parts

__all__ = ["recoil_cases", "validate_recoil", "recoil_table", "MUS", "ZETAS", "WITHIN"]

MUS = (0.3, 0.6, 1.0, 2.0, math.inf)
ZETAS = (0.2, 0.5)
HS = (-0.01, -0.005)
WITHIN = 0.5e-3
REFUSED = (C.UNRESOLVED, C.TIMEOUT, C.PENETRATION, C.UNCONVERGED, C.INCONSISTENT, C.INVALID_START)


def recoil_cases(n: int, seed: int = 0, parts=None, *, x_max: float = 0.45, recoil: float = math.radians(3.0)):
    """``n`` random throws: a list of dicts (part name, side, x m, ω rad/s, μ, h m, ζ, recoil rad)."""
    parts = default_parts() if parts is None else parts
    names = list(parts)
    rng = np.random.default_rng(seed)
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


def validate_recoil(n: int = 200, seed: int = 0, parts=None, impact_law: str = "velocity", engine_refine: int = 16,
                    progress=None) -> dict:
    """Throw ``n`` random recoil cases with rigid_body (moving arm) and the engine, and both with the impulse.

    The reference is the engine at its step (``dt``, ``coarse_dt``) divided by ``engine_refine``: at its
    default 0.125 ms the engine is not converged on impacts against the fast-moving arm (its own row,
    "engine vs engine/k", shows by how much). ``impact_law`` is rigid_body's (default "velocity", the
    one-step law of time-stepping engines such as pymunk; "routh" differs from it at μ = 0.3). Returns a dict: ``cases``, per-throw ``results`` (``rb``,
    ``engine``, ``engine_default``, ``rb_impulse``, ``engine_impulse``: lists of (x, side, status,
    message)), ``summary`` (:func:`_summary`), ``seconds`` per model."""
    from ..system.motion import RecoilThrow
    from ..engine.settings import EngineSettings

    base = EngineSettings()
    fine = EngineSettings(dt=base.dt / engine_refine, coarse_dt=base.coarse_dt / engine_refine)
    parts = default_parts() if parts is None else parts
    cases = recoil_cases(n, seed, parts)
    res = {"rb": [], "engine": [], "engine_default": [], "rb_impulse": [], "engine_impulse": []}
    secs = dict.fromkeys(res, 0.0)
    for i, c in enumerate(cases):
        part = parts[c["part"]]
        r = RecoilThrow.for_release_rate(c["omega"], c["recoil"], c["zeta"])
        for key, model, real, opts in (("rb", "rigid_body", r, {"impact_law": impact_law}),
                                       ("engine", "engine", r, {"settings": fine}),
                                       ("engine_default", "engine", r, {}),
                                       ("rb_impulse", "rigid_body", None, {"impact_law": impact_law}),
                                       ("engine_impulse", "engine", None, {"settings": fine})):
            t0 = time.perf_counter()
            res[key].append(_one(part, c, model, real, **opts))
            secs[key] += time.perf_counter() - t0
        if progress is not None:
            progress(i + 1, n)
    # where the engine's answer rests on its friction cap (studies/engine_cap.py): the recoil throws again with
    # the cap relaxed from 0.7 to 0.9; those that move by > 0.25 mm (or change side/status) are cap-bound
    res["engine_cap_alt"] = []
    t0 = time.perf_counter()
    with friction_cap(CAP_ALT):
        for c in cases:
            r = RecoilThrow.for_release_rate(c["omega"], c["recoil"], c["zeta"])
            res["engine_cap_alt"].append(_one(parts[c["part"]], c, "engine", r, settings=fine))
    secs["engine_cap_alt"] = time.perf_counter() - t0
    arr = {key: {"x": np.array([v[0] for v in res[key]]), "side": np.array([v[1] for v in res[key]]),
                 "status": np.array([v[2] for v in res[key]])} for key in ("engine", "engine_cap_alt")}
    bound = cap_sensitive(arr["engine"], arr["engine_cap_alt"])
    free = [i for i in range(n) if not bound[i]]
    mus = np.array([c["mu"] for c in cases])
    finite = [i for i in range(n) if math.isfinite(mus[i])]
    k = engine_refine
    return {"cases": cases, "results": res, "seconds": secs, "impact_law": impact_law, "engine_refine": k,
            "cap_bound": [int(i) for i in np.flatnonzero(bound)],
            "summary": {f"rb vs engine/{k} (recoil)": _summary(res["rb"], res["engine"]),
                        "rb vs engine (recoil, default dt)": _summary(res["rb"], res["engine_default"]),
                        f"engine vs engine/{k} (recoil)": _summary(res["engine_default"], res["engine"]),
                        f"rb vs engine/{k} (recoil), cap-bound left out": _summary([res["rb"][i] for i in free],
                                                                                 [res["engine"][i] for i in free]),
                        f"rb vs engine/{k} (recoil), μ finite": _summary([res["rb"][i] for i in finite],
                                                                        [res["engine"][i] for i in finite]),
                        f"rb vs engine/{k} (recoil), μ = ∞": _summary(
                            [res["rb"][i] for i in range(n) if i not in set(finite)],
                            [res["engine"][i] for i in range(n) if i not in set(finite)]),
                        f"rb vs engine/{k} (impulse)": _summary(res["rb_impulse"], res["engine_impulse"]),
                        "recoil vs impulse (rigid_body)": _summary(res["rb"], res["rb_impulse"]),
                        f"recoil vs impulse (engine/{k})": _summary(res["engine"], res["engine_impulse"])}}


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


def recoil_table(report: dict) -> str:
    """The summary as a Markdown table, then the refusals by reason."""
    lines = ["| comparison | compared | same side % (95 % CI) | \\|Δx\\| ≤ 0.5 mm % (95 % CI) | median \\|Δx\\| mm "
             "| p95 \\|Δx\\| mm | max \\|Δx\\| mm |", "|---|---|---|---|---|---|---|"]
    for label, s in report["summary"].items():
        lines.append(f"| {label} | {s['n_compared']}/{s['n']} | {s['same_pct']:.1f} ({s['same_ci95'][0]:.1f}–"
                     f"{s['same_ci95'][1]:.1f}) | {s['within_pct']:.1f} ({s['within_ci95'][0]:.1f}–"
                     f"{s['within_ci95'][1]:.1f}) | {s['dx_median_mm']:.3f} | {s['dx_p95_mm']:.3f} | "
                     f"{s['dx_max_mm']:.3f} |")
    lines.append("")
    for label, s in report["summary"].items():
        for side, key in (("first", "refused_first"), ("second", "refused_second")):
            for why, k in s[key].items():
                lines.append(f"- {label}, refused by the {side}: {k} × {why}")
    secs = report["seconds"]
    n = max(len(report["cases"]), 1)
    lines.append("- seconds per throw: " + ", ".join(f"{k} {v / n:.3f}" for k, v in secs.items()))
    return "\n".join(lines)
