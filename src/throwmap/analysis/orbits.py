"""Orbits lying on a limit set, for drawing (paper Sec. III-D, Fig. 5).

:func:`orbit_on_attractor` brings one of a :class:`~throwmap.analysis.limitset.LimitSet`'s
starting configurations onto its attractor and returns the next throws: the orbit
drawn on the limit-set figure (:func:`throwmap.viz.limit_set.plot_limit_set`).
"""

from __future__ import annotations

import numpy as np

from ..records.orbit import Orbit
from ..throws.orbit import iterate

__all__ = ["orbit_on_attractor", "ORBIT_THROWS", "ORBIT_LEAD_MAX"]

ORBIT_THROWS = 40
"""Throws of the orbit drawn on the limit-set figure (``throwmap limitset --plot``, the demo)."""
ORBIT_LEAD_MAX = 1000
"""Most throws thrown (and not drawn) to bring that orbit onto its attractor."""


def orbit_on_attractor(part, arm, omega: float, model: str, limit, n: int = ORBIT_THROWS, **throw_kw) -> Orbit:
    """An orbit of ``n`` throws at ``omega`` (rad/s) lying on the limit set ``limit``, for drawing (paper Fig. 5).

    Starts from the first of ``limit``'s starting configurations that ends on an
    attractor, throws it as many times as the recurrence test discarded (at most
    :data:`ORBIT_LEAD_MAX`), and returns the next ``n`` throws as an
    :class:`~throwmap.records.orbit.Orbit`. Where every start escapes, the orbit of the first
    start is returned (it ends with its escape). ``throw_kw`` (e.g. ``options=``) go to
    :func:`~throwmap.throws.orbit.iterate`.
    """
    on = np.flatnonzero(np.asarray(limit.labels) >= 1)
    i = int(on[0]) if on.size else 0
    x0, s0 = float(limit.starts_x[i]), int(limit.starts_side[i])
    if on.size:
        lead = min(int(limit.caps.get("transient_used", limit.caps.get("transient", 0))), ORBIT_LEAD_MAX)
        if lead > 0:
            pre = iterate(part, arm, (x0, s0), omega, n=lead, model=model, **throw_kw)
            if not pre.escaped:
                x0, s0 = float(pre.x[-1]), int(pre.side[-1])
    return iterate(part, arm, (x0, s0), omega, n=n, model=model, **throw_kw)
