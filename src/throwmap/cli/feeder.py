"""``throwmap feeder design PART --out DIR``: search a feeder for a part, verify it in the engine, say the verdict.

A thin shell over :func:`throwmap.feeder.search.design_feeder`: the exact-model screen, then engine
verification of the best candidates (feeding experiment, ≥ ``--n`` trials and an independent rerun).
Exit 0 with a verified feeder (``DIR/feeder.toml`` runs as ``throwmap experiment feed DIR/feeder.toml``),
1 without one (the reason says why), 2 on bad input.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from .options import JsonOpt, guard, to_json
from .usage import ThrowmapGroup

__all__ = ["register", "feeder_app"]

feeder_app = typer.Typer(name="feeder", cls=ThrowmapGroup, no_args_is_help=True, add_completion=False,
                         pretty_exceptions_enable=False, help="Feeders for any part: search, verify in the engine, write the config.")


@feeder_app.command("design")
def design_cmd(
    part: Annotated[str, typer.Argument(help="Built-in part name or a .toml/.json part file.")],
    out: Annotated[Path, typer.Option("--out", help="Folder for the feeder's files and every candidate tried.")],
    side: Annotated[int | None, typer.Option("--side", help="Side to feed (default: the search chooses).")] = None,
    mu: Annotated[float, typer.Option("--mu", help="Arm friction μ (± 10 % per trial).")] = 1.0,
    budget: Annotated[float, typer.Option("--budget", help="Minutes after which no further candidate is started (one "
                                                           "running is finished).")]
    = 10.0,
    n: Annotated[int, typer.Option("--n", help="Engine trials of a full verification (and of its rerun).")] = 200,
    n_pre: Annotated[int, typer.Option("--n-pre", help="Engine trials a candidate must pass first (90 %).")] = 20,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the verification (the rerun uses seed + 1).")] = 0,
    workers: Annotated[int, typer.Option("--workers", help="Engine processes (0: all cores).")] = 0,
    as_json: JsonOpt = False,
) -> None:
    """Search a feeder that feeds one side of PART into a pocket at the arm's end, verified in the engine."""
    from rich.progress import Progress

    from ..errors import InvalidStateError
    from ..feeder.search import VerifyPlan, design_feeder
    from ..io.config import resolve_part

    with guard():
        import math

        if not (math.isfinite(budget) and budget >= 0):
            raise InvalidStateError("budget", f"must be a number of minutes ≥ 0, got {budget}")
        for name, value in (("n", n), ("n-pre", n_pre)):
            if value < 1:
                raise InvalidStateError(name, f"must be ≥ 1, got {value}")
        if seed < 0:
            raise InvalidStateError("seed", f"must be ≥ 0, got {seed}")
        if workers < 0:
            raise InvalidStateError("workers", f"must be ≥ 0 (0: all cores), got {workers}")
        if not (math.isfinite(mu) and mu >= 0):
            raise InvalidStateError("mu", f"must be a finite number ≥ 0, got {mu}")
        p = resolve_part(part).part
        if side is not None:
            p.check_side(side)
        plan = VerifyPlan(n_pre=n_pre, n_verify=n, seed=seed, workers=workers, budget_s=60.0 * budget)
        with Progress(transient=True, disable=as_json) as bar:
            tasks = {}

            def progress(stage, done, total):
                if stage not in tasks:
                    tasks[stage] = bar.add_task(stage, total=total)
                bar.update(tasks[stage], completed=done)

            res = design_feeder(p, out, side=side, mu=mu, plan=plan, progress=progress)
        if as_json:
            doc = res.to_dict()
            doc["verified"] = (None if res.verified is None else
                               {k: res.verified[k] for k in ("n", "successes", "ci95")})
            typer.echo(to_json(doc))
        else:
            typer.echo(res.screen.table(5))
            for t in res.tried:
                rates = ", ".join(f"{r['successes']}/{r['n']}" for r in t.runs)
                typer.echo(f"  candidate {t.k} (side {t.candidate.side}, ω = {t.candidate.omega:g} rad/s, h = "
                           f"{t.candidate.h:g} m): {rates}: {t.verdict}")
            typer.echo(res.summary())
    if not res.success:
        raise typer.Exit(1)


def register(app: typer.Typer) -> None:
    app.add_typer(feeder_app)
