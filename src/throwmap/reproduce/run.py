"""``throwmap reproduce``: every draft figure that has an analogue, the draft's four experiments against ours, the
design example, the parameters chosen where the draft is silent, and the errata — one Markdown and one HTML report.

:func:`reproduce` writes into ``out``:

* ``figures/<key>.png`` — one per :data:`~throwmap.reproduce.plan.FIGURES` entry;
* ``experiments/<key>/`` — each experiment's kept trials (``trials.jsonl``, ``result.json``, ``trials.parquet``);
  a rerun resumes them, so an interrupted reproduction loses no finished trial;
* ``report.json`` (everything the report says, SI), ``report.md`` and ``report.html`` (self-contained: the
  figures inline), each written atomically.

A figure or an experiment that fails is reported as failed with its one-line reason (and the command exits 1),
never left out silently.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path

from ..budget import Limits
from ..version import __version__
from ..errors import InvalidStateError, ThrowmapError, shown
from ..io.files import make_directory
from .plan import EXPERIMENTS, FIGURES, SIZES

__all__ = ["Reproduction", "reproduce"]


@dataclass(frozen=True, slots=True)
class Reproduction:
    """What :func:`reproduce` made: ``size`` (``"full"``/``"quick"``), ``figures`` (per figure: key, draft,
    caption, file, numbers, parameters, error, seconds), ``experiments`` (per experiment: the draft's and our
    successes, n, Wilson interval, failures, parameters, error, seconds), ``elapsed_s``, ``out``, ``version``,
    ``started`` (UTC ISO time)."""

    size: str
    figures: tuple
    experiments: tuple
    elapsed_s: float
    out: str
    version: str = __version__
    started: str = ""
    workers: int = 0
    errata: str = field(default="", repr=False)

    @property
    def failed(self) -> list[str]:
        return [f["key"] for f in self.figures if f.get("error")] + [e["key"] for e in self.experiments
                                                                    if e.get("error")]

    def to_dict(self) -> dict:
        return {"size": self.size, "version": self.version, "started": self.started, "elapsed_s": self.elapsed_s,
                "workers": self.workers, "out": self.out, "figures": list(self.figures),
                "experiments": list(self.experiments), "failed": self.failed}


def _errata() -> str:
    from importlib.resources import files

    text = files("throwmap").joinpath("data", "errata.md").read_text(encoding="utf-8")
    return "\n".join(line for line in text.splitlines() if not line.startswith("<!--"))


def _one_line(err: BaseException) -> str:
    text = str(err).strip().splitlines()
    return f"{type(err).__name__}: {text[0] if text else ''}"


def _figure(spec, out: Path, size, ctx) -> dict:
    import os

    from .figures import MAKERS

    os.environ.setdefault("MPLBACKEND", "Agg")
    path = out / "figures" / f"{spec.key}.png"
    t0 = time.perf_counter()
    row = {"key": spec.key, "draft": spec.draft, "caption": spec.caption, "file": f"figures/{spec.key}.png",
           "numbers": {}, "parameters": {}, "error": None}
    try:
        got = MAKERS[spec.maker](path, size, ctx)
        row["numbers"], row["parameters"] = got.get("numbers", {}), got.get("parameters", {})
        if got.get("caption"):  # a caption that depends on what was drawn comes from the result
            row["caption"] = got["caption"]
        if row["numbers"].get("success") is False:  # the figure shows a result that failed: a failed piece
            row["error"] = "its result failed (success: false)" + (f": {got['failure']}" if got.get("failure") else "")
            row["caption"] = "Not reproduced — the result failed. " + row["caption"]
    except Exception as err:  # noqa: BLE001 - reported in the report, never dropped
        row["error"], row["file"] = _one_line(err), None
    row["seconds"] = time.perf_counter() - t0
    return row


def _experiment(spec, out: Path, size, workers: int, progress) -> dict:
    from ..experiments import experiment_names, get_experiment
    from ..experiments.runner import run_experiment
    from ..experiments.stats import wilson_interval

    lo, hi = wilson_interval(spec.draft_successes, spec.draft_n)
    row = {"key": spec.key, "title": spec.title, "section": spec.section, "experiment": spec.experiment,
           "note": spec.note, "goal": spec.goal,
           "draft": {"successes": spec.draft_successes, "n": spec.draft_n, "ci95": [lo, hi]},
           "ours": None, "error": None}
    t0 = time.perf_counter()
    try:
        if spec.experiment not in experiment_names():
            raise InvalidStateError("experiment", f"{spec.experiment!r} is not registered in this version")
        exp = get_experiment(spec.experiment)
        res = run_experiment(exp, spec.config, n=size.n, seed=0, workers=workers, out=out / "experiments" / spec.key,
                             progress=progress, limits=Limits(force=True))
        vals = res.value_summary()
        row["ours"] = {"successes": res.successes, "n": res.n, "success_rate": res.success_rate,
                       "ci95": list(res.ci95), "failures": dict(res.failures), "seed": res.seed,
                       "throws": vals.get("throws_to_capture") or vals.get("throws"),
                       "parameters": res.parameters, "resumed": res.resumed}
    except (ThrowmapError, OSError, RuntimeError, ValueError) as err:
        row["error"] = _one_line(err)
    row["seconds"] = time.perf_counter() - t0
    return row


def reproduce(out, *, size: str = "full", workers: int = 0, only=None, progress=None) -> Reproduction:
    """Make every figure and run every experiment of :mod:`throwmap.reproduce.plan` at ``size`` (``"full"``: ≥ 200
    trials per experiment; ``"quick"``: a smoke run) into ``out``; ``only`` (keys) limits the work;
    ``progress(message)`` is called before each piece. Returns the :class:`Reproduction` and writes the reports."""
    from ..io.files import atomic_write_text
    from ..serial import json_ready
    from .report import html_report, markdown_report

    if size not in SIZES:
        raise InvalidStateError("size", f"must be one of {sorted(SIZES)}, got {shown(size)}")
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 0:
        raise InvalidStateError("workers", f"must be an integer ≥ 0 (0: all cores), got {shown(workers)}")
    keys = {f.key for f in FIGURES} | {e.key for e in EXPERIMENTS}
    chosen = set(only) if only else keys
    if chosen - keys:
        raise InvalidStateError("only", f"unknown keys {sorted(chosen - keys)} (choose from {sorted(keys)})")
    sz = SIZES[size]
    out = Path(out)
    for folder in (out, out / "figures", out / "experiments"):  # out alone: a missing folder above it is refused
        make_directory(folder, "out")
    say = progress or (lambda msg, done=None, total=None: None)
    started = datetime.now(timezone.utc).isoformat(timespec="seconds")
    t0 = time.perf_counter()
    ctx: dict = {}
    figs = []
    for spec in FIGURES:
        if spec.key in chosen:
            say(f"figure {spec.key} ({spec.draft})")
            figs.append(_figure(spec, out, sz, ctx))
    exps = []
    for spec in EXPERIMENTS:
        if spec.key in chosen:
            say(f"experiment {spec.key} ({spec.experiment}, {sz.n} trials)")
            exps.append(_experiment(spec, out, sz, workers,
                                    lambda done, total, k=spec.key: say(f"experiment {k}", done, total)))
    rep = Reproduction(size, tuple(figs), tuple(exps), time.perf_counter() - t0, str(out), started=started,
                       workers=workers, errata=_errata())
    atomic_write_text(out / "report.json", json.dumps(json_ready(rep.to_dict()), indent=2, allow_nan=False) + "\n")
    atomic_write_text(out / "report.md", markdown_report(rep))
    atomic_write_text(out / "report.html", html_report(rep, out))
    return rep
