"""The throw map and its results: one throw, batches, orbits, samples and motions.

========================  ========================================================
:mod:`.throw`             ``throw``, ``throw_batch``: validate once, dispatch to a model
:mod:`.outcome`           :class:`Status`, :class:`ThrowOutcome`, :class:`BatchOutcome`
:mod:`.orbit`             ``iterate`` and :class:`Orbit` (paper Sec. III-D, Figs. 5, 7)
:mod:`.samples`           T(x) sampled on a grid per side (paper Fig. 2), for figures
:mod:`.trajectory`        :class:`Trajectory`: sampled poses, contacts, events
:mod:`.orbit_trajectory`  ``throw_trajectory``, ``orbit_trajectory`` (animation)
========================  ========================================================
"""
