"""``throwmap design …``: limit-set design on the command line (paper Sec. V).

A thin shell over :mod:`throwmap.design`:

``throwmap design points``           place a lead weight (and set ω, h, …) so that r_i hit targets
``throwmap design example draft``    the draft's Sec. V-B example, reproduced (tables + Fig. 8 analogue)
``throwmap design example feeder``   the realisable feeder design (tables + Fig. 8 analogue)

A ``cavity`` subcommand is added by :mod:`throwmap.cli.cavity` when that module is present
(it defines ``register(group)``). Errors follow :mod:`throwmap.cli.options`: one
``error: <field>: <reason>`` line on stderr, exit 2. SI units (m, kg, rad/s) on input and in JSON.
"""

from __future__ import annotations

import importlib
import importlib.util
from pathlib import Path
from typing import Annotated

import typer

from ..version import __version__
from ..errors import InvalidStateError
from .options import (BackOpt, GOpt, HOpt, JsonOpt, LengthOpt, MuOpt, PartOpt, arm_dict, check_finite,
                      check_output, figure_format, guard, parse_floats, part_and_arm, save_figure, to_json, write_text)
from .usage import ThrowmapGroup

__all__ = ["register", "design_app", "points_cmd", "example_cmd"]

design_app = typer.Typer(name="design", cls=ThrowmapGroup, no_args_is_help=True, add_completion=False,
                         pretty_exceptions_enable=False,
                         help="Limit-set design (paper Sec. V): a lead weight's place, ω, h, α chosen so that the "
                              "limit set's critical points hit targets.")

TargetOpt = Annotated[list[str], typer.Option("--target", metavar="SIDE=R",
                                              help="Target critical point r_i of a side, m; repeatable "
                                                   "(e.g. --target 0=0.30 --target 1=0.175).")]
ModelOpt = Annotated[str, typer.Option("--model", help="Map the features come from: a throw model (rigid_body, "
                                                       "paper, engine, …) or small_angle_F (the draft's corrected "
                                                       "energy test, fast).")]
PlotOpt = Annotated[Path | None, typer.Option("--plot", help="Write the Fig. 8 analogue (each iterate's part beside "
                                                            "its limit set), e.g. design.png.")]


def parse_targets(items: list[str]) -> dict:
    """``["0=0.3", "1=0.175"]`` → ``{0: 0.3, 1: 0.175}`` (m); one-line errors on field ``target``."""
    out = {}
    for item in items or []:
        side, sep, val = item.partition("=")
        if not sep:
            raise InvalidStateError("target", f"must be SIDE=R (e.g. 0=0.30), got {item!r}")
        try:
            s = int(side.strip())
        except ValueError:
            raise InvalidStateError("target", f"side must be an integer, got {side.strip()!r}") from None
        try:
            r = float(val.strip())
        except ValueError:
            raise InvalidStateError("target", f"r must be a number in m, got {val.strip()!r}") from None
        check_finite(r, "target")
        if s in out:
            raise InvalidStateError("target", f"side {s} is given twice")
        out[s] = r
    if not out:
        raise InvalidStateError("target", "give at least one --target SIDE=R")
    return out


def _pair(text: str, field: str) -> tuple:
    v = parse_floats(text, field)
    if len(v) != 2:
        raise InvalidStateError(field, f"must be two numbers X,Y in m, got {text!r}")
    return v[0], v[1]


@design_app.command("points")
def points_cmd(
    part: PartOpt = "triangle",
    omega: Annotated[float, typer.Option("--omega", help="Start release rate ω, rad/s.")] = 5.0,
    target: TargetOpt = None,
    weight_mass: Annotated[float, typer.Option("--weight-mass", help="Lead weight, kg (0: none).")] = 0.03,
    weight_at: Annotated[str | None, typer.Option("--weight-at", metavar="X,Y",
                                                  help="Start place of the weight in the frame of the part's vertices, "
                                                       "m (default: the plate's centroid).")] = None,
    vary: Annotated[str, typer.Option("--vary", help="Comma list of parameters to vary: weight_x, weight_y, "
                                                     "weight_mass, omega, h, alpha.")] = "weight_x,weight_y,omega",
    model: ModelOpt = "rigid_body",
    h: HOpt = None,
    g: GOpt = None,
    length: LengthOpt = None,
    mu: MuOpt = None,
    back: BackOpt = None,
    alpha: Annotated[float | None, typer.Option("--alpha", help="Start arm rest angle α, rad (needs a model with "
                                                                "tilt).")] = None,
    margin: Annotated[float, typer.Option("--margin", help="The weight stays this far inside every edge, m.")] = 0.008,
    tol: Annotated[float, typer.Option("--tol", help="Success when every r_i is within tol of its target, m.")] = 1e-4,
    escape_margin: Annotated[float, typer.Option("--escape-margin", help="Refuse a design whose ω lies within this "
                                                                         "share of ω of where starts begin to escape "
                                                                         "(0: no margins measured).")] = 0.05,
    as_json: JsonOpt = False,
    plot: PlotOpt = None,
) -> None:
    """Place a lead weight (and set ω…) so that the critical points r_i hit --target (paper Sec. V-B).

    A design that reaches its targets then gets its margins (a short continuation of its limit set along ω, and
    along the weight's x and y): the distance to the nearest event, and to where starts begin to escape; within
    --escape-margin × ω of escape it is refused. Exit status 0 when the targets are reached with the margin, 1 when
    the solver stops short or the margin is not met (the message says why), 2 on bad input."""
    from ..design import design
    from ..design.api import SolveOptions, SpaceOptions

    with guard():
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        check_finite(omega, "omega")
        targets = parse_targets(target)
        at = _pair(weight_at, "weight_at") if weight_at is not None else None
        names = tuple(v.strip() for v in vary.split(",") if v.strip())
        fmt = figure_format(plot, "plot")
        if not (escape_margin >= 0 and escape_margin < 1):
            raise InvalidStateError("escape-margin", f"must be a share of ω in [0, 1), got {escape_margin}")
        res = design(the_part, arm, omega, targets, weight_mass=weight_mass, weight_at=at, vary=names, model=model,
                     alpha=alpha, space=SpaceOptions(margin=margin), solve=SolveOptions(tol=tol))
        margins = []
        if res.success and escape_margin > 0:
            res, margins = _with_margins(res, the_part, escape_margin)
        if plot is not None:
            save_figure(res.plot(), plot, fmt, "plot")
        if as_json:
            doc = res.to_dict()
            doc.update({"arm": arm_dict(res.arm), "plot": str(plot) if plot is not None else None,
                        "margins": [m.to_dict() for m in margins], "version": __version__})
            typer.echo(to_json(doc))
        else:
            typer.echo(f"{res.part.name}: h = {res.arm.h:g} m, model {model!r}")
            typer.echo(res.table())
            for m in margins:
                typer.echo(m.text())
            if plot is not None:
                typer.echo(f"wrote {plot}")
    if not res.success:
        raise typer.Exit(1)


def _with_margins(res, plate, share: float):
    """The design's margins along ω (± 3 × ``share`` × ω, at least ± 10 %) and, for a weight on a plate without
    others, along its x and y (± 1 cm); the result refused when escape lies within ``share`` × ω."""
    import dataclasses

    from ..analysis.margins import margin

    opts = {"alpha": res.alpha} if res.alpha else {}
    w = res.omega
    out = [margin(res.part, res.arm, "omega", w, span=max(3 * share, 0.1) * w, model=res.model, **opts)]
    if res.weight_mass > 0 and not plate.point_masses:
        for k, name in enumerate(("weight_x", "weight_y")):
            out.append(margin(res.part, res.arm, name, float(res.weight_at[k]), span=0.01, omega=w, model=res.model,
                              **opts))
    if out[0].escape_distance < share * w:
        res = dataclasses.replace(res, success=False, message=f"targets reached, but within {100 * share:g} % of ω of "
                                                              f"escape: {out[0].text()}")
    return res, out


@design_app.command("example")
def example_cmd(
    name: Annotated[str, typer.Argument(metavar="NAME", help="draft (the draft's Sec. V-B example) or feeder (the "
                                                            "realisable feeder design).")],
    plot: Annotated[Path | None, typer.Option("--plot", help="Write the Fig. 8 analogue here "
                                                            "(default design_NAME.png; 'none' to skip).")] = None,
    engine: Annotated[bool, typer.Option("--engine/--no-engine", help="Also compute the engine's (pymunk) r_i.")]
    = True,
    write_data: Annotated[Path | None, typer.Option("--write-data", help="feeder: write the recomputed design as a "
                                                                         "TOML data file (the format of "
                                                                         "throwmap/data/feeder_design.toml).")] = None,
    as_json: JsonOpt = False,
) -> None:
    """Reproduce a design: print its tables and write its Fig. 8 analogue."""
    from ..design import examples as ex

    with guard():
        if name not in ("draft", "feeder"):
            raise InvalidStateError("name", f"must be draft or feeder, got {name!r}")
        if plot is None:
            plot = Path(f"design_{name}.png")
        if str(plot) == "none":
            plot = None
        fmt = figure_format(plot, "plot")
        if write_data is not None:
            if name != "feeder":
                raise InvalidStateError("write_data", "only the feeder design is stored as data")
            check_output(write_data, "write_data")
        if name == "draft":
            res = ex.draft_example(engine=engine)
            text = res.table()
            result = res.exact
            doc = {"example": "draft", "exact": res.exact.to_dict(), "small_angle": res.small_angle.to_dict(),
                   "as_printed": res.as_printed.to_dict(),
                   "rows": [{"label": r.label, "omega_rad_s": r.omega, "weight": [[m, list(p)] for m, p in
                                                                                   r.part.point_masses],
                             "energy_r_m": r.f_r, "exact_r_m": r.exact_r, "engine_r_m": r.engine_r,
                             "draft_r_m": r.draft_r} for r in res.rows],
                   "readings": {k: [{"name": c.name, "meaning": c.meaning, "com_m": list(c.com),
                                     "inside_plate": c.inside_plate, "realisable": c.weight.realisable,
                                     "weight_kg": c.weight.mass, "weight_at_m": list(c.weight.at)} for c in rd]
                                for k, rd in (("start", res.readings_start), ("design", res.readings_design))}}
            sep = None
        else:
            result, fd = ex.run_feeder_design(engine=engine)
            text = fd.table() + "\n\n" + result.table()
            if write_data is None:
                stored = ex.feeder_design()
                text += ("\n\nstored (throwmap/data/feeder_design.toml): max |Δr_i| = "
                         f"{1000 * max(abs(stored.r[s] - fd.r[s]) for s in fd.r):.4f} mm")
            from ..design.targets import Separation

            sep = Separation(fd.target_side, fd.separation_x, fd.separation_margin)
            doc = {"example": "feeder", "design": result.to_dict(), "target_side": fd.target_side,
                   "separation": {"x_m": fd.separation_x, "margin_m": fd.separation_margin,
                                  "holds": sep.holds(fd.tops)},
                   "tops_m": fd.tops, "bottoms_m": fd.bottoms, "engine_r_m": fd.engine_r,
                   "engine_xtol_m": fd.engine_xtol, "arm": arm_dict(fd.arm),
                   "end_wall": {"jitter": fd.jitter, "window_m": list(fd.wall_window), "S_m": fd.wall_separation}}
            if write_data is not None:
                write_text(write_data, ex.feeder_toml(fd, result), "write_data")
        if plot is not None:
            save_figure(result.plot(separation=sep), plot, fmt, "plot")
        doc.update({"plot": str(plot) if plot is not None else None, "version": __version__})
        if as_json:
            typer.echo(to_json(doc))
        else:
            typer.echo(text)
            for p in (plot, write_data):
                if p is not None:
                    typer.echo(f"wrote {p}")


def _register_cavity(group: typer.Typer) -> None:
    """Add ``design cavity`` and ``design passage`` from :mod:`throwmap.cli.cavity` and
    :mod:`throwmap.cli.passage` where those modules exist and define ``register``."""
    for name in ("cavity", "passage"):
        if importlib.util.find_spec(f"{__package__}.{name}") is None:
            continue
        mod = importlib.import_module(f"{__package__}.{name}")
        reg = getattr(mod, "register", None)
        if callable(reg):
            reg(group)


_register_cavity(design_app)


def register(app: typer.Typer) -> None:
    """Add the ``design`` group to ``app``."""
    app.add_typer(design_app, name="design")


