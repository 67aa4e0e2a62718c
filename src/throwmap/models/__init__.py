"""Throw models behind one interface and a registry (STYLE §12).

``throw``, ``throw_batch``, ``iterate``, analysis and the CLI look a model up by
name (:func:`get_model`) and never branch on it. Built-in models, one module each:

========================  ==========================================================
``"rigid_body"``          (default) exact rigid-body dynamics with Coulomb friction
``"paper"``               exact within the paper's assumptions (Sec. III, Eqs. 1–4)
``"small_angle"``         the draft's first-order closed forms, corrected
``"small_angle2"``        the same to second order (ours)
``"engine"``              full pymunk simulation: fixtures, tilt, arm realisations
``"mujoco"``              MuJoCo cross-check (optional extra)
========================  ==========================================================

Adding a model: one module here (or your own code) with a class that has ``name``,
``summary``, ``options_type`` (a frozen dataclass), ``features`` (:class:`Features`),
``throw_one``, ``throw_batch`` and ``trajectory`` (see :class:`ThrowModel`), and a call
of :func:`register` on an instance; see docs/explanation/models.md.
"""

from .base import BatchArrays, Features, NoOptions, ThrowModel, build_options
from .registry import DEFAULT_MODEL, check_model, get_model, model_names, options_taken, register, unregister

__all__ = ["BatchArrays", "DEFAULT_MODEL", "Features", "NoOptions", "ThrowModel", "build_options",
           "check_model", "get_model", "model_names", "options_taken", "register",
           "unregister"]
