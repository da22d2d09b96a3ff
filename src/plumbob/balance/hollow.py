"""Hollowing: empty part of a body's interior so that it stands.

Why it is a small linear problem (Prévost et al., *Make It Stand*, 2013): cut the
interior — what lies deeper than the wall thickness, the inward offset
(:mod:`plumbob.bodies.offset`) — into cells (:mod:`plumbob.balance.cells`), cell
``i`` of mass ``m_i`` and centre ``c_i``. Emptying it adds a negative mass at
``c_i``, so with ``x_i ∈ {0, 1}`` (emptied or not) a stability target's rows
(:class:`plumbob.balance.targets.Target`: ``M·slack(c) + Σ m_j·slack(p_j) ≥ 0``)
read::

    Σ_i x_i m_i slack_k(c_i) ≤ M slack_k(c)            for every row k

and the least material removed is ``min Σ x_i m_i`` (``--lightest``: the most),
a 0–1 linear program that HiGHS (``scipy.optimize.milp``) solves at once for the
few hundred cells and handful of rows a body has. More rows keep the emptied cells
*well-composed* (no two touching only along an edge or at a corner,
:func:`plumbob.balance.cells.manifold_rows`), so the carved mesh is a 2-manifold
that any slicer accepts. The carved body is the body less
the emptied cells, one closed mesh with an inner shell (manifold3d), and the void
(the emptied cells' union) is a mesh of its own, for a slicer's modifier.

What the plan predicts is checked where it matters: :func:`write_hollow` writes
both meshes, reads the carved one back and measures its mass properties and its
stability from the file, as ``plumbob check`` would.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..bodies.base import Body
from ..bodies.offset import InwardOffset, inward_offset, manifold_triangles
from ..bodies.solid import MeshSolid
from ..errors import GeometryError, StabilityError
from ..massprops import MassProperties
from ..results import Result
from ..tolerances import size_of
from .cells import GridCells, box_union, grid_cells, manifold_rows

__all__ = ["HollowResult", "WrittenHollow", "hollow", "write_hollow", "CELLS_ALONG"]

#: the default cell size is the interior's longest extent over this
CELLS_ALONG = 16
#: seconds HiGHS may spend choosing cells before the best choice found is taken
TIME_LIMIT = 30.0


@dataclass(frozen=True, eq=False, repr=False)
class HollowResult(Result):
    """A hollowing plan: which cells of the interior to empty, and the bodies it gives.

    carved: the body less the emptied cells (a mesh with an inner shell), or the body's
        own mesh when nothing need be emptied.
    void: the emptied cells' union (None when none are).
    wall: m, the wall thickness asked for (the walls are at least this thick).
    offset: the interior's inward offset (how it was made, its error).
    cells: the interior's cells; emptied: (n,) bool, which are emptied.
    before, after: mass properties of the body's mesh (a curved body's faceting, 256
        segments per turn) and of the carved body, as planned.
    target_met: whether the carved body's centre meets every row of the target.
    lightest: whether the most material was removed (else the least).
    """

    carved: MeshSolid
    void: MeshSolid | None
    wall: float
    offset: InwardOffset
    cells: GridCells
    emptied: np.ndarray
    before: MassProperties
    after: MassProperties
    target_met: bool
    lightest: bool = False

    _repr_fields = ("wall", "target_met", "lightest")

    @property
    def removed_mass(self) -> float:
        """kg taken out."""
        return self.before.mass - self.after.mass

    def as_dict(self) -> dict[str, Any]:
        """``wall``, ``cell_size``, ``cells``, ``cells_emptied``, ``mass_before``,
        ``mass_after``, ``removed_mass``, ``center_of_mass_before``,
        ``center_of_mass_after``, ``target_met``, ``lightest``, ``offset`` (SI)."""
        return {
            "wall": self.wall, "cell_size": self.cells.size, "cells": len(self.cells),
            "cells_emptied": int(self.emptied.sum()),
            "mass_before": self.before.mass, "mass_after": self.after.mass,
            "removed_mass": self.removed_mass,
            "center_of_mass_before": self.before.center_of_mass,
            "center_of_mass_after": self.after.center_of_mass,
            "target_met": self.target_met, "lightest": self.lightest,
            "offset": self.offset.as_dict(),
        }


def _density(body: Body) -> float | None:
    densities = body.densities()
    if len(densities) != 1 or "field" in densities:
        raise GeometryError("hollowing needs a body of one density (carve each part of an "
                            "assembly on its own)")
    density = densities.pop()
    return density if isinstance(density, float) else None


def _choose(cells: GridCells, density: float, mass: float, centre: np.ndarray, target,
            lightest: bool, safety: float) -> np.ndarray:
    """Which cells to empty (n,) bool: the 0–1 program of the module's doc."""
    from scipy.optimize import Bounds, LinearConstraint, milp

    masses = density * cells.volumes
    rows = masses[None, :] * target.slack(cells.centres)  # (k, n), kg·m
    limit = mass * np.asarray(target.slack(centre), dtype=float) - safety
    # in units of the body's mass and the cells' reach, so that HiGHS's absolute
    # feasibility tolerance (1e-7) is far below every moment that matters
    unit = mass * max(float(np.abs(rows).max()) / max(float(masses.max()), 1e-300), 1e-300)
    rows, limit = rows / unit, limit / unit
    cost = (-masses if lightest else masses) / mass
    shape, shape_limit = manifold_rows(cells)
    constraints = [LinearConstraint(rows, -np.inf, limit)]
    if shape.shape[0]:
        constraints.append(LinearConstraint(shape, -np.inf, shape_limit))
    result = milp(cost, constraints=constraints, integrality=np.ones(len(masses)),
                  bounds=Bounds(0, 1), options={"time_limit": TIME_LIMIT})
    if result.x is None:
        best = np.where(rows.sum(axis=0) > 0, 0.0, 1.0)  # every cell that helps every row…
        short = float(np.min(mass * target.slack(centre) - rows @ best)) / mass
        raise StabilityError(
            "hollowing cannot meet the target: even emptying the interior leaves the centre "
            f"of mass about {-short:.3g} m short of it; give a thinner --wall, add ballast, "
            "or widen the base")
    chosen = np.rint(result.x)
    if np.any(rows @ chosen > limit + 1e-9) or np.any(shape @ chosen > shape_limit + 0.5):
        raise StabilityError("hollowing found no choice of whole cells that meets the target "
                             "within its time: give a smaller --cell size or a thinner --wall")
    return chosen.astype(bool)


def hollow(body: Body, *, wall: float, target, lightest: bool = False,
           cell_size: float | None = None, step: float | None = None) -> HollowResult:
    """Empty cells of ``body``'s interior, keeping walls ``wall`` m thick, so that it
    meets ``target``.

    Parameters
    ----------
    body : Body
        A solid of one density (a mesh read from a file, a primitive, a boolean).
    wall : float
        m, positive: the least wall thickness kept everywhere.
    target : Target
        What to meet (:func:`plumbob.balance.targets.target_for`): anything with a
        ``slack(points) -> (k, n)`` whose rows must stay ≥ 0.
    lightest : bool
        Empty as much as the target allows (a light print), not as little.
    cell_size : float, optional
        m, the grid the interior is cut by; default its longest extent / 16.
    step : float, optional
        m, the level-set step of the inward offset when it has no closed form; the
        offset is then taken one step deeper so its own error never thins a wall.

    Returns
    -------
    HollowResult

    Raises
    ------
    StabilityError
        When no choice of cells meets the target.
    GeometryError
        When nothing lies ``wall`` inside the body, or the body is not one solid.

    Examples
    --------
    Any target with rows of slack works; here, lowering a 1 m cube's centre to 0.45 m
    (``slack = 0.45 − z``) with 0.1 m walls empties the top of its interior:

    >>> from plumbob.bodies.primitives import box
    >>> class Low:
    ...     def slack(self, points):
    ...         return 0.45 - np.asarray(points, dtype=float).T[2:3]
    >>> plan = hollow(box(1, 1, 1, density=1000.0), wall=0.1, target=Low(), cell_size=0.2)
    >>> plan.target_met, plan.offset.exact, bool(plan.after.center_of_mass[2] <= 0.45)
    (True, True, True)

    Taking m kg from at most 0.8 m up lowers the centre to (500 − 0.8 m)/(1000 − m): at
    least 50/0.35 kg must go, and whole cells of 8 kg take a little more:

    >>> bool(50 / 0.35 <= plan.removed_mass < 50 / 0.35 + 4 * 8)
    True
    """
    wall = float(wall)
    if not (np.isfinite(wall) and wall > 0):
        raise GeometryError(f"a wall thickness must be a positive length, not {wall!r}")
    if cell_size is not None and not (np.isfinite(cell_size) and cell_size > 0):
        raise GeometryError(f"a cell size must be a positive length, not {cell_size!r}")
    density = _density(body)
    triangles, own = body.surface(256)
    # the plan starts from the mesh that is carved and written (a curved body's faceting),
    # not from the exact body: the written file is what must meet the target
    outer_mesh = MeshSolid(triangles, density)
    before = outer_mesh.mass_properties()
    rho = before.mass / before.measure
    size = size_of(triangles.reshape(-1, 3))
    h = float(step) if step is not None else min(wall / 2, size / 64)
    # float32 files move vertices by ~1e-7 of the size: keep the exact walls that much thicker
    offset = inward_offset(body, wall * (1 + 1e-6) + 1e-6 * size, step=h, extra=h)
    if offset.body is None:
        raise GeometryError(f"nothing lies {wall:g} m inside the body: give a thinner --wall")
    interior = offset.body.to_geometry(256)
    lo, hi = np.asarray(interior.bounding_box()[:3]), np.asarray(interior.bounding_box()[3:])
    cell = float(cell_size) if cell_size is not None else float(np.max(hi - lo)) / CELLS_ALONG
    cells = grid_cells(interior, cell)
    safety = 1e-6 * before.mass * size  # round-off of the written file, as a moment
    emptied = _choose(cells, rho, before.mass, before.center_of_mass, target, lightest, safety)
    if not emptied.any():
        return HollowResult(outer_mesh, None, wall, offset, cells, emptied, before,
                            outer_mesh.mass_properties(), bool(np.all(target.slack(
                                before.center_of_mass) >= 0)), lightest)
    import manifold3d

    # the void is the interior within the chosen cells' boxes: one boolean, not a union of
    # cells meeting face to face (which leaves coincident slivers behind)
    void_manifold = interior ^ box_union(cells, emptied)
    outer = outer_mesh.to_geometry() if own else body.to_geometry(256)
    carved_manifold = outer - void_manifold
    if carved_manifold.status() != manifold3d.Error.NoError or carved_manifold.is_empty():
        raise GeometryError(f"the carved body could not be built ({carved_manifold.status()})")
    carved = MeshSolid(manifold_triangles(carved_manifold), density)
    void = MeshSolid(manifold_triangles(void_manifold), density)
    after = carved.mass_properties()
    met = bool(np.all(np.asarray(target.slack(after.center_of_mass)) >= -safety / after.mass))
    return HollowResult(carved, void, wall, offset, cells, emptied, before, after, met, lightest)


@dataclass(frozen=True, eq=False, repr=False)
class WrittenHollow(Result):
    """The carved body as written, measured from the file.

    out, void: the paths written (void None when not asked for or nothing emptied).
    mass_properties: of the carved body read back from ``out``.
    verdict: :func:`plumbob.stability.check` of the body read back, resting along the
        target's ``down`` (its margin and critical tilt are what was achieved).
    plan: the :class:`HollowResult` written.
    body: the carved body as read back from ``out`` (with the plan's density), for what
        comes next (ballast on top of the carving).
    """

    out: str
    void: str | None
    mass_properties: MassProperties
    verdict: Any
    plan: HollowResult
    body: Body | None = None

    _repr_fields = ("out", "void")

    def as_dict(self) -> dict[str, Any]:
        """The plan's keys, then ``out``, ``void``, ``mass_after`` and
        ``center_of_mass_after`` (from the file), ``margin``, ``critical_tilt_deg``,
        ``verdict``."""
        out = self.plan.as_dict()
        out.update(out=self.out, void=self.void, mass_after=self.mass_properties.mass,
                   center_of_mass_after=self.mass_properties.center_of_mass,
                   removed_mass=self.plan.before.mass - self.mass_properties.mass,
                   verdict=self.verdict.verdict, margin=self.verdict.margin,
                   critical_tilt_deg=self.verdict.critical_tilt_deg)
        return out


def write_hollow(plan: HollowResult, out: str, *, void: str | None = None, units: str | None = None,
                 down=None) -> WrittenHollow:
    """Write the carved body to ``out`` (and the void to ``void``), each atomically, then
    read ``out`` back and measure it.

    Parameters
    ----------
    plan : HollowResult
    out, void : str
        Paths, ``.stl`` (binary) or ``.3mf``; ``void`` optional.
    units : str, optional
        The unit of the files' coordinates (that of the file the body came from: ``mm``
        for most prints); default metres. A 3MF states it
        (:func:`plumbob.formats.writers.write_mesh`).
    down : array_like, optional
        The direction of gravity for the stability check of the written body
        (default −z).

    Returns
    -------
    WrittenHollow
    """
    from ..formats.writers import mesh_format, write_mesh
    from ..loading import read
    from ..stability import check

    for path in (out, void):
        if path is not None and mesh_format(path) is None:
            raise GeometryError(f"hollowing writes STL or 3MF files (.stl, .3mf), not {path!r}")
    unit = write_mesh(str(out), plan.carved.triangles, units, "plumbob carved")
    written_void = None
    if void is not None and plan.void is not None:
        write_mesh(str(void), plan.void.triangles, units, "plumbob void")
        written_void = str(void)
    stl = mesh_format(out) == "stl"
    back = read(str(out), units=unit if stl else None).body
    density = plan.before.mass / plan.before.measure
    back = back.with_default_density(density)
    props = back.mass_properties()
    verdict = check(back, down, props=props)
    return WrittenHollow(str(out), written_void, props, verdict, plan, back)
