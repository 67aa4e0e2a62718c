"""The drift checks a feeder must pass before its verification: ω and the lead weight's place, a few percent and a
millimetre or two off.

A feeder verified at its nominal ω and weight place may lose its feed when the arm's rate drifts by one jitter σ or
the weight is glued a little off its mark; the search (:mod:`throwmap.feeder.search`) runs these checks between a
candidate's first trials and its verification, so a fragile feeder is named as such and never called fed. The
design sheet's margins (:mod:`throwmap.feeder.sheet`) drift the same config further with :func:`drifted`.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .search import VerifyPlan

__all__ = ["OMEGA_DRIFT", "OMEGA_SHIFT", "WEIGHT_DRIFT_M", "omega_check", "weight_check", "drifted", "drift_text",
           "stage_label"]

OMEGA_DRIFT = 0.03
"""The systematic ω drift a feeder must tolerate (one jitter σ): a feeder verified at ω but clearly below the goal at
ω(1 ± this) is *fragile*, not fed."""
OMEGA_SHIFT = 0.05
"""How far a fragile feeder's ω is moved away from the drift it cannot take (relative), for the next candidate."""


def _check_doc(what: str, step: float, res) -> dict:
    return {"check": what, "step": step, "n": res.n, "successes": res.successes,
            "ci95": [float(res.ci95[0]), float(res.ci95[1])]}


def omega_check(cfg, here: Path, plan: VerifyPlan, *, workers: int, stop_by: float, progress, label: str,
                 record: list | None = None):
    """``plan.omega_check`` engine trials (seed 100) at ω(1 − :data:`OMEGA_DRIFT`) and ω(1 + :data:`OMEGA_DRIFT`):
    ``("fed", 0.0)`` when neither is clearly below the goal (its Wilson 95 % upper end under it), else the verdict
    ``"fragile in ω: …"`` and the relative shift of ω to try next (away from the failing drift; 0 when both fail).
    Each run is appended to ``record`` (:func:`_check_doc`)."""
    from ..experiments.runner import run_experiment

    failed, seen = [], []
    for step in (-OMEGA_DRIFT, OMEGA_DRIFT):
        c = cfg.model_copy(update={"omega": cfg.omega * (1.0 + step)})
        lab = stage_label(f"{label}: {drift_text(step)}", here / f"omega_{step:+g}", plan.omega_check)
        cb = None if progress is None else (lambda d, t, lab=lab: progress(lab, d, t))
        res = run_experiment("feed", c, n=plan.omega_check, seed=100, workers=workers, out=here / f"omega_{step:+g}",
                             progress=cb, stop_by=stop_by)
        if record is not None:
            record.append(_check_doc("omega", step, res))
        if res.n < plan.omega_check:
            return f"the budget ran out in the ω check ({res.n}/{plan.omega_check} trials run)", 0.0
        seen.append(f"{drift_text(step)} {res.successes}/{res.n}")
        if res.ci95[1] < plan.goal:
            failed.append(step)
    if not failed:
        return "fed", 0.0
    verdict = ("fragile in ω: " + ", ".join(seen) + f" fed (below {100 * plan.goal:g} % with 95 % confidence at "
               + " and ".join(drift_text(s) for s in failed) + ")")
    return verdict, (0.0 if len(failed) == 2 else -OMEGA_SHIFT * math.copysign(1, failed[0]))


WEIGHT_DRIFT_M = 0.0015
"""How far the lead weight may sit from its place (m, each way in the part's x and y) before a feeder that loses its
feed there is *fragile*: a weight glued by hand lands within a millimetre or two (a verified feeder fed 4 of 30 with
its weight 1.5 mm off)."""


def weight_check(cfg, here: Path, plan: VerifyPlan, *, workers: int, stop_by: float, progress, label: str,
                  record: list | None = None) -> str:
    """``plan.weight_check`` engine trials (seed 100) with the lead weight moved :data:`WEIGHT_DRIFT_M` each way in
    the part's x and y (a move off the plate is skipped): ``"fed"`` when none is clearly below the goal (its Wilson
    95 % upper end under it), else ``"fragile in the weight's place: …"``; it stops at the first that is. Each run is
    appended to ``record``."""
    from ..experiments.runner import run_experiment

    seen = []
    for what in ("weight_x", "weight_y"):
        for step in (-WEIGHT_DRIFT_M, WEIGHT_DRIFT_M):
            name = f"{what}_{step:+g}"
            c = drifted(cfg, what, step, here / name)
            if c is None:
                continue
            lab = stage_label(f"{label}: weight {what[-1]} {1000 * step:+.1f} mm", here / name / "run", plan.weight_check)
            cb = None if progress is None else (lambda d, t, lab=lab: progress(lab, d, t))
            res = run_experiment("feed", c, n=plan.weight_check, seed=100, workers=workers, out=here / name / "run",
                                 progress=cb, stop_by=stop_by)
            if record is not None:
                record.append(_check_doc(what, step, res))
            if res.n < plan.weight_check:
                return f"the budget ran out in the weight check ({res.n}/{plan.weight_check} trials run)"
            seen.append(f"{what[-1]} {1000 * step:+.1f} mm {res.successes}/{res.n}")
            if res.ci95[1] < plan.goal:
                return (f"fragile in the weight's place: " + ", ".join(seen) + f" fed (below {100 * plan.goal:g} % "
                        f"with 95 % confidence at {what[-1]} {1000 * step:+.1f} mm)")
    return "fed"


def stage_label(stage: str, folder: Path, n: int) -> str:
    """``stage``, with "(read back)" when ``folder`` already holds ``n`` trials of an earlier run."""
    try:
        with open(folder / "trials.jsonl", "rb") as fh:
            stored = sum(1 for line in fh if line.endswith(b"\n"))
    except OSError:
        return stage
    return f"{stage} (read back)" if stored >= n and (folder / "run.json").exists() else stage


def drift_text(step: float) -> str:
    """A relative drift of ω as the verdicts write it: −0.03 → "ω −3 %" (ω moved by −3 %, ω × 0.97)."""
    return f"ω {'−' if step < 0 else '+'}{100 * abs(step):.3g} %"


def drifted(cfg, what: str, step: float, folder: Path):
    """The feed config ``cfg`` with one quantity drifted by ``step`` (None when the drift is not possible)."""
    from ..io.config import resolve_part, save_part_toml
    from ..system.geometry import point_in_convex_polygon
    from .family import Weight, with_weight, without_last_weight

    if what == "omega":
        return cfg.model_copy(update={"omega": cfg.omega * (1.0 + step)})
    if what == "mu":
        return cfg.model_copy(update={"arm": cfg.arm.model_copy(update={"mu": cfg.arm.mu * step})})
    if what == "jitter":
        return cfg.model_copy(update={"noise": cfg.noise.model_copy(update={"omega_rel": step})})
    part = resolve_part(cfg.part).part
    if not part.point_masses:
        return None
    m, at = part.point_masses[-1]
    at = (at[0] + step, at[1]) if what == "weight_x" else (at[0], at[1] + step)
    if not point_in_convex_polygon(np.asarray(part.vertices), np.asarray(at)):  # the moved weight leaves the plate
        return None
    moved = with_weight(without_last_weight(part), Weight(m, at))
    folder.mkdir(parents=True, exist_ok=True)
    path = save_part_toml(moved, None, folder / "part.toml")
    return cfg.model_copy(update={"part": str(path.resolve())})
