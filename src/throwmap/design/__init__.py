"""Limit-set design (paper Sec. V, corrected): shape the forward limit set by choosing the part's
mass properties (a lead weight on the plate), the release rate, the arm's offset and tilt.

=====================================  ====================================================
:func:`design_critical_points`         the minimal contract: weight place + ω → r_i targets
:func:`design`                         any parameters, r_i / band top / bottom / separation targets
:class:`DesignResult`                  frozen result with ``.success``, ``.message``, ``.plot()``
:mod:`~throwmap.design.small_angle`    the draft's F = K + U − U_crit, corrected (fast first guess)
:mod:`~throwmap.design.plate`          where a weight may go; the lightest weight for a given CM
:mod:`~throwmap.design.examples`       the draft's example, reproduced, and the feeder design
=====================================  ====================================================

``design_cavity`` and ``CavityDesign`` (the fixture that captures the designed side) come from
:mod:`throwmap.design.cavity` when it is present; they are loaded on first use.
"""

from __future__ import annotations

from .api import DEFAULT_MARGIN, DEFAULT_TOL, SMALL_ANGLE_F, design, design_critical_points
from .plate import inset_polygon, lightest_weight_for_com
from .result import DesignResult, DesignStep
from .small_angle import energy_critical_points
from .space import PARAMETERS, DesignSpace
from .targets import Separation, Target, WallWindow

__all__ = ["DEFAULT_MARGIN", "DEFAULT_TOL", "DesignResult", "DesignSpace", "DesignStep", "PARAMETERS",
           "SMALL_ANGLE_F", "Separation", "Target", "WallWindow", "design", "design_critical_points", "energy_critical_points",
           "inset_polygon", "lightest_weight_for_com", "draft_example", "feeder_design", "design_cavity",
           "CavityDesign"]

_LAZY = {"design_cavity": ".cavity", "CavityDesign": ".cavity", "draft_example": ".examples",
         "feeder_design": ".examples"}


def __getattr__(name):
    """Load ``design_cavity``/``CavityDesign`` (from :mod:`.cavity`) and the examples on first use."""
    if name in _LAZY:
        import importlib

        mod = importlib.import_module(_LAZY[name], __name__)
        return getattr(mod, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
