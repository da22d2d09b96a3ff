"""The geometry libraries' booleans as the bodies' booleans use them: unions and overlaps of
shapely geometries (laminas) and manifold3d ``Manifold`` s (solids), and their size."""

from __future__ import annotations

__all__ = ["manifold_union", "shapely_union", "measure", "overlap"]


def manifold_union(manifolds: list):
    import manifold3d

    if len(manifolds) == 1:
        return manifolds[0]
    return manifold3d.Manifold.batch_boolean(manifolds, manifold3d.OpType.Add)


def measure(geometry, dim: int) -> float:
    return float(geometry.area) if dim == 2 else float(geometry.volume())


def overlap(a, b, dim: int):
    if dim == 2:
        return a.intersection(b)
    return a ^ b


def shapely_union(geometries: list):
    import shapely

    return shapely.union_all(geometries)
