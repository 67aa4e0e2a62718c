"""Feedback throwing (paper Sec. IV; issue 12 item 3): one-bit sensors, controllers and the closed loop.

* :mod:`.sensors` — :class:`SideSensor`, :class:`BeyondSensor`, :class:`WithinSensor` (one bit, with
  false-positive/negative rates and hysteresis) and :class:`PositionSensor` (a noisy estimate);
* :mod:`.controllers` — :class:`PaperController` (the draft's: high ω until on the side, low ω until
  at the goal), :class:`InverseJogController` (model-based inverse jogs), :class:`FunnelController`
  (a funnel graph's policy), with :class:`Goal`, :class:`ControlState`, :class:`Decision`;
* :mod:`.loop` — :func:`closed_loop` on any model (the engine keeping the part's pose), :class:`Episode`.

Importing this package loads neither matplotlib nor pymunk.
"""

from __future__ import annotations

from .controllers import (CONTROLLER_KINDS, ControlState, Decision, FunnelController, Goal, InverseJogController,
                          PaperController)
from .loop import Episode, Step, closed_loop
from .sensors import BeyondSensor, PositionSensor, SideSensor, WithinSensor

__all__ = ["SideSensor", "BeyondSensor", "WithinSensor", "PositionSensor", "Goal", "ControlState", "Decision",
           "PaperController", "InverseJogController", "FunnelController", "CONTROLLER_KINDS", "closed_loop",
           "Episode", "Step"]
