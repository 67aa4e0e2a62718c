"""The makers of ``throwmap reproduce``'s figures: each calls the library function that computes the analogue and
the :mod:`throwmap.viz` function that draws it, writes the figure (atomically) and returns what the report quotes.

Every maker has the signature ``maker(path, size, ctx) -> dict`` (``path`` the PNG to write, ``size`` a
:class:`~throwmap.reproduce.plan.Size`, ``ctx`` a dict shared by the makers of one run, e.g. the assembly episode
that Figs. 15 and 16 both draw) and returns ``{"numbers": {...}, "parameters": {...}}`` in SI units.
"""

from __future__ import annotations

import math

__all__ = ["MAKERS"]

OMEGA = 4.0
"""Release rate of Figs. 2 and 5 (rad/s), the demo's."""


def _canonical():
    from ..system.arm import Arm
    from ..system.catalogue import triangle_30_60_90

    return triangle_30_60_90(0.17), Arm(h=-0.01)


def _save(fig, path):
    import matplotlib.pyplot as plt

    from ..viz.style import save_figure

    save_figure(fig, path)
    plt.close(fig)


def throw_map(path, size, ctx) -> dict:
    from ..throws.samples import throw_map_samples

    part, arm = _canonical()
    s = throw_map_samples(part, arm, OMEGA, model="paper", x_max=0.6)
    _save(s.plot(compact=True), path)
    return {"numbers": {}, "parameters": {"part": part.name, "h_m": arm.h, "omega_rad_s": OMEGA, "model": "paper",
                                          "x_max_m": 0.6}}


def funnels(path, size, ctx) -> dict:
    from ..analysis import funnels as compute_funnels
    from ..viz.funnels import plot_funnel_graph

    part, arm = _canonical()
    goal = "0:0.50-0.90,1:0.50-0.90,2:0.50-0.90"
    graph = compute_funnels(part, arm, [3.0, 4.0], "rigid_body", goal=goal, grid=400, x_max=1.0, rng=0)
    _save(plot_funnel_graph(graph), path)
    return {"numbers": {"order": [graph.funnels[i].name for i in graph.order],
                        "mouth_fractions": {f.name: f.mouth_fraction for f in graph.funnels}},
            "parameters": {"omegas_rad_s": [3.0, 4.0], "goal": goal, "grid_per_side": 400, "x_max_m": 1.0,
                           "model": "rigid_body"}}


def limit_set(path, size, ctx) -> dict:
    from ..analysis import critical_points, limit_set as compute_limit_set
    from ..analysis.orbits import orbit_on_attractor
    from ..viz.limit_set import plot_limit_set

    part, arm = _canonical()
    crit = critical_points(part, arm, OMEGA, "rigid_body", x_max=0.6)
    lim = compute_limit_set(part, arm, OMEGA, "rigid_body", x_max=0.6, rng=0)
    orbit = orbit_on_attractor(part, arm, OMEGA, "rigid_body", lim)
    _save(plot_limit_set(lim, critical=crit, orbit=orbit), path)
    cp = crit.to_dict()
    return {"numbers": {"r_m": cp["r_m"], "l_m": cp["l_m"], "kind": lim.kind, "unique": lim.unique,
                        "bands_m": [[s, lo, hi] for a in lim.attractors for s, lo, hi in a.bands]},
            "parameters": {"omega_rad_s": OMEGA, "model": "rigid_body", "x_max_m": 0.6, "h_m": arm.h}}


def position_episode(path, size, ctx) -> dict:
    from ..experiments import get_experiment
    from ..experiments.base import config_of

    exp = get_experiment("position")
    cfg = config_of(exp)
    for index in range(10):
        ep = exp.episode(cfg, index, 0)
        if ep is not None and ep.success:
            break
    if ep is None:
        raise RuntimeError("no drop came to rest in trials 0…9 of seed 0")
    _save(ep.plot(), path)
    return {"numbers": {"trial": index, "seed": 0, "success": ep.success, "throws": ep.throws,
                        "switches": ep.switches}, "parameters": exp.parameters(cfg)}


def design(path, size, ctx) -> dict:
    from ..design import examples as ex
    from ..design.targets import Separation

    result, fd = ex.run_feeder_design(engine=size.engine)
    sep = Separation(fd.target_side, fd.separation_x, fd.separation_margin)
    _save(result.plot(separation=sep), path)
    return {"numbers": {"success": bool(result.success), "r_exact_m": {str(k): v for k, v in fd.r.items()},
                        "r_engine_m": ({str(k): v for k, v in fd.engine_r.items()} if fd.engine_r else None),
                        "target_side": fd.target_side},
            "parameters": {"arm": {"h_m": fd.arm.h, "length_m": fd.arm.length, "mu": fd.arm.mu}}}


def capture(path, size, ctx) -> dict:
    from ..design.cavity import evaluate_cavity
    from ..experiments import get_experiment
    from ..experiments.base import config_of
    from ..experiments.feed import build_design

    cfg = config_of(get_experiment("feed"))
    d = evaluate_cavity(build_design(cfg), verify=True)
    _save(d.plot(), path)
    doc = d.to_dict()
    out = {"numbers": {"success": bool(d.success)}, "parameters": {k: doc[k] for k in list(doc)[:12]}}
    if not d.success:
        out["failure"] = str(getattr(d, "message", "") or doc.get("message", "") or "no engine capture")
    return out


def lean(path, size, ctx) -> dict:
    from ..statics import edge_frame_cm, lean_free_beta
    from ..statics.figures import lean_data
    from ..statics.tables import lean_table

    part, _ = _canonical()
    alpha = math.radians(-10.0)
    _save(lean_data(part, alpha=alpha, beta_show=0.5, mu_show=2.0).plot(), path)
    a, b, _ = edge_frame_cm(part)
    t = lean_table(part, n=size.lean_n, seed=0, engine=size.engine)
    return {"numbers": {"beta_star_rad": {"mu=1": lean_free_beta(a, b, alpha, 1.0),
                                          "mu=2": lean_free_beta(a, b, alpha, 2.0)},
                        "table": t.lines()},
            "parameters": {"alpha_rad": alpha, "wall_mu": 0.0, "random_leans": size.lean_n}}


def partial(path, size, ctx) -> dict:
    from ..statics.figures import partial_data
    from ..statics.tables import partial_table

    part, _ = _canonical()
    alpha = math.radians(-10.0)
    _save(partial_data(part, alpha=alpha, gamma_show=math.radians(-15), mu_show=1.0).plot(), path)
    rows = partial_table(part, alpha_deg=-10.0, mu=1.0, engine=size.engine).rows
    return {"numbers": {"mu_needed_max": max(r[1] for r in rows),
                        "rows": [[g, need, lp, stayed] for g, need, lp, stayed, _, _ in rows]},
            "parameters": {"alpha_rad": alpha, "arm_mu": 1.0, "wall_mu": 0.0, "part_mu": 0.0}}


def _episode(ctx):
    from ..experiments.assemble_episode import first_success

    if "assembly" not in ctx:
        ctx["assembly"] = first_success(None, 1, max_tries=10)
    return ctx["assembly"]


def assembly_episode(path, size, ctx) -> dict:
    ep = _episode(ctx)
    _save(ep.plot(), path)
    return {"numbers": ep.summary(), "parameters": {"experiment": "assemble (built-in config)", "seed": ep.seed,
                                                    "index": ep.index}}


def assembly_snapshots(path, size, ctx) -> dict:
    ep = _episode(ctx)
    _save(ep.plot_snapshots(), path)
    shots = [[label, int(ep.throw_no[r])] for label, r in ep.snapshot_runs()]
    drawn = ", ".join(f"{label} (throw {k})" for label, k in shots) or "no snapshot"
    return {"numbers": {"snapshots": shots}, "parameters": {"seed": ep.seed, "index": ep.index},
            "caption": f"The same trial, {len(shots)} panel{'s' if len(shots) != 1 else ''}: the pair {drawn}."}


MAKERS = {"throw_map": throw_map, "funnels": funnels, "limit_set": limit_set, "position_episode": position_episode,
          "design": design, "capture": capture, "lean": lean, "partial": partial,
          "assembly_episode": assembly_episode, "assembly_snapshots": assembly_snapshots}
"""Maker functions by the name :class:`~throwmap.reproduce.plan.FigureSpec` gives."""
