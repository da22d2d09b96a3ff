"""The balance room's stability target, for the hollowing tests.

Uses :func:`plumbob.balance.targets.target_for` when the balance room has it; else this
minimal local copy of its margin rows (``inward_e · p − (base_e + margin) ≥ 0`` per
support edge; see the balance room's ``targets.py``), so the hollowing tests run on a
branch where the room is still being built.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

try:
    from plumbob.balance.targets import target_for
except ImportError:  # the balance room's targets are not on this branch yet
    from plumbob.stability import support_polygon

    @dataclass(frozen=True)
    class Target:
        normals: np.ndarray
        offsets: np.ndarray
        down: np.ndarray

        def slack(self, points):
            pts = np.asarray(points, dtype=float)
            return self.normals @ pts.T - (self.offsets[:, None] if pts.ndim == 2 else self.offsets)

    def target_for(body, *, down=None, margin=None, require_tilt_deg=None, support=None):
        assert require_tilt_deg is None, "the local copy knows margins only"
        support = support or support_polygon(body, down)
        frame = support.frame
        inward = -frame.from_ground(support.edge_normals)
        base = inward @ support.plane_point - support.edge_distances
        return Target(inward, base + (margin or 0.0), frame.down.copy())

__all__ = ["target_for"]
