"""``throwmap experiment``: every Monte Carlo experiment behind one contract.

::

    throwmap experiment --list
    throwmap experiment NAME [CONFIG] --n N --seed S [--workers W] [--json] [--out DIR]
                        [--no-resume] [--plot FILE] [--max-time S] [--max-memory GB] [--force]

A thin shell over :func:`throwmap.experiments.run_experiment`. ``CONFIG`` is a
``.toml``/``.json`` file validated by the experiment's config type (omitted: the built-in
example). With ``--json`` stdout carries exactly one JSON object (at least ``n``,
``successes``, ``success_rate``, ``ci95`` [low, high], ``failures`` by kind, ``seed``,
``parameters``); without it a table. ``--out DIR`` keeps the trials (``trials.jsonl``
line by line, then ``result.json`` and ``trials.parquet``) and resumes an interrupted run.
A progress bar goes to stderr when it is a terminal. Errors: one ``error: <field>: <reason>``
line on stderr, exit 2.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated

import typer

from ..budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, cli_limits
from ..errors import InvalidStateError
from .options import (ForceOpt, progress_bar, JsonOpt, MaxMemoryOpt, MaxTimeOpt, check_out_dir, figure_format, guard, save_figure,
                      interrupted_line, stderr_line, strict_int, to_json)

__all__ = ["register", "experiment_cmd"]


def _setting(p: dict) -> str:
    """One line naming what a result is about, from its ``parameters``: the part, the side fed, ω, the arm and the
    fixtures (SI units), each only where the experiment states it."""
    def num(v):
        return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)

    bits = []
    if isinstance(p.get("part"), str):
        bits.append(f"part {p['part']}")
    if num(p.get("target_side")):
        bits.append(f"side {p['target_side']} wanted")
    if num(p.get("omega_rad_s")):
        bits.append(f"ω = {p['omega_rad_s']:.4g} rad/s")
    arm = [f"h = {p['h_m']:.4g} m"] if num(p.get("h_m")) else []
    arm += [f"length {p['length_m']:.4g} m"] if num(p.get("length_m")) else []
    arm += [f"μ = {p['mu']:.3g}"] if num(p.get("mu")) else []
    if arm:
        bits.append("arm " + ", ".join(arm))
    noise = p.get("noise")
    thrown = num(p.get("omega_rad_s"))  # an experiment that throws (settle only drops the part)
    if thrown and isinstance(noise, dict) and isinstance(noise.get("realisation"), str):
        jitter = noise.get("omega_rel")
        bits.append(f"{noise['realisation']} throw" + (f", ω jitter {100 * jitter:.3g} %" if num(jitter) and jitter else ""))
    fixtures = []
    cavity, wall = p.get("cavity"), p.get("wall")
    if isinstance(cavity, dict):
        numbers = cavity.get("numbers") or {}
        fixtures.append("cavity" + (f" (end wall at {numbers['L_m']:.4g} m, {100 * numbers['depth_m']:.3g} cm deep)"
                                    if num(numbers.get("L_m")) and num(numbers.get("depth_m")) else ""))
    if isinstance(wall, dict):
        h = wall.get("height_m")
        fixtures.append("end wall" + (f" {h:.3g} m high" if num(h) else ""))
    if bits:
        bits.append("fixtures: " + (", ".join(fixtures) if fixtures else "none"))
    return "; ".join(bits)


def _table(result) -> None:
    """The result as a Rich table on stdout, captioned with the part, ω, the arm and the fixtures."""
    from rich.console import Console
    from rich.table import Table

    lo, hi = result.ci95
    rate = "n/a" if math.isnan(result.success_rate) else f"{100 * result.success_rate:.1f} %"
    t = Table(title=f"experiment {result.name} — seed {result.seed}, {result.n} trials"
                    + ("" if result.complete else f" of {result.planned} (incomplete)"))
    t.add_column("outcome")
    t.add_column("trials", justify="right")
    t.add_column("fraction", justify="right")
    t.add_column("Wilson 95 %", justify="right")
    t.add_row("success", str(result.successes), rate, f"[{100 * lo:.1f}, {100 * hi:.1f}] %")
    from ..experiments.stats import wilson_interval

    for kind, c in result.failures.items():
        a, b = wilson_interval(c, result.n)
        t.add_row(kind, str(c), f"{100 * c / result.n:.1f} %", f"[{100 * a:.1f}, {100 * b:.1f}] %")
    console = Console()
    setting = _setting(result.parameters or {})
    if setting:
        from rich.markup import escape

        console.print(escape(setting), soft_wrap=True)
    console.print(t)
    console.print(f"{result.elapsed_s:.3g} s on {result.workers} worker(s)"
                  + (f", {result.resumed} trials resumed" if result.resumed else ""))


def experiment_cmd(
    name: Annotated[str | None, typer.Argument(help="The experiment (see --list).", show_default=False)] = None,
    config: Annotated[Path | None, typer.Argument(help="A .toml/.json config file (default: the built-in example).",
                                                  show_default=False)] = None,
    n: Annotated[int, typer.Option("--n", parser=strict_int, metavar="INTEGER", help="Number of trials.")] = 100,
    seed: Annotated[int, typer.Option("--seed", parser=strict_int, metavar="INTEGER",
                                      help="Seed of the run (trial i uses SeedSequence(seed).spawn(n)\\[i]).")] = 0,
    workers: Annotated[int, typer.Option("--workers", parser=strict_int, metavar="INTEGER",
                                         help="Processes (0: all cores).")] = 0,
    as_json: JsonOpt = False,
    out: Annotated[Path | None, typer.Option("--out", help="Directory keeping the trials (trials.jsonl, "
                                                           "result.json, trials.parquet); a rerun resumes.")] = None,
    resume: Annotated[bool, typer.Option("--resume/--no-resume", help="Reuse the trials stored in --out.")] = True,
    plot: Annotated[Path | None, typer.Option("--plot", help="Write a figure of the outcomes with the success "
                                                             "rate's interval (e.g. settle.png).")] = None,
    list_: Annotated[bool, typer.Option("--list", help="List the experiments and exit.")] = False,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Run a Monte Carlo experiment: success rate with its Wilson 95 % interval, failures by kind."""
    from ..experiments import experiment_names, get_experiment
    from ..experiments.base import read_config
    from ..experiments.runner import run_experiment

    with guard():
        if list_ or name == "list":
            names = experiment_names()
            if as_json:
                typer.echo(to_json({k: get_experiment(k).summary for k in names}))
            else:
                width = max(len(k) for k in names) + 2
                for k in names:
                    typer.echo(f"{k:<{width}}{get_experiment(k).summary}")
            return
        if name is None:
            raise InvalidStateError("name", f"give an experiment (choose from {', '.join(experiment_names())}) or --list")
        exp = get_experiment(name)
        cfg = read_config(exp, config) if config is not None else None
        limits = cli_limits(max_memory, max_time, force)
        if out is not None:
            check_out_dir(out)
        fmt = figure_format(plot, "plot")
        try:
            with progress_bar(exp.name) as update:
                result = run_experiment(exp, cfg, n=n, seed=seed, workers=workers, out=out, resume=resume,
                                        progress=update, limits=limits)
            if plot is not None:
                save_figure(result.plot(), plot, fmt, "plot")
            if as_json:
                typer.echo(to_json(result.to_json()))
            else:
                _table(result)
        except KeyboardInterrupt:
            stderr_line(interrupted_line(out, "trial"))
            raise typer.Exit(130) from None


def register(app: typer.Typer) -> None:
    """Add the ``experiment`` command to ``app``."""
    app.command("experiment")(experiment_cmd)
