"""Sizes of a body besides its mass properties: surface area and bounding boxes.

What a CAD panel or trimesh shows next to the mass: the area of a solid's boundary,
its axis-aligned bounding box and its smallest oriented one. Each result says
whether it is exact (a polytope, a mesh) or how far a faceting of curved faces can
be off.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..errors import GeometryError
from ..results import Key, Result, pick
from ..tolerances import CONTACT
from .base import Body

__all__ = ["MASS_KEYS", "SurfaceArea", "BoundingBox", "surface_area", "bounding_box", "oriented_bounding_box",
           "size_keys", "has_surface", "FACET_SEGMENTS"]

#: chords a turn for curved faces when measuring their area (a relative error under 1.6e-4)
FACET_SEGMENTS = 256


#: the keys of ``plumbob mass --json``, in order (``MassReport.KEYS``; docs/cli.md's table
#: and the batch table's mass columns are made from them)
MASS_KEYS = (
    Key("path", "", "the file read", "when read from a file", type="str"),
    Key("name", "", "the body's name", "when it has one", type="str"),
    Key("kind", "", "`lamina`, `solid`, `particles` or `assembly`", type="str"),
    Key("mass", "kg", "the mass", attr="props.mass", type="float"),
    Key("volume", "m³", "the volume", "solids and assemblies", type="float"),
    Key("area", "m²", "the area", "laminas", type="float"),
    Key("center_of_mass", "m", "the centre of mass (2 or 3 numbers)", attr="props.center_of_mass",
        type="xyz"),
    Key("inertia", "kg·m²", "the inertia tensor about the centre of mass (3×3)",
        attr="props.inertia", type="xyz×xyz"),
    Key("principal_moments", "kg·m²", "the principal moments, ascending",
        attr="props.principal_moments", type="123"),
    Key("principal_axes", "", "the principal axes: rows, unit vectors, right-handed",
        attr="props.principal_axes", type="123×xyz"),
    Key("exact", "", "false when curves were faceted by a boolean or a density field was "
                     "integrated numerically", attr="props.exact", type="bool"),
    Key("relative_error", "", "when not exact, the error's estimate (a bound for "
                              "booleans); when exact, a bound on the round-off of a boolean "
                              "of polytopes, else 0", attr="props.relative_error",
        type="float"),
    Key("parts", "", "how many parts", attr="props.parts", type="int"),
    Key("notes", "", "what was assumed or approximated (e.g. the assumed density of 1)",
        "when there are any", attr="props.notes", type="strings"),
    Key("part_properties", "", "each part of an assembly: `name`, `kind`, `mass`, "
                               "`volume`/`area`, `center_of_mass`, `exact`", "assemblies"),
    Key("radii_of_gyration", "m", "about the principal axes, sqrt(moment / mass)",
        attr="sizes.radii_of_gyration", type="123"),
    Key("inertia_about", "m, kg·m²", "`point` and `inertia`, the 3×3 tensor about it",
        "with `--about X,Y,Z`"),
    Key("inertia_in_frame", "m, kg·m²", "`axes` (rows, unit vectors in the body's "
                                        "coordinates), `point` (the centre of mass or the "
                                        "`--about` point) and `inertia`, the 3×3 tensor about "
                                        "it in that frame, R I Rᵀ",
        "with `--frame principal` or `--frame x=X,Y,Z y=X,Y,Z`"),
    Key("bounding_box_lower", "m", "the bounding box's least corner: the farthest points "
                                   "along −x, −y (, −z), exact for curved primitives too",
        "with `--sizes`", attr="sizes.bounding_box_lower"),
    Key("bounding_box_upper", "m", "its greatest corner, along +x, +y (, +z)",
        "with `--sizes`", attr="sizes.bounding_box_upper"),
    Key("surface_area", "m²", "the boundary's area (an assembly's: the sum of its parts')",
        "solids, with `--sizes`", attr="sizes.surface_area"),
    Key("surface_area_exact", "", "false where curved faces were faceted",
        "solids, with `--sizes`", attr="sizes.surface_area_exact"),
    Key("surface_area_relative_error", "", "a bound for curved faces (faceted at 256 "
                                           "chords a turn)", "solids, with `--sizes`",
        attr="sizes.surface_area_relative_error"),
    Key("notices", "", "what the reader assumed or repaired", "when there are any",
        attr="reading.notices", type="strings"),
)


@dataclass(frozen=True, repr=False)
class SurfaceArea(Result):
    """The area of a solid's boundary.

    area: m². exact: the boundary is planar faces (a polytope or a mesh), so the area
    is exact up to round-off. relative_error: otherwise, a bound on the relative error
    of faceting curved faces into ``segments`` chords a turn.
    """

    area: float
    exact: bool
    relative_error: float
    segments: int

    def _repr_items(self) -> list[tuple[str, Any]]:
        return [("area", self.area), ("exact", self.exact)]

    #: ``surface_area`` (m²), ``surface_area_exact`` and ``surface_area_relative_error``:
    #: the mass report's keys (``MASS_KEYS``), read from this result's fields
    KEYS = tuple(replace(k, when="", attr=attr) for k, attr in zip(
        pick(MASS_KEYS, ("surface_area", "surface_area_exact", "surface_area_relative_error")),
        ("area", "exact", "relative_error"), strict=True))


@dataclass(frozen=True, repr=False)
class BoundingBox(Result):
    """A box around the body: axis-aligned, or oriented (the smallest volume found).

    lower, upper: corners in the box's own frame, m. axes: (dim, dim) rows, the box's
    unit edge directions in the body's frame (the identity for the axis-aligned box).
    center: the box's centre in the body's frame, m. extents: ``upper - lower``, m.
    """

    lower: np.ndarray
    upper: np.ndarray
    axes: np.ndarray
    center: np.ndarray

    @property
    def extents(self) -> np.ndarray:
        """Edge lengths along ``axes``, m."""
        return self.upper - self.lower

    @property
    def volume(self) -> float:
        """The box's volume (area for a lamina), m³ (m²)."""
        return float(np.prod(self.extents))

    def _repr_items(self) -> list[tuple[str, Any]]:
        return [("extents", self.extents), ("center", self.center)]

    KEYS = (
        Key("extents", "m", "edge lengths along `axes`"),
        Key("center", "m", "the box's centre, body frame"),
        Key("axes", "", "the box's unit edge directions, rows, body frame"),
        Key("lower", "m", "its least corner, in the box's frame"),
        Key("upper", "m", "its greatest corner, in the box's frame"),
    )


def surface_area(body: Body, segments: int = FACET_SEGMENTS) -> SurfaceArea:
    """The area of a solid's boundary (an assembly: every part's boundary, added up,
    faces where parts touch counted for each).

    Parameters
    ----------
    body : Body
        A solid or an assembly of solids.
    segments : int
        Chords a turn for curved faces. A chord of a turn of n cuts the arc it spans
        short by a factor sin(π/n)/(π/n) and a curved face's area by at most
        2·(1 − cos(π/n)) relative (the bound stated; checked against spheres,
        cylinders, cones and tori in the tests).

    Returns
    -------
    SurfaceArea

    Examples
    --------
    >>> from plumbob.bodies.primitives import box, sphere
    >>> surface_area(box(1, 2, 3))
    SurfaceArea(area=22, exact=True)
    >>> a = surface_area(sphere(1.0))
    >>> a.exact, abs(a.area / (4 * np.pi) - 1) <= a.relative_error
    (False, True)
    """
    if body.dim != 3 or body.kind == "particles":
        raise GeometryError(f"a {body.dim}D {body.kind} has no surface area" +
                            (": its area is its mass properties' area" if body.dim == 2 else ""))
    parts = body.assembly_parts()
    if parts:  # each part's own boundary (faces where parts touch count for both)
        areas = [surface_area(part, segments) for part in parts]
        return SurfaceArea(float(sum(a.area for a in areas)), all(a.exact for a in areas),
                           max(a.relative_error for a in areas), segments)
    surface = body.surface(segments)
    tri = surface.triangles
    origin = tri.reshape(-1, 3).mean(axis=0) if len(tri) else np.zeros(3)
    a, b, c = (tri[:, k] - origin for k in range(3))  # local origin: no far-away cancellation
    area = float(0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum())
    exact = bool(surface.exact or body.is_polytope)
    error = 0.0 if exact else float(2 * (1 - np.cos(np.pi / segments)))
    return SurfaceArea(area, exact, error, segments)


def bounding_box(body: Body) -> BoundingBox:
    """The axis-aligned bounding box: the body's farthest points along ±x, ±y (, ±z),
    its support points, which curved primitives give exactly (a sphere's poles, a
    cylinder's rim), not a sampling of the surface.

    >>> from plumbob.bodies.primitives import box, sphere
    >>> bounding_box(box(1, 2, 3, centered=True)).extents.tolist()
    [1.0, 2.0, 3.0]
    >>> bounding_box(sphere(0.05)).upper.tolist()
    [0.05, 0.05, 0.05]
    """
    axes = np.eye(body.dim)
    tolerance = CONTACT * body.size
    upper = np.array([(body.support_points(e, tolerance) @ e).max() for e in axes])
    lower = np.array([(body.support_points(-e, tolerance) @ e).min() for e in axes])
    return BoundingBox(lower, upper, axes, (lower + upper) / 2)


def oriented_bounding_box(body: Body) -> BoundingBox:
    """The smallest oriented bounding box trimesh's ``oriented_bounds`` finds around the
    body's hull points (minimum volume over the hull's face directions).

    >>> from plumbob.bodies.primitives import box
    >>> from scipy.spatial.transform import Rotation
    >>> turned = box(1, 2, 3).transformed(Rotation.from_euler("z", 30, degrees=True).as_matrix())
    >>> sorted(np.round(oriented_bounding_box(turned).extents, 9).tolist())
    [1.0, 2.0, 3.0]
    """
    from trimesh.bounds import oriented_bounds

    points = np.asarray(body.hull_points(), dtype=float)
    dim = points.shape[1]
    origin = points.mean(axis=0)  # local origin: far-away bodies keep their digits
    to_box, extents = oriented_bounds(points - origin)
    rotation = np.asarray(to_box)[:dim, :dim]
    shift = np.asarray(to_box)[:dim, dim]
    center = origin - rotation.T @ shift
    half = np.asarray(extents, dtype=float) / 2
    return BoundingBox(-half, half, rotation, center)


def has_surface(body: Body) -> bool:
    """Whether ``body`` has a closed boundary to measure: a solid, or an assembly of
    solids (not a lamina, not particles)."""
    parts = body.assembly_parts() or (body,)
    return all(p.dim == 3 and p.kind != "particles" for p in parts)


def size_keys(body: Body, props, sizes: bool = False) -> dict[str, Any]:
    """The size keys of ``plumbob mass --json`` (and of a batch row): the radii of
    gyration (m, about the principal axes, sqrt(moment / mass)); with ``sizes``
    (``--sizes``: it facets curved faces and asks every part of an assembly, so it costs
    more than the mass properties) the bounding box's ``bounding_box_lower`` and
    ``bounding_box_upper`` (m), and for solids ``surface_area`` (m²),
    ``surface_area_exact`` and ``surface_area_relative_error``.

    >>> from plumbob.bodies.primitives import box
    >>> cube = box(1, 1, 1, density=6.0)
    >>> sorted(size_keys(cube, cube.mass_properties()))
    ['radii_of_gyration']
    >>> keys = size_keys(cube, cube.mass_properties(), sizes=True)
    >>> keys["surface_area"], keys["bounding_box_upper"].tolist()
    (6.0, [1.0, 1.0, 1.0])
    >>> bool(np.allclose(keys["radii_of_gyration"], np.sqrt(1 / 6)))
    True
    """
    out: dict[str, Any] = {
        "radii_of_gyration": np.sqrt(np.maximum(props.principal_moments, 0.0) / props.mass)}
    if sizes:
        box = bounding_box(body)
        out.update(bounding_box_lower=box.lower, bounding_box_upper=box.upper)
        if has_surface(body):
            out.update(surface_area(body).as_dict())
    return out
