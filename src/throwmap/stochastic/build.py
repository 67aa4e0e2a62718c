"""Estimating a chain's transition matrix from throws on cells.

Row ``i`` of ``P`` is estimated from ``samples`` throws started at rests drawn uniformly in cell ``i``
(x uniform on the cell's ``(left, right]``, its side), each with its own noise draw: the chain is Ulam's
approximation of the stochastic throw map (the starting point forgotten below the cell size). Where each
throw ends: a cell, or an absorbing label (:data:`THROW_LABELS`; a rest beyond the cells' span is
``outside``; a policy's stop is ``stop:*``, :data:`STOP_LABELS`).

A **step** is a callable ``step(x, side, rng) -> (x_new, side_new, label)`` over arrays (label ``""``
for a rest on the arm). Two are given:

* :class:`ThrowStep` — open loop: a fixed nominal ω, every throw jittered (ω(1 + σ_ω N(0, 1)), clipped at
  0, :class:`~throwmap.system.noise.Noise`), the arm's motion by the noise's realisation where the
  model takes one (rigid_body rides the recoil arm; "paper" always throws the impulse).
* :class:`PolicyStep` — a feedback policy that is a function of the rest: the controller's sensors are
  read at the sampled rest (their errors drawn per sample) and ``decide`` is asked from its initial
  state. This is exact for controllers without memory: :class:`~throwmap.control.PaperController` with
  ``confirm = 1`` and no hysteresis (its ``want`` is memoryless; with ``confirm = 1`` every wish is
  accepted) — others are refused, since the chain's state would have to include the mode.

Noise drawn once per trial (the arm's μ: ``mu_rel`` / ``mu_range``) is not a per-throw noise: the chain
given μ is Markov and a trial is a mixture over μ. :func:`build_mixture` builds one chain per μ node
(equal-probability quantile midpoints of the μ distribution, :func:`mu_nodes`) and returns a
:class:`~throwmap.stochastic.chain.ChainMixture`.

**Convergence check** (reported, never silent): the samples of each cell are split into two independent
halves, each half gives a matrix, and the total-variation distance between their rows,
TV_i = ½ Σ_j |P^a_ij − P^b_ij|, is reported as its maximum and mean over cells (sampling noise alone gives
about √(n_targets / samples)); :meth:`ChainBuild.curve_gap` compares P(goal by k) of the two halves
(sup over k), and :func:`cell_gap` the curve at the cell size and at half of it.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, shown
from ..rng import as_generator
from .cells import Cells
from .chain import ChainMixture, MarkovChain

__all__ = ["THROW_LABELS", "STOP_LABELS", "ThrowStep", "PolicyStep", "ChainBuild", "build_chain", "build_mixture",
           "mu_nodes", "cell_gap"]

THROW_LABELS = ("off_end", "behind_joint", "refused", "outside")
"""Absorbing states a throw can end in: off the end, behind the joint, refused by the model (any other
status), at rest beyond the cells' span."""
STOP_LABELS = ("stop:goal", "stop:off_goal", "stop:wrong_side")
"""Absorbing states of a policy's stop (entered without a throw): within the goal, on its side outside ε,
on another side."""


def _jitter(omega, noise, rng, n):
    z = rng.standard_normal(n)
    rel = 0.0 if noise is None else noise.omega_rel
    return np.maximum(0.0, np.asarray(omega, dtype=float) * (1.0 + rel * z))


def _throw(part, arm, x, side, w, model, noise, options):
    """One throw of each start on an ensemble of ``model`` (:func:`~throwmap.throws.session.open_ensemble`), with the
    noise's arm motion where the model follows one (``features.realisation``); ``(x, side, label)``."""
    from ..records.outcome import Status
    from ..throws.session import open_ensemble

    kw = dict(options)
    ens = open_ensemble(part, arm, x, side, model, **kw)
    moving = ens.features.realisation and noise is not None and noise.realisation != "impulse" and "realisation" not in kw
    b = ens.throw(w, noise.realisation_for if moving else None)
    st = np.asarray(b.status)
    label = np.full(st.shape, "", dtype=object)
    label[st == int(Status.OFF_END)] = "off_end"
    label[st == int(Status.BEHIND_JOINT)] = "behind_joint"
    label[(st != int(Status.OK)) & (label == "")] = "refused"
    return np.asarray(b.x, dtype=float), np.asarray(b.side, dtype=np.int64), label


@dataclass(frozen=True, slots=True, eq=False)
class ThrowStep:
    """Open-loop throws at nominal ``omega`` (rad/s) on ``model`` with ``noise`` (module docstring);
    ``options``: the model's keywords as (name, value) pairs."""

    part: object
    arm: object
    omega: float
    model: str = "rigid_body"
    noise: object = None
    options: tuple = ()

    labels = THROW_LABELS
    free = ()

    def __post_init__(self):
        w = self.omega
        if isinstance(w, bool) or not isinstance(w, (int, float, np.integer, np.floating)) or not math.isfinite(w) \
                or w <= 0:
            raise InvalidStateError("omega", f"must be a release rate > 0 rad/s, got {shown(w)}")

    def with_arm(self, arm) -> "ThrowStep":
        return dataclasses.replace(self, arm=arm)

    def __call__(self, x, side, rng):
        w = _jitter(self.omega, self.noise, rng, np.size(x))
        return _throw(self.part, self.arm, x, side, w, self.model, self.noise, self.options)

    def to_dict(self) -> dict:
        return {"kind": "open_loop", "omega": self.omega, "model": self.model,
                "noise": None if self.noise is None else self.noise.to_dict()}


def _memoryless(controller) -> None:
    if not getattr(controller, "rest_policy", False):
        raise InvalidStateError("controller", f"the chain needs a policy of the rest alone: a 'paper' or 'inverse' "
                                              f"controller, got {type(controller).__name__}")
    if getattr(controller, "confirm", 1) != 1:
        raise InvalidStateError("controller.confirm", "must be 1 for a chain on rests: confirmations are memory "
                                                      f"(got {controller.confirm})")
    if getattr(controller, "hysteresis", 0.0) != 0.0:
        raise InvalidStateError("controller.hysteresis", "must be 0 for a chain on rests: a hysteretic sensor "
                                                         "remembers its last reading")


@dataclass(frozen=True, slots=True, eq=False)
class PolicyStep:
    """One decision of a memoryless ``controller`` (module docstring) and, unless it stops, its throw."""

    part: object
    arm: object
    controller: object
    model: str = "rigid_body"
    noise: object = None
    options: tuple = ()

    labels = THROW_LABELS + STOP_LABELS
    free = STOP_LABELS

    def __post_init__(self):
        _memoryless(self.controller)

    def with_arm(self, arm) -> "PolicyStep":
        return dataclasses.replace(self, arm=arm)

    def decide(self, x, side, rng) -> np.ndarray:
        """Nominal ω per rest (nan: stop)."""
        ctl = self.controller
        sensors = ctl.sensors()
        names = sorted(sensors)
        out = np.empty(np.size(x))
        s0 = ctl.initial()
        for i, (xi, ki) in enumerate(zip(np.ravel(x), np.ravel(side))):
            obs = {n: sensors[n].read(float(xi), int(ki), rng, None) for n in names}
            d = ctl.decide(s0, obs)
            if d.action == "look":  # pragma: no cover - excluded by _memoryless
                raise InvalidStateError("controller", "asked to look again: not a policy of the rest alone")
            out[i] = math.nan if d.action == "stop" else float(d.omega)
        return out

    def __call__(self, x, side, rng):
        x = np.asarray(x, dtype=float).ravel()
        side = np.asarray(side, dtype=np.int64).ravel()
        w_nom = self.decide(x, side, rng)
        stop = np.isnan(w_nom)
        xn, sn, label = x.copy(), side.copy(), np.full(x.size, "", dtype=object)
        g = self.controller.goal
        on = side == g.side
        label[stop & on & (np.abs(x - g.x) <= g.eps)] = "stop:goal"
        label[stop & on & (np.abs(x - g.x) > g.eps)] = "stop:off_goal"
        label[stop & ~on] = "stop:wrong_side"
        t = ~stop
        if t.any():
            w = _jitter(w_nom[t], self.noise, rng, int(t.sum()))
            xn[t], sn[t], label[t] = _throw(self.part, self.arm, x[t], side[t], w, self.model, self.noise,
                                            self.options)
        return xn, sn, label

    def to_dict(self) -> dict:
        ctl = self.controller
        return {"kind": "policy", "controller": ctl.to_dict() if hasattr(ctl, "to_dict") else type(ctl).__name__,
                "model": self.model, "noise": None if self.noise is None else self.noise.to_dict()}


@dataclass(frozen=True, slots=True, eq=False)
class ChainBuild:
    """A chain estimated from throws, with the chains of the two halves of its samples and the check:
    ``check`` = {samples, cell_m, tv_max, tv_mean, throws}."""

    chain: MarkovChain
    halves: tuple
    check: dict = field(default_factory=dict)

    def curve_gap(self, k_max: int, goal, initial=None) -> float:
        """sup_k |P_a(goal by k) − P_b(goal by k)| between the halves' chains."""
        a, b = (h.p_goal_by(k_max, goal, initial) for h in self.halves)
        return float(np.max(np.abs(a - b)))


def _matrix(cells: Cells, labels: tuple, start: np.ndarray, x, side, label, samples: int, keep) -> np.ndarray:
    n = cells.n
    N = n + len(labels)
    tgt = cells.index(x, side)
    on = label == ""
    tgt = np.where(on & (tgt < 0), n + labels.index("outside"), tgt)
    for j, lab in enumerate(labels):
        tgt = np.where(label == lab, n + j, tgt)
    P = np.zeros((N, N))
    np.add.at(P, (start[keep], tgt[keep]), 1.0)
    P[:n] /= P[:n].sum(axis=1, keepdims=True)
    P[np.arange(n, N), np.arange(n, N)] = 1.0
    return P


def build_chain(cells: Cells, step, *, samples: int = 64, rng=None, initial=None, meta=None,
                within: str = "uniform") -> ChainBuild:
    """The chain of ``step`` on ``cells`` from ``samples`` throws per cell (module docstring), the halves'
    chains and the convergence check. ``initial``: a distribution over the cells (or None: uniform).
    ``within``: ``"uniform"`` (starts uniform in the cell: Ulam's approximation) or ``"centre"`` (every start
    at the cell's midpoint: without noise each row is one unit entry, the map of cell centres)."""
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or samples < 2:
        raise InvalidStateError("samples", f"must be an integer ≥ 2 (two halves), got {shown(samples)}")
    if not isinstance(cells, Cells):
        raise InvalidStateError("cells", f"must be Cells, got {type(cells).__name__}")
    if within not in ("uniform", "centre"):
        raise InvalidStateError("within", f"must be 'uniform' or 'centre', got {shown(within)}")
    rng = as_generator(rng)
    left, right, side = cells.bounds()
    start = np.repeat(np.arange(cells.n), samples)
    u = rng.random(start.size)
    x0 = right[start] - u * (right[start] - left[start])  # uniform on (left, right]
    if within == "centre":
        x0 = 0.5 * (left[start] + right[start])
    xn, sn, label = step(x0, side[start], rng)
    labels = tuple(step.labels)
    half = np.tile(np.arange(samples) % 2 == 0, cells.n)
    P = _matrix(cells, labels, start, xn, sn, label, samples, np.ones(start.size, dtype=bool))
    Pa = _matrix(cells, labels, start, xn, sn, label, samples, half)
    Pb = _matrix(cells, labels, start, xn, sn, label, samples, ~half)
    tv = 0.5 * np.abs(Pa[: cells.n] - Pb[: cells.n]).sum(axis=1)
    all_labels = cells.labels() + labels
    info = dict(meta or {})
    info.update(step.to_dict() if hasattr(step, "to_dict") else {})
    info.update(cells=cells.to_dict(), samples=int(samples))
    mk = lambda M: MarkovChain(M, all_labels, cells.n, initial, tuple(step.free), cells, info)  # noqa: E731
    check = {"samples": int(samples), "cell_m": cells.size, "n_cells": cells.n, "throws": int(start.size),
             "tv_max": float(tv.max()), "tv_mean": float(tv.mean())}
    info["check"] = check
    return ChainBuild(mk(P), (mk(Pa), mk(Pb)), check)


def mu_nodes(noise, mu: float, n: int = 5) -> tuple[np.ndarray, np.ndarray]:
    """``(μ values, weights)``: ``n`` equal-probability quantile midpoints of the trial's μ distribution
    (:meth:`Noise.mu`: uniform over ``mu_range``, else μ(1 + σ_μ N(0, 1)) clipped at 0); one node (μ) when
    the noise has no μ spread or μ is ∞."""
    from statistics import NormalDist

    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise InvalidStateError("mu_nodes", f"must be an integer ≥ 1, got {shown(n)}")
    q = (np.arange(n) + 0.5) / n
    if noise is not None and noise.mu_range is not None:
        lo, hi = noise.mu_range
        return lo + q * (hi - lo), np.full(n, 1.0 / n)
    if noise is None or noise.mu_rel == 0 or math.isinf(mu) or n == 1:
        return np.array([float(mu)]), np.array([1.0])
    z = np.array([NormalDist().inv_cdf(float(v)) for v in q])
    return np.maximum(0.0, mu * (1.0 + noise.mu_rel * z)), np.full(n, 1.0 / n)


def build_mixture(cells: Cells, step, *, samples: int = 64, rng=None, initial=None, n_mu: int = 5,
                  meta=None) -> tuple[ChainMixture, list]:
    """One chain per μ node (:func:`mu_nodes` of the step's noise and arm) and their mixture;
    returns ``(mixture, builds)``. Each node uses its own child stream of ``rng``."""
    rng = as_generator(rng)
    mus, weights = mu_nodes(step.noise, step.arm.mu, n_mu)
    seeds = rng.bit_generator.seed_seq.spawn(len(mus)) if hasattr(rng.bit_generator, "seed_seq") else \
        [rng.integers(2**63) for _ in mus]
    builds = []
    for m, s in zip(mus, seeds):
        arm = dataclasses.replace(step.arm, mu=float(m))
        builds.append(build_chain(cells, step.with_arm(arm), samples=samples, rng=np.random.default_rng(s),
                                  initial=initial, meta=dict(meta or {}, mu=float(m))))
    info = dict(meta or {}, mu_nodes=[float(m) for m in mus],
                check={"tv_max": max(b.check["tv_max"] for b in builds),
                       "tv_mean": float(np.mean([b.check["tv_mean"] for b in builds])),
                       "samples": int(samples), "cell_m": cells.size, "n_cells": cells.n,
                       "throws": sum(b.check["throws"] for b in builds)})
    return ChainMixture(tuple(b.chain for b in builds), weights, info), builds


def cell_gap(curve_at, cell: float, k_max: int) -> float:
    """sup_k |curve(cell) − curve(cell / 2)|, ``curve_at(cell) -> P(goal by k), k = 0 … k_max`` (the caller
    builds both chains: the check for the cell size)."""
    a = np.asarray(curve_at(cell))[: k_max + 1]
    b = np.asarray(curve_at(0.5 * cell))[: k_max + 1]
    return float(np.max(np.abs(a - b)))
