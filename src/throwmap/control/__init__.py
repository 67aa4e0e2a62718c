"""Feedback throwing (paper Sec. IV): one-bit sensors, controllers and the closed loop.

* :mod:`.sensors` — :class:`SideSensor`, :class:`BeyondSensor`, :class:`WithinSensor` (one bit, with
  false-positive/negative rates and hysteresis) and :class:`PositionSensor` (a noisy estimate);
* :mod:`.controllers` — :class:`PaperController` (the draft's: high ω until on the side, low ω until
  at the goal), :class:`InverseJogController` (model-based inverse jogs), :class:`FunnelController`
  (a funnel graph's policy), with :class:`Goal`, :class:`ControlState`, :class:`Decision`;
* :mod:`.loop` — :func:`closed_loop` on any model (the engine keeping the part's pose), :class:`Episode`;
* :mod:`.inverse` — :func:`jog_rate` / :func:`inverse_jog`, the rate that jogs a part to a chosen x
  (Lemma 4.2, checked), and :func:`jog_size`; :mod:`.inverse_check` checks them forward on every model;
* :mod:`.planner` — :func:`plan_throws` (open-loop plans: Lemma 4.1 round the limit set, then jogs) and
  :func:`reachability` (Prop. 4.3 per rate, with the reason when a goal is unreachable).

Importing this package loads neither matplotlib nor pymunk.
"""

from __future__ import annotations

from .controllers import (CONTROLLER_KINDS, ControlState, Decision, FunnelController, Goal, InverseJogController,
                          PaperController)
from .inverse import InverseJog, inverse_jog, jog_rate, jog_size
from .loop import Episode, Step, closed_loop
from .planner import Plan, PlanStep, Reachability, plan_throws, reachability
from .sensors import BeyondSensor, PositionSensor, SideSensor, WithinSensor

__all__ = ["SideSensor", "BeyondSensor", "WithinSensor", "PositionSensor", "Goal", "ControlState", "Decision",
           "PaperController", "InverseJogController", "FunnelController", "CONTROLLER_KINDS", "closed_loop",
           "Episode", "Step", "InverseJog", "inverse_jog", "jog_rate", "jog_size", "Plan", "PlanStep", "Reachability",
           "plan_throws", "reachability"]
