"""Agreement of a model with a reference, throw by throw: the one statistic every validation study reports.

Given the same throws answered by a model and by a reference (each a status, a side and a CM abscissa x):

* a throw is **refused** by a side when its status is one of :data:`REFUSED` (the model or the engine gave
  no answer: unresolved, timeout, penetration, unconverged, inconsistent, or a start not thrown). Refused
  throws are **not compared**: they are left out of every denominator and reported as counts — refused by
  the model, refused by the reference, and by both (counted in each of the two);
* over the **compared** throws (neither side refused), the two agree on the **outcome** when they end with
  the same status and, where both rest on the arm (status ok), on the same side;
* among the **same-outcome rests** (both at rest on the same side), they agree on the **position** when
  |Δx| ≤ ``tol`` (0.5 mm by default, :data:`WITHIN`).

Each share carries its Wilson 95 % score interval (:func:`throwmap.experiments.stats.wilson_interval`), which
stays informative at 0 and n successes, where the Wald interval collapses. With nothing compared the shares
are nan and their intervals (0, 1).

:func:`agreement` computes one :class:`Agreement`; :class:`AgreementTable` holds the rows of a study, with
``table()`` (Markdown), ``to_dict()`` (JSON) and ``.plot()`` (:func:`throwmap.viz.agreement.plot_agreement`).
Units: m (``tol``, x); shares as fractions in the objects, in % in the tables.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidStateError, shown
from ..experiments.stats import wilson_interval
from ..kernels import codes as C
from ..records.outcome import Status

__all__ = ["REFUSED", "WITHIN", "DEFINITION", "Agreement", "AgreementTable", "agreement", "is_refused", "refusal_counts"]

REFUSED = (C.UNRESOLVED, C.TIMEOUT, C.PENETRATION, C.UNCONVERGED, C.INCONSISTENT, C.INVALID_START)
"""Statuses that refuse an answer rather than give one (or mark a start not thrown): never compared."""
WITHIN = 0.5e-3
"""|Δx| counted as agreement on the position, m (the 0.5 mm of the validation goals)."""


def is_refused(status) -> np.ndarray:
    """Throw by throw: whether ``status`` (codes) is a refusal (:data:`REFUSED`)."""
    return np.isin(np.asarray(status), REFUSED)


def _column(answers, key: str) -> np.ndarray:
    value = answers[key] if isinstance(answers, dict) else getattr(answers, key)
    return np.asarray(value)


def _share(k: int, n: int) -> float:
    return k / n if n else math.nan


@dataclass(frozen=True, slots=True)
class Agreement:
    """One comparison of a model with a reference (see the module docstring).

    Attributes
    ----------
    label : str
        What is compared (``"rigid_body vs pymunk"``).
    n : int
        Throws thrown.
    refused_model, refused_reference, refused_both : int
        Throws refused by the model, by the reference, by both (a throw refused by both counts in each).
    compared : int
        Throws neither refused: the denominator of ``same``.
    same : int
        Compared throws with the same outcome (same status; same side where both rest).
    rests : int
        Compared throws at rest on the same side in both: the denominator of ``within``.
    within : int
        Same-outcome rests with |Δx| ≤ ``tol``.
    tol : float
        The position tolerance, m.
    same_ci95, within_ci95 : tuple of float
        Wilson 95 % intervals of ``same/compared`` and ``within/rests`` (fractions; (0, 1) when the
        denominator is 0).
    """

    label: str
    n: int
    refused_model: int
    refused_reference: int
    refused_both: int
    compared: int
    same: int
    rests: int
    within: int
    tol: float = WITHIN
    same_ci95: tuple = (0.0, 1.0)
    within_ci95: tuple = (0.0, 1.0)

    def __post_init__(self):
        for name in ("n", "refused_model", "refused_reference", "refused_both", "compared", "same", "rests", "within"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 0:
                raise InvalidStateError(f"agreement.{name}", f"must be an integer ≥ 0, got {shown(v)}")
            object.__setattr__(self, name, int(v))
        if self.compared != self.n - self.refused_model - self.refused_reference + self.refused_both:
            raise InvalidStateError("agreement.compared", f"{self.compared} is not n − refused (model, reference) + "
                                                          f"refused by both = {self.n} − {self.refused_model} − "
                                                          f"{self.refused_reference} + {self.refused_both}")
        if not (self.within <= self.rests <= self.same <= self.compared):
            raise InvalidStateError("agreement.within", f"needs within ≤ rests ≤ same ≤ compared, got {self.within}, "
                                                        f"{self.rests}, {self.same}, {self.compared}")
        object.__setattr__(self, "tol", float(self.tol))
        object.__setattr__(self, "same_ci95", wilson_interval(self.same, self.compared))
        object.__setattr__(self, "within_ci95", wilson_interval(self.within, self.rests))

    @property
    def same_rate(self) -> float:
        """same / compared (nan when nothing was compared)."""
        return _share(self.same, self.compared)

    @property
    def within_rate(self) -> float:
        """within / rests (nan when no throw rested alike)."""
        return _share(self.within, self.rests)

    def cells(self) -> list[str]:
        """This row's cells in :meth:`AgreementTable.table`."""
        return [self.label, str(self.n), f"{self.refused_model} / {self.refused_reference}", str(self.compared),
                _pct(self.same_rate, self.same_ci95), str(self.rests), _pct(self.within_rate, self.within_ci95)]

    def table(self) -> str:
        """This comparison as a one-row Markdown table."""
        return AgreementTable((self,)).table()

    def to_dict(self) -> dict:
        """JSON-ready: every count, the tolerance (m), the two shares (fractions, None when undefined) and their
        Wilson 95 % intervals."""
        return {"label": self.label, "n": self.n, "refused_model": self.refused_model,
                "refused_reference": self.refused_reference, "refused_both": self.refused_both,
                "compared": self.compared, "same": self.same, "same_rate": _none(self.same_rate),
                "same_ci95": list(self.same_ci95), "rests": self.rests, "within": self.within,
                "within_rate": _none(self.within_rate), "within_ci95": list(self.within_ci95), "tol_m": self.tol}

    @classmethod
    def from_dict(cls, d: dict) -> "Agreement":
        """The inverse of :meth:`to_dict` (the rates and intervals are recomputed from the counts)."""
        return cls(str(d["label"]), int(d["n"]), int(d["refused_model"]), int(d["refused_reference"]),
                   int(d["refused_both"]), int(d["compared"]), int(d["same"]), int(d["rests"]), int(d["within"]),
                   float(d.get("tol_m", WITHIN)))

    def plot(self, ax=None):
        """The two shares with their Wilson intervals (:func:`throwmap.viz.agreement.plot_agreement`)."""
        return AgreementTable((self,)).plot(ax=ax)


def agreement(model, reference, *, label: str = "", tol: float = WITHIN) -> Agreement:
    """The :class:`Agreement` of ``model`` with ``reference`` on the same throws (see the module docstring).

    ``model`` and ``reference``: mappings (or objects, e.g. :class:`~throwmap.records.BatchOutcome`) with
    equal-length arrays ``status`` (codes), ``side`` and ``x`` (m). ``tol``: the position tolerance, m (> 0).
    """
    if isinstance(tol, bool) or not isinstance(tol, (int, float)) or not (math.isfinite(tol) and tol >= 0):
        raise InvalidStateError("tol", f"must be a finite number ≥ 0 (m), got {shown(tol)}")
    st_m, st_r = _column(model, "status"), _column(reference, "status")
    if st_m.shape != st_r.shape or st_m.ndim != 1:
        raise InvalidStateError("reference", f"must answer the same throws as the model: {st_r.shape} statuses "
                                             f"against the model's {st_m.shape}")
    ref_m, ref_r = is_refused(st_m), is_refused(st_r)
    cmp = ~ref_m & ~ref_r
    rest = cmp & (st_m == C.OK) & (st_r == C.OK) & (_column(model, "side") == _column(reference, "side"))
    same = rest | (cmp & (st_m == st_r) & (st_m != C.OK))
    dx = np.abs(np.asarray(_column(model, "x"), float) - np.asarray(_column(reference, "x"), float))
    within = rest & (dx <= tol)
    return Agreement(label, int(st_m.size), int(ref_m.sum()), int(ref_r.sum()), int((ref_m & ref_r).sum()),
                     int(cmp.sum()), int(same.sum()), int(rest.sum()), int(within.sum()), tol)


@dataclass(frozen=True, slots=True)
class AgreementTable:
    """The :class:`Agreement` rows of a study, in order, against ``reference`` (its name, for the header)."""

    rows: tuple
    reference: str = "reference"

    def __post_init__(self):
        rows = tuple(self.rows)
        for r in rows:
            if not isinstance(r, Agreement):
                raise InvalidStateError("rows", f"must be Agreement rows, got {type(r).__name__}")
        object.__setattr__(self, "rows", rows)

    def __len__(self) -> int:
        return len(self.rows)

    def __iter__(self):
        return iter(self.rows)

    def row(self, label: str) -> Agreement:
        """The row called ``label`` (one-line error listing the labels when none is)."""
        for r in self.rows:
            if r.label == label:
                return r
        raise InvalidStateError("label", f"no row {label!r} (rows: {', '.join(r.label for r in self.rows)})")

    def table(self) -> str:
        """The rows as Markdown: counts, refusals (model / reference), the two shares in % with their Wilson 95 %
        intervals; the tolerance in the header (mm)."""
        tols = sorted({r.tol for r in self.rows}) or [WITHIN]
        tol = "/".join(f"{1e3 * t:g}" for t in tols)
        head = (f"| agreement with the {self.reference} | throws | refused: model / reference | compared "
                f"| same outcome % [95 % CI] | same-outcome rests | \\|Δx\\| ≤ {tol} mm % [95 % CI] |")
        lines = [head, "|" + "---|" * 7]
        lines += ["| " + " | ".join(r.cells()) + " |" for r in self.rows]
        return "\n".join(lines)

    def to_dict(self) -> dict:
        """``{"reference", "definition", "rows": [Agreement.to_dict(), …]}``."""
        return {"reference": self.reference, "definition": DEFINITION, "rows": [r.to_dict() for r in self.rows]}

    @classmethod
    def from_dict(cls, d: dict) -> "AgreementTable":
        return cls(tuple(Agreement.from_dict(r) for r in d.get("rows", ())), str(d.get("reference", "reference")))

    def plot(self, ax=None):
        """Each row's two shares with their Wilson 95 % intervals (:func:`throwmap.viz.agreement.plot_agreement`)."""
        from ..viz.agreement import plot_agreement

        return plot_agreement(self, ax=ax)


DEFINITION = ("refused throws (either side) are not compared and are counted apart; same outcome = same status, "
              "and the same side where both rest, over the compared throws; |Δx| ≤ tol over the same-outcome rests; "
              "Wilson 95 % intervals")
"""The statistic in one sentence (written into every study's JSON)."""


def _pct(rate: float, ci) -> str:
    return "—" if not math.isfinite(rate) else f"{100 * rate:.1f} [{100 * ci[0]:.1f}, {100 * ci[1]:.1f}]"


def _none(v: float):
    return None if not math.isfinite(v) else v


def refusal_counts(status) -> dict:
    """``{status label: count}`` over the refused throws of ``status``, in :data:`REFUSED` order."""
    status = np.asarray(status)
    return {Status(int(c)).label: int(np.sum(status == c)) for c in REFUSED if np.any(status == c)}


def goals(ag: Agreement, label: str, same_goal: float = 99.0, within_goal: float = 95.0) -> dict:
    """A study's goals on one comparison, read from its :class:`Agreement` (the one statistic): the same outcome
    in ≥ ``same_goal`` % of the compared throws, and |Δx| ≤ ``ag.tol`` in ≥ ``within_goal`` % of the same-outcome
    rests. Each goal: ``{"value" (%), "goal" (%), "met", "ci95" (%), "n"}``; ``met`` is False when nothing was
    compared (a goal is never met on no evidence), and the position goal is left out when no throw rested alike."""
    out = {}
    for name, rate, ci, n, goal in (
            ("same outcome", ag.same_rate, ag.same_ci95, ag.compared, same_goal),
            (f"|Δx| ≤ {ag.tol * 1e3:g} mm (same-outcome rests)", ag.within_rate, ag.within_ci95, ag.rests, within_goal)):
        if n == 0 and name != "same outcome":
            continue
        value = 100.0 * rate if n else math.nan
        out[f"{label}: {name}"] = {"value": value, "goal": goal, "met": bool(n and value >= goal),
                                   "ci95": [100.0 * ci[0], 100.0 * ci[1]], "n": int(n)}
    return out
