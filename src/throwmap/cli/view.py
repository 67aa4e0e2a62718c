"""``throwmap view``: one self-contained HTML page that plays a motion beside its orbit plot.

::

    throwmap view FILE.npz --out view.html                 # a saved trajectory (throwmap.io.trajectory_file)
    throwmap view DIR --out view.html [--trial I]          # an experiment's --out: outcomes and trials tables;
                                                           #   --trial I replays trial I (assemble experiments)
    throwmap view --assemble [--config C] --seed S --index I [--first-success] [--start drop] --out view.html
    throwmap view --part P --omega W --x X --side K [-n N] [--model M] [--h …] [--wall …] --out view.html
    … [--save-trajectory FILE.npz] [--fps F]

Exactly one source: a RESULT path, ``--assemble`` (one trial of ``experiment assemble``, rerun throw by throw
with :func:`throwmap.experiments.assemble_episode.assembly_episode`) or ``--part`` (an orbit of ``-n`` throws,
:func:`throwmap.throws.orbit_trajectory.orbit_trajectory`). Whatever motion is shown can be kept with
``--save-trajectory`` (a ``.npz`` that ``throwmap view FILE.npz`` plays again without recomputing; an episode's
orbit and summary travel in its ``meta``). The page (:mod:`throwmap.viz.viewer`) needs no network. A thin shell:
this module computes or loads, the viz module renders. Errors: one ``error: <field>: <reason>`` line, exit 2.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Annotated

import typer

from ..errors import InvalidStateError, ThrowmapError
from .options import (AlphaOpt, BackOpt, CavityOpt, GOpt, HOpt, LengthOpt, ModelOptionOpt, MuOpt, WallMuOpt, WallOpt,
                      check_finite, check_output, guard, model_options, part_and_arm, side_value, strict_int,
                      system_options)

__all__ = ["register", "view_cmd", "episode_trajectory", "experiment_page"]


# ------------------------------------------------------------------ sources → (trajectory, title, sections)
def episode_trajectory(ep, start: str = "switch", throws_before: int = 2):
    """The episode's motion (:meth:`AssemblyEpisode.motion`) with its orbit (every run: throw, both parts' x and
    side, phase, and when its motion starts in the trajectory; None before the motion starts) and its summary in
    ``meta`` (``"orbit"``, ``"episode"``)."""
    import dataclasses

    traj = ep.motion(start=start, throws_before=throws_before)
    first = 0
    if start == "switch" and ep.switch_run is not None:
        first = max(0, ep.switch_run - throws_before)
    runs = ep.trajectories[first:]
    starts, end = [float(runs[0].t[0])], float(runs[0].t[-1])
    for tr in runs[1:]:
        starts.append(end)
        end += float(tr.t[-1] - tr.t[0])
    t = [None] * first + starts
    orbit = {"throw": [int(k) for k in ep.throw_no], "x": ep.states[:, :, 0].tolist(),
             "side": ep.states[:, :, 1].astype(int).tolist(), "phase": list(ep.phases), "t": t}
    meta = dict(traj.meta, orbit=orbit, episode=ep.summary())
    return dataclasses.replace(traj, meta=meta)


def _episode_title(summary: dict) -> str:
    end = (f"assembled at throw {summary['assembled_throw']}" if summary["success"]
           else f"failed: {summary['failure']}")
    sw = "never switched" if summary["switch_throw"] is None else f"switch after throw {summary['switch_throw']}"
    return f"self-assembly, seed {summary['seed']} trial {summary['index']}: {sw}, {end}"


def _kv(pairs) -> str:
    import html

    return "<dl class=\"kv\">" + "".join(f"<dt>{html.escape(str(k))}</dt><dd>{html.escape(str(v))}</dd>"
                                         for k, v in pairs) + "</dl>"


def _read_trials(directory: Path) -> list[dict]:
    path = directory / "trials.jsonl"
    if not path.exists():
        return []
    out = {}
    lines = path.read_text(encoding="utf-8").splitlines()
    for k, line in enumerate(lines, start=1):
        if not line.strip():
            continue
        try:
            rec = json.loads(line)
        except json.JSONDecodeError:
            if k == len(lines):
                continue  # the last line cut by an interrupted run
            raise InvalidStateError("result", f"{path}: line {k} is not JSON") from None
        out[int(rec["index"])] = rec
    return [out[i] for i in sorted(out)]


def experiment_page(directory: Path, trial: int | None = None):
    """``(trajectory or None, title, subtitle, sections)`` of an experiment's ``--out`` directory: its header,
    the outcomes with Wilson intervals, the trials table, and with ``trial`` that trial's motion re-created
    (an experiment whose ``trial`` takes an ``observer``, e.g. ``assemble``)."""
    from ..experiments.stats import wilson_interval
    from ..viz.viewer import table_html

    head_path, result_path = directory / "run.json", directory / "result.json"
    if not head_path.exists() and not result_path.exists():
        raise InvalidStateError("result", f"{directory} holds no experiment run (run.json or result.json)")
    head = json.loads(head_path.read_text(encoding="utf-8")) if head_path.exists() else {}
    result = json.loads(result_path.read_text(encoding="utf-8")) if result_path.exists() else {}
    name = result.get("experiment") or head.get("experiment")
    seed = result.get("seed", head.get("seed"))
    trials = _read_trials(directory)
    n = len(trials) if trials else int(result.get("n", 0))
    wins = sum(1 for r in trials if r["success"]) if trials else int(result.get("successes", 0))
    failures: dict = {}
    for r in trials:
        if not r["success"]:
            failures[r["failure"]] = failures.get(r["failure"], 0) + 1
    if not trials:
        failures = dict(result.get("failures", {}))
    rows = []
    for kind, count in [("success", wins), *failures.items()]:
        lo, hi = wilson_interval(count, n) if n else (math.nan, math.nan)
        rows.append((kind, count, f"{100 * count / n:.1f} %" if n else "–", f"[{100 * lo:.1f}, {100 * hi:.1f}] %"))
    sections = ["<section id=\"summary\"><h2>Run</h2>" + _kv([
        ("experiment", name), ("seed", seed), ("trials", f"{n}" + (f" of {result['planned']} planned"
                                                                    if result.get("planned", n) != n else "")),
        ("throwmap version", result.get("version", head.get("version", "?"))),
        ("elapsed", f"{result['elapsed_s']:.3g} s on {result.get('workers', '?')} worker(s)" if "elapsed_s" in result
         else "– (no result.json: an interrupted run)"),
        ("directory", str(directory))]),
        table_html(("outcome", "trials", "fraction", "Wilson 95 %"), rows, caption="Outcomes", table_id="outcomes")]
    keys = []
    for r in trials:
        keys.extend(k for k in r.get("values", {}) if k not in keys)
    highlight = next((i for i, r in enumerate(trials) if r["index"] == trial), None) if trial is not None else None
    sections.append(table_html(("index", "success", "failure", *keys),
                               [(r["index"], r["success"], r["failure"], *(r["values"].get(k) for k in keys))
                                for r in trials], caption=f"Trials ({len(trials)})", highlight=highlight,
                               table_id="trials"))
    sections.append("</section>")
    subtitle = (f"{wins}/{n} succeeded" + (f" = {100 * wins / n:.1f} %" if n else "") + f", seed {seed}")
    traj = None
    if trial is not None:
        traj, note = _replay(name, head.get("config", result.get("config")), seed, trial, trials)
        subtitle += f"; playing trial {trial} ({note})"
    return traj, f"experiment {name}", subtitle, "".join(sections)


def _replay(name, config, seed, index: int, trials):
    """Trial ``index`` of the run re-created with its motion: ``(trajectory, note)``."""
    import inspect

    from ..experiments import get_experiment
    from ..experiments.assemble_episode import assembly_episode

    exp = get_experiment(name)
    if "observer" not in inspect.signature(exp.trial).parameters:
        raise InvalidStateError("trial", f"experiment {name!r} cannot re-create a trial's motion (it records no "
                                         f"runs); the tables are shown without --trial")
    if index < 0:
        raise InvalidStateError("trial", f"must be ≥ 0, got {index}")
    stored = next((r for r in trials if r["index"] == index), None)
    if stored is None:
        have = sorted(r["index"] for r in trials)
        span = f"{have[0]}…{have[-1]}" if have else "none"
        raise InvalidStateError("trial", f"trial {index} is not in this run's stored trials (indices {span})")
    ep = assembly_episode(config, index, int(seed), motion=True, experiment=name)
    if bool(stored["success"]) != ep.success or stored.get("failure") != ep.trial.failure:
        note = f"differs from the stored trial: {stored.get('failure') or 'success'} stored"
    else:
        note = "as stored: " + ("success" if ep.success else ep.trial.failure)
    return episode_trajectory(ep, start="drop"), note


def _orbit_source(part, omega, x, side, h, g, length, mu, back, n, model, model_option, alpha, wall, wall_mu,
                  cavity):
    from ..models import DEFAULT_MODEL
    from ..throws.orbit_trajectory import orbit_trajectory, trajectory_models

    model = model or DEFAULT_MODEL
    if model not in trajectory_models():
        raise InvalidStateError("model", f"model {model!r} records no trajectory (choose from "
                                         f"{', '.join(trajectory_models())})")
    for value, fld in ((omega, "omega"), (x, "x"), (side, "side")):
        if value is None:
            raise InvalidStateError(fld, "give --part, --omega, --x and --side for an orbit of throws")
    check_finite(x, "x")
    check_finite(omega, "omega")
    if n < 1:
        raise InvalidStateError("n", f"must be a positive integer, got {n}")
    opts = {**model_options(model_option, model), **system_options(alpha, wall, wall_mu, cavity)}
    the_part, arm = part_and_arm(part, h, g, length, mu, back)
    system_options(alpha, wall, wall_mu, cavity, arm)
    side = the_part.check_side(side)
    try:
        traj = orbit_trajectory(the_part, arm, x, side, omega, n, model=model, **opts)
    except ImportError as err:
        raise ThrowmapError("model", f"the {model!r} model needs an optional package "
                                     f"({getattr(err, 'name', None) or err}; pip install it)") from None
    title = f"{the_part.name or 'part'} — h = {arm.h:g} m, ω = {omega:g} rad/s, model {model!r}, {n} throw" \
            + ("s" if n != 1 else "")
    return traj, title


# ------------------------------------------------------------------ the command
OptStr = Annotated[str | None, typer.Option("--part", help="Orbit mode: a built-in part or a part file.")]


def view_cmd(
    result: Annotated[Path | None, typer.Argument(help="A trajectory file (.npz) or an experiment's --out "
                                                       "directory.", show_default=False)] = None,
    out: Annotated[Path, typer.Option("--out", help="The page to write (.html).")] = Path("view.html"),
    assemble: Annotated[bool, typer.Option("--assemble", help="Play one trial of `experiment assemble`.")] = False,
    config: Annotated[Path | None, typer.Option("--config", help="With --assemble: its config (.toml/.json; "
                                                                 "default: built-in).")] = None,
    index: Annotated[int, typer.Option("--index", parser=strict_int, metavar="INTEGER",
                                       help="With --assemble: the trial index.")] = 0,
    seed: Annotated[int, typer.Option("--seed", parser=strict_int, metavar="INTEGER",
                                      help="With --assemble: the run's seed.")] = 0,
    first: Annotated[bool, typer.Option("--first-success", help="With --assemble: the first successful trial "
                                                                "from --index on (at most 20).")] = False,
    start: Annotated[str, typer.Option("--start", help="With --assemble: 'switch' (two throws before it) or "
                                                       "'drop'.")] = "switch",
    trial: Annotated[int | None, typer.Option("--trial", parser=strict_int, metavar="INTEGER",
                                              help="With an experiment directory: re-create and play this trial "
                                                   "(assemble experiments).")] = None,
    part: OptStr = None,
    omega: Annotated[float | None, typer.Option("--omega", help="Orbit mode: release rate ω, rad/s.")] = None,
    x: Annotated[float | None, typer.Option("--x", help="Orbit mode: resting CM position, m.")] = None,
    side: Annotated[int | None, typer.Option("--side", parser=side_value, metavar="INTEGER",
                                             help="Orbit mode: the side it rests on.")] = None,
    n: Annotated[int, typer.Option("-n", "--n", parser=strict_int, metavar="INTEGER",
                                   help="Orbit mode: number of throws.")] = 5,
    model: Annotated[str | None, typer.Option("--model", help="Orbit mode: a model that records "
                                                              "trajectories.")] = None,
    model_option: ModelOptionOpt = None,
    h: HOpt = None, g: GOpt = None, length: LengthOpt = None, mu: MuOpt = None, back: BackOpt = None,
    alpha: AlphaOpt = None, wall: WallOpt = None, wall_mu: WallMuOpt = None, cavity: CavityOpt = None,
    fps: Annotated[float, typer.Option("--fps", help="Frames stored per simulated second.")] = 60.0,
    save_trajectory: Annotated[Path | None, typer.Option("--save-trajectory", help="Also keep the motion shown "
                                                                                   "as a .npz trajectory file.")]
    = None,
) -> None:
    """Write one self-contained HTML page playing a trajectory, an assembly episode or an experiment's trial."""
    with guard():
        from ..viz.viewer import player_data, viewer_html, write_viewer

        sources = [s for s, on in (("RESULT", result is not None), ("--assemble", assemble), ("--part", part))
                   if on]
        if len(sources) != 1:
            raise InvalidStateError("result", "give one of: RESULT (a .npz trajectory or an experiment --out "
                                              "directory), --assemble, --part …" +
                                    (f" (got {' and '.join(sources)})" if sources else ""))
        if out.suffix.lower() not in (".html", ".htm"):
            raise InvalidStateError("out", f"the viewer is an .html file, got {str(out)!r}")
        if not (math.isfinite(fps) and fps > 0):
            raise InvalidStateError("fps", f"must be a positive finite number, got {fps}")
        if start not in ("switch", "drop"):
            raise InvalidStateError("start", f"must be 'switch' or 'drop', got {start!r}")
        if trial is not None and (result is None or not Path(result).is_dir()):
            raise InvalidStateError("trial", "goes with an experiment directory (RESULT)")
        check_output(out, "out")
        if save_trajectory is not None:
            if save_trajectory.suffix.lower() != ".npz":
                raise InvalidStateError("save_trajectory", f"a trajectory file ends in .npz, got "
                                                           f"{str(save_trajectory)!r}")
            check_output(save_trajectory, "save_trajectory")
        traj, subtitle, sections = None, "", ""
        if result is not None and Path(result).is_dir():
            traj, title, subtitle, sections = experiment_page(Path(result), trial)
        elif result is not None:
            from ..io.trajectory_file import load_trajectory

            traj = load_trajectory(result)
            ep = traj.meta.get("episode")
            title = _episode_title(ep) if isinstance(ep, dict) else f"trajectory {Path(result).name}"
        elif assemble:
            from ..experiments import get_experiment
            from ..experiments.assemble_episode import assembly_episode, first_success
            from ..experiments.base import config_of, read_config

            if index < 0 or seed < 0:
                raise InvalidStateError("index" if index < 0 else "seed", "must be ≥ 0")
            exp = get_experiment("assemble")
            cfg = read_config(exp, config) if config is not None else config_of(exp)
            ep = (first_success(cfg, seed, start=index, motion=True) if first
                  else assembly_episode(cfg, index, seed, motion=True))
            traj = episode_trajectory(ep, start=start)
            title = _episode_title(ep.summary())
        else:
            traj, title = _orbit_source(part, omega, x, side, h, g, length, mu, back, n, model, model_option, alpha,
                                        wall, wall_mu, cavity)
        if traj is not None and not subtitle:
            subtitle = f"{traj.source}: {len(traj.parts)} part{'s' if len(traj.parts) != 1 else ''}, " \
                       f"{traj.t[-1] - traj.t[0]:.3g} s simulated, {len(traj.events)} events"
        if traj is not None and isinstance(traj.meta.get("episode"), dict) and not sections:
            from ..viz.viewer import table_html

            s = traj.meta["episode"]
            sections = table_html(("field", "value"), [(k, v) for k, v in s.items() if k != "values"],
                                  caption="Episode", table_id="episode")
        player = player_data(traj, fps=fps) if traj is not None else None
        page = viewer_html(title=title, subtitle=subtitle, player=player, sections=sections)
        write_viewer(out, page)
        if save_trajectory is not None and traj is not None:
            from ..io.trajectory_file import save_trajectory as save

            save(traj, save_trajectory)
            typer.echo(f"wrote {save_trajectory} ({save_trajectory.stat().st_size / 1e3:.0f} kB)")
        what = (f"{player['n']} frames, {len(traj.parts)} part{'s' if len(traj.parts) != 1 else ''}"
                + (f", {len(player['orbit']['throw'])} orbit steps" if player["orbit"] else "")) if player else \
            "tables only"
        typer.echo(f"wrote {out} ({len(page.encode('utf-8')) / 1e3:.0f} kB; {what})")


def register(app: typer.Typer) -> None:
    """Add the ``view`` command to ``app``."""
    app.command("view")(view_cmd)
