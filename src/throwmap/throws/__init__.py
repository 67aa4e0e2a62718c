"""The throw map: one throw, batches, orbits, samples and motions, dispatched to a model.

========================  ========================================================
:mod:`.throw`             ``throw``, ``throw_batch``: validate once, dispatch to a model
:mod:`.orbit`             ``iterate`` (paper Sec. III-D, Figs. 5, 7) on a throwing session
:mod:`.samples`           T(x) sampled on a grid per side (paper Fig. 2), for figures
:mod:`.orbit_trajectory`  ``throw_trajectory``, ``orbit_trajectory`` (animation)
========================  ========================================================

The records these return (:class:`~throwmap.records.outcome.ThrowOutcome`,
:class:`~throwmap.records.orbit.Orbit`, :class:`~throwmap.records.trajectory.Trajectory`) live
in :mod:`throwmap.records`.
"""
