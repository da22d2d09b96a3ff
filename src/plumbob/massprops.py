"""The mass-property algebra: the seed's "model each part as a particle at its centre".

A :class:`MassProperties` holds what every later question needs — mass, size,
centre of mass, inertia tensor about the centre of mass — and combines by the
seed's equation (15): parts add (``a + b``), holes subtract (``a - b``), and a
rigid motion moves the centre and turns the tensor.

Conventions
-----------
* SI units: kg, m, m² (area), m³ (volume), kg·m².
* ``inertia`` is the inertia *tensor* about the centre of mass:
  ``I_xx = ∫(y² + z²) dm`` on the diagonal and ``I_xy = −∫ x y dm`` off it.
* A lamina (``dim == 2``) lies in the plane ``z = 0``: its centre of mass has two
  coordinates, its tensor is still 3×3 with ``I_zz = I_xx + I_yy``.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from .errors import GeometryError

__all__ = ["MassProperties", "combine", "point_mass", "rotation_matrix"]


def _as_3d(vector: np.ndarray) -> np.ndarray:
    return np.pad(np.asarray(vector, dtype=float), (0, 3 - len(vector)))


def _parallel_axis(mass: float, offset: np.ndarray) -> np.ndarray:
    """Tensor of a point mass ``mass`` at ``offset`` (3,) about the origin."""
    return mass * (np.dot(offset, offset) * np.eye(3) - np.outer(offset, offset))


def rotation_matrix(axis: np.ndarray | list[float], angle: float) -> np.ndarray:
    """The 3×3 matrix turning by ``angle`` radians about ``axis`` (right-hand rule).

    >>> np.round(rotation_matrix([0, 0, 1], np.pi / 2) @ [1, 0, 0], 12)
    array([0., 1., 0.])
    """
    axis = np.asarray(axis, dtype=float)
    norm = np.linalg.norm(axis)
    if not np.isfinite(norm) or norm == 0:
        raise GeometryError("a rotation axis must be a non-zero finite vector")
    x, y, z = axis / norm
    c, s = np.cos(angle), np.sin(angle)
    # Quarter turns are exact: cos(π/2) is 6e-17 in floating point, not 0.
    c, s = (0.0 if abs(c) < 1e-15 else c), (0.0 if abs(s) < 1e-15 else s)
    k = np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
    return c * np.eye(3) + s * k + (1 - c) * np.outer([x, y, z], [x, y, z])


@dataclass(frozen=True, eq=False)
class MassProperties:
    """Mass properties of a lamina (``dim`` 2), a solid or a set of particles (``dim`` 3).

    Attributes
    ----------
    dim: 2 for a lamina in the plane z = 0, 3 otherwise (particles may have 2).
    mass: total mass, kg.
    measure: area (m², laminas) or volume (m³, solids); 0 for particles.
    center_of_mass: shape (dim,), m.
    inertia: shape (3, 3), kg·m², the inertia tensor about the centre of mass.
    exact: False when a curved shape was approximated by facets or a density
        field was integrated numerically.
    relative_error: an estimate of the relative error of the mass (and so of the
        other quantities) when not exact; 0 when exact.
    parts: how many parts were combined.
    notes: human-readable notes on how the numbers were obtained.
    """

    dim: int
    mass: float
    measure: float
    center_of_mass: np.ndarray
    inertia: np.ndarray
    exact: bool = True
    relative_error: float = 0.0
    parts: int = 1
    notes: tuple[str, ...] = field(default=())

    def __post_init__(self) -> None:
        com = np.array(self.center_of_mass, dtype=float).reshape(-1)
        inertia = np.array(self.inertia, dtype=float).reshape(3, 3)
        if com.shape != (self.dim,):
            raise ValueError(f"center_of_mass must have {self.dim} coordinates")
        com.setflags(write=False)
        inertia.setflags(write=False)
        object.__setattr__(self, "center_of_mass", com)
        object.__setattr__(self, "inertia", inertia)
        object.__setattr__(self, "mass", float(self.mass))
        object.__setattr__(self, "measure", float(self.measure))

    # ------------------------------------------------------------------ views
    @property
    def area(self) -> float:
        """Area in m² (laminas only; NaN for other bodies)."""
        return self.measure if self.dim == 2 else float("nan")

    @property
    def volume(self) -> float:
        """Volume in m³ (solids; 0 for particles, NaN for laminas)."""
        return self.measure if self.dim == 3 else float("nan")

    @property
    def density(self) -> float:
        """Mean density: kg/m³ for solids, kg/m² for laminas."""
        return self.mass / self.measure if self.measure else float("nan")

    @cached_property
    def _principal(self) -> tuple[np.ndarray, np.ndarray]:
        moments, axes = np.linalg.eigh(self.inertia)
        axes = axes.T.copy()
        # Deterministic signs: the first and last axes have their largest
        # component positive; the middle one completes a right-handed frame.
        for i in (0, 2):
            if axes[i, np.argmax(np.abs(axes[i]))] < 0:
                axes[i] *= -1
        axes[1] = np.cross(axes[2], axes[0])
        axes += 0.0  # no negative zeros
        moments.setflags(write=False)
        axes.setflags(write=False)
        return moments, axes

    @property
    def principal_moments(self) -> np.ndarray:
        """Principal moments of inertia, ascending, kg·m², shape (3,)."""
        return self._principal[0]

    @property
    def principal_axes(self) -> np.ndarray:
        """Principal axes as rows (unit vectors), matching ``principal_moments``, shape (3, 3)."""
        return self._principal[1]

    @property
    def center_of_mass_3d(self) -> np.ndarray:
        """Centre of mass with z = 0 appended for a lamina, shape (3,), m."""
        return _as_3d(self.center_of_mass)

    def inertia_about(self, point: np.ndarray | list[float]) -> np.ndarray:
        """Inertia tensor about ``point`` (parallel axes), kg·m², shape (3, 3).

        >>> disc = point_mass(2.0, [1.0, 0.0, 0.0])
        >>> float(disc.inertia_about([0, 0, 0])[1, 1])
        2.0
        """
        offset = self.center_of_mass_3d - _as_3d(np.asarray(point, dtype=float))
        return self.inertia + _parallel_axis(self.mass, offset)

    def moment_about_axis(
        self, point: np.ndarray | list[float], axis: np.ndarray | list[float]
    ) -> float:
        """Moment of inertia about the line through ``point`` along ``axis``, kg·m²."""
        axis = np.asarray(axis, dtype=float)
        axis = _as_3d(axis) / np.linalg.norm(axis)
        return float(axis @ self.inertia_about(point) @ axis)

    # ------------------------------------------------------------- algebra
    def __add__(self, other: MassProperties) -> MassProperties:
        return combine([self, other])

    def __sub__(self, other: MassProperties) -> MassProperties:
        """Remove ``other`` (a hole lying inside ``self``): a part of negative mass."""
        return combine([self, other], signs=[1.0, -1.0])

    def scaled(self, factor: float) -> MassProperties:
        """The same shape with every mass multiplied by ``factor`` (a density change)."""
        return replace(self, mass=self.mass * factor, inertia=self.inertia * factor)

    def with_density(self, density: float) -> MassProperties:
        """The same shape at a uniform ``density`` (kg/m³ or kg/m² for laminas)."""
        if self.measure == 0:
            raise GeometryError("a body of zero size has no density to set")
        return self.scaled(density * self.measure / self.mass)

    def translated(self, offset: np.ndarray | list[float]) -> MassProperties:
        """Moved by ``offset`` (dim,), m: the tensor about the centre is unchanged."""
        offset = np.asarray(offset, dtype=float)
        return replace(self, center_of_mass=self.center_of_mass + offset[: self.dim])

    def transformed(
        self, matrix: np.ndarray, offset: np.ndarray | list[float] | None = None
    ) -> MassProperties:
        """Turned (or mirrored) by the orthogonal ``matrix`` about the origin, then moved.

        ``matrix`` is (2, 2) for a lamina — it must keep the plane — or (3, 3).
        """
        matrix = np.asarray(matrix, dtype=float)
        n = matrix.shape[0]
        if matrix.shape != (n, n) or n not in (2, 3) or n < self.dim:
            raise GeometryError(f"a {self.dim}D body needs a {self.dim}×{self.dim} or 3×3 matrix")
        if not np.allclose(matrix @ matrix.T, np.eye(n), atol=1e-12):
            raise GeometryError("a rigid motion needs an orthogonal matrix")
        full = np.eye(3)
        full[:n, :n] = matrix
        if self.dim == 2 and n == 3 and not np.allclose(full[2, :2], 0, atol=1e-15):
            raise GeometryError("a lamina can only be turned within its plane; use to_3d() first")
        com = (full @ self.center_of_mass_3d)[: self.dim]
        result = replace(self, center_of_mass=com, inertia=full @ self.inertia @ full.T)
        return result if offset is None else result.translated(offset)

    def rotated(
        self, angle: float, axis: np.ndarray | list[float] = (0.0, 0.0, 1.0)
    ) -> MassProperties:
        """Turned by ``angle`` radians about ``axis`` through the origin (z for a lamina)."""
        return self.transformed(rotation_matrix(axis, angle))

    def mirrored(self, normal: np.ndarray | list[float]) -> MassProperties:
        """Reflected in the plane (line, for a lamina) through the origin with this normal."""
        normal = _as_3d(np.asarray(normal, dtype=float))
        normal = normal / np.linalg.norm(normal)
        return self.transformed(np.eye(3) - 2 * np.outer(normal, normal))

    def to_3d(self) -> MassProperties:
        """A lamina seen as a (zero-thickness) body in space: centre gains z = 0."""
        if self.dim == 3:
            return self
        return replace(self, dim=3, center_of_mass=self.center_of_mass_3d)



def point_mass(mass: float, position: np.ndarray | list[float]) -> MassProperties:
    """A particle: mass at a point, no size and no inertia about itself.

    >>> point_mass(3.0, [1, 2, 3]).center_of_mass
    array([1., 2., 3.])
    """
    position = np.asarray(position, dtype=float)
    return MassProperties(position.size, mass, 0.0, position, np.zeros((3, 3)))


def combine(parts: list[MassProperties], signs: list[float] | None = None) -> MassProperties:
    """Equation (15): the parts as particles at their centres, plus their own inertia.

    ``signs`` of −1 remove a part (a hole). The result's centre is the
    mass-weighted mean of the parts' centres; the inertia is summed about it by
    parallel axes, with offsets taken from the combined centre so nothing large
    is subtracted.

    >>> a = point_mass(1.0, [0.0, 0.0, 0.0]); b = point_mass(3.0, [4.0, 0.0, 0.0])
    >>> combine([a, b]).center_of_mass
    array([3., 0., 0.])
    """
    if not parts:
        raise GeometryError("nothing to combine: a body needs at least one part")
    signs = [1.0] * len(parts) if signs is None else [float(s) for s in signs]
    dims = {p.dim for p in parts}
    dim = max(dims)
    if len(dims) > 1:
        parts = [p.to_3d() for p in parts]
    masses = np.array([s * p.mass for s, p in zip(signs, parts)])
    measures = np.array([s * p.measure for s, p in zip(signs, parts)])
    total = masses.sum()
    scale = np.abs(masses).sum()
    if not total > 1e-12 * scale or not np.isfinite(total):
        raise GeometryError("the parts add up to no mass: a hole larger than its body?")
    centres = np.array([p.center_of_mass for p in parts])
    # Work relative to the heaviest part so that far-away coordinates cancel first.
    anchor = centres[np.argmax(np.abs(masses))]
    local = centres - anchor
    com_local = masses @ local / total
    offsets = local - com_local
    inertia = np.zeros((3, 3))
    for sign, part, mass, offset in zip(signs, parts, masses, offsets):
        inertia += sign * part.inertia + _parallel_axis(mass, _as_3d(offset))
    exact = all(p.exact for p in parts)
    error = float(sum(abs(m) * p.relative_error for m, p in zip(masses, parts)) / total)
    notes: tuple[str, ...] = ()
    for p in parts:
        notes += tuple(n for n in p.notes if n not in notes)
    return MassProperties(
        dim=dim,
        mass=total,
        measure=float(measures.sum()),
        center_of_mass=anchor + com_local,
        inertia=(inertia + inertia.T) / 2,
        exact=exact,
        relative_error=error,
        parts=int(sum(p.parts for p in parts)),
        notes=notes,
    )
