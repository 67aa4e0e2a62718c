"""Feeders for any part: a lead weight, a throw and a lined pocket that feed one side, found by search and
verified in the engine.

:func:`design_feeder` searches the family of :mod:`throwmap.feeder.family` (the part alone or with a lead
weight) over ω and h: an exact-model screen of which side arrives first at an end stop
(:mod:`throwmap.feeder.arrival`), short runs of the feeding experiment in the engine that rank the candidates, then
a full run with an independent rerun and an ω-drift check (:mod:`throwmap.feeder.search`). :func:`feeder_files` writes the part file and the ``feed`` config of a
candidate (:mod:`throwmap.feeder.files`); :func:`write_sheet` the design sheet (:mod:`throwmap.feeder.sheet`);
:func:`random_plate` draws parts nobody tuned for (:mod:`throwmap.feeder.plates`).
"""

from .arrival import Arrival, arrival
from .family import Variant, Weight, weight_variants, with_weight
from .files import feeder_files
from .plates import random_plate
from .search import FeederSearch, Tried, VerifyPlan, design_feeder

design = design_feeder
"""``throwmap.feeder.design(part, out=…)``: the same function as :func:`design_feeder`."""

__all__ = ["Arrival", "arrival", "Variant", "Weight", "weight_variants", "with_weight", "feeder_files",
           "random_plate", "FeederSearch", "Tried", "VerifyPlan", "design_feeder", "design"]
