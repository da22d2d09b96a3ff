"""What a stability check is asked: one value, checked once, shared by every command.

A :class:`Requirement` holds the orientation (gravity's direction ``down`` and
``g``), the tilted plane to check it on (``tilt_deg`` toward ``toward_deg``), the
friction coefficient, the design checks (a static stability ``margin``, a critical
tilt ``require_tilt_deg`` in every direction) and the applied ``loads``. It is built
once — by :func:`plumbob.check`'s keywords, by the command line (``--down``, ``--g``,
``--tilt``, ``--toward``, ``--friction``, ``--margin``, ``--require-tilt``,
``--force``, ``--hang``), by a batch's options — and checked in ``__post_init__``,
so every command reads the same spelling in the same unit.

Units: lengths m, g m/s², **angles in degrees** (at every boundary: library, CLI,
JSON); the direction a tilted plane descends toward is an angle in the ground plane
from its first axis toward its second (for ``down = −z``, from +x toward +y).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..arguments import in_range, non_negative, number, optional, positive, vector
from ..errors import StabilityError
from ..loads import Force, Hang, Press, Push
from ..units import SEED_GRAVITY

__all__ = ["Requirement"]


@dataclass(frozen=True, eq=False)
class Requirement:
    """How the body rests and what it must withstand.

    down: (dim,) the direction of gravity in the body's frame (any length), or None for
        the default (−z; −y for a lamina).
    g: gravitational acceleration, m/s² (> 0).
    tilt_deg: a plane tilted this many degrees, [0, 90), or None.
    toward_deg: the direction that plane descends toward, degrees in the ground plane,
        or None for the worst direction.
    friction: the friction coefficient μ ≥ 0, or None.
    margin: the static stability margin the design must have, m (≥ 0), or None.
    require_tilt_deg: the tilt, degrees in [0, 90], it must withstand in every
        direction, or None.
    loads: applied loads (:class:`~plumbob.stability.loads.Force`,
        :class:`~plumbob.stability.loads.Hang`).
    """

    down: np.ndarray | None = None
    g: float = SEED_GRAVITY
    tilt_deg: float | None = None
    toward_deg: float | None = None
    friction: float | None = None
    margin: float | None = None
    require_tilt_deg: float | None = None
    loads: tuple = field(default=())

    def __post_init__(self) -> None:
        def put(name: str, value: Any) -> None:
            object.__setattr__(self, name, value)

        put("down", optional(vector, self.down, "down", (2, 3), error=StabilityError))
        put("g", positive(self.g, "g", error=StabilityError))
        if self.tilt_deg is not None:
            tilt = number(self.tilt_deg, "tilt_deg", error=StabilityError)
            if not 0 <= tilt < 90:
                raise StabilityError(f"a tilt must be between 0° and 90°, not {tilt:g}°")
            put("tilt_deg", tilt)
        put("toward_deg", optional(number, self.toward_deg, "toward_deg", error=StabilityError))
        if self.friction is not None:
            try:
                friction = float(self.friction)
            except (TypeError, ValueError):
                raise StabilityError(f"friction must be a number, not {self.friction!r}") from None
            if not (np.isfinite(friction) and friction >= 0):
                raise StabilityError(f"a friction coefficient must be ≥ 0, not {friction:g}")
            put("friction", friction)
        put("margin", optional(non_negative, self.margin, "margin", error=StabilityError))
        put("require_tilt_deg", optional(in_range, self.require_tilt_deg, "require_tilt_deg",
                                         0, 90, unit="°", error=StabilityError))
        loads = tuple(self.loads or ())
        for load in loads:
            if not isinstance(load, (Force, Hang, Push, Press)):
                raise StabilityError("a load must be a plumbob.Force, Hang, Push or Press, "
                                     f"not {type(load).__name__}")
        put("loads", loads)

    @property
    def asks_design(self) -> bool:
        """Whether a design check (a margin or a required tilt) is asked."""
        return self.margin is not None or self.require_tilt_deg is not None

    def gravity_down(self, dim: int) -> np.ndarray:
        """The unit direction of gravity for a body of ``dim`` dimensions (the default
        −z, −y for a lamina, when ``down`` is not given)."""
        from .support import default_down, unit_vector

        return default_down(dim) if self.down is None else unit_vector(self.down, dim)

    def toward_direction(self, dim: int) -> np.ndarray | None:
        """``toward_deg`` as a horizontal unit vector in the body's frame, or None."""
        if self.toward_deg is None:
            return None
        from .support import ground_frame

        return ground_frame(self.gravity_down(dim)).direction(self.toward_deg)

    def replace(self, **changes: Any) -> Requirement:
        """This requirement with ``changes`` (checked again)."""
        from dataclasses import replace

        return replace(self, **changes)
