"""The model registry (STYLE §12, like Gymnasium's ``register``/``make``): callers look models up by name.

Adding a model touches one file: a module in this package that defines the model
and calls :func:`register` at its top level (:class:`throwmap.discovery.Registry` finds such
modules on the first look-up), or a user's code calling :func:`register` at run time.
"""

from __future__ import annotations

from ..discovery import Registry
from ..errors import InvalidStateError
from .base import ThrowModel

__all__ = ["DEFAULT_MODEL", "DISPLAY_ORDER", "register", "get_model", "model_names", "check_model", "options_taken"]

DEFAULT_MODEL = "rigid_body"
"""The default everywhere (``throw``, ``iterate``, analysis, the CLI): the most faithful
validated model (docs/explanation/validation.md: within 0.5 mm of pymunk in 99.5 % of throws at μ = 1.5)."""

DISPLAY_ORDER = ("paper", "small_angle", "small_angle2", "rigid_body", "engine", "mujoco")
"""The order in which the built-in models are listed; other models follow in registration order."""

def _check(model) -> None:
    if not isinstance(model, ThrowModel):
        raise InvalidStateError("model", f"{model!r} does not implement the ThrowModel protocol")


_REGISTRY = Registry("model", __package__, "register", _check, first=DISPLAY_ORDER)


def register(model: ThrowModel, *, replace: bool = False) -> ThrowModel:
    """Make ``model`` available by ``model.name``; refuses a clash unless ``replace``."""
    return _REGISTRY.register(model, replace=replace)


def unregister(name: str) -> None:
    """Remove a model added with :func:`register` (built-ins come back on the next discovery only)."""
    _REGISTRY.unregister(name)


def model_names() -> tuple[str, ...]:
    """Every registered model name: the built-ins in :data:`DISPLAY_ORDER`, then the others."""
    return _REGISTRY.names()


def check_model(name) -> str:
    """``name`` if it is a registered model, else a one-line :class:`InvalidStateError` (field ``model``)."""
    if not (isinstance(name, str) and name in _REGISTRY):
        raise InvalidStateError("model", f"unknown model {name!r} (choose from {', '.join(model_names())})")
    return name


def get_model(name) -> ThrowModel:
    """The registered model called ``name`` (or ``name`` itself if it is a model object)."""
    if not isinstance(name, str) and isinstance(name, ThrowModel):
        return name
    return _REGISTRY.get(check_model(name))


def options_taken(name, **keywords) -> dict:
    """Those of ``keywords`` that model ``name``'s options take, leaving out None values (a keyword such as
    ``settings`` goes to the models that have it, whichever they are, never by a model's name)."""
    import dataclasses

    own = {f.name for f in dataclasses.fields(get_model(name).options_type)}
    return {k: v for k, v in keywords.items() if k in own and v is not None}
