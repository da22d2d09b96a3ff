"""Particle systems: point masses, the seed's starting point (equation 15)."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..arguments import floats, placement
from ..errors import DensityError, GeometryError
from ..massprops import MassProperties
from .base import Body
from .cells import DensityCells

__all__ = ["ParticleSystem"]


@dataclass(frozen=True, eq=False, repr=False)
class ParticleSystem(Body):
    """Point masses with positions and (optionally) velocities.

    masses: (n,) kg, each > 0.
    positions: (n, d) m, d = 2 or 3.
    velocities: (n, d) m/s, or None for a system at rest.
    names: optional labels, one per particle.
    name: optional label of the whole system.
    """

    masses: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray | None = None
    names: tuple[str, ...] | None = None
    name: str | None = None

    kind = "particles"

    def __post_init__(self) -> None:
        masses = floats(self.masses, "masses", error=GeometryError).reshape(-1)
        positions = floats(self.positions, "positions", error=GeometryError)
        if len(masses) == 0:
            raise GeometryError("a particle system needs at least one particle")
        if positions.ndim == 1 and positions.size % len(masses) == 0:
            positions = positions.reshape(len(masses), -1)
        if positions.ndim != 2 or positions.shape[0] != len(masses) or \
                positions.shape[1] not in (2, 3):
            raise GeometryError("each particle needs a position with 2 or 3 coordinates")
        if not np.all(np.isfinite(masses)) or np.any(masses <= 0):
            raise GeometryError("every particle needs a positive, finite mass")
        if not np.all(np.isfinite(positions)):
            raise GeometryError("a particle position is not a finite number")
        velocities = self.velocities
        if velocities is not None:
            velocities = floats(velocities, "velocities", error=GeometryError)
            if velocities.shape != positions.shape and velocities.size == positions.size == \
                    positions.shape[1] and velocities.ndim == 1:  # one particle, one vector
                velocities = velocities.reshape(positions.shape)
            if velocities.shape != positions.shape:
                raise GeometryError(f"velocities must be an array of shape {positions.shape} "
                                    f"like the positions, not {velocities.shape}")
            if not np.all(np.isfinite(velocities)):
                raise GeometryError("a particle velocity is not a finite number")
            velocities.setflags(write=False)
        if self.names is not None and len(self.names) != len(masses):
            raise GeometryError("give one name per particle")
        masses.setflags(write=False)
        positions.setflags(write=False)
        object.__setattr__(self, "masses", masses)
        object.__setattr__(self, "positions", positions)
        object.__setattr__(self, "velocities", velocities)

    @property
    def dim(self) -> int:
        return self.positions.shape[1]

    @property
    def total_mass(self) -> float:
        """kg."""
        return float(self.masses.sum())

    @property
    def center_of_mass(self) -> np.ndarray:
        """(d,) m: Σ mᵢ rᵢ / M, summed about the first particle."""
        anchor = self.positions[0]
        return anchor + self.masses @ (self.positions - anchor) / self.total_mass

    # -------------------------------------------------------------- motion
    @property
    def _velocities(self) -> np.ndarray:
        """(n, d) m/s; zeros for a system given without velocities."""
        if self.velocities is None:
            return np.zeros_like(self.positions)
        return self.velocities

    @property
    def velocity_of_center(self) -> np.ndarray:
        """(d,) m/s: the velocity of the centre of mass, Σ mᵢ vᵢ / M.

        >>> ParticleSystem([1.0, 3.0], [[0, 0], [1, 0]], [[4, 0], [0, 0]]).velocity_of_center
        array([1., 0.])
        """
        return self.momentum / self.total_mass

    @property
    def momentum(self) -> np.ndarray:
        """(d,) kg·m/s: the total linear momentum P = Σ mᵢ vᵢ = M v_G (seed eq. 25).

        >>> ParticleSystem([5e4, 3e4], [[0, 0], [10, 0]], [[2, 0], [0, 0]]).momentum
        array([100000.,      0.])
        >>> ParticleSystem([1.0], [[0, 0]]).momentum   # no velocities: at rest
        array([0., 0.])
        """
        return self.masses @ self._velocities

    @property
    def kinetic_energy(self) -> float:
        """J: ½ Σ mᵢ |vᵢ|².

        >>> ParticleSystem([3.0, 3.0], [[0, 0], [1, 0]], [[2, 0], [0, 0]]).kinetic_energy
        6.0
        """
        v = self._velocities
        return 0.5 * float(self.masses @ np.einsum("ki,ki->k", v, v))

    @property
    def kinetic_energy_relative(self) -> float:
        """J: ½ Σ mᵢ |vᵢ − v_G|², the kinetic energy relative to the centre of mass.

        The total is ``½ M |v_G|² + kinetic_energy_relative`` (König's theorem);
        it is what an instantaneous internal impact can take away.

        >>> ParticleSystem([3.0, 3.0], [[0, 0], [1, 0]], [[2, 0], [0, 0]]).kinetic_energy_relative
        3.0
        """
        w = self._velocities - self.velocity_of_center
        return 0.5 * float(self.masses @ np.einsum("ki,ki->k", w, w))

    def mass_properties(self) -> MassProperties:
        """Mass, centre of mass and inertia tensor (about the centre) of the particles."""
        com = self.center_of_mass
        offsets = self.positions - com
        if self.dim == 2:
            offsets = np.pad(offsets, ((0, 0), (0, 1)))
        inertia = (self.masses @ np.einsum("ki,ki->k", offsets, offsets)) * np.eye(3) - np.einsum(
            "k,ki,kj->ij", self.masses, offsets, offsets
        )
        return MassProperties(self.dim, self.total_mass, 0.0, com, inertia, parts=len(self.masses))

    def transformed(self, matrix: np.ndarray, offset: np.ndarray | None = None) -> Body:
        """The particles turned or mirrored by ``matrix`` (d × d) and moved by ``offset``;
        velocities turn with them."""
        matrix, offset = placement(matrix, offset, self.dim, error=GeometryError)
        velocities = None if self.velocities is None else self.velocities @ matrix.T
        return replace(self, positions=self.positions @ matrix.T + offset, velocities=velocities)

    def hull_points(self, tolerance: float | None = None) -> np.ndarray:
        """(n, d) points whose convex hull is the system's."""
        return self.positions

    # ------------------------------------------------------------ questions
    def contains(self, points: np.ndarray, tolerance: float | None = None) -> np.ndarray:
        """Which points coincide with a particle, within ``tolerance`` (m; default 1e-6 of
        the system's size): the particles are all the system occupies.

        >>> ParticleSystem([1.0, 2.0], [[0, 0], [1, 0]]).contains([[1, 0], [0.5, 0]]).tolist()
        [True, False]
        """
        pts = points
        tol = self._contains_tolerance(tolerance)
        inside = np.zeros(len(pts), dtype=bool)
        step = max(1, (1 << 16) // len(pts))  # particles per pass
        for start in range(0, len(self.positions), step):
            gap = pts[:, None, :] - self.positions[None, start:start + step]
            inside |= (np.einsum("mki,mki->mk", gap, gap) <= tol * tol).any(axis=1)
        return inside

    @property
    def is_polytope(self) -> bool:
        return True

    def density_cells(self) -> DensityCells:
        raise DensityError("particles have their own masses: a density field needs a lamina or a solid")

    def densities(self) -> set:
        return set()

    def _describe(self) -> str:
        n = len(self.masses)
        moving = "" if self.velocities is None or not self.velocities.any() else ", moving"
        return (f"{n} particle{'s' if n > 1 else ''} in {self.dim}D, "
                f"mass {self.total_mass:.4g} kg{moving}")
