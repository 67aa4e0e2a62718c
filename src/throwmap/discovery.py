"""Discovery of plug-in modules: the model and experiment registries import their package's modules once.

A registry (:mod:`throwmap.models.registry`, :mod:`throwmap.experiments.registry`) is filled by
modules that call its ``register`` at import; :func:`import_submodules` imports every such module
of a package (not its infrastructure, not private ``_`` modules) so that a look-up finds them all.
"""

from __future__ import annotations

import importlib
import pkgutil

__all__ = ["import_submodules"]


def import_submodules(package: str, skip=()) -> None:
    """Import every module of ``package`` whose name neither starts with ``_`` nor is in ``skip``."""
    pkg = importlib.import_module(package)
    for info in pkgutil.iter_modules(pkg.__path__):
        if not info.name.startswith("_") and info.name not in skip:
            importlib.import_module(f"{package}.{info.name}")
