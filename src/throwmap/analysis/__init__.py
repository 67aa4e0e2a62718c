"""Analysis of throw maps: critical points, limit sets, basins and funnels (paper Sec. I-A, III-D).

Everything here works on a *configuration map* (:mod:`throwmap.analysis.maps`): the
physical throw map of a part on an arm under any model, a composed sequence of
throws, or a synthetic map given as a function. Default model: ``"rigid_body"``.

========================  ===================================================
:func:`critical_points`   r_i (where jogs end) and l_i (inf S) per side
:func:`limit_set`         fixed points, cycles, bands and escapes (label −1)
:func:`basins`            attractor, throws to reach it, fractions, certificate
:func:`funnels`           mouths, spouts and the priority order to a goal
:func:`push`              a sequence of throws Π T^{ω_j} applied to a set
========================  ===================================================

Modules: ``maps`` (the map interface), ``caps`` (:class:`RecurrenceCaps`),
``recurrence`` (orbits and the recurrence test), ``attractors`` (labels, fates,
:class:`Attractor`), ``limitset``, ``critical``, ``cellmap`` (exact orbits and cell
mapping), ``basins``, ``sets`` (:class:`ConfigSet`, :func:`push`) and ``funnels``.
Results (``CriticalPoints``, ``LimitSet``, ``Basins``, ``Certificate``, ``FunnelGraph``,
``ConfigSet``, ``SetImage``, ``Attractor``) share ``to_dict``/``from_dict``, ``table()``
where a table reads well and ``plot()`` where a figure exists.
"""

from .attractors import LABEL_ESCAPE, Attractor
from .basins import Basins, Certificate, basins
from .caps import RecurrenceCaps
from .critical import CriticalPoints, critical_points
from .funnels import Funnel, FunnelGraph, funnels
from .limitset import LimitSet, limit_set
from .maps import ConfigMap, FunctionMap, ThrowMap, as_map
from .sets import ConfigSet, SetImage, push

__all__ = [
    "Attractor", "Basins", "Certificate", "ConfigMap", "ConfigSet", "CriticalPoints", "Funnel", "FunnelGraph",
    "FunctionMap", "LABEL_ESCAPE", "LimitSet", "RecurrenceCaps", "SetImage", "ThrowMap", "as_map", "basins",
    "critical_points", "funnels", "limit_set", "push",
]
