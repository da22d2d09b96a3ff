"""The least ballast that meets a target, and where to put it.

One added mass ``m`` at a point ``p`` meets a :class:`~.targets.Target` iff for
every row ``k``: ``M s_k(c) + m s_k(p) ≥ 0`` (``s`` the rows' slack, ``M`` and
``c`` the body's mass and centre). Per point this is a closed form: rows the body
already meets (``s_k(c) ≥ 0``) cap the mass where ``s_k(p) < 0``; rows it misses
need ``s_k(p) > 0`` and ``m ≥ −M s_k(c) / s_k(p)``. The least mass over a point's
feasible interval is evaluated at once for every candidate point (vectorised), and
the best candidate is refined on finer grids around it.

One point is enough: the conditions depend on the added masses only through their
total and their first moment, so masses at several points act as their total at
their weighted centroid. Within a convex region that centroid is a point of the
region, so no split beats the best single point. A point mass is also solved
exactly over the region's convex hull (a linear program in the mass and its moment,
:func:`_hull_optimum`); its answer is taken when its point lies in the region, which
it always does for a convex one — the grid then only covers non-convex regions and
ballasts of a given size.

Candidates are the centres of a grid over the region (the body itself, or a second
body the user gives), kept where the region ``contains`` them — with a ballast
material, where a box or cylinder of the ballast's volume centred there fits inside.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..errors import StabilityError, TargetNotMet
from ..limits import MAX_SAMPLES, check_count
from ..tolerances import size_of
from .targets import Target

__all__ = ["BallastPlan", "plan_ballast", "required_mass", "SHAPES", "ballast_body"]

#: the shapes a ballast of a given material may take
SHAPES = ("box", "cylinder")
_GRID = {2: 160, 3: 28}  # grid cells per axis of the first search
_REFINE_ROUNDS = 6
_BATCH = 256  # candidates tested for fit at once
_CHUNK = 2048  # candidates scored at once
_TIE_ROWS = 3  # equal masses are ranked by their smallest this many slacks
# The plan aims this many contact tolerances inside every margin row (the check calls a
# margin within one tolerance neutral) and a round-off's worth inside every tilt row.
_SAFETY = {"margin": 2.0, "tilt": 1e-3}


@dataclass(frozen=True)
class BallastPlan:
    """Where the least ballast goes: ``mass`` kg at ``point`` (dim,) m; with a material,
    its ``volume`` m³ and ``shape`` (``"box"``, ``"cylinder"`` or, for a lamina, a
    ``"square"`` through its thickness) of ``dimensions`` m."""

    mass: float
    point: np.ndarray
    density: float | None = None
    volume: float | None = None
    shape: str | None = None
    dimensions: tuple[float, ...] = ()
    depth: float | None = None


def required_mass(target: Target, mass: float, center: np.ndarray,
                  points: np.ndarray) -> np.ndarray:
    """The least mass (kg) that, added at each of ``points`` (n, dim), meets ``target``;
    ``inf`` where no mass there does.

    >>> from plumbob.balance.targets import Target
    >>> t = Target(np.array([[1.0]]), np.array([0.0]))  # the centre must have x ≥ 0
    >>> required_mass(t, 2.0, np.array([-1.0]), np.array([[1.0], [4.0], [-3.0]])).tolist()
    [2.0, 0.5, inf]
    """
    s0 = mass * target.slack(np.asarray(center, dtype=float))  # (k,)
    s = target.slack(np.asarray(points, dtype=float))  # (k, n)
    missed = s0 < 0
    with np.errstate(divide="ignore", invalid="ignore"):
        need = np.where(s[missed] > 0, -s0[missed, None] / s[missed], np.inf)
        cap = np.where(s[~missed] < 0, s0[~missed, None] / -s[~missed], np.inf)
    lo = need.max(axis=0) if need.size else np.zeros(s.shape[1])
    hi = cap.min(axis=0) if cap.size else np.full(s.shape[1], np.inf)
    return np.where(lo <= hi, lo, np.inf)


def _ranking(goal: Target, mass: float, center: np.ndarray,
             points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The least mass at each point, and the points that can take one, best first.

    Least mass first; among equal masses, the point that leaves the rows the body
    already meets the most slack — the smallest first, then the next (a counterweight
    for the front edge goes in the middle, not in a corner). Points are scored in
    chunks so a round base's thousands of rows never make a huge array.
    """
    s0 = goal.slack(center)
    met = s0 >= 0
    need = np.empty(len(points))
    keys = np.zeros((len(points), _TIE_ROWS))
    for start in range(0, len(points), _CHUNK):
        chunk = points[start:start + _CHUNK]
        m = required_mass(goal, mass, center, chunk)
        need[start:start + _CHUNK] = m
        if met.any():
            m0 = np.where(np.isfinite(m), m, 0.0)
            after = (mass * s0[met, None] + m0 * goal.slack(chunk)[met]) / (mass + m0)
            low = min(_TIE_ROWS, after.shape[0])
            smallest = np.sort(np.partition(after, low - 1, axis=0)[:low], axis=0)
            keys[start:start + _CHUNK, :low] = smallest.T
    finite = np.isfinite(need)
    if not finite.any():
        return need, np.zeros(0, dtype=int)
    level = np.round(need / max(float(need[finite].min()), 1e-300), 9)
    order = np.lexsort((*(-keys[:, i] for i in reversed(range(_TIE_ROWS))), level))
    return need, order[finite[order]]


def _hull_optimum(region, goal: Target, mass: float,
                  center: np.ndarray) -> tuple[float, np.ndarray] | None:
    """The exact least point mass over the region's convex hull, when its point lies in
    the region (always, for a convex region), else None.

    With the moment ``q = m p`` the conditions are linear in ``(m, q)``:
    ``M s(c) + N q − m b ≥ 0`` per row, and ``p`` in the hull ``A p + e ≤ 0`` is
    ``A q + e m ≤ 0``; the least ``m`` is a linear program (scipy ``linprog``, HiGHS).
    """
    from scipy.optimize import linprog
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = ConvexHull(np.asarray(region.hull_points(), dtype=float))
    except QhullError:
        return None
    a, e = hull.equations[:, :-1], hull.equations[:, -1]
    dim = goal.dim
    rows = np.vstack((np.column_stack((goal.offsets, -goal.normals)), np.column_stack((e, a))))
    bounds = np.concatenate((mass * goal.slack(center), np.zeros(len(e))))
    cost = np.zeros(dim + 1)
    cost[0] = 1.0
    result = linprog(cost, A_ub=rows, b_ub=bounds, method="highs",
                     bounds=[(0, None)] + [(None, None)] * dim)
    if result.status != 0 or not result.x[0] > 0:
        return None
    point = result.x[1:] / result.x[0]
    size = size_of(hull.points)
    point = np.where(np.abs(point) < 1e-12 * size, 0.0, point) + 0.0  # round-off of a vertex
    if not region.contains(point[None])[0]:
        return None  # the hull's best point is outside a non-convex region
    need = float(required_mass(goal, mass, center, point[None])[0])
    return (need, point) if np.isfinite(need) else None


def _grid(lo: np.ndarray, hi: np.ndarray, n: int) -> np.ndarray:
    """Centres of an n^dim grid of cells over the box [lo, hi]."""
    axes = [a + (b - a) * (np.arange(n) + 0.5) / n for a, b in zip(lo, hi)]
    return np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, len(lo))


def _frame_matrix(target: Target) -> np.ndarray:
    """Columns: the ground axes and up (a rotation taking a shape's own axes, z or y up,
    onto the target's frame)."""
    frame = target.support.frame
    return np.column_stack([*frame.axes, frame.up])


def _scale(shape: str, dim: int, volume, depth: float | None):
    """The size (m) of a ballast of ``volume`` m³ (array or number): a cube's side, a
    cylinder's radius (its height is its diameter), a lamina's square side (through its
    ``depth``) — the factor taking :func:`_outline`'s unit shape to it."""
    volume = np.asarray(volume, dtype=float)
    if dim == 2:
        return np.sqrt(volume / depth)
    if shape == "cylinder":
        return np.cbrt(volume / (2 * np.pi))
    return np.cbrt(volume)


def _dimensions(shape: str, dim: int, volume: float, depth: float | None) -> tuple[float, ...]:
    """A ballast's sizes, m: (side,) of a cube or square, (radius, height) of a cylinder."""
    size = float(_scale(shape, dim, volume, depth))
    return (size, 2 * size) if dim == 3 and shape == "cylinder" else (size,)


def _outline(shape: str, dim: int) -> np.ndarray:
    """Points on a unit shape's boundary, centred at the origin, up the last axis:
    the cube [−½, ½]³ (or square), or the cylinder of radius 1 and height 2."""
    if dim == 3 and shape == "cylinder":
        angle = np.linspace(0, 2 * np.pi, 24, endpoint=False)
        ring = np.stack((np.cos(angle), np.sin(angle)), axis=1)
        rings = [np.column_stack((ring * r, np.full(len(ring), z)))
                 for z in (-1.0, -0.5, 0.0, 0.5, 1.0) for r in (1.0, 0.5)]
        return np.concatenate([*rings, [[0, 0, -1.0], [0, 0, 1.0]]])
    cells = 9 if dim == 2 else 7
    grid = _grid(np.full(dim, -0.5), np.full(dim, 0.5), cells) * cells / (cells - 1)
    return grid[np.max(np.abs(grid), axis=1) >= 0.5 - 1e-12]


def plan_ballast(region, target: Target, mass: float, center: np.ndarray, *,
                 density: float | None = None, shape: str = "box",
                 depth: float | None = None, samples: int | None = None) -> BallastPlan:
    """The least ballast inside ``region`` (a body: where it may go) that meets ``target``
    for a body of ``mass`` kg and centre ``center``.

    density: the ballast's material, kg/m³; with it the ballast is a ``shape`` (box or
        cylinder; a square through ``depth`` m for a lamina) that must fit in ``region``.
    samples: cells per axis of the first grid (default 160 for a lamina, 28 for a solid).

    Raises :class:`StabilityError` when no point of the region meets the target with
    any mass (the support itself is too narrow for it).
    """
    center = np.asarray(center, dtype=float)
    dim = target.dim
    tol = target.support.tolerance
    safety = np.array([_SAFETY.get(kind, 2.0) for kind in target.kinds] or
                      np.full(len(target.offsets), 2.0))
    goal = replace(target, offsets=target.offsets + safety * tol)
    if goal.met_by(center):
        return BallastPlan(0.0, center.copy())
    if density is not None and shape not in SHAPES:
        raise StabilityError(f"a ballast shape is one of {', '.join(SHAPES)}, not {shape!r}")
    n = samples or _GRID[dim]
    check_count("ballast candidate points", n ** dim, MAX_SAMPLES, hint="give fewer samples")
    hull = np.asarray(region.hull_points(), dtype=float)
    lo, hi = hull.min(axis=0), hull.max(axis=0)
    spacing = (hi - lo) / n
    rotation = _frame_matrix(target)
    outline = _outline(shape, dim) @ rotation.T
    plane = target.support.plane_point @ target.support.frame.up
    clearance = 1e-6 * float(np.linalg.norm(hi - lo))

    def sizes(masses: np.ndarray) -> np.ndarray:
        return np.zeros(len(masses)) if density is None else _scale(shape, dim, masses / density,
                                                                    depth)

    def best(points: np.ndarray) -> tuple[float, np.ndarray] | None:
        points = points[points @ target.support.frame.up > plane]
        if len(points) == 0:
            return None
        need, order = _ranking(goal, mass, center, points)
        if len(order) == 0:
            return None
        for start in range(0, len(order), _BATCH):
            idx = order[start:start + _BATCH]
            pts, scale = points[idx], sizes(need[idx])
            probes = (pts[:, None, :] + scale[:, None, None] * outline[None]).reshape(-1, dim)
            if density is None:
                probes = pts
            inside = region.contains(probes, -clearance).reshape(len(idx), -1).all(axis=1)
            if inside.any():
                k = idx[np.argmax(inside)]
                return float(need[k]), points[k]
        return None

    found = best(_grid(lo, hi, n))
    if found is None:
        raise TargetNotMet(
            "no ballast inside the body meets the target: its support is too narrow for it "
            "(the centre of mass would have to be beyond the support's edge"
            + (", or the ballast does not fit)" if density is not None else ")"))
    for _ in range(_REFINE_ROUNDS):
        step = spacing
        spacing = spacing / 4
        local = _grid(found[1] - step, found[1] + step, 8)
        better = best(np.concatenate((local, found[1][None])))
        if better is not None and better[0] <= found[0]:
            found = better
    need, point = found
    if density is None:
        exact = _hull_optimum(region, goal, mass, center)
        if exact is not None and exact[0] <= need:
            need, point = exact
        return BallastPlan(need, point)
    volume = need / density
    return BallastPlan(need, point, density, volume, "square" if dim == 2 else shape,
                       _dimensions(shape, dim, volume, depth), depth)


def ballast_body(plan: BallastPlan, target: Target):
    """The ballast as a body in the target's frame: a particle, or its shape of its
    material centred at the plan's point."""
    from ..bodies.particles import ParticleSystem
    from ..bodies.primitives import box, cylinder, rectangle

    if plan.shape is None:
        return ParticleSystem([plan.mass], [plan.point], name="ballast")
    rotation = _frame_matrix(target)
    if plan.shape == "square":
        (s,) = plan.dimensions
        local = rectangle(s, s, density=plan.density, thickness=plan.depth)
        local = local.translated([-s / 2, -s / 2])
    elif plan.shape == "cylinder":
        r, h = plan.dimensions
        local = cylinder(r, h, density=plan.density).translated([0.0, 0.0, -h / 2])
    else:
        (a,) = plan.dimensions
        local = box(a, a, a, density=plan.density).translated([-a / 2] * 3)
    return local.transformed(rotation, plan.point)
