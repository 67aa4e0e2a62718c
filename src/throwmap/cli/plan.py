"""``throwmap plan …``: inverse throws and open-loop plans on the command line (paper Sec. IV).

A thin shell over :mod:`throwmap.control.inverse` and :mod:`throwmap.control.planner`:

``throwmap plan jog``            the rate that jogs (x, side) to --target on the same side (Lemma 4.2)
``throwmap plan route``          a throw sequence to (--to-x, --to-side), or why it is unreachable (Prop. 4.3)
``throwmap plan check-inverse``  inverse throws checked by forward throws on every model (a table)

Errors: one ``error: <field>: <reason>`` line, exit 2 (:mod:`throwmap.cli.options`). SI units.
"""

from __future__ import annotations

from typing import Annotated

import typer

from ..version import __version__
from ..models import DEFAULT_MODEL
from .options import (BackOpt, GOpt, HOpt, JsonOpt, LengthOpt, ModelOpt, ModelOptionOpt, MuOpt, PartOpt, SideOpt,
                      XOpt, arm_dict, check_finite, guard, model_options, parse_floats, part_and_arm, strict_int,
                      to_json)
from .usage import ThrowmapGroup

__all__ = ["register", "plan_app"]

plan_app = typer.Typer(name="plan", cls=ThrowmapGroup, no_args_is_help=True, add_completion=False,
                       pretty_exceptions_enable=False,
                       help="Inverse throws and open-loop throw plans (paper Sec. IV: Lemmas 4.1, 4.2, Prop. 4.3).")

RealisationOpt = Annotated[str | None, typer.Option(
    "--realisation", help="How the arm throws: impulse (default) or recoil (the draft's arm; models that take "
                          "realisations: engine).")]
OmegaMaxOpt = Annotated[float, typer.Option("--omega-max", help="Largest jog rate searched, rad/s.")]


@plan_app.command("jog")
def jog_cmd(
    part: PartOpt = "triangle",
    x: XOpt = 0.25,
    side: SideOpt = 0,
    target: Annotated[float, typer.Option("--target", help="Where the jog should land, m (CM x, same side).")] = 0.27,
    model: ModelOpt = DEFAULT_MODEL,
    model_option: ModelOptionOpt = None,
    realisation: RealisationOpt = None,
    omega_max: OmegaMaxOpt = 10.0,
    tol: Annotated[float, typer.Option("--tol", help="Accepted |T(ω) − target|, m.")] = 1e-6,
    h: HOpt = None, g: GOpt = None, length: LengthOpt = None, mu: MuOpt = None, back: BackOpt = None,
    as_json: JsonOpt = False,
) -> None:
    """The release rate ω whose throw jogs (x, side) to --target (Lemma 4.2, monotonicity checked)."""
    from ..control.inverse import inverse_jog

    with guard():
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        opts = model_options(model_option, model)
        for v, f in ((x, "x"), (target, "target"), (omega_max, "omega_max"), (tol, "tol")):
            check_finite(v, f)
        r = inverse_jog(the_part, arm, x, side, target, model, omega_max=omega_max, tol=tol, realisation=realisation,
                        **opts)
        if as_json:
            doc = {k: getattr(r, k) for k in ("omega", "x", "residual", "x0", "side", "x_target", "omega_flip",
                                              "beyond", "reach", "monotone", "model", "n_throws", "scatter")}
            typer.echo(to_json({**doc, "part": the_part.name, "arm": arm_dict(arm), "version": __version__}))
        else:
            typer.echo(r.summary())


@plan_app.command("route")
def route_cmd(
    part: PartOpt = "triangle",
    x: XOpt = 0.2,
    side: SideOpt = 0,
    to_x: Annotated[float, typer.Option("--to-x", help="Goal CM x, m.")] = 0.45,
    to_side: Annotated[int, typer.Option("--to-side", parser=strict_int, metavar="INTEGER", help="Goal side.")] = 1,
    omegas: Annotated[str, typer.Option("--omegas", help="High rates offered for going round the limit set, rad/s "
                                                         "(comma list, tried in order).")] = "5.6,4.0",
    model: ModelOpt = DEFAULT_MODEL,
    model_option: ModelOptionOpt = None,
    max_throws: Annotated[int, typer.Option("--max-throws", help="Throws allowed per attempt.")] = 500,
    x_max: Annotated[float | None, typer.Option("--x-max", help="Range the limit sets are searched on, m "
                                                                "(default: the arm length, else 0.6).")] = None,
    h: HOpt = None, g: GOpt = None, length: LengthOpt = None, mu: MuOpt = None, back: BackOpt = None,
    as_json: JsonOpt = False,
) -> None:
    """A throw plan from (x, side) to (--to-x, --to-side): round the limit set, then jogs; or why not.

    Exit status 0 when a plan reaches the goal, 1 when it is unreachable (the reason is printed)."""
    from ..control.planner import plan_throws

    with guard():
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        opts = model_options(model_option, model)
        check_finite(x, "x")
        check_finite(to_x, "to_x")
        rates = parse_floats(omegas, "omegas")
        p = plan_throws(the_part, arm, x, side, to_x, to_side, omegas=rates, model=model, max_throws=max_throws,
                        x_max=x_max, **opts)
        if as_json:
            doc = {"reachable": p.reachable, "explanation": p.explanation, "model": p.model, "x0": p.x0,
                   "side0": p.side0, "x_f": p.x_f, "side_f": p.side_f, "final": list(p.final), "error_m": p.error,
                   "steps": [s.__dict__ for s in p.steps], "part": the_part.name, "arm": arm_dict(arm),
                   "version": __version__}
            typer.echo(to_json(doc))
        else:
            typer.echo(p.summary())
            if p.steps:
                typer.echo(p.table())
    if not p.reachable:
        raise typer.Exit(1)


@plan_app.command("check-inverse")
def check_cmd(
    part: PartOpt = "triangle",
    models: Annotated[str, typer.Option("--models", help="Comma list of models.")] =
        "paper,small_angle,small_angle2,rigid_body,engine",
    n: Annotated[int, typer.Option("--n", help="Random problems per model.")] = 20,
    seed: Annotated[int, typer.Option("--seed", help="Seed of the problems.")] = 0,
    tol: Annotated[float, typer.Option("--tol", help="Accepted forward |x − target|, m.")] = 1e-6,
    h: HOpt = None, g: GOpt = None, length: LengthOpt = None, mu: MuOpt = None, back: BackOpt = None,
    as_json: JsonOpt = False,
) -> None:
    """Inverse throws checked against forward throws on every model: random starts and targets, a table."""
    from ..control.inverse_check import HEADER, check_inverse
    from ..models import get_model

    with guard():
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        names = tuple(get_model(m.strip()).name for m in models.split(",") if m.strip())
        if n < 1:
            from ..errors import InvalidStateError

            raise InvalidStateError("n", f"must be ≥ 1, got {n}")
        check_finite(tol, "tol")
        rows = check_inverse(the_part, arm, names, n=n, seed=seed, tol=tol)
        if as_json:
            typer.echo(to_json({"part": the_part.name, "arm": arm_dict(arm), "n": n, "seed": seed, "tol_m": tol,
                                "rows": [{k: v for k, v in r.__dict__.items() if k != "cases"} | {"cases": [list(c) for c in r.cases]}
                                         for r in rows], "version": __version__}))
        else:
            typer.echo(f"{the_part.name}, arm h = {arm.h} m, μ = {arm.mu}: {n} random problems per model, seed {seed}, "
                       f"tol {tol * 1e6:g} µm")
            typer.echo(HEADER)
            for r in rows:
                typer.echo(r.line(tol))


def register(app: typer.Typer) -> None:
    app.add_typer(plan_app)
