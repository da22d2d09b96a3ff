"""Solids swept from a profile: prisms (extrusions) and solids of revolution.

Both are exact from the exact area moments of their profile (Pappus–Guldin, extended
to second moments); with the closed mesh of :mod:`plumbob.bodies.solid` they are the
three generators every closed-form primitive in :mod:`plumbob.bodies.primitives` is
one of. Kept apart from the mesh solid, so reading a mesh never defines them.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import partial
from typing import TYPE_CHECKING

import numpy as np

from ..errors import GeometryError
from ..massprops import MassProperties
from ..tolerances import contact_tolerance, sampling_tolerance
from .base import check_density, contact_sampling, lowest
from .cells import DensityCells
from .solid import _UniformSolid

if TYPE_CHECKING:
    from .region import Region

__all__ = ["Extrusion", "Revolution"]


def _circle_steps(radius: float, tolerance: float) -> int:
    """Points per turn so that chords stay within ``tolerance`` of a circle."""
    if radius <= tolerance:
        return 4
    # the half-angle of a chord whose sagitta is the tolerance, arccos(1 - t/r), written
    # 2 arcsin(sqrt(t/2r)) so that a tolerance below round-off of r (1e-300) stays > 0
    half_angle = 2.0 * np.arcsin(np.sqrt(tolerance / (2.0 * radius)))
    return int(min(4096, max(8, np.ceil(np.pi / half_angle))))


def _cross_section(region: Region, segments: int):
    import manifold3d

    tol = region.size * (1 - np.cos(np.pi / segments))
    rings = [r.flattened(tol, segments) for r in region.rings]
    return manifold3d.CrossSection(rings, manifold3d.FillRule.Positive)


@dataclass(frozen=True, eq=False, repr=False)
class Extrusion(_UniformSolid):
    """A prism: ``profile`` (in the xy-plane) swept from z = 0 to z = ``height`` (m)."""

    profile: Region
    height: float
    density: float | None = None
    name: str | None = None

    def __post_init__(self) -> None:
        if not (np.isfinite(self.height) and self.height > 0):
            raise GeometryError(f"an extrusion needs a positive height, not {self.height}")
        object.__setattr__(self, "density", check_density(self.density))

    def mass_properties(self) -> MassProperties:
        from .lamina import lamina_mass_properties

        area, centre2, central2 = lamina_mass_properties(self.profile)
        h = self.height
        central = np.zeros((3, 3))
        central[:2, :2] = h * central2
        central[2, 2] = area * h**3 / 12
        return self._finish(area * h, np.append(centre2, h / 2), central)

    def _profile_points(self, tolerance: float | None) -> np.ndarray:
        from .lamina import Lamina

        return Lamina(self.profile).hull_points(tolerance)

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        pts = self._profile_points(tolerance)
        return np.concatenate(
            (
                np.pad(pts, ((0, 0), (0, 1))),
                np.pad(pts, ((0, 0), (0, 1)), constant_values=self.height),
            )
        )

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        from .lamina import Lamina

        down = np.asarray(down, dtype=float)
        flat = down[:2]
        size = self.profile.size
        # Down along the axis: a whole end face touches, sampled finely; otherwise
        # coarse samples plus the exact extreme points (see contact_sampling).
        face_down = np.linalg.norm(flat) * size <= tolerance
        pts = self._profile_points(tolerance / 4 if face_down else contact_sampling(tolerance, size))
        if np.linalg.norm(flat) > 0:
            exact = Lamina(self.profile).support_points(flat / np.linalg.norm(flat), tolerance)
            pts = np.concatenate((pts, exact))
        levels = [np.pad(pts, ((0, 0), (0, 1)), constant_values=z) for z in (0.0, self.height)]
        return lowest(np.concatenate(levels), down, tolerance)

    def to_geometry(self, segments: int = 128):
        import manifold3d

        return manifold3d.Manifold.extrude(_cross_section(self.profile, segments), self.height)

    # ------------------------------------------------------------ questions
    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        from .containment import region_contains

        pts = points
        tol = self._contains_tolerance(tolerance)
        z = pts[:, 2]
        return region_contains(self.profile, pts, tol) & (z >= -tol) & (z <= self.height + tol)

    def _contains_tolerance(self, tolerance: float | None) -> float:
        return contact_tolerance(self.profile.size, tolerance)

    @property
    def is_polytope(self) -> bool:
        return not self.profile.is_curved

    def density_cells(self) -> DensityCells:
        from .tiling import prism_cells

        o2 = self.profile.local_origin()
        return DensityCells(np.append(o2, 0.0), float(np.hypot(self.profile.size, self.height)),
                            partial(prism_cells, self.profile, self.height, o2), self.hull_points)

    def _shape_words(self) -> str:
        return f"prism of {self.profile.describe()}, height {self.height:.4g} m"


@dataclass(frozen=True, eq=False, repr=False)
class Revolution(_UniformSolid):
    """The solid swept by ``profile`` — a region in the (r, z) half-plane r ≥ 0,
    given as (x, y) = (r, z) — turning a full circle about the z-axis.

    Exact from the profile's area moments up to degree 3:
    ``V = 2π∫r dA``, ``∫z dV = 2π∫r z dA``, ``∫z² dV = 2π∫r z² dA``,
    ``∫x² dV = ∫y² dV = π∫r³ dA``.
    """

    profile: Region
    density: float | None = None
    name: str | None = None

    def __post_init__(self) -> None:
        if self.profile.bounds[0, 0] < -1e-12 * self.profile.size:
            raise GeometryError("a profile to revolve must lie where x ≥ 0 (x is the radius)")
        object.__setattr__(self, "density", check_density(self.density))

    def mass_properties(self) -> MassProperties:
        z0 = float(self.profile.local_origin()[1])
        m = self.profile.moments(np.array([0.0, z0]), degree=3)
        s_r = m.m1[0]
        if not s_r > 0:
            raise GeometryError("the profile has no area to revolve (or its rings run clockwise)")
        volume = 2 * np.pi * s_r
        zc = m.m2[0, 1] / s_r  # relative to z0
        czz = 2 * np.pi * m.m3[0, 1, 1] - volume * zc * zc
        cxx = np.pi * m.m3[0, 0, 0]
        central = np.diag([cxx, cxx, czz])
        return self._finish(volume, np.array([0.0, 0.0, z0 + zc]), central)

    def _rings(self, tolerance: float | None) -> tuple[np.ndarray, int]:
        from .lamina import Lamina

        # Half the tolerance each: the profile's chords fall short of the profile by up
        # to its share, and the rings' chords short of the swept profile by up to theirs,
        # and the two shortfalls add up.
        tol = sampling_tolerance(self.profile.size, tolerance) / 2
        pts = Lamina(self.profile).hull_points(tol)
        return pts, _circle_steps(float(pts[:, 0].max()), tol)

    @staticmethod
    def _sweep(pts: np.ndarray, angles: np.ndarray) -> np.ndarray:
        c, s = np.cos(angles), np.sin(angles)
        r, z = pts[:, 0:1], pts[:, 1:2]
        return np.stack(
            (r * c, r * s, np.broadcast_to(z, (len(pts), len(angles)))), axis=-1
        ).reshape(-1, 3)

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        pts, steps = self._rings(tolerance)
        return self._sweep(pts, 2 * np.pi * np.arange(steps) / steps)

    def support_points(self, down: np.ndarray, tolerance: float) -> np.ndarray:
        from .lamina import Lamina

        down = np.asarray(down, dtype=float)
        radial = np.hypot(down[0], down[1])
        size = self.profile.size
        profile = Lamina(self.profile)
        direction = np.array([radial, down[2]])
        # The profile's own lowest points in the half-plane facing down: exact.
        exact = profile.support_points(direction / np.linalg.norm(direction), tolerance)
        coarse = np.concatenate((profile.hull_points(contact_sampling(tolerance, size)), exact))
        on_axis = coarse[:, 0] <= 1e-12 * size
        axis_points = np.stack((0 * coarse[on_axis, 1], 0 * coarse[on_axis, 1], coarse[on_axis, 1]), axis=1)
        if radial * size <= tolerance:
            # Down along the axis: whole rings may touch (a cylinder's base rim): sweep
            # finely in angle; the profile itself stays coarse but for its exact points.
            steps = _circle_steps(float(coarse[:, 0].max()), tolerance / 4)
            swept = self._sweep(coarse[~on_axis], 2 * np.pi * np.arange(steps) / steps)
            return lowest(np.concatenate((swept, axis_points)), down, tolerance)
        # Otherwise every lowest point lies in the half-plane facing down.
        psi = np.arctan2(down[1], down[0])
        candidates = (self._sweep(coarse[~on_axis], np.array([psi])), axis_points)
        return lowest(np.concatenate(candidates), down, tolerance)

    def to_geometry(self, segments: int = 128):
        import manifold3d

        return manifold3d.Manifold.revolve(_cross_section(self.profile, segments), segments)

    # ------------------------------------------------------------ questions
    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        from .containment import region_contains

        pts = points
        rz = np.stack((np.hypot(pts[:, 0], pts[:, 1]), pts[:, 2]), axis=1)
        return region_contains(self.profile, rz, self._contains_tolerance(tolerance))

    def _contains_tolerance(self, tolerance: float | None) -> float:
        return contact_tolerance(self.profile.size, tolerance)

    @property
    def is_polytope(self) -> bool:
        return False

    def density_cells(self) -> DensityCells:
        from .tiling import revolution_cells

        z0 = float(self.profile.local_origin()[1])
        return DensityCells(np.array([0.0, 0.0, z0]), 2 * self.profile.size,
                            partial(revolution_cells, self.profile, z0), self.hull_points)

    def _shape_words(self) -> str:
        return f"turned profile of {self.profile.describe()}"
