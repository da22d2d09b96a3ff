"""Primitives with closed forms, each built on an exact generator.

2D (laminas, exact regions of lines and arcs): rectangle, triangle, polygon,
regular polygon, disc, semicircle, sector, segment, annulus.
3D: box and pyramid (exact meshes), cylinder, cone, frustum, sphere,
hemisphere and torus (exact solids of revolution), prism (extrusion) of any
lamina, revolution of any lamina.

Frames: every primitive sits in a stated local frame; place it with
``body.transformed(matrix, offset)``. Axial solids have their axis along +z
with the base at z = 0; round laminas are centred at the origin.
"""

from .laminas import (
    annulus,
    circular_segment,
    disc,
    disc_region,
    polygon,
    polygon_region,
    rectangle,
    rectangle_region,
    regular_polygon,
    sector,
    sector_region,
    segment_region,
    semicircle,
    semicircle_region,
    triangle,
)
from .solids import (
    box,
    cone,
    cylinder,
    frustum,
    hemisphere,
    prism,
    pyramid,
    revolve,
    sphere,
    tetrahedron,
    torus,
)

__all__ = [
    "rectangle",
    "triangle",
    "polygon",
    "regular_polygon",
    "disc",
    "semicircle",
    "sector",
    "circular_segment",
    "annulus",
    "box",
    "pyramid",
    "tetrahedron",
    "cylinder",
    "cone",
    "frustum",
    "sphere",
    "hemisphere",
    "torus",
    "prism",
    "revolve",
    "rectangle_region",
    "polygon_region",
    "disc_region",
    "semicircle_region",
    "sector_region",
    "segment_region",
]
