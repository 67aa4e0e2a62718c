"""``throwmap continuation``: how the attractors change along one parameter, or a map over two.

::

    throwmap continuation --part P --h H [--omega W] --model M --param omega|h|alpha|mu|weight_x|weight_y
                          --from A --to B --n N [--starts S] [--horizon T] [--tol TOL] [--json] [--plot F]
    throwmap continuation ... --param2 NAME --from2 A2 --to2 B2 --n2 N2 --out DIR [--workers K] [--plot F]

A thin shell over :func:`throwmap.analysis.continuation.continuation` (one parameter: attractors matched along
it, events located to ``--tol``) and :func:`throwmap.sweeps.attractor_map.attractor_map` (two parameters: the
number of attractors and the escape share at every grid point, on Dask, kept in ``--out`` and resumed).
Errors: one ``error: <field>: <reason>`` line on stderr, exit 2.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from ..budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, cli_limits
from .options import (AlphaOpt, BackOpt, CavityOpt, ForceOpt, GOpt, HOpt, JsonOpt, LengthOpt, MaxMemoryOpt,
                      MaxTimeOpt, ModelOpt, ModelOptionOpt, MuOpt, PartOpt, WallMuOpt, WallOpt, check_out_dir,
                      figure_format, guard, model_options, part_and_arm, save_figure, stage_bars, strict_int,
                      system_options, to_json)

__all__ = ["register", "continuation_cmd"]

ParamOpt = Annotated[str, typer.Option("--param", help="The parameter: omega (rad/s), h (m), alpha (rad), mu, "
                                                       "weight_x or weight_y (m: the part's first lead weight).")]


def continuation_cmd(
    part: PartOpt,
    param: ParamOpt,
    start: Annotated[float, typer.Option("--from", help="First value of the parameter (its unit).")],
    stop: Annotated[float, typer.Option("--to", help="Last value of the parameter.")],
    n: Annotated[int, typer.Option("--n", parser=strict_int, metavar="INTEGER", help="Values, ends included (≥ 2).")]
    = 31,
    omega: Annotated[float | None, typer.Option("--omega", help="Release rate ω, rad/s (required unless the "
                                                                "parameter is omega).")] = None,
    h: HOpt = None,
    g: GOpt = None,
    length: LengthOpt = None,
    mu: MuOpt = None,
    back: BackOpt = None,
    model: ModelOpt = "rigid_body",
    model_option: ModelOptionOpt = None,
    alpha: AlphaOpt = None,
    wall: WallOpt = None,
    wall_mu: WallMuOpt = None,
    cavity: CavityOpt = None,
    starts: Annotated[int, typer.Option("--starts", parser=strict_int, metavar="INTEGER",
                                        help="Starts per stable side, evenly up to --x-max.")] = 200,
    x_max: Annotated[float | None, typer.Option("--x-max", help="Outer end of the starts, m (default: the arm "
                                                                "length, else 0.6).")] = None,
    horizon: Annotated[int, typer.Option("--horizon", parser=strict_int, metavar="INTEGER",
                                         help="Throws an orbit is followed; an escape later is not seen.")] = 500,
    tol: Annotated[float, typer.Option("--tol", help="Events located to this width (the parameter's unit).")]
    = 1e-3,
    match_tol: Annotated[float, typer.Option("--match-tol", help="Largest distance, m, between one attractor's "
                                                                 "sets at neighbouring values.")] = 0.03,
    critical: Annotated[bool, typer.Option("--critical", help="Also r_i (where jogs end) at every value.")] = False,
    seed: Annotated[int, typer.Option("--seed", parser=strict_int, metavar="INTEGER",
                                      help="Seed of the limit-set search (the same at every value).")] = 0,
    param2: Annotated[str | None, typer.Option("--param2", help="A second parameter: a map over both (needs "
                                                                "--out).")] = None,
    start2: Annotated[float | None, typer.Option("--from2", help="First value of --param2.")] = None,
    stop2: Annotated[float | None, typer.Option("--to2", help="Last value of --param2.")] = None,
    n2: Annotated[int, typer.Option("--n2", parser=strict_int, metavar="INTEGER", help="Values of --param2.")] = 11,
    out: Annotated[Path | None, typer.Option("--out", help="Two parameters: the sweep's folder (resumed when run "
                                                           "again).")] = None,
    workers: Annotated[int, typer.Option("--workers", parser=strict_int, metavar="INTEGER",
                                         help="Two parameters: local Dask workers (0: all cores).")] = 0,
    as_json: JsonOpt = False,
    plot: Annotated[Path | None, typer.Option("--plot", help="Write the figure (bifurcation diagram, or the "
                                                             "two-parameter map), e.g. continuation.png.")] = None,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Attractors along a parameter (events located), or the attractor count and escape share over two."""
    import numpy as np

    from ..analysis.continuation import PARAMS, Resolution, continuation
    from ..errors import InvalidStateError
    from ..throws.throw import check_model

    with guard():
        check_model(model)
        opts = model_options(model_option, model)
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        sysk = system_options(alpha, wall, wall_mu, cavity, arm)
        if param not in PARAMS:
            raise InvalidStateError("param", f"must be one of {', '.join(PARAMS)}, got {param!r}")
        if n < 2:
            raise InvalidStateError("n", f"must be ≥ 2 (the ends), got {n}")
        import math

        for name, v in (("from", start), ("to", stop)):
            if not math.isfinite(v):
                raise InvalidStateError(name, f"must be a finite number, got {v}")
        if not stop > start:
            raise InvalidStateError("to", f"must be above --from ({start:g}), got {stop:g}")
        fmt = figure_format(plot, "plot")
        limits = cli_limits(max_memory, max_time, force)
        if param2 is not None:
            _two(the_part, part, arm, model, opts, sysk, param, (start, stop, n), param2, (start2, stop2, n2), omega,
                 starts, x_max, horizon, seed, out, workers, plot, fmt, as_json, limits)
            return
        res = Resolution(starts=starts, x_max=x_max, horizon=horizon, tol=tol, match_tol=match_tol,
                         critical=critical)
        with stage_bars() as bar:
            c = continuation(the_part, arm, param, np.linspace(start, stop, n), omega=omega, model=model,
                             resolution=res, rng=seed, progress=bar, limits=limits, **opts, **sysk)
        if plot is not None:
            save_figure(c.plot(), plot, fmt, "plot")
        if as_json:
            typer.echo(to_json(c.to_dict()))
            return
        typer.echo(c.table())
        typer.echo(f"{len(c.points)} values evaluated ({len(c.points) - len(c.at_grid())} added to locate events) "
                   f"in {c.time_s:.1f} s")
        if plot is not None:
            typer.echo(f"wrote {plot}")


def _two(the_part, part_arg, arm, model, opts, sysk, p1, r1, p2, r2, omega, starts, x_max, horizon, seed, out,
         workers, plot, fmt, as_json, limits) -> None:
    """The two-parameter map (:func:`throwmap.sweeps.attractor_map.attractor_map`)."""
    from ..errors import InvalidStateError
    from ..sweeps.attractor_map import attractor_map, limit_set_config

    if out is None:
        raise InvalidStateError("out", "a two-parameter map needs --out (its sweep's folder, resumed when run again)")
    check_out_dir(out)
    if r2[0] is None or r2[1] is None:
        raise InvalidStateError("from2" if r2[0] is None else "to2", "required with --param2")
    if not r2[1] > r2[0]:
        raise InvalidStateError("to2", f"must be above --from2 ({r2[0]:g}), got {r2[1]:g}")
    if r2[2] < 2:
        raise InvalidStateError("n2", f"must be ≥ 2 (the ends), got {r2[2]}")
    if opts:
        raise InvalidStateError("model-option", "a two-parameter map runs the sweep's limit-set target, which takes "
                                                "no model options")
    config = limit_set_config(part_arg, arm, omega=omega, model=model, throw_options=sysk, n_starts=starts,
                              x_max=x_max, horizon=horizon)
    with stage_bars() as bar:
        m = attractor_map({p1: r1, p2: r2}, out, config, seed=seed, workers=workers,
                          progress=lambda d, t: bar("points", d, t), limits=limits)
    if plot is not None:
        save_figure(m.plot(), plot, fmt, "plot")
    if as_json:
        typer.echo(to_json(m.to_dict()))
        return
    typer.echo(m.table())
    if plot is not None:
        typer.echo(f"wrote {plot}")


def register(app: typer.Typer) -> None:
    app.command("continuation")(continuation_cmd)
