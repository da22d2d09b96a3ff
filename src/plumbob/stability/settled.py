"""A verdict for a solid set down on a point, a line or a sliver: where it comes to rest.

When it settles there (``settling.stays``: within the poses' roll angle, or rocking back
into a bowl's bottom) every field of the verdict is where it rests, ``down`` included
(the down it was set down with is ``settling.down_from``); when it rolls away they are
where it was set down, and ``settling`` says where it goes.

:func:`plumbob.check` hands over here when the support is a point, a line or a sliver
(:func:`~.support.contact_kind`): the roll into the pose whose basin holds the
orientation (:func:`~.poses.settling.settle`), then the verdict where it rests. Loaded
only for such a support (the poses with it).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np

from .poses.settling import settle

__all__ = ["settled_verdict", "tipping_over_line"]


def settled_verdict(body, result, contact: str, g: float, props,
                    check_at: Callable[[np.ndarray], Any]):
    """``result`` (the verdict where the body was set down) with its settling: where it
    settles there, the verdict where it rests (``check_at(down)``, the check without
    settling), else ``result`` itself, the way it goes in ``settling``."""
    rolls_here = result.verdict == "neutral" and result.rocking is not None
    settling, _ = settle(body, result.down, contact=contact, g=g, props=props,
                         rolls_here=rolls_here)
    there = check_at(settling.down)
    if settling.pose_kind == "rocking" and settling.own_face and there.verdict == "stands":
        # at a bowl's bottom a tilt rocks it, not over its facet's edge: the rocker's tilt
        there = _rocker_tilt(there, settling.critical_tilt_deg)
    else:
        settling = replace(settling, verdict=there.verdict,
                           critical_tilt_deg=there.critical_tilt_deg)
    return replace(there if settling.stays else result, settling=settling)


def _rocker_tilt(there, tilt: float):
    """``there`` with the critical tilt of the rocker it rests in, degrees (and the tilt
    design check on it)."""
    design = there.design
    if design is not None and design.required_tilt_deg is not None:
        design = replace(design, passes=bool(tilt >= design.required_tilt_deg))
    return replace(there, critical_tilt_deg=tilt, design=design)


def tipping_over_line(sup, direction) -> float:
    """On a line of contact ``sup`` it rolls across (a segment support of a solid): the
    tilt, degrees, that tips it over the end it faces when the plane descends toward
    ``direction`` (body frame) — ``atan(d / (h cos φ))``, ``d`` the end's distance from the
    foot, ``φ`` the angle from the line — and 90° straight across it (it only rolls)."""
    d = sup.frame.to_ground(np.asarray(direction, dtype=float))
    d = d / np.linalg.norm(d)
    cos = sup.edge_normals[2:] @ d  # a segment's edges: its two sides, then its ends
    facing = cos > 1e-12
    if not facing.any():
        return 90.0
    reach = float(np.min(sup.edge_distances[2:][facing] / cos[facing]))
    return float(np.degrees(np.arctan2(max(reach, 0.0), sup.com_height)))
