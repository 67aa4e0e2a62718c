"""``throwmap assemble …`` and ``throwmap sensitivity``: one self-assembly trial as figures and an animation
(paper Sec. VI, Figs. 15 and 16), and any experiment's success against one parameter.

::

    throwmap assemble episode [CONFIG] --index I --seed S [--first-success] --plot FILE --snapshots FILE [--json]
    throwmap assemble animate [CONFIG] --index I --seed S [--first-success] --out FILE.gif [--speed X] [--fps N]
    throwmap sensitivity NAME [CONFIG] --param FIELD [--param FIELD2] --values V1,V2,… --n N --seed S
                         [--workers W] [--plot FILE] [--goal RATE] [--out DIR] [--json]

``CONFIG`` is an ``assemble`` config (``.toml``/``.json``; omitted: the built-in example). ``episode`` and
``animate`` rerun one trial of a Monte Carlo run (the same random stream as trial I of ``experiment assemble
--seed S``); ``--first-success`` takes the first successful trial from I on. ``sensitivity`` runs the experiment
once per value with every ``--param`` (a dotted config field, e.g. ``tilt_rate``, ``noise.omega_rel``,
``sensor.false_positive``) set to it. Errors: one ``error: <field>: <reason>`` line on stderr, exit 2.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Annotated

import typer

from ..budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, cli_limits
from ..errors import InvalidStateError
from .options import (ForceOpt, JsonOpt, MaxMemoryOpt, MaxTimeOpt, check_out_dir, check_output, figure_format, guard,
                      interrupted_line, parse_floats, progress_bar, save_figure, stderr_line, strict_int, to_json)
from .usage import ThrowmapGroup

__all__ = ["register", "assemble_app", "sensitivity_cmd"]

assemble_app = typer.Typer(name="assemble", cls=ThrowmapGroup, no_args_is_help=True, add_completion=False,
                           pretty_exceptions_enable=False,
                           help="One self-assembly trial (Sec. VI): x of both parts per throw with the switch "
                                "(Fig. 16), snapshots (Fig. 15), an animation.")

ConfigArg = Annotated[Path | None, typer.Argument(help="An `assemble` config (.toml/.json; default: built-in).",
                                                  show_default=False)]
IndexOpt = Annotated[int, typer.Option("--index", parser=strict_int, metavar="INTEGER", help="Trial index.")]
SeedOpt = Annotated[int, typer.Option("--seed", parser=strict_int, metavar="INTEGER", help="Run seed.")]
FirstOpt = Annotated[bool, typer.Option("--first-success", help="Take the first successful trial from --index on "
                                                                "(at most --tries trials).")]
TriesOpt = Annotated[int, typer.Option("--tries", parser=strict_int, metavar="INTEGER",
                                       help="Trials tried with --first-success.")]


def _config(path):
    from ..experiments import get_experiment
    from ..experiments.base import config_of, read_config

    exp = get_experiment("assemble")
    return read_config(exp, path) if path is not None else config_of(exp)


def _episode(config, index: int, seed: int, first: bool, tries: int, motion: bool):
    from ..experiments.assemble_episode import assembly_episode, first_success

    if index < 0:
        raise InvalidStateError("index", f"must be ≥ 0, got {index}")
    if seed < 0:
        raise InvalidStateError("seed", f"must be ≥ 0, got {seed}")
    cfg = _config(config)
    if first:
        return first_success(cfg, seed, start=index, max_tries=tries, motion=motion)
    return assembly_episode(cfg, index, seed, motion=motion)


@assemble_app.command("episode")
def episode_cmd(config: ConfigArg = None, index: IndexOpt = 0, seed: SeedOpt = 0, first: FirstOpt = False,
                tries: TriesOpt = 20,
                plot: Annotated[Path | None, typer.Option("--plot", help="x of both parts per throw with the switch "
                                                                         "(Fig. 16 analogue), e.g. fig16.png.")] = None,
                snapshots: Annotated[Path | None, typer.Option("--snapshots", help="The pair at the switch, partly "
                                                                                   "and fully assembled (Fig. 15 "
                                                                                   "analogue).")] = None,
                as_json: JsonOpt = False) -> None:
    """One trial of `experiment assemble`, throw by throw: phases, rates, both parts' x and side."""
    with guard():
        fmt = figure_format(plot, "plot")
        fmt2 = figure_format(snapshots, "snapshots")
        os.environ.setdefault("MPLBACKEND", "Agg")
        ep = _episode(config, index, seed, first, tries, motion=False)
        if plot is not None:
            save_figure(ep.plot(), plot, fmt, "plot")
        if snapshots is not None:
            save_figure(ep.plot_snapshots(), snapshots, fmt2, "snapshots")
        if as_json:
            typer.echo(to_json({"summary": ep.summary(), "runs": ep.rows()}))
            return
        typer.echo(repr(ep))
        roles = [n for n, _ in ep.roles()]
        for r in ep.rows():
            if r["phase"] in ("drop", "tilt") or r["status"] != "ok" or r["run"] == ep.assembled_run:
                parts = "; ".join(f"{roles[i]} x = {100 * p['x_m']:.2f} cm side {p['side']}"
                                  for i, p in enumerate(r["parts"]))
                typer.echo(f"  throw {r['throw']:>3} {r['phase']:<5} ω = {r['omega_rad_s']:.3g} rad/s: {parts}"
                           f"{'' if r['status'] == 'ok' else ' — ' + r['status']}")


@assemble_app.command("animate")
def animate_cmd(config: ConfigArg = None, index: IndexOpt = 0, seed: SeedOpt = 0, first: FirstOpt = False,
                tries: TriesOpt = 20,
                out: Annotated[Path, typer.Option("--out", help="The animation (.gif, or .mp4 with ffmpeg).")] = Path(
                    "assembly.gif"),
                start: Annotated[str, typer.Option("--start", help="'switch' (two throws before it) or 'drop'.")] =
                "switch",
                speed: Annotated[float, typer.Option("--speed", help="Playback speed (× real time).")] = 2.0,
                fps: Annotated[int, typer.Option("--fps", parser=strict_int, metavar="INTEGER",
                                                 help="Frames per second.")] = 20) -> None:
    """Animate one trial of `experiment assemble` (its throws from the switch, or from the drop, to the end)."""
    import math

    with guard():
        if fps < 1:
            raise InvalidStateError("fps", f"must be a positive integer, got {fps}")
        if not (math.isfinite(speed) and speed > 0):
            raise InvalidStateError("speed", f"must be a positive finite number, got {speed}")
        if start not in ("switch", "drop"):
            raise InvalidStateError("start", f"must be 'switch' or 'drop', got {start!r}")
        os.environ.setdefault("MPLBACKEND", "Agg")
        from ..viz.animation import animate, check_animation_path

        check_animation_path(out, need_directory=False)
        check_output(out, "out")
        ep = _episode(config, index, seed, first, tries, motion=True)
        traj = ep.motion(start=start)
        s = ep.summary()
        end = f"assembled at throw {s['assembled_throw']}" if ep.success else f"failed: {ep.trial.failure}"
        title = f"self-assembly, seed {ep.seed} trial {ep.index}: switch after throw {s['switch_throw']}, {end}"
        try:
            made = animate(traj, out, fps=fps, speed=speed, title=title, figsize=(8.0, 3.6))
        except OSError as err:
            raise InvalidStateError("out", f"cannot write {out}: {err.strerror or err}") from None
        n_frames = getattr(made, "n_frames", None)
        typer.echo(f"wrote {out} ({n_frames} frames, {fps} fps, {speed:g}× real time, {traj.t[-1]:.1f} s simulated)")
        typer.echo(repr(ep))


def sensitivity_cmd(
    name: Annotated[str, typer.Argument(help="The experiment (see `throwmap experiment --list`).")],
    config: Annotated[Path | None, typer.Argument(help="Its config (.toml/.json; default: built-in).",
                                                  show_default=False)] = None,
    param: Annotated[list[str], typer.Option("--param", help="Dotted config field set to each value (repeat to set "
                                                             "several to the same value).")] = None,
    values: Annotated[list[str], typer.Option("--values", help="Values (comma list, SI units).")] = None,
    n: Annotated[int, typer.Option("--n", parser=strict_int, metavar="INTEGER", help="Trials per value.")] = 50,
    seed: SeedOpt = 0,
    workers: Annotated[int, typer.Option("--workers", parser=strict_int, metavar="INTEGER",
                                         help="Processes (0: all cores).")] = 0,
    plot: Annotated[Path | None, typer.Option("--plot", help="Success against the value with Wilson intervals.")] =
    None,
    goal: Annotated[float | None, typer.Option("--goal", help="A goal rate drawn on the plot (0–1).")] = None,
    out: Annotated[Path | None, typer.Option("--out", help="Keep each run's trials in DIR/<field>=<value> (a "
                                                           "rerun resumes).")] = None,
    as_json: JsonOpt = False,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Success rate of an experiment against one config parameter (same seed, n trials per value)."""
    from ..experiments import get_experiment
    from ..experiments.base import read_config
    from ..experiments.sensitivity import sensitivity

    with guard():
        if not param:
            raise InvalidStateError("param", "give at least one --param (a dotted config field, e.g. tilt_rate)")
        if not values:
            raise InvalidStateError("values", "give --values (comma list)")
        vals = parse_floats(values, "values")
        if goal is not None and not 0 <= goal <= 1:
            raise InvalidStateError("goal", f"must be a rate in [0, 1], got {goal}")
        fmt = figure_format(plot, "plot")
        exp = get_experiment(name)
        cfg = read_config(exp, config) if config is not None else None
        if out is not None:
            check_out_dir(out)
        limits = cli_limits(max_memory, max_time, force)
        try:
            with progress_bar(f"{exp.name} × {len(vals)}") as update:
                res = sensitivity(exp, cfg, fields=tuple(param), values=vals, n=n, seed=seed, workers=workers,
                                  out=out, progress=update, limits=limits)
        except KeyboardInterrupt:
            stderr_line(interrupted_line(out, "trial", "*/trials.jsonl"))
            raise typer.Exit(130) from None
        if plot is not None:
            os.environ.setdefault("MPLBACKEND", "Agg")
            save_figure(res.plot(goal=goal), plot, fmt, "plot")
        if as_json:
            typer.echo(to_json(res.to_dict()))
        else:
            typer.echo(res.table())
            if plot is not None:
                typer.echo(f"wrote {plot}")


def register(app: typer.Typer) -> None:
    """Add the ``assemble`` group and the ``sensitivity`` command to ``app``."""
    app.add_typer(assemble_app, name="assemble")
    app.command("sensitivity")(sensitivity_cmd)
