"""What throws produce: the records every model, engine and analysis shares.

========================  ========================================================
:mod:`.outcome`           :class:`Status`, :class:`ThrowOutcome` (one throw), :class:`BatchOutcome`
:mod:`.orbit`             :class:`Orbit`: repeated throws of one part (paper Sec. III-D)
:mod:`.trajectory`        :class:`Trajectory`: sampled poses, contacts, events
========================  ========================================================

Records sit below the models and the dispatcher: models, engines and analyses import
them, never the code that produces them. A record turns itself into plain JSON values
(:mod:`throwmap.serial`) without going through :mod:`throwmap.io`.
"""
