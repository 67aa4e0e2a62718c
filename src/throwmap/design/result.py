"""The result of a limit-set design: :class:`DesignResult` (frozen, with ``.plot()``; STYLE §6–7)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..system.arm import Arm
from ..system.part import Part

__all__ = ["DesignStep", "DesignResult"]


@dataclass(frozen=True, slots=True)
class DesignStep:
    """One iterate of the design: parameter values (SI), the part, what it achieves, the residual.

    ``values`` every parameter (varied or fixed) by name; ``achieved`` the targeted features by
    label (``r_0``, ``top_2``… m); ``r`` every side's r_i when computed (m); ``residual`` achieved −
    target per row (m); ``norm`` its Euclidean norm; ``bounds_hit`` the bounds active there.
    """

    values: dict
    part: Part
    achieved: dict
    r: dict
    residual: dict
    norm: float
    bounds_hit: tuple


@dataclass(frozen=True, slots=True, eq=False)
class DesignResult:
    """A limit-set design (paper Sec. V): solver outcome, the designed part and the path to it.

    Attributes
    ----------
    success : bool
        Every targeted feature within ``tol`` of its target on ``model``.
    message : str
        Why it stopped (reached; hit a bound; residual stalled; rank deficient; undefined features).
    part : Part
        The designed part: plate + weight (or the plate with its CM moved, for com_x/com_y).
    arm : Arm
        The arm (with the designed h if h varied).
    omega : float
        Release rate, rad/s.
    weight_at : (x, y)
        The lead weight's place in the frame of the plate's vertices, m.
    weight_mass : float
        kg (0: no weight).
    alpha : float or None
        Arm rest angle, rad (None: not used).
    achieved : dict
        {side: r_i} (m) for the r-targets at the solution.
    features : dict
        Every targeted feature at the solution by label (m).
    targets : tuple
        The :class:`~throwmap.design.targets.Target` / ``Separation`` objects.
    vary : tuple
        The varied parameters, in the order of p.
    bounds : dict
        The box bounds used; the weight's margin is ``margin`` (m).
    jacobian_rank, condition : int, float
        Rank and condition number of ∂(features)/∂p·diag(scale) at the solution.
    jacobian_rank_start, condition_start : int, float
        The same at the start (the draft's implicit-function-theorem test).
    jacobian : ndarray
        ∂(features)/∂p at the solution (rows: targets, columns: ``vary``; SI).
    singular_values : tuple
        Of J·diag(scale) at the solution.
    rank_tol : float
        The singular-value threshold of the rank.
    scales : dict
        The units of the rank/condition statement.
    history : tuple of DesignStep
        Every accepted iterate, the start first.
    model : str
        The map the features come from (a registered model, or ``"small_angle_F"``).
    tol, xtol : float
        Success tolerance on every feature, and the tolerance r_i is found to (m).
    n_evaluations : int
        Feature evaluations (each one :func:`critical_points` and/or :func:`limit_set` call).
    margin : float
    x_max : float or None
    """

    success: bool
    message: str
    part: Part
    arm: Arm
    omega: float
    weight_at: tuple
    weight_mass: float
    alpha: float | None
    achieved: dict
    features: dict
    targets: tuple
    vary: tuple
    bounds: dict
    jacobian_rank: int
    condition: float
    jacobian_rank_start: int
    condition_start: float
    jacobian: np.ndarray
    singular_values: tuple
    rank_tol: float
    scales: dict
    history: tuple
    model: str
    tol: float
    xtol: float
    n_evaluations: int
    margin: float
    x_max: float | None
    targets_reached: bool = False
    """The solver hit every target within ``tol`` (``success`` also needs the limit set on the arm)."""
    limit_set_note: str = ""
    """What the designed part's limit set is over the searched starts (attractors, escapes), when checked."""

    def __repr__(self) -> str:
        ach = ", ".join(f"{k}: {100 * v:.3f}" for k, v in self.features.items())
        return (f"DesignResult(success={self.success}, {self.part.name}, ω = {self.omega:.4g} rad/s, "
                f"features (cm) {{{ach}}}, rank {self.jacobian_rank}, cond {self.condition:.3g}: {self.message})")

    @property
    def start(self) -> DesignStep:
        return self.history[0]

    @property
    def n_steps(self) -> int:
        return len(self.history) - 1

    def target_values(self) -> dict:
        """{label: target value (m)} for the Target rows."""
        from .targets import Target

        return {t.label: t.value for t in self.targets if isinstance(t, Target)}

    def table(self) -> str:
        """Iterates as a plain-text table (cm, g, rad/s for reading; the data stay SI)."""
        tv = self.target_values()
        labels = list(self.history[0].achieved)
        head = "step  " + "  ".join(f"{k:>11}" for k in self.vary) + "  " + "  ".join(f"{k:>9}" for k in labels) \
            + "   |res| (mm)"
        rows = [head]
        unit = {"weight_x": 100, "weight_y": 100, "com_x": 100, "com_y": 100, "h": 100, "weight_mass": 1000,
                "omega": 1, "alpha": 180 / math.pi}
        for i, st in enumerate(self.history):
            vals = "  ".join(f"{unit[k] * st.values[k]:>11.4f}" for k in self.vary)
            ach = "  ".join(f"{100 * st.achieved[k]:>9.3f}" for k in labels)
            rows.append(f"{i:>4}  {vals}  {ach}   {1000 * st.norm:>10.3f}")
        if tv:
            rows.append("target" + " " * (13 * len(self.vary)) + "  ".join(f"{100 * tv[k]:>9.3f}" if k in tv else
                                                                       f"{'':>9}" for k in labels))
        units = {"weight_x": "cm", "weight_y": "cm", "com_x": "cm", "com_y": "cm", "h": "cm", "weight_mass": "g",
                 "omega": "rad/s", "alpha": "deg"}
        rows.append("units: " + ", ".join(f"{k} {units[k]}" for k in self.vary) + "; features cm")
        res = self.history[-1].residual
        n_act = sum(1 for lb, v in res.items() if not lb.startswith(("sep_", "wall_")) or v != 0)
        rows.append(f"Jacobian (in units of {', '.join(f'{k} {self._scale_text(k)}' for k in self.vary)}): rank "
                    f"{self.jacobian_rank_start} → {self.jacobian_rank} of {n_act} active targets, condition "
                    f"{self.condition_start:.3g} → {self.condition:.3g}")
        rows.append(f"{'success' if self.success else 'FAILED'}: {self.message}")
        return "\n".join(rows)

    def _scale_text(self, k) -> str:
        s = self.scales[k]
        return {"weight_x": f"{100 * s:g} cm", "weight_y": f"{100 * s:g} cm", "com_x": f"{100 * s:g} cm",
                "com_y": f"{100 * s:g} cm", "h": f"{100 * s:g} cm", "weight_mass": f"{1000 * s:g} g",
                "omega": f"{s:g} rad/s", "alpha": f"{math.degrees(s):g}°"}[k]

    def to_dict(self) -> dict:
        from .targets import Separation, WallWindow

        def fin(v):
            return float(v) if v is not None and math.isfinite(v) else None

        return {
            "success": self.success, "message": self.message, "model": self.model,
            "targets_reached": self.targets_reached, "limit_set": self.limit_set_note,
            "part": {"name": self.part.name, "vertices_m": [list(v) for v in self.part.vertices],
                     "mass_kg": self.part.mass, "com_m": list(self.part.com),
                     "radius_of_gyration_m": self.part.radius_of_gyration,
                     "point_masses": [[m, list(p)] for m, p in self.part.point_masses]},
            "omega_rad_s": self.omega, "weight_at_m": list(self.weight_at), "weight_mass_kg": self.weight_mass,
            "alpha_rad": self.alpha, "h_m": self.arm.h,
            "achieved_r_m": {str(s): fin(v) for s, v in self.achieved.items()},
            "features_m": {k: fin(v) for k, v in self.features.items()},
            "targets": [({"kind": "separation", "side": t.side, "x_m": t.x, "margin_m": t.margin}
                         if isinstance(t, Separation) else
                         {"kind": "wall_window", "side": t.side, "jitter": t.jitter, "width_m": t.width}
                         if isinstance(t, WallWindow) else {"kind": t.kind, "side": t.side, "value_m": t.value})
                        for t in self.targets],
            "vary": list(self.vary), "bounds": {k: list(v) for k, v in self.bounds.items()}, "margin_m": self.margin,
            "jacobian": {"rank_start": self.jacobian_rank_start, "rank": self.jacobian_rank,
                         "condition_start": fin(self.condition_start), "condition": fin(self.condition),
                         "matrix_si": self.jacobian.tolist(), "singular_values": list(self.singular_values),
                         "rank_tol": self.rank_tol, "scales": {k: self.scales[k] for k in self.vary}},
            "history": [{"values": st.values, "achieved_m": {k: fin(v) for k, v in st.achieved.items()},
                         "residual_m": {k: fin(v) for k, v in st.residual.items()}, "norm_m": st.norm,
                         "bounds_hit": list(st.bounds_hit)} for st in self.history],
            "tol_m": self.tol, "xtol_m": self.xtol, "n_evaluations": self.n_evaluations, "x_max_m": self.x_max,
        }

    def limit_sets(self, steps, n_starts: int = 16) -> dict:
        """{step: LimitSet} of the chosen iterates' parts on this design's map (``n_starts`` per side,
        seed 0); the small-angle design's are drawn on ``rigid_body``."""
        from ..analysis.limitset import limit_set
        from ..models import model_names

        model = self.model if self.model in model_names() else "rigid_body"
        out = {}
        for i in steps:
            st = self.history[int(i)]
            arm = self.arm if st.values.get("h", self.arm.h) == self.arm.h else _replace_h(self.arm, st.values["h"])
            opts = {} if st.values.get("alpha") is None else {"alpha": st.values["alpha"]}
            out[int(i)] = limit_set(st.part, arm, st.values["omega"], model, n_starts=n_starts, rng=0,
                                    x_max=self.x_max, **opts)
        return out

    def plot(self, ax=None, *, steps=None, limit_sets: bool = True, unit: str = "cm", separation=None):
        """The Fig. 8 analogue: for chosen iterates the part with its weight beside its limit set,
        r_i and the targets; see :func:`throwmap.viz.design.plot_design`."""
        from ..viz.design import plot_design

        return plot_design(self, ax=ax, steps=steps, limit_sets=limit_sets, unit=unit, separation=separation)


def _replace_h(arm, h):
    import dataclasses

    return dataclasses.replace(arm, h=h)
