"""Families of poses: stable faces a small tilt rolls between are one pose.

A tessellated surface of revolution — a cylinder's or a cone's side, a capsule,
a sphere — is a ring (or a cover) of stable facets, each a minimum of the height
function by a sliver: a tilt of half the angle between neighbouring facets rolls
the body onto the next. Two candidate poses are joined when the saddle between
them lies within the *roll angle* of both: a body resting on a face of height
``h`` crosses the saddle at height ``s`` after turning by ``acos(h / s)`` (exactly
the tilt that rolls it over the edge, for neighbouring faces). Joining is
monotone: a larger roll angle only joins more.

A family of more than one pose is then either

* **rolling** — its members lie level, within a few times the family's own ripple
  (the rise of the saddles inside it), and reach far round (at least
  :data:`ROLL_MEMBERS` faces, their normals spread over :data:`ROLL_EXTENT_DEG`):
  the body rolls along it and stops anywhere; reported once, with the axis it
  rolls about when its normals lie on
  a circle (a cylinder, a cone, a capsule) and no axis when they cover a patch of
  the sphere (a ball); or
* **rocking** — it has a bottom (the members rise away from the lowest by more
  than the ripple) or is short (a crease between two nearly flush faces, a bowl
  a few degrees across): the body rocks back to its lowest face, reported as one
  stable pose there.

Candidates on one physical face (:mod:`.faces`) are joined whatever the roll
angle: such a family is one **face**. On a sampled curved surface (a primitive's
cylinder or sphere, not a mesh) candidates joined by saddles no higher than the
sampling's ripple are joined too, as before the roll angle existed. Every step works on all families at
once.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ...arrays import connected_components, dot, group_first
from .landscape import Landscape

__all__ = ["Families", "families", "ROLL_ANGLE_DEG", "ROLL_EXTENT_DEG", "ROLL_MEMBERS",
           "LEVEL_RIPPLES", "CIRCLE_RESIDUAL"]

#: Default roll angle, degrees: faces a tilt this small rolls the body between are one
#: pose. A 12-sided prism rolls over an edge at a 15° tilt (a 64-sided one at 2.8°);
#: a hexagonal pencil needs 30°, a cube 45°, an icosahedron 20.9°.
ROLL_ANGLE_DEG = 15.0
#: A level family whose normals spread less than this (from its lowest) rocks, not rolls.
ROLL_EXTENT_DEG = 30.0
#: A rolling family has at least this many faces (fewer: a crease it rocks across).
ROLL_MEMBERS = 6
#: Members within this many ripples of one another lie level (they roll, not rock).
LEVEL_RIPPLES = 4.0
#: Normals this close (rms, sine of an angle) to a plane lie on a circle: an axis.
CIRCLE_RESIDUAL = 0.02


class Families(NamedTuple):
    """Per candidate pose its family; per family what it is.

    label: (P,) family of each candidate. kind: (F,) ``"face"``, ``"rolling"`` or
    ``"rocking"``. rep: (F,) the candidate that stands for it (a rolling family's or a
    physical face's largest exact face, a bowl's lowest face). members: (F,) candidates
    in it. ripple: (F,)
    the highest rise of a saddle inside it above its faces, m (0 for one face).
    axis: (F, 3) the axis a rolling family rolls about (NaN when it has none).
    """

    label: np.ndarray
    kind: np.ndarray
    rep: np.ndarray
    members: np.ndarray
    ripple: np.ndarray
    axis: np.ndarray


def _axes(normals: np.ndarray, label: np.ndarray, nfam: int) -> np.ndarray:
    """Per family, the unit axis its members' normals circle about (the normal of the
    plane through their tips), NaN where they do not lie on a circle."""
    dim = normals.shape[1]
    if dim == 2:  # a lamina rolls in its own plane: about the plane's normal
        return np.tile([0.0, 0.0, 1.0], (nfam, 1))
    count = np.bincount(label, minlength=nfam).astype(float)
    mean = np.zeros((nfam, 3))
    np.add.at(mean, label, normals)
    mean /= np.maximum(count, 1)[:, None]
    rel = normals - mean[label]
    cov = np.zeros((nfam, 3, 3))
    np.add.at(cov, label, rel[:, :, None] * rel[:, None, :])
    cov /= np.maximum(count, 1)[:, None, None]
    value, vector = np.linalg.eigh(cov)
    axis = vector[:, :, 0]
    # two normals span no plane of tips: they turn about their common perpendicular
    first = group_first(label, np.arange(len(label), dtype=float), nfam)
    last = np.zeros(nfam, dtype=np.int64)
    np.maximum.at(last, label, np.arange(len(label)))
    pair = count == 2
    if pair.any():
        c = np.cross(normals[first[pair]], normals[last[pair]])
        axis[pair] = c / np.linalg.norm(c, axis=1)[:, None]
    on_circle = (np.sqrt(np.maximum(value[:, 0], 0.0)) <= CIRCLE_RESIDUAL) | pair
    big = np.argmax(np.abs(axis), axis=1)
    axis *= np.sign(axis[np.arange(nfam), big])[:, None]  # a deterministic sign
    return np.where(on_circle[:, None], axis, np.nan)


def families(land: Landscape, roll_angle_deg: float = ROLL_ANGLE_DEG,
             neutral_height: float = 0.0) -> Families:
    """The families of ``land``'s candidate poses: candidates on one physical face,
    candidates joined by saddles within ``roll_angle_deg`` of both sides (0 joins none),
    and candidates joined by saddles at most ``neutral_height`` (m) above both (the
    ripple sampling leaves on a curved surface; 0 for a mesh or a polytope)."""
    P = len(land.heights)
    low_side = np.minimum(land.heights[land.sa], land.heights[land.sb])
    high_side = np.maximum(land.heights[land.sa], land.heights[land.sb])
    join = (land.sh * np.cos(np.radians(roll_angle_deg)) <= low_side) & (roll_angle_deg > 0)
    join |= land.sh - high_side <= neutral_height
    label = connected_components(P, np.concatenate((land.sa[join], land.same[0])),
                                 np.concatenate((land.sb[join], land.same[1])))
    nfam = int(label.max()) + 1 if P else 0
    members = np.bincount(label, minlength=nfam)
    ripple = np.zeros(nfam)
    np.maximum.at(ripple, label[land.sa[join]], (land.sh - high_side)[join])
    lowest = group_first(label, land.heights, nfam)
    largest = group_first(label, -land.face_area, nfam)  # its largest face: not traced areas
    top = np.full(nfam, -np.inf)
    np.maximum.at(top, label, land.heights)
    span = top - land.heights[lowest]
    cos_spread = np.ones(nfam)
    np.minimum.at(cos_spread, label, dot(land.normals, land.normals[lowest[label]]))
    spread = np.degrees(np.arccos(np.clip(cos_spread, -1.0, 1.0)))
    # one physical face: every member lies on the physical face of the largest
    a, b = land.same
    on_face = np.ones(nfam, dtype=np.int64)
    np.add.at(on_face, label[a], (a == largest[label[a]]) & (b != a))
    rolls = ((span <= LEVEL_RIPPLES * ripple) & (spread >= ROLL_EXTENT_DEG)
             & (members >= ROLL_MEMBERS))
    kind = np.where(on_face >= members, "face", np.where(rolls, "rolling", "rocking"))
    rep = np.where(kind == "rocking", lowest, largest)
    faces = np.where(kind == "face", 1, members)
    axis = np.full((nfam, 3), np.nan)
    rolling = kind == "rolling"
    if rolling.any():
        axis = np.where(rolling[:, None], _axes(land.normals, label, nfam), np.nan)
    return Families(label, kind, rep, faces, ripple, axis)
