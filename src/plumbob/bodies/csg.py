"""Constructive geometry: union, difference, intersection — exact where it can be.

The user writes the shape; plumbob picks the method:

* parts that do not overlap, or a removed part lying wholly inside what it is
  removed from, compose exactly by the mass-property algebra (a
  :class:`Composite`: the seed's parts-as-particles, holes as negative mass);
* parts that do overlap go through a boolean in float64 — shapely in 2D,
  manifold3d in 3D. When every part is a polytope (boxes, prisms of polygons,
  meshes) there is nothing to facet: the result is exact but for round-off, and
  says so with a bound on it. Curved parts are cut into an explicit number of
  segments per turn and the result integrated exactly at n and at n/2; since the
  faceting error falls as 1/n², ``(4 P_n − P_n/2) / 3`` removes its leading term
  (Richardson). That result is marked not exact, with a bound on its error
  (:mod:`plumbob.bodies.bounds`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..arguments import count as whole_count
from ..errors import DensityError, GeometryError
from ..limits import MAX_SIDES
from ..massprops import MassProperties, combine
from .base import Body, Grader, lowest
from .booleans import manifold_union, measure, overlap, shapely_union
from .faceted import Faceted
from .overlaps import Facets, bounding_boxes, boxes_meet, candidate_pairs, connected_groups, local_origin

__all__ = ["Composite", "Assembly", "Faceted", "as_assembly", "union", "difference", "intersection",
           "leaf_densities", "DEFAULT_SEGMENTS"]

DEFAULT_SEGMENTS = 256  # circular segments per full turn for faceted booleans


class _OfParts(Body):
    """What a body made of parts answers from its parts."""

    parts: tuple[Body, ...]

    def with_default_density(self, density: float) -> Body:
        return replace(self, parts=tuple(p.with_default_density(density) for p in self.parts))

    @property
    def is_polytope(self) -> bool:
        return all(part.is_polytope for part in self.parts)

    def densities(self) -> set:
        return set().union(*(p.densities() for p in self.parts))

    def transformed(self, matrix: np.ndarray, offset: np.ndarray | None = None) -> Body:
        """Each part moved, so each keeps its own digits (see :func:`combined`)."""
        moved = Body.transformed(self, matrix, offset)  # checks the arguments
        if any(p.dim != self.dim for p in self.parts):
            return moved  # a lamina in a solid assembly: placed as a whole
        return replace(self, parts=tuple(p.transformed(moved.matrix, moved.offset)
                                         for p in self.parts))


@dataclass(frozen=True, eq=False, repr=False)
class Composite(_OfParts):
    """Parts of one body combined exactly: ``signs`` +1 adds a part, −1 removes a hole.

    The parts must not overlap (added ones) and each hole must lie inside the
    added parts — :func:`union` and :func:`difference` check this before
    building one.
    """

    parts: tuple[Body, ...]
    signs: tuple[float, ...]
    name: str | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "parts", tuple(self.parts))
        object.__setattr__(self, "signs", tuple(float(s) for s in self.signs))
        if not self.parts or len(self.parts) != len(self.signs):
            raise GeometryError("a composite needs parts, each with a sign")
        if len({p.dim for p in self.parts}) != 1:
            raise GeometryError("cannot combine laminas with solids in one body; use an assembly")

    @property
    def dim(self) -> int:  # type: ignore[override]
        return self.parts[0].dim

    @property
    def kind(self) -> str:  # type: ignore[override]
        return self.parts[0].kind if len({p.kind for p in self.parts}) == 1 else "solid"

    def mass_properties(self) -> MassProperties:
        return combined(self.parts, list(self.signs))

    def _added(self) -> list[Body]:
        return [p for p, s in zip(self.parts, self.signs) if s > 0]

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        return np.concatenate([p.hull_points(tolerance) for p in self._added()])

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        pts = np.concatenate([p.support_points(down, tolerance) for p in self._added()])
        return lowest(pts, np.asarray(down, dtype=float), tolerance)

    def to_geometry(self, segments: int = 128):
        added = [p.to_geometry(segments) for p, s in zip(self.parts, self.signs) if s > 0]
        removed = [p.to_geometry(segments) for p, s in zip(self.parts, self.signs) if s < 0]
        if self.dim == 2:
            import shapely

            result = shapely.union_all(added)
            return shapely.difference(result, shapely.union_all(removed)) if removed else result
        result = manifold_union(added)
        return result - manifold_union(removed) if removed else result

    # ------------------------------------------------------------ questions
    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        """In an added part (within ``tolerance``) and not inside a hole (by more than
        ``tolerance``): a hole's rim stays on the body."""
        pts = points
        inside = np.zeros(len(pts), dtype=bool)
        for part in self._added():
            inside |= part.contains(pts, tolerance)
        for part, sign in zip(self.parts, self.signs):
            if sign < 0 and inside.any():
                inside &= ~part.contains(pts, -part._contains_tolerance(tolerance))
        return inside

    def exact_region(self):
        if self.dim != 2:
            return super().exact_region()
        from .region import Region

        return Region(tuple(r if s > 0 else r.reversed() for p, s in zip(self.parts, self.signs)
                            for r in p.exact_region().rings))

    def graded(self, grader: Grader) -> Body:
        holes = tuple(p for p, s in zip(self.parts, self.signs) if s < 0)
        return replace(self, parts=tuple(p.graded(grader.part(s < 0, holes))
                                         for p, s in zip(self.parts, self.signs)))

    def _describe(self) -> str:
        removed = sum(1 for s in self.signs if s < 0)
        added = len(self.parts) - removed
        holes = f" less {removed} hole{'s' if removed > 1 else ''}" if removed else ""
        return f"{self.kind} of {added} part{'s' if added > 1 else ''}{holes}"


@dataclass(frozen=True, eq=False, repr=False)
class Assembly(_OfParts):
    """Separate parts, each its own body and material, reported part by part.

    Unlike a :class:`Composite`, an assembly keeps its parts' identities: the
    report gives each part's mass and centre beside the combined properties.
    """

    parts: tuple[Body, ...]
    name: str | None = None

    kind = "assembly"

    def __post_init__(self) -> None:
        object.__setattr__(self, "parts", _bodies(self.parts, "an assembly"))
        if not self.parts:
            raise GeometryError("an assembly needs at least one part")

    @property
    def dim(self) -> int:  # type: ignore[override]
        return max(p.dim for p in self.parts)

    def assembly_parts(self) -> tuple[Body, ...]:
        return self.parts

    def part_properties(self) -> list[MassProperties]:
        return [p.mass_properties() for p in self.parts]

    def mass_properties(self) -> MassProperties:
        return combined(self.parts, None, self.part_properties())

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        pts = [p.hull_points(tolerance) for p in self.parts]
        if len({p.shape[1] for p in pts}) > 1:
            pts = [np.pad(p, ((0, 0), (0, 3 - p.shape[1]))) for p in pts]
        return np.concatenate(pts)

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        down = np.asarray(down, dtype=float)
        pts = [
            p.support_points(down, tolerance)
            if p.dim == len(down)
            # a lamina in a solid assembly lies in z = 0: its hull points, in space
            else np.pad(p.hull_points(tolerance), ((0, 0), (0, len(down) - p.dim)))
            for p in self.parts
        ]
        return lowest(np.concatenate(pts), down, tolerance)

    # ------------------------------------------------------------ questions
    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        """In any part; a lamina in a solid assembly lies in z = 0 (within its tolerance)."""
        pts = points
        inside = np.zeros(len(pts), dtype=bool)
        for part in self.parts:
            tol = part._contains_tolerance(tolerance)
            flat = np.all(np.abs(pts[:, part.dim:]) <= tol, axis=1)
            if flat.any():
                inside[flat] |= part.contains(pts[flat, :part.dim], tol)
        return inside

    def graded(self, grader: Grader) -> Body:
        return replace(self, parts=tuple(p.graded(grader.separate()) for p in self.parts))

    def _describe(self) -> str:
        names = [repr(p.name) for p in self.parts[:3] if p.name]
        listed = f": {', '.join(names)}{', …' if len(self.parts) > 3 else ''}" if names else ""
        return f"of {len(self.parts)} part{'s' if len(self.parts) > 1 else ''}{listed}"


def combined(parts: tuple[Body, ...], signs: list[float] | None,
             props: list[MassProperties] | None = None) -> MassProperties:
    """The parts' mass properties combined (``signs``: +1 adds, −1 removes), far from the
    origin about a local one.

    Each part's centre is a float: at 1e6 m it is known to 1e-10 m, and the parallel
    axes would carry that into the inertia (5e-10 of it for parts 0.2 m apart). So when
    the parts lie further from the origin than their spread, they are moved to the
    heaviest part's centre (the move is exact: coordinates within a factor 2 of it
    subtract without rounding), combined there, and the result moved back once.

    >>> from plumbob.bodies.primitives import box
    >>> far = [box(1, 1, 1).translated([1e6 + k, 0, 0]) for k in (0, 1)]
    >>> float(combined(tuple(far), None).inertia[1, 1] * 12)   # 2 · 2 + 12 · 2 · (1/2)²
    10.0
    """
    props = [p.mass_properties() for p in parts] if props is None else props
    dims = {p.dim for p in parts} | {len(p.center_of_mass) for p in props}
    if len(parts) < 2 or len(dims) > 1:  # a lamina in a solid assembly: combined as it is
        return combine(props, signs)
    masses = np.array([abs(p.mass) for p in props])
    centres = np.array([p.center_of_mass for p in props])
    anchor = centres[int(np.argmax(masses))]
    spread = float(np.max(np.linalg.norm(centres - anchor, axis=1))) + max(
        float(np.sqrt(np.trace(p.inertia) / p.mass)) if p.mass > 0 else 0.0 for p in props)
    if not float(np.max(np.abs(anchor))) > spread:
        return combine(props, signs)
    local = combine([p.translated(-anchor).mass_properties() for p in parts], signs)
    return local.transformed(np.eye(len(anchor)), anchor)


# ------------------------------------------------------------------ booleans
def _bodies(parts, what: str) -> tuple[Body, ...]:
    """``parts`` as a tuple, each checked to be a plumbob body."""
    if isinstance(parts, (str, bytes, Body)) or not hasattr(parts, "__iter__"):
        raise GeometryError(f"{what} needs a sequence of bodies, not {type(parts).__name__}")
    parts = tuple(parts)
    for k, part in enumerate(parts, 1):
        if not isinstance(part, Body):
            raise GeometryError(f"{what}: part {k} is not a plumbob body but "
                                f"{type(part).__name__}")
    return parts


def _same_dim(bodies: tuple[Body, ...], segments: int) -> int:
    """The bodies' common dimension, after checking the arguments of a boolean."""
    if not bodies:
        raise GeometryError("a boolean needs at least one body")
    _bodies(bodies, "a boolean")
    whole_count(segments, "segments", MAX_SIDES, minimum=8, error=GeometryError)
    dims = {b.dim for b in bodies}
    if len(dims) != 1:
        raise GeometryError("a boolean needs all laminas or all solids")
    return dims.pop()


def _slack(bodies: tuple[Body, ...]) -> float:
    """How much overlap is round-off, not overlap: 1e-9 of the parts' size.

    Not the faceting's own error: a true overlap smaller than that (a lens where two
    balls just meet) would be taken for none and the parts composed as if disjoint, a
    wrong answer reported exact. Facets inscribed in convex parts that only touch do
    not overlap; parts whose facets overlap at all go through the boolean, whose
    stated error covers the faceting."""
    return 1e-9 * sum(abs(b.mass_properties().measure) for b in bodies)


def _faceted_body(bodies: tuple[Body, ...], build, segments: int, what: str,
                  geometries: list | None = None, origin: np.ndarray | None = None) -> Body:
    """The boolean of ``bodies`` on their facets (:func:`.faceted.integrate_boolean`),
    once their densities agree."""
    from .faceted import integrate_boolean

    densities = leaf_densities(Assembly(bodies))
    if len(densities) > 1:
        raise GeometryError(
            f"the {what} mixes overlapping parts of different densities: carve one out of the "
            "other with a difference, or use an assembly"
        )
    density = densities.pop()
    if density == "field":
        raise DensityError(f"a density field cannot be carried through a {what} of overlapping "
                           "parts: combine the parts first, then give the combined body the field")
    return integrate_boolean(bodies, build, segments, what, density, geometries, origin)


def union(*bodies: Body, segments: int = DEFAULT_SEGMENTS) -> Body:
    """The union of bodies: exact when the parts do not overlap.

    Parameters
    ----------
    *bodies : Body
        All laminas or all solids.
    segments : int
        Circular segments per turn when the parts overlap and the union is
        computed on facets (then Richardson-extrapolated from ``segments`` and
        ``segments / 2``; the result is marked not exact).

    Returns
    -------
    Body
        A :class:`Composite` (exact) when no two parts overlap; a :class:`Faceted`
        when they all join into one overlapping group; else a :class:`Composite` of
        the parts that overlap nothing and one :class:`Faceted` per overlapping
        group. A single body is returned as it is. Only parts whose bounding boxes
        meet are ever faceted (:mod:`plumbob.bodies.overlaps`), and a boolean far
        from the origin is computed about a local origin.

    Raises
    ------
    GeometryError
        Laminas mixed with solids, or overlapping parts of different densities.
    DensityError
        Overlapping parts with a density field.

    Examples
    --------
    >>> from plumbob.bodies.primitives import box, disc
    >>> two = union(box(1, 1, 1), box(1, 1, 1).translated([2, 0, 0]))
    >>> type(two).__name__, two.mass_properties().exact, two.mass_properties().measure
    ('Composite', True, 2.0)
    >>> lens = union(disc(1), disc(1).translated([1, 0]))
    >>> type(lens).__name__, lens.mass_properties().exact
    ('Faceted', False)
    >>> union(disc(1), box(1, 1, 1))
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: a boolean needs all laminas or all solids
    """
    dim = _same_dim(bodies, segments)
    if len(bodies) == 1:
        return bodies[0]
    boxes = bounding_boxes(bodies)
    origin = local_origin(boxes)
    shapes = Facets(bodies, segments, origin)
    overlapping = [
        (i, j) for i, j in candidate_pairs(boxes)
        if measure(overlap(shapes[i], shapes[j], dim), dim)
        > _slack((bodies[i], bodies[j]))
    ]
    if not overlapping:
        return Composite(bodies, (1.0,) * len(bodies))
    joined = manifold_union if dim == 3 else shapely_union
    parts = [
        bodies[group[0]] if len(group) == 1 else _faceted_body(
            tuple(bodies[k] for k in group), joined, segments, "union",
            [shapes[k] for k in group], origin)
        for group in connected_groups(len(bodies), overlapping)
    ]
    # parts that overlap nothing stay exact beside the faceted unions of those that do
    return parts[0] if len(parts) == 1 else Composite(tuple(parts), (1.0,) * len(parts))


def leaf_densities(body: Body) -> set:
    """The densities of a body's parts (see :meth:`Body.densities`): kg/m³, areal kg/m² for
    laminas, None where not given, "field" for a density field.

    Parameters
    ----------
    body : Body

    Returns
    -------
    set

    Examples
    --------
    >>> from plumbob.bodies.primitives import box, sphere
    >>> sorted(leaf_densities(Assembly((box(1, 1, 1, density=2), sphere(1, density=5)))))
    [2.0, 5.0]
    >>> leaf_densities(box(1, 1, 1))
    {None}
    """
    return body.densities()


def as_assembly(body: Body) -> Body:
    """A composite of parts of several densities as an :class:`Assembly` of its parts
    (reported part by part); any other body as it is."""
    return Assembly(body.parts) if isinstance(body, Composite) and len(body.densities()) > 1 else body


def difference(body: Body, *holes: Body, segments: int = DEFAULT_SEGMENTS) -> Body:
    """``body`` with ``holes`` removed: exact when each hole lies inside ``body``
    (and the holes do not overlap each other); a hole wholly outside is ignored.

    A hole with no density of its own weighs what it is cut from.

    Parameters
    ----------
    body : Body
        What the holes are cut from.
    *holes : Body
        Of the same dimension as ``body``.
    segments : int
        Circular segments per turn when a hole crosses the boundary and the
        difference is computed on facets (see :func:`union`).

    Returns
    -------
    Body
        A :class:`Composite` (holes as negative parts) when exact, ``body``
        itself when no hole touches it, else a :class:`Faceted`.

    Examples
    --------
    >>> from plumbob.bodies.primitives import rectangle, disc
    >>> washer = difference(rectangle(4, 4, density=2.0), disc(1).translated([2, 2]))
    >>> props = washer.mass_properties()
    >>> props.exact, bool(np.isclose(props.mass, 2 * (16 - np.pi), rtol=1e-15))
    (True, True)
    >>> plate = rectangle(1, 1)
    >>> difference(plate, disc(0.1).translated([5, 5])) is plate   # a hole outside: ignored
    True
    """
    dim = _same_dim((body,) + holes, segments)
    parent = leaf_densities(body)
    if len(parent) == 1 and isinstance(density := next(iter(parent)), float):
        holes = tuple(
            h.with_default_density(density) if leaf_densities(h) == {None} else h for h in holes
        )
    boxes = bounding_boxes((body,) + holes)
    origin = local_origin(boxes)
    shapes = Facets((body,) + holes, segments, origin)
    kept: list[int] = []
    for k in range(1, len(holes) + 1):
        if not boxes_meet(boxes[0], boxes[k]):
            continue  # the hole's box misses the body: nothing to remove
        g = shapes[k]
        size = measure(g, dim)
        inside = measure(overlap(shapes[0], g, dim), dim)
        slack = _slack((holes[k - 1],))
        if inside <= slack:
            continue  # disjoint: nothing to remove
        if size - inside > slack or any(
            boxes_meet(boxes[k], boxes[j]) and measure(overlap(g, shapes[j], dim), dim) > slack
            for j in kept
        ):
            return _faceted_difference(body, holes, segments, origin)
        kept.append(k)
    if not kept:
        return body
    return Composite((body,) + tuple(holes[k - 1] for k in kept), (1.0,) + (-1.0,) * len(kept))


def _faceted_difference(body: Body, holes: tuple[Body, ...], segments: int,
                        origin: np.ndarray | None) -> Body:
    def build(geoms):
        if body.dim == 2:
            import shapely

            return shapely.difference(geoms[0], shapely.union_all(geoms[1:]))
        return geoms[0] - manifold_union(geoms[1:])

    return _faceted_body((body,) + holes, build, segments, "difference", origin=origin)


def intersection(*bodies: Body, segments: int = DEFAULT_SEGMENTS) -> Body:
    """The common part of bodies: exact when one part lies inside all the others.

    Parameters
    ----------
    *bodies : Body
        All laminas or all solids.
    segments : int
        Circular segments per turn when computed on facets (see :func:`union`).

    Returns
    -------
    Body
        The innermost body itself when one lies inside all the others, else a
        :class:`Faceted`.

    Examples
    --------
    >>> from plumbob.bodies.primitives import disc
    >>> small = disc(1)
    >>> intersection(disc(2), small) is small
    True
    >>> intersection(disc(1), disc(1).translated([5, 0]))
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: the intersection is empty: the parts do not overlap
    """
    dim = _same_dim(bodies, segments)
    if len(bodies) == 1:
        return bodies[0]
    boxes = bounding_boxes(bodies)
    if len(candidate_pairs(boxes)) < len(bodies) * (len(bodies) - 1) // 2:
        raise GeometryError("the intersection is empty: the parts do not overlap")
    origin = local_origin(boxes)
    facets = Facets(bodies, segments, origin)
    geoms = [facets[i] for i in range(len(bodies))]
    for i, (b, g) in enumerate(zip(bodies, geoms)):
        slack = _slack((b,))
        if all(
            measure(g, dim) - measure(overlap(g, h, dim), dim) <= slack
            for j, h in enumerate(geoms)
            if j != i
        ):
            return b

    def build(gs):
        result = gs[0]
        for g in gs[1:]:
            result = overlap(result, g, dim)
        return result

    return _faceted_body(bodies, build, segments, "intersection", geoms, origin)
