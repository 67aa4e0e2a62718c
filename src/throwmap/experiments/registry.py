"""The experiment registry: experiments are looked up by name, like models
(:mod:`throwmap.models.registry`).

Adding an experiment touches one file: a module in this package that defines it and calls
:func:`register_experiment` at its top level (:class:`throwmap.discovery.Registry` finds such modules
on the first look-up; the package's other modules are never imported for it).
"""

from __future__ import annotations

from ..discovery import Registry
from ..errors import InvalidStateError, shown
from .base import Experiment

__all__ = ["register_experiment", "get_experiment", "experiment_names", "unregister_experiment"]

def _check(exp) -> None:
    if not isinstance(exp, Experiment):
        raise InvalidStateError("experiment", f"{shown(exp)} does not implement the Experiment protocol")


_REGISTRY = Registry("experiment", __package__, "register_experiment", _check, sort=True)


def register_experiment(exp, *, replace: bool = False):
    """Make ``exp`` available by ``exp.name``; refuses a clash unless ``replace``. Returns ``exp``
    (so it can decorate a class instance's creation: ``FEED = register_experiment(Feed())``)."""
    return _REGISTRY.register(exp, replace=replace)


def unregister_experiment(name: str) -> None:
    """Remove an experiment added with :func:`register_experiment`."""
    _REGISTRY.unregister(name)


def experiment_names() -> tuple[str, ...]:
    """Every registered experiment name, sorted."""
    return _REGISTRY.names()


def get_experiment(name) -> Experiment:
    """The registered experiment called ``name`` (or ``name`` itself if it is an experiment);
    an unknown name is a one-line :class:`InvalidStateError` (field ``experiment``) listing them."""
    if not isinstance(name, str) and isinstance(name, Experiment):
        return name
    return _REGISTRY.get(name)
