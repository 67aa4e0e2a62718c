"""``throwmap design passage``: which side reaches an end stop first under the jittered recoil arm.

A thin shell over :func:`throwmap.design.passage.recoil_table` and
:func:`~throwmap.design.passage.first_passage`: tabulates the engine's recoil throw map of a part
(±3σ of ω jitter, every side, a grid in x), runs Markov chains on it and prints, per end-stop
position X (m), the share of chains whose outer vertex first passes X on the target side and on
another side, and whether the target side holds there; then the window of X where an end stop
should feed only the target side. Exit 0 with a window, 1 without one, 2 on bad input.
"""

from __future__ import annotations

import math
from typing import Annotated

import typer

from .options import GOpt, HOpt, JsonOpt, MuOpt, PartOpt, SideOpt, arm_dict, guard, part_and_arm, to_json

__all__ = ["passage_cmd", "feed_search_cmd", "register"]


def passage_cmd(
    part: PartOpt,
    omega: Annotated[float, typer.Option("--omega", help="Nominal release rate ω, rad/s (> 0).")],
    side: SideOpt = 0,
    h: HOpt = None,
    g: GOpt = None,
    mu: MuOpt = None,
    sigma: Annotated[float, typer.Option("--sigma", help="Relative ω jitter per throw (σ).")] = 0.03,
    recoil: Annotated[float, typer.Option("--recoil", help="Recoil depth of the arm, rad.")] = math.radians(3.0),
    zeta: Annotated[float, typer.Option("--zeta", help="Recoil loop damping ratio.")] = 0.2,
    step: Annotated[float, typer.Option("--step", help="Grid step of the table in x, m.")] = 0.005,
    x_max: Annotated[float, typer.Option("--x-max", help="Table reaches this far, m.")] = 0.56,
    n: Annotated[int, typer.Option("--n", help="Markov chains.")] = 3000,
    throws: Annotated[int, typer.Option("--throws", help="Throws per chain.")] = 60,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the chains.")] = 0,
    purity: Annotated[float, typer.Option("--purity", help="Least share first on the target side in the window.")]
    = 0.99,
    workers: Annotated[int, typer.Option("--workers", help="Engine processes for the table (0: all cores).")] = 0,
    as_json: JsonOpt = False,
) -> None:
    """Find where an end stop feeds only the target side under the recoil arm (first passage)."""
    from ..design.passage import check_chains, first_passage, recoil_table
    from ..errors import InvalidStateError

    with guard():
        workers = _workers(workers)
        if not 0.0 <= purity <= 1.0:
            raise InvalidStateError("purity", f"must be in [0, 1], got {purity}")
        check_chains(n, throws, seed)
        p_obj, arm = part_and_arm(part, h, g, None, mu)
        target = p_obj.check_side(side)
        table = recoil_table(p_obj, arm, omega, sigma=sigma, step=step, x_max=x_max, recoil=recoil, zeta=zeta,
                             workers=workers)
        res = first_passage(p_obj, table, target, n=n, throws=throws, seed=seed)
        window = res.window(purity)
        if as_json:
            typer.echo(to_json({"part": p_obj.name, "arm": arm_dict(arm), "omega_rad_s": omega, "side": target,
                                "sigma": sigma, "recoil_rad": recoil, "zeta": zeta, "step_m": step, "n": n,
                                "throws": throws, "seed": seed, "purity": purity, "rows": res.rows(),
                                "window_m": [min(window), max(window)] if window else None}))
        else:
            typer.echo(f"{p_obj.name}: side {target}, ω = {omega:.6g} rad/s ± {100 * sigma:g} %, recoil "
                       f"{math.degrees(recoil):.3g}°, ζ = {zeta:g}; {n} chains × {throws} throws, seed {seed}")
            typer.echo("  X (m)   first on target   first on another   holds")
            for r in res.rows():
                typer.echo(f"  {r['X_m']:.3f}   {r['good']:15.4f}   {r['wrong']:16.4f}   {'yes' if r['holds'] else 'no'}")
            if window:
                typer.echo(f"window (≥ {purity:g} first on side {target}, none first on another, holds): "
                           f"X ∈ [{min(window):.3f}, {max(window):.3f}] m")
            else:
                typer.echo(f"no window: no X has ≥ {purity:g} first on side {target}, none on another, and holds")
    if not window:
        raise typer.Exit(1)


def feed_search_cmd(
    n: Annotated[int, typer.Option("--n", help="Candidates to draw (each ≈ 2,300 engine throws, ≈ 10 s on 2 cores).")]
    = 10,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the candidates.")] = 0,
    purity: Annotated[float, typer.Option("--purity", help="Least share first on the fed side in a window.")] = 0.99,
    workers: Annotated[int, typer.Option("--workers", help="Engine processes (0: all cores).")] = 0,
    as_json: JsonOpt = False,
) -> None:
    """Search feeders for the recoil arm: the draft's plate + lead, ω, h (first-passage screen)."""
    from rich.progress import Progress

    from ..design.examples import plexiglas_triangle
    from ..design.feed_search import search_feeders
    from ..errors import InvalidStateError

    hits = []
    with guard():
        workers = _workers(workers)
        if not 0.0 <= purity <= 1.0:
            raise InvalidStateError("purity", f"must be in [0, 1], got {purity}")
        out = []
        with Progress(transient=True, disable=as_json) as bar:
            task = bar.add_task("candidates", total=n)
            for c in search_feeders(plexiglas_triangle(), n=n, seed=seed, purity=purity, workers=workers,
                                    progress=lambda i, t: bar.update(task, completed=i)):
                out.append(c)
                if c.best is not None:
                    hits.append(c)
        if as_json:
            typer.echo(to_json({"n": n, "seed": seed, "purity": purity, "candidates": [c.to_dict() for c in out]}))
        else:
            typer.echo(f"{n} candidates (seed {seed}): lead 30/50/80 g on the 17 cm plexiglas triangle, "
                       "ω ∈ [3.5, 6.5] rad/s, h ∈ [−5, 0] cm; window = end-stop X with ≥ "
                       f"{purity:g} first on one side, none on another, and that side holding")
            for c in out:
                wins = ", ".join(f"side {k}: [{w[0]:.2f}, {w[1]:.2f}] m" for k, w in c.windows.items() if w)
                typer.echo(f"  #{c.index}: {1000 * c.weight_mass:.0f} g at ({100 * c.weight_at[0]:.3f}, "
                           f"{100 * c.weight_at[1]:.3f}) cm, ω = {c.omega:.4f} rad/s, h = {100 * c.h:.3f} cm: "
                           f"{wins or 'no window'}")
    if not hits:
        raise typer.Exit(1)


def _workers(workers: int) -> int:
    """``--workers``: 0 means all cores; more than the cores are not started."""
    import os

    from ..errors import InvalidStateError

    if workers < 0:
        raise InvalidStateError("workers", f"must be ≥ 0 (0: all cores), got {workers}")
    cores = os.cpu_count() or 1
    return cores if workers == 0 else min(workers, cores)


def register(group: typer.Typer) -> None:
    """Add the ``passage`` and ``feed-search`` subcommands to the ``throwmap design`` group."""
    group.command("passage")(passage_cmd)
    group.command("feed-search")(feed_search_cmd)
