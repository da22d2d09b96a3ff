"""Constructive geometry: union, difference, intersection — exact where it can be.

The user writes the shape; plumbob picks the method:

* parts that do not overlap, or a removed part lying wholly inside what it is
  removed from, compose exactly by the mass-property algebra (a
  :class:`Composite`: the seed's parts-as-particles, holes as negative mass);
* parts that do overlap go through a boolean on faceted geometry — shapely in
  2D, manifold3d in 3D with an explicit circular-segment count — and the
  result is integrated exactly, marked not exact, with an error estimate from
  repeating the boolean at half the segment count (faceting error falls as
  1/n², so the estimate is a third of the change).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..errors import GeometryError
from ..massprops import MassProperties, combine
from .base import Body, lowest

__all__ = [
    "Composite",
    "Assembly",
    "union",
    "difference",
    "intersection",
    "leaf_densities",
    "DEFAULT_SEGMENTS",
]

DEFAULT_SEGMENTS = 256  # circular segments per full turn for faceted booleans


@dataclass(frozen=True, eq=False)
class Composite(Body):
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
        return combine([p.mass_properties() for p in self.parts], list(self.signs))

    def _added(self) -> list[Body]:
        return [p for p, s in zip(self.parts, self.signs) if s > 0]

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        return np.concatenate([p.hull_points(tolerance) for p in self._added()])

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        pts = np.concatenate([p.support_points(down, tolerance) for p in self._added()])
        return lowest(pts, np.asarray(down, dtype=float), tolerance)

    def with_default_density(self, density: float) -> Body:
        return replace(self, parts=tuple(p.with_default_density(density) for p in self.parts))

    def to_geometry(self, segments: int = 128):
        added = [p.to_geometry(segments) for p, s in zip(self.parts, self.signs) if s > 0]
        removed = [p.to_geometry(segments) for p, s in zip(self.parts, self.signs) if s < 0]
        if self.dim == 2:
            import shapely

            result = shapely.union_all(added)
            return shapely.difference(result, shapely.union_all(removed)) if removed else result
        result = _manifold_union(added)
        return result - _manifold_union(removed) if removed else result


@dataclass(frozen=True, eq=False)
class Assembly(Body):
    """Separate parts, each its own body and material, reported part by part.

    Unlike a :class:`Composite`, an assembly keeps its parts' identities: the
    report gives each part's mass and centre beside the combined properties.
    """

    parts: tuple[Body, ...]
    name: str | None = None

    kind = "assembly"

    def __post_init__(self) -> None:
        object.__setattr__(self, "parts", tuple(self.parts))
        if not self.parts:
            raise GeometryError("an assembly needs at least one part")

    @property
    def dim(self) -> int:  # type: ignore[override]
        return max(p.dim for p in self.parts)

    def part_properties(self) -> list[MassProperties]:
        return [p.mass_properties() for p in self.parts]

    def mass_properties(self) -> MassProperties:
        return combine(self.part_properties())

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

    def with_default_density(self, density: float) -> Body:
        return replace(self, parts=tuple(p.with_default_density(density) for p in self.parts))


# ------------------------------------------------------------------ booleans
def _manifold_union(manifolds: list):
    import manifold3d

    if len(manifolds) == 1:
        return manifolds[0]
    return manifold3d.Manifold.batch_boolean(manifolds, manifold3d.OpType.Add)


def _measure(geometry, dim: int) -> float:
    return float(geometry.area) if dim == 2 else float(geometry.volume())


def _overlap(a, b, dim: int):
    if dim == 2:
        return a.intersection(b)
    return a ^ b


def _same_dim(bodies: tuple[Body, ...]) -> int:
    dims = {b.dim for b in bodies}
    if len(dims) != 1:
        raise GeometryError("a boolean needs all laminas or all solids")
    return dims.pop()


def _slack(bodies: tuple[Body, ...], geometries: list, dim: int, segments: int) -> float:
    """What faceting alone may make of overlap: the gap between exact and faceted size."""
    exact = sum(abs(b.mass_properties().measure) for b in bodies)
    faceted = sum(_measure(g, dim) for g in geometries)
    return abs(exact - faceted) + 1e-9 * exact


def _faceted_body(bodies: tuple[Body, ...], build, segments: int, what: str) -> Body:
    """Integrate a faceted boolean of ``bodies`` and estimate its faceting error."""
    from .lamina import Lamina
    from .region import Region
    from .solid import MeshSolid

    densities = {getattr(b, "density", None) for b in bodies}
    if len(densities) > 1:
        raise GeometryError(
            f"the {what} mixes overlapping parts of different densities: carve one out of the "
            "other with a difference, or use an assembly"
        )
    density = densities.pop()
    dim = bodies[0].dim
    fine = build([b.to_geometry(segments) for b in bodies])
    coarse = build([b.to_geometry(max(8, segments // 2)) for b in bodies])
    fine_size, coarse_size = _measure(fine, dim), _measure(coarse, dim)
    if not fine_size > 0:
        raise GeometryError(f"the {what} is empty: the parts do not overlap")
    error = abs(fine_size - coarse_size) / 3 / fine_size
    note = (
        f"the {what} of overlapping parts was computed on facets "
        f"({segments} segments per turn); estimated relative error {error:.1e}"
    )
    if dim == 2:
        import shapely

        region = Region.from_shapely(shapely.make_valid(fine))
        return Lamina(region, density, exact=False, relative_error=error, note=note)
    mesh = fine.to_mesh()
    verts = np.asarray(mesh.vert_properties, dtype=float)[:, :3]
    tris = verts[np.asarray(mesh.tri_verts, dtype=np.int64)]
    return MeshSolid(tris, density, exact=False, relative_error=error, note=note)


def union(*bodies: Body, segments: int = DEFAULT_SEGMENTS) -> Body:
    """The union: exact when the parts do not overlap."""
    if len(bodies) == 1:
        return bodies[0]
    dim = _same_dim(bodies)
    geoms = [b.to_geometry(segments) for b in bodies]
    slack = _slack(bodies, geoms, dim, segments)
    overlap = sum(
        _measure(_overlap(geoms[i], geoms[j], dim), dim)
        for i in range(len(geoms))
        for j in range(i + 1, len(geoms))
    )
    if overlap <= slack:
        return Composite(bodies, (1.0,) * len(bodies))
    if dim == 2:
        import shapely

        return _faceted_body(bodies, shapely.union_all, segments, "union")
    return _faceted_body(bodies, _manifold_union, segments, "union")


def leaf_densities(body: Body) -> set:
    """The densities of a body's parts: kg/m³, areal kg/m² for laminas, None where not
    given, "field" for a density field."""
    from .lamina import Lamina

    parts = getattr(body, "parts", None)
    if parts is not None:
        return set().union(*(leaf_densities(p) for p in parts))
    inner = getattr(body, "body", body)
    if isinstance(inner, Lamina):
        return {None if inner.density is None else inner.areal_density}
    return {getattr(inner, "density", "field")}


def difference(body: Body, *holes: Body, segments: int = DEFAULT_SEGMENTS) -> Body:
    """``body`` with ``holes`` removed: exact when each hole lies inside ``body``
    (and the holes do not overlap each other); a hole wholly outside is ignored.

    A hole with no density of its own weighs what it is cut from.
    """
    dim = _same_dim((body,) + holes)
    parent = leaf_densities(body)
    if len(parent) == 1 and isinstance(density := next(iter(parent)), float):
        holes = tuple(
            h.with_default_density(density) if leaf_densities(h) == {None} else h for h in holes
        )
    outer = body.to_geometry(segments)
    kept: list[Body] = []
    for hole in holes:
        g = hole.to_geometry(segments)
        size = _measure(g, dim)
        inside = _measure(_overlap(outer, g, dim), dim)
        slack = _slack((hole,), [g], dim, segments)
        if inside <= slack:
            continue  # disjoint: nothing to remove
        if size - inside > slack or any(
            _measure(_overlap(g, k.to_geometry(segments), dim), dim) > slack for k in kept
        ):
            return _faceted_difference(body, holes, segments)
        kept.append(hole)
    if not kept:
        return body
    return Composite((body,) + tuple(kept), (1.0,) + (-1.0,) * len(kept))


def _faceted_difference(body: Body, holes: tuple[Body, ...], segments: int) -> Body:
    def build(geoms):
        if body.dim == 2:
            import shapely

            return shapely.difference(geoms[0], shapely.union_all(geoms[1:]))
        return geoms[0] - _manifold_union(geoms[1:])

    return _faceted_body((body,) + holes, build, segments, "difference")


def intersection(*bodies: Body, segments: int = DEFAULT_SEGMENTS) -> Body:
    """The common part: exact when one part lies inside all the others."""
    if len(bodies) == 1:
        return bodies[0]
    dim = _same_dim(bodies)
    geoms = [b.to_geometry(segments) for b in bodies]
    for i, (b, g) in enumerate(zip(bodies, geoms)):
        slack = _slack((b,), [g], dim, segments)
        if all(
            _measure(g, dim) - _measure(_overlap(g, h, dim), dim) <= slack
            for j, h in enumerate(geoms)
            if j != i
        ):
            return b

    def build(gs):
        result = gs[0]
        for g in gs[1:]:
            result = _overlap(result, g, dim)
        return result

    return _faceted_body(bodies, build, segments, "intersection")
