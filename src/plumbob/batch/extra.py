"""The optional ``batch`` extra (Dask, pyarrow, pandas): imported only when used, with a
one-line error naming the extra when it is missing."""

from __future__ import annotations

import importlib
from types import ModuleType

from ..errors import PlumbobError

__all__ = ["require", "EXTRA"]

EXTRA = "pip install 'plumbob[batch]'"


def require(module: str, purpose: str) -> ModuleType:
    """Import ``module`` or say, in one line, which extra brings it."""
    try:
        return importlib.import_module(module)
    except ImportError:
        raise PlumbobError(f"{purpose} needs the '{module.split('.')[0]}' package, part of "
                           f"plumbob's batch extra: {EXTRA}") from None
