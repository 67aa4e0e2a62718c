"""``throwmap animate``: draw one throw, or an orbit of throws, to a GIF or MP4.

A thin shell: parse, build the part and arm, get a :class:`~throwmap.records.trajectory.Trajectory`
from the chosen model (:func:`throwmap.throws.orbit_trajectory.orbit_trajectory`), draw it
(:func:`throwmap.viz.animation.animate`) and say where the file went. Errors follow
:mod:`throwmap.cli.options`: one ``error: <field>: <reason>`` line on stderr, exit 2.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Annotated

import typer

from ..errors import InvalidStateError, ThrowmapError
from ..models import DEFAULT_MODEL, model_names
from ..throws.orbit_trajectory import orbit_trajectory, trajectory_models
from .options import (AlphaOpt, BackOpt, CavityOpt, GOpt, HOpt, LengthOpt, ModelOptionOpt, MuOpt, OmegaOpt, PartOpt,
                      SideOpt, WallMuOpt, WallOpt, XOpt, check_finite, check_output, guard, model_options,
                      part_and_arm, strict_int, system_options)
from ..budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, cli_limits as work_limits
from .options import ForceOpt, MaxMemoryOpt, MaxTimeOpt

__all__ = ["register", "animate_cmd", "ANIMATE_MODELS", "PROGRESS_FRAMES"]

ANIMATE_MODELS = trajectory_models()
"""Models ``animate`` can draw: those that record a trajectory."""
PROGRESS_FRAMES = 60
"""A progress bar (stderr, terminals only) is shown for animations with more frames than this."""



def _trajectory(model, part, arm, x, side, omega, n, opts=None, limits=None):
    """The trajectory of ``n`` throws (:func:`~throwmap.throws.orbit_trajectory.orbit_trajectory`); raises
    :class:`ImportError` where the model's module is not installed."""
    return orbit_trajectory(part, arm, x, side, omega, n, model=model, **(opts or {}), limits=limits)


def _summary(traj) -> tuple[str, str]:
    from ..records.outcome import Status

    outcomes = traj.meta.get("outcomes", ())
    kinds = [o.kind for o in outcomes]
    throws = f"{len(outcomes)} throw{'s' if len(outcomes) != 1 else ''}"
    counted = [f"{kinds.count(k)} {k}{'s' if kinds.count(k) != 1 else ''}" for k in dict.fromkeys(kinds)]
    if outcomes and outcomes[-1].status != Status.OK:
        last = outcomes[-1]
        final = f"escaped ({last.status.label}) at x = {last.x:.4g} m"
    elif outcomes:
        final = f"rests at x = {outcomes[-1].x:.4g} m on side {outcomes[-1].side}"
    else:  # pragma: no cover - orbit_trajectory always throws once
        final = "no throw"
    return throws, f"{throws} ({', '.join(counted)}); {final}"


def animate_cmd(
    part: PartOpt,
    omega: OmegaOpt,
    x: XOpt,
    side: SideOpt,
    h: HOpt = None,
    g: GOpt = None,
    length: LengthOpt = None,
    mu: MuOpt = None,
    back: BackOpt = None,
    n: Annotated[int, typer.Option("-n", "--n", parser=strict_int, metavar="INTEGER",
                                   help="Number of throws (> 1 animates an orbit).")] = 1,
    model: Annotated[str, typer.Option("--model", help=f"Model: {', '.join(ANIMATE_MODELS)} "
                                                       f"(default {DEFAULT_MODEL}).")] = DEFAULT_MODEL,
    model_option: ModelOptionOpt = None,
    alpha: AlphaOpt = None,
    wall: WallOpt = None,
    wall_mu: WallMuOpt = None,
    cavity: CavityOpt = None,
    out: Annotated[Path, typer.Option("--out", help="Animation file, .gif or .mp4 (mp4 needs ffmpeg).")]
    = Path("out/throw.gif"),
    fps: Annotated[int, typer.Option("--fps", parser=strict_int, metavar="INTEGER", help="Frames per second.")] = 30,
    speed: Annotated[float, typer.Option("--speed", help="Playback speed relative to real time "
                                                         "(0.25: four times slower).")] = 0.25,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Draw a throw (or -n throws: an orbit) as an animation."""
    with guard():
        if model not in ANIMATE_MODELS:
            what = f"model {model!r} records no trajectory" if model in model_names() else f"unknown model {model!r}"
            raise InvalidStateError("model", f"{what} (choose from {', '.join(ANIMATE_MODELS)})")
        opts = {**model_options(model_option, model), **system_options(alpha, wall, wall_mu, cavity)}  # values
        if n < 1:
            raise InvalidStateError("n", f"must be a positive integer, got {n}")
        if fps < 1:
            raise ThrowmapError("fps", f"must be a positive integer, got {fps}")
        if not (math.isfinite(speed) and speed > 0):
            raise ThrowmapError("speed", f"must be a positive finite number, got {speed}")
        limits = work_limits(max_memory, max_time, force)
        from ..viz.animation import animate, check_animation_path, frame_times

        check_animation_path(out, need_directory=False)  # before any work; its folder: check_output
        check_output(out, "out")  # its folder there and writable
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        system_options(alpha, wall, wall_mu, cavity, arm)  # fixtures need the arm's length
        side = the_part.check_side(side)  # the library's rule for a side, before any work
        check_finite(x, "x")
        check_finite(omega, "omega")
        if "alpha" in opts or "fixtures" in opts:  # refused before any work by a model without them
            from ..throws.throw import prepare

            prepare(model, arm, opts.get("fixtures", ()), opts.get("alpha", 0.0), opts.get("options"), {})
        os.environ.setdefault("MPLBACKEND", "Agg")  # files only, never a window
        try:
            traj = _trajectory(model, the_part, arm, x, side, omega, n, opts, limits)
        except ImportError as err:
            missing = getattr(err, "name", None) or ""
            if missing.startswith("throwmap") or not missing:
                reason = f"the {model!r} model is not available in this installation"
            else:
                reason = f"the {model!r} model needs the optional package {missing!r} (pip install it)"
            raise ThrowmapError("model", reason) from None
        throws, summary = _summary(traj)
        from ..analysis.maps import system_text

        extra = system_text(opts.get("fixtures", ()), opts.get("alpha", 0.0))
        title = (f"{the_part.name or 'part'} — h = {arm.h:g} m, ω = {omega:g} rad/s, model {model!r}, "
                 f"{extra + ', ' if extra else ''}{throws}")
        n_drawn = len(frame_times(traj, fps, speed, 0.5))  # the progress bar's total
        try:
            from rich.console import Console

            console = Console(stderr=True)
            if n_drawn > PROGRESS_FRAMES and console.is_terminal:
                from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn

                with Progress(TextColumn("drawing"), BarColumn(), MofNCompleteColumn(),
                              console=console, transient=True) as bar:
                    task = bar.add_task("drawing", total=n_drawn)
                    made = animate(traj, out, fps=fps, speed=speed, title=title,
                                   progress=lambda done, total: bar.update(task, completed=done))
            else:
                made = animate(traj, out, fps=fps, speed=speed, title=title)
        except OSError as err:
            raise ThrowmapError("out", f"cannot write {out}: {err.strerror or err}") from None
        n_frames = getattr(made, "n_frames", n_drawn)  # frames in the file (a GIF merges a held end)
        typer.echo(f"wrote {out} ({n_frames} frames, {fps} fps, {speed:g}× real time)")
        typer.echo(summary)


def register(app: typer.Typer) -> None:
    """Add the ``animate`` command to ``app``."""
    app.command("animate")(animate_cmd)
