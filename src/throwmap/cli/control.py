"""``throwmap control …``: feedback throwing figures and summaries (paper Sec. IV-A, Fig. 7).

A thin shell over :mod:`throwmap.control` and the ``position`` experiment
(:mod:`throwmap.experiments.position`), every command taking the experiment's CONFIG
(``.toml``/``.json``; omitted: the built-in example):

``throwmap control episode [CONFIG] --index I --seed S --plot FILE``   one trial's episode (Fig. 7 analogue)
``throwmap control fan [CONFIG] --n N --seed S --plot FILE``           N episodes overlaid
``throwmap control tradeoff [CONFIG] --eps 0.002,0.005,0.01 --n N``    throws and success against ε
``throwmap control summary DIR``                                       throws to success of a kept run

Errors: one ``error: <field>: <reason>`` line on stderr, exit 2. SI units in JSON.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import typer

from ..errors import InvalidStateError
from .options import JsonOpt, figure_format, guard, parse_floats, save_figure, strict_int, to_json
from .usage import ThrowmapGroup

__all__ = ["register", "control_app"]

control_app = typer.Typer(name="control", cls=ThrowmapGroup, no_args_is_help=True, add_completion=False,
                          pretty_exceptions_enable=False,
                          help="Feedback throwing to a chosen rest (paper Sec. IV-A): episodes, fans, the ε "
                               "trade-off, summaries of `experiment position` runs.")

ConfigArg = Annotated[Path | None, typer.Argument(help="A `position` config (.toml/.json; default: built-in).",
                                                  show_default=False)]
SeedOpt = Annotated[int, typer.Option("--seed", parser=strict_int, metavar="INTEGER", help="Run seed.")]
PlotOpt = Annotated[Path | None, typer.Option("--plot", help="Write the figure here (e.g. episode.png).")]


def _config(path):
    from ..experiments import get_experiment
    from ..experiments.base import config_of, read_config

    exp = get_experiment("position")
    return exp, (read_config(exp, path) if path is not None else config_of(exp))


@control_app.command("episode")
def episode_cmd(config: ConfigArg = None,
                index: Annotated[int, typer.Option("--index", parser=strict_int, metavar="INTEGER",
                                                   help="Trial index.")] = 0,
                seed: SeedOpt = 0, plot: PlotOpt = None, as_json: JsonOpt = False) -> None:
    """One trial of `experiment position` as an episode: x per throw, side, ω, switches (Fig. 7 analogue)."""
    with guard():
        if index < 0:
            raise InvalidStateError("index", f"must be ≥ 0, got {index}")
        fmt = figure_format(plot, "plot")
        exp, cfg = _config(config)
        ep = exp.episode(cfg, index, seed)
        if ep is None:
            raise InvalidStateError("index", f"trial {index} of seed {seed}: no drop came to rest (refused:drop)")
        if plot is not None:
            save_figure(ep.plot(), plot, fmt, "plot")
        rows = [{"throw": s.n_thrown, "x_m": s.x, "side": s.side, "action": s.action, "omega_rad_s": s.omega,
                 "mode": s.mode, "switched": s.switched, "reason": s.reason,
                 "readings": {k: (list(v) if isinstance(v, tuple) else v) for k, v in s.readings}} for s in ep.steps]
        if as_json:
            typer.echo(to_json({"summary": ep.summary(), "goal": ep.goal.to_dict(), "steps": rows}))
        else:
            typer.echo(repr(ep))
            for r in rows:
                if r["switched"] or r["action"] != "throw":
                    what = r["action"] if r["mode"] == r["action"] else f"{r['action']} (mode {r['mode']})"
                    typer.echo(f"  throw {r['throw']:>3}: x = {100 * r['x_m']:.2f} cm side {r['side']} → {what} "
                               f"({r['reason']})")


@control_app.command("fan")
def fan_cmd(config: ConfigArg = None,
            n: Annotated[int, typer.Option("--n", parser=strict_int, metavar="INTEGER", help="Episodes.")] = 30,
            seed: SeedOpt = 0, plot: PlotOpt = None, as_json: JsonOpt = False) -> None:
    """N trials of `experiment position` overlaid (trials 0…N−1 of the seed, run in this process)."""
    with guard():
        if not 1 <= n <= 2000:
            raise InvalidStateError("n", f"must be in [1, 2000], got {n}")
        fmt = figure_format(plot, "plot")
        exp, cfg = _config(config)
        eps = [exp.episode(cfg, i, seed) for i in range(n)]
        if plot is not None:
            from ..viz.control import plot_fan

            save_figure(plot_fan(eps), plot, fmt, "plot")
        out = [None if e is None else e.summary() for e in eps]
        ok = sum(1 for e in eps if e is not None and e.success)
        if as_json:
            typer.echo(to_json({"n": n, "successes": ok, "episodes": out}))
        else:
            typer.echo(f"{ok}/{n} episodes succeeded")


@control_app.command("tradeoff")
def tradeoff_cmd(config: ConfigArg = None,
                 eps: Annotated[list[str], typer.Option("--eps", help="Goal radii, m (comma list).")] = None,
                 omega_low: Annotated[list[str] | None, typer.Option(
                     "--omega-low", help="Low rate per ε, rad/s (comma list; default: the largest rate on a 0.1 "
                                         "rad/s grid whose jog at x_f − ε is shorter than ε)")] = None,
                 n: Annotated[int, typer.Option("--n", parser=strict_int, metavar="INTEGER", help="Trials per ε.")] = 100,
                 seed: SeedOpt = 0,
                 workers: Annotated[int, typer.Option("--workers", parser=strict_int, metavar="INTEGER",
                                                      help="Processes (0: all cores).")] = 0,
                 plot: PlotOpt = None, as_json: JsonOpt = False) -> None:
    """Throws to the goal (median, p90) and success rate against ε, one `position` run per ε."""
    from ..experiments.position import low_rate, throws_summary
    from ..experiments.runner import run_experiment

    with guard():
        fmt = figure_format(plot, "plot")
        radii = parse_floats(eps or ["0.002,0.005,0.01,0.02"], "eps")
        if any(e <= 0 for e in radii):
            raise InvalidStateError("eps", "must be > 0 m")
        lows = parse_floats(omega_low, "omega_low") if omega_low else None
        if lows is not None and len(lows) != len(radii):
            raise InvalidStateError("omega_low", f"needs one rate per ε ({len(radii)}), got {len(lows)}")
        exp, cfg = _config(config)
        rows = []
        for i, e in enumerate(radii):
            w = lows[i] if lows is not None else low_rate(cfg, e)
            c = cfg.model_copy(update={"eps": e, "omega_low": w})
            res = run_experiment(exp, c, n=n, seed=seed, workers=workers)
            rows.append({"eps_m": e, "omega_low": w, "n": res.n, "successes": res.successes,
                         "success_rate": res.success_rate, "ci95": list(res.ci95), "failures": res.failures,
                         **throws_summary(res.trials)})
        if plot is not None:
            from ..viz.control import plot_tradeoff

            save_figure(plot_tradeoff(rows), plot, fmt, "plot")
        if as_json:
            typer.echo(to_json({"seed": seed, "rows": rows}))
        else:
            typer.echo(f"{'ε mm':>7} {'ω_low':>6} {'success':>14} {'Wilson 95 %':>16} {'median':>7} {'p90':>5}")
            for r in rows:
                typer.echo(f"{1000 * r['eps_m']:>7.3g} {r['omega_low']:>6.3g} {r['successes']:>6}/{r['n']:<7} "
                           f"[{100 * r['ci95'][0]:.1f}, {100 * r['ci95'][1]:.1f}] % {r['median']!s:>7} {r['p90']!s:>5}")


@control_app.command("summary")
def summary_cmd(directory: Annotated[Path, typer.Argument(help="The --out folder of an `experiment position` run.")],
                as_json: JsonOpt = False) -> None:
    """Throws to success (median, p90, max) of a kept `experiment position` run, with its success rate."""
    from ..experiments.base import Trial
    from ..experiments.position import throws_summary
    from ..experiments.stats import wilson_interval

    with guard():
        path = Path(directory) / "trials.jsonl"
        if not path.is_file():
            raise InvalidStateError("directory", f"no trials.jsonl in {directory}")
        trials = []
        for line in path.read_text().splitlines():
            try:
                trials.append(Trial.from_json(json.loads(line)))
            except (ValueError, KeyError):
                continue  # a line cut by a kill
        k, m = sum(t.success for t in trials), len(trials)
        out = {"n": m, "successes": k, "ci95": list(wilson_interval(k, m)), "throws": throws_summary(trials)}
        if as_json:
            typer.echo(to_json(out))
        else:
            t = out["throws"]
            typer.echo(f"{k}/{m} successes, Wilson 95 % [{100 * out['ci95'][0]:.1f}, {100 * out['ci95'][1]:.1f}] %; "
                       f"throws to success: median {t['median']}, p90 {t['p90']}, max {t['max']}")


def register(app: typer.Typer) -> None:
    """Add the ``control`` group to ``app``."""
    app.add_typer(control_app, name="control")
