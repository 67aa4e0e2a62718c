"""Grids of starts shared by the agreement tests (the rigid_body–pymunk grid at low μ, the impact-law tests)."""

from __future__ import annotations

import numpy as np

__all__ = ["side_grid"]


def side_grid(part, x_max: float = 0.45, n_x: int = 5, omegas=(3.0, 5.0, 7.0), margin: float = 0.01):
    """Starts ``(x, side, omega)`` as three flat arrays: on every side k, ``n_x`` x from ``margin``
    (m) past the joint-side limit −u_L[k] up to ``x_max`` (m), each at every ω of ``omegas`` (rad/s)."""
    xs, ks, oms = [], [], []
    for k in range(len(part.d)):
        for x in np.linspace(-part.uL[k] + margin, x_max, n_x):
            for om in omegas:
                xs.append(x), ks.append(k), oms.append(om)
    return np.array(xs), np.array(ks), np.array(oms)
