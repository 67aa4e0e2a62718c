"""``throwmap throw``, ``throwmap iterate`` and ``throwmap map``: one throw, an orbit of throws, and the throw
map T(x) of every side (paper Sec. III).

A thin shell over :func:`throwmap.throws.throw.throw`, :func:`throwmap.throws.orbit.iterate` and
:func:`throwmap.throws.samples.throw_map_samples`:
parse, build the part and arm (:func:`~throwmap.cli.options.part_and_arm`), throw, print a
table (or JSON with ``--json``) and, for ``iterate --plot``, write the orbit's figure.
Errors follow :mod:`throwmap.cli.options`: one ``error: <field>: <reason>`` line, exit 2.
"""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from ..version import __version__
from ..errors import InvalidStateError
from ..records.orbit import Orbit
from ..throws.orbit import iterate
from ..throws.throw import DEFAULT_MODEL, check_model, throw
from .options import (AlphaOpt, BackOpt, CavityOpt, GOpt, HOpt, JsonOpt, LengthOpt, ModelOpt, ModelOptionOpt, MuOpt,
                      OmegaOpt, PartOpt, SideOpt, WallMuOpt, WallOpt, XOpt, arm_dict, check_finite, figure_format,
                      compiling_notice, format_value, guard, model_options, options_doc, parse_floats, part_and_arm, save_figure,
                      strict_int, system_doc, system_options, to_json)
from ..analysis.maps import system_text
from ..budget import DEFAULT_MAX_MEMORY, DEFAULT_MAX_SECONDS, cli_limits as work_limits
from .options import ForceOpt, MaxMemoryOpt, MaxTimeOpt

__all__ = ["register", "throw_cmd", "iterate_cmd", "map_cmd", "PROGRESS_THRESHOLD"]

PROGRESS_THRESHOLD = 200
"""``iterate`` shows a progress bar (on stderr) for more throws than this."""



# ------------------------------------------------------------------ throw
def throw_cmd(
    part: PartOpt,
    omega: OmegaOpt,
    x: XOpt,
    side: SideOpt,
    h: HOpt = None,
    g: GOpt = None,
    length: LengthOpt = None,
    mu: MuOpt = None,
    back: BackOpt = None,
    model: ModelOpt = DEFAULT_MODEL,
    model_option: ModelOptionOpt = None,
    alpha: AlphaOpt = None,
    wall: WallOpt = None,
    wall_mu: WallMuOpt = None,
    cavity: CavityOpt = None,
    as_json: JsonOpt = False,
) -> None:
    """One throw from rest at (x, side): where the part lands and how."""
    with guard():
        check_model(model)
        opts = model_options(model_option, model)
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        sysk = system_options(alpha, wall, wall_mu, cavity, arm)
        side = the_part.check_side(side)  # the library's rule for a side, before any work
        check_finite(x, "x")
        check_finite(omega, "omega")
        compiling_notice(model)
        out = throw(the_part, arm, x, side, omega, model=model, **opts, **sysk)
        if out.status.label == "invalid_start":  # a start the tilted arm cannot hold: bad input, as any other start
            raise InvalidStateError("side", f"not at rest on the tilted arm: {out.message}")
        if as_json:
            doc = {**out.to_dict(), "part": the_part.name, "arm": arm_dict(arm), **system_doc(sysk),
                   "model_options": options_doc(opts), "version": __version__}
            typer.echo(to_json(doc))
            return
        from rich.console import Console
        from rich.markup import escape
        from rich.table import Table

        fmt = format_value
        console = Console()
        extra = system_text(sysk.get("fixtures", ()), sysk.get("alpha", 0.0))
        console.print(escape(f"{the_part.name}: throw from x = {fmt(x)} m, side {side}, ω = {fmt(omega)} rad/s "
                             f"(model {model!r}{', ' + extra if extra else ''})"), soft_wrap=True)
        table = Table()
        table.add_column("quantity")
        table.add_column("value", justify="right")
        rested = out.status.label == "ok"  # otherwise x and side are where the part was when the throw ended
        rows = [
            ("new x (m)" if rested else "x when it ended (m)", fmt(out.x)),
            ("side" if rested else "side when it ended", fmt(out.side)),
            ("status", out.status.label),
            ("kind", out.kind),
            ("flight time (s)", fmt(out.t_flight)),
            ("contact vertex", fmt(out.contact_vertex)),
            ("impacts", fmt(out.n_impacts)),
            ("flips", fmt(out.n_flips)),
            ("friction ratio needed", fmt(out.friction_ratio_max, ".4g")),
            ("lift-off", fmt(out.lift_off)),
        ]
        if out.message:  # why a result was refused (unresolved, unconverged, penetration, timeout)
            rows.append(("reason", out.message))
        for name, value in rows:
            table.add_row(name, value)
        console.print(table)
        if not rested:
            console.print(escape(_ENDED.get(out.status.label, f"the throw ended {out.status.label}: it did not come to rest "
                                                        "on the arm")), soft_wrap=True)


# ------------------------------------------------------------------ iterate
def _iterate_with_progress(part, arm, state, omegas, n, total: int, model: str, opts: dict) -> Orbit:
    """:func:`throwmap.iterate` with a Rich progress bar on stderr (``total`` throws planned)."""
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn, TimeRemainingColumn

    bar = Progress(TextColumn("throwing"), BarColumn(), MofNCompleteColumn(), TimeRemainingColumn(),
                   console=Console(stderr=True), transient=True)
    task = bar.add_task("throwing", total=total)
    started = []

    def progress(done):
        if not started:  # shown from the first throw on: a refusal before any work stays one line on stderr
            bar.start()
            started.append(True)
        bar.update(task, completed=done)

    try:
        return iterate(part, arm, state, omegas, n, model=model, **opts, progress=progress)
    finally:
        if started:
            bar.stop()


def _orbit_summary(orbit: Orbit, requested: int) -> dict:
    """Throws done, status, jogs/flips, final state, escape and the x range visited per side."""
    import numpy as np

    kinds = orbit.kinds
    per_side = {}
    for s in np.unique(orbit.side):
        xs = orbit.x[orbit.side == s]
        per_side[str(int(s))] = {"x_min": float(xs.min()), "x_max": float(xs.max()), "visits": int(xs.size)}
    return {
        "throws_requested": requested,
        "throws_done": orbit.n_throws,
        "status": orbit.status.label,
        "jogs": sum(k == "jog" for k in kinds),
        "flips": sum(k == "flip" for k in kinds),
        "tumbles": sum(k == "tumble" for k in kinds),
        "final": {"x": float(orbit.x[-1]), "side": int(orbit.side[-1])},
        "escape": orbit.outcomes[-1].to_dict() if orbit.escaped else None,
        "per_side": per_side,
    }


def _throw_rates(omega: list[str], n: int | None) -> tuple[float | list[float], int | None, int]:
    """The release rates of ``--omega`` for :func:`throwmap.iterate`: ``(ω, n, n)`` for one ω
    repeated ``-n`` times (never expanded here: the library guards the size), or ``(ωs, None, len)``."""
    omegas = parse_floats(omega, "omega")
    if len(omegas) == 1:
        if n is None:
            raise InvalidStateError("n", "give -n/--n, the number of throws, with a single --omega")
        if n < 0:
            raise InvalidStateError("n", f"must be a non-negative integer, got {n}")
        return omegas[0], n, n
    if n is not None and n != len(omegas):
        raise InvalidStateError("n", f"got n = {n} but {len(omegas)} omegas")
    return omegas, None, len(omegas)


def iterate_cmd(
    part: PartOpt,
    omega: Annotated[list[str], typer.Option("--omega", help="Release rate ω, rad/s: one value (with -n), or "
                                                             "one per throw (repeat the option or give a comma list).")],
    x: XOpt,
    side: SideOpt,
    n: Annotated[int | None, typer.Option("-n", "--n", parser=strict_int, metavar="INTEGER",
                                               help="Number of throws (required with a single ω).")] = None,
    h: HOpt = None,
    g: GOpt = None,
    length: LengthOpt = None,
    mu: MuOpt = None,
    back: BackOpt = None,
    model: ModelOpt = DEFAULT_MODEL,
    model_option: ModelOptionOpt = None,
    alpha: AlphaOpt = None,
    wall: WallOpt = None,
    wall_mu: WallMuOpt = None,
    cavity: CavityOpt = None,
    as_json: JsonOpt = False,
    plot: Annotated[Path | None, typer.Option("--plot", help="Write a figure of the orbit (e.g. orbit.png).")] = None,
    max_memory: MaxMemoryOpt = DEFAULT_MAX_MEMORY / 1e9,
    max_time: MaxTimeOpt = DEFAULT_MAX_SECONDS,
    force: ForceOpt = False,
) -> None:
    """Repeated throws from (x, side): an orbit of the throw map."""
    with guard():
        check_model(model)
        opts = model_options(model_option, model)
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        sysk = system_options(alpha, wall, wall_mu, cavity, arm)
        side = the_part.check_side(side)  # the library's rule for a side, before any work
        check_finite(x, "x")
        omegas, n_lib, planned = _throw_rates(omega, n)
        limits = work_limits(max_memory, max_time, force)
        fmt = figure_format(plot, "plot")
        if sysk:  # a model without tilt or fixtures refuses them before any throw (the library's rule)
            from ..throws.throw import prepare

            prepare(model, arm, sysk.get("fixtures", ()), sysk.get("alpha", 0.0), opts.get("options"), {})
        if planned > PROGRESS_THRESHOLD:
            orbit = _iterate_with_progress(the_part, arm, (x, side), omegas, n_lib, planned, model,
                                           {**opts, **sysk, "limits": limits})
        else:
            orbit = iterate(the_part, arm, (x, side), omegas, n_lib, model=model, **opts, **sysk, limits=limits)
        summary = _orbit_summary(orbit, planned)
        if plot is not None:
            save_figure(orbit.plot(part=the_part, arm=arm), plot, fmt, "plot")
        if as_json:
            doc = {**orbit.to_dict(), "summary": summary, "part": the_part.name, "arm": arm_dict(arm),
                   **system_doc(sysk), "plot": str(plot) if plot is not None else None, "model_options": options_doc(opts), "version": __version__}
            typer.echo(to_json(doc))
            return
        from rich.console import Console
        from rich.markup import escape
        from rich.table import Table

        console = Console()
        extra = system_text(sysk.get("fixtures", ()), sysk.get("alpha", 0.0))
        console.print(escape(f"{the_part.name}: orbit from x = {format_value(x)} m, side {side} (model {model!r}"
                             f"{', ' + extra if extra else ''})"), soft_wrap=True)
        table = Table()
        table.add_column("quantity")
        table.add_column("value", justify="right")
        table.add_row("throws done", f"{summary['throws_done']} of {summary['throws_requested']}")
        table.add_row("status", summary["status"])
        table.add_row("jogs / flips", f"{summary['jogs']} / {summary['flips']}")
        table.add_row("final state", f"x = {format_value(summary['final']['x'])} m, side {summary['final']['side']}")
        for s, band in summary["per_side"].items():
            table.add_row(f"side {s}: x min … max (m)",
                          f"{format_value(band['x_min'])} … {format_value(band['x_max'])} ({band['visits']} visits)")
        if plot is not None:
            table.add_row("figure", str(plot))
        console.print(table)


# ------------------------------------------------------------------ map
def map_cmd(
    part: PartOpt,
    omega: OmegaOpt,
    h: HOpt = None,
    g: GOpt = None,
    length: LengthOpt = None,
    mu: MuOpt = None,
    back: BackOpt = None,
    model: ModelOpt = DEFAULT_MODEL,
    model_option: ModelOptionOpt = None,
    alpha: AlphaOpt = None,
    wall: WallOpt = None,
    wall_mu: WallMuOpt = None,
    cavity: CavityOpt = None,
    x_max: Annotated[float | None, typer.Option("--x-max", help="Outer end of the starts, m (default: the arm "
                                                                "length, else 0.5).")] = None,
    n: Annotated[int, typer.Option("--n", parser=strict_int, metavar="INTEGER",
                                   help="Starts per stable side, evenly spaced.")] = 400,
    as_json: JsonOpt = False,
    plot: Annotated[Path | None, typer.Option("--plot", help="Write T(x) per side, e.g. map.png.")] = None,
) -> None:
    """The throw map T(x) of every stable side: where a part resting at x lands, as runs of x with one outcome."""
    from ..throws.samples import throw_map_samples
    from ..records.outcome import Status

    with guard():
        check_model(model)
        opts = model_options(model_option, model)
        the_part, arm = part_and_arm(part, h, g, length, mu, back)
        sysk = system_options(alpha, wall, wall_mu, cavity, arm)
        check_finite(omega, "omega")
        if x_max is not None:
            check_finite(x_max, "x-max")
        if n < 2:
            raise InvalidStateError("n", f"must be ≥ 2, got {n}")
        fmt = figure_format(plot, "plot")
        smp = throw_map_samples(the_part, arm, omega, model=model, x_max=x_max, n=n, **opts, **sysk)
        runs = []  # (side, x from, x to, what, x' lo, x' hi)
        for i in range(smp.x.size):
            st = int(smp.status[i])
            what = (f"side {int(smp.side_next[i])}" if st == 0 else Status(st).label)
            if st == 0:
                what = ("jog" if int(smp.side_next[i]) == int(smp.side[i]) else "flip to ") + (
                    "" if int(smp.side_next[i]) == int(smp.side[i]) else what)
            xn = float(smp.x_next[i]) if st == 0 else None
            r = runs[-1] if runs else None
            if r and r[0] == int(smp.side[i]) and r[3] == what:
                r[2] = float(smp.x[i])
                if xn is not None:
                    r[4], r[5] = min(r[4], xn), max(r[5], xn)
            else:
                runs.append([int(smp.side[i]), float(smp.x[i]), float(smp.x[i]), what,
                             xn if xn is not None else float("inf"), xn if xn is not None else float("-inf")])
        seen_other: set = set()
        for r in runs:  # beyond r_i a throw that lands on its own side has tumbled over and back, not jogged
            if r[3] != "jog":
                seen_other.add(r[0])
            elif r[0] in seen_other:
                r[3] = "tumbles over and back"
        if plot is not None:
            from ..analysis.maps import plot_throw_map

            save_figure(plot_throw_map(the_part, arm, omega, model=model, x_max=x_max, n=n, **opts, **sysk), plot,
                        fmt, "plot")
        if as_json:
            doc = {"part": the_part.name, "arm": arm_dict(arm), **system_doc(sysk), "omega": omega, "model": model,
                   "model_options": options_doc(opts), "n_per_side": smp.n,
                   "sides": {str(s): {"x_lo_m": smp.x_lo[k], "x_hi_m": smp.x_hi[k]} for k, s in enumerate(smp.sides)},
                   "runs": [{"side": r[0], "x_from_m": r[1], "x_to_m": r[2], "outcome": r[3],
                             "x_next_m": [r[4], r[5]] if r[4] <= r[5] else None} for r in runs],
                   "samples": {"x_m": smp.x.tolist(), "side": smp.side.tolist(), "x_next_m": [
                       float(v) if int(st) == 0 else None for v, st in zip(smp.x_next, smp.status)],
                       "side_next": [int(v) if int(st) == 0 else None for v, st in zip(smp.side_next, smp.status)],
                       "status": [Status(int(st)).label for st in smp.status]},
                   "plot": str(plot) if plot is not None else None, "version": __version__}
            typer.echo(to_json(doc))
            return
        typer.echo(f"throw map of {the_part.name} at ω = {omega:g} rad/s, h = {arm.h:g} m, model {model!r}"
                   f"{system_text(sysk.get('fixtures', ()), sysk.get('alpha', 0.0))}; {smp.n} starts per side")
        typer.echo("side  x from (cm)  x to (cm)  outcome                   lands at x' (cm)")
        for r in runs:
            lands = f"{100 * r[4]:.2f} … {100 * r[5]:.2f}" if r[4] <= r[5] else "—"
            said = _MAP_WORDS.get(r[3], r[3].replace("_", " "))
            typer.echo(f"{r[0]:>4}  {100 * r[1]:>11.2f}  {100 * r[2]:>9.2f}  {said:<24}  {lands}")
        typer.echo("jog: lands on the side it rested on without turning over; flip: on another side; tumbles over and "
                   "back: turns over and lands on its own side again; any other outcome leaves the arm or is refused "
                   "(an x between two runs lies between two samples)")
        if plot is not None:
            typer.echo(f"wrote {plot}")


_ENDED = {"behind_joint": "the part left the arm behind the joint (a contact at x ≤ 0): it does not rest there",
          "off_end": "the part left the arm past its end: it does not rest there"}
"""What the throw table says under an escape."""
_MAP_WORDS = {"behind_joint": "escapes behind the joint", "off_end": "falls off the arm's end"}
"""The map table's words for the escapes (the JSON keeps the status labels)."""


def register(app: typer.Typer) -> None:
    """Add the ``throw``, ``iterate`` and ``map`` commands to ``app``."""
    app.command("throw")(throw_cmd)
    app.command("iterate")(iterate_cmd)
    app.command("map")(map_cmd)
