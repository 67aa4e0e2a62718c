"""Models "small_angle" and "small_angle2": the draft's closed forms (Sec. IV Lemma 4.1, Sec. V-A), corrected.

"small_angle" keeps the draft's first order in ω t*, "small_angle2" keeps every term
consistently to second order (ours); the corrections are listed in
:mod:`throwmap.kernels.small_angle`. Plain arm only, no trajectory.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..kernels import codes as C
from ..kernels.small_angle import (PARALLEL_MIN, throw_many_small_angle, throw_many_small_angle_serial,
                                   throw_one_small_angle)
from .base import BatchArrays, Features, NoOptions
from .registry import register

__all__ = ["SmallAngleModel", "MODEL", "MODEL2"]


@dataclass(frozen=True, slots=True)
class SmallAngleModel:
    """The corrected small-angle closed forms of ``order`` 1 ("small_angle") or 2 ("small_angle2")."""

    name: str
    order: int
    summary: str
    options_type: type = NoOptions
    features: Features = Features()

    def throw_one(self, part, system, x, side, omega, o):
        arm = system.arm
        rec = np.empty(C.NREC)
        xn, kn, st = throw_one_small_angle(x, side, omega, arm.h, arm.g, arm.length_or_inf, arm.back,
                                           part.radius_of_gyration**2, part.d, part.uL, part.uR, part.ell,
                                           part.length, part.stable, self.order, rec)
        return xn, kn, st, rec

    def throw_batch(self, part, system, x, side, omega, valid, o, progress=None):
        arm = system.arm
        m = x.size
        out = BatchArrays(np.empty(m), np.empty(m, dtype=np.int64), np.empty(m, dtype=np.int64), np.empty((m, C.NREC)))
        kernel = throw_many_small_angle if m >= PARALLEL_MIN else throw_many_small_angle_serial
        kernel(x, side, omega, valid, arm.h, arm.g, arm.length_or_inf, arm.back, part.radius_of_gyration**2, part.d,
               part.uL, part.uR, part.ell, part.length, part.stable, self.order, out.x, out.side, out.status,
               out.records)
        return out

    @property
    def unresolved_reason(self) -> str:
        """Why a throw is ``unresolved`` when its record gives no reason code."""
        from ..records.outcome import spin_reason

        second = ", or g ≤ d ω² (the second-order expansion has no contact)" if self.order == 2 else ""
        return "the closed forms give no answer here: " + spin_reason() + second

    def assumptions(self, records, mu, status) -> str:
        """What this model assumes (validation table)."""
        return "small-angle flight and the paper's no-slip, no-lift contact"

    def trajectory(self, part, system, x, side, omega, o, dt):  # pragma: no cover - features.trajectory is False
        raise NotImplementedError


MODEL = register(SmallAngleModel("small_angle", 1, "the draft's first-order closed forms of Sec. IV–V with its "
                                                   "errors corrected"))
MODEL2 = register(SmallAngleModel("small_angle2", 2, "the same closed forms kept consistently to second order in "
                                                     "ωt* (ours)"))
