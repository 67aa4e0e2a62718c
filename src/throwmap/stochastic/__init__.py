"""Stochastic throw maps as Markov chains on cells.

========================  ===============================================================
:mod:`.cells`             :class:`Cells`: rests ``(x, side)`` cut into intervals per side
:mod:`.chain`             :class:`MarkovChain`, :class:`ChainMixture`: P(goal by k), absorption,
                          expected throws, the stationary distribution
:mod:`.build`             transition matrices from throws on cells (open loop, memoryless policy),
                          μ per trial as a mixture, the convergence check
:mod:`.montecarlo`        :class:`GoalSet`, the open-loop Monte Carlo the chain is checked against
:mod:`.compare`           the chain's curve against the Monte Carlo's Wilson 95 % band
:mod:`.experiments`       the chain of the ``position`` experiment (its memoryless controller)
:mod:`.assembly`          self-assembly's first low phase on a reduced pair state, from episodes
========================  ===============================================================
"""

from .build import ChainBuild, PolicyStep, ThrowStep, build_chain, build_mixture, mu_nodes
from .cells import Cells
from .chain import Absorption, ChainMixture, MarkovChain, Stationary
from .compare import Comparison, compare_curve, mc_curve
from .montecarlo import GoalSet, open_loop_trials

__all__ = ["Cells", "MarkovChain", "ChainMixture", "Absorption", "Stationary", "ThrowStep", "PolicyStep",
           "ChainBuild", "build_chain", "build_mixture", "mu_nodes", "Comparison", "compare_curve", "mc_curve",
           "GoalSet", "open_loop_trials"]
