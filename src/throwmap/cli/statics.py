"""``throwmap statics …``: rest of parts against the wall and each other (paper Sec. VI, Figs. 13, 14).

``throwmap statics lean``     Fig. 13: leaning against a frictionless wall — closed form vs LP vs engine
``throwmap statics partial``  Fig. 14: the partial assembly over γ — friction needed (LP) vs engine

Errors: one ``error: <field>: <reason>`` line, exit 2 (:mod:`throwmap.cli.options`). SI units; angles in
degrees on this command line (as the draft states them), radians in the library.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated

import typer

from ..budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, cli_limits
from .options import (ForceOpt, MaxMemoryOpt, MaxTimeOpt, check_finite, figure_format, guard, save_figure)
from .usage import ThrowmapGroup

__all__ = ["register", "statics_app"]

statics_app = typer.Typer(name="statics", cls=ThrowmapGroup, no_args_is_help=True, add_completion=False,
                          pretty_exceptions_enable=False,
                          help="Statics of parts on a tilted arm, against the wall and each other (Sec. VI, "
                               "Figs. 13, 14): LP over friction cones, closed forms, engine rest checks.")
PlotOpt = Annotated[Path | None, typer.Option("--plot", help="Write the figure analogue (PNG/PDF/SVG).")]
AlphaDegOpt = Annotated[float, typer.Option("--alpha-deg", help="Arm rest angle α, degrees (draft: −10).")]
EngineOpt = Annotated[bool, typer.Option("--engine/--no-engine", help="Check each placement in the engine.")]


@statics_app.command("lean")
def lean_cmd(
    n: Annotated[int, typer.Option("--n", help="Random leans (β, α, μ) compared.")] = 200,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the leans.")] = 0,
    alpha_deg: AlphaDegOpt = -10.0,
    mu: Annotated[float, typer.Option("--mu", help="Arm μ of the figure and of the lean-free angle.")] = 2.0,
    engine: EngineOpt = True,
    plot: PlotOpt = None,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Fig. 13: can the draft's triangle lean on a frictionless wall? Closed form vs LP vs engine, the lean-free β."""
    import throwmap as tm

    from ..statics import edge_frame_cm, lean_free_beta
    from ..statics.tables import lean_table

    with guard():
        if n < 1:
            from ..errors import InvalidStateError

            raise InvalidStateError("n", f"must be ≥ 1, got {n}")
        _check_alpha_mu(alpha_deg, mu)
        fmt = figure_format(plot, "plot")
        part = tm.triangle_30_60_90()
        a, b, c = edge_frame_cm(part)
        alpha = math.radians(alpha_deg)
        typer.echo(f"{part.name}: CM at ({a:.4f}, {b:.4f})·c along/off the hypotenuse from its 30° vertex, c = {c} m "
                   f"(the draft's 0.58 and 0.14)")
        for m in (1.0, 2.0, mu) if mu not in (1.0, 2.0) else (1.0, 2.0):
            typer.echo(f"  α = {alpha_deg:g}°, μ = {m:g}: no lean below β* = {lean_free_beta(a, b, alpha, m):.4f} rad")
        t = lean_table(part, n=n, seed=seed, engine=engine, limits=cli_limits(max_memory, max_time, force))
        for line in t.lines():
            typer.echo(line)
        if plot is not None:
            from ..statics.figures import lean_data

            save_figure(lean_data(part, alpha=alpha, beta_show=0.5, mu_show=mu).plot(), plot, fmt, "plot")
            typer.echo(f"wrote {plot}")


@statics_app.command("partial")
def partial_cmd(
    alpha_deg: AlphaDegOpt = -10.0,
    mu: Annotated[float, typer.Option("--mu", help="Arm μ at which rest is checked (draft: measured > 1).")] = 1.0,
    engine: EngineOpt = True,
    plot: PlotOpt = None,
) -> None:
    """Fig. 14: the partial assembly of two triangles at the wall, γ from −29° to −1°: μ needed, LP, engine."""
    import throwmap as tm

    from ..statics.tables import partial_table

    with guard():
        _check_alpha_mu(alpha_deg, mu)
        fmt = figure_format(plot, "plot")
        part = tm.triangle_30_60_90()
        typer.echo(f"partial assembly of two {part.name} at a frictionless wall, frictionless parts, "
                   f"α = {alpha_deg:g}°, arm μ = {mu:g}:")
        typer.echo(partial_table(part, alpha_deg=alpha_deg, mu=mu, engine=engine).table())
        if plot is not None:
            from ..statics.figures import partial_data

            data = partial_data(part, alpha=math.radians(alpha_deg), gamma_show=math.radians(-15), mu_show=mu)
            save_figure(data.plot(), plot, fmt, "plot")
            typer.echo(f"wrote {plot}")


def _check_alpha_mu(alpha_deg: float, mu: float) -> None:
    """α in (−90°, 90°) and μ ≥ 0 (∞ allowed: no slip), else one line naming the option."""
    import math

    from ..errors import InvalidStateError

    check_finite(alpha_deg, "alpha_deg")
    if not -90.0 < alpha_deg < 90.0:
        raise InvalidStateError("alpha_deg", f"must be in (-90, 90) degrees, got {alpha_deg:g}")
    if math.isnan(mu) or mu < 0:
        raise InvalidStateError("mu", f"must be ≥ 0 (inf: no slip), got {mu:g}")


def register(app: typer.Typer) -> None:
    app.add_typer(statics_app)
