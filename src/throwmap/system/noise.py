"""Noise: what varies from throw to throw and from trial to trial on a real feeder.

* **ω jitter** — each throw's release rate is ω·(1 + σ_ω·N(0, 1)) (clipped at 0), σ_ω
  relative (the feeding experiment's default: 3 %, ``omega_rel=0.03``). The draft's arm
  reached its commanded rate within a few per cent (Sec. IV-A).
* **μ spread** — the arm–part friction of a trial is drawn once per trial (a part's
  surface, the arm's wear): either relative, μ·(1 + σ_μ·N(0, 1)) clipped at 0
  (``mu_rel``), or uniform over an absolute range (``mu_range``, which wins if given).
  μ = ∞ (no slip) stays ∞ under a relative spread.
* **Realisation** — how the arm moves: ``"impulse"`` (the paper's idealisation,
  :class:`throwmap.system.motion.ImpulseThrow`) or ``"recoil"`` (the Flatland arm of Sec. IV-A,
  :meth:`throwmap.system.motion.RecoilThrow.for_release_rate`, recoil ``recoil`` rad and damping
  ratio ``zeta``), built for each throw's (jittered) ω.

:class:`Noise` is a frozen value that checks its own fields (the one statement of their rules); its
methods take the generator, so the draws belong to the trial's stream. Configs declare it as
:class:`throwmap.io.spec.NoiseSpec` (``[noise]``).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from ..errors import InvalidStateError, shown
from ..rng import as_generator
from .arm import Arm

__all__ = ["Noise", "REALISATIONS"]

REALISATIONS = ("impulse", "recoil")
"""Arm motions a :class:`Noise` can build: the paper's impulse, the Flatland recoil profile."""


def _nonneg(value, field: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
        raise InvalidStateError(field, f"must be a finite number ≥ 0, got {shown(value)}")
    return float(value)


@dataclass(frozen=True, slots=True)
class Noise:
    """What varies between throws and trials (see the module docstring).

    ``omega_rel``: relative σ of each throw's ω (dimensionless, ≥ 0); ``mu_rel``:
    relative σ of the trial's arm μ; ``mu_range``: (low, high) uniform arm μ per trial
    (overrides ``mu_rel``); ``realisation``: ``"impulse"`` or ``"recoil"``; ``recoil``
    (rad) and ``zeta`` the recoil profile's depth and damping ratio.
    """

    omega_rel: float = 0.0
    mu_rel: float = 0.0
    mu_range: tuple | None = None
    realisation: str = "impulse"
    recoil: float = math.radians(3.0)
    zeta: float = 0.5

    def __post_init__(self):
        object.__setattr__(self, "omega_rel", _nonneg(self.omega_rel, "noise.omega_rel"))
        object.__setattr__(self, "mu_rel", _nonneg(self.mu_rel, "noise.mu_rel"))
        if self.mu_range is not None:
            try:
                lo, hi = (float(v) for v in self.mu_range)
            except (TypeError, ValueError):
                raise InvalidStateError("noise.mu_range", f"must be a pair (low, high), got {shown(self.mu_range)}") from None
            if not (0 <= lo <= hi and math.isfinite(hi)):
                raise InvalidStateError("noise.mu_range", f"must satisfy 0 ≤ low ≤ high < ∞, got {shown(self.mu_range)}")
            object.__setattr__(self, "mu_range", (lo, hi))
        if self.realisation not in REALISATIONS:
            raise InvalidStateError("noise.realisation", f"must be one of {', '.join(REALISATIONS)}, got {shown(self.realisation)}")
        rec = _nonneg(self.recoil, "noise.recoil")
        if rec == 0:
            raise InvalidStateError("noise.recoil", "must be > 0 rad")
        object.__setattr__(self, "recoil", rec)
        z = _nonneg(self.zeta, "noise.zeta")
        if not 0 < z < 1:
            raise InvalidStateError("noise.zeta", f"must be in (0, 1), got {shown(self.zeta)}")
        object.__setattr__(self, "zeta", z)

    @property
    def is_quiet(self) -> bool:
        """No random draw at all (ω and μ exact)."""
        return self.omega_rel == 0 and self.mu_rel == 0 and self.mu_range is None

    def omega(self, nominal: float, rng=None) -> float:
        """One throw's release rate (rad/s): ``nominal``·(1 + σ_ω·N(0, 1)), at least 0.

        Always draws one normal (even when σ_ω = 0), so the stream's use does not depend on σ."""
        rng = as_generator(rng)
        z = float(rng.standard_normal())
        return max(0.0, float(nominal) * (1.0 + self.omega_rel * z))

    def mu(self, nominal: float, rng=None) -> float:
        """A trial's arm μ: uniform over ``mu_range``, else ``nominal``·(1 + σ_μ·N(0, 1)) ≥ 0 (∞ stays ∞).

        Always draws one number from ``rng``."""
        rng = as_generator(rng)
        if self.mu_range is not None:
            return float(rng.uniform(*self.mu_range))
        z = float(rng.standard_normal())
        if math.isinf(nominal):
            return math.inf
        return max(0.0, float(nominal) * (1.0 + self.mu_rel * z))

    def arm(self, arm: Arm, rng=None) -> Arm:
        """``arm`` with this trial's μ (:meth:`mu`)."""
        return dataclasses.replace(arm, mu=self.mu(arm.mu, rng))

    def realisation_for(self, omega: float):
        """The arm motion of a throw at release rate ``omega`` (rad/s): ImpulseThrow or RecoilThrow."""
        from ..system.motion import ImpulseThrow, RecoilThrow

        if self.realisation == "recoil" and omega > 0:
            return RecoilThrow.for_release_rate(float(omega), recoil=self.recoil, zeta=self.zeta)
        return ImpulseThrow(float(omega))

    def throw(self, nominal: float, rng=None):
        """``(ω, realisation)`` of one noisy throw at nominal rate ``nominal`` (rad/s)."""
        w = self.omega(nominal, rng)
        return w, self.realisation_for(w)

    def to_dict(self) -> dict:
        return {"omega_rel": self.omega_rel, "mu_rel": self.mu_rel,
                "mu_range": None if self.mu_range is None else list(self.mu_range),
                "realisation": self.realisation, "recoil_rad": self.recoil, "zeta": self.zeta}
