"""Experiment ``settle``: drop the part onto the arm from a random pose and see where it rests.

The draft's trials began "with random initial conditions (obtained by dropping the part
onto the arm)" (Sec. IV-B, V-C). This experiment measures that step alone, in the pymunk
engine (:func:`throwmap.experiments.drop.drop_part` with ``max_redraws=0``): a trial
succeeds when the part comes to rest flat on a stable side on the arm, which is the
start every throw needs. Failures by kind: ``off_end`` / ``behind_joint`` (fell off an
end), ``tilted`` (came to rest leaning, which on the bare arm the engine refuses as
unconverged), ``held_tilted`` (at rest, tilted against a fixture), ``refused:<status>``
(the engine gave no answer). Per-trial values give the drop-outcome statistics later
experiments start from: the resting ``x`` (m), ``side`` and ``tilt`` (rad), the draw
(``x0`` m, ``phi0`` rad, ``height`` m), the fall time ``t_fall`` (s) and the trial's ``mu``.
"""

from __future__ import annotations

import math

from pydantic import Field

from ..errors import InvalidStateError
from ..io.spec import ArmSpec, NoiseSpec, Point, SystemSpec
from ..system.fixtures import Cavity
from .base import Trial, seed_of
from .drop import DEFAULT_HEIGHT, drop_part
from .registry import register_experiment

__all__ = ["SettleConfig", "Settle", "SETTLE"]


class SettleConfig(SystemSpec):
    """Config of ``settle`` (SI units): the system (:class:`~throwmap.io.spec.SystemSpec`: ``part``, ``[arm]``,
    ``alpha``, ``[wall]``, ``[noise]``) and the drop. The defaults are the built-in example: the draft's 17 cm
    30-60-90 plexiglas triangle dropped 2–10 cm onto a 40 cm arm (h = −1 cm, μ = 0.8)."""

    arm: ArmSpec = Field(default_factory=lambda: ArmSpec(h=-0.01, length=0.40, mu=0.8))
    noise: NoiseSpec = Field(default_factory=NoiseSpec, description="per-trial μ spread (ω unused here)")
    x_range: Point | None = Field(None, description="CM abscissa range of the drop, m (None: the arm)")
    height: Point = Field(DEFAULT_HEIGHT, description="lowest vertex above the arm at release, m")
    cavity: list[Point] | None = Field(None, description="Cavity profile (s, y) at the arm's end, m")


class Settle:
    """Drop the part; success = at rest flat on a stable side on the arm."""

    name = "settle"
    summary = "drop the part from a random pose onto the arm (pymunk); success = at rest flat on a stable side"
    config_type = SettleConfig

    @staticmethod
    def build(cfg: SettleConfig):
        """``(part, arm, fixtures)`` of a config."""
        part = cfg.build_part()
        arm = cfg.build_arm()
        if arm.length is None:
            raise InvalidStateError("config.arm.length", "required: the part is dropped over a bounded arm")
        cavity = () if cfg.cavity is None else (Cavity(tuple(cfg.cavity)),)
        return part, arm, cavity + cfg.fixtures()

    def trial(self, cfg: SettleConfig, index: int, rng) -> Trial:
        from ..engine.rest import FLAT_TILT

        part, arm, fixtures = self.build(cfg)
        arm = cfg.noise.noise().arm(arm, rng)
        d = drop_part(part, arm, rng, fixtures=fixtures, alpha=cfg.alpha, x_range=cfg.x_range, height=cfg.height,
                      max_redraws=0)
        kind = d.kind
        if kind is None and abs(d.tilt) >= FLAT_TILT:
            kind = "held_tilted"
        values = {"x": d.x, "side": d.side, "tilt": d.tilt, "x0": d.start[0], "phi0": d.start[2],
                  "height": d.height, "t_fall": d.t_fall, "mu": arm.mu}
        return Trial(index, seed_of(rng), kind is None, kind, values)

    def parameters(self, cfg: SettleConfig) -> dict:
        part, arm, fixtures = self.build(cfg)
        return {"part": part.name, "part_mass_kg": part.mass, "h_m": arm.h, "length_m": arm.length,
                "mu": None if math.isinf(arm.mu) else arm.mu, "g_m_s2": arm.g, "alpha_rad": cfg.alpha,
                "x_range_m": list(cfg.x_range) if cfg.x_range else [0.0 - arm.back, arm.length],
                "height_m": list(cfg.height), "fixtures": [repr(f) for f in fixtures],
                "noise": cfg.noise.noise().to_dict(), "engine": "pymunk, EngineSettings() defaults",
                "success": "at rest flat (|tilt| < 0.02 rad) on a stable side on the arm"}


SETTLE = register_experiment(Settle())
