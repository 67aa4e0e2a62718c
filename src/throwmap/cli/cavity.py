"""``throwmap design cavity``: the cavity that captures the designed part (paper Sec. V-C, Fig. 9(b)).

A thin shell over :func:`throwmap.design.cavity.design_cavity`, built from the same config as
``throwmap experiment feed`` (:class:`throwmap.experiments.feed.FeedConfig`), so that the cavity
printed here is the one the experiment throws into. Prints the cavity's numbers, its checks
(each PASS/FAIL with its figure) and the reasons; ``--plot FILE`` draws the part captured in it
(the engine's capture check's final pose). Exit status 0 when every check passes, 1 when one
fails, 2 on bad input.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated

import typer

from ..version import __version__
from ..errors import InvalidStateError
from .options import JsonOpt, arm_dict, figure_format, guard, save_figure, to_json

__all__ = ["cavity_cmd", "register"]


def cavity_cmd(
    example: Annotated[str, typer.Option("--example", help="The designed part: feeder (throwmap.design.examples."
                                                           "feeder_design()).")] = "feeder",
    realisation: Annotated[str, typer.Option("--realisation", help="How the arm moves: recoil (the Flatland arm) "
                                                                   "or impulse (the paper's).")] = "recoil",
    zeta: Annotated[float, typer.Option("--zeta", help="Recoil loop damping ratio.")] = 0.2,
    recoil: Annotated[float, typer.Option("--recoil", help="Recoil depth, rad.")] = math.radians(3.0),
    sigma: Annotated[float, typer.Option("--sigma", help="Relative ω jitter designed for.")] = 0.03,
    depth: Annotated[float, typer.Option("--depth", help="Cavity depth, m.")] = 0.02,
    end_gap: Annotated[float, typer.Option("--end-gap", help="Floor ends this short of the end wall, m (0: flush).")]
    = 0.0,
    wall_mu: Annotated[float, typer.Option("--wall-mu", help="End wall friction.")] = 0.0,
    place: Annotated[float, typer.Option("--place", help="Where in the window the arm's end L goes (0…1).")] = 0.5,
    length: Annotated[float | None, typer.Option("--length", help="Set the arm's end L instead, m.")] = None,
    verify: Annotated[bool, typer.Option("--verify/--no-verify", help="Run the engine checks (capture, hold, "
                                                                      "release).")] = True,
    plot: Annotated[Path | None, typer.Option("--plot", help="Draw the captured part in the cavity here "
                                                            "(e.g. capture.png).")] = None,
    config: Annotated[Path | None, typer.Option("--config", help="Take part, side, ω, h, μ, noise and cavity from "
                                                                 "this `experiment feed` config (TOML/JSON; e.g. "
                                                                 "examples/feed_recoil.toml) instead of the options "
                                                                 "above.")] = None,
    as_json: JsonOpt = False,
) -> None:
    """Design the cavity at the arm's end that captures the designed part on its target side."""
    from pydantic import ValidationError

    from ..design.cavity import evaluate_cavity
    from ..experiments.feed import FeedConfig, build_design

    with guard():
        if example != "feeder":
            raise InvalidStateError("example", f"must be feeder, got {example!r}")
        if realisation not in ("recoil", "impulse"):
            raise InvalidStateError("realisation", f"must be recoil or impulse, got {realisation!r}")
        fmt = figure_format(plot, "plot")
        if config is not None:
            from ..experiments.base import read_config
            from ..experiments.feed import FEED

            cfg = read_config(FEED, config)
            if cfg.variant != "closed" or cfg.fixture != "cavity":
                raise InvalidStateError("config", "must be a closed-variant config with fixture = 'cavity'")
        try:
            cfg = cfg if config is not None else FeedConfig.model_validate({
                "cavity": {"depth": depth, "end_gap": end_gap, "wall_mu": wall_mu, "place": place, "length": length},
                "noise": {"omega_rel": sigma, "mu_rel": 0.1, "realisation": realisation, "zeta": zeta,
                          "recoil": recoil}})
        except ValidationError as err:  # name the first bad option
            first = err.errors(include_url=False)[0]
            raise InvalidStateError(str(first["loc"][-1]).replace("_", "-"), first["msg"]) from None
        d = build_design(cfg)
        if verify:  # with a config: the capture check may use as many throws as its trials do
            d = evaluate_cavity(d, verify=True, **({"n_capture": cfg.max_throws} if config is not None else {}))
        if plot is not None:
            save_figure(d.plot(), plot, fmt, "plot")
        if as_json:
            doc = d.to_dict()
            doc.update({"arm": arm_dict(d.arm), "plot": str(plot) if plot is not None else None,
                        "version": __version__})
            typer.echo(to_json(doc))
        else:
            typer.echo(d.table())
            if plot is not None:
                typer.echo(f"wrote {plot}")
    if not d.success:
        raise typer.Exit(1)


def register(group: typer.Typer) -> None:
    """Add the ``cavity`` subcommand to the ``throwmap design`` group."""
    group.command("cavity")(cavity_cmd)
