"""The inverse throws checked against forward throws, on every model.

For each model, ``n`` random problems: a start (x0, side) drawn uniformly over the side's rests with
x0 ≤ ``x_hi``, the jog branch there measured (:func:`~throwmap.control.inverse.inverse_jog` towards
x0 itself), and a target a uniform share u ∈ [0.05, 0.95] of the way to the branch's far end. The
rate found is thrown again, forward, and the landing compared with the target: a check independent
of the search's own bookkeeping. Rows: problems posed, answered within ``tol``, refused (the map
discontinuous at the target), the largest forward residual (m), the share where Lemma 4.2's
monotonicity held on the sampled branch, median throws per inverse, and the median scatter of the
map about a straight line where bisection met jumps (the engine's contact slop and settling; nan
where the map was continuous at 1 µm). Units: m, rad/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ThrowmapError
from ..rng import as_generator
from ..system.arm import regime_warnings_once
from .inverse import inverse_jog

__all__ = ["HEADER", "InverseCheckRow", "check_inverse"]


@dataclass(frozen=True)
class InverseCheckRow:
    """One model's figures (see the module docstring); ``cases`` keeps (x0, side, target, ω, forward x, residual)."""

    model: str
    n: int
    hit: int
    refused: int
    no_branch: int
    max_residual: float
    monotone: int
    median_throws: float
    scatter: float
    cases: tuple

    def line(self, tol: float) -> str:
        return (f"| {self.model} | {self.n} | {self.hit} | {self.refused} | {self.no_branch} | "
                f"{self.max_residual * 1e6:.3g} | {self.monotone}/{self.n - self.no_branch} | {self.median_throws:.0f} | "
                + (f"{self.scatter * 1e6:.3g} |" if math.isfinite(self.scatter) else "— |"))


@regime_warnings_once()
def check_inverse(part, arm, models=("paper", "small_angle", "small_angle2", "rigid_body", "engine"), *, n: int = 20,
                  seed: int = 0, x_hi: float = 0.45, tol: float = 1e-6, omega_max: float = 8.0, progress=None,
                  **throw_options) -> list[InverseCheckRow]:
    """The table's rows, one per model (see the module docstring); ``progress(done, total)`` after each problem."""
    from ..system.starts import start_interval
    from ..throws.throw import throw

    rng = as_generator(seed)
    sides = np.flatnonzero(part.stable)
    problems = []
    for _ in range(n):
        k = int(rng.choice(sides))
        lo, hi = start_interval(part, arm, k)
        x0 = float(rng.uniform(lo + 1e-3, min(hi, x_hi)))
        problems.append((x0, k, float(rng.uniform(0.05, 0.95))))
    rows, done = [], 0
    for model in models:
        cases, refused, no_branch, mono, throws, scat = [], 0, 0, 0, [], []
        for x0, k, u in problems:
            done += 1
            try:
                probe = inverse_jog(part, arm, x0, k, x0, model, omega_max=omega_max, **throw_options)
            except ThrowmapError:
                no_branch += 1
                continue
            lo, hi = probe.reach
            end = hi if hi - x0 >= x0 - lo else lo
            if abs(end - x0) < 10 * tol:
                no_branch += 1  # jogs make no progress here (e.g. near the joint): nothing to invert
                continue
            target = x0 + u * (end - x0)
            try:
                r = inverse_jog(part, arm, x0, k, target, model, omega_max=omega_max, tol=tol, **throw_options)
            except ThrowmapError:
                refused += 1
                continue
            out = throw(part, arm, x0, k, r.omega, model, **throw_options)
            res = abs(out.x - target) if (out.side == k and str(out.status) == "ok") else math.inf
            cases.append((x0, k, target, r.omega, float(out.x), res))
            mono += int(r.monotone)
            if math.isfinite(r.scatter):
                scat.append(r.scatter)
            throws.append(r.n_throws + probe.n_throws)
            if progress is not None:
                progress(done, n * len(models))
        res_all = [c[-1] for c in cases]
        rows.append(InverseCheckRow(model, n, sum(r <= tol for r in res_all), refused, no_branch,
                                    max(res_all) if res_all else math.nan, mono,
                                    float(np.median(throws)) if throws else math.nan,
                                    float(np.median(scat)) if scat else math.nan, tuple(cases)))
    return rows


HEADER = ("| model | problems | forward error ≤ tol | refused (map scatters) | no jog branch | max forward "
          "residual (µm) | Lemma 4.2 monotone | median throws | map scatter (µm, median) |\n|---|---|---|---|---|---|---|---|---|")
"""The Markdown header of :meth:`InverseCheckRow.line` rows."""
