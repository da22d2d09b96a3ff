"""Mass properties of a uniform body from the moments of its geometry: the inertia
tensor from second moments, and the density (or its default) applied.

Shared by every kind of uniform body (laminas, meshes, extrusions, revolutions, graded
bodies' cells), so a mesh solid needs nothing of the lamina's machinery.
"""

from __future__ import annotations

import numpy as np

from ..massprops import MassProperties
from .base import DEFAULT_DENSITY_NOTE

__all__ = ["second_moments_to_inertia", "uniform_mass_properties"]


def second_moments_to_inertia(central: np.ndarray) -> np.ndarray:
    """The inertia tensor ``tr(C) 1 − C`` from second moments ``C = ∫ r rᵀ dm``.

    Parameters
    ----------
    central : ndarray, shape (2, 2) or (3, 3)
        kg·m²; a plane body's (2, 2) moments lie in z = 0.

    Returns
    -------
    ndarray, shape (3, 3)
        kg·m².

    Examples
    --------
    A unit mass at (1, 0): no inertia about x, 1 about y and z.

    >>> second_moments_to_inertia(np.array([[1.0, 0.0], [0.0, 0.0]]))
    array([[0., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    c = np.zeros((3, 3))
    n = central.shape[0]
    c[:n, :n] = central
    return np.trace(c) * np.eye(3) - c


def uniform_mass_properties(
    dim: int,
    measure: float,
    centre: np.ndarray,
    central: np.ndarray,
    density: float | None,
    *,
    exact: bool = True,
    relative_error: float = 0.0,
    note: str | None = None,
) -> MassProperties:
    """Mass properties of a uniform body from its geometry's moments.

    Parameters
    ----------
    dim : int
        2 (lamina) or 3 (solid).
    measure : float
        Area, m², or volume, m³.
    centre : ndarray, shape (dim,)
        The centroid, m.
    central : ndarray, shape (dim, dim)
        ``∫ r rᵀ`` over the region about the centroid (m⁴ or m⁵).
    density : float or None
        kg/m² or kg/m³; None: not given, 1 is used and a note says so.
    exact, relative_error, note
        Carried into the result.

    Returns
    -------
    MassProperties

    Examples
    --------
    >>> p = uniform_mass_properties(2, 2.0, np.array([1.0, 0.5]), np.eye(2), None)
    >>> p.mass, p.notes
    (2.0, ('no density given: 1 kg/m³ (1 kg/m² for a lamina) assumed',))
    """
    rho = 1.0 if density is None else density
    notes = [] if density is not None else [DEFAULT_DENSITY_NOTE]
    if note:
        notes.append(note)
    return MassProperties(dim, rho * measure, measure, centre, rho * second_moments_to_inertia(central),
                          exact=exact, relative_error=relative_error, notes=tuple(notes))
