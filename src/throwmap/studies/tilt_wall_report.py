"""The report of :func:`throwmap.studies.tilt_wall.validate_tilt_wall`: its rows as tables and lines.

:class:`TiltWallRow` is one comparison (a model against the engine on one condition's throws, see
:func:`~throwmap.studies.tilt_wall.compare_rows`); :class:`TiltWallReport` holds the rows, the goals, the wall's
fixed point (:class:`~throwmap.analysis.wall.WallFixedPoint`) and the agreement of every row by the one statistic
(:mod:`throwmap.studies.agreement`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..analysis.wall import WallFixedPoint
from .agreement import Agreement, AgreementTable

__all__ = ["MU_BANDS", "TiltWallReport", "TiltWallRow"]

MU_BANDS = ((0.3, 0.6), (0.6, 1.0), (1.0, 3.0), (math.inf, math.inf))
"""Arm-friction bands of the per-μ breakdown ([lo, hi); the last is μ = ∞). Below μ ≈ 0.6 rigid_body's
Routh impacts and pymunk's velocity-level impacts differ by mm; at μ = ∞ pymunk caps its friction
(docs/explanation/validation.md): there the reference itself is uncertain by mm."""


def _band(lo: float, hi: float) -> str:
    return "∞" if math.isinf(lo) else f"{lo:g}–{hi:g}"


_ROW_KEYS = ("row", "n", "n_compared", "available", "same_pct", "same_ci95", "within_pct", "within_ci95",
             "dx_median_mm", "dx_p95_mm", "dx_max_mm", "model_refused", "engine_refused", "model_refused_why",
             "engine_refused_why", "engine_leaning", "at_wall_pct", "wall_changed_pct", "by_mu", "baseline", "cap",
             "worst")


@dataclass(frozen=True, slots=True)
class TiltWallRow:
    """One row of the tilt/wall study: a model against the engine on one condition's throws.

    ``row`` its label, ``n`` throws, ``n_compared`` those neither side refused; ``available`` False when the model
    refused the condition's keywords (``message`` says why; nothing else is set). Shares in % of the compared
    throws with their Wilson 95 % intervals (``same_pct``/``same_ci95``: same outcome — the same escape, or at rest
    on the same side; ``within_pct``/``within_ci95``: the same escape, or the same side within 0.5 mm); |Δx|
    median, p95, max (mm) over the same-side rests; refusals per status and per reason on each side;
    ``engine_leaning`` engine rests leaning on the wall; ``at_wall_pct`` / ``wall_changed_pct`` (None without a
    wall); ``by_mu`` the shares per arm-μ band; ``baseline`` the same draws at α = 0; ``cap`` the agreement
    without the cap-bound throws; ``worst`` the worst misses as reproducers; ``agreement`` the row by the one
    agreement statistic (refusals apart, same-outcome rests within 0.5 mm).
    """

    row: str
    n: int
    n_compared: int
    available: bool
    message: str | None = None
    same_pct: float = math.nan
    same_ci95: list = field(default_factory=list)
    within_pct: float = math.nan
    within_ci95: list = field(default_factory=list)
    dx_median_mm: float = math.nan
    dx_p95_mm: float = math.nan
    dx_max_mm: float = math.nan
    model_refused: dict = field(default_factory=dict)
    engine_refused: dict = field(default_factory=dict)
    model_refused_why: dict = field(default_factory=dict)
    engine_refused_why: dict = field(default_factory=dict)
    engine_leaning: int = 0
    at_wall_pct: float = 0.0
    wall_changed_pct: float | None = None
    by_mu: dict = field(default_factory=dict)
    baseline: dict | None = None
    cap: dict | None = None
    worst: list = field(default_factory=list)
    agreement: Agreement | None = None

    def to_dict(self) -> dict:
        """The row as a dict (JSON-ready after :func:`throwmap.serial.json_ready`); an unavailable row has
        ``row``, ``n``, ``n_compared``, ``available`` and ``message`` only."""
        if not self.available:
            return {"row": self.row, "n": self.n, "n_compared": self.n_compared, "available": False,
                    "message": self.message}
        return {k: getattr(self, k) for k in _ROW_KEYS}

    @classmethod
    def from_dict(cls, d: dict) -> "TiltWallRow":
        """The inverse of :meth:`to_dict` (the agreement is not in the row's dict)."""
        nums = ("same_pct", "within_pct", "dx_median_mm", "dx_p95_mm", "dx_max_mm")  # nan is written as null
        return cls(**{k: _nan(d[k]) if k in nums else d[k] for k in d if k in _ROW_KEYS or k == "message"})

    def line(self) -> str:
        """The row's line of :meth:`TiltWallReport.table`."""
        if not self.available:
            return f"| {self.row} | {self.n} (0) | — | — | — | — | — | — | not run: {self.message} |"
        ref = ", ".join(f"{k} {v}" for k, v in self.model_refused.items()) or "0"
        eng = ", ".join(f"{k} {v}" for k, v in self.engine_refused.items()) or "0"
        lean = f"; leaning {self.engine_leaning}" if self.engine_leaning else ""
        base = self.baseline
        return (f"| {self.row} | {self.n} ({self.n_compared}) | {_pct(self.same_pct, self.same_ci95)} | "
                f"{_pct(self.within_pct, self.within_ci95)} | {_f(self.dx_median_mm)} | "
                f"{_f(self.dx_p95_mm)} | {_f(base['within_pct'], '.1f') if base else '—'} | {_wall(self)} | "
                f"{ref} / {eng}{lean} |")

    def table(self) -> str:
        """The row as a one-row Markdown table (the header of :meth:`TiltWallReport.table`)."""
        return "\n".join(_HEAD + [self.line()])

    def plot(self, ax=None):
        """The row's agreement with its Wilson intervals (:func:`throwmap.viz.agreement.plot_agreement`)."""
        from ..viz.agreement import plot_agreement

        rows = (self.agreement,) if self.agreement is not None else ()
        return plot_agreement(AgreementTable(rows, "engine"), ax=ax, title=self.row)


_HEAD = ["| condition: model vs reference | throws (compared) | same outcome % [95 % CI] | same escape or "
         "|Δx| ≤ 0.5 mm % [95 % CI] | |Δx| median (mm) | |Δx| p95 (mm) | α = 0: ≤ 0.5 mm % | wall changed % / at wall % "
         "| refused: model / reference |", "|" + "---|" * 9]


@dataclass(frozen=True, slots=True)
class TiltWallReport:
    """Result of :func:`validate_tilt_wall`: ``rows`` (one :class:`TiltWallRow` per model and condition), ``goals``
    (per row: met or not), ``fixed_point`` (a :class:`~throwmap.analysis.wall.WallFixedPoint`, or None),
    ``settings`` (seed, n, every range drawn from), the cases and raw results per condition, and ``agreement``
    (every available row by the one agreement statistic, :mod:`throwmap.studies.agreement`)."""

    rows: tuple
    goals: dict
    fixed_point: WallFixedPoint | None
    settings: dict
    cases: dict = field(default_factory=dict)
    results: dict = field(default_factory=dict)
    agreement: AgreementTable | None = None

    def table(self) -> str:
        """The rows as a Markdown table (distances in mm, shares in % with their Wilson 95 % interval), then
        the share within 0.5 mm by arm friction μ, each with the same draws on the level arm (α = 0)."""
        lines = list(_HEAD) + [r.line() for r in self.rows]
        bands = [_band(*b) for b in MU_BANDS]
        lines += ["", "| same escape or |Δx| ≤ 0.5 mm % by arm μ (throws), tilted [α = 0] | " + " | ".join(f"μ {b}" for b in bands)
                  + " |", "|" + "---|" * (len(bands) + 1)]
        for r in (r for r in self.rows if r.available):
            base = (r.baseline or {}).get("by_mu", {})
            cells = ["—" if b not in r.by_mu else f"{r.by_mu[b]['within_pct']:.1f} ({r.by_mu[b]['n']})"
                     + (f" [{base[b]['within_pct']:.1f}]" if b in base else "") for b in bands]
            lines.append(f"| {r.row} | " + " | ".join(cells) + " |")
        return "\n".join(lines)

    def agreement_table(self) -> str:
        """Every available row by the one agreement statistic (:meth:`AgreementTable.table`); empty without one."""
        return self.agreement.table() if self.agreement is not None else ""

    def goal_lines(self) -> list[str]:
        return [f"{name}: {g['value']:.2f} % (goal ≥ {g['goal']:g} %) — {'met' if g['met'] else 'NOT met'} by the estimate; "
                f"95 % interval [{g['ci95'][0]:.1f}, {g['ci95'][1]:.1f}] % over {g['n']} throws" for name, g in self.goals.items()]

    def cap_lines(self) -> list[str]:
        """Per row: the throws whose engine answer moves when its friction cap is relaxed (0.7 → 0.9), and the
        agreement on the others (:mod:`~throwmap.studies.engine_cap`)."""
        out = []
        for r in self.rows:
            c = r.cap if r.available else None
            if c:
                out.append(f"{r.row}: the engine's answer moves > 0.25 mm (or changes) with its friction cap 0.7 → 0.9 "
                           f"in {c['n_sensitive']} of {r.n_compared} compared throws; on the other {c['n_kept']}: same "
                           f"outcome {_pct(c['same_pct'], c['same_ci95'])} %, same escape or |Δx| ≤ 0.5 mm "
                           f"{_pct(c['within_pct'], c['within_ci95'])} %")
        return out

    def refusal_lines(self) -> list[str]:
        """Why throws were refused, per row and side (the model's own message)."""
        out = []
        for r in self.rows:
            for side, why_count in (("model", r.model_refused_why), ("reference", r.engine_refused_why)):
                for why, count in (why_count or {}).items():
                    out.append(f"{r.row}: {side} refused {count}: {why}")
        return out

    def fixed_point_lines(self) -> list[str]:
        """The wall's fixed point in words (:meth:`WallFixedPoint.lines`; none without it)."""
        return self.fixed_point.lines() if self.fixed_point is not None else []

    def to_dict(self) -> dict:
        from ..serial import json_ready

        doc = {"rows": [r.to_dict() for r in self.rows], "goals": self.goals,
               "fixed_point": self.fixed_point.to_dict() if self.fixed_point is not None else None,
               "settings": self.settings, "table_markdown": self.table()}
        if self.agreement is not None:
            doc["agreement"] = self.agreement.to_dict()
        return json_ready(doc)

    @classmethod
    def from_dict(cls, d: dict) -> "TiltWallReport":
        """The summary back from :meth:`to_dict` (cases and raw results are not written)."""
        fp = d.get("fixed_point")
        return cls(tuple(TiltWallRow.from_dict(r) for r in d["rows"]), dict(d["goals"]),
                   WallFixedPoint.from_dict(fp) if fp else None, dict(d["settings"]),
                   agreement=AgreementTable.from_dict(d["agreement"]) if d.get("agreement") else None)

    def plot(self, ax=None):
        """Every row's agreement with its Wilson intervals (:func:`throwmap.viz.agreement.plot_agreement`)."""
        from ..viz.agreement import plot_agreement

        table = self.agreement if self.agreement is not None else AgreementTable((), "engine")
        return plot_agreement(table, ax=ax, title="tilted arms and walls: models against the engine")


def _f(v, spec=".3f"):
    return "—" if v is None or not math.isfinite(v) else format(v, spec)


def _nan(v):
    return math.nan if v is None else v


def _pct(v, ci) -> str:
    return "—" if v is None or not math.isfinite(v) else f"{v:.1f} [{ci[0]:.1f}, {ci[1]:.1f}]"


def _wall(r: TiltWallRow) -> str:
    if r.wall_changed_pct is None:
        return "no wall"
    return f"{r.wall_changed_pct:.1f} / {r.at_wall_pct:.1f}"
