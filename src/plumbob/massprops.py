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
from typing import Any

import numpy as np

from .arguments import floats, instance, mass_fields, non_negative, positive, unit_vector, vector
from .errors import GeometryError
from .frames import frame_axes, frame_rows, rotation_matrix
from .results import Result, Source

__all__ = ["MassProperties", "combine", "point_mass", "rotation_matrix", "frame_axes"]


def _as_3d(vector: np.ndarray) -> np.ndarray:
    return np.pad(np.asarray(vector, dtype=float), (0, 3 - len(vector)))


def _parallel_axis(mass: float, offset: np.ndarray) -> np.ndarray:
    """Tensor of a point mass ``mass`` at ``offset`` (3,) about the origin."""
    return mass * (np.dot(offset, offset) * np.eye(3) - np.outer(offset, offset))



def size_key(props: MassProperties, kind: str | None = None) -> str | None:
    """``"area"``, ``"volume"`` or None (a particle has no size): the key ``plumbob mass``
    gives the size of ``props`` under, for a body of ``kind``."""
    if kind == "lamina" or (props.dim == 2 and props.measure > 0):
        return "area"
    if props.measure > 0 or (kind is not None and kind != "particles"):
        return "volume"
    return None

@dataclass(frozen=True, eq=False, repr=False)
class MassProperties(Result):
    """Mass properties of a lamina (``dim`` 2), a solid or a set of particles (``dim`` 3).

    Parameters
    ----------
    dim : int
        2 for a lamina in the plane z = 0, 3 otherwise (particles may have 2).
    mass, measure : float
        Total mass, kg; area (m², laminas) or volume (m³, solids), 0 for particles.
    center_of_mass, inertia : array_like, shapes (dim,) and (3, 3)
        m; the inertia tensor about the centre of mass, kg·m² (``I_xy = −∫ x y dm``).
    exact, relative_error : bool, float
        False, and an estimate of the relative error of every quantity, when a curved shape
        was faceted or a density field integrated numerically (exact: a round-off bound).
    parts : int
        How many parts were combined.
    notes : tuple of str
        Human-readable notes on how the numbers were obtained.

    Examples
    --------
    A 1 m cube of water, its corner at the origin:

    >>> cube = MassProperties(3, 1000.0, 1.0, [0.5, 0.5, 0.5], np.eye(3) * 1000 / 6)
    >>> cube
    MassProperties(dim=3, mass=1000 kg, volume=1 m³, center_of_mass=[0.5, 0.5, 0.5] m, \
principal_moments=[166.667, 166.667, 166.667] kg·m², exact=True)
    >>> cube.density
    1000.0

    The centre must have ``dim`` coordinates:

    >>> MassProperties(2, 1.0, 1.0, [0.0, 0.0, 0.0], np.zeros((3, 3)))
    Traceback (most recent call last):
    ...
    plumbob.errors.ArgumentError: center_of_mass must be one vector of 2 numbers, not 3 numbers
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
    source: Source | None = field(default=None, compare=False)  # the file, for str()
    _repr_units = {"mass": "kg", "area": "m²", "volume": "m³", "center_of_mass": "m",
                   "principal_moments": "kg·m²"}

    def __post_init__(self) -> None:
        # Checked here, once, so every result built anywhere is a physical one.
        com, inertia, mass, measure = mass_fields(self.dim, self.mass, self.measure,
                                                  self.center_of_mass, self.inertia)
        com.setflags(write=False)
        inertia.setflags(write=False)
        object.__setattr__(self, "center_of_mass", com)
        object.__setattr__(self, "inertia", inertia)
        object.__setattr__(self, "mass", mass)
        object.__setattr__(self, "measure", measure)

    def _repr_items(self) -> list[tuple[str, Any]]:
        # The headline numbers only: the tensor and the notes are an attribute away.
        size = size_key(self)
        items = [("dim", self.dim), ("mass", self.mass)]
        items += [(size, self.measure)] if size else []
        items += [("center_of_mass", self.center_of_mass),
                  ("principal_moments", self.principal_moments), ("exact", self.exact)]
        items += [] if self.exact else [("relative_error", self.relative_error)]
        return items + ([("parts", self.parts)] if self.parts != 1 else [])

    @property
    def exactness(self) -> str:
        """How ``plumbob mass`` says it: yes, yes (round-off at most …) or no (…)."""
        return ("yes" + (f" (round-off at most {self.relative_error:.1e})" if self.relative_error else "")
                if self.exact else f"no (relative error ~{self.relative_error:.1e})")

    # ------------------------------------------------------------ serialising
    def as_dict(self, kind: str | None = None) -> dict[str, Any]:
        """The mass properties keyed as ``plumbob mass --json`` prints them, SI units.

        Parameters
        ----------
        kind : str, optional
            The body's kind (``lamina``, ``solid``, ``particles``, ``assembly``): when
            given it leads, and every body but particles reports a size (``volume`` 0).

        Returns
        -------
        dict
            ``kind`` (when given), ``mass``, ``area`` (laminas) or ``volume`` (solids;
            neither for particles), ``center_of_mass``, ``inertia``,
            ``principal_moments``, ``principal_axes``, ``exact``, ``relative_error``,
            ``parts`` and, when there are any, ``notes``. Vectors and tensors are
            numpy arrays (:func:`plumbob.results.jsonable` makes them lists).

        Examples
        --------
        >>> d = point_mass(2.0, [1.0, 0.0]).as_dict()
        >>> list(d)
        ['mass', 'center_of_mass', 'inertia', 'principal_moments', 'principal_axes', \
'exact', 'relative_error', 'parts']
        >>> list(point_mass(2.0, [1.0, 0.0]).as_dict("assembly"))[:3]
        ['kind', 'mass', 'volume']
        """
        out: dict[str, Any] = {} if kind is None else {"kind": kind}
        out["mass"] = self.mass
        size = size_key(self, kind)
        if size:
            out[size] = self.measure
        out.update(center_of_mass=self.center_of_mass, inertia=self.inertia,
                   principal_moments=self.principal_moments, principal_axes=self.principal_axes,
                   exact=self.exact, relative_error=self.relative_error, parts=self.parts)
        if self.notes:
            out["notes"] = list(self.notes)
        return out

    # ------------------------------------------------------------------ views
    @property
    def area(self) -> float:
        """Area in m² (laminas only; NaN for other bodies).

        >>> point_mass(1.0, [0.0, 0.0, 0.0]).area
        nan
        """
        return self.measure if self.dim == 2 else float("nan")

    @property
    def volume(self) -> float:
        """Volume in m³ (solids; 0 for particles, NaN for laminas).

        >>> point_mass(1.0, [0.0, 0.0, 0.0]).volume, point_mass(1.0, [0.0, 0.0]).volume
        (0.0, nan)
        """
        return self.measure if self.dim == 3 else float("nan")

    @property
    def density(self) -> float:
        """Mean density: kg/m³ for solids, kg/m² for laminas (NaN for particles).

        >>> point_mass(1.0, [0.0, 0.0, 0.0]).density
        nan
        """
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
        """Principal moments of inertia, ascending, kg·m², shape (3,).

        >>> MassProperties(3, 1.0, 1.0, [0, 0, 0], np.diag([3.0, 1.0, 2.0])).principal_moments
        array([1., 2., 3.])
        """
        return self._principal[0]

    @property
    def principal_axes(self) -> np.ndarray:
        """Principal axes as rows (unit vectors, a right-handed frame), matching
        ``principal_moments``, shape (3, 3).

        >>> MassProperties(3, 1.0, 1.0, [0, 0, 0], np.diag([3.0, 1.0, 2.0])).principal_axes
        array([[0., 1., 0.],
               [0., 0., 1.],
               [1., 0., 0.]])
        """
        return self._principal[1]

    @property
    def center_of_mass_3d(self) -> np.ndarray:
        """Centre of mass with z = 0 appended for a lamina, shape (3,), m.

        >>> point_mass(1.0, [1.0, 2.0]).center_of_mass_3d
        array([1., 2., 0.])
        """
        return _as_3d(self.center_of_mass)

    def inertia_about(self, point: np.ndarray | list[float]) -> np.ndarray:
        """Inertia tensor about another point, by the parallel-axis theorem.

        Parameters
        ----------
        point : array_like, shape (dim,) or (3,)
            The point, m (a lamina's point may omit z).

        Returns
        -------
        numpy.ndarray, shape (3, 3)
            The inertia tensor about ``point``, kg·m².

        Examples
        --------
        >>> disc = point_mass(2.0, [1.0, 0.0, 0.0])
        >>> float(disc.inertia_about([0, 0, 0])[1, 1])
        2.0
        >>> float(disc.inertia_about([1, 0, 0])[1, 1])   # about its own centre: none
        0.0
        """
        offset = self.center_of_mass_3d - _as_3d(vector(point, "point", (self.dim, 3)))
        return self.inertia + _parallel_axis(self.mass, offset)

    def inertia_in(self, axes, point: np.ndarray | list[float] | None = None) -> np.ndarray:
        """The inertia tensor about ``point`` (default the centre of mass) in another frame.

        Parameters
        ----------
        axes : ``"principal"`` or array_like (3, 3)
            The frame's unit axes as rows, right-handed and at right angles (see
            :func:`frame_axes`), in the body's coordinates; ``"principal"``: the principal
            axes (about the centre of mass the tensor is then diagonal).
        point : array_like, shape (dim,) or (3,), optional
            The point, m (the parallel-axis theorem, :meth:`inertia_about`).

        Returns
        -------
        numpy.ndarray
            ``R I_point Rᵀ`` (3, 3), kg·m², ``R`` the rows of ``axes``.

        Examples
        --------
        >>> rod = MassProperties(3, 1.0, 0.0, [0, 0, 0], np.diag([0.0, 1 / 3, 1 / 3]))  # 2 m on x
        >>> rod.inertia_in([[0, 1, 0], [-1, 0, 0], [0, 0, 1]]).diagonal().round(6)
        array([0.333333, 0.      , 0.333333])
        >>> rod.inertia_in("principal").diagonal().round(6)
        array([0.      , 0.333333, 0.333333])
        """
        rows = self.principal_axes if isinstance(axes, str) and axes == "principal" else \
            frame_rows(axes)
        tensor = self.inertia if point is None else self.inertia_about(point)
        return rows @ tensor @ rows.T

    def moment_about_axis(self, point: np.ndarray | list[float], axis: np.ndarray | list[float]) -> float:
        """Moment of inertia about a line.

        Parameters
        ----------
        point, axis : array_like
            A point of the line, m, and its direction (any length but zero).

        Returns
        -------
        float
            The moment of inertia about the line through ``point`` along ``axis``, kg·m².

        Examples
        --------
        >>> ball = point_mass(2.0, [1.0, 0.0, 0.0])
        >>> ball.moment_about_axis([0, 0, 0], [0, 0, 5])
        2.0
        >>> ball.moment_about_axis([0, 0, 0], [1, 0, 0])   # on the axis: none
        0.0
        """
        axis = _as_3d(unit_vector(axis, "axis", (self.dim, 3)))
        return float(axis @ self.inertia_about(point) @ axis)

    # ------------------------------------------------------------- algebra
    def __add__(self, other: MassProperties) -> MassProperties:
        """Two parts as one body (equation 15; see :func:`combine`)."""
        return combine([self, other])

    def __sub__(self, other: MassProperties) -> MassProperties:
        """Remove ``other`` (a hole lying inside ``self``): a part of negative mass.

        >>> (point_mass(3.0, [0, 0, 0]) - point_mass(1.0, [2, 0, 0])).center_of_mass
        array([-1.,  0.,  0.])
        >>> point_mass(1.0, [0, 0, 0]) - point_mass(1.0, [0, 0, 0])
        Traceback (most recent call last):
        ...
        plumbob.errors.GeometryError: the parts add up to no mass: a hole larger than its body?
        """
        return combine([self, other], signs=[1.0, -1.0])

    def scaled(self, factor: float) -> MassProperties:
        """Every mass multiplied by a factor (a change of density), shape unchanged.

        Parameters
        ----------
        factor : float
            The factor on the mass and the inertia.

        Returns
        -------
        MassProperties

        Examples
        --------
        >>> point_mass(2.0, [1.0, 0.0]).scaled(1.5).mass
        3.0
        """
        factor = non_negative(factor, "factor")
        return replace(self, mass=self.mass * factor, inertia=self.inertia * factor, source=None)

    def with_density(self, density: float) -> MassProperties:
        """The same shape at a uniform density.

        Parameters
        ----------
        density : float
            kg/m³, or kg/m² for a lamina.

        Returns
        -------
        MassProperties
            Mass ``density × measure`` and the inertia scaled with it.

        Examples
        --------
        >>> cube = MassProperties(3, 1.0, 2.0, [0, 0, 0], np.eye(3))
        >>> cube.with_density(7850.0).mass
        15700.0
        >>> point_mass(1.0, [0, 0, 0]).with_density(1000.0)
        Traceback (most recent call last):
        ...
        plumbob.errors.GeometryError: a body of zero size has no density to set
        """
        if self.measure == 0:
            raise GeometryError("a body of zero size has no density to set")
        return self.scaled(positive(density, "density") * self.measure / self.mass)

    def translated(self, offset: np.ndarray | list[float]) -> MassProperties:
        """Moved without turning: the tensor about the centre is unchanged.

        Parameters
        ----------
        offset : array_like, shape (dim,) or (3,)
            The displacement, m (a lamina ignores a z component).

        Returns
        -------
        MassProperties

        Examples
        --------
        >>> point_mass(1.0, [1.0, 2.0]).translated([1.0, 1.0, 5.0]).center_of_mass
        array([2., 3.])
        """
        offset = vector(offset, "offset", (self.dim, 3))
        return replace(self, center_of_mass=self.center_of_mass + offset[: self.dim], source=None)

    def transformed(
        self, matrix: np.ndarray, offset: np.ndarray | list[float] | None = None
    ) -> MassProperties:
        """Turned (or mirrored) about the origin, then moved.

        Parameters
        ----------
        matrix, offset : array_like (2, 2) or (3, 3), array_like (optional)
            An orthogonal matrix (a lamina's must keep its plane); then moved by offset, m.

        Returns
        -------
        MassProperties
            Centre ``matrix @ c + offset``, tensor ``matrix @ I @ matrix.T``.

        Examples
        --------
        >>> p = point_mass(1.0, [1.0, 0.0, 0.0])
        >>> p.transformed(np.diag([-1.0, 1.0, 1.0]), [0.0, 0.0, 1.0]).center_of_mass
        array([-1.,  0.,  1.])
        >>> p.transformed(2 * np.eye(3))
        Traceback (most recent call last):
        ...
        plumbob.errors.GeometryError: a rigid motion needs an orthogonal matrix
        """
        matrix = floats(matrix, "matrix", error=GeometryError)
        n = len(matrix) if matrix.ndim else 0
        if matrix.shape != (n, n) or n not in (2, 3) or n < self.dim:
            raise GeometryError(f"a {self.dim}D body needs a {self.dim}×{self.dim} or 3×3 matrix")
        if not np.allclose(matrix @ matrix.T, np.eye(n), atol=1e-12):
            raise GeometryError("a rigid motion needs an orthogonal matrix")
        full = np.eye(3)
        full[:n, :n] = matrix
        if self.dim == 2 and n == 3 and not np.allclose(full[2, :2], 0, atol=1e-15):
            raise GeometryError("a lamina can only be turned within its plane; use to_3d() first")
        com = (full @ self.center_of_mass_3d)[: self.dim]
        result = replace(self, center_of_mass=com, inertia=full @ self.inertia @ full.T, source=None)
        return result if offset is None else result.translated(offset)

    def rotated(self, angle: float, axis: np.ndarray | list[float] = (0.0, 0.0, 1.0)) -> MassProperties:
        """Turned about an axis through the origin.

        Parameters
        ----------
        angle, axis : float, array_like
            Radians, by the right-hand rule, about ``axis`` (default z; a lamina's).

        Returns
        -------
        MassProperties

        Examples
        --------
        >>> point_mass(1.0, [1.0, 0.0]).rotated(np.pi / 2).center_of_mass
        array([0., 1.])
        """
        return self.transformed(rotation_matrix(axis, angle))

    def mirrored(self, normal: np.ndarray | list[float]) -> MassProperties:
        """Reflected in the plane (the line, for a lamina) through the origin.

        Parameters
        ----------
        normal : array_like
            The mirror's normal (any length but zero).

        Returns
        -------
        MassProperties

        Examples
        --------
        >>> point_mass(1.0, [1.0, 2.0, 3.0]).mirrored([0, 0, 1]).center_of_mass
        array([ 1.,  2., -3.])
        """
        normal = _as_3d(unit_vector(normal, "normal", (self.dim, 3)))
        return self.transformed(np.eye(3) - 2 * np.outer(normal, normal))

    def to_3d(self) -> MassProperties:
        """A lamina seen as a (zero-thickness) body in space: its centre gains z = 0.

        Returns
        -------
        MassProperties
            ``dim`` 3; a body already in space unchanged.

        Examples
        --------
        >>> point_mass(1.0, [1.0, 2.0]).to_3d().center_of_mass
        array([1., 2., 0.])
        """
        if self.dim == 3:
            return self
        return replace(self, dim=3, center_of_mass=self.center_of_mass_3d, source=None)


def point_mass(mass: float, position: np.ndarray | list[float]) -> MassProperties:
    """A particle: mass at a point, no size and no inertia about itself.

    Parameters
    ----------
    mass : float
        kg.
    position : array_like, shape (2,) or (3,)
        m; two coordinates make a particle of the plane (``dim`` 2).

    Returns
    -------
    MassProperties
        Measure 0 and a zero inertia tensor.

    Examples
    --------
    >>> point_mass(3.0, [1, 2, 3]).center_of_mass
    array([1., 2., 3.])
    >>> point_mass(3.0, [1, 2]).dim
    2
    """
    position = np.asarray(position, dtype=float)
    return MassProperties(position.size, mass, 0.0, position, np.zeros((3, 3)))


def combine(parts: list[MassProperties], signs: list[float] | None = None) -> MassProperties:
    """Equation (15): the parts as particles at their centres, plus their own inertia.

    The result's centre is the mass-weighted mean of the parts' centres; the
    inertia is summed about it by parallel axes, with offsets taken from the
    combined centre so nothing large is subtracted.

    Parameters
    ----------
    parts : list of MassProperties
        At least one; laminas mixed with bodies in space are seen in space (z = 0).
    signs : list of float, optional
        One per part: −1 removes a part (a hole). Default all +1.

    Returns
    -------
    MassProperties
        Exact when every part is; the notes of every part, each once.

    Raises
    ------
    GeometryError
        For no parts, or parts that add up to no mass (a hole larger than its body).

    Examples
    --------
    >>> a = point_mass(1.0, [0.0, 0.0, 0.0]); b = point_mass(3.0, [4.0, 0.0, 0.0])
    >>> combine([a, b]).center_of_mass
    array([3., 0., 0.])
    >>> combine([a, point_mass(1.0, [1.0, 0.0])]).center_of_mass   # a lamina's point: z = 0
    array([0.5, 0. , 0. ])
    >>> combine([])
    Traceback (most recent call last):
    ...
    plumbob.errors.GeometryError: nothing to combine: a body needs at least one part
    """
    if not parts:
        raise GeometryError("nothing to combine: a body needs at least one part")
    for part in parts:
        instance(part, "a part to combine", MassProperties)
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
    return MassProperties(dim, total, float(measures.sum()), anchor + com_local,
                          (inertia + inertia.T) / 2, exact=exact, relative_error=error,
                          parts=int(sum(p.parts for p in parts)), notes=notes)
