"""The public entry points: from points or a body to its :class:`~.result.Poses`.

:func:`poses_from_points` checks its input, builds the landscape of the convex hull
(:mod:`.landscape`) and :func:`assemble` turns it into poses: stable faces merged
into rolling families (or into a bowl's single rocking pose), each with its
probability, critical tilt and energy barrier. :func:`resting_poses` does the same
for a body, sampling its curved surfaces first.
"""

from __future__ import annotations

import numpy as np

from ...arguments import answering, finite_result, instance, non_negative, optional, positive
from ...errors import GeometryError, StabilityError
from ...massprops import MassProperties
from ...tolerances import contact_tolerance, sampling_tolerance
from ..rocking import rocking
from ..support import body_dim, body_size, hull_points, is_polytope
from ..verdict import STANDARD_GRAVITY
from .landscape import Landscape, families, landscape2, landscape3
from .result import Pose, Poses

__all__ = ["resting_poses", "poses_from_points", "assemble", "FALLBACK_SAMPLES",
           "BOWL_SPREAD_DEG"]

FALLBACK_SAMPLES = 200_000  # Fibonacci directions when the exact basins cannot be traced
# A family of stable sampled faces whose normals all lie within this angle of its lowest
# face is the bottom of a bowl (a self-righting rocker), not a rolling surface.
BOWL_SPREAD_DEG = 5.0


def assemble(land: Landscape, com: np.ndarray, mass: float, g: float,
              neutral_height: float, notes: list[str], X: np.ndarray | None = None) -> Poses:
    """The poses of a landscape: stable faces merged into families, each with its
    probability, critical tilt and energy barrier, most probable first.

    com: (dim,) the centre of mass, m (the landscape is relative to it). notes: appended
    to. X: the hull points relative to the centre, when a bowl's rocking pose should be
    measured (only with ``neutral_height`` > 0).
    """
    ids = np.flatnonzero(land.stable)
    family = families(land, neutral_height)
    total = land.area[ids].sum()
    weight = mass * g
    roots, members_of = np.unique(family[ids], return_inverse=True)
    fam_a, fam_b = family[land.sa], family[land.sb]
    poses = []
    for k, root in enumerate(roots.tolist()):
        members = ids[members_of == k]
        p = float(land.area[members].sum() / total)
        rep = int(members[np.argmax(land.area[members])])
        neutral = len(members) > 1
        bowl = False
        if neutral:
            low = int(members[np.argmin(land.heights[members])])
            # The members as low as the lowest (within the sampling's ridges): spread along
            # a rolling surface, or clustered round the bottom of a bowl, which rocks back.
            level = members[land.heights[members] <= land.heights[low] + 4 * neutral_height]
            spread = np.degrees(np.arccos(np.clip(land.normals[level] @ land.normals[low], -1, 1)))
            bowl = X is not None and float(spread.max()) <= BOWL_SPREAD_DEG
            if bowl:
                rep, neutral = low, False
        between = (fam_a != fam_b) & ((fam_a == root) | (fam_b == root))
        barrier = None
        if between.any():
            barrier = float(weight * max(0.0, float(np.min(land.sh[between])) - land.heights[rep]))
        margin, face = land.margin(rep)
        tilt = 0.0 if neutral else float(np.degrees(np.arctan2(max(margin, 0.0),
                                                               land.heights[rep])))
        if bowl:
            tilt = float(rocking(X, land.normals[rep], neutral_height).tilts_deg.min())
        poses.append(Pose(land.normals[rep].copy(), float(land.heights[rep]), p, tilt, barrier,
                          face + com, neutral, len(members)))
    poses.sort(key=lambda q: (-q.probability, q.com_height))
    neutral_poses = [q for q in poses if q.neutral]
    if neutral_poses:
        notes.append(f"{sum(q.members for q in neutral_poses)} hull faces of rolling surfaces "
                     f"were merged into {len(neutral_poses)} neutral pose(s)")
    rockers = [q for q in poses if q.members > 1 and not q.neutral]
    if rockers:
        notes.append(f"{sum(q.members for q in rockers)} hull faces at the bottom of curved bowls "
                     f"were merged into {len(rockers)} rocking pose(s); their critical tilt is "
                     "that of the rocker, to about a degree")
    if land.method == "sampled":
        notes.append("the basins could not be traced exactly (degenerate hull): probabilities "
                     f"come from rolling {FALLBACK_SAMPLES} directions downhill")
    return Poses(tuple(poses), mass, g, com.copy(), land.method, len(land.normals),
                 int(len(land.sh)), land.error, tuple(notes))


def poses_from_points(points, center_of_mass, *, mass: float = 1.0,
                      g: float = STANDARD_GRAVITY, tolerance: float | None = None,
                      neutral_height: float = 0.0, samples: int = FALLBACK_SAMPLES,
                      notes: tuple[str, ...] = ()) -> Poses:
    """Resting poses of the convex hull of a set of points.

    The basins are traced on the exact hull; faces coplanar within ``tolerance`` are
    then reported as one physical face, their probabilities summed.

    Parameters
    ----------
    points : array_like
        (n, 3) points of a solid, or (n, 2) of a lamina resting on the edges of its hull
        in its own plane, m.
    center_of_mass : array_like
        (3,) or (2,), m; it must lie strictly inside the hull.
    mass : float, optional
        kg, for the energy barriers (default 1).
    g : float, optional
        Gravitational acceleration, m/s² (default standard gravity).
    tolerance : float, optional
        Faces coplanar within it are one physical face, m; default 1e-6 of the points'
        size.
    neutral_height : float, optional
        Stable faces joined by saddles at most this much higher, m, are one neutral
        (rolling) pose; 0 (the default) merges nothing.
    samples : int, optional
        Directions rolled downhill when the exact basins cannot be traced (a degenerate
        hull); the result's ``method`` is then ``"sampled"``.
    notes : tuple of str, optional
        Notes to carry into the result, before its own.

    Returns
    -------
    Poses
        The stable poses, most probable first; their probabilities add up to 1.

    Raises
    ------
    GeometryError
        Too few points, points spanning no volume (area), or non-finite numbers.
    StabilityError
        The centre of mass is not strictly inside the hull: the body rests on no face.

    Examples
    --------
    A cube: six poses of 1/6.

    >>> cube = np.array([[x, y, z] for x in (0, 1) for y in (0, 1) for z in (0, 1)], float)
    >>> ps = poses_from_points(cube, [0.5, 0.5, 0.5])
    >>> len(ps), ps.method, bool(np.allclose(ps.probabilities, 1 / 6, rtol=0, atol=1e-12))
    (6, 'exact', True)

    >>> ps  # doctest: +NORMALIZE_WHITESPACE
    Poses(6 pose(s), probabilities=(0.1667, 0.1667, 0.1667, 0.1667, 0.1667, 0.1667),
          method='exact', mass=1 kg, hull_faces=6)

    A lamina rests on the edges of its hull. This triangle's centre of mass lies
    straight above its corner (0, 0): on its bottom edge it would balance on a knife's
    edge, which is no pose.

    >>> triangle = poses_from_points([[0, 0], [1, 0], [-1, 3]], [0, 1])
    >>> len(triangle), [round(p.probability, 4) for p in triangle]
    (2, [0.5512, 0.4488])

    A centre of mass on the hull's surface rests on no face:

    >>> poses_from_points(cube, [0.5, 0.5, 1.0])
    Traceback (most recent call last):
    ...
    plumbob.errors.StabilityError: the centre of mass lies on the surface of ...
    """
    X = np.asarray(points, dtype=float)
    com = np.asarray(center_of_mass, dtype=float).reshape(-1)
    if X.ndim != 2 or X.shape[1] not in (2, 3) or com.shape != (X.shape[1],):
        raise GeometryError("poses need points (n, 2) or (n, 3) and a centre of the same size")
    if not (np.all(np.isfinite(X)) and np.all(np.isfinite(com))):
        raise GeometryError("a point or the centre of mass is not a finite number")
    if len(X) < X.shape[1] + 1:
        what = "a volume" if X.shape[1] == 3 else "an area"
        raise GeometryError(f"resting poses need points spanning {what}: at least "
                            f"{X.shape[1] + 1}, and this body has {len(X)}")
    size = float(np.linalg.norm(np.ptp(X, axis=0)))
    tol = contact_tolerance(size, tolerance)
    if not (size > 0 and tol > 0):
        raise GeometryError("the points have no extent, or the tolerance is not positive")
    X = X - com
    land = landscape2(X, tol) if X.shape[1] == 2 else landscape3(X, tol, samples)
    return assemble(land, com, float(mass), float(g), float(neutral_height), list(notes),
                    X if neutral_height > 0 else None)


def resting_poses(body, *, g: float = STANDARD_GRAVITY, tolerance: float | None = None,
                  hull_tolerance: float | None = None, neutral_height: float | None = None,
                  props=None) -> Poses:
    """All stable resting poses of a body and how likely a random drop lands in each.

    The quasi-static model of Baktash, Sharp, Zhou, Crane and Jacobson (2025): a pose's
    probability is the area of its basin on the sphere of down directions over 4π.

    Parameters
    ----------
    body : Body
        A solid (poses on the faces of its convex hull) or a lamina (on the edges of its
        hull, in its own plane).
    g : float, optional
        Gravitational acceleration, m/s², for the energy barriers.
    tolerance : float, optional
        Faces coplanar within it are one physical face, m (default 1e-6 of the body's
        size).
    hull_tolerance : float, optional
        How closely curved surfaces are sampled, m (default 1e-4 of the size).
    neutral_height : float, optional
        Poses joined by saddles at most this high above them are merged into one neutral
        (rolling) pose, m. Default: for a body with curved surfaces, twice the hull
        tolerance (the ridges sampling leaves on a rolling surface); for a polytope, 0.
    props : MassProperties, optional
        The body's mass properties, when already computed.

    Returns
    -------
    Poses
        The stable poses, most probable first; their probabilities add up to 1.

    Raises
    ------
    StabilityError
        The centre of mass is not strictly inside the hull (an open mesh, a negative
        density); it never hangs.

    Examples
    --------
    A 1 × 1 × 4 block rarely lands on an end:

    >>> from plumbob.bodies.primitives import box
    >>> [round(p.probability, 4) for p in resting_poses(box(1, 1, 4))]
    [0.2406, 0.2406, 0.2406, 0.2406, 0.0187, 0.0187]

    A curved surface that rolls is one neutral pose, with no critical tilt: a
    cylinder lies on its side or stands on an end.

    >>> from plumbob.bodies.primitives import cylinder
    >>> side, *ends = resting_poses(cylinder(1.0, 2.0))
    >>> side.neutral, side.critical_tilt_deg, len(ends)
    (True, 0.0, 2)
    """
    body, g = answering(body, "body", "mass_properties"), positive(g, "g", error=StabilityError)
    tolerance = optional(positive, tolerance, "tolerance", error=StabilityError)
    hull_tolerance = optional(positive, hull_tolerance, "hull_tolerance", error=StabilityError)
    neutral_height = optional(non_negative, neutral_height, "neutral_height", error=StabilityError)
    props = body.mass_properties() if props is None else instance(props, "props", MassProperties)
    finite_result(props.mass * g, "the weight M g", error=StabilityError)
    dim = body_dim(body, props)
    size = body_size(body)
    htol = sampling_tolerance(size, hull_tolerance)
    pts = hull_points(body, htol)
    if neutral_height is None:  # only sampled (curved) surfaces have rolling families
        neutral_height = 0.0 if is_polytope(body, size) else 2.0 * htol
    com = np.asarray(props.center_of_mass, dtype=float)
    if com.size < dim:
        com = np.pad(com, (0, dim - com.size))
    if pts.shape[1] != dim:
        pts = pts[:, :dim]
    return poses_from_points(pts, com[:dim], mass=props.mass, g=g, tolerance=tolerance,
                             neutral_height=float(neutral_height))
