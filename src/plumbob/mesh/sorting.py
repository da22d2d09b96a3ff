"""Stable sorts of integer keys by sorting packed words: numpy's ``np.sort`` of int64 is
SIMD-accelerated and 3× faster than ``np.argsort``, and 5–10× faster than a stable
``np.argsort``. Packing each key above its index (``key << bits | index``) makes one
plain sort a stable argsort whenever key and index fit in 63 bits together; otherwise
the plain stable ``np.argsort`` answers. Same orders, to the element.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

__all__ = ["stable_order", "lex_order"]


def stable_order(keys: np.ndarray) -> np.ndarray:
    """``np.argsort(keys, kind="stable")`` of integer keys (1-D).

    >>> stable_order(np.array([3, -1, 3, 0])).tolist()
    [1, 3, 0, 2]
    """
    keys = np.asarray(keys).reshape(-1)
    n = len(keys)
    if n < 2:
        return np.arange(n, dtype=np.intp)
    lo, hi = int(keys.min()), int(keys.max())
    bits = (n - 1).bit_length()
    if (hi - lo).bit_length() + bits > 63:
        return np.argsort(keys, kind="stable")
    packed = np.subtract(keys, lo, dtype=np.int64)
    packed <<= bits
    packed |= np.arange(n, dtype=np.int64)
    packed.sort()
    packed &= (1 << bits) - 1
    return packed


def lex_order(keys: Sequence[np.ndarray]) -> np.ndarray:
    """``np.lexsort(keys)`` of integer keys (the last the primary one), one stable sort
    per key from the first.

    >>> lex_order([np.array([1, 0, 2, 1]), np.array([5, 5, 4, 4])]).tolist()
    [3, 2, 1, 0]
    """
    order = stable_order(keys[0])
    for key in keys[1:]:
        order = order[stable_order(np.asarray(key)[order])]
    return order
