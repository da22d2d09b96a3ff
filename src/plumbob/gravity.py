"""The values of g plumbob knows, m/s² (a module without numpy: ``import plumbob``
needs them, and the command sets up numpy's threads before numpy loads)."""

from __future__ import annotations

__all__ = ["SEED_GRAVITY", "STANDARD_GRAVITY"]

#: m/s², the value of g the seed's worked answers use: the default wherever gravity enters
#: (``--g`` and every ``g=`` argument), so those answers come out as the seed prints them
SEED_GRAVITY = 9.81

#: m/s², standard gravity gₙ as defined (CGPM 1901, exact); pass it as ``g`` (``--g 9.80665``)
#: for answers in the standard's terms
STANDARD_GRAVITY = 9.80665
