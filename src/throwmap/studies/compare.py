"""Accuracy of the approximate models against the exact "paper" model over a grid."""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from ..budget import Limits, check_count, guard_work
from ..system.arm import Arm, regime_warnings_once
from ..records.outcome import Status
from ..system.part import Part
from ..throws.throw import check_model, throw_batch

__all__ = ["ModelComparison", "compare_models", "BYTES_PER_START"]

BYTES_PER_START = 1000
"""Memory a comparison holds per start configuration, bytes: the starts and two models' batch
results with their records at one ω (≈ 970 bytes measured at ``n_x`` = 20 000)."""
TIMED_STARTS = 64
"""Starts thrown once per model to measure the time per throw before a comparison."""


@dataclass(frozen=True, slots=True)
class ModelComparison:
    """Per (model, ω) agreement with the reference model.

    Each row: ``model``, ``omega`` (rad/s), ``n`` throws compared (both at rest on
    the arm), ``side_agreement`` (fraction), ``dx_median``/``dx_p90``/``dx_max``
    (|Δx| in m over same-side outcomes), ``jog_rel_err_median``/``jog_rel_err_max``
    (|Δ jog length| / reference jog length over jogs of both), ``max_phi`` (largest
    reference rotation in flight ω t, rad). ``settings``: what was run — ``x_min``,
    ``x_max`` (m; starts x ∈ (max(x_min, side's x_min), x_max] on every stable side),
    ``n_x``, ``omegas`` (rad/s), ``mu``, ``g`` (m/s²); the table's heading states them.
    """

    part_name: str
    h: float
    reference: str
    models: tuple
    rows: tuple
    switches: tuple = ()
    settings: dict = field(default_factory=dict)

    def settings_line(self) -> str:
        """The range and settings the table covers, in one line (empty if unknown)."""
        st = self.settings
        if not st:
            return ""
        lo = "the side's x_min" if st.get("x_min") is None else f"max({st['x_min']:g} m, the side's x_min)"
        oms = ", ".join(f"{w:g}" for w in st.get("omegas", ()))
        return (f"starts x ∈ ({lo}, {st['x_max']:g} m] on every stable side, {st['n_x']} per side; "
                f"ω ∈ {{{oms}}} rad/s; μ = {st['mu']:g}; g = {st['g']:g} m/s²; "
                f"models {', '.join(self.models)} against {self.reference!r}")

    def switch_table(self) -> str:
        """r_i, the first x on each side at which a throw stops being a jog, per model (cm)."""
        models = (self.reference, *self.models)
        head = f"{'ω rad/s':>8}{'side':>6}" + "".join(f"{m + ' cm':>16}" for m in models)
        lines = ["jog→flip switch r_i (first non-jog x on the grid)", head, "-" * len(head)]
        for r in self.switches:
            vals = "".join(f"{100 * r[m]:>16.2f}" if r[m] == r[m] else f"{'none':>16}" for m in models)
            lines.append(f"{r['omega']:>8.2f}{r['side']:>6d}{vals}")
        return "\n".join(lines)

    def table(self) -> str:
        return self.error_table() + "\n\n" + self.switch_table()

    def error_table(self) -> str:
        head = (f"{'model':<13}{'ω rad/s':>8}{'n':>7}{'same side':>11}{'|Δx| med mm':>13}{'p90 mm':>9}"
                f"{'max mm':>9}{'jog err med':>13}{'jog err max':>13}{'max ωt':>8}")
        lines = [f"{self.part_name}, h = {self.h:g} m, against model {self.reference!r}"]
        if self.settings:
            lines.append(self.settings_line())
        lines += [head, "-" * len(head)]
        for r in self.rows:
            lines.append(
                f"{r['model']:<13}{r['omega']:>8.2f}{r['n']:>7d}{100 * r['side_agreement']:>10.1f}%"
                f"{1e3 * r['dx_median']:>13.3f}{1e3 * r['dx_p90']:>9.3f}{1e3 * r['dx_max']:>9.3f}"
                f"{100 * r['jog_rel_err_median']:>12.2f}%{100 * r['jog_rel_err_max']:>12.2f}%{r['max_phi']:>8.3f}"
            )
        return "\n".join(lines)

    def to_dict(self) -> dict:
        st = {k: (list(v) if isinstance(v, tuple) else v) for k, v in self.settings.items()}
        return {"part": self.part_name, "h": self.h, "reference": self.reference, "models": list(self.models),
                "rows": [dict(r) for r in self.rows], "switches": [dict(r) for r in self.switches], "settings": st}

    @classmethod
    def from_dict(cls, d: dict) -> "ModelComparison":
        """Inverse of :meth:`to_dict` (after JSON, missing switches — ``None`` — come back as nan)."""
        nan = float("nan")
        switches = tuple({k: (nan if v is None else v) for k, v in r.items()} for r in d.get("switches", ()))
        rows = tuple({k: (nan if v is None else v) for k, v in r.items()} for r in d["rows"])
        st = dict(d.get("settings", {}))
        if "omegas" in st:
            st["omegas"] = tuple(st["omegas"])
        if st.get("mu", 0.0) is None:  # JSON has no infinity: μ = ∞ written as null
            st["mu"] = float("inf")
        return cls(d["part"], d["h"], d["reference"], tuple(d["models"]), rows, switches, st)

    def plot(self, ax=None):
        from ..viz.comparison import plot_model_comparison

        return plot_model_comparison(self, ax=ax)


@regime_warnings_once()
def compare_models(part: Part, arm: Arm, omegas=(1.0, 2.0, 3.0, 4.0, 5.0, 6.0), n_x: int = 200,
                   x_max: float | None = None, models=("small_angle", "small_angle2"),
                   reference: str = "paper", x_min: float | None = None, *, limits: Limits | None = None) -> ModelComparison:
    """Compare ``models`` with ``reference`` over x ∈ (lo, x_max] on every stable side, for each ω.

    lo is the side's smallest admissible start x_min (m), or ``x_min`` where that is
    larger. ``x_max`` (m) defaults to the arm length or 0.4 m and must exceed every
    side's lo. Also records, per ω and side, the first grid x at which each model's
    throw is not a jog (the switch r_i, Sec. III-D), with the grid's resolution
    (x_max − lo)/n_x. The result's ``settings`` (and its table) state the range.

    Work guard (:mod:`throwmap.budget`): memory :data:`BYTES_PER_START` per start
    (``n_x`` per stable side) and time from :data:`TIMED_STARTS` throws of each model
    measured now (every start is thrown once per ω and model); above ``limits``
    (:class:`~throwmap.budget.Limits`) it is refused with one line on ``n_x``, unless ``limits.force``.
    """
    from ..errors import InvalidStateError

    for m in (*models, reference):
        check_model(m)
    if x_max is None:
        x_max = arm.length if arm.length is not None else 0.4
    for name, v in (("x_max", x_max), ("x_min", x_min)):
        if v is not None and not (isinstance(v, (int, float)) and np.isfinite(v)):
            raise InvalidStateError(name, f"must be a finite number (m), got {v!r}")
    x_max = float(x_max)
    los = {s: max(part.x_min(s), x_min) if x_min is not None else part.x_min(s) for s in part.stable_sides}
    if x_max <= max(los.values()):
        raise InvalidStateError("x_max", f"must exceed the largest start bound {max(los.values()):.4g} m, "
                                         f"got {x_max:g}")
    n_x = check_count("n_x", n_x, minimum=1)
    omegas = tuple(np.atleast_1d(np.asarray(omegas, dtype=float)))
    n_starts = n_x * len(part.stable_sides)

    def seconds_per_throw() -> float:
        lo = max(los.values())
        xt = np.linspace(lo, x_max, TIMED_STARTS + 1)[1:]
        st = np.full(xt.shape, part.stable_sides[0])
        w = omegas[0] if omegas else 1.0
        total = 0.0
        for m in (reference, *models):
            throw_batch(part, arm, xt[:2], st[:2], w, model=m, on_invalid="status")  # warm the kernels
            t0 = time.perf_counter()
            throw_batch(part, arm, xt, st, w, model=m, on_invalid="status")
            total += time.perf_counter() - t0
        return total / (xt.size * (1 + len(models)))

    guard_work(f"compare (n_x = {n_x:,} per stable side)", "n_x", n_starts, BYTES_PER_START, limits,
               throws_per_config=len(omegas) * (1 + len(models)), timer=seconds_per_throw,
               hint="a smaller n_x (--n-x)", unit="starts")
    xs, ss = [], []
    for s in part.stable_sides:
        x = np.linspace(los[s], x_max, n_x + 1)[1:]
        xs.append(x)
        ss.append(np.full(x.shape, s))
    xs = np.concatenate(xs)
    ss = np.concatenate(ss)
    rows = []
    switches = []

    def first_non_jog(res):
        out = {}
        for s in part.stable_sides:
            m = ss == s
            bad = np.flatnonzero(res.side[m] != s)
            out[s] = float(xs[m][bad[0]]) if bad.size else float("nan")
        return out

    for om in omegas:
        ref = throw_batch(part, arm, xs, ss, om, model=reference, on_invalid="status")
        sw = {reference: first_non_jog(ref)}
        phi = om * ref.record("T_FLIGHT")
        for model in models:
            res = throw_batch(part, arm, xs, ss, om, model=model, on_invalid="status")
            sw[model] = first_non_jog(res)
            both = (ref.status == Status.OK) & (res.status == Status.OK)
            same = both & (ref.side == res.side)
            dx = np.abs(res.x - ref.x)[same]
            jogs = same & (ref.side == ss)
            jog_ref = (ref.x - xs)[jogs]
            rel = np.abs((res.x - ref.x)[jogs]) / np.maximum(np.abs(jog_ref), 1e-15)
            rows.append({
                "model": model,
                "omega": float(om),
                "n": int(both.sum()),
                "side_agreement": float(same.sum() / max(both.sum(), 1)),
                "dx_median": float(np.median(dx)) if dx.size else float("nan"),
                "dx_p90": float(np.percentile(dx, 90)) if dx.size else float("nan"),
                "dx_max": float(dx.max()) if dx.size else float("nan"),
                "jog_rel_err_median": float(np.median(rel)) if rel.size else float("nan"),
                "jog_rel_err_max": float(rel.max()) if rel.size else float("nan"),
                "max_phi": float(np.nanmax(phi[both])) if both.any() else float("nan"),
            })
        for s in part.stable_sides:
            switches.append({"omega": float(om), "side": int(s), **{m: sw[m][s] for m in (reference, *models)}})
    settings = {"x_min": None if x_min is None else float(x_min), "x_max": x_max, "n_x": int(n_x),
                "omegas": tuple(float(w) for w in omegas), "mu": float(arm.mu), "g": float(arm.g)}
    return ModelComparison(part.name, arm.h, reference, tuple(models), tuple(rows), tuple(switches), settings)
