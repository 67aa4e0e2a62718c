"""The design sheet of a verified feeder: drawing, numbers, margins, one fed trial to watch.

:func:`write_sheet` writes into the feeder's folder:

* ``drawing.svg`` / ``drawing.png`` — the arm's end with the lined pocket and the end wall, the part at
  rest in its fed pose with the lead weight marked, dimensioned (:func:`throwmap.viz.capture.plot_capture`),
  beside the part in its own frame with the weight's place and the fed side;
* ``margins`` — how far the nominal ω, the arm's μ, the ω jitter and the weight's place may drift before the
  feeding experiment falls below the goal: for each direction, steps of growing drift, each an engine run of
  ``margin_trials`` trials (a step fails when its rate is clearly below the goal — its Wilson 95 % upper end under
  it, the test the search's own drift checks use — and holds otherwise), stopped at the first step that fails
  (for the weight's place, a first step that fails is followed by one of half its size); the steps go breadth
  first (every quantity's smallest drift before any larger one), so a short budget still measures each quantity;
* ``fed_trial.html`` — the viewer page of one fed trial of the verification, replayed from its seed
  (:meth:`throwmap.experiments.feed.Feed.replay`): the throws from the settled drop to 3 throws after capture;
* ``sheet.md`` / ``sheet.html`` — all of it: the feeder (part, weight, throw schedule, pocket and wall),
  predicted and verified success with Wilson 95 % intervals and the range a new run lands in, throws to
  capture (median, p90), the failure
  modes seen, the margins and the assumptions.

The sheet is built from the search's result and the feeder's own files; every number on it is in SI units
(lengths also in cm where a drawing speaks cm).
"""

from __future__ import annotations

import dataclasses
import html
import json
import math
import time
from pathlib import Path

import numpy as np

from ..errors import InvalidStateError
from ..io.files import atomic_write_text
from .checks import drift_text, drifted, stage_label

__all__ = ["write_sheet", "drawing", "margins", "drifted", "MARGIN_STEPS"]

MARGIN_STEPS = {
    "omega": ((-0.03, -0.06, -0.10), (0.03, 0.06, 0.10)),
    "mu": ((0.8, 0.6), (1.25, 1.5)),
    "jitter": ((0.05, 0.08),),
    "weight_x": ((-0.003, -0.006), (0.003, 0.006)),
    "weight_y": ((-0.003, -0.006), (0.003, 0.006)),
}
"""Drift steps per quantity and direction: ω relative change; μ factor on the nominal; jitter σ (absolute);
the weight's place shifted in the part's x / y, m."""
HALVED = ("weight_x", "weight_y")
"""Quantities whose first step, when it fails, is followed by one of half the size (a weight that must sit within
3 mm is told apart from one that must sit within 1.5 mm)."""


def margins(cfg, folder, *, trials: int = 30, goal: float = 0.95, seed: int = 100, workers: int = 0,
            budget_s: float = math.inf, progress=None) -> dict:
    """The drift each quantity of :data:`MARGIN_STEPS` tolerates (see the module docstring): per quantity and
    direction ``{"passed": last step passing or None, "failed": first step failing or None, "runs": [...]}``.

    The steps go breadth first: the first step of every quantity and direction, then every second step, …, so that
    a short budget measures each quantity's smallest drift before any larger one. No step is started after
    ``budget_s`` seconds; a direction with no step run gets ``"not measured": "budget"``."""
    import time

    from ..experiments.runner import run_experiment

    t0 = time.perf_counter()
    folder = Path(folder)
    lanes = [{"what": what, "steps": list(steps), "runs": [], "passed": None, "failed": None, "open": True}
             for what, directions in MARGIN_STEPS.items() for steps in directions]
    while any(lane["open"] for lane in lanes) and time.perf_counter() - t0 <= budget_s:
        for lane in lanes:
            if not lane["open"] or time.perf_counter() - t0 > budget_s:
                continue
            what, step = lane["what"], lane["steps"].pop(0)
            here = folder / f"{what}_{step:+g}"
            c = drifted(cfg, what, step, here)
            lane["open"] = bool(lane["steps"])
            if c is None:  # off the plate (or no weight to move): this direction ends here
                lane["open"], lane["off"] = False, not lane["runs"]
                continue
            here.mkdir(parents=True, exist_ok=True)
            lab = stage_label(f"margin {what} {step:+g}", here / "run", trials)
            cb = None if progress is None else (lambda d, t, lab=lab: progress(lab, d, t))
            res = run_experiment("feed", c, n=trials, seed=seed, workers=workers, out=here / "run", progress=cb,
                                 stop_by=t0 + budget_s)
            if res.n < trials:  # cut short by the budget: no verdict on this step, but its count is shown
                lane["open"], lane["cut"] = False, {"step": step, "n": res.n, "successes": res.successes,
                                                   "planned": trials}
                continue
            lane["runs"].append({"step": step, "n": res.n, "successes": res.successes,
                                 "ci95": [float(res.ci95[0]), float(res.ci95[1])]})
            if res.ci95[1] >= goal:  # fails only when clearly below: 30 trials cannot tell 95 % from 90 %
                lane["passed"] = step
                continue
            lane["failed"], lane["open"] = step, False
            if what in HALVED and lane["passed"] is None and len(lane["runs"]) == 1:  # the first failed: half of it
                lane["steps"], lane["open"] = [step / 2.0], True
    out = {}
    for lane in lanes:
        runs = lane["runs"]
        if lane.get("off"):  # nothing to drift that way (a part without a weight; a weight at the plate's edge)
            continue
        if lane["what"] in HALVED:  # the half step ran after the first: in order of size (μ and ω keep the order run)
            runs.sort(key=lambda x: abs(x["step"]))
        row = ({"passed": lane["passed"], "failed": lane["failed"], "runs": runs} if runs else
               {"passed": None, "failed": None, "runs": [], "not measured": "budget"})
        if lane.get("cut"):  # the step the budget cut short: how far it got (no verdict)
            row["cut_short"] = lane["cut"]
        out.setdefault(lane["what"], []).append(row)
    return out


def _margin_text(what: str, rows: list) -> str:
    unit = {"omega": ("ω", lambda v: f"{100 * v:+.0f} %"), "mu": ("μ", lambda v: f"× {v:g}"),
            "jitter": ("ω jitter σ", lambda v: f"{100 * v:g} %"),
            "weight_x": ("weight x", lambda v: f"{1000 * v:+.2g} mm"),
            "weight_y": ("weight y", lambda v: f"{1000 * v:+.2g} mm")}[what]
    if rows and all(r.get("not measured") and not (r.get("cut_short") or {}).get("n") for r in rows):
        return unit[0], "not measured (the search's time budget was spent)"
    parts = []
    for r in rows:
        cut = r.get("cut_short")
        cut = (f"{unit[1](cut['step'])} cut short by the budget at {cut['successes']}/{cut['n']} of {cut['planned']} "
               "trials, no verdict") if cut and cut["n"] else ""
        if r.get("not measured"):
            parts.append("not measured (the search's time budget was spent" + (f"; {cut})" if cut else ")"))
            continue
        runs = ", ".join(f"{unit[1](x['step'])}: {x['successes']}/{x['n']}" for x in r["runs"])
        if r["failed"] is None:
            verdict = f"holds to {unit[1](r['passed'])} (the largest step tried)"
        elif r["passed"] is None:
            verdict = f"falls clearly below the goal at {unit[1](r['failed'])}"
        else:
            verdict = f"holds to {unit[1](r['passed'])}, not to {unit[1](r['failed'])}"
        parts.append(f"{verdict} ({runs}" + (f"; {cut})" if cut else ")"))
    return unit[0], "; ".join(parts)


def _draw(res, design, out: Path) -> list:
    """The drawing (:func:`drawing`) as ``out/drawing.svg`` and ``out/drawing.png``; returns their paths."""
    import matplotlib.pyplot as plt

    from ..viz.style import save_figure

    fig = drawing(res, design)
    paths = [save_figure(fig, out / f"drawing.{ext}", tight=True) for ext in ("svg", "png")]
    plt.close(fig)
    return paths


def drawing(res, design):
    """The design sheet's drawing of a found feeder (``res.feeder``) and its pocket (``design``, the
    :class:`~throwmap.design.cavity.CavityDesign` its config builds): the fed pose against the end wall with the
    CM and the lead weight in the arm's frame (cm), beside the part in its own frame with its side numbers, the
    weight's place and the CM. Returns the Figure."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon

    from ..system.pose import pose_against_wall
    from ..viz.capture import plot_capture
    from ..viz.style import side_colors
    from .family import side_endpoints

    f = res.feeder
    part = f.variant.part
    weight = f.variant.weight
    grams = "" if weight is None else _grams(weight.mass)
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 5), gridspec_kw={"width_ratios": [2.2, 1]})
    plot_capture(design, ax=ax, title=f"fed pose: side {f.side} against the end wall at L = {100 * f.X:.1f} cm")
    gap = design.numbers.get("end_gap_m", 0.0)
    pose = design.captured_pose or pose_against_wall(part, design.floor_y, design.length - gap, f.side)
    fed_cm = 100 * np.asarray(pose[:2])  # plot_capture marks the CM there with a dot
    fed_lead = None
    if weight is not None:  # the weight in the fed pose (the pose plot_capture draws)
        c, s_ = math.cos(pose[2]), math.sin(pose[2])
        d = np.asarray(weight.at) - np.asarray(part.com)
        fed_lead = fed_cm + 100 * np.array([c * d[0] - s_ * d[1], s_ * d[0] + c * d[1]])
        ax.plot(*fed_lead, "o", ms=LEAD_PT, mfc="#555", mec="k", zorder=5)
    V = np.asarray(part.vertices)
    colors = side_colors(len(V))
    bx.add_patch(Polygon(100 * V, closed=True, facecolor="#dde6f0", edgecolor="k", lw=1))
    centre = V.mean(axis=0)
    for k in range(len(V)):
        a, b = side_endpoints(part, k)
        bx.plot(100 * np.array([a[0], b[0]]), 100 * np.array([a[1], b[1]]), color=colors[k], lw=4 if k == f.side else 2)
        mid = 0.5 * (a + b)
        normal = np.array([b[1] - a[1], a[0] - b[0]]) / max(float(np.hypot(*(b - a))), 1e-12)
        normal *= 1.0 if np.dot(normal, mid - centre) >= 0 else -1.0  # outward: the number sits outside the plate
        offset = SIDE_LABEL_PT * normal
        bx.annotate(f"{k}" + (" (fed)" if k == f.side else ""), 100 * mid, xytext=tuple(offset),
                    textcoords="offset points", fontsize=9, ha="center", va="center",
                    bbox={"boxstyle": "round", "fc": "white", "ec": colors[k]})
    c = 100 * np.asarray(part.com)
    bx.plot(*c, "k+", ms=10, zorder=6)
    bx.set_aspect("equal")
    bx.set_xlabel("x (cm, part frame)\n" + _where(weight, c))
    bx.set_ylabel("y (cm)")
    bx.set_title("the part" + (" and its lead weight" if weight is not None else " (no weight)"))
    pad = 0.18 * float(np.ptp(100 * V))  # room for the side numbers outside the plate
    bx.set_xlim(100 * V[:, 0].min() - pad, 100 * V[:, 0].max() + pad)
    bx.set_ylim(100 * V[:, 1].min() - pad, 100 * V[:, 1].max() + pad)
    spans = [float(np.ptp(x.get_xlim())) / float(np.ptp(x.get_ylim())) for x in (ax, bx)]
    ax.get_gridspec().set_width_ratios(spans)  # each panel as wide as its drawing: no blank beside the arm
    fig.set_size_inches(min(max(3.6 * sum(spans) + 2.5, 8.0), 16.0), 5.0)
    fig.tight_layout(w_pad=2.0)
    # tight_layout measures the panels before their equal aspect shrinks them and can overlap them (a negative
    # space was measured): keep the part panel's axis labels clear of the arm panel
    fig.subplots_adjust(wspace=max(fig.subplotpars.wspace, 0.22))
    fig.canvas.draw()  # the final layout: labels are placed in points, clear of the side numbers and each other
    # the arm panel: its side numbers (plot_capture's texts), the fed CM's dot and the weight's mark
    busy = _texts(ax) + [_mark(ax, fed_cm, 2.5)]
    if fed_lead is not None:
        busy.append(_mark(ax, fed_lead, LEAD_PT / 2))
        busy.append(_free_label(ax, f"lead {grams}", fed_lead, 4.0, busy))
    _free_label(ax, "CM", fed_cm, 3.0, busy)
    # the part panel: its side numbers, the CM, the weight
    busy = _texts(bx) + [_mark(bx, c, 5.0)]
    if weight is not None:
        p = 100 * np.asarray(weight.at)
        bx.plot(*p, "o", ms=LEAD_PT, mfc="#555", mec="k", zorder=5)
        bx.plot([p[0], p[0]], [bx.get_ylim()[0], p[1]], ":", color="#555", lw=0.8)
        bx.plot([bx.get_xlim()[0], p[0]], [p[1], p[1]], ":", color="#555", lw=0.8)
        busy.append(_mark(bx, p, LEAD_PT / 2))
        busy.append(_free_label(bx, "lead", p, 4.0, busy))
    _free_label(bx, "CM", c, 5.0, busy)
    return fig


LEAD_PT = 8.0
"""The lead weight's mark, points across (a mark, not to scale: the weight is a point mass on the plate)."""
SIDE_LABEL_PT = 11.0
"""How far outside its side a side's number sits, points."""


def _grams(kg: float) -> str:
    """A mass as the sheet writes it everywhere: grams, one decimal."""
    return f"{1000 * kg:.1f} g"


def _where(weight, c) -> str:
    """The axis note of the part panel: the weight's mass and place and the CM, cm (part frame)."""
    where = f"CM ({c[0]:.2f}, {c[1]:.2f}) cm"
    if weight is None:
        return where
    p = 100 * np.asarray(weight.at)
    return f"lead {_grams(weight.mass)} at ({p[0]:.2f}, {p[1]:.2f}) cm; " + where


def _free_label(bx, text: str, at, r_pt: float, busy: list):
    """Annotate ``text`` ``r_pt`` points beyond the edge of its box from ``at`` (data), in the one of 8 directions
    whose box keeps farthest from the ``busy`` boxes (display ``(x0, y0, x1, y1)``: texts, marks, other labels)
    inside the panel; returns the label's box."""
    dpp = bx.figure.dpi / 72.0  # display pixels per point
    base = bx.transData.transform(at)
    label = bx.annotate(text, at, xytext=(0.0, 0.0), textcoords="offset points", fontsize=8, ha="center",
                        va="center", zorder=6, bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "none",
                                                     "alpha": 0.85})
    ext = label.get_window_extent(renderer=bx.figure.canvas.get_renderer())
    half = np.array([ext.width, ext.height]) / 2.0  # display pixels
    panel = bx.get_window_extent()
    best, best_score, best_box = None, -math.inf, None
    for k in range(8):
        u = np.array([math.cos(k * math.pi / 4 + math.pi / 2), math.sin(k * math.pi / 4 + math.pi / 2)])
        centre = base + dpp * r_pt * u + half * u  # a long label moves sideways by its half width
        box = (centre[0] - half[0], centre[1] - half[1], centre[0] + half[0], centre[1] + half[1])
        score = min((_gap(box, b) for b in busy), default=math.inf)
        if box[0] < panel.x0 or box[1] < panel.y0 or box[2] > panel.x1 or box[3] > panel.y1:
            score -= 1e6  # off the panel: only when nothing else is left
        if score > best_score + 1e-9:
            best, best_score, best_box = (centre - base) / dpp, score, box
    label.xyann = tuple(best)
    return best_box


def _gap(a, b) -> float:
    """The distance between two boxes ``(x0, y0, x1, y1)``, or minus the area they share when they overlap."""
    dx, dy = max(a[0] - b[2], b[0] - a[2]), max(a[1] - b[3], b[1] - a[3])
    if dx < 0 and dy < 0:
        return dx * dy * -1.0
    return float(np.hypot(max(dx, 0.0), max(dy, 0.0)))


def _mark(bx, at, r_pt: float) -> tuple:
    """The display box of a mark ``r_pt`` points in radius at ``at`` (data)."""
    x, y = bx.transData.transform(at)
    r = r_pt * bx.figure.dpi / 72.0
    return (x - r, y - r, x + r, y + r)


def _texts(bx) -> list:
    """The display boxes of the texts and annotations drawn in a panel."""
    r = bx.figure.canvas.get_renderer()
    return [tuple(t.get_window_extent(renderer=r).extents) for t in bx.texts]


def _viewer(cfg, seed: int, index: int, out: Path, title: str):
    from ..experiments.feed import Feed
    from ..viz.viewer import player_data, viewer_html, write_viewer

    trial, traj = Feed().replay(cfg, seed, index)
    if traj is None:
        return None, trial
    page = viewer_html(title=title, subtitle=f"trial {index} of the verification (seed {seed}), replayed: "
                                             f"{trial.values['throws']} throws, captured at throw "
                                             f"{trial.values['throws_to_capture']:g}", player=player_data(traj))
    return write_viewer(out / "fed_trial.html", page), trial


def _side_length(part, k: int) -> float:
    return float(part.length[k])


def _md_table(header, rows) -> str:
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def _html_table(header, rows) -> str:
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in r) + "</tr>" for r in rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _tail_note(ttc: dict, max_throws: int) -> str:
    """A warning when the slowest capture came near the throws allowed (a longer run may leave parts uncaught)."""
    if ttc.get("max", 0) > 0.8 * max_throws:
        return f" — the slowest used {ttc['max']:g} of the {max_throws} throws allowed"
    return ""


def _edge_rows(f, grid: dict) -> list:
    """A row saying so when the feeder's ω or h is at an end of the grid searched (a better one may lie beyond)."""
    out = []
    for name, value, values, unit, k in (("ω", f.omega, grid.get("omegas_rad_s"), "rad/s", 1.0),
                                         ("h", f.h, grid.get("hs_m"), "cm", 100.0)):
        if values and len(values) > 1 and (value <= min(values) + 1e-12 or value >= max(values) - 1e-12):
            out.append((f"{name} at the grid's edge", f"{k * value:.4g} {unit}, searched {k * min(values):.4g} to "
                                                     f"{k * max(values):.4g} {unit}: a better value may lie beyond"))
    return out


def write_sheet(res, out, *, margin_trials: int = 30, workers: int | None = None, budget_s: float = math.inf,
                progress=None):
    """Write the design sheet of the verified feeder ``res`` (a successful :class:`~throwmap.feeder.search.FeederSearch`)
    into ``out`` (see the module docstring); returns ``res`` with ``sheet`` holding the files written, the margins,
    throws to capture and failure modes. ``margin_trials`` 0 leaves the margins out; no margin step is started after
    ``budget_s`` seconds from the call (the drawing and the fed trial's replay count)."""
    from ..experiments.base import read_config
    from ..experiments.feed import Feed, build_design

    if not res.success or res.feeder is None:
        raise InvalidStateError("result", "has no verified feeder to draw (success is False)")
    t0 = time.perf_counter()
    out = Path(out)
    cfg = read_config(Feed(), (out / "feeder.toml").resolve())  # the runs store the part's absolute path: resumable from any cwd
    design = build_design(cfg)
    from ..experiments.stats import rerun_range
    from .family import side_endpoints

    f, v, r, e = res.feeder, res.verified, res.rerun, res.evidence
    workers = 0 if workers is None else workers
    files = {"config": str(out / "feeder.toml"), "part": str(out / "part.toml")}
    files.update({p.suffix[1:]: str(p) for p in _draw(res, design, out)})
    title = f"Feeder for {f.variant.part.name}: side {f.side}"
    page, replayed = None, None
    if v.get("first_success") is not None:
        page, replayed = _viewer(cfg, v["seed"], v["first_success"], out, title)
    if page is not None:
        files["viewer"] = str(page)
    marg = {}
    if margin_trials:
        import hashlib

        tag = hashlib.sha1((out / "feeder.toml").read_bytes()).hexdigest()[:10]  # a rerun that found another feeder
        marg = margins(cfg, out / "margins" / tag, trials=margin_trials, goal=res.assumptions.get("goal", 0.95),
                       workers=workers, budget_s=budget_s - (time.perf_counter() - t0), progress=progress)  # after the drawing
    both = [x for x in (v, r) if x]
    failures = {}
    for x in both:
        for k, n in x["failures"].items():
            failures[k] = failures.get(k, 0) + n
    ttc = v.get("throws_to_capture")
    part = f.variant.part
    nums = design.numbers
    wall_h = float(design.wall.height)
    rows_feeder = [
        ("part", part.name), ("part mass (with weight)", f"{1000 * part.mass:.1f} g"),
        ("lead weight", f.variant.label() + ("" if f.variant.side in (None, f.side) else
                                             f" (proposed for side {f.variant.side}; it feeds side {f.side})")), ("CM (part frame)", f"({100 * part.com[0]:.2f}, {100 * part.com[1]:.2f}) cm"),
        ("fed side", f"{f.side} (length {100 * _side_length(part, f.side):.2f} cm, from "
                     + " to ".join(f"({100 * p[0]:.2f}, {100 * p[1]:.2f})" for p in side_endpoints(part, f.side))
                     + " cm in the part's frame)"),
        ("throw", f"ω = {f.omega:.4g} rad/s nominal, ± {100 * cfg.noise.omega_rel:g} % per throw, recoil arm "
                  f"({math.degrees(cfg.noise.recoil):g}°, ζ = {cfg.noise.zeta:g})"),
        ("throw schedule", f"throw every time the part has settled; up to {cfg.max_throws} throws to capture, then "
                           f"{cfg.hold_throws} hold throws"),
        ("arm", f"surface h = {100 * f.h:.3g} cm from the joint axis, μ = {cfg.arm.mu:g} ± {100 * cfg.noise.mu_rel:g} %"),
        *_edge_rows(f, res.assumptions.get("grid", {})),
        ("end wall", f"at L = {100 * f.X:.1f} cm from the joint, {100 * wall_h:.1f} cm above the arm's surface, lined μ = {cfg.cavity.wall_mu:g}"),
        ("pocket", f"{100 * cfg.cavity.depth:.1f} cm deep, floor lined (μ {cfg.cavity.wall_mu:g}), lip "
                   f"{math.degrees(cfg.cavity.ramp_angle):.0f}°, floor side + {100 * cfg.cavity.clearance:.1f} cm"),
        ("drops", f"CM x in {list(cfg.x_range)} m, 2–10 cm above the arm, any pose"),
    ]
    rows_result = [
        (f"predicted (first arrival on the fed side, screened on the {f.model} model)", f"{100 * f.predicted:.1f} %"),
        ("verification", f"{v['successes']}/{v['n']} = {100 * v['rate']:.1f} %, Wilson 95 % [{100 * v['ci95'][0]:.1f}, "
                         f"{100 * v['ci95'][1]:.1f}] % (seed {v['seed']})"),
        ("independent rerun", f"{r['successes']}/{r['n']} = {100 * r['rate']:.1f} % (seed {r['seed']}), "
                              + ("inside the range a new run lands in after the verification"
                                 if r["successes"] <= rerun_range(v["successes"], v["n"], r["n"])[1]
                                 else "above the range a new run lands in after the verification")),
        ("verified (both runs, less the trials that chose it)",
         f"{e['successes']}/{e['n']} = {100 * e['successes'] / max(e['n'], 1):.1f} %, Wilson 95 % "
         f"[{100 * e['ci95'][0]:.1f}, {100 * e['ci95'][1]:.1f}] % (the verification's first {e['left_out']['n']} "
         f"trials, {e['left_out']['successes']} fed, chose the candidate and are left out)"),
        (f"a new run of {e['rerun95']['n']} trials, another seed", f"lands in {e['rerun95']['successes'][0]}–"
         f"{e['rerun95']['successes'][1]} fed ({100 * e['rerun95']['rate'][0]:.1f}–{100 * e['rerun95']['rate'][1]:.1f} "
         f"%) with 95 % probability: compare an independent check with this, not with the Wilson interval"),
        (f"throws to capture (the verification, seed {v['seed']})", "—" if not ttc else f"median {ttc['median']:g}, p90 {ttc['p90']:g}, max {ttc['max']:g}"
                              + _tail_note(ttc, cfg.max_throws)),
        ("failure modes (both runs)", (", ".join(f"{k} {n}" for k, n in sorted(failures.items())) or "none")
         + ("; refused:unconverged: the engine could not settle the trial (a half-step rerun disagreed by more than "
            "5 mm after two refinements), scored as not fed" if "refused:unconverged" in failures else "")),
    ]
    rows_margin = [_margin_text(k, rr) for k, rr in marg.items()]
    sheet = {"files": files, "margins": marg, "failures": failures, "throws_to_capture": ttc,
             "margin_trials": margin_trials, "wall_height_m": wall_h,
             "fed_trial": None if replayed is None else {"seed": v["seed"], "index": v["first_success"],
                                                         "replayed_ok": bool(replayed.success)}}
    md = [f"# {title}", "", "![drawing](drawing.svg)", "", "## The feeder", "", _md_table(("item", "value"), rows_feeder), "",
          "## Predicted and verified", "", _md_table(("item", "value"), rows_result), ""]
    if rows_margin:
        md += ["## Margins", "", f"Each step is {margin_trials} engine trials (seed 100) with one quantity drifted; "
               f"a step fails when clearly below {100 * res.assumptions.get('goal', 0.95):g} % fed (its Wilson 95 % "
               f"upper end under it: {margin_trials} trials cannot tell 95 % from 90 %) and holds otherwise.", "",
               _md_table(("quantity", "margin"), rows_margin), ""]
    md += ["## Assumptions", "", "```json", json.dumps(res.assumptions, indent=1, ensure_ascii=False), "```", ""]
    if page is not None:
        md += ["One fed trial, replayed: [fed_trial.html](fed_trial.html).", ""]
    files["markdown"] = str(atomic_write_text(out / "sheet.md", "\n".join(md)))
    body = [f"<h1>{html.escape(title)}</h1>", '<img src="drawing.svg" alt="drawing" style="max-width:100%">',
            "<h2>The feeder</h2>", _html_table(("item", "value"), rows_feeder), "<h2>Predicted and verified</h2>",
            _html_table(("item", "value"), rows_result)]
    if rows_margin:
        body += ["<h2>Margins</h2>", f"<p>Each step is {margin_trials} engine trials (seed 100) with one quantity "
                 f"drifted; a step fails when clearly below {100 * res.assumptions.get('goal', 0.95):g} % fed (its "
                 f"Wilson 95 % upper end under it) and holds otherwise.</p>",
                 _html_table(("quantity", "margin"), rows_margin)]
    body += ["<h2>Assumptions</h2>", f"<pre>{html.escape(json.dumps(res.assumptions, indent=1, ensure_ascii=False))}</pre>"]
    if page is not None:
        body.append('<p>One fed trial, replayed: <a href="fed_trial.html">fed_trial.html</a>.</p>')
    style = ("body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em}"
             "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #ccc;padding:4px 8px;text-align:left}")
    doc = (f"<!doctype html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title><style>{style}</style>"
           f"</head><body>{''.join(body)}</body></html>")
    files["html"] = str(atomic_write_text(out / "sheet.html", doc))
    dt = time.perf_counter() - t0  # the sheet's margins and drawing: part of the design's time
    res = dataclasses.replace(res, sheet=sheet, time_s=res.time_s + dt, stages_s={**res.stages_s, "sheet": dt})
    why = margin_refusal(marg, res.assumptions.get("goal", 0.95))
    if why:
        res = dataclasses.replace(res, success=False, reason=why)
    return res


REFUSE_WITHIN = 0.03
"""A verified feeder is refused when at ω(1 ± this) (the first margin step, one jitter σ) its success is below the
goal with 95 % confidence (the Wilson interval's upper end under the goal)."""


def margin_refusal(marg: dict, goal: float) -> str:
    """Why a feeder sits within :data:`REFUSE_WITHIN` of ω of losing its feed (``marg``: :func:`margins`), or ``""``.
    Only a step clearly below ``goal`` refuses: 30 trials cannot tell 95 % from 90 %, so a step that merely fails
    its 95 % is a margin reported, not a refusal."""
    for row in marg.get("omega", []):
        for run in row.get("runs", []):
            if abs(abs(run["step"]) - REFUSE_WITHIN) < 1e-9 and run["ci95"][1] < goal:
                return (f"verified, but within {100 * REFUSE_WITHIN:g} % of ω of losing its feed: at "
                        f"{drift_text(run['step'])} {run['successes']}/{run['n']} fed (Wilson 95 % up to "
                        f"{100 * run['ci95'][1]:.1f} % < {100 * goal:g} %)")
    return ""
