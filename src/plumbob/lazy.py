"""Names a package exports without importing their modules until first use (PEP 562).

``import plumbob.stability`` must not load every kind of stability code, nor ``import
plumbob.mesh`` the repair and shell code a well-formed mesh never needs: a command
pays start-up time for each module it loads. A package lists, per exported name, the
module that defines it, and takes its module-level ``__getattr__`` and ``__dir__`` from
:func:`lazy_exports`.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterable, Mapping
from importlib import import_module
from typing import Any

__all__ = ["lazy_exports"]


def lazy_exports(package: str, where: Mapping[str, str], public: Iterable[str]
                 ) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """The module-level ``__getattr__`` and ``__dir__`` of ``package``.

    ``where`` maps each lazily exported name to the module that defines it, relative to
    ``package`` (``".poses"``). A name's module is imported on its first use, and the
    value is then kept in the package's namespace, so it is looked up once. ``__dir__``
    shows the ``public`` names as if imported, with whatever the package holds already.

    >>> getattr_, dir_ = lazy_exports("plumbob", {"PlumbobError": ".errors"}, [])
    >>> getattr_("PlumbobError").__name__
    'PlumbobError'
    """
    names = set(public)

    def __getattr__(name: str) -> Any:
        if name not in where:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(import_module(where[name], package), name)
        setattr(sys.modules[package], name, value)  # looked up once
        return value

    def __dir__() -> list[str]:
        """What the package shows: its public names as if imported, with its modules."""
        return sorted(set(vars(sys.modules[package])) | names)

    return __getattr__, __dir__
