"""Statics of parts resting on the arm, against the wall and on each other (paper Sec. VI, Figs. 13, 14).

* :mod:`.rest` — :func:`analyse_rest`: can a placement rest (an LP over the exact 2-D friction cones),
  the friction it needs, the contact forces and their ranges; :class:`Body`, :class:`Contact`;
* :mod:`.contacts` — :func:`find_contacts`: the contacts of a placement read off its geometry;
* :mod:`.leaning` — Fig. 13: the lean condition in closed form (complete, and the draft's printed one).

Importing this package loads neither SciPy's optimiser nor matplotlib until a function runs.
"""

from __future__ import annotations

from .contacts import find_contacts
from ..system.geometry import overlap_depth
from .leaning import drafts_no_lean, edge_frame_cm, lean_free_beta, lean_possible, leaning_bodies
from .rest import Body, Contact, RestAnalysis, analyse_rest, gravity_arm_frame

__all__ = ["Body", "Contact", "RestAnalysis", "analyse_rest", "gravity_arm_frame", "find_contacts", "overlap_depth",
           "drafts_no_lean", "edge_frame_cm", "lean_free_beta", "lean_possible", "leaning_bodies"]
