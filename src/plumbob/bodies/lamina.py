"""Laminas: plane regions with an areal density, exact by Green's theorem."""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import partial
from typing import TYPE_CHECKING

import numpy as np

from ..arguments import placement
from ..errors import GeometryError
from ..massprops import MassProperties
from ..tolerances import contact_tolerance, sampling_tolerance
from .base import (
    Body,
    check_density,
    contact_sampling,
    density_words,
    lowest,
    measure_words,
)
from .cells import DensityCells
from .uniform import second_moments_to_inertia, uniform_mass_properties

if TYPE_CHECKING:
    from .region import Region

# The region, containment and tiling modules (and numpy.polynomial under them) load when
# a lamina is made or asked.

__all__ = ["Lamina", "lamina_mass_properties", "second_moments_to_inertia", "uniform_mass_properties"]


def lamina_mass_properties(region: Region) -> tuple[float, np.ndarray, np.ndarray]:
    """Area (m²), centre (2,) m and central second moments ``∫ r rᵀ dA`` (2, 2) m⁴."""
    origin = region.local_origin()
    m = region.moments(origin)
    if not m.m0 > 0:
        raise GeometryError(
            "the region has no area (zero, or its rings run clockwise): "
            "outer boundaries must run counter-clockwise, holes clockwise"
        )
    centre = m.m1 / m.m0
    central = m.m2 - m.m0 * np.outer(centre, centre)
    return m.m0, origin + centre, central


@dataclass(frozen=True, eq=False, repr=False)
class Lamina(Body):
    """A plane region with uniform areal density.

    region: the exact shape (lines, arcs, Béziers).
    density: kg/m³ when ``thickness`` is given, else kg/m² (areal); None = not given (1).
    thickness: m, or None for a lamina given by its areal density.
    exact, relative_error, note: for regions that came out of a faceted boolean.
    """

    region: Region
    density: float | None = None
    thickness: float | None = None
    name: str | None = None
    exact: bool = True
    relative_error: float = 0.0
    note: str | None = None

    kind = "lamina"
    dim = 2

    def __post_init__(self) -> None:
        from .region import Region

        if not isinstance(self.region, Region):
            raise GeometryError(f"a lamina needs a Region (see plumbob.primitives."
                                f"polygon_region), not {type(self.region).__name__}")
        object.__setattr__(self, "density", check_density(self.density))
        object.__setattr__(self, "thickness", check_density(self.thickness, "thickness"))

    @property
    def areal_density(self) -> float:
        """kg/m²: density × thickness, or the areal density itself."""
        rho = 1.0 if self.density is None else self.density
        return rho * self.thickness if self.thickness is not None else rho

    def mass_properties(self) -> MassProperties:
        area, centre, central = lamina_mass_properties(self.region)
        return uniform_mass_properties(
            2, area, centre, central, None if self.density is None else self.areal_density,
            exact=self.exact, relative_error=self.relative_error, note=self.note)

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        tol = sampling_tolerance(self.region.size, tolerance)
        return np.concatenate([r.flattened(tol) for r in self.region.rings])

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        from ..integrals.polygon import bulge_arc_geometry

        down = np.asarray(down, dtype=float)
        candidates = [self.hull_points(contact_sampling(tolerance, self.region.size))]
        for ring in self.region.rings:
            if ring.bulges is None:
                continue
            arcs = ring.bulges != 0
            p0, p1 = ring._ends(arcs)
            centre, radius, alpha, bisector = bulge_arc_geometry(p0, p1, ring.bulges[arcs])
            # The arc's point furthest along `down`, if the arc's sweep reaches it.
            cos_angle = bisector @ down
            inside = cos_angle >= np.cos(alpha)
            candidates.append(centre[inside] + radius[inside, None] * down)
        return lowest(np.concatenate(candidates), down, tolerance)

    def transformed(self, matrix: np.ndarray, offset: np.ndarray | None = None) -> Body:
        matrix, offset = placement(matrix, offset, 2, error=GeometryError)
        return replace(self, region=self.region.transformed(matrix, offset))

    def with_default_density(self, density: float) -> Body:
        return self if self.density is not None else replace(self, density=check_density(density))

    def to_geometry(self, segments: int = 128):
        return self.region.to_shapely(self.region.size * (1 - np.cos(np.pi / segments)), segments)

    def outline(self, tolerance: float, segments: int = 384) -> list[np.ndarray]:
        return [np.vstack((v, v[:1])) for v in (r.flattened(tolerance) for r in self.region.rings)]

    def exact_region(self) -> Region:
        return self.region

    def with_material(self, density: float | None, thickness: float | None = None) -> Body:
        return replace(self, density=density, thickness=thickness)

    # ------------------------------------------------------------ questions
    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        from .containment import region_contains

        return region_contains(self.region, points, self._contains_tolerance(tolerance))

    def _contains_tolerance(self, tolerance: float | None) -> float:
        return contact_tolerance(self.region.size, tolerance)

    @property
    def is_polytope(self) -> bool:
        return not self.region.is_curved

    def density_cells(self) -> DensityCells:
        from .tiling import region_cells

        origin = self.region.local_origin()
        return DensityCells(origin, self.region.size, partial(region_cells, self.region, origin),
                            self.hull_points)

    def densities(self) -> set:
        return {None if self.density is None else self.areal_density}

    def _describe(self) -> str:
        thick = "" if self.thickness is None else f", thickness {self.thickness:.4g} m"
        unit = "kg/m³" if self.thickness is not None else "kg/m²"
        return f"{self.region.describe()}, {measure_words(self)}{thick}{density_words(self.density, unit)}"
