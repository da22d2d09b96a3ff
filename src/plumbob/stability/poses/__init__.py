"""Resting poses: where a body can come to rest, and how likely each landing is.

The model is the quasi-static one of Baktash, Sharp, Zhou, Crane and Jacobson,
"Putting Rigid Bodies to Rest" (SIGGRAPH 2025). Over all down directions ``u``
(unit vectors in the body's frame) the height of the centre of mass ``c`` above
the plane the body rests on is the support function of its convex hull,

    h(u) = max over hull vertices v of (v − c)·u,

and a body dropped without momentum rolls downhill on ``h`` until it rests.
On the sphere of directions (the Gauss map of the hull):

* a face's normal is a point; the face is a **stable pose** — a minimum of ``h``
  — when the foot of the centre of mass lies strictly inside it;
* an edge is an arc between its two faces' normals; it holds a **saddle** where
  the direction from ``c`` square to the edge's line falls within the arc and
  the foot lies inside the edge;
* a vertex ``v`` owns a spherical polygon, on which the body pivots about ``v``:
  directions move along great circles away from ``w = (v − c)/|v − c|``; a vertex
  whose ``w`` lies in its own polygon is a **maximum** (balanced on that tip).

A pose's probability is the area of its basin — the directions that roll into
it — divided by 4π. Basins are bounded by the curves that flow into saddles,
traced back uphill, region by region, to maxima; each basin's area is the
exact sum of signed spherical triangles fanned from its face's normal over its
boundary. Every step is vectorised over all saddles (and all rolls) at once.

The landscape is traced on the *exact* hull — qhull's triangles merged only
where exactly coplanar — so that it is consistent to rounding error; faces
coplanar within the tolerance are merged into physical faces only when the
poses are reported (their probabilities summed). The areas are checked to add
up to 4π. A degenerate landscape (a centre of mass exactly above a vertex or an
edge's end, as symmetric meshes have) is traced again from a centre nudged by
a hair, and the directions landing on a face the true centre sees on its edge
roll on from there; should that fail too, the probabilities come from rolling
a deterministic Fibonacci lattice of directions downhill (and the result says
so). Probabilities add up to 1 by construction, and no NaN can arise.

For a lamina the same holds one dimension down: the hull's edges are the
poses, the circle of directions is cut into arcs, and the basins are exact arcs.

For bodies with curved surfaces (sampled hulls) neighbouring facets of a
rolling surface — a cylinder's side, a sphere — are all stable with barriers
no higher than the sampling's sagitta; poses joined by such saddles are merged
into one *neutral* pose (a body that rolls), whose probability is their sum.
Exact polytopes are never merged that way.

The pieces, lowest first:

* :mod:`.vectors` — vectorised helpers (row-wise algebra, spherical triangles);
* :mod:`.hull` — the exact hull with its edge list, and its physical faces;
* :mod:`.rolling` — the Gauss map's arcs and the roll downhill (:class:`~.rolling.Roller`);
* :mod:`.basins` — basin areas, traced exactly or sampled;
* :mod:`.landscape` — the landscape over physical faces (3D) or edges (2D), families;
* :mod:`.result` — :class:`Pose` and :class:`Poses`;
* :mod:`.resting` — :func:`resting_poses` and :func:`poses_from_points`.
"""

from .resting import FALLBACK_SAMPLES, poses_from_points, resting_poses
from .result import Pose, Poses

__all__ = ["Pose", "Poses", "resting_poses", "poses_from_points", "FALLBACK_SAMPLES"]
