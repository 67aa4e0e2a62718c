"""The report of :func:`throwmap.studies.tilt_wall.validate_tilt_wall`: its rows as tables and lines (issue 11)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..records.outcome import Status

__all__ = ["MU_BANDS", "TiltWallReport"]

MU_BANDS = ((0.3, 0.6), (0.6, 1.0), (1.0, 3.0), (math.inf, math.inf))
"""Arm-friction bands of the per-μ breakdown ([lo, hi); the last is μ = ∞). Below μ ≈ 0.6 rigid_body's
Routh impacts and pymunk's velocity-level impacts differ by mm; at μ = ∞ pymunk caps its friction
(README, Validation): there the reference itself is uncertain by mm."""


def _band(lo: float, hi: float) -> str:
    return "∞" if math.isinf(lo) else f"{lo:g}–{hi:g}"


@dataclass(frozen=True, slots=True)
class TiltWallReport:
    """Result of :func:`validate_tilt_wall`: ``rows`` (one dict per model and condition), ``goals``
    (per row: met or not), ``fixed_point`` (:func:`wall_fixed_point`'s dict, or None), ``settings``
    (seed, n, every range drawn from), and the cases and raw results per condition."""

    rows: tuple
    goals: dict
    fixed_point: dict | None
    settings: dict
    cases: dict = field(default_factory=dict)
    results: dict = field(default_factory=dict)

    def table(self) -> str:
        """The rows as a Markdown table (distances in mm, shares in % with their Wilson 95 % interval), then
        the share within 0.5 mm by arm friction μ, each with the same draws on the level arm (α = 0)."""
        lines = ["| condition: model vs reference | throws (compared) | same outcome % [95 % CI] | |Δx| ≤ 0.5 mm % "
                 "[95 % CI] | |Δx| median (mm) | |Δx| p95 (mm) | α = 0: ≤ 0.5 mm % | wall changed % / at wall % "
                 "| refused: model / reference |", "|" + "---|" * 9]
        for r in self.rows:
            if not r["available"]:
                lines.append(f"| {r['row']} | {r['n']} (0) | — | — | — | — | — | — | not run: {r['message']} |")
                continue
            ref = ", ".join(f"{k} {v}" for k, v in r["model_refused"].items()) or "0"
            eng = ", ".join(f"{k} {v}" for k, v in r["engine_refused"].items()) or "0"
            lean = f"; leaning {r['engine_leaning']}" if r["engine_leaning"] else ""
            base = r.get("baseline")
            lines.append(f"| {r['row']} | {r['n']} ({r['n_compared']}) | {_pct(r['same_pct'], r['same_ci95'])} | "
                         f"{_pct(r['within_pct'], r['within_ci95'])} | {_f(r['dx_median_mm'])} | "
                         f"{_f(r['dx_p95_mm'])} | {_f(base['within_pct'], '.1f') if base else '—'} | {_wall(r)} | "
                         f"{ref} / {eng}{lean} |")
        bands = [_band(*b) for b in MU_BANDS]
        lines += ["", "| |Δx| ≤ 0.5 mm % by arm μ (throws), tilted [α = 0] | " + " | ".join(f"μ {b}" for b in bands)
                  + " |", "|" + "---|" * (len(bands) + 1)]
        for r in (r for r in self.rows if r["available"]):
            base = (r.get("baseline") or {}).get("by_mu", {})
            cells = ["—" if b not in r["by_mu"] else f"{r['by_mu'][b]['within_pct']:.1f} ({r['by_mu'][b]['n']})"
                     + (f" [{base[b]['within_pct']:.1f}]" if b in base else "") for b in bands]
            lines.append(f"| {r['row']} | " + " | ".join(cells) + " |")
        return "\n".join(lines)

    def goal_lines(self) -> list[str]:
        return [f"{name}: {g['value']:.2f} % (goal ≥ {g['goal']:g} %) — {'met' if g['met'] else 'NOT met'} by the estimate; "
                f"95 % interval [{g['ci95'][0]:.1f}, {g['ci95'][1]:.1f}] % over {g['n']} throws" for name, g in self.goals.items()]

    def cap_lines(self) -> list[str]:
        """Per row: the throws whose engine answer moves when its friction cap is relaxed (0.7 → 0.9), and the
        agreement on the others (:mod:`~throwmap.studies.engine_cap`)."""
        out = []
        for r in self.rows:
            c = r.get("cap") if r.get("available") else None
            if c:
                out.append(f"{r['row']}: the engine's answer moves > 0.25 mm (or changes) with its friction cap 0.7 → 0.9 "
                           f"in {c['n_sensitive']} of {r['n_compared']} compared throws; on the other {c['n_kept']}: same "
                           f"outcome {_pct(c['same_pct'], c['same_ci95'])} %, |Δx| ≤ 0.5 mm "
                           f"{_pct(c['within_pct'], c['within_ci95'])} %")
        return out

    def refusal_lines(self) -> list[str]:
        """Why throws were refused, per row and side (the model's own message)."""
        out = []
        for r in self.rows:
            for side, key in (("model", "model_refused_why"), ("reference", "engine_refused_why")):
                for why, count in (r.get(key) or {}).items():
                    out.append(f"{r['row']}: {side} refused {count}: {why}")
        return out

    def fixed_point_lines(self) -> list[str]:
        fp = self.fixed_point
        if not fp:
            return []
        if not fp.get("found"):
            return [f"wall fixed point ({fp['model']}, {fp['part']}, side {fp['side']}): NOT found — {fp['message']}"]
        fd = ", ".join(f"h = {h:g} m: {v:+.3g}" for h, v in zip(fp["fd_steps_m"], fp["fd_left"]))
        ref = fp.get("reference") or {}
        imgs = "; ".join(f"T(x_w {1e3 * g['start_offset_m']:+g} mm) − x_w = {1e6 * g['dx_from_x_wall_m']:+.3g} µm "
                         f"(side {g['side']}, {Status(g['status']).label})" for g in ref.get("images", ()))
        return [f"wall fixed point ({fp['model']}, {fp['part']}, ω = {fp['omega_rad_s']:g} rad/s, L = "
                f"{fp['length_m']:g} m, μ = {_mu(fp['mu'])}, α = {fp['alpha_deg']:g}°, wall μ {_mu(fp['wall_mu'])}): "
                f"x* = {fp['x_star_m']:.6f} m on side {fp['side']} ({1e6 * fp['gap_m']:.3g} µm below x_w = length − u_R = "
                f"{fp['x_wall_m']:.6f} m), multiplier "
                f"{fp['multiplier']:+.3g}, residual {fp['residual_m']:.3g} m, reached from {100 * fp['fraction']:.1f} % "
                f"of {fp['n_starts']} starts ({fp['range']}; {fp['n_at_wall']} fixed point(s) at the wall in all)",
                f"  left difference quotients (T(x*) − T(x* − h))/h: {fd}; the map without the wall at x*: slope "
                f"{_f(fp['free_slope'], '+.3g')}"] + ([f"  {ref['model']}: {imgs}"] if imgs else [])

    def to_dict(self) -> dict:
        from ..serial import json_ready

        return json_ready({"rows": list(self.rows), "goals": self.goals, "fixed_point": self.fixed_point,
                           "settings": self.settings, "table_markdown": self.table()})

    @classmethod
    def from_dict(cls, d: dict) -> "TiltWallReport":
        """The summary back from :meth:`to_dict` (cases and raw results are not written)."""
        return cls(tuple(d["rows"]), dict(d["goals"]), d.get("fixed_point"), dict(d["settings"]))


def _f(v, spec=".3f"):
    return "—" if v is None or not math.isfinite(v) else format(v, spec)


def _pct(v, ci) -> str:
    return "—" if v is None or not math.isfinite(v) else f"{v:.1f} [{ci[0]:.1f}, {ci[1]:.1f}]"


def _wall(r: dict) -> str:
    if r.get("wall_changed_pct") is None:
        return "no wall"
    return f"{r['wall_changed_pct']:.1f} / {r['at_wall_pct']:.1f}"


def _mu(v) -> str:
    return "∞" if v is None or math.isinf(v) else f"{v:g}"
