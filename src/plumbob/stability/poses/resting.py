"""The public entry points: from points or a body to its :class:`~.result.Poses`.

:func:`poses_from_points` checks its input, builds the landscape of the convex hull
(:mod:`.landscape`) and :func:`assemble` turns it into poses: stable faces merged
into rolling families (or into a bowl's single rocking pose), each with its
probability, critical tilt and energy barrier. :func:`resting_poses` does the same
for a body, sampling its curved surfaces first.
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np

from ...arguments import answering, count, finite_result, instance, non_negative, optional, positive
from ...errors import GeometryError, StabilityError
from ...massprops import MassProperties
from ...tolerances import CONTACT, HULL_ROUND_OFF, HULL_SAMPLING, size_of
from ...tolerances import sampling_tolerance as sampling
from ...units import SEED_GRAVITY
from ..ground import body_dim, body_size, hull_points, is_polytope
from ..tipping import tipping_angle_deg
from .convex import may_be_own_hull, sample_triangles
from .families import ROLL_ANGLE_DEG, Families, families
from .landscape import Landscape, landscape2, landscape3
from .placement import placement
from .result import Pose, Poses

__all__ = ["resting_poses", "poses_from_points", "assemble", "assemble_indexed",
           "body_points", "points_landscape", "FALLBACK_SAMPLES", "ROLL_ANGLE_DEG"]

FALLBACK_SAMPLES = 200_000  # Fibonacci directions when the exact basins cannot be traced
_FLOAT32_ULPS = 8 * 2.0 ** -24  # float32 round-off of coordinates, relative to their size


def _exits(land: Landscape, fam: Families) -> np.ndarray:
    """Per family, the height of its lowest saddle to another family, m (inf: none)."""
    nfam = len(fam.kind)
    a, b = fam.label[land.sa], fam.label[land.sb]
    out = a != b
    low = np.full(nfam, np.inf)
    np.minimum.at(low, a[out], land.sh[out])
    np.minimum.at(low, b[out], land.sh[out])
    return low


def assemble(land: Landscape, com: np.ndarray, mass: float, g: float,
             roll_angle_deg: float, neutral_height: float, notes: list[str],
             critical_tilts: int | None = None) -> Poses:
    """The poses of a landscape: candidates joined into families (:mod:`.families`), each
    with its probability, critical tilt, energy barrier and placement, most probable
    first.

    com: (dim,) the centre of mass, m (the landscape is relative to it). notes: appended
    to. critical_tilts: how many of the most probable poses get a rocking pose's critical
    tilt (its rocker swept, the costly part on a curved part); a rocking pose after
    them has NaN. None: every pose.
    """
    return assemble_indexed(land, com, mass, g, roll_angle_deg, neutral_height, notes,
                            critical_tilts)[0]


def assemble_indexed(land: Landscape, com: np.ndarray, mass: float, g: float,
                     roll_angle_deg: float, neutral_height: float, notes: list[str],
                     critical_tilts: int | None = None) -> tuple[Poses, np.ndarray]:
    """:func:`assemble`, and per candidate of ``land`` the index (0-based) of the pose it
    belongs to: which pose a roll that ends on a candidate's face has come to rest in."""
    fam = families(land, roll_angle_deg, neutral_height)
    prob = np.bincount(fam.label, weights=land.area, minlength=len(fam.kind))
    prob /= prob.sum()
    exit_height = _exits(land, fam)
    rise = np.maximum(0.0, exit_height - land.heights[fam.rep])
    barrier = np.where(np.isfinite(exit_height), mass * g * rise, np.nan)
    order = np.lexsort((land.heights[fam.rep], -prob))
    size = size_of(land.points)
    poses = []
    for k, f in enumerate(order.tolist()):
        r = int(fam.rep[f])
        down, height = land.normals[r].copy(), float(land.heights[r])
        t = tipping_angle_deg(max(float(land.margin[r]), 0.0), height)
        if fam.kind[f] == "rolling":
            t = 0.0
        elif fam.kind[f] == "rocking" and critical_tilts is not None and k >= critical_tilts:
            t = math.nan  # not asked for: its rocker is not swept
        elif fam.kind[f] == "rocking":  # where the rocker's equilibrium ends
            from ..rocking import least_tilt  # only a bowl's bottom needs it

            eps = 2.0 * max(float(fam.ripple[f]), HULL_SAMPLING * size)
            # no rocker holds a tilt steeper than the one rolling it over its lowest exit
            exit_tilt = math.degrees(math.acos(min(1.0, height / float(exit_height[f]))))
            rocks = least_tilt(land.points, down, eps, cap_deg=exit_tilt)
            t = max(t, rocks)  # and never less than its own face's
        axis = None if np.isnan(fam.axis[f, 0]) else fam.axis[f].copy()
        poses.append(Pose(down, height, float(prob[f]), t,
                          None if np.isnan(barrier[f]) else float(barrier[f]),
                          land.corners(r) + com, str(fam.kind[f]), int(fam.members[f]), axis,
                          placement(down, com, height)))
    rolling = [q for q in poses if q.kind == "rolling"]
    if rolling:
        notes.append(f"{sum(q.members for q in rolling)} faces of rolling surfaces were merged "
                     f"into {len(rolling)} rolling pose(s) (neighbours within a "
                     f"{roll_angle_deg:g}° roll)")
    rockers = [q for q in poses if q.kind == "rocking"]
    if rockers:
        notes.append(f"{sum(q.members for q in rockers)} faces at the bottom of curved bowls "
                     f"were merged into {len(rockers)} rocking pose(s); their critical tilt is "
                     "that of the rocker, to about a degree")
    if land.method == "sampled":
        notes.append("the basins could not be traced exactly (degenerate hull): probabilities "
                     f"come from rolling {FALLBACK_SAMPLES} directions downhill")
    pose_of_family = np.empty(len(order), dtype=np.int64)
    pose_of_family[order] = np.arange(len(order))
    return (Poses(tuple(poses), mass, g, com.copy(), land.method, land.faces,
                  int(len(land.sh)), land.error, tuple(notes)), pose_of_family[fam.label])


def _own_surface(mesh, pts: np.ndarray, com: np.ndarray, size: float
                 ) -> tuple[np.ndarray, np.ndarray | None]:
    """A mesh body's (:meth:`Body.as_mesh`) welded vertices and triangles, for
    :func:`~.convex.own_hull` to take as the hull if it proves the mesh convex; ``pts``
    and None when a sample of its triangles' planes already shows it is not
    (:func:`~.convex.may_be_own_hull`), so that such a mesh is not welded again."""
    corners = sample_triangles(mesh.triangles) - com
    if not may_be_own_hull(pts - com, corners, HULL_ROUND_OFF * size):
        return pts, None
    return mesh.welded


def _triangle_indices(surface, n: int) -> np.ndarray:
    """``surface`` as (m, 3) int64 indices below ``n``, or a GeometryError."""
    tri = np.asarray(surface)
    if tri.ndim != 2 or tri.shape[1] != 3 or not (tri.dtype.kind in "iu" or tri.size == 0):
        raise GeometryError("a surface for the poses needs (m, 3) integer indices into the "
                            f"points, not an array of shape {tri.shape} ({tri.dtype})")
    tri = tri.astype(np.int64, copy=False)
    if tri.size and not (tri.min() >= 0 and tri.max() < n):
        raise GeometryError(f"a surface's triangles index points 0 … {n - 1} only, "
                            f"not {int(tri.min())} … {int(tri.max())}")
    return tri


def poses_from_points(points, center_of_mass, *, mass: float = 1.0,
                      g: float = SEED_GRAVITY, tolerance: float | None = None,
                      roll_angle_deg: float = ROLL_ANGLE_DEG, neutral_height: float = 0.0,
                      samples: int = FALLBACK_SAMPLES,
                      notes: tuple[str, ...] = (), surface=None,
                      critical_tilts: int | None = None) -> Poses:
    """Resting poses of the convex hull of a set of points.

    The basins are traced on the exact hull; faces coplanar within ``tolerance`` of a
    stable face's plane are then one physical face, their probabilities summed, and
    faces a tilt of at most ``roll_angle_deg`` rolls the body between are one rolling
    (or rocking) family.

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
        Gravitational acceleration, m/s² (default 9.81, the seed's g: ``units.SEED_GRAVITY``).
    tolerance : float, optional
        Faces whose corners lie within it of a stable face's plane are one physical face,
        m; default 1e-6 of the points' size (and at least 8 float32 round-offs of their
        largest coordinate, so float32 noise never splits a face).
    roll_angle_deg : float, optional
        Stable faces the body rolls between when tilted by at most this, degrees, are
        one pose of kind ``"rolling"`` (or ``"rocking"`` for a bowl's bottom); 0 merges
        nothing. Default :data:`~.families.ROLL_ANGLE_DEG` (15°).
    neutral_height : float, optional
        Stable faces joined by saddles at most this much higher, m, are one family too
        (the ripple of a sampled curved surface); 0 (the default) joins none that way.
    samples : int, optional
        Directions rolled downhill when the exact basins cannot be traced (a degenerate
        hull); the result's ``method`` is then ``"sampled"``.
    notes : tuple of str, optional
        Notes to carry into the result, before its own.
    surface : array_like of int, optional
        (m, 3) the triangles of the body's closed, outward-wound mesh through the
        points (indices into ``points``, every point a corner). When checks that prove
        it find the mesh convex (:func:`~.convex.own_hull`), its triangles are the
        hull's and no hull is computed (on a finely tessellated capsule the hull is
        most of the time); otherwise, and for a lamina, it changes nothing.
    critical_tilts : int, optional
        How many of the most probable poses get a rocking pose's critical tilt, whose
        rocker sweep is most of the time on a curved part; a rocking pose after them has
        ``critical_tilt_deg`` NaN (not computed). None (the default): every pose. A
        batch row shows the first pose only (``plumbob batch --poses``: 1).

    Returns
    -------
    Poses
        The stable poses, most probable first; their probabilities add up to 1.

    Raises
    ------
    GeometryError
        Too few points, points spanning no volume (area), or non-finite numbers; a
        ``surface`` that is not (m, 3) indices into the points.
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
    land, com = points_landscape(points, center_of_mass, tolerance=tolerance,
                                 roll_angle_deg=roll_angle_deg, neutral_height=neutral_height,
                                 samples=samples, surface=surface)
    return assemble(land, com, float(mass), float(g), float(roll_angle_deg),
                    float(neutral_height), list(notes), critical_tilts)


def points_landscape(points, center_of_mass, *, tolerance: float | None,
                     roll_angle_deg: float, neutral_height: float, samples: int,
                     surface=None) -> tuple[Landscape, np.ndarray]:
    """The checked landscape of :func:`poses_from_points` (its parameters), and the centre
    of mass (dim,) m it is relative to."""
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
    size = size_of(X)
    if tolerance is None:
        tol = max(CONTACT * size, _FLOAT32_ULPS * float(np.abs(X).max()))
    else:
        tol = float(tolerance)
    if not (size > 0 and tol > 0):
        raise GeometryError("the points have no extent, or the tolerance is not positive")
    if surface is not None:
        surface = _triangle_indices(surface, len(X))
    X = X - com
    if X.shape[1] == 2:
        land = landscape2(X, tol)
    else:  # the families are known before the trace: only the boundaries between poses
        land = landscape3(X, tol, samples, partial(families, roll_angle_deg=roll_angle_deg,
                                                   neutral_height=neutral_height), surface)
    return land, com


def resting_poses(body, *, g: float = SEED_GRAVITY, tolerance: float | None = None,
                  sampling_tolerance: float | None = None,
                  roll_angle_deg: float = ROLL_ANGLE_DEG,
                  props=None, critical_tilts: int | None = None) -> Poses:
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
        Faces whose corners lie within it of a stable face's plane are one physical face,
        m (default 1e-6 of the body's size, and at least 8 float32 round-offs of its
        largest coordinate).
    sampling_tolerance : float, optional
        How closely curved surfaces of shapes (primitives, specs) are sampled, m (default
        1e-4 of the size). A mesh's hull is its own vertices: this does not change it.
    roll_angle_deg : float, optional
        Stable faces a tilt of at most this many degrees rolls the body between are one
        pose (default 10°): ``"rolling"`` when they lie level (a cylinder's side, a
        tessellated cone, a ball), ``"rocking"`` when they are a bowl's bottom. 0 merges
        nothing.
    props : MassProperties, optional
        The body's mass properties, when already computed.
    critical_tilts : int, optional
        How many of the most probable poses get a rocking pose's critical tilt (see
        :func:`poses_from_points`); the others' rocking poses have NaN. None: every pose.

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

    A curved surface that rolls is one rolling pose, with its axis and no critical
    tilt: a cylinder lies on its side or stands on an end. Every pose carries the
    rigid transform that sets the body down in it, on z = 0.

    >>> from plumbob.bodies.primitives import cylinder
    >>> side, *ends = resting_poses(cylinder(1.0, 2.0))
    >>> side.kind, side.axis.tolist(), side.critical_tilt_deg, len(ends)
    ('rolling', [0.0, 0.0, 1.0], 0.0, 2)
    >>> ends[0].transform.shape
    (4, 4)
    """
    body, g = answering(body, "body", "mass_properties"), positive(g, "g", error=StabilityError)
    tolerance = optional(positive, tolerance, "tolerance", error=StabilityError)
    sampling_tolerance = optional(positive, sampling_tolerance, "sampling_tolerance",
                                  error=StabilityError)
    roll_angle_deg = non_negative(roll_angle_deg, "roll_angle_deg", error=StabilityError)
    critical_tilts = optional(count, critical_tilts, "critical_tilts", math.inf,
                              error=StabilityError)
    props = body.mass_properties() if props is None else instance(props, "props", MassProperties)
    finite_result(props.mass * g, "the weight M g", error=StabilityError)
    pts, com, neutral_height, surface = body_points(body, props, sampling_tolerance)
    return poses_from_points(pts, com, mass=props.mass, g=g, tolerance=tolerance,
                             roll_angle_deg=roll_angle_deg, neutral_height=neutral_height,
                             surface=surface, critical_tilts=critical_tilts)


def body_points(body, props: MassProperties, sampling_tolerance: float | None
                ) -> tuple[np.ndarray, np.ndarray, float, np.ndarray | None]:
    """What :func:`resting_poses` hands :func:`poses_from_points` for ``body``: its hull
    points (n, dim) m, its centre of mass (dim,) m, the neutral height (m: the ripple of
    sampled curved surfaces, 0 for an exact hull) and its own convex mesh's triangles
    (or None)."""
    dim = body_dim(body, props)
    size = body_size(body)
    htol = sampling(size, sampling_tolerance)
    pts = hull_points(body, htol)
    # sampled (curved) surfaces leave ridges up to the sampling tolerance: below them is one
    # family whatever the roll angle; a mesh's or a polytope's hull is exact
    neutral_height = 0.0 if is_polytope(body, size) else 2.0 * htol
    com = np.asarray(props.center_of_mass, dtype=float)
    if com.size < dim:
        com = np.pad(com, (0, dim - com.size))
    if pts.shape[1] != dim:
        pts = pts[:, :dim]
    surface = None
    mesh = body.as_mesh() if dim == 3 else None
    if mesh is not None:  # its own mesh: the hull, if convex
        pts, surface = _own_surface(mesh, pts, com, size)
    return pts, com[:dim], neutral_height, surface
