"""``throwmap limitset``, ``throwmap basins``, ``throwmap funnels``: the analysis of throw maps on the command line.

A thin shell over :mod:`throwmap.analysis` (paper Sec. III-D and I-A): parse, build the
part and arm, call one library function (:func:`~throwmap.analysis.limit_set` with
:func:`~throwmap.analysis.critical_points`, :func:`~throwmap.analysis.basins`,
:func:`~throwmap.analysis.funnels`), print its text (or JSON with ``--json``), and write
figures (``--plot``) and result files (``--out DIR``) atomically. SI units throughout;
the default model is ``rigid_body``, as in the library. Errors follow
:mod:`throwmap.cli.options`: one ``error: <field>: <reason>`` line on stderr, exit 2.

A progress bar (Rich, on stderr) is drawn while the maps are iterated, when stderr
is a terminal; redirected output stays clean.
"""

from __future__ import annotations

import io as _io
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated

import typer

from ..version import __version__
from ..analysis import ConfigSet, basins, critical_points, funnels, limit_set
from ..budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, cli_limits as work_limits
from .options import ForceOpt, MaxMemoryOpt, MaxTimeOpt, stage_bars
from ..analysis.limitset import DEFAULT_CAPS
from ..analysis.maps import ThrowMap, system_text
from ..analysis.orbits import orbit_on_attractor
from ..errors import InvalidStateError, ThrowmapError
from ..throws.throw import check_model
from .options import (AlphaOpt, BackOpt, CavityOpt, GOpt, HOpt, JsonOpt, LengthOpt, ModelOpt, ModelOptionOpt, MuOpt,
                      OmegaOpt, PartOpt, WallMuOpt, WallOpt, arm_dict, check_finite, check_out_dir, figure_format,
                      guard, make_out_dir, model_options, options_doc, parse_floats, part_and_arm, save_figure,
                      strict_int, system_doc, system_options, to_json, write_bytes, write_text)

__all__ = ["register", "limitset_cmd", "basins_cmd", "funnels_cmd", "JSON_ARRAYS_MAX", "OPTION_FIELDS"]

JSON_ARRAYS_MAX = 200_000
"""``basins --out`` puts the per-configuration arrays into ``basins.json`` up to this many
configurations; above it the JSON holds the summary and the arrays are in ``basins.npz`` only."""

OPTION_FIELDS = {"n_starts": "starts", "n_seeds": "starts", "n_record": "record", "n_check": "check",
                 "max_seconds": "max_time"}
"""Library argument names that the command line calls differently (errors name the option)."""

XMaxOpt = Annotated[float | None, typer.Option("--x-max", help="Outer end of the analysed configurations, m "
                                                              "(default: the arm length, else 0.6).")]
SeedOpt = Annotated[int, typer.Option("--seed", parser=strict_int, metavar="INTEGER",
                                      help="Seed of the random starts and checks (same seed, same "
                                           "result).")]
StartsOpt = Annotated[int, typer.Option("--starts", parser=strict_int, metavar="INTEGER",
                                        help="Starting configurations per stable side for the "
                                             "limit-set search (stratified, drawn with --seed).")]
TransientOpt = Annotated[int | None, typer.Option("--transient", parser=strict_int, metavar="INTEGER",
                                                  help="Throws discarded before recording "
                                                       f"(default {DEFAULT_CAPS['transient']}).")]
MaxTransientOpt = Annotated[int | None, typer.Option("--max-transient", parser=strict_int, metavar="INTEGER",
                                                     help="Most throws discarded in all while the orbits have not "
                                                          "settled (default "
                                                          f"{DEFAULT_CAPS['max_transient']}, raised with --transient "
                                                          "to 3 × transient + 2 × record).")]
RecordOpt = Annotated[int | None, typer.Option("--record", parser=strict_int, metavar="INTEGER",
                                               help="Throws recorded per orbit "
                                                    f"(default {DEFAULT_CAPS['n_record']}).")]




# ------------------------------------------------------------------ helpers (no physics)
def _stderr_console():
    from rich.console import Console

    return Console(stderr=True)


def _progress():
    """One Rich bar per stage on stderr (:func:`~throwmap.cli.options.stage_bars`)."""
    return stage_bars(_stderr_console())


@contextmanager
def _option_names():
    """Re-raise a library error on ``n_starts`` (…) as one on the option the user typed (``starts``)."""
    try:
        yield
    except ThrowmapError as err:
        if err.field in OPTION_FIELDS:
            raise type(err)(OPTION_FIELDS[err.field], err.reason) from None
        raise


# ------------------------------------------------------------------ limitset
def limitset_cmd(
    part: PartOpt,
    omega: OmegaOpt,
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
    x_max: XMaxOpt = None,
    starts: StartsOpt = 64,
    transient: TransientOpt = None,
    max_transient: MaxTransientOpt = None,
    record: RecordOpt = None,
    tol: Annotated[float | None, typer.Option("--tol", help="Recurrence tolerance, m "
                                                            f"(default {DEFAULT_CAPS['tol']:g}).")] = None,
    max_period: Annotated[int | None, typer.Option("--max-period", parser=strict_int, metavar="INTEGER",
                                                   help="Longest cycle looked for "
                                                        f"(default {DEFAULT_CAPS['max_period']}).")]
    = None,
    seed: SeedOpt = 0,
    as_json: JsonOpt = False,
    plot: Annotated[Path | None, typer.Option("--plot", help="Write the limit set along the arm with r_i, l_i "
                                                             "and an orbit (paper Fig. 5), e.g. limit_set.png.")]
    = None,
    plot_map: Annotated[Path | None, typer.Option("--plot-map", help="Write T(x) per side with r_i, l_i and the "
                                                                     "limit set (paper Fig. 2), e.g. map.png.")]
    = None,
    out: Annotated[Path | None, typer.Option("--out", help="Directory for limit_set.json (created).")] = None,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Critical points r_i, l_i and the forward limit set(s) of the throw map T^ω (paper Sec. III-D)."""
    with guard():
        check_model(model)
        opts = model_options(model_option, model)
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        sysk = system_options(alpha, wall, wall_mu, cavity, arm)
        check_finite(omega, "omega")
        fmt = figure_format(plot, "plot")
        fmt_map = figure_format(plot_map, "plot_map")
        check_out_dir(out)
        limits = work_limits(max_memory, max_time, force)
        cmap = ThrowMap(the_part, arm, omega, model, x_max, {**opts, **sysk})  # refuses what the model lacks
        crit = critical_points(the_part, arm, omega, model, x_max=x_max, limits=limits, **opts, **sysk)
        with _option_names(), _progress() as bar:
            limit = limit_set(the_part, arm, omega, model, n_starts=starts, rng=seed, x_max=x_max, limits=limits, **opts, **sysk,
                              transient=transient, max_transient=max_transient, n_record=record, tol=tol, max_period=max_period,
                              progress=lambda done, total: bar("iterating", done, total))
        if plot is not None:
            from ..viz.limit_set import plot_limit_set

            orbit = orbit_on_attractor(the_part, arm, omega, model, limit, **opts, **sysk)
            save_figure(plot_limit_set(limit, critical=crit, orbit=orbit), plot, fmt, "plot")
        if plot_map is not None:
            from ..throws.samples import sample_map

            save_figure(sample_map(cmap).plot(critical=crit, limit=limit), plot_map, fmt_map, "plot_map")
        doc = {"limit_set": limit.to_dict(), "critical_points": crit.to_dict(), "part": the_part.name,
               "arm": arm_dict(arm), **system_doc(sysk), "omega": omega, "model": model, "seed": seed,
               "plot": str(plot) if plot is not None else None,
               "plot_map": str(plot_map) if plot_map is not None else None, "model_options": options_doc(opts), "version": __version__}
        written = [p for p in (plot, plot_map) if p is not None]
        if out is not None:
            make_out_dir(out)
            write_text(out / "limit_set.json", to_json(doc) + "\n", "out")
            written.append(out / "limit_set.json")
        if as_json:
            typer.echo(to_json(doc))
            return
        typer.echo(f"{the_part.name}: ω = {omega:g} rad/s, h = {arm.h:g} m, model {model!r}"
                   + (f", {system_text(cmap.fixtures, cmap.alpha)}" if sysk else ""))
        typer.echo("critical points (r_i: jogs end; l_i = inf S):")
        typer.echo(crit.table())
        typer.echo("")
        typer.echo(limit.summary())
        for p in written:
            typer.echo(f"wrote {p}")

# ------------------------------------------------------------------ basins
def basins_cmd(
    part: PartOpt,
    omega: OmegaOpt,
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
    x_max: XMaxOpt = None,
    grid: Annotated[int, typer.Option("--grid", parser=strict_int, metavar="INTEGER",
                                      help="Configurations per stable side (≥ 2), evenly spaced "
                                           "up to --x-max.")] = 1000,
    method: Annotated[str, typer.Option("--method", help="auto (cells above 20 000 configurations), orbits "
                                                         "(exact orbits) or cells (cell-to-cell mapping).")]
    = "auto",
    seed: SeedOpt = 0,
    max_throws: Annotated[int, typer.Option("--max-throws", parser=strict_int, metavar="INTEGER",
                                            help="Throw cap per orbit; beyond it an orbit is "
                                                 "unresolved (label -1).")] = 500,
    check: Annotated[int, typer.Option("--check", parser=strict_int, metavar="INTEGER",
                                       help="Configurations checked by exact orbits "
                                            "(cells method; 0: none).")] = 1000,
    starts: StartsOpt = 64,
    transient: TransientOpt = None,
    max_transient: MaxTransientOpt = None,
    record: RecordOpt = None,
    as_json: JsonOpt = False,
    plot: Annotated[Path | None, typer.Option("--plot", help="Write the basin map, e.g. basins.png.")] = None,
    out: Annotated[Path | None, typer.Option("--out", help="Directory for basins.json and basins.npz "
                                                           "(created).")] = None,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Basins of attraction over a grid of configurations, with a certificate of global attractivity."""
    with guard():
        check_model(model)
        opts = model_options(model_option, model)
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        sysk = system_options(alpha, wall, wall_mu, cavity, arm)
        check_finite(omega, "omega")
        fmt = figure_format(plot, "plot")
        check_out_dir(out)
        limits = work_limits(max_memory, max_time, force)
        with _option_names(), _progress() as bar:
            result = basins(the_part, arm, omega, model, grid=grid, method=method, rng=seed, limits=limits, **opts, **sysk,
                            max_throws=max_throws, n_check=check, n_seeds=starts, transient=transient,
                            max_transient=max_transient, n_record=record, x_max=x_max, progress=bar)
        if plot is not None:
            from ..viz.basins import plot_basins

            save_figure(plot_basins(result), plot, fmt, "plot")
        extra = {"part": the_part.name, "arm": arm_dict(arm), **system_doc(sysk), "omega": omega, "model": model, "seed": seed,
                 "plot": str(plot) if plot is not None else None, "model_options": options_doc(opts), "version": __version__}
        written = [plot] if plot is not None else []
        if out is not None:
            import numpy as np

            make_out_dir(out)
            with_arrays = result.n_configs <= JSON_ARRAYS_MAX
            buf = _io.BytesIO()
            np.savez_compressed(buf, x=result.x, side=result.side, labels=result.labels, fates=result.fates,
                                throws=result.throws)
            write_bytes(out / "basins.npz", buf.getvalue(), "out")
            full = {**result.to_dict(arrays=with_arrays), **extra, "arrays": "basins.npz" if not with_arrays
                    else "grid (also in basins.npz)"}
            write_text(out / "basins.json", to_json(full) + "\n", "out")
            written += [out / "basins.json", out / "basins.npz"]
        if as_json:
            typer.echo(to_json({**result.to_dict(arrays=False), **extra}))
            return
        typer.echo(result.summary())
        for p in written:
            typer.echo(f"wrote {p}")

# ------------------------------------------------------------------ funnels
def funnels_cmd(
    part: PartOpt,
    omega: Annotated[list[str], typer.Option("--omega", help="Release rates ω, rad/s, one funnel map each "
                                                             "(repeat the option or give a comma list).")],
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
    x_max: XMaxOpt = None,
    goal: Annotated[str | None, typer.Option("--goal", help="Goal configurations 'side:lo-hi, …' in m "
                                                            "(e.g. '0:0.50-0.90'); none: no priorities.")]
    = None,
    grid: Annotated[int, typer.Option("--grid", parser=strict_int, metavar="INTEGER",
                                      help="Configurations per stable side for each map's basins "
                                           "(≥ 2).")] = 400,
    containment: Annotated[float, typer.Option("--containment", help="Share of a spout that must end in "
                                                                     "another funnel for an edge, in (0, 1].")]
    = 1.0,
    method: Annotated[str, typer.Option("--method", help="Basin method: auto, orbits or cells.")] = "auto",
    seed: SeedOpt = 0,
    starts: StartsOpt = 64,
    as_json: JsonOpt = False,
    plot: Annotated[Path | None, typer.Option("--plot", help="Write the funnel graph, e.g. funnels.png.")]
    = None,
    out: Annotated[Path | None, typer.Option("--out", help="Directory for funnels.json (created).")] = None,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Funnels (mouth: basin, spout: attractor) of several throws and the priority order to a goal (Sec. I-A)."""
    with guard():
        check_model(model)
        opts = model_options(model_option, model)
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        sysk = system_options(alpha, wall, wall_mu, cavity, arm)
        omegas = parse_floats(omega, "omega")
        target = None
        if goal is not None:
            target = ConfigSet.parse(goal)
            stable = list(the_part.stable_sides)
            for s in target.sides:
                if s not in stable:
                    raise InvalidStateError("goal", f"side {s} is not a stable side of {the_part.name} "
                                                    f"(stable sides: {stable})")
        fmt = figure_format(plot, "plot")
        check_out_dir(out)
        limits = work_limits(max_memory, max_time, force)
        with _option_names(), _progress() as bar:
            graph = funnels(the_part, arm, omegas, model, goal=target, grid=grid, containment=containment, limits=limits, **opts,
                            **sysk,
                            rng=seed, x_max=x_max, method=method, n_seeds=starts, progress=bar)
        if plot is not None:
            from ..viz.funnels import plot_funnel_graph

            save_figure(plot_funnel_graph(graph), plot, fmt, "plot")
        doc = {**graph.to_dict(), "part": the_part.name, "arm": arm_dict(arm), **system_doc(sysk), "omegas": omegas,
               "model": model, "seed": seed, "plot": str(plot) if plot is not None else None,
               "model_options": options_doc(opts), "version": __version__}
        written = [plot] if plot is not None else []
        if out is not None:
            make_out_dir(out)
            write_text(out / "funnels.json", to_json(doc) + "\n", "out")
            written.append(out / "funnels.json")
        if as_json:
            typer.echo(to_json(doc))
            return
        typer.echo(graph.table())
        for p in written:
            typer.echo(f"wrote {p}")


def register(app: typer.Typer) -> None:
    """Add the ``limitset``, ``basins`` and ``funnels`` commands to ``app``."""
    app.command("limitset")(limitset_cmd)
    app.command("basins")(basins_cmd)
    app.command("funnels")(funnels_cmd)
