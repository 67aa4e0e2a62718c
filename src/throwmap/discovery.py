"""Registries of plug-ins: the throw models and the experiments are looked up by name, one registry class for both.

A :class:`Registry` is filled by the modules of its package that call its ``register`` function at their top level
(``MODEL = register(PaperModel())``). On the first look-up it finds those modules by reading each module's source
(:mod:`ast`; nothing is imported to find out) and imports them: the package's infrastructure modules (a runner, a
plot module) are never imported for it, and there is no list of them to keep. Users add their own plug-ins at run
time with ``register``.
"""

from __future__ import annotations

import ast
import importlib
import importlib.util
import pkgutil
from pathlib import Path
from typing import Callable

from .errors import InvalidStateError, shown

__all__ = ["Registry", "plugin_modules"]


def plugin_modules(package: str, register: str) -> tuple[str, ...]:
    """The modules of ``package`` (not private ``_`` ones) whose source calls ``register(...)`` at its top level
    (as an expression or the value of an assignment), in name order."""
    spec = importlib.util.find_spec(package)
    out = []
    for info in pkgutil.iter_modules(spec.submodule_search_locations):
        if info.name.startswith("_") or info.ispkg:
            continue
        path = Path(info.module_finder.path) / f"{info.name}.py"
        try:
            tree = ast.parse(path.read_text(encoding="utf-8"))
        except (OSError, SyntaxError):  # pragma: no cover - a module that cannot be read is not a plug-in
            continue
        for node in tree.body:
            value = node.value if isinstance(node, (ast.Expr, ast.Assign)) else None
            if isinstance(value, ast.Call) and isinstance(value.func, ast.Name) and value.func.id == register:
                out.append(info.name)
                break
    return tuple(out)


class Registry:
    """Plug-ins of one ``kind`` (``"model"``, ``"experiment"``) by name.

    ``package``: the package whose modules register built-ins by calling ``register_name`` at their top level;
    ``check(obj)`` raises :class:`~throwmap.errors.InvalidStateError` for an object that is no such plug-in;
    ``first``: names listed first (in this order) by :meth:`names`; the others follow sorted (``sort``) or in
    registration order.
    """

    def __init__(self, kind: str, package: str, register_name: str, check: Callable, *, first=(), sort=False):
        self.kind, self.package, self.register_name, self.check = kind, package, register_name, check
        self.first, self.sort = tuple(first), bool(sort)
        self._items: dict = {}
        self._discovered = False

    def discover(self) -> None:
        """Import the package's plug-in modules once (each registers its own)."""
        if self._discovered:
            return
        self._discovered = True
        for name in plugin_modules(self.package, self.register_name):
            importlib.import_module(f"{self.package}.{name}")

    def register(self, obj, *, replace: bool = False):
        """Make ``obj`` available by ``obj.name``; a clash is refused unless ``replace``. Returns ``obj``."""
        self.check(obj)
        name = getattr(obj, "name", None)
        if not isinstance(name, str) or not name:
            raise InvalidStateError(f"{self.kind}.name", f"must be a non-empty string, got {shown(name)}")
        if name in self._items and self._items[name] is not obj and not replace:
            raise InvalidStateError(f"{self.kind}.name", f"a {self.kind} named {name!r} is already registered")
        self._items[name] = obj
        return obj

    def unregister(self, name: str) -> None:
        """Remove a plug-in (a built-in comes back on the next discovery only)."""
        self._items.pop(name, None)

    def names(self) -> tuple[str, ...]:
        """Every registered name: :attr:`first` in order, then the others."""
        self.discover()
        head = tuple(n for n in self.first if n in self._items)
        rest = [n for n in self._items if n not in head]
        return head + tuple(sorted(rest) if self.sort else rest)

    def __contains__(self, name) -> bool:
        return isinstance(name, str) and (name in self._items or name in self.names())

    def get(self, name):
        """The plug-in called ``name``; an unknown name is a one-line error on ``kind`` listing the names."""
        if isinstance(name, str) and name in self._items:
            return self._items[name]
        names = self.names()
        if isinstance(name, str) and name in self._items:
            return self._items[name]
        raise InvalidStateError(self.kind, f"unknown {self.kind} {shown(name)} (choose from {', '.join(names) or 'none'})")

    def registered(self, name):
        """The registered object called ``name``, or None (no discovery)."""
        return self._items.get(name)
