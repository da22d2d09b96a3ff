"""The one home of plumbob's relative tolerances.

Every tolerance scales with the body, so a part drawn in millimetres and the same
part in metres get the same answers. A tolerance given explicitly (in metres) always
wins over these defaults.
"""

from __future__ import annotations

import numpy as np

__all__ = ["CONTACT", "HULL_LEFT_OUT", "HULL_ROUND_OFF", "HULL_SAMPLING", "SLIVER", "TEXT_ROUND_OFF", "WELD",
           "contact_tolerance", "sampling_tolerance", "size_of", "weld_tolerance"]

#: Points within this fraction of the body's size of the lowest level touch the
#: ground, and faces coplanar within it are one face: far above float64 round-off
#: on coordinates, far below anything a maker can build.
CONTACT = 1e-6

#: Mesh vertices on unshared edges closer than this fraction of the mesh's size are one
#: vertex (welded). CAD exporters write copies of a vertex that differ by round-off
#: (1e-17 of the size in SolidWorks STL files; a float32 ulp is 6e-8 of a coordinate);
#: real features of trimesh's test models are 2e-4 of the size apart or more.
WELD = 1e-7

#: Curved surfaces are sampled so no point of the body lies further than this
#: fraction of its size outside the samples' hull.
HULL_SAMPLING = 1e-4

#: A convex hull's planes, corners and edges are exact to this fraction of the size:
#: coplanar within it is one face, concave by less is convex (float64 round-off of
#: the hull's own arithmetic, far below the contact tolerance).
HULL_ROUND_OFF = 1e-12

#: manifold3d's quickhull leaves out points within its epsilon (1e-7 of the largest
#: coordinate) of a facet; a hull that leaves a point further out than this fraction of
#: the size is wrong and is not used (``stability/poses/holds.py``).
HULL_LEFT_OUT = 1e-7

#: A support polygon narrower than this fraction of the body's size is a *sliver*: a
#: facet of a fine tessellation (a scan's curved bottom: an icosphere's facets are 1.6–2.1 %
#: of its size across at 5120 triangles, 0.8–1.0 % at 20 480), on which the body touches
#: the ground at a point in all but name. ``check`` then says where it settles, as for a
#: point or a line of contact. A plate standing on an edge a fortieth of its size is a
#: sliver too, and settles 0° into the pose it stands in.
SLIVER = 2.5e-2

#: Text reports show values below this fraction of their scale as 0: round-off
#: that six significant digits would otherwise print as noise (JSON keeps every digit).
TEXT_ROUND_OFF = 1e-9


def size_of(points: np.ndarray) -> float:
    """The size every relative tolerance scales with, m: the diagonal of the bounding box
    of ``points`` (n, dim), ``np.linalg.norm(np.ptp(points, axis=0))`` to the bit.

    Column by column: a reduction down the rows of an (n, 3) array runs an inner loop of
    3 per row, 20 times slower than one column at a time.

    >>> size_of(np.array([[0.0, 0.0, 0.0], [3.0, 4.0, 0.0], [1.0, 1.0, 0.0]]))
    5.0
    """
    points = np.asarray(points)
    if points.ndim != 2 or len(points) == 0:
        return float(np.linalg.norm(np.ptp(points, axis=0)))
    span = np.array([points[:, k].max() - points[:, k].min() for k in range(points.shape[1])])
    return float(np.linalg.norm(span))


def contact_tolerance(size: float, tolerance: float | None = None) -> float:
    """The contact tolerance, m: ``tolerance`` if given, else :data:`CONTACT` of ``size`` (m).

    >>> contact_tolerance(2.0), contact_tolerance(2.0, 0.5)
    (2e-06, 0.5)
    """
    return CONTACT * size if tolerance is None else float(tolerance)


def sampling_tolerance(size: float, tolerance: float | None = None) -> float:
    """How closely curved surfaces are sampled, m: ``tolerance`` if given, else
    :data:`HULL_SAMPLING` of ``size`` (m).

    >>> sampling_tolerance(2.0)
    0.0002
    """
    return HULL_SAMPLING * size if tolerance is None else float(tolerance)


def weld_tolerance(size: float, tolerance: float | None = None) -> float:
    """The distance, m, within which mesh vertices are welded: ``tolerance`` if given,
    else :data:`WELD` of ``size`` (m).

    >>> weld_tolerance(2.0)
    2e-07
    """
    return WELD * size if tolerance is None else float(tolerance)
