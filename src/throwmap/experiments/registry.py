"""The experiment registry: experiments are looked up by name, like models
(:mod:`throwmap.models.registry`).

Adding an experiment touches one file: a module in this package that defines it and calls
:func:`register_experiment` at import (every module of :mod:`throwmap.experiments` is
discovered on first look-up).
"""

from __future__ import annotations

from ..discovery import import_submodules
from ..errors import InvalidStateError, shown
from .base import Experiment

__all__ = ["register_experiment", "get_experiment", "experiment_names", "unregister_experiment"]

_REGISTRY: dict[str, Experiment] = {}
_DISCOVERED = False
_INFRA = ("base", "registry", "runner", "stats", "noise", "drop", "plot", "sensitivity", "assemble_episode")


def _discover() -> None:
    """Import every experiment module of this package once (each registers its experiments)."""
    global _DISCOVERED
    if _DISCOVERED:
        return
    _DISCOVERED = True
    import_submodules(__package__, skip=_INFRA)


def register_experiment(exp, *, replace: bool = False):
    """Make ``exp`` available by ``exp.name``; refuses a clash unless ``replace``. Returns ``exp``
    (so it can decorate a class instance's creation: ``FEED = register_experiment(Feed())``)."""
    if not isinstance(exp, Experiment):
        raise InvalidStateError("experiment", f"{shown(exp)} does not implement the Experiment protocol")
    name = exp.name
    if not isinstance(name, str) or not name:
        raise InvalidStateError("experiment.name", f"must be a non-empty string, got {shown(name)}")
    if name in _REGISTRY and _REGISTRY[name] is not exp and not replace:
        raise InvalidStateError("experiment.name", f"an experiment named {name!r} is already registered")
    _REGISTRY[name] = exp
    return exp


def unregister_experiment(name: str) -> None:
    """Remove an experiment added with :func:`register_experiment`."""
    _REGISTRY.pop(name, None)


def experiment_names() -> tuple[str, ...]:
    """Every registered experiment name, sorted."""
    _discover()
    return tuple(sorted(_REGISTRY))


def get_experiment(name) -> Experiment:
    """The registered experiment called ``name`` (or ``name`` itself if it is an experiment);
    an unknown name is a one-line :class:`InvalidStateError` (field ``experiment``) listing them."""
    if not isinstance(name, str) and isinstance(name, Experiment):
        return name
    if isinstance(name, str) and name in _REGISTRY:
        return _REGISTRY[name]
    names = experiment_names()
    if isinstance(name, str) and name in _REGISTRY:
        return _REGISTRY[name]
    raise InvalidStateError("experiment", f"unknown experiment {shown(name)} (choose from {', '.join(names) or 'none'})")
