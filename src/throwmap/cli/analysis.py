"""``throwmap limitset``, ``throwmap basins``, ``throwmap funnels``: the analysis of throw maps on the command line.

A thin shell over :mod:`throwmap.analysis` (paper Sec. III-D and I-A): parse, build the
part and arm, call one library function (:func:`~throwmap.analysis.limit_set` with
:func:`~throwmap.analysis.critical_points`, :func:`~throwmap.analysis.basins`,
:func:`~throwmap.analysis.funnels`), print its text (or JSON with ``--json``), and write
figures (``--plot``) and result files (``--out DIR``) atomically. SI units throughout;
the default model is ``rigid_body``, as in the library. Errors follow
:mod:`throwmap.cli.app`: one ``error: <field>: <reason>`` line on stderr, exit 2.

A progress bar (Rich, on stderr) is drawn while the maps are iterated, when stderr
is a terminal; redirected output stays clean.
"""

# no ``from __future__ import annotations``: Typer evaluates the option annotations, which
# are imported from throwmap.cli.app inside register() (so cli.py may import this module anywhere).
import io as _io
import os
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated

import typer

from ..errors import ConfigError, InvalidStateError, ThrowmapError

__all__ = ["register", "orbit_on_attractor", "ORBIT_THROWS", "ORBIT_LEAD_MAX", "JSON_ARRAYS_MAX", "OPTION_FIELDS"]

ORBIT_THROWS = 40
"""Throws of the orbit drawn on the limit-set figure (``limitset --plot``)."""
ORBIT_LEAD_MAX = 1000
"""Most throws thrown (and not drawn) to bring that orbit onto its attractor."""
JSON_ARRAYS_MAX = 200_000
"""``basins --out`` puts the per-configuration arrays into ``basins.json`` up to this many
configurations; above it the JSON holds the summary and the arrays are in ``basins.npz`` only."""


# ------------------------------------------------------------------ helpers (no physics)
def orbit_on_attractor(part, arm, omega: float, model: str, limit, n: int = ORBIT_THROWS):
    """An orbit of ``n`` throws lying on the limit set, for drawing (paper Fig. 5).

    Starts from the first of ``limit``'s starting configurations that ends on an
    attractor, throws it as many times as the recurrence test discarded (at most
    :data:`ORBIT_LEAD_MAX`), and returns the next ``n`` throws as an
    :class:`~throwmap.throws.orbit.Orbit`. Where every start escapes, the orbit of the first
    start is returned (it ends with its escape).
    """
    import numpy as np

    from ..throws.orbit import iterate

    on = np.flatnonzero(np.asarray(limit.labels) >= 1)
    i = int(on[0]) if on.size else 0
    x0, s0 = float(limit.starts_x[i]), int(limit.starts_side[i])
    if on.size:
        lead = min(int(limit.caps.get("transient_used", limit.caps.get("transient", 0))), ORBIT_LEAD_MAX)
        if lead > 0:
            pre = iterate(part, arm, (x0, s0), omega, n=lead, model=model)
            if not pre.escaped:
                x0, s0 = float(pre.x[-1]), int(pre.side[-1])
    return iterate(part, arm, (x0, s0), omega, n=n, model=model)


def _stderr_console():
    from rich.console import Console

    return Console(stderr=True)


@contextmanager
def _progress():
    """Yields ``update(stage, done, total)``: one Rich bar per stage on stderr (a no-op off a terminal)."""
    console = _stderr_console()
    if not console.is_terminal:
        yield lambda stage, done, total: None
        return
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

    with Progress(TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                  console=console, transient=True) as bar:
        tasks: dict = {}

        def update(stage, done, total):
            if stage not in tasks:
                tasks[stage] = bar.add_task(str(stage), total=total)
            bar.update(tasks[stage], completed=done, total=total)

        yield update


OPTION_FIELDS = {"n_starts": "starts", "n_seeds": "starts", "n_record": "record", "n_check": "check"}
"""Library argument names that the command line calls differently (errors name the option)."""


@contextmanager
def _option_names():
    """Re-raise a library error on ``n_starts`` (…) as one on the option the user typed (``starts``)."""
    try:
        yield
    except ThrowmapError as err:
        if err.field in OPTION_FIELDS:
            raise type(err)(OPTION_FIELDS[err.field], err.reason) from None
        raise


def _figure_format(path: Path | None, field: str) -> str | None:
    """Check a figure path (directory exists, image type known) before any work; its format."""
    if path is None:
        return None
    from .app import _check_output, _plot_format

    _check_output(path, field)
    os.environ.setdefault("MPLBACKEND", "Agg")  # files only, never a window
    try:
        return _plot_format(path)
    except ThrowmapError as err:
        raise ConfigError(field, err.reason) from None


def _check_out_dir(out: Path | None) -> None:
    if out is not None and out.exists() and not out.is_dir():
        raise ConfigError("out", f"{out} exists and is not a directory")


def _make_out_dir(out: Path) -> None:
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as err:
        raise ConfigError("out", f"cannot create {out}: {err.strerror or err}") from None


def _write_bytes(path: Path, data: bytes, field: str) -> None:
    from ..io.files import atomic_write_bytes

    try:
        atomic_write_bytes(path, data)
    except OSError as err:
        raise ConfigError(field, f"cannot write {path}: {err.strerror or err}") from None


def register(app: typer.Typer) -> None:
    """Add the ``limitset``, ``basins`` and ``funnels`` commands to ``app``."""
    from .. import __version__
    from ..analysis.limitset import DEFAULT_CAPS
    from .app import (GOpt, HOpt, JsonOpt, LengthOpt, MuOpt, PartOpt, _arm_dict, _finite, _floats, _guard,
                      _part_and_arm, _save_figure, _to_json, _write_text)
    from ..throws.throw import MODELS, check_model

    OmegaOpt = Annotated[float, typer.Option("--omega", help="Release angular velocity ω, rad/s (≥ 0).")]
    ModelOpt = Annotated[str, typer.Option("--model", help=f"Throw model: {', '.join(MODELS)}.")]
    XMaxOpt = Annotated[float | None, typer.Option("--x-max", help="Outer end of the analysed configurations, m "
                                                                  "(default: the arm length, else 0.6).")]
    SeedOpt = Annotated[int, typer.Option("--seed", help="Seed of the random starts and checks (same seed, same "
                                                         "result).")]
    StartsOpt = Annotated[int, typer.Option("--starts", help="Starting configurations per stable side for the "
                                                             "limit-set search (stratified, drawn with --seed).")]
    TransientOpt = Annotated[int | None, typer.Option("--transient", help="Throws discarded before recording "
                                                                          f"(default {DEFAULT_CAPS['transient']}).")]
    RecordOpt = Annotated[int | None, typer.Option("--record", help="Throws recorded per orbit "
                                                                    f"(default {DEFAULT_CAPS['n_record']}).")]

    # -------------------------------------------------------------- limitset
    @app.command("limitset")
    def limitset_cmd(
        part: PartOpt,
        omega: OmegaOpt,
        h: HOpt = None,
        g: GOpt = None,
        length: LengthOpt = None,
        mu: MuOpt = None,
        model: ModelOpt = "rigid_body",
        x_max: XMaxOpt = None,
        starts: StartsOpt = 64,
        transient: TransientOpt = None,
        record: RecordOpt = None,
        tol: Annotated[float | None, typer.Option("--tol", help="Recurrence tolerance, m "
                                                                f"(default {DEFAULT_CAPS['tol']:g}).")] = None,
        max_period: Annotated[int | None, typer.Option("--max-period", help="Longest cycle looked for "
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
    ) -> None:
        """Critical points r_i, l_i and the forward limit set(s) of the throw map T^ω (paper Sec. III-D)."""
        from ..analysis import critical_points, limit_set

        with _guard():
            check_model(model)
            the_part, arm = _part_and_arm(part, h, g, length, mu)
            _finite(omega, "omega")
            fmt = _figure_format(plot, "plot")
            fmt_map = _figure_format(plot_map, "plot_map")
            _check_out_dir(out)
            crit = critical_points(the_part, arm, omega, model, x_max=x_max)
            with _option_names(), _progress() as bar:
                limit = limit_set(the_part, arm, omega, model, n_starts=starts, rng=seed, x_max=x_max,
                                  transient=transient, n_record=record, tol=tol, max_period=max_period,
                                  progress=lambda done, total: bar("iterating", done, total))
            if plot is not None:
                from ..viz.limit_set import plot_limit_set

                orbit = orbit_on_attractor(the_part, arm, omega, model, limit)
                _save_figure(plot_limit_set(limit, critical=crit, orbit=orbit), plot, fmt, "plot")
            if plot_map is not None:
                from ..throws.samples import sample_map
                from ..analysis.maps import ThrowMap

                cmap = ThrowMap(the_part, arm, omega, model, x_max)
                _save_figure(sample_map(cmap).plot(critical=crit, limit=limit), plot_map, fmt_map, "plot_map")
            doc = {"limit_set": limit.to_dict(), "critical_points": crit.to_dict(), "part": the_part.name,
                   "arm": _arm_dict(arm), "omega": omega, "model": model, "seed": seed,
                   "plot": str(plot) if plot is not None else None,
                   "plot_map": str(plot_map) if plot_map is not None else None, "version": __version__}
            written = [p for p in (plot, plot_map) if p is not None]
            if out is not None:
                _make_out_dir(out)
                _write_text(out / "limit_set.json", _to_json(doc) + "\n", "out")
                written.append(out / "limit_set.json")
            if as_json:
                typer.echo(_to_json(doc))
                return
            typer.echo(f"{the_part.name}: ω = {omega:g} rad/s, h = {arm.h:g} m, model {model!r}")
            typer.echo("critical points (r_i: jogs end; l_i = inf S):")
            typer.echo(crit.table())
            typer.echo("")
            typer.echo(limit.summary())
            for p in written:
                typer.echo(f"wrote {p}")

    # -------------------------------------------------------------- basins
    @app.command("basins")
    def basins_cmd(
        part: PartOpt,
        omega: OmegaOpt,
        h: HOpt = None,
        g: GOpt = None,
        length: LengthOpt = None,
        mu: MuOpt = None,
        model: ModelOpt = "rigid_body",
        x_max: XMaxOpt = None,
        grid: Annotated[int, typer.Option("--grid", help="Configurations per stable side (≥ 2), evenly spaced "
                                                         "up to --x-max.")] = 1000,
        method: Annotated[str, typer.Option("--method", help="auto (cells above 20 000 configurations), orbits "
                                                             "(exact orbits) or cells (cell-to-cell mapping).")]
        = "auto",
        seed: SeedOpt = 0,
        max_throws: Annotated[int, typer.Option("--max-throws", help="Throw cap per orbit; beyond it an orbit is "
                                                                     "unresolved (label -1).")] = 500,
        check: Annotated[int, typer.Option("--check", help="Configurations checked by exact orbits "
                                                           "(cells method; 0: none).")] = 1000,
        starts: StartsOpt = 64,
        transient: TransientOpt = None,
        record: RecordOpt = None,
        as_json: JsonOpt = False,
        plot: Annotated[Path | None, typer.Option("--plot", help="Write the basin map, e.g. basins.png.")] = None,
        out: Annotated[Path | None, typer.Option("--out", help="Directory for basins.json and basins.npz "
                                                               "(created).")] = None,
    ) -> None:
        """Basins of attraction over a grid of configurations, with a certificate of global attractivity."""
        from ..analysis import basins

        with _guard():
            check_model(model)
            the_part, arm = _part_and_arm(part, h, g, length, mu)
            _finite(omega, "omega")
            fmt = _figure_format(plot, "plot")
            _check_out_dir(out)
            with _option_names(), _progress() as bar:
                result = basins(the_part, arm, omega, model, grid=grid, method=method, rng=seed,
                                max_throws=max_throws, n_check=check, n_seeds=starts, transient=transient,
                                n_record=record, x_max=x_max, progress=bar)
            if plot is not None:
                from ..viz.basins import plot_basins

                _save_figure(plot_basins(result), plot, fmt, "plot")
            extra = {"part": the_part.name, "arm": _arm_dict(arm), "omega": omega, "model": model, "seed": seed,
                     "plot": str(plot) if plot is not None else None, "version": __version__}
            written = [plot] if plot is not None else []
            if out is not None:
                import numpy as np

                _make_out_dir(out)
                with_arrays = result.n_configs <= JSON_ARRAYS_MAX
                buf = _io.BytesIO()
                np.savez_compressed(buf, x=result.x, side=result.side, labels=result.labels, fates=result.fates,
                                    throws=result.throws)
                _write_bytes(out / "basins.npz", buf.getvalue(), "out")
                full = {**result.to_dict(arrays=with_arrays), **extra, "arrays": "basins.npz" if not with_arrays
                        else "grid (also in basins.npz)"}
                _write_text(out / "basins.json", _to_json(full) + "\n", "out")
                written += [out / "basins.json", out / "basins.npz"]
            if as_json:
                typer.echo(_to_json({**result.to_dict(arrays=False), **extra}))
                return
            typer.echo(result.summary())
            for p in written:
                typer.echo(f"wrote {p}")

    # -------------------------------------------------------------- funnels
    @app.command("funnels")
    def funnels_cmd(
        part: PartOpt,
        omega: Annotated[list[str], typer.Option("--omega", help="Release rates ω, rad/s, one funnel map each "
                                                                 "(repeat the option or give a comma list).")],
        h: HOpt = None,
        g: GOpt = None,
        length: LengthOpt = None,
        mu: MuOpt = None,
        model: ModelOpt = "rigid_body",
        x_max: XMaxOpt = None,
        goal: Annotated[str | None, typer.Option("--goal", help="Goal configurations 'side:lo-hi, …' in m "
                                                                "(e.g. '0:0.50-0.90'); none: no priorities.")]
        = None,
        grid: Annotated[int, typer.Option("--grid", help="Configurations per stable side for each map's basins "
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
    ) -> None:
        """Funnels (mouth: basin, spout: attractor) of several throws and the priority order to a goal (Sec. I-A)."""
        from ..analysis import ConfigSet, funnels

        with _guard():
            check_model(model)
            the_part, arm = _part_and_arm(part, h, g, length, mu)
            omegas = _floats(omega, "omega")
            target = None
            if goal is not None:
                target = ConfigSet.parse(goal)
                stable = list(the_part.stable_sides)
                for s in target.sides:
                    if s not in stable:
                        raise InvalidStateError("goal", f"side {s} is not a stable side of {the_part.name} "
                                                        f"(stable sides: {stable})")
            fmt = _figure_format(plot, "plot")
            _check_out_dir(out)
            with _option_names(), _progress() as bar:
                graph = funnels(the_part, arm, omegas, model, goal=target, grid=grid, containment=containment,
                                rng=seed, x_max=x_max, method=method, n_seeds=starts, progress=bar)
            if plot is not None:
                from ..viz.funnels import plot_funnel_graph

                _save_figure(plot_funnel_graph(graph), plot, fmt, "plot")
            doc = {**graph.to_dict(), "part": the_part.name, "arm": _arm_dict(arm), "omegas": omegas,
                   "model": model, "seed": seed, "plot": str(plot) if plot is not None else None,
                   "version": __version__}
            written = [plot] if plot is not None else []
            if out is not None:
                _make_out_dir(out)
                _write_text(out / "funnels.json", _to_json(doc) + "\n", "out")
                written.append(out / "funnels.json")
            if as_json:
                typer.echo(_to_json(doc))
                return
            typer.echo(graph.table())
            for p in written:
                typer.echo(f"wrote {p}")
