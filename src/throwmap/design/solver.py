"""Damped Newton / Levenberg–Marquardt with bounds and finite-difference Jacobians (paper Sec. V-A).

The draft solves F(p, r*) = 0 with Mathematica's FindRoot (a damped Newton method) after
checking that ∂F/∂p has full rank (the implicit-function theorem: rank = number of targets
means the targets can be moved independently near p, so a root is locally reachable). Here
the residual is "achieved feature − target" on the exact map and :func:`damped_lm` is a
Levenberg–Marquardt iteration (Marquardt's diagonal damping, so the step does not depend on
the parameters' units) with projection onto the bounds.

Jacobian
--------
Central differences ``(f(p + h_j e_j) − f(p − h_j e_j)) / 2h_j`` (one-sided where p ± h_j e_j
leaves the bounds; a column is zero where both do). A feature found to ``noise`` (e.g. r_i
to ``xtol``) gives a derivative error ≤ noise / h_j, so h_j ≫ noise / |∂f/∂p_j| keeps it small
while the O(h²) truncation error stays below the solver's tolerance.

Rank and condition
------------------
Both are reported at the start and at the solution for J·diag(scale) (p in the parameters'
typical units). A singular value counts towards the rank when it exceeds
``10 √(m n) max_j(noise · scale_j / h_j)``: the size of the difference noise in those units.
``condition`` is σ_max / σ_min over the min(m, n) singular values (inf if one is zero).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from ..errors import InvalidStateError, shown

__all__ = ["Iterate", "Jacobian", "LMReport", "LMSettings", "damped_lm", "fd_jacobian", "jacobian_summary"]


@dataclass(frozen=True, slots=True)
class Iterate:
    """One accepted point of the iteration: p (SI), the residual rows (m), |residual|, λ, active bounds, info."""

    p: tuple
    residual: dict
    norm: float
    lam: float
    bounds_hit: tuple
    info: Any


@dataclass(frozen=True, slots=True)
class Jacobian:
    """∂residual/∂p at one point: ``matrix`` (rows × parameters, SI), singular values of
    J·diag(scale), ``rank`` with its threshold ``rank_tol``, ``condition``."""

    matrix: np.ndarray
    singular_values: tuple
    rank: int
    rank_tol: float
    condition: float


@dataclass(frozen=True, slots=True)
class LMReport:
    success: bool
    message: str
    p: np.ndarray
    residual: np.ndarray
    info: Any
    iterates: tuple
    jacobian_start: Jacobian | None
    jacobian_end: Jacobian | None
    n_evals: int


def jacobian_summary(J: np.ndarray, scale: np.ndarray, step: np.ndarray, noise: float) -> Jacobian:
    """Rank, singular values and condition of J·diag(scale) (see the module's Notes)."""
    Jz = np.asarray(J, dtype=float) * np.asarray(scale, dtype=float)[None, :]
    m, n = Jz.shape
    s = np.linalg.svd(Jz, compute_uv=False) if Jz.size else np.zeros(0)
    tol = 10.0 * math.sqrt(m * n) * float(np.max(noise * np.asarray(scale) / np.asarray(step))) if n else 0.0
    tol = max(tol, 1e-12 * (float(s[0]) if s.size else 0.0))
    rank = int(np.sum(s > tol))
    cond = float(s[0] / s[-1]) if s.size and s[-1] > 0 else math.inf
    return Jacobian(matrix=np.array(J, dtype=float), singular_values=tuple(float(v) for v in s), rank=rank,
                    rank_tol=float(tol), condition=cond)


def fd_jacobian(fun, p, f0, step, project) -> tuple[np.ndarray, int]:
    """Central-difference Jacobian of ``fun`` at p; returns (J, evaluations).

    One-sided where p ± h leaves the bounds or the features are undefined (nan) there; a zero
    column where neither side can be evaluated."""
    p = np.asarray(p, dtype=float)
    J = np.zeros((f0.size, p.size))
    n_ev = 0
    for j in range(p.size):
        e = np.zeros(p.size)
        e[j] = step[j]
        pp, _ = project(p + e)
        pm, _ = project(p - e)
        up, dn = abs(pp[j] - (p[j] + step[j])) < 1e-15, abs(pm[j] - (p[j] - step[j])) < 1e-15
        fp = fm = None
        if up:
            fp, _ = fun(pp)
            n_ev += 1
            fp = fp if np.all(np.isfinite(fp)) else None
        if dn:
            fm, _ = fun(pm)
            n_ev += 1
            fm = fm if np.all(np.isfinite(fm)) else None
        if fp is not None and fm is not None:
            J[:, j] = (fp - fm) / (2 * step[j])
        elif fp is not None:
            J[:, j] = (fp - f0) / step[j]
        elif fm is not None:
            J[:, j] = (f0 - fm) / step[j]
        # else: the features are undefined on both sides (or p_j is pinned by its bounds): a zero column
    return J, n_ev


@dataclass(frozen=True, slots=True)
class LMSettings:
    """How long the damped Levenberg–Marquardt iteration runs: ``max_iter`` outer iterations, ``lam0`` initial
    damping, ``max_tries`` damping increases tried per iteration; it stops ("residual stalled") when
    ``stall_window`` accepted steps reduce |residual| by less than the fraction ``stall_rtol``."""

    max_iter: int = 40
    lam0: float = 1e-3
    max_tries: int = 10
    stall_window: int = 5
    stall_rtol: float = 0.01

    def __post_init__(self):
        for name in ("max_iter", "max_tries", "stall_window"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < 1:
                raise InvalidStateError(name, f"must be an integer ≥ 1, got {shown(v)}")
        for name in ("lam0", "stall_rtol"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not (math.isfinite(v) and v > 0):
                raise InvalidStateError(name, f"must be a positive finite number, got {shown(v)}")


def damped_lm(fun: Callable, p0, *, project: Callable, scale, step, tol: float, noise: float, labels=None,
              inequality=None, settings: LMSettings = LMSettings()) -> LMReport:
    """Solve ``fun(p)[0] = 0`` (residual rows, m) by damped Levenberg–Marquardt within bounds.

    Parameters
    ----------
    fun
        ``p -> (residual vector, info)``; nan rows mean "undefined here" (a step there is refused).
    project
        ``p -> (p in the bounds, names of the active bounds)``.
    scale, step
        Typical size and finite-difference half-step of each parameter (SI).
    tol
        Success when every |residual| ≤ tol (m).
    noise
        How precisely ``fun`` finds its features (m), for the rank threshold.
    labels
        A name per residual row (for the history and messages).
    inequality
        Per row, whether it is a hinge max(0, …) of an inequality; a satisfied one (zero) is
        inactive and does not count among the targets the rank is compared with (the
        implicit-function test concerns the active rows only).
    settings
        The iteration's caps and its stall test (:class:`LMSettings`).

    Returns an :class:`LMReport`; never raises on non-convergence: ``success`` False and
    ``message`` says why (features undefined, rank deficient, a bound, a stalled residual,
    the iteration cap).
    """
    scale = np.asarray(scale, dtype=float)
    step = np.asarray(step, dtype=float)
    max_iter, lam0, max_tries = settings.max_iter, settings.lam0, settings.max_tries
    stall_window, stall_rtol = settings.stall_window, settings.stall_rtol
    p, hits = project(np.asarray(p0, dtype=float))
    f, info = fun(p)
    n_ev = 1
    labels = list(labels) if labels is not None else [str(i) for i in range(f.size)]

    def it(p, f, lam, hits, info):
        return Iterate(p=tuple(float(v) for v in p), residual=dict(zip(labels, (float(v) for v in f))),
                       norm=float(np.linalg.norm(f)), lam=float(lam), bounds_hit=tuple(hits), info=info)

    lam = lam0
    iterates = [it(p, f, lam, hits, info)]
    if not np.all(np.isfinite(f)):
        bad = [lb for lb, v in zip(labels, f) if not math.isfinite(v)]
        return LMReport(False, f"the targeted features are undefined at the start ({', '.join(bad)}: no such "
                               "critical point or limit set on that side)", p, f, info, tuple(iterates), None, None, n_ev)
    J, k = fd_jacobian(fun, p, f, step, project)
    n_ev += k
    jac0 = jacobian_summary(J, scale, step, noise)
    ineq = np.zeros(f.size, dtype=bool) if inequality is None else np.asarray(inequality, dtype=bool)

    def n_active(f):
        return int(np.sum(~ineq) + np.sum(ineq & (np.abs(f) > 0)))

    m0 = n_active(f)
    message = ""
    success = False
    for _ in range(max_iter):
        if np.max(np.abs(f)) <= tol:
            success = True
            break
        Jz = J * scale[None, :]
        A = Jz.T @ Jz
        g = Jz.T @ f
        d = np.diag(A).copy()
        d = np.where(d > 0, d, 1e-12 * max(float(d.max()), 1e-300))
        accepted = False
        for _try in range(max_tries):
            try:
                dz = -np.linalg.solve(A + lam * np.diag(d), g)
            except np.linalg.LinAlgError:
                lam *= 4.0
                continue
            if not np.all(np.isfinite(dz)):
                lam *= 4.0
                continue
            pn, hn = project(p + dz * scale)
            if np.allclose(pn, p, rtol=0.0, atol=1e-14):
                break
            fn, infon = fun(pn)
            n_ev += 1
            if np.all(np.isfinite(fn)) and np.linalg.norm(fn) < np.linalg.norm(f):
                p, f, info, hits = pn, fn, infon, hn
                lam = max(lam / 3.0, 1e-9)
                accepted = True
                break
            lam *= 4.0
        if not accepted:
            if hits:
                message = f"hit a bound ({'; '.join(hits)}) with the residual {1000 * np.max(np.abs(f)):.3g} mm > tol"
            else:
                message = (f"residual stalled at {1000 * np.max(np.abs(f)):.3g} mm: no damped step reduces it "
                           f"(λ = {lam:.3g})")
            break
        iterates.append(it(p, f, lam, hits, info))
        if len(iterates) > stall_window and iterates[-1].norm > (1 - stall_rtol) * iterates[-1 - stall_window].norm:
            message = (f"residual stalled at {1000 * np.max(np.abs(f)):.3g} mm (less than {100 * stall_rtol:g} % "
                       f"progress in {stall_window} steps)")
            if hits:
                message += f", at a bound ({'; '.join(hits)})"
            break
        J, k = fd_jacobian(fun, p, f, step, project)
        n_ev += k
    else:
        if np.max(np.abs(f)) <= tol:
            success = True
        else:
            message = f"iteration cap ({max_iter}) reached with the residual {1000 * np.max(np.abs(f)):.3g} mm > tol"
            if hits:
                message += f", at a bound ({'; '.join(hits)})"
    if not success and not message:  # pragma: no cover - every exit above sets one
        message = "not converged"
    J_end, k = fd_jacobian(fun, p, f, step, project)
    n_ev += k
    jac1 = jacobian_summary(J_end, scale, step, noise)
    m = n_active(f)
    if success:
        message = f"reached: every |achieved − target| ≤ {1000 * tol:.3g} mm after {len(iterates) - 1} steps"
        if jac1.rank < m:
            message += (f"; the Jacobian's rank {jac1.rank} < {m} targets (near the solution the targets cannot all be "
                        "moved independently)")
    else:
        if jac0.rank < m0 or jac1.rank < m:
            message += (f"; the Jacobian is rank deficient (rank {jac0.rank} at the start, {jac1.rank} at the end, "
                        f"< {max(m0, m)} targets): the targets cannot all be moved independently (implicit-function "
                        "test fails)")
    return LMReport(success, message, p, f, info, tuple(iterates), jac0, jac1, n_ev)
