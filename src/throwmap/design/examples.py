"""The draft's design example (paper Sec. V-B), reproduced honestly, and a realisable feeder design.

The part is the draft's 17 cm 30-60-90 plexiglas triangle (:func:`plexiglas_triangle`: PMMA,
1190 kg/m³, 6.35 mm = 1/4 in thick → 47.3 g), sides numbered as in :mod:`throwmap.conventions`
(side 0 the hypotenuse, as the draft's text says; 1 the long leg, 2 the short leg). The draft
gives its numbers in cm; they are converted here, at the edge.

:func:`draft_example`
    What the draft's CM (u_L, v_L) = (−2, −3.5) cm and its design (−2.8, −3.8) cm mean on this
    plate (three readings; which can be realised by a lead weight, and how heavy), the r_i of
    the draft's start and design on the corrected energy test, the exact model and the engine,
    the corrected small-angle design for the draft's goal and its miss on the exact model, and
    the exact design for the same goal.
:func:`feeder_design`
    The realisable design handed to the feeding experiment: a 50 g lead weight on the plate,
    side 0 alone reaches the far part of the arm. Read from ``data/feeder_design.toml``
    (computed by :func:`run_feeder_design`; a test re-runs it and checks the stored numbers).

Chosen values the draft does not state (the parameter table of docs/how-to/design.md): h = −1 cm (inside the
paper's regime 0 > h > −min d for every part here but the draft's CM-only parameterisation),
g = 9.81 m/s², μ = ∞ (the paper's no-slip), arm length 60 cm, weight margin 8 mm (a lead
cylinder of 8 mm radius: 50 g is 4.4 cm³, 16 mm across and 22 mm tall), engine r_i on a 48-point
grid to 20 µm.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from importlib import resources

import numpy as np

from ..system.arm import Arm
from ..system.catalogue import triangle_30_60_90
from ..system.part import Part
from .api import DEFAULT_MARGIN, SMALL_ANGLE_F, design
from .plate import WeightForCom, lightest_weight_for_com
from .radii import SideRadii
from .result import DesignResult
from .small_angle import energy_critical_points

__all__ = ["PMMA_DENSITY", "PLATE_THICKNESS", "LEAD_DENSITY", "HYPOTENUSE", "DRAFT", "DRAFT_TARGETS",
           "FEEDER", "plexiglas_triangle", "draft_arm", "feeder_arm", "draft_cm_readings", "CmReading",
           "PointRow", "DraftExample", "draft_example", "FeederDesign", "feeder_design", "run_feeder_design",
           "exact_r", "engine_r", "ENGINE_GRID", "end_wall_window", "feeder_toml"]

PMMA_DENSITY = 1190.0
"""Plexiglas (PMMA), kg/m³."""
PLATE_THICKNESS = 0.00635
"""1/4 in, m (the draft does not say; a common sheet)."""
LEAD_DENSITY = 11340.0
"""kg/m³ (for the weight's size in the parameter table)."""
HYPOTENUSE = 0.17
"""The draft's triangle (Sec. IV-A, V-C), m."""

DRAFT = {
    "start_uv": (-0.02, -0.035), "design_uv": (-0.028, -0.038),  # (u_L^0, v_L^0), m (draft: cm)
    "omega_start": 5.6, "omega_design": 4.6,  # rad/s
    "targets_printed": {0: 0.10, 1: 0.10, 2: 0.20},  # {r_0, r_1, r_2}, m, as printed
    "simulated_printed": {0: 0.14, 1: 0.14, 2: 0.20},  # the draft's "numerically simulated" r_i, m
}
"""The draft's numbers (Sec. V-B), converted to SI."""

DRAFT_TARGETS = {0: 0.20, 1: 0.10, 2: 0.10}
"""The draft's goal in this numbering: its text asks r_0 ≫ r_i (side 0 the hypotenuse) while its
Fig. 8 and targets make r_2 the large one (the reviewer's remark: the numbering is inconsistent).
The hypotenuse is the side that reaches farthest on this triangle, so the 20 cm goes to side 0."""

FEEDER = {"weight_mass": 0.050, "start_at": "centroid", "omega_start": 5.0, "h": -0.01, "length": 0.60,
          "targets": {0: 0.320, 1: 0.155, 2: 0.235}, "side": 0, "x": 0.335, "margin": 0.035, "jitter": 0.06,
          "wall_width": 0.05}
"""The feeder's design problem: start (50 g at the plate's centroid, ω = 5 rad/s), arm, r-targets (m),
the separation it is checked against (the limit set passes x = 33.5 cm only on side 0, margin 3.5 cm)
and the robust-separation objective: an end wall holds side 0 only, for ω within ± 6 % (2σ of the
experiment's 3 % noise), over a window of L at least 5 cm wide (:class:`~throwmap.design.targets.WallWindow`)."""

ENGINE_GRID = {"n_grid": 48, "n_split": 7, "xtol": 2e-5}
"""critical_points options for the engine's r_i (its cost bounded: ≈ 300 throws per part)."""


def plexiglas_triangle() -> Part:
    """The draft's 17 cm 30-60-90 triangle of 6.35 mm PMMA (47.3 g), uniform, no weight."""
    a = 0.5 * HYPOTENUSE
    b = 0.5 * math.sqrt(3.0) * HYPOTENUSE
    return triangle_30_60_90(HYPOTENUSE, mass=PMMA_DENSITY * PLATE_THICKNESS * 0.5 * a * b)


def draft_arm() -> Arm:
    """The arm for the draft's example: h = −1 cm, 60 cm long, no slip (values the draft leaves open)."""
    return Arm(h=-0.01, length=0.60)


def feeder_arm() -> Arm:
    """The arm the feeder is designed on: h = −1 cm, 60 cm long, no slip (its r_i do not depend on μ ∈ {0.5, 1, ∞}
    to 0.01 mm; the feeding arm ends earlier, at a wall inside :func:`end_wall_window`)."""
    return Arm(h=FEEDER["h"], length=FEEDER["length"])


# ----------------------------------------------------------------- realisability
@dataclass(frozen=True, slots=True)
class CmReading:
    """One reading of the draft's (u_L^0, v_L^0): the CM it means (m) and the lightest weight giving it."""

    name: str
    meaning: str
    com: tuple
    weight: WeightForCom

    @property
    def inside_plate(self) -> bool:
        return self.weight.inside_plate


def draft_cm_readings(uv, plate: Part | None = None, margin: float = DEFAULT_MARGIN) -> tuple:
    """The CM the draft's (u_L^0, v_L^0) = ``uv`` (m) stands for, in three readings.

    ``A``: Sec. III-A's definition — the vector from the CM to the left support vertex of side 0
    (the hypotenuse) — with the left vertex of :mod:`throwmap.conventions` (the 30° corner);
    ``B``: the same with the other end of the hypotenuse (the 60° corner) as "left";
    ``C``: the vector from the CM to the right-angle corner (the body origin), legs as axes.
    Each with the lightest lead weight that puts the CM there (:func:`lightest_weight_for_com`).
    """
    plate = plexiglas_triangle() if plate is None else plate
    V = np.asarray(plate.vertices, dtype=float)
    A, B, C = V  # 30° corner, 60° corner, right angle (catalogue order)
    e = (B - A) / np.linalg.norm(B - A)
    n_in = np.array([-e[1], e[0]])
    if np.dot(C - A, n_in) < 0:
        n_in = -n_in
    u, v = uv
    m_plate = plate.mass - sum(m for m, _ in plate.point_masses)
    out = []
    for name, meaning, c in (
        ("A", "CM → left support vertex of the hypotenuse (30° corner), Sec. III-A", A - u * e - v * n_in),
        ("B", "CM → the hypotenuse's other end (60° corner) as 'left'", B + u * e - v * n_in),
        ("C", "CM → the right-angle corner (legs as axes)", C - np.array([u, v])),
    ):
        out.append(CmReading(name, meaning, (float(c[0]), float(c[1])),
                             lightest_weight_for_com(V, m_plate, c, margin)))
    return tuple(out)


# ----------------------------------------------------------------- r_i on every model
def exact_r(part, arm, omega, model: str = "rigid_body", **options) -> SideRadii:
    """r_i of every stable side on a registered model (m), l_i skipped: a :class:`~throwmap.design.radii.SideRadii`
    (``.r``: side → m)."""
    from ..analysis.critical import critical_points
    from .targets import _NoLimit

    return SideRadii(dict(critical_points(part, arm, omega, model, limit=_NoLimit(), **options).r), model, part.name,
                     float(omega))


def engine_r(part, arm, omega) -> SideRadii:
    """r_i in the pymunk engine with :data:`ENGINE_GRID` (to 20 µm): a :class:`~throwmap.design.radii.SideRadii`."""
    return exact_r(part, arm, omega, "engine", **ENGINE_GRID)


@dataclass(frozen=True, slots=True)
class PointRow:
    """One design point of the draft-example table: r_i (m) on the energy test, the exact model, the engine."""

    label: str
    part: Part
    omega: float
    f_r: dict
    exact_r: dict
    engine_r: dict
    draft_r: dict


def _row(label, part, arm, omega, draft_r, engine: bool) -> PointRow:
    return PointRow(label, part, float(omega), energy_critical_points(part, arm, omega).r, exact_r(part, arm, omega).r,
                    engine_r(part, arm, omega).r if engine else {}, dict(draft_r))


@dataclass(frozen=True, slots=True, eq=False)
class DraftExample:
    """The draft's Sec. V-B example on the 17 cm plexiglas triangle (see :func:`draft_example`)."""

    plate: Part
    arm: Arm
    readings_start: tuple
    readings_design: tuple
    rows: tuple
    small_angle: DesignResult
    exact: DesignResult
    as_printed: DesignResult
    targets: dict
    exact_limit: str
    exact_limit_kind: str
    exact_escapes: dict

    def table(self) -> str:
        def cm(d, sides=(0, 1, 2)):
            return "{" + ", ".join(f"{100 * d[s]:.2f}" if s in d and math.isfinite(d[s]) else "—" for s in sides) + "}"

        lines = [f"plate: {self.plate.name}, {1000 * self.plate.mass:.1f} g (PMMA {PMMA_DENSITY:g} kg/m³, "
                 f"{1000 * PLATE_THICKNESS:g} mm); arm h = {100 * self.arm.h:g} cm, length {100 * self.arm.length:g} cm",
                 "", "the draft's CM (u_L, v_L) on this plate (lightest lead weight, 8 mm inside every edge):"]
        for what, rd in (("start (−2, −3.5) cm", self.readings_start), ("design (−2.8, −3.8) cm", self.readings_design)):
            for r in rd:
                w = r.weight
                where = (f"lead {1000 * w.mass:.1f} g ({w.ratio:.2f} × plate) at ({100 * w.at[0]:.2f}, "
                         f"{100 * w.at[1]:.2f}) cm" if w.realisable else
                         ("inside the plate but within 8 mm of an edge: no weight of finite size" if r.inside_plate
                          else "OUTSIDE the plate: no mass distribution on it has this CM"))
                lines.append(f"  {what:<24} reading {r.name}: CM ({100 * r.com[0]:.2f}, {100 * r.com[1]:.2f}) cm — {where}")
        lines += ["", "r_i in cm {r_0, r_1, r_2} (sides: 0 hypotenuse, 1 long leg, 2 short leg):",
                  f"{'point':<44} {'lead g at (x, y) cm':>24} {'ω':>6}  {'draft':>20}  {'energy test F':>20}  "
                  f"{'exact (rigid_body)':>20}  {'engine (pymunk)':>20}"]
        for r in self.rows:
            m, (x, y) = r.part.point_masses[0]
            lead = f"{1000 * m:.1f} at ({100 * x:.2f}, {100 * y:.2f})"
            lines.append(f"{r.label:<44} {lead:>24} {r.omega:>6.3f}  {cm(r.draft_r):>20}  {cm(r.f_r):>20}  "
                         f"{cm(r.exact_r):>20}  {cm(r.engine_r):>20}")
        lines.append("(draft column: the draft's own 'numerically simulated' r_i of its design; its F-targets were "
                     f"{cm(DRAFT['targets_printed'])} cm; —: no flip below the arm's end in that test)")
        miss = {s: self.rows[2].exact_r[s] - self.targets[s] for s in self.targets}
        lines += ["", f"corrected small-angle design for {cm(self.targets)} cm: {self.small_angle.message}",
                  f"  its miss on the exact model: {cm(miss)} cm (the draft's own: {{+4, +4, 0}} cm)",
                  f"exact design for {cm(self.targets)} cm (from the draft's start): {self.exact.message}",
                  f"  but its limit set: {self.exact_limit_kind}"
                  + (f" ({', '.join(f'{k} {100 * v:.1f} %' for k, v in self.exact_escapes.items())} of starts)"
                     if self.exact_escapes else "")
                  + (": r_i meet the goal, yet no orbit stays on the arm — sup S = r_i presumes a limit set that "
                     "is not there" if self.exact_limit_kind == "escape" else ""),
                  f"the draft's targets as printed ({cm(DRAFT['targets_printed'])} cm, r_2 large) in this numbering: "
                  f"{self.as_printed.message}"]
        return "\n".join(lines)

    def plot(self, **kwargs):
        """The Fig. 8 analogue of the exact design (start → solution)."""
        return self.exact.plot(**kwargs)


def draft_example(*, engine: bool = True) -> DraftExample:
    """Reproduce the draft's Sec. V-B example (reading C of its CM, the only one that fits the plate).

    Rows: the draft's start and design (each CM realised by its lightest lead weight), the
    corrected small-angle design for :data:`DRAFT_TARGETS` (weight mass fixed to the start's,
    weight place and ω varied, from the draft's start) and the exact design for the same goal
    from the same start; then the limit set of the exact design (32 starts per side, seed 0). ``engine`` False skips the engine's r_i (≈ 2 s per row).
    """
    plate = plexiglas_triangle()
    arm = draft_arm()
    rs = draft_cm_readings(DRAFT["start_uv"], plate)
    rd = draft_cm_readings(DRAFT["design_uv"], plate)
    ws, wd = rs[2].weight, rd[2].weight
    p_start = Part.from_vertices(plate.vertices, mass=plate.mass, point_masses=((ws.mass, ws.at),))
    p_design = Part.from_vertices(plate.vertices, mass=plate.mass, point_masses=((wd.mass, wd.at),))
    sa = design(plate, arm, DRAFT["omega_start"], DRAFT_TARGETS, weight_mass=ws.mass, weight_at=ws.at,
                model=SMALL_ANGLE_F)
    ex = design(plate, arm, DRAFT["omega_start"], DRAFT_TARGETS, weight_mass=ws.mass, weight_at=ws.at)
    from ..analysis.limitset import limit_set

    ls = limit_set(ex.part, arm, ex.omega, n_starts=32, rng=0)
    printed = design(plate, arm, DRAFT["omega_start"], DRAFT["targets_printed"], weight_mass=ws.mass, weight_at=ws.at)
    rows = (
        _row("draft start: CM (2, 3.5) cm, ω 5.6", p_start, arm, DRAFT["omega_start"], {}, engine),
        _row("draft design: CM (2.8, 3.8) cm, ω 4.6", p_design, arm, DRAFT["omega_design"],
             DRAFT["simulated_printed"], engine),
        _row("corrected small-angle design (weight + ω)", sa.part, arm, sa.omega, {}, engine),
        _row("exact design (weight + ω, from the start)", ex.part, arm, ex.omega, {}, engine),
    )
    return DraftExample(plate=plate, arm=arm, readings_start=rs, readings_design=rd, rows=rows, small_angle=sa,
                        exact=ex, as_printed=printed, targets=dict(DRAFT_TARGETS), exact_limit=ls.summary(),
                        exact_limit_kind=ls.kind, exact_escapes=dict(ls.escapes))


# ----------------------------------------------------------------- the feeder
@dataclass(frozen=True, slots=True, eq=False)
class FeederDesign:
    """The realisable design the feeding experiment uses (SI).

    ``part`` plate + lead weight; ``arm``, ``omega`` (rad/s); ``target_side`` the side that alone
    reaches beyond ``separation_x`` + ``separation_margin`` while every other side's limit set
    stays below ``separation_x`` − ``separation_margin`` (m). ``r``, ``tops``, ``bottoms`` the
    exact-model r_i and the limit set's band tops/bottoms per side, ``engine_r`` the engine's
    r_i (to ``engine_xtol``), ``targets`` the r-targets the design met, all as stored in
    ``data/feeder_design.toml``.
    """

    plate: Part
    part: Part
    arm: Arm
    omega: float
    weight_mass: float
    weight_at: tuple
    target_side: int
    separation_x: float
    separation_margin: float
    targets: dict
    r: dict
    tops: dict
    bottoms: dict
    engine_r: dict
    engine_xtol: float
    model: str
    jitter: float
    wall_window: tuple

    @property
    def wall_separation(self) -> float:
        """S = hi − lo of :func:`end_wall_window` (m)."""
        return self.wall_window[1] - self.wall_window[0]

    def table(self) -> str:
        s = sorted(self.r)
        f = lambda d: "  ".join(f"{100 * d[k]:8.3f}" for k in s)  # noqa: E731
        return "\n".join([
            f"part: {self.part.name} ({1000 * self.part.mass:.1f} g, CM ({100 * self.part.com[0]:.2f}, "
            f"{100 * self.part.com[1]:.2f}) cm, ρ {100 * self.part.radius_of_gyration:.2f} cm)",
            f"arm: h {100 * self.arm.h:g} cm, length {100 * self.arm.length:g} cm; ω = {self.omega:.5f} rad/s; "
            f"model {self.model}",
            "side        " + "  ".join(f"{k:>8}" for k in s),
            "target r_i  " + f(self.targets),
            "exact r_i   " + f(self.r),
            "engine r_i  " + f(self.engine_r) + f"   (to {1e6 * self.engine_xtol:g} µm)",
            "band top    " + f(self.tops),
            "band bottom " + f(self.bottoms),
            f"x beyond {100 * self.separation_x:g} cm is reached only on side {self.target_side} "
            f"(margin {100 * self.separation_margin:g} cm)   [cm]",
            f"end wall at L in ({100 * self.wall_window[0]:.2f}, {100 * self.wall_window[1]:.2f}) cm holds side "
            f"{self.target_side} only, for ω within ±{100 * self.jitter:g} % (S = {100 * self.wall_separation:.2f} cm)",
        ])


def end_wall_window(part, arm, omega, side: int, jitter: float = 0.06) -> tuple:
    """Where an end wall turns the shaped limit set into a fixed point on ``side`` only: ``(lo, hi, S)`` (m).

    A part resting against a wall at the arm's end L has its CM at L − u_R(i) (u_R: CM → outer
    support vertex). The throw from there is a jog — the part stays at the wall — iff
    L − u_R(i) < r_i. So side k is held for every ω in [ω(1 − jitter), ω(1 + jitter)] iff
    L < hi = r_k(ω(1 + jitter)) + u_R(k) (r_i falls as ω rises), and every other side j flips away
    iff L > lo = max_j r_j(ω(1 − jitter)) + u_R(j). ``S = hi − lo`` is the usable width (> 0 needed).
    r_i on ``arm`` (exact model).
    """
    r_lo = exact_r(part, arm, omega * (1 - jitter)).r
    r_hi = exact_r(part, arm, omega * (1 + jitter)).r
    hi = r_hi[side] + float(part.uR[side])
    lo = max(r_lo[j] + float(part.uR[j]) for j in r_lo if j != side)
    return lo, hi, hi - lo


def _load_toml() -> dict:
    with resources.files("throwmap").joinpath("data/feeder_design.toml").open("rb") as fh:
        return tomllib.load(fh)


def feeder_design() -> FeederDesign:
    """The realisable feeder design, from ``data/feeder_design.toml`` (cheap; see :func:`run_feeder_design`)."""
    d = _load_toml()
    plate = plexiglas_triangle()
    w = d["weight"]
    part = Part.from_vertices(plate.vertices, mass=plate.mass, point_masses=((w["mass_kg"], tuple(w["at_m"])),),
                              name=f"{plate.name}+lead({1000 * w['mass_kg']:.4g} g at ({100 * w['at_m'][0]:.4g}, "
                                   f"{100 * w['at_m'][1]:.4g}) cm)")
    a = d["arm"]
    arm = Arm(h=a["h_m"], length=a["length_m"])
    sides = lambda t: {int(k): float(v) for k, v in t.items()}  # noqa: E731
    return FeederDesign(plate=plate, part=part, arm=arm, omega=float(d["omega_rad_s"]), weight_mass=float(w["mass_kg"]),
                        weight_at=tuple(float(v) for v in w["at_m"]), target_side=int(d["separation"]["side"]),
                        separation_x=float(d["separation"]["x_m"]), separation_margin=float(d["separation"]["margin_m"]),
                        targets=sides(d["targets_r_m"]), r=sides(d["exact"]["r_m"]), tops=sides(d["exact"]["top_m"]),
                        bottoms=sides(d["exact"]["bottom_m"]), engine_r=sides(d["engine"]["r_m"]),
                        engine_xtol=float(d["engine"]["xtol_m"]), model=str(d["model"]),
                        jitter=float(d["end_wall"]["jitter"]), wall_window=tuple(d["end_wall"]["window_m"]))


def run_feeder_design(*, engine: bool = True, limit_starts: int = 64) -> tuple:
    """Compute the feeder design from scratch: ``(DesignResult, FeederDesign)``.

    The design: 50 g of lead, starting at the plate's centroid with ω = 5 rad/s, weight place
    and ω varied until the exact r_i hit :data:`FEEDER` ``["targets"]`` and the end-wall window for
    ±6 % ω is at least 5 cm wide (a hinge: inactive once met); then the limit set
    (``limit_starts`` per side, seed 0) gives the band tops/bottoms, and the engine its r_i.
    """
    from ..analysis.limitset import limit_set

    plate = plexiglas_triangle()
    arm = feeder_arm()
    from .targets import Target, WallWindow

    objective = [Target("r", s, v) for s, v in sorted(FEEDER["targets"].items())]
    objective.append(WallWindow(FEEDER["side"], FEEDER["jitter"], FEEDER["wall_width"]))
    res = design(plate, arm, FEEDER["omega_start"], objective, weight_mass=FEEDER["weight_mass"])
    ls = limit_set(res.part, arm, res.omega, n_starts=limit_starts, rng=0)
    er = engine_r(res.part, arm, res.omega).r if engine else {s: math.nan for s in res.achieved}
    fd = FeederDesign(plate=plate, part=res.part, arm=arm, omega=res.omega, weight_mass=res.weight_mass,
                      weight_at=res.weight_at, target_side=FEEDER["side"], separation_x=FEEDER["x"],
                      separation_margin=FEEDER["margin"], targets=dict(FEEDER["targets"]), r=dict(res.achieved),
                      tops={s: ls.u(s) for s in res.part.stable_sides},
                      bottoms={s: ls.l(s) for s in res.part.stable_sides}, engine_r=er,
                      engine_xtol=ENGINE_GRID["xtol"], model="rigid_body", jitter=FEEDER["jitter"],
                      wall_window=end_wall_window(res.part, arm, res.omega, FEEDER["side"], FEEDER["jitter"])[:2])
    return res, fd


def feeder_toml(fd: FeederDesign, res: DesignResult) -> str:
    """The data file's text for a computed design (written by ``throwmap design example feeder --write-data``)."""
    def tab(d):
        return "{ " + ", ".join(f'"{k}" = {v!r}' for k, v in sorted(d.items())) + " }"

    return "\n".join([
        "# The realisable feeder design (throwmap.design.examples.run_feeder_design), SI units.",
        "# Regenerate: throwmap design example feeder --write-data; tests/design re-run the design and",
        "# check these numbers still meet the targets on the exact model.",
        f'model = "{fd.model}"',
        f"omega_rad_s = {fd.omega!r}",
        f"targets_r_m = {tab(fd.targets)}",
        "",
        "[plate]",
        f'name = "{fd.plate.name}"',
        f"mass_kg = {fd.plate.mass!r}",
        f"pmma_density_kg_m3 = {PMMA_DENSITY!r}",
        f"thickness_m = {PLATE_THICKNESS!r}",
        "",
        "[weight]",
        f"mass_kg = {fd.weight_mass!r}",
        f"at_m = [{fd.weight_at[0]!r}, {fd.weight_at[1]!r}]",
        f"margin_m = {res.margin!r}",
        "",
        "[arm]",
        f"h_m = {fd.arm.h!r}",
        f"length_m = {fd.arm.length!r}",
        "",
        "[separation]",
        f"side = {fd.target_side}",
        f"x_m = {fd.separation_x!r}",
        f"margin_m = {fd.separation_margin!r}",
        "",
        "[exact]",
        f"r_m = {tab(fd.r)}",
        f"top_m = {tab(fd.tops)}",
        f"bottom_m = {tab(fd.bottoms)}",
        f"jacobian_rank = {res.jacobian_rank}",
        f"condition = {res.condition!r}",
        f"steps = {res.n_steps}",
        "",
        "[engine]",
        f"r_m = {tab(fd.engine_r)}",
        f"xtol_m = {fd.engine_xtol!r}",
        "",
        "[end_wall]",
        f"objective_width_m = {FEEDER['wall_width']!r}",
        f"jitter = {fd.jitter!r}",
        f"window_m = [{fd.wall_window[0]!r}, {fd.wall_window[1]!r}]",
        "",
    ])
