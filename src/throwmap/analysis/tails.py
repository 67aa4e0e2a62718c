"""The tails of a configuration map's orbits: every start thrown on, the last throws recorded (paper Sec. III-D).

:func:`run_orbits` is the recurrence test's engine room (:mod:`throwmap.analysis.recurrence`
reads the tails it records). A map that declares itself deterministic has its exactly
repeating orbits copied on instead of thrown, with the same arrays as a result.
"""

from __future__ import annotations

import numpy as np

from ..kernels import codes as C
from .maps import ConfigMap

__all__ = ["run_orbits", "bytes_per_orbit", "EXACT_PERIOD_MAX"]


EXACT_PERIOD_MAX = 16
"""Longest exact repeat (throws) :func:`run_orbits` looks for in a deterministic map's orbits."""


def run_orbits(cmap: ConfigMap, x0, s0, n_skip: int, n_record: int, progress=None):
    """Iterate ``cmap`` ``n_skip + n_record`` times from every start; record the last ``n_record``.

    Returns ``(X, S, fate, fate_step)``: recorded x (m) and sides, shape (M, n_record),
    nan / −1 after an escape; ``fate`` the escape status (0 if none) and ``fate_step``
    the step at which it happened (−1 if none). ``progress(done, total)`` after each step.

    For a map that declares itself ``deterministic`` (every :class:`ThrowMap`), an orbit
    that comes back to a state it had p ≤ :data:`EXACT_PERIOD_MAX` throws before — the
    same side and the same float, bit for bit — repeats those p states for ever: it is
    no longer thrown, its remaining states are copied from the repeat. The arrays are
    the same, bit for bit, as throwing it on (a fixed point reached to the last bit
    costs a few throws, not ``n_skip + n_record``).
    """
    x = np.array(x0, dtype=float).ravel()
    s = np.array(s0).ravel().astype(np.int64)
    m = x.size
    X = np.full((m, n_record), np.nan)
    S = np.full((m, n_record), -1, dtype=np.int64)
    fate = np.zeros(m, dtype=np.int64)
    fate_step = np.full(m, -1, dtype=np.int64)
    total = n_skip + n_record
    exact = bool(getattr(cmap, "deterministic", False))
    P = EXACT_PERIOD_MAX
    if exact:  # the last P states of each orbit (ring, slot t % P holds the state after t throws)
        hx = np.zeros((m, P), dtype=np.int64)
        hs = np.full((m, P), -1, dtype=np.int64)
        hx[:, 0] = x.view(np.int64)
        hs[:, 0] = s
        period = np.zeros(m, dtype=np.int64)  # > 0: the orbit repeats with this period
        cyc_x = np.zeros((m, P))  # its p states, in order
        cyc_s = np.zeros((m, P), dtype=np.int64)
        since = np.zeros(m, dtype=np.int64)  # throws done when the repeat was found
    rep = np.zeros(0, dtype=np.int64)  # the orbits copied from their repeat, not thrown
    for t in range(total):
        if exact:
            rep = np.flatnonzero(period > 0)
            if rep.size:
                k = (t - since[rep]) % period[rep]
                x[rep] = cyc_x[rep, k]
                s[rep] = cyc_s[rep, k]
            alive = np.flatnonzero((fate == C.OK) & (period == 0))
        else:
            alive = np.flatnonzero(fate == C.OK)
        if alive.size == 0 and rep.size == 0:
            if progress is not None:
                progress(total, total)
            break
        if alive.size:
            xn, sn, st = cmap(x[alive], s[alive])
            bad = st != C.OK
            fate[alive[bad]] = st[bad]
            fate_step[alive[bad]] = t + 1
            x[alive] = np.where(bad, x[alive], xn)
            s[alive] = np.where(bad, s[alive], sn)
            if exact:
                _find_repeats(alive[~bad], t + 1, x, s, hx, hs, period, cyc_x, cyc_s, since)
        else:
            bad = np.zeros(0, dtype=bool)
        if t >= n_skip:
            ok = alive[~bad]
            X[ok, t - n_skip] = x[ok]
            S[ok, t - n_skip] = s[ok]
            if rep.size:
                X[rep, t - n_skip] = x[rep]
                S[rep, t - n_skip] = s[rep]
        if progress is not None:
            progress(t + 1, total)
    return X, S, fate, fate_step


def _find_repeats(idx, n, x, s, hx, hs, period, cyc_x, cyc_s, since):
    """Orbits ``idx`` after ``n`` throws: mark those whose state equals, bit for bit, one of their last P.

    An orbit found to repeat with period p (the smallest) gets its p states (those after throws
    n − p + 1 … n, in order) in ``cyc_x``/``cyc_s`` and ``since`` = n; the state after
    throw n + j is then entry (j − 1) mod p of them.
    """
    if idx.size == 0:
        return
    P = hx.shape[1]
    bits = x[idx].view(np.int64)
    side = s[idx]
    n_back = min(P, n)
    cols = (n - np.arange(1, n_back + 1)) % P  # column of the state p = 1 … n_back throws back
    same = (hx[idx][:, cols] == bits[:, None]) & (hs[idx][:, cols] == side[:, None])
    hx[idx, n % P] = bits
    hs[idx, n % P] = side
    hit = np.flatnonzero(same.any(axis=1))
    if hit.size == 0:
        return
    p = same[hit].argmax(axis=1) + 1  # the smallest period
    rows = idx[hit]
    q = np.arange(P)
    slots = (n - p[:, None] + 1 + q[None, :]) % P  # state after throw n − p + 1 + q (used for q < p)
    cyc_x[rows] = hx[rows[:, None], slots].view(np.float64)
    cyc_s[rows] = hs[rows[:, None], slots]
    period[rows] = p
    since[rows] = n


def bytes_per_orbit(n_record: int) -> int:
    """Memory :func:`run_orbits` holds per start, bytes: the recorded x and sides (16 per recorded throw), the
    current state and fate (32), and the repeat search's four rings of :data:`EXACT_PERIOD_MAX` (32 each)."""
    return 16 * int(n_record) + 64 + 32 * EXACT_PERIOD_MAX
