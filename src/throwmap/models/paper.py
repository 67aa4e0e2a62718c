"""Model "paper": the exact throw map within the paper's assumptions (Sec. III, Eqs. 1–4).

No small-angle approximation: release (Eq. 1), first contact of any vertex (Eq. 3),
plastic no-slip impact (Eq. 4), then the exact pivot/landing/rocking cascade
(:mod:`throwmap.kernels.paper`). Plain arm only (no fixtures, α = 0); friction is
not modelled (the record reports the friction the throw needs).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kernels import codes as C
from ..kernels.paper import throw_many, throw_one
from ._checks import int_at_least, positive_float
from .base import BatchArrays, Features
from .registry import register

__all__ = ["PaperOptions", "PaperModel", "MODEL"]


@dataclass(frozen=True, slots=True)
class PaperOptions:
    """Numerical options of the "paper" kernel.

    ``tol`` (m): contact tolerance of the first-contact search; ``max_iter``: cap on its
    steps (status NO_CONTACT beyond); ``max_impacts``: cap on plastic impacts in one
    throw (status NO_REST beyond); ``n_samples``: points per pivot swing at which the
    friction demand (record ``friction_ratio_max``) is sampled.
    """

    tol: float = 1e-14
    max_iter: int = 100_000
    max_impacts: int = 10_000
    n_samples: int = 16

    def __post_init__(self):
        object.__setattr__(self, "tol", positive_float(self.tol, "tol"))
        object.__setattr__(self, "max_iter", int_at_least(self.max_iter, "max_iter", 1))
        object.__setattr__(self, "max_impacts", int_at_least(self.max_impacts, "max_impacts", 1))
        object.__setattr__(self, "n_samples", int_at_least(self.n_samples, "n_samples", 2))


class PaperModel:
    name = "paper"
    summary = ("exact within the paper's assumptions (Sec. III, Eqs. 1–4): first contact of any vertex, "
               "plastic no-slip impact, exact pivoting, landings, flips and rocking; lift-off and pulling "
               "impulses flagged, not modelled")
    options_type = PaperOptions
    features = Features(trajectory=True)

    def throw_one(self, part, system, x, side, omega, o: PaperOptions):
        arm = system.arm
        rec = np.empty(C.NREC)
        xn, kn, st = throw_one(x, side, omega, arm.h, arm.g, arm.length_or_inf, part.radius_of_gyration**2, part.w,
                               part.beta, part.d, part.uL, part.uR, part.ell, part.stable, o.tol, o.max_iter,
                               o.max_impacts, o.n_samples, rec)
        return xn, kn, st, rec

    def throw_batch(self, part, system, x, side, omega, valid, o: PaperOptions, progress=None):
        arm = system.arm
        m = x.size
        out = BatchArrays(np.empty(m), np.empty(m, dtype=np.int64), np.empty(m, dtype=np.int64), np.empty((m, C.NREC)))
        throw_many(x, side, omega, valid, arm.h, arm.g, arm.length_or_inf, part.radius_of_gyration**2, part.w,
                   part.beta, part.d, part.uL, part.uR, part.ell, part.stable, o.tol, o.max_iter, o.max_impacts,
                   o.n_samples, out.x, out.side, out.status, out.records)
        return out

    def trajectory(self, part, system, x, side, omega, o: PaperOptions, dt):
        from ..throws.trajectories import kernel_trajectory

        return kernel_trajectory(part, system.arm, x, side, omega, "paper", dt=dt, options=o)


MODEL = register(PaperModel())
