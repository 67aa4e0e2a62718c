"""``throwmap feeder design PART --out DIR``: search a feeder for a part, verify it in the engine, say the verdict.

A thin shell over :func:`throwmap.feeder.search.design_feeder`: the exact-model screen, short engine runs of
the feeding experiment that rank the candidates, then engine verification of the best (``--n`` trials, an
independent rerun, ω ± 3 %), and the design sheet of a feeder found.
Exit 0 with a verified feeder (``DIR/feeder.toml`` runs as ``throwmap experiment feed DIR/feeder.toml``),
1 without one (the reason says why), 2 on bad input.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from .options import JsonOpt, check_out_dir, guard, stage_bars, to_json
from .usage import ThrowmapGroup

END_S = 5.0
"""Seconds of ``--budget`` kept for writing the result at the end."""


def _started_s() -> float:
    """Seconds since this process started (its imports count against ``--budget``); 0 where it cannot be read."""
    import time

    try:
        import psutil

        return max(time.time() - psutil.Process().create_time(), 0.0)
    except Exception:  # noqa: BLE001 - no psutil, or no access: count from now
        return 0.0


SHEET_S = 60.0
"""Seconds of ``--budget`` kept for the design sheet (its margins and drawing) when margins are measured."""

DRAW_S = 25.0
"""Seconds of the sheet's share kept for its drawing and the fed trial's replay; the rest may finish a verification
or rerun under way (the margins then get what is left, possibly nothing)."""

__all__ = ["register", "feeder_app"]

feeder_app = typer.Typer(name="feeder", cls=ThrowmapGroup, no_args_is_help=True, add_completion=False,
                         pretty_exceptions_enable=False, help="Feeders for any part: search, verify in the engine, write the config.")


@feeder_app.command("design")
def design_cmd(
    part: Annotated[str, typer.Argument(help="Built-in part name or a .toml/.json part file.")],
    out: Annotated[Path, typer.Option("--out", help="Folder for the feeder's files and every candidate tried.")],
    side: Annotated[int | None, typer.Option("--side", help="Side to feed (default: the search chooses); one the bare part cannot rest on is searched with the lead weights that make it stable.")] = None,
    weight: Annotated[str, typer.Option("--weight", help="Lead weight: 'auto' (none or up to 1.7 × the part's mass), "
                                                          "'none', or the heaviest allowed in kg.")] = "auto",
    arm_length: Annotated[float | None, typer.Option("--arm-length", help="Longest arm allowed, m (the end wall is at "
                                                                          "most there; default: 0.6 m).")] = None,
    mu: Annotated[float, typer.Option("--mu", help="Arm friction μ (± 10 % per trial).")] = 1.0,
    budget: Annotated[float, typer.Option("--budget", help="Minutes for the whole design: no candidate is started "
                                                           "after 3/4 of them, no trial after them (the design "
                                                           "sheet gets the last minute, which a verification under "
                                                           "way may use to finish).")]
    = 10.0,
    n: Annotated[int, typer.Option("--n", help="Engine trials of a full verification (and of its rerun).")] = 200,
    n_pre: Annotated[int, typer.Option("--n-pre", help="Engine trials a candidate must pass first (90 %).")] = 20,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the verification (the rerun uses seed + 1).")] = 0,
    workers: Annotated[int, typer.Option("--workers", help="Engine processes (0: all cores).")] = 0,
    omegas: Annotated[list[float] | None, typer.Option("--omega", help="Release rate to search, rad/s (repeat the "
                                                                       "option for several; default 3.5–6 by 0.5).")]
    = None,
    hs: Annotated[list[float] | None, typer.Option("--h", help="Arm surface height to search, m (repeat for several; "
                                                               "default -0.03, -0.02, -0.01, 0).")] = None,
    candidates: Annotated[int, typer.Option("--candidates", help="Most candidates run in the engine (the budget "
                                                                 "usually ends the search first).")] = 120,
    margin_trials: Annotated[int, typer.Option("--margin-trials", help="Engine trials per margin step of the design "
                                                                       "sheet (0: no margins).")] = 30,
    omega_check: Annotated[int, typer.Option("--omega-check", help="Engine trials at each of ω(1 ± 3 %) before a "
                                                                   "candidate's verification (0: no check).")] = 30,
    weight_check: Annotated[int, typer.Option("--weight-check", help="Engine trials with the lead weight moved 1.5 "
                                                                     "mm each way in x and y before a candidate's "
                                                                     "verification (0: no check).")] = 30,
    as_json: JsonOpt = False,
) -> None:
    """Search a feeder that feeds one side of PART into a pocket at the arm's end, verified in the engine."""
    from ..errors import InvalidStateError
    from ..feeder.search import VerifyPlan, design_feeder
    from ..io.config import resolve_part

    with guard():
        import math

        if not (math.isfinite(budget) and budget > 0):
            raise InvalidStateError("budget", f"must be a number of minutes > 0, got {budget}")
        for name, value in (("n", n), ("n-pre", n_pre), ("candidates", candidates)):
            if value < 1:
                raise InvalidStateError(name, f"must be ≥ 1, got {value}")
        for name, value in (("omega-check", omega_check), ("weight-check", weight_check)):
            if value < 0:
                raise InvalidStateError(name, f"must be ≥ 0 (0: no check), got {value}")
        if margin_trials < 0:
            raise InvalidStateError("margin-trials", f"must be ≥ 0 (0: no margins), got {margin_trials}")
        for name, values in (("omega", omegas), ("h", hs)):
            for value in values or ():
                if not math.isfinite(value) or (name == "omega" and value <= 0):
                    raise InvalidStateError(name, f"must be a finite number{' > 0' if name == 'omega' else ''}, "
                                                  f"got {value}")
        if seed < 0:
            raise InvalidStateError("seed", f"must be ≥ 0, got {seed}")
        if workers < 0:
            raise InvalidStateError("workers", f"must be ≥ 0 (0: all cores), got {workers}")
        if not (math.isfinite(mu) and mu >= 0):
            raise InvalidStateError("mu", f"must be a finite number ≥ 0, got {mu}")
        if weight not in ("auto", "none"):
            try:
                weight_kg = float(weight)
            except ValueError:
                raise InvalidStateError("weight", f"must be 'auto', 'none' or a mass in kg, got {weight!r}") from None
            if not (math.isfinite(weight_kg) and weight_kg >= 0):
                raise InvalidStateError("weight", f"must be a mass ≥ 0 kg, got {weight!r}")
        else:
            weight_kg = weight
        if arm_length is not None and not (math.isfinite(arm_length) and arm_length > 0):
            raise InvalidStateError("arm-length", f"must be a length > 0 m, got {arm_length}")
        check_out_dir(out)  # before any work: only DIR itself is made, never a missing folder above it
        p = resolve_part(part).part
        if side is not None:  # unstable on the bare part: refused here only when no weight may make it stable
            p.check_side(side, require_stable=weight == "none" or weight_kg == 0)
        grid = {k: tuple(v) for k, v in (("omegas", omegas), ("hs", hs)) if v}
        sheet_s = min(SHEET_S if margin_trials else 10.0, 30.0 * budget)  # kept for the sheet (≤ half the budget)
        total_s = max(60.0 * budget - _started_s() - END_S, 0.0)  # the budget counts from the command's start
        plan = VerifyPlan(n_pre=n_pre, n_verify=n, seed=seed, workers=workers, budget_s=max(total_s - sheet_s, 0.0),
                          engine_candidates=candidates, omega_check=omega_check, weight_check=weight_check,
                          finish_s=max(sheet_s - DRAW_S, 0.0), **grid)  # a run under way may use the margins' share
        with stage_bars(lines=True) as progress:  # on stderr: stdout keeps the table or the JSON alone
            res = design_feeder(p, out, side=side, weight=weight_kg, arm_length=arm_length, mu=mu, plan=plan,
                                progress=progress)
            if res.success:
                from ..feeder.sheet import write_sheet

                left = total_s - res.time_s - 30.0  # the sheet: what the search left (trials in flight 30 s)
                res = write_sheet(res, out, margin_trials=margin_trials, workers=workers, budget_s=left,
                                  progress=progress)
        if as_json:
            typer.echo(to_json(res.to_dict()))
        else:
            typer.echo(res.table(5))
            typer.echo(res.summary())
            if res.sheet:
                typer.echo(f"design sheet: {res.sheet['files']['html']} (and sheet.md, drawing.svg/.png"
                           + (", fed_trial.html" if "viewer" in res.sheet["files"] else "") + ")")
    if not res.success:
        raise typer.Exit(1)


def register(app: typer.Typer) -> None:
    app.add_typer(feeder_app)
