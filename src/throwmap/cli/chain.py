"""``throwmap chain …``: stochastic throw maps as Markov chains, checked against the Monte Carlo.

``throwmap chain throw``     one part, open loop at a fixed ω: the chain (ω jitter, μ per trial, realisation),
                             P(goal by k) against a Monte Carlo of the same model, the long-run distribution
``throwmap chain position``  the ``position`` experiment's closed loop as a chain, against a Monte Carlo run
                             of ``throwmap experiment position CONFIG --out DIR`` (its trials' ``throws``)
``throwmap chain assemble``  self-assembly's first low phase on a reduced pair state, from recorded engine
                             episodes (estimated on the even ones, checked on the odd ones)

Errors: one ``error: <field>: <reason>`` line, exit 2 (:mod:`throwmap.cli.options`). SI units.
"""

from __future__ import annotations

import glob
from pathlib import Path
from typing import Annotated

import typer

from ..budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS
from .options import (ForceOpt, MaxMemoryOpt, MaxTimeOpt, check_finite, check_output, figure_format, guard,
                      save_figure, stderr_line, stored_lines, to_json, write_text)
from .usage import ThrowmapGroup

__all__ = ["register", "chain_app"]

chain_app = typer.Typer(name="chain", cls=ThrowmapGroup, no_args_is_help=True, add_completion=False,
                        pretty_exceptions_enable=False,
                        help="Stochastic throw maps as Markov chains on cells: P(goal by throw k), absorption, "
                             "the long-run distribution; checked against the Monte Carlo's 95 % band.")
CellOpt = Annotated[float, typer.Option("--cell", help="Largest cell, m.")]
SamplesOpt = Annotated[int, typer.Option("--samples", help="Throws per cell (split in halves for the check).")]
MuNodesOpt = Annotated[int, typer.Option("--mu-nodes", help="μ nodes of the per-trial μ mixture.")]
SeedOpt = Annotated[int, typer.Option("--seed", help="Seed of the chain's throws (and the Monte Carlo's).")]
OutOpt = Annotated[Path | None, typer.Option("--out", help="Write the comparison as JSON here.")]
PlotOpt = Annotated[Path | None, typer.Option("--plot", help="Figure of P(goal by k) with the Monte Carlo points.")]
StatOpt = Annotated[Path | None, typer.Option("--plot-stationary", help="Figure of the long-run mass per side.")]


def _positive(value, field: str, integer: bool = False, minimum: int = 1, why: str = ""):
    from ..errors import InvalidStateError

    if integer:
        if value < minimum:
            raise InvalidStateError(field, f"must be an integer ≥ {minimum}{why}, got {value}")
        return value
    check_finite(value, field)
    if value <= 0:
        raise InvalidStateError(field, f"must be > 0, got {value}")
    return value


def _seconds_per_throw(step, part, arm, n: int = 32) -> float:
    """Seconds per throw of ``step``, measured on ``n`` rests spread over the first stable side (after a warm-up)."""
    import time

    import numpy as np

    from ..system.starts import start_interval

    k = part.stable_sides[0]
    lo, hi = start_interval(part, arm, k)
    x = np.linspace(lo, hi, n + 2)[1:-1] if np.isfinite(lo) and np.isfinite(hi) else np.zeros(n)
    side = np.full(n, k, dtype=np.int64)
    from ..rng import as_generator

    rng = as_generator(0)
    step(x[:2], side[:2], rng)
    t0 = time.perf_counter()
    step(x, side, rng)
    return (time.perf_counter() - t0) / n


def _emit(result: dict, out: Path | None) -> None:
    text = to_json(result)
    if out is not None:
        write_text(out, text + "\n", "out")
        typer.echo(f"wrote {out}")


CURVE_GAP_WARN = 0.05
"""A chain whose two independent halves' curves differ by more than this (probability) is reported as unconverged."""


def _report(cmp, check: dict) -> None:
    s = cmp.summary()
    typer.echo(f"{s['label']}: {s['trials']} trials, k = 0…{s['k_max']}: chain inside the Wilson 95 % band at "
               f"{100 * s['fraction_inside']:.1f} % of k (largest miss {100 * s['max_outside']:.2f} points; "
               f"sup |chain − MC| {100 * s['sup_abs_diff']:.2f} points)")
    typer.echo(f"  at k = {s['k_max']}: chain {100 * s['final']['chain']:.1f} %, Monte Carlo "
               f"{100 * s['final']['mc']:.1f} % [{100 * s['final']['band'][0]:.1f}, {100 * s['final']['band'][1]:.1f}]")
    typer.echo(f"  check: {check['n_cells']} cells ≤ {1000 * check['cell_m']:g} mm, {check['samples']} throws/cell "
               f"({check['throws']} throws); halves' rows TV max {check['tv_max']:.3f}, mean {check['tv_mean']:.3f}; "
               f"halves' curves differ by ≤ {100 * check.get('curve_gap', float('nan')):.2f} points")
    gap = check.get("curve_gap", 0.0)
    if gap > CURVE_GAP_WARN:
        typer.echo(f"warning: the chain is not converged: its two halves' P(goal by k) differ by up to "
                   f"{100 * gap:.1f} points (> {100 * CURVE_GAP_WARN:g}), so its agreement with the Monte Carlo is "
                   f"not evidence; use more --samples or a larger --cell", err=True)


@chain_app.command("throw")
def throw_cmd(
    part: Annotated[str, typer.Option("--part", help="Built-in part name or part file.")] = "triangle",
    h: Annotated[float, typer.Option("--h", help="Arm surface height, m.")] = -0.01,
    length: Annotated[float, typer.Option("--length", help="Arm length, m.")] = 0.60,
    mu: Annotated[float, typer.Option("--mu", help="Nominal arm μ.")] = 1.0,
    omega: Annotated[float, typer.Option("--omega", help="Nominal release rate, rad/s.")] = 3.0,
    model: Annotated[str, typer.Option("--model", help="An analytic model (rigid_body, paper, small_angle).")]
    = "rigid_body",
    omega_rel: Annotated[float, typer.Option("--omega-rel", help="ω jitter, relative σ per throw.")] = 0.03,
    mu_rel: Annotated[float, typer.Option("--mu-rel", help="μ spread, relative σ per trial.")] = 0.1,
    realisation: Annotated[str, typer.Option("--realisation", help="impulse or recoil (rigid_body).")] = "impulse",
    goal: Annotated[str, typer.Option("--goal", help="'off_end', 'behind_joint' or SIDE:LO:HI (m).")] = "off_end",
    cell: CellOpt = 0.005,
    samples: SamplesOpt = 32,
    mu_nodes: MuNodesOpt = 5,
    trials: Annotated[int, typer.Option("--trials", help="Monte Carlo trials (0: none).")] = 400,
    k_max: Annotated[int, typer.Option("--k-max", help="Throws compared.")] = 60,
    seed: SeedOpt = 0,
    out: OutOpt = None,
    plot: PlotOpt = None,
    plot_stationary: StatOpt = None,
    plot_quasi: Annotated[Path | None, typer.Option("--plot-quasi", help="Figure of the quasi-stationary mass "
                                                                         "per side (the nominal-μ chain).")] = None,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """One part thrown open loop at a fixed ω: the chain against a Monte Carlo of the same model."""
    import math

    import numpy as np

    from ..budget import cli_limits
    from ..errors import InvalidStateError
    from ..system.noise import Noise
    from ..stochastic.budget import count_cells, guard_chain
    from ..stochastic import Cells, GoalSet, ThrowStep, build_mixture, compare_curve, open_loop_trials
    from .options import part_and_arm

    with guard():
        _positive(cell, "cell")
        _positive(samples, "samples", True, 2, " (two halves)")
        _positive(k_max, "k_max", True)
        _positive(mu_nodes, "mu_nodes", True)
        _positive(omega, "omega")
        if trials < 0:
            raise InvalidStateError("trials", f"must be an integer ≥ 0 (0: no Monte Carlo), got {trials}")
        limits = cli_limits(max_memory, max_time, force)
        fmt = figure_format(plot, "plot")
        if out is not None:
            check_output(out, "out")
        fmt_s = figure_format(plot_stationary, "plot_stationary")
        fmt_q = figure_format(plot_quasi, "plot_quasi")
        from ..models import get_model

        if get_model(model).features.pose:
            raise InvalidStateError("model", f"{model!r} keeps the part's pose between throws; the chain is on rests "
                                             f"(x, side): use an analytic model (rigid_body, paper, small_angle)")
        p, arm = part_and_arm(part, h, None, length, mu)
        noise = Noise(omega_rel=omega_rel, mu_rel=mu_rel, realisation=realisation)
        if goal in ("off_end", "behind_joint"):
            gs = GoalSet(label=goal)
        else:
            try:
                s, lo, hi = goal.split(":")
                s, lo, hi = int(s), float(lo), float(hi)
            except ValueError:
                raise InvalidStateError("goal", f"must be off_end, behind_joint or SIDE:LO:HI, got {goal!r}") from None
            if s not in p.stable_sides:
                raise InvalidStateError("goal", f"side {s} is not a stable side of {p.name} (its stable sides: "
                                                f"{', '.join(map(str, p.stable_sides))})")
            if math.isnan(lo) or math.isnan(hi) or not lo < hi:
                raise InvalidStateError("goal", f"needs LO < HI (m), got {lo:g} and {hi:g}")
            gs = GoalSet(side=s, lo=lo, hi=hi)
        step = ThrowStep(p, arm, omega, model, noise)
        n_cells = count_cells(p, arm, cell, gs.breaks)
        n_mu = 1 if noise.mu_range is None and (noise.mu_rel == 0 or math.isinf(arm.mu)) else mu_nodes
        guard_chain(n_cells=n_cells, n_labels=len(step.labels), samples=samples, n_mu=n_mu, k_max=k_max,
                    trials=trials, timer=lambda: _seconds_per_throw(step, p, arm), limits=limits)
        cells = Cells.on_arm(p, arm, cell, breaks=gs.breaks)
        init = np.ones(cells.n)
        mix, builds = build_mixture(cells, step, samples=samples, rng=seed, n_mu=mu_nodes, initial=init,
                                    meta={"kind": "open_loop", "omega": omega, "model": model})
        mask = gs.mask(mix.chains[0])
        curve = mix.p_goal_by(k_max, mask, init)
        check = dict(mix.meta["check"], curve_gap=max(b.curve_gap(k_max, mask, init) for b in builds))
        st = mix.stationary(init)
        result = {"chain": {"cells": cells.n, "check": check, "mu_nodes": mix.meta["mu_nodes"],
                            "p_goal_by": curve.tolist(), "goal": gs.to_dict(),
                            "absorbed": mix.absorption_of(init),
                            "stationary": {"on_arm": st.on_arm, "absorbed": st.absorbed(), "converged": st.converged}}}
        typer.echo(f"chain: {cells.n} cells, P(goal by {k_max}) = {100 * curve[-1]:.1f} %; long run: "
                   + ", ".join([f"{100 * st.on_arm:.1f} % on the arm"]
                               + [f"{k} {100 * v:.1f} %" for k, v in st.absorbed().items() if v > 5e-4]))
        if trials > 0:
            hits = open_loop_trials(step, cells, init, gs, n=trials, k_max=k_max, rng=seed + 1)
            cmp = compare_curve(curve, hits, k_max, label=f"{p.name}, ω = {omega:g} rad/s ({model}), goal "
                                                           f"{goal}", meta={"check": check})
            _report(cmp, check)
            result["comparison"] = cmp.to_dict()
            if plot is not None:
                save_figure(cmp.plot(), plot, fmt, "plot")
                typer.echo(f"wrote {plot}")
        if plot_stationary is not None:
            save_figure(st.plot(title=f"long run at ω = {omega:g} rad/s ({model}), uniform start"),
                        plot_stationary, fmt_s, "plot_stationary")
            typer.echo(f"wrote {plot_stationary}")
        q = mix.chains[len(mix.chains) // 2].quasi_stationary()  # the median μ node
        result["chain"]["quasi_stationary"] = {"rate": q.rate, "per_side": {k: float(v[2].sum())
                                                                              for k, v in q.per_side().items()}}
        typer.echo(f"quasi-stationary (μ = {mix.meta['mu_nodes'][len(mix.chains) // 2]:.3g}): a part still moving "
                   f"on the arm stays another throw with probability {q.rate:.4f}; by side "
                   + ", ".join(f"{k}: {100 * float(v[2].sum()):.1f} %" for k, v in q.per_side().items()))
        if plot_quasi is not None:
            save_figure(q.plot(title=f"quasi-stationary (not yet absorbed), ω = {omega:g} rad/s ({model})"), plot_quasi, fmt_q, "plot_quasi")
            typer.echo(f"wrote {plot_quasi}")
        _emit(result, out)


@chain_app.command("position")
def position_cmd(
    trials: Annotated[Path, typer.Argument(help="A Monte Carlo run directory (throwmap experiment position … --out).")],
    config: Annotated[Path | None, typer.Argument(help="The run's config (.toml/.json; default: the run's own).")]
    = None,
    initial: Annotated[Path | None, typer.Option("--initial", help="Take the drops from this run directory "
                                                                  "instead (an independent start distribution).")]
    = None,
    cell: CellOpt = 0.005,
    samples: SamplesOpt = 64,
    mu_nodes: MuNodesOpt = 5,
    seed: SeedOpt = 0,
    out: OutOpt = None,
    plot: PlotOpt = None,
    plot_stationary: StatOpt = None,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """The ``position`` experiment's closed loop as a chain against the run's trials (their ``throws``)."""
    import json

    from ..budget import cli_limits
    from ..experiments.base import config_of, read_config
    from ..experiments.registry import get_experiment
    from ..stochastic import compare_curve
    from ..stochastic.budget import count_cells, guard_chain
    from ..stochastic.experiments import position_chain, position_hits, position_initial, position_step, read_trials

    with guard():
        _positive(cell, "cell")
        _positive(samples, "samples", True, 2, " (two halves)")
        _positive(mu_nodes, "mu_nodes", True)
        limits = cli_limits(max_memory, max_time, force)
        fmt = figure_format(plot, "plot")
        if out is not None:
            check_output(out, "out")
        fmt_s = figure_format(plot_stationary, "plot_stationary")
        exp = get_experiment("position")
        if config is not None:
            cfg = read_config(exp, config)
        else:
            from ..errors import InvalidStateError

            meta = Path(trials) / "run.json"
            if not meta.is_file():
                raise InvalidStateError("trials", f"no run.json in {trials} (a run directory of 'throwmap experiment "
                                                  f"position … --out DIR', or give the config)")
            run = json.loads(meta.read_text(encoding="utf-8"))
            if run.get("experiment") not in (None, "position"):
                raise InvalidStateError("trials", f"{trials} is a run of {run.get('experiment')!r}, not 'position'")
            cfg = config_of(exp, run.get("config"))
        rows = read_trials(trials)
        hits = position_hits(rows)
        k_max = max(1, int(hits.max()))
        part, arm, step, breaks = position_step(cfg)
        guard_chain(n_cells=count_cells(part, arm, cell, breaks), n_labels=len(step.labels), samples=samples,
                    n_mu=mu_nodes, k_max=k_max, trials=0, timer=lambda: _seconds_per_throw(step, part, arm), limits=limits)
        mix, builds = position_chain(cfg, cell=cell, samples=samples, n_mu=mu_nodes, rng=seed)
        init = position_initial(mix.cells, read_trials(initial) if initial is not None else rows)
        curve = mix.p_goal_by(k_max, "stop:goal", init)
        check = dict(mix.meta["check"],
                     curve_gap=max(b.curve_gap(k_max, "stop:goal", init) for b in builds))
        sn = cfg.sensors
        errs = f", sensor errors fp {sn.false_positive:g} / fn {sn.false_negative:g}" if sn.false_positive or \
            sn.false_negative else ""
        cmp = compare_curve(curve, hits, k_max, label=f"position ({cfg.model}, {cfg.noise.realisation}, {cfg.controller} "
                                                         f"controller{errs})",
                            meta={"check": check, "mu_nodes": mix.meta["mu_nodes"],
                                  "initial": str(initial or trials)})
        _report(cmp, check)
        from ..experiments.stats import mean_interval, wilson_interval

        ab = mix.absorption_of(init)
        p_reach, mean_chain = mix.reach("stop:goal", init)
        mc_mean, mc_lo, mc_hi = mean_interval(hits[hits >= 0])
        half = 0.5 * (mc_hi - mc_lo)
        k, n_mc = int((hits >= 0).sum()), int(hits.size)
        p_lo, p_hi = wilson_interval(k, n_mc)
        typer.echo(f"  throws of a success: chain mean {mean_chain:.2f}, Monte Carlo mean {mc_mean:.2f} ± {half:.2f} "
                   f"(95 %); P(success) chain {100 * p_reach:.1f} %, Monte Carlo {100 * k / max(n_mc, 1):.1f} % "
                   f"[{100 * p_lo:.1f}, {100 * p_hi:.1f}] (Wilson 95 %)")
        on_arm = sum(v for k, v in ab.items() if k.startswith("side "))  # mass the chain never absorbs
        typer.echo("  chain's end states: " + ", ".join([f"{k} {100 * v:.1f} %" for k, v in ab.items() if v > 5e-4
                                                        and not k.startswith("side ")]
                                                       + ([f"never absorbed (cycling on the arm) {100 * on_arm:.1f} %"]
                                                          if on_arm > 5e-4 else [])))
        if plot is not None:
            save_figure(cmp.plot(), plot, fmt, "plot")
            typer.echo(f"wrote {plot}")
        if plot_stationary is not None:
            st = mix.stationary(init)
            save_figure(st.plot(title=f"position ({cfg.model}): long-run mass from the drops"), plot_stationary,
                        fmt_s, "plot_stationary")
            typer.echo(f"wrote {plot_stationary}")
        _emit(dict(cmp.to_dict(), absorbed=ab, mean_throws={"chain": mean_chain, "mc": mc_mean, "mc_half_width_95": half},
                   p_success={"chain": p_reach, "mc": k / n_mc if n_mc else None, "mc_ci95": [p_lo, p_hi]}), out)


@chain_app.command("assemble")
def assemble_cmd(
    episodes: Annotated[Path, typer.Argument(help="Recorded episodes (JSON lines; --record adds to it).")],
    record: Annotated[int, typer.Option("--record", help="Record episodes 0…N−1 of --seed first (engine; resumes).")]
    = 0,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the recorded run.")] = 0,
    bin_m: Annotated[float, typer.Option("--bin", help="Bin of a's CM abscissa, m.")] = 0.02,
    estimate_on: Annotated[str, typer.Option("--estimate-on", help="'even' or 'odd' episodes estimate the chain; "
                                                                   "the others check it.")] = "even",
    out: OutOpt = None,
    plot: PlotOpt = None,
) -> None:
    """Self-assembly's first low phase as a chain on a reduced pair state, from half the episodes, against the rest."""
    from ..errors import InvalidStateError
    from ..experiments.assemble import AssembleConfig, _setup
    from ..stochastic import compare_curve
    from ..stochastic.assembly import (low_phase_chain, low_phase_hits, low_phase_sequences, read_episodes,
                                       record_episodes)

    with guard():
        _positive(bin_m, "bin")
        fmt = figure_format(plot, "plot")
        if out is not None:
            check_output(out, "out")
        if record > 0:
            check_output(episodes, "episodes")
            try:
                rows = record_episodes(episodes, seed, record)
            except KeyboardInterrupt:
                kept = stored_lines(Path(episodes).parent, glob.escape(Path(episodes).name))
                stderr_line(f"interrupted: {kept} episode(s) "
                            f"stored in {str(episodes)!r}; the same command resumes from them")
                raise typer.Exit(130) from None
        elif not Path(episodes).is_file():
            raise InvalidStateError("episodes", f"no file {episodes} (record some with --record N)")
        else:
            rows = read_episodes(episodes)
        seeds = sorted({r["seed"] for r in rows})
        if len(seeds) > 1:
            raise InvalidStateError("episodes", f"{str(episodes)!r} holds episodes of several seeds "
                                                f"({', '.join(map(str, seeds))}): keep one seed per file")
        part, arm, _ = _setup(AssembleConfig())
        if estimate_on not in ("even", "odd"):
            raise InvalidStateError("estimate_on", f"must be 'even' or 'odd', got {estimate_on!r}")
        par = 0 if estimate_on == "even" else 1
        est = [r for r in rows if r["index"] % 2 == par]
        test = [r for r in rows if r["index"] % 2 != par]
        if not est or not test:
            raise InvalidStateError("episodes", f"need even and odd episodes, got {len(est)} and {len(test)}")
        seq_est = low_phase_sequences(est, part, length=arm.length, h=arm.h, bin=bin_m)
        seq_test = low_phase_sequences(test, part, length=arm.length, h=arm.h, bin=bin_m)
        chain = low_phase_chain(seq_est)
        hits = low_phase_hits(seq_test)
        k_max = max(1, int(hits.max()))
        curve = chain.p_goal_by(k_max, ["assembled"])
        cmp = compare_curve(curve, hits, k_max, label=f"self-assembly, first low phase (chain from the {estimate_on} "
                                                      f"episodes)",
                            meta={"check": dict(chain.meta, states=chain.n_cells, bin_m=bin_m,
                                                test_episodes=len(seq_test))})
        s = cmp.summary()
        typer.echo(f"chain: {chain.n_cells} reduced states from {chain.meta['transitions']} low throws of "
                   f"{chain.meta['episodes']} episodes; test: {len(seq_test)} episodes reaching the low phase")
        typer.echo(f"{s['label']}: k = 0…{s['k_max']}: chain inside the Wilson 95 % band at "
                   f"{100 * s['fraction_inside']:.1f} % of k (largest miss {100 * s['max_outside']:.2f} points; "
                   f"sup |chain − MC| {100 * s['sup_abs_diff']:.2f} points); at k = {s['k_max']}: chain "
                   f"{100 * s['final']['chain']:.1f} %, episodes {100 * s['final']['mc']:.1f} % "
                   f"[{100 * s['final']['band'][0]:.1f}, {100 * s['final']['band'][1]:.1f}]")
        if plot is not None:
            save_figure(cmp.plot(), plot, fmt, "plot")
            typer.echo(f"wrote {plot}")
        _emit(dict(cmp.to_dict(), states=list(chain.labels)), out)


def register(app: typer.Typer) -> None:
    app.add_typer(chain_app, name="chain")
