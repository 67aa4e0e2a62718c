"""What ``throwmap reproduce`` makes: the draft's figures that have an analogue, its four experiments, the sizes.

Every entry names the draft's figure or section and the throwmap code that makes its analogue. The draft's
experiment numbers are its hardware results (20 trials each): positioning 20/20 (Sec. IV-A, Fig. 7), feeding
19/20 (Sec. V-C, Fig. 9), sequential assembly 11/20 (Sec. V-D, Fig. 10) and sensor-switched self-assembly 14/20
(Sec. VI, Figs. 15 and 16).
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["FigureSpec", "ExperimentSpec", "Size", "FIGURES", "EXPERIMENTS", "SIZES"]


@dataclass(frozen=True, slots=True)
class FigureSpec:
    """One figure: ``key`` (file stem), ``draft`` (the draft's figure), ``caption``, ``maker`` (the name of the
    function in :mod:`throwmap.reproduce.figures` that makes it)."""

    key: str
    draft: str
    caption: str
    maker: str


@dataclass(frozen=True, slots=True)
class ExperimentSpec:
    """One of the draft's experiments: ``key``, ``title``, ``section``, the draft's ``draft_successes`` of
    ``draft_n`` hardware trials, the throwmap ``experiment`` name and its ``config`` (None: the built-in example),
    ``goal`` (the target success rate) and ``note`` (what the draft's experiment was)."""

    key: str
    title: str
    section: str
    draft_successes: int
    draft_n: int
    experiment: str
    config: dict | None = None
    goal: float | None = None
    note: str = ""


@dataclass(frozen=True, slots=True)
class Size:
    """``name``; ``n`` trials per experiment; ``engine`` whether engine checks run beside the exact figures;
    ``lean_n`` random leans in the Fig. 13 table."""

    name: str
    n: int
    engine: bool
    lean_n: int


SIZES = {"full": Size("full", 200, True, 200), "quick": Size("quick", 3, False, 10)}
"""``full``: ≥ 200 trials per experiment; ``quick``: a smoke run for tests (minutes)."""

FIGURES = (
    FigureSpec("fig02_throw_map", "Fig. 2", "The throw map T(x) per side at ω = 4 rad/s (\"paper\" model) with the "
               "diagonal: jogs below the switch to a flip, flips beyond it (the draft's conceptual 1-D maps).",
               "throw_map"),
    FigureSpec("fig02_funnels", "Fig. 2", "Funnels: the maps at ω = 3 and 4 rad/s ordered towards a goal far on "
               "the arm (rigid_body, arm analysed to 1 m): which map's spout lies in which map's mouth.", "funnels"),
    FigureSpec("fig05_limit_set", "Fig. 5", "The canonical triangle's limit set at ω = 4 rad/s (rigid_body, "
               "x ≤ 0.6 m searched) with the critical radii r_i, l_i and an orbit on it.", "limit_set"),
    FigureSpec("fig07_position", "Fig. 7", "Feedback positioning with one-bit sensors: x per throw of one trial of "
               "`experiment position` (engine, recoil arm), the controller's switches marked.", "position_episode"),
    FigureSpec("fig08_design", "Fig. 8", "The realisable feeder design: iterates of the Levenberg–Marquardt design "
               "on the exact model, each part drawn with its weight beside its limit set and the targets.", "design"),
    FigureSpec("fig09_capture", "Fig. 9", "The designed part captured in its cavity at the arm's end (the "
               "engine's capture check's final pose), the cavity's profile designed for it.", "capture"),
    FigureSpec("fig13_lean", "Fig. 13", "Leaning against a frictionless wall at α = −10°: the configuration with "
               "its contact forces and cones, and the feasible region over (β, μ).", "lean"),
    FigureSpec("fig14_partial", "Fig. 14", "The partial assembly of two triangles at the wall: forces and cones at "
               "γ = −15°, and the arm friction needed over γ.", "partial"),
    FigureSpec("fig16_assembly", "Fig. 16", "Self-assembly (engine): x of both triangles against throw number, "
               "the sensor's switch and the assembly marked.", "assembly_episode"),
    FigureSpec("fig15_snapshots", "Fig. 15", "The same trial: the pair at the switch, partly assembled, "
               "assembled.", "assembly_snapshots"),
)
"""Figures, in report order (Fig. 15 is drawn from the same trial as Fig. 16)."""

EXPERIMENTS = (
    ExperimentSpec("positioning", "Positioning with one-bit sensors", "Sec. IV-A, Fig. 7", 20, 20, "position",
                   goal=0.95, note="a part driven to a chosen rest by feedback throws"),
    ExperimentSpec("feeding", "Feeding into a cavity", "Sec. V-C, Fig. 9", 19, 20, "feed", goal=0.99,
                   note="the designed part captured on its target side and still there after 50 more throws"),
    ExperimentSpec("sequential", "Sequential assembly into a cavity", "Sec. V-D, Fig. 10", 11, 20,
                   "assemble-sequential", goal=0.80,
                   note="a triangle and a four-sided part thrown into one cavity (the draft: open loop; here a "
                        "one-bit 'stuck' sensor switches in a tilted recovery throw)"),
    ExperimentSpec("self_assembly", "Sensor-switched self-assembly", "Sec. VI, Figs. 15–16", 14, 20, "assemble",
                   goal=0.95, note="two triangles, a one-bit vision sensor switches from high to low throws at "
                                   "α = −10° against a frictionless wall"),
)
"""The draft's four hardware experiments and the throwmap experiment that reproduces each."""
