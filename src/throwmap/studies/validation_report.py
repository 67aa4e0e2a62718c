"""The report of :func:`throwmap.studies.validation.validate`: its comparison rows, tables and JSON.

:func:`compare_row` compares one model's answers with the reference's throw by throw (the validation table's
row, a :class:`ValidationRow`: same status %, same side %, |Δx| statistics, |Δx| ≤ 0.5 mm %);
:class:`ValidationReport` holds the rows,
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

__all__ = ["ValidationReport", "ValidationRow", "compare_row"]


_ROW_KEYS = ("model", "n", "n_both_ok", "same_status_pct", "same_side_pct", "dx_median_mm", "dx_p90_mm", "dx_max_mm",
             "within_0p5mm_pct", "assumptions")


@dataclass(frozen=True, slots=True)
class ValidationRow:
    """One row of the validation table: ``model`` (its label) against the reference over ``n`` throws, ``n_both_ok``
    of them at rest in both; ``same_status_pct``; ``same_side_pct`` (same side at rest, or the same escape);
    |Δx| median, p90 and max (mm) over the same-side rests; ``within_0p5mm_pct`` (same side within 0.5 mm, or the
    same escape); ``assumptions`` the model's own account of where its assumptions failed. Shares in % of all
    throws (a refusal is a status like any other here; :mod:`throwmap.studies.agreement` counts it apart)."""

    model: str
    n: int
    n_both_ok: int
    same_status_pct: float
    same_side_pct: float
    dx_median_mm: float
    dx_p90_mm: float
    dx_max_mm: float
    within_0p5mm_pct: float
    assumptions: str

    def line(self) -> str:
        """The row's line of :meth:`ValidationReport.table`."""
        return (f"| {self.model} | {self.n} | {self.same_status_pct:.1f} | {self.same_side_pct:.1f} | "
                f"{_f(self.dx_median_mm)} | {_f(self.dx_p90_mm)} | {_f(self.dx_max_mm)} | "
                f"{_f(self.within_0p5mm_pct, '.1f')} | {self.assumptions} |")

    def realisation_line(self) -> str:
        """The row's line of :meth:`ValidationReport.realisation_table` (mm to 0.01)."""
        return (f"| {self.model} | {self.n} | {self.same_status_pct:.1f} | {self.same_side_pct:.1f} | "
                f"{_f(self.dx_median_mm, '.2f')} | {_f(self.dx_p90_mm, '.2f')} | {_f(self.dx_max_mm, '.2f')} |")

    def table(self) -> str:
        """The row as a one-row Markdown table."""
        return "\n".join([_HEAD.format(reference="reference"), "|" + "---|" * 9, self.line()])

    def to_dict(self) -> dict:
        """The row as a dict, as the report's JSON holds it."""
        return {k: getattr(self, k) for k in _ROW_KEYS}

    @classmethod
    def from_dict(cls, d: dict) -> "ValidationRow":
        """The inverse of :meth:`to_dict` (null shares, as JSON writes nan, come back as nan)."""
        return cls(**{k: (math.nan if d[k] is None and k != "assumptions" else d[k]) for k in _ROW_KEYS})


_HEAD = ("| model vs {reference} | throws | same status % | same side % | |Δx| median (mm) "
         "| |Δx| p90 (mm) | |Δx| max (mm) | |Δx| ≤ 0.5 mm % | assumptions failed |")


@dataclass(frozen=True, slots=True)
class ValidationReport:
    """Results of :func:`~throwmap.studies.validation.validate`.

    ``results[model]`` holds flat arrays over all cases: ``x``, ``side``,
    ``status`` and, for analytic models, the per-throw record flags. ``rows`` is
    the comparison table (one :class:`ValidationRow` per model vs ``reference``;
    ``realisation_rows`` likewise, finite arm motions vs the impulse), ``goals`` the
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
        lines = [_HEAD.format(reference=self.reference), "|" + "---|" * 9]
        lines += [r.line() for r in self.rows]
        return "\n".join(lines)

    def realisation_table(self) -> str:
        """How far finite arm motions land from the impulse idealisation (engine vs engine, mm)."""
        if not self.realisation_rows:
            return ""
        lines = ["| realisation vs impulse (pymunk) | throws | same status % | same side % | |Δx| median (mm) "
                 "| |Δx| p90 (mm) | |Δx| max (mm) |", "|" + "---|" * 7]
        lines += [r.realisation_line() for r in self.realisation_rows]
        return "\n".join(lines)

    def agreement_table(self) -> str:
        """The agreement statistic of every comparison (:meth:`AgreementTable.table`); empty without one."""
        return self.agreement.table() if self.agreement is not None else ""

    def goal_lines(self) -> list[str]:
        return [f"{name}: {g['value']:.2f} % (goal ≥ {g['goal']:g} %) — {'met' if g['met'] else 'NOT met'}"
                + (f"; 95 % interval [{g['ci95'][0]:.1f}, {g['ci95'][1]:.1f}] % over {g['n']} throws" if "ci95" in g else "")
                for name, g in self.goals.items()]

    def to_dict(self) -> dict:
        from ..serial import json_ready

        doc = {"reference": self.reference, "rows": [r.to_dict() for r in self.rows], "goals": self.goals,
               "settings": self.settings, "table_markdown": self.table(),
               "realisations": [r.to_dict() for r in self.realisation_rows]}
        if self.agreement is not None:
            doc["agreement"] = self.agreement.to_dict()
        return json_ready(doc)

    @classmethod
    def from_dict(cls, d: dict) -> "ValidationReport":
        """The report's summary back from :meth:`to_dict` (rows, goals, settings, realisations, agreement);
        the per-throw arrays (``cases``, ``results``) are not written and come back empty."""
        agree = AgreementTable.from_dict(d["agreement"]) if d.get("agreement") else None
        return cls(d["reference"], {}, {}, tuple(ValidationRow.from_dict(r) for r in d["rows"]), dict(d["goals"]),
                   dict(d.get("settings", {})), tuple(ValidationRow.from_dict(r) for r in d.get("realisations", ())),
                   agree)

    def plot(self, ax=None):
        """The agreement of every comparison with its Wilson intervals (:func:`throwmap.viz.agreement.plot_agreement`)."""
        from ..viz.agreement import plot_agreement

        table = self.agreement if self.agreement is not None else AgreementTable((), self.reference)
        return plot_agreement(table, ax=ax, title=f"validation: models against {self.reference}")


def _f(v, spec=".3f"):
    return "—" if v is None or not math.isfinite(v) else format(v, spec)


def compare_row(name, ref, res, assumptions: str) -> ValidationRow:
    """The validation table's row (a :class:`ValidationRow`) of ``res`` against ``ref`` (dicts of arrays ``x``,
    ``side``, ``status``).

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
    return ValidationRow(
        model=name,
        n=n,
        n_both_ok=int(both_ok.sum()),
        same_status_pct=100.0 * same_status.mean() if n else math.nan,
        same_side_pct=100.0 * (same_side.sum() + (same_status & ~both_ok).sum()) / n if n else math.nan,
        dx_median_mm=float(np.median(dx)) if dx.size else math.nan,
        dx_p90_mm=float(np.percentile(dx, 90)) if dx.size else math.nan,
        dx_max_mm=float(dx.max()) if dx.size else math.nan,
        within_0p5mm_pct=100.0 * within.mean() if n else math.nan,
        assumptions=assumptions,
    )
