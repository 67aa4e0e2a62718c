"""The report of :func:`throwmap.studies.validation.validate`: its comparison rows, tables and JSON.

:func:`compare_row` compares one model's answers with the reference's throw by throw (the validation table's
row: same status %, same side %, |Δx| statistics, |Δx| ≤ 0.5 mm %); :class:`ValidationReport` holds the rows,
the goals, the settings, the per-throw answers and the study's :class:`~throwmap.studies.agreement.AgreementTable`
(the one agreement statistic, with refusals counted apart and Wilson intervals), with ``table()`` (Markdown),
``to_dict()`` (JSON) and ``.plot()``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..records.outcome import Status
from .agreement import AgreementTable

__all__ = ["ValidationReport", "compare_row"]


@dataclass(frozen=True, slots=True)
class ValidationReport:
    """Results of :func:`~throwmap.studies.validation.validate`.

    ``results[model]`` holds flat arrays over all cases: ``x``, ``side``,
    ``status`` and, for analytic models, the per-throw record flags. ``rows`` is
    the comparison table (one dict per model vs ``reference``), ``goals`` the
    rigid_body-vs-pymunk goals with pass/fail, ``settings`` what was run,
    ``agreement`` the same comparisons by the one agreement statistic
    (:mod:`throwmap.studies.agreement`).
    """

    reference: str
    cases: dict
    results: dict
    rows: tuple
    goals: dict
    settings: dict = field(default_factory=dict)
    realisation_rows: tuple = ()
    agreement: AgreementTable | None = None

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

    def agreement_table(self) -> str:
        """The agreement statistic of every comparison (:meth:`AgreementTable.table`); empty without one."""
        return self.agreement.table() if self.agreement is not None else ""

    def goal_lines(self) -> list[str]:
        return [f"{name}: {g['value']:.2f} % (goal ≥ {g['goal']:g} %) — {'met' if g['met'] else 'NOT met'}"
                for name, g in self.goals.items()]

    def to_dict(self) -> dict:
        from ..serial import json_ready

        doc = {"reference": self.reference, "rows": list(self.rows), "goals": self.goals,
               "settings": self.settings, "table_markdown": self.table(),
               "realisations": list(self.realisation_rows)}
        if self.agreement is not None:
            doc["agreement"] = self.agreement.to_dict()
        return json_ready(doc)

    @classmethod
    def from_dict(cls, d: dict) -> "ValidationReport":
        """The report's summary back from :meth:`to_dict` (rows, goals, settings, realisations, agreement);
        the per-throw arrays (``cases``, ``results``) are not written and come back empty."""
        agree = AgreementTable.from_dict(d["agreement"]) if d.get("agreement") else None
        return cls(d["reference"], {}, {}, tuple(d["rows"]), dict(d["goals"]), dict(d.get("settings", {})),
                   tuple(d.get("realisations", ())), agree)

    def plot(self, ax=None):
        """The agreement of every comparison with its Wilson intervals (:func:`throwmap.viz.agreement.plot_agreement`)."""
        from ..viz.agreement import plot_agreement

        table = self.agreement if self.agreement is not None else AgreementTable((), self.reference)
        return plot_agreement(table, ax=ax, title=f"validation: models against {self.reference}")


def _f(v, spec=".3f"):
    return "—" if v is None or not math.isfinite(v) else format(v, spec)


def compare_row(name, ref, res, assumptions: str) -> dict:
    """The validation table's row of ``res`` against ``ref`` (dicts of arrays ``x``, ``side``, ``status``).

    Refusals are statuses like any other here (the table's record); the agreement statistic
    (:func:`~throwmap.studies.agreement.agreement`) counts them apart.
    """
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
