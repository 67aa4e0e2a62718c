"""A stochastic throw map as a finite Markov chain.

One step of the chain is one decision of the thrower: a throw (the part goes from its cell to the cell
it comes to rest in, or leaves the arm), or — for a feedback policy — a stop. States ``0 … n−1`` are
the cells (:class:`~throwmap.stochastic.cells.Cells`), the rest are absorbing labels (``off_end``,
``behind_joint``, ``refused``, ``outside`` for a rest beyond the cells' span, ``stop:goal``,
``stop:off_goal``, ``stop:wrong_side``). A state is absorbing iff its row of ``P`` is the unit row.

Stops are decisions, not throws: the absorbing states named in ``free`` are entered without a throw, so
that "after k throws" counts only throws (:meth:`MarkovChain.p_goal_by`, :meth:`expected_throws`).

What is computed (dense linear algebra; a chain has at most a few thousand states):

* :meth:`MarkovChain.p_goal_by` — P(goal reached by throw k), k = 0 … K, from an initial distribution;
  goal states are made absorbing first (first hitting).
* :meth:`MarkovChain.absorption` — the absorption probabilities B = (I − Q)⁻¹ R (Kemeny & Snell 1960,
  Thm. 3.3.7) over the cells that can reach an absorbing state, and ``escape`` = 1 − Σ B: the mass kept
  on the arm for ever (a closed class of cells: a fixed point or cycle of the throw map that noise does
  not break). ``sum(B) + escape = 1`` holds by construction; a test pins it.
* :meth:`MarkovChain.expected_throws` — E[throws to absorption] = (I − Q)⁻¹ 1 (inf where absorption is
  not certain), or given a goal, E[throws | the goal is reached] = (N h)/h, h the goal's absorption
  probability (the Doob h-transform).
* :meth:`MarkovChain.stationary` — the long-run distribution from an initial one: the mean of π₀Pᵏ over a
  window (m, 2m] (a periodic orbit of the map gives its average), m doubling up to a documented cap: the
  "probability mass funnelled" of the draft (Sec. III-D), split into the mass on the arm per cell and
  the mass absorbed.

:class:`ChainMixture` averages chains with weights (a trial-level random parameter such as the arm's μ,
drawn once per trial: the chain conditional on μ is Markov, the trial is a mixture of them).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..errors import InvalidStateError, shown

__all__ = ["MarkovChain", "ChainMixture", "Absorption", "Stationary"]

ROW_TOL = 1e-9
"""Rows of P must sum to 1 within this."""


@dataclass(frozen=True, slots=True, eq=False)
class Absorption:
    """Absorption from every cell: ``B`` (n_cells × n_absorbing), ``escape`` (n_cells,) the probability of
    never being absorbed, ``labels`` of the absorbing states (columns of B)."""

    B: np.ndarray
    escape: np.ndarray
    labels: tuple

    def of(self, initial) -> dict:
        """Absorption probabilities from an initial distribution over cells: {label: p, 'escape': p}."""
        w = np.asarray(initial, dtype=float)[: self.B.shape[0]]
        w = w / w.sum()
        out = {lab: float(w @ self.B[:, j]) for j, lab in enumerate(self.labels)}
        out["escape"] = float(w @ self.escape)
        return out


@dataclass(frozen=True, slots=True, eq=False)
class Stationary:
    """The long-run distribution (the mean of π₀Pᵏ over k in (steps/2, steps]; or, from
    :meth:`MarkovChain.quasi_stationary`, the distribution conditioned on not yet absorbed, with ``rate`` the
    probability per throw of staying unabsorbed): ``pi`` over all states,
    ``converged`` (the mean moved by < ``tol`` in total variation over the last doubling), ``labels``,
    ``cells`` (for the per-side split), ``n_cells``."""

    pi: np.ndarray
    labels: tuple
    n_cells: int
    steps: int
    converged: bool
    cells: object = None
    rate: float = math.nan

    @property
    def on_arm(self) -> float:
        """The mass resting on the arm (in the cells) in the long run."""
        return float(self.pi[: self.n_cells].sum())

    def absorbed(self) -> dict:
        return {lab: float(p) for lab, p in zip(self.labels[self.n_cells:], self.pi[self.n_cells:])}

    def per_side(self) -> dict:
        """{side: (left edges m, right edges m, mass per cell)}."""
        if self.cells is None:
            raise InvalidStateError("cells", "this chain has no cells to split by side")
        left, right, side = self.cells.bounds()
        p = self.pi[: self.n_cells]
        return {int(k): (left[side == k], right[side == k], p[side == k]) for k in self.cells.sides}

    def plot(self, ax=None, **kw):
        """Mass per cell against x, one panel per side (:func:`throwmap.viz.chain.plot_stationary`)."""
        from ..viz.chain import plot_stationary

        return plot_stationary(self.per_side(), self.absorbed(), ax=ax, **kw)


def _check_P(P: np.ndarray) -> np.ndarray:
    P = np.asarray(P, dtype=float)
    if P.ndim != 2 or P.shape[0] != P.shape[1]:
        raise InvalidStateError("P", f"must be a square matrix, got shape {P.shape}")
    if not np.all(np.isfinite(P)) or np.any(P < 0):
        raise InvalidStateError("P", "must have finite entries ≥ 0")
    s = P.sum(axis=1)
    bad = np.flatnonzero(np.abs(s - 1.0) > ROW_TOL)
    if bad.size:
        raise InvalidStateError("P", f"row {int(bad[0])} sums to {s[bad[0]]:.12g}, not 1")
    return P


@dataclass(frozen=True, slots=True, eq=False)
class MarkovChain:
    """A chain on cells and absorbing labels (module docstring).

    ``P``: (N, N) row-stochastic; ``labels``: N names; ``n_cells``: the first ``n_cells`` states are the
    cells; ``initial``: (N,) distribution or None; ``free``: labels of absorbing states entered without a
    throw (a stop); ``cells``: the :class:`~throwmap.stochastic.cells.Cells` or None; ``meta``: how it was
    built (model, ω, noise, samples, seed, convergence check).
    """

    P: np.ndarray
    labels: tuple
    n_cells: int
    initial: np.ndarray | None = None
    free: tuple = ()
    cells: object = None
    meta: dict = field(default_factory=dict)

    def __post_init__(self):
        P = _check_P(self.P)
        object.__setattr__(self, "P", P)
        if len(self.labels) != P.shape[0]:
            raise InvalidStateError("labels", f"need {P.shape[0]} labels, got {len(self.labels)}")
        object.__setattr__(self, "labels", tuple(str(s) for s in self.labels))
        if not 0 <= int(self.n_cells) <= P.shape[0]:
            raise InvalidStateError("n_cells", f"must be in [0, {P.shape[0]}], got {shown(self.n_cells)}")
        object.__setattr__(self, "n_cells", int(self.n_cells))
        if self.initial is not None:
            object.__setattr__(self, "initial", self._distribution(self.initial))
        unknown = [f for f in self.free if f not in self.labels]
        if unknown:
            raise InvalidStateError("free", f"unknown state {unknown[0]!r}")

    @property
    def n(self) -> int:
        return self.P.shape[0]

    @property
    def absorbing(self) -> np.ndarray:
        """Boolean mask: the states whose row is the unit row."""
        return np.diag(self.P) == 1.0

    def _distribution(self, initial) -> np.ndarray:
        w = np.asarray(initial, dtype=float)
        if w.shape == (self.n_cells,):
            w = np.concatenate([w, np.zeros(self.n - self.n_cells)])
        if w.shape != (self.n,) or not np.all(np.isfinite(w)) or np.any(w < 0) or not w.sum() > 0:
            raise InvalidStateError("initial", f"must be {self.n} (or {self.n_cells}) masses ≥ 0, not all 0")
        return w / w.sum()

    def _initial(self, initial) -> np.ndarray:
        if initial is None:
            if self.initial is None:
                return self._distribution(np.ones(self.n_cells))
            return self.initial
        return self._distribution(initial)

    def states(self, goal) -> np.ndarray:
        """A boolean mask of states from labels, indices or a mask over cells/states."""
        if isinstance(goal, str):
            goal = [goal]
        g = np.asarray(goal)
        if g.dtype == bool:
            if g.shape == (self.n_cells,):
                g = np.concatenate([g, np.zeros(self.n - self.n_cells, dtype=bool)])
            if g.shape != (self.n,):
                raise InvalidStateError("goal", f"a mask must have {self.n_cells} or {self.n} entries")
            return g
        mask = np.zeros(self.n, dtype=bool)
        for s in list(goal):
            if isinstance(s, str):
                if s not in self.labels:
                    raise InvalidStateError("goal", f"unknown state {s!r}")
                mask[self.labels.index(s)] = True
            else:
                if isinstance(s, bool) or not isinstance(s, (int, np.integer)) or not 0 <= int(s) < self.n:
                    raise InvalidStateError("goal", f"state index {shown(s)} is not one of the chain's states "
                                                    f"0 … {self.n - 1}")
                mask[int(s)] = True
        return mask

    def with_goal(self, goal) -> "MarkovChain":
        """The chain with the ``goal`` states made absorbing (first hitting)."""
        g = self.states(goal)
        P = self.P.copy()
        P[g] = 0.0
        P[g, np.flatnonzero(g)] = 1.0
        return MarkovChain(P, self.labels, self.n_cells, self.initial, self.free, self.cells, dict(self.meta))

    def evolve(self, k_max: int, initial=None) -> np.ndarray:
        """(k_max + 1, N): the distribution after 0 … k_max steps."""
        w = self._initial(initial)
        out = np.empty((int(k_max) + 1, self.n))
        out[0] = w
        for k in range(1, int(k_max) + 1):
            out[k] = out[k - 1] @ self.P
        return out

    def p_goal_by(self, k_max: int, goal, initial=None) -> np.ndarray:
        """P(goal reached by throw k), k = 0 … ``k_max`` (the goal states made absorbing; a goal state in
        ``free`` — a stop — is reached at the step after the k-th throw, and counted at k)."""
        from ..budget import guard_work

        if isinstance(k_max, bool) or not isinstance(k_max, (int, np.integer)) or k_max < 0:
            raise InvalidStateError("k_max", f"must be an integer ≥ 0, got {shown(k_max)}")
        k_max = int(k_max)
        g = self.states(goal)
        free = self.states(list(self.free)) if self.free else np.zeros(self.n, dtype=bool)
        chain = self.with_goal(g)
        w = chain._initial(initial)

        def one_step_seconds():
            t0 = time.perf_counter()
            _ = w @ chain.P
            return time.perf_counter() - t0

        guard_work("p_goal_by", "k_max", k_max + 1, 8.0, throws_per_config=1.0, timer=one_step_seconds,
                   hint="a smaller k_max", unit="steps")
        held, newly = g & ~free, g & free  # a goal stop is counted one step later, at the throw before it
        out = np.empty(k_max + 1)
        for k in range(k_max + 1):
            nxt = w @ chain.P
            out[k] = w[held].sum() + nxt[newly].sum()
            w = nxt
        return out

    def _reach(self) -> np.ndarray:
        """Mask of the states that can reach an absorbing state (absorbing ones included)."""
        A = self.absorbing
        can = A.copy()
        adj = self.P > 0
        while True:
            new = can | adj[:, can].any(axis=1)
            if np.array_equal(new, can):
                return can
            can = new

    def absorption(self) -> Absorption:
        """Absorption probabilities from every cell (module docstring); cells that are absorbing themselves
        (a goal made absorbing) are columns too."""
        A = self.absorbing
        T = ~A
        ok = self._reach() & T
        idx = np.flatnonzero(ok)
        cols = np.flatnonzero(A)
        Q = self.P[np.ix_(idx, idx)]
        R = self.P[np.ix_(idx, cols)]
        B_ok = np.linalg.solve(np.eye(idx.size) - Q, R) if idx.size else np.zeros((0, cols.size))
        B = np.zeros((self.n_cells, cols.size))
        full = np.zeros((self.n, cols.size))
        full[idx] = B_ok
        full[cols, np.arange(cols.size)] = 1.0
        B = full[: self.n_cells]
        escape = np.clip(1.0 - B.sum(axis=1), 0.0, 1.0)
        return Absorption(B, escape, tuple(self.labels[c] for c in cols))

    def expected_throws(self, goal=None) -> np.ndarray:
        """Per cell: E[throws until absorption] (inf where absorption is not certain), or with ``goal``
        E[throws | the goal is reached first among the absorbing states] (nan where it is never reached)."""
        chain = self if goal is None else self.with_goal(goal)
        A = chain.absorbing
        ok = chain._reach() & ~A
        idx = np.flatnonzero(ok)
        N = np.linalg.inv(np.eye(idx.size) - chain.P[np.ix_(idx, idx)]) if idx.size else np.zeros((0, 0))
        out = np.full(chain.n, np.nan)
        free = chain.states(list(chain.free)) if chain.free else np.zeros(chain.n, dtype=bool)
        if goal is None:
            ab = chain.absorption()
            steps = N.sum(axis=1)
            fcols = [j for j, lab in enumerate(ab.labels) if lab in chain.free]
            pf = ab.B[:, fcols].sum(axis=1) if fcols else np.zeros(chain.n_cells)
            out[idx] = steps - pf[idx]
            out[: chain.n_cells][ab.escape > 1e-12] = math.inf
            out[A] = 0.0
            return out[: chain.n_cells]
        ab = chain.absorption()
        g = chain.states(goal)
        gcols = [j for j, lab in enumerate(ab.labels) if g[chain.labels.index(lab)]]
        fcols = [j for j in gcols if ab.labels[j] in chain.free]
        full_h = np.zeros(chain.n)
        full_h[: chain.n_cells] = ab.B[:, gcols].sum(axis=1)
        full_f = np.zeros(chain.n)
        full_f[: chain.n_cells] = ab.B[:, fcols].sum(axis=1) if fcols else 0.0
        h, hf = full_h[idx], full_f[idx]
        with np.errstate(invalid="ignore", divide="ignore"):
            out[idx] = np.where(h > 1e-15, (N @ h - hf) / h, np.nan)
        out[g] = 0.0
        return out[: chain.n_cells]

    def reach(self, goal, initial=None) -> tuple[float, float]:
        """``(P(goal reached), E[throws | goal reached])`` from ``initial`` (the goal made absorbing)."""
        w = self._initial(initial)[: self.n_cells]
        chain = self.with_goal(goal)
        g = chain.states(goal)
        ab = chain.absorption()
        cols = [j for j, lab in enumerate(ab.labels) if g[chain.labels.index(lab)]]
        h = ab.B[:, cols].sum(axis=1)
        e = np.nan_to_num(chain.expected_throws(goal), nan=0.0, posinf=0.0)
        p = float(w @ h)
        return p, float(w @ (h * e)) / p if p > 0 else math.nan

    def quasi_stationary(self) -> Stationary:
        """The quasi-stationary distribution: the left Perron vector of the block Q of the non-absorbing states
        (where a part that has not left the arm is found after many throws, whatever the start, on an irreducible
        Q; Darroch & Seneta 1965), normalised; ``rate`` its eigenvalue (the per-throw probability of staying).
        A cell that maps to itself alone is absorbing here, not part of Q."""
        T = np.flatnonzero(~self.absorbing)
        pi = np.zeros(self.n)
        if T.size == 0:
            return Stationary(pi, self.labels, self.n_cells, 0, False, self.cells, 0.0)
        vals, vecs = np.linalg.eig(self.P[np.ix_(T, T)].T)
        j = int(np.argmax(vals.real))
        v = np.abs(vecs[:, j].real)
        pi[T] = v / v.sum() if v.sum() > 0 else 0.0
        return Stationary(pi, self.labels, self.n_cells, 0, bool(v.sum() > 0), self.cells, float(vals[j].real))

    def stationary(self, initial=None, *, max_steps: int = 100_000, tol: float = 1e-10) -> Stationary:
        """The long-run distribution from ``initial``: the mean of π₀Pᵏ over the window (m, 2m], m doubling
        until two windows' means differ by < ``tol`` in total variation or 2m passes ``max_steps`` (then
        ``converged`` is False). A periodic orbit of the map gives its average over the period."""
        w = self._initial(initial)
        cur, m, prev, converged = w @ self.P, 1, None, False
        while True:
            acc = np.zeros_like(cur)
            for _ in range(m):
                cur = cur @ self.P
                acc += cur
            mean = acc / m
            if prev is not None and 0.5 * np.abs(mean - prev).sum() < tol:
                converged = True
            prev = mean
            if converged or 2 * m > max_steps:
                break
            m *= 2
        return Stationary(prev / prev.sum(), self.labels, self.n_cells, 2 * m, converged, self.cells)


@dataclass(frozen=True, slots=True, eq=False)
class ChainMixture:
    """Chains with weights (a trial-level parameter drawn once per trial, e.g. μ): P(goal by k),
    absorption and the stationary distribution are the weighted means of the chains'."""

    chains: tuple
    weights: np.ndarray
    meta: dict = field(default_factory=dict)

    def __post_init__(self):
        w = np.asarray(self.weights, dtype=float)
        if len(self.chains) == 0 or w.shape != (len(self.chains),) or np.any(w < 0) or not w.sum() > 0:
            raise InvalidStateError("weights", "need one weight ≥ 0 per chain, not all 0")
        object.__setattr__(self, "weights", w / w.sum())
        object.__setattr__(self, "chains", tuple(self.chains))

    @property
    def cells(self):
        return self.chains[0].cells

    @property
    def labels(self):
        return self.chains[0].labels

    @property
    def n_cells(self):
        return self.chains[0].n_cells

    @property
    def free(self):
        return self.chains[0].free

    def p_goal_by(self, k_max: int, goal, initial=None) -> np.ndarray:
        return sum(w * c.p_goal_by(k_max, goal, initial) for w, c in zip(self.weights, self.chains))

    def reach(self, goal, initial=None) -> tuple[float, float]:
        """``(P(goal reached), E[throws | goal reached])`` of the mixture."""
        parts = [c.reach(goal, initial) for c in self.chains]
        p = float(sum(w * q for w, (q, _) in zip(self.weights, parts)))
        m = sum(w * q * e for w, (q, e) in zip(self.weights, parts) if q > 0)
        return p, float(m) / p if p > 0 else math.nan

    def absorption_of(self, initial=None) -> dict:
        out: dict = {}
        for w, c in zip(self.weights, self.chains):
            for k, v in c.absorption().of(c._initial(initial)).items():
                out[k] = out.get(k, 0.0) + w * v
        return out

    def stationary(self, initial=None, **kw) -> Stationary:
        parts = [c.stationary(initial, **kw) for c in self.chains]
        pi = sum(w * s.pi for w, s in zip(self.weights, parts))
        return Stationary(pi, parts[0].labels, parts[0].n_cells, max(s.steps for s in parts),
                          all(s.converged for s in parts), parts[0].cells)
