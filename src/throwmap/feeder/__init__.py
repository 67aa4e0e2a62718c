"""Feeders for any part: the search for a pocket, throw and arm that feed one side, screened on the exact model.

:func:`screen` scores candidate feeders (side, ω, h, pocket depth) by their end-wall windows
(:mod:`throwmap.feeder.screen`); :func:`feeder_files` writes the part file and the ``feed`` experiment config
of a candidate, which ``throwmap experiment feed`` runs as it is (:mod:`throwmap.feeder.files`);
:func:`design_feeder` verifies the screened candidates in the engine and gives the verdict
(:mod:`throwmap.feeder.search`).
"""

from .files import feeder_files
from .screen import Candidate, Screen, screen
from .search import FeederSearch, Tried, VerifyPlan, design_feeder

__all__ = ["Candidate", "Screen", "screen", "feeder_files", "FeederSearch", "Tried", "VerifyPlan", "design_feeder"]
