"""The chains of the Monte Carlo experiments: ``position``.

**position** (:mod:`throwmap.experiments.position`) on an analytic model: the chain's state is the rest
``(x, side)`` alone. That is exact for the draft's controller as configured by default — one-bit sensors
read at the true rest, ``confirm = 1``, no hysteresis: its decision is a function of the readings only
(:meth:`~throwmap.control.PaperController.want`) and every wish is accepted — and the readings' errors
(false positives/negatives, blur) are drawn per sample of the chain as the loop draws them per look. A
config with ``confirm > 1`` or hysteresis has memory and is refused. The cells are cut at the sensors'
thresholds (x_f ± ε, the approach and kick rungs). μ is drawn once per trial: a mixture over μ nodes.
The trial's ``throws`` of a successful trial is the hitting throw of ``stop:goal`` (a stop is not a
throw). The chain starts from the drops: the drop is the engine's (:func:`throwmap.experiments.drop.drop_part`)
and not part of the chain; :func:`position_initial` takes it from trials (their ``drop_x``, ``drop_side``).
"""

from __future__ import annotations

import numpy as np

from ..errors import InvalidStateError
from ..models import get_model
from .build import PolicyStep, build_mixture
from .cells import Cells

__all__ = ["position_step", "position_chain", "position_initial", "position_hits", "read_trials"]


def read_trials(path) -> list[dict]:
    """The trials of a Monte Carlo run directory (``trials.jsonl``) or file, as dicts."""
    import json
    from pathlib import Path

    p = Path(path)
    if p.is_dir():
        p = p / "trials.jsonl"
    if not p.is_file():
        raise InvalidStateError("trials", f"no trials file at {p}")
    rows = [json.loads(line) for line in p.read_text(encoding="utf-8").splitlines() if line.strip()]
    return sorted(rows, key=lambda r: r["index"])


def position_hits(trials) -> np.ndarray:
    """Each trial's hitting throw of the goal: ``throws`` of a successful trial, −1 otherwise."""
    return np.array([int(t["values"]["throws"]) if t["success"] else -1 for t in trials], dtype=np.int64)


def position_initial(cells: Cells, trials) -> np.ndarray:
    """The drops of ``trials`` as a distribution over ``cells`` (a drop that is not on the cells is dropped)."""
    x = [t["values"].get("drop_x") for t in trials if t["values"].get("drop_x") is not None]
    s = [t["values"].get("drop_side") for t in trials if t["values"].get("drop_x") is not None]
    if not x:
        raise InvalidStateError("trials", "no trial has a drop (drop_x, drop_side)")
    h = cells.histogram(np.asarray(x, dtype=float), np.asarray(s, dtype=np.int64))
    if not h.sum() > 0:
        raise InvalidStateError("trials", "no drop lies on the cells")
    return h / h.sum()


def position_step(cfg):
    """``(part, arm, step, breaks)`` of the ``position`` experiment's config ``cfg``: the :class:`PolicyStep` the
    chain throws with and the cell breaks (the goal band's edges, the approach and kick thresholds, m)."""
    from ..experiments.position import _setup

    if not get_model(cfg.model).features.ensemble:
        raise InvalidStateError("config.model", "the position chain throws batches of independent starts: it runs on "
                                                "a model that throws ensembles (features.ensemble, e.g. 'rigid_body')")
    part, arm, ctl = _setup(cfg)
    g = ctl.goal
    breaks = [g.x - g.eps, g.x + g.eps] + [x for x, _ in cfg.approach] + [x for x, _ in cfg.kick]
    return part, arm, PolicyStep(part, arm, ctl, cfg.model, cfg.noise.noise()), breaks


def position_chain(cfg, *, cell: float = 0.005, samples: int = 64, n_mu: int = 5, rng=None, initial=None):
    """The chain mixture of the ``position`` experiment's config ``cfg`` (module docstring) and its builds."""
    part, arm, step, breaks = position_step(cfg)
    cells = Cells.on_arm(part, arm, cell, breaks=breaks)
    mix, builds = build_mixture(cells, step, samples=samples, rng=rng, initial=initial, n_mu=n_mu,
                                meta={"experiment": "position", "model": cfg.model})
    return mix, builds
