"""Hollowing: empty part of a body's interior so that it stands.

Why it is nearly linear (Prévost et al., *Make It Stand*, 2013): the interior — what
lies deeper than the wall thickness, the inward offset (:mod:`plumbob.bodies.offset`)
— may be emptied anywhere. Emptying a piece of mass ``m_i`` at ``c_i`` adds ``−m_i`` at
``c_i``, so every row of a stability target
(:class:`plumbob.balance.targets.Target`: ``M·slack(c) + Σ m_j·slack(p_j) ≥ 0``) is
linear in what is emptied, and over the interior cut into cells
(:mod:`plumbob.balance.cells`) the continuous relaxation is a linear program
(:mod:`plumbob.balance.relax`). Its optimum is a **threshold carve**: the cells on one
side of a plane — the overhanging side — emptied, the rest kept.

So the carve is a plane cut of the interior, and it is taken exactly: the relaxation
gives the bound at the cell size and the plane's direction, and the plane is then
refined on the interior's own mesh (:mod:`plumbob.balance.search`) — the continuous
limit, no cells left to round. That gives

* **the bound**: the best margin (or tilt, or least slack) any carve keeping the walls
  reaches (:class:`HollowBound`); a target beyond it is refused with the bound stated;
* **the carve**: the plane that meets the target emptying the least material
  (``lightest``: the most). The void is the interior beyond the plane, one boolean
  (manifold3d): the carved body is a closed 2-manifold with an inner shell, and every
  piece of the void reaches the interior's surface (where a drain hole may go).

What the plan predicts is checked where it matters: :func:`write_hollow` writes both
meshes, reads the carved one back and measures its mass properties and its stability
from the file, as ``plumbob check`` would.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..bodies.base import Body
from ..bodies.offset import InwardOffset, manifold_triangles
from ..bodies.solid import MeshSolid
from ..errors import GeometryError, TargetNotMet
from ..massprops import MassProperties
from ..results import Key, Result
from ..tolerances import size_of
from .cells import grid_cells
from .interior import carving_interior
from .relax import best_relaxed, least_relaxed
from .search import Carver, Cut

__all__ = ["HollowBound", "HollowResult", "Hollowing", "WrittenHollow", "hollow",
           "hollow_bound", "write_hollow", "CELLS_ALONG"]

#: the relaxation's default cell size is the interior's longest extent over this
CELLS_ALONG = 16


@dataclass(frozen=True, eq=False, repr=False)
class HollowBound(Result):
    """The best any carve keeping the walls reaches.

    measure: ``"margin"`` (m), ``"critical_tilt_deg"`` (degrees) or ``"slack"`` (m, the
        least slack of a target's rows): what ``value`` and ``relaxed`` are.
    value: the best of any carve, by exact plane cuts of the interior (the continuous
        limit of the relaxation).
    relaxed: the same from the linear-programming relaxation at the cell size.
    cell_size: m, the relaxation's cells.
    wall: m.
    normal, offset: the best cut: the interior where ``normal · p ≥ offset`` emptied.
    """

    measure: str
    value: float
    relaxed: float
    cell_size: float
    wall: float
    normal: np.ndarray
    offset: float

    _repr_fields = ("measure", "value", "relaxed")

    #: the keys of ``bound`` in ``plumbob balance --wall --json``
    KEYS = (
        Key("measure", "", "`margin`, `critical_tilt_deg` or `slack`: what the values are"),
        Key("value", "m, °", "the best of any carve, by exact plane cuts of the interior"),
        Key("relaxed", "m, °", "the same from the relaxation at the cell size"),
        Key("cell_size", "m", "the relaxation's cells"),
        Key("wall", "m", "the wall thickness"),
        Key("normal", "", "the best cut: the interior where normal · p ≥ offset emptied"),
        Key("offset", "m", "the best cut's offset"),
    )

    def sentence(self) -> str:
        """The bound in words: ``the best any carve with 2 mm walls reaches is …``."""
        if self.measure == "critical_tilt_deg":
            what = f"a critical tilt of {self.value:.3g}°"
        elif self.measure == "margin":
            what = f"a margin of {_length(self.value)}"
        else:
            what = f"a least slack of {_length(self.value)} (the target's rows)"
        return f"the best any carve with {_length(self.wall)} walls reaches is {what}"


def _length(value: float) -> str:
    """A length for a sentence: in mm below a metre (``3.4 mm``), else m."""
    return f"{value * 1e3:.3g} mm" if abs(value) < 1 else f"{value:.4g} m"


@dataclass(frozen=True, eq=False, repr=False)
class HollowResult(Result):
    """A hollowing plan: the plane cut of the interior that is emptied, and the bodies it gives.

    carved: the body less the void (a mesh with an inner shell), or the body's own mesh
        when nothing need be emptied.
    void: the emptied part of the interior (None when nothing is).
    wall: m, the wall thickness asked for (the walls are at least this thick).
    offset: the interior's inward offset (how it was made, its error).
    bound: the best any carve reaches (:class:`HollowBound`).
    cut: the cut emptied (None when nothing is): ``cut.normal`` (3,), ``cut.offset`` m.
    before, after: mass properties of the body's mesh (a curved body's faceting, 256
        segments per turn) and of the carved body, as planned.
    target_met: whether the carved body's centre meets every row of the target.
    lightest: whether the most material was removed (else the least).
    pieces: how many separate pieces the void has (each reaches the interior's surface,
        where a drain hole may go).
    seconds: s, the time the plan took.
    """

    carved: MeshSolid
    void: MeshSolid | None
    wall: float
    offset: InwardOffset
    bound: HollowBound
    cut: Cut | None
    before: MassProperties
    after: MassProperties
    target_met: bool
    lightest: bool = False
    pieces: int = 0
    seconds: float = 0.0

    _repr_fields = ("wall", "target_met", "lightest")

    @property
    def removed_mass(self) -> float:
        """kg taken out."""
        return self.before.mass - self.after.mass

    @property
    def cut_dict(self) -> dict[str, Any] | None:
        """The cut emptied as ``normal`` and ``offset`` (m), or None."""
        return None if self.cut is None else {"normal": self.cut.normal,
                                              "offset": self.cut.offset}

    #: the keys of ``hollow`` in ``plumbob balance --wall --json`` (SI)
    KEYS = (
        Key("wall", "m", "the wall thickness asked for"),
        Key("mass_before", "kg", "the body's mass", attr="before.mass"),
        Key("mass_after", "kg", "the carved body's", attr="after.mass"),
        Key("removed_mass", "kg", "what was taken out"),
        Key("center_of_mass_before", "m", "the body's centre of mass",
            attr="before.center_of_mass"),
        Key("center_of_mass_after", "m", "the carved body's", attr="after.center_of_mass"),
        Key("target_met", "", "whether the carved body meets every row of the target"),
        Key("lightest", "", "whether the most material was removed (else the least)"),
        Key("cut", "", "the cut emptied: `normal`, `offset` (m); `null` when nothing is",
            attr="cut_dict"),
        Key("void_pieces", "", "how many separate pieces the void has", attr="pieces"),
        Key("bound", "", "the best any carve reaches (`HollowBound`)"),
        Key("offset", "", "the interior's inward offset: how it was made, its error"),
        Key("seconds", "s", "the time the plan took"),
    )


def _density(body: Body) -> float | None:
    densities = body.densities()
    if len(densities) != 1 or "field" in densities:
        raise GeometryError("hollowing needs a body of one density (carve each part of an "
                            "assembly on its own)")
    density = densities.pop()
    return density if isinstance(density, float) else None


def _measure(target, slack: float) -> tuple[str, float]:
    """What a target's best least slack means: a margin (m) for a margin target, else the
    slack itself (a tilt is measured by :func:`_best_tilt`)."""
    kinds = set(getattr(target, "kinds", ()) or ())
    if kinds == {"margin"} and getattr(target, "margin", None) is not None:
        return "margin", float(target.margin) + slack
    return "slack", slack


class _Problem:
    """A body's interior, cut into cells, ready for the relaxation and the exact search.

    The search runs on ``rough`` (the level set as extracted: fewer triangles, its surface
    within a few hundredths of the step of ``interior``'s), and its answers are finished
    on ``interior`` itself, the one carved."""

    def __init__(self, interior, rough, rho: float, before: MassProperties, cell: float):
        self.cells = grid_cells(rough, cell)
        self.masses = rho * self.cells.volumes
        self.mass, self.centre = before.mass, before.center_of_mass
        self.carver = Carver(manifold_triangles(interior), rho, before.mass,
                             before.center_of_mass)
        self.rough = self.carver if rough is interior else Carver(
            manifold_triangles(rough), rho, before.mass, before.center_of_mass)

    def best(self, target) -> tuple[float, Cut]:
        """The relaxation's best least slack (m), and the exact best cut."""
        relaxed = best_relaxed(self.masses, self.cells.centres, self.mass, self.centre, target)
        cut = self.rough.best(target, relaxed.normal)
        return relaxed.value, self.carver.best_along(target, cut.normal)

    def least(self, target, safety: float, lightest: bool, best: Cut) -> Cut | None:
        relaxed = least_relaxed(self.masses, self.cells.centres, self.mass, self.centre,
                                target, safety)
        start = relaxed.normal if np.any(relaxed.normal) else best.normal
        cut = self.rough.least(target, start, safety, lightest, best)
        found = None if cut is None else self.carver.least_along(target, cut.normal, safety,
                                                                 lightest)
        return found or self.carver.least_along(target, best.normal, safety, lightest)


def _best_tilt(problem: _Problem, target, found: tuple[float, Cut]) -> tuple[float, float, Cut]:
    """The best critical tilt (degrees) of any carve, relaxed and exact, by bisection on the
    tilt: the largest at which the best least slack is still ≥ 0."""
    from .targets import target_for

    def at(angle: float) -> tuple[float, Cut]:
        return problem.best(target_for(None, require_tilt_deg=float(np.degrees(angle)),
                                       support=target.support))

    results = []
    for pick in (0, 1):  # the relaxed bound, then the exact one
        lo, hi = 0.0, float(np.radians(target.require_tilt_deg))
        value = found[pick] if pick == 0 else found[1].slack
        if value >= 0:
            lo, hi = hi, np.pi / 2 - 1e-6
        for _ in range(30):
            mid = 0.5 * (lo + hi)
            value = at(mid)[pick] if pick == 0 else at(mid)[1].slack
            lo, hi = (mid, hi) if value >= 0 else (lo, mid)
            if hi - lo < 1e-5:
                break
        results.append(float(np.degrees(lo)))
    return results[0], results[1], at(np.radians(results[1]))[1]


def hollow_bound(problem: _Problem, target, wall: float) -> tuple[HollowBound, Cut]:
    """The best any carve reaches (see :class:`HollowBound`), and the best cut for the
    target's own rows."""
    relaxed, cut = problem.best(target)
    kinds = set(getattr(target, "kinds", ()) or ())
    if kinds == {"tilt"} and getattr(target, "support", None) is not None:
        low, high, best = _best_tilt(problem, target, (relaxed, cut))
        bound = HollowBound("critical_tilt_deg", high, low, problem.cells.size, wall,
                            best.normal, best.offset)
        return bound, cut
    measure, value = _measure(target, cut.slack)
    return HollowBound(measure, value, _measure(target, relaxed)[1], problem.cells.size, wall,
                       cut.normal, cut.offset), cut


def _void(interior, cut: Cut, carver: Carver, target, safety: float):
    """The interior beyond the cut, its separate pieces that the target does not need
    dropped (the smallest first); returns the manifold and how many pieces it has."""
    import manifold3d

    void = interior.trim_by_plane(list(map(float, cut.normal)), float(cut.offset))
    pieces = sorted(void.decompose(), key=lambda piece: piece.volume())
    if len(pieces) > 1:
        from ..integrals.mesh import triangle_soup_moments

        kept = list(pieces)
        first = [triangle_soup_moments(manifold_triangles(p)) for p in pieces]
        moments = [(m.m0, m.m1 + m.m0 * m.origin) for m in first]
        volume = sum(m[0] for m in moments)
        moment = sum(m[1] for m in moments)
        for i in range(len(pieces) - 1):  # never the largest
            v, m1 = volume - moments[i][0], moment - moments[i][1]
            left = carver.mass - carver.density * v
            centre = (carver.moment - carver.density * m1) / left
            if float(np.min(target.slack(centre))) >= safety:
                kept.remove(pieces[i])
                volume, moment = v, m1
        void = manifold3d.Manifold.batch_boolean(kept, manifold3d.OpType.Add)
        pieces = kept
    return void, len(pieces)


def hollow(body: Body, *, wall: float, target, lightest: bool = False,
           cell_size: float | None = None, step: float | None = None,
           best_effort: bool = False) -> HollowResult:
    """Empty part of ``body``'s interior, keeping walls ``wall`` m thick, so that it meets
    ``target``.

    Parameters
    ----------
    body : Body
        A solid of one density (a mesh read from a file, a primitive, a boolean).
    wall : float
        m, positive: the least wall thickness kept everywhere.
    target : Target
        What to meet (:func:`plumbob.balance.targets.target_for`): anything with a
        ``slack(points) -> (k, n)`` linear in the points, whose rows must stay ≥ 0.
    lightest : bool
        Empty as much as the target allows (a light print), not as little.
    cell_size : float, optional
        m, the cells of the relaxation (its bound at that size, and the cut's first
        direction); default the interior's longest extent / 16.
    step : float, optional
        m, the level-set step of the inward offset when it has no closed form (default
        the smaller of wall / 4 and the body's size / 64); the offset is then taken one
        step deeper so its own error never thins a wall.
    best_effort : bool
        When no carve meets the target, return the best carve (``target_met`` False)
        instead of raising — for ballast to make up the rest.

    Returns
    -------
    HollowResult

    Raises
    ------
    StabilityError
        When no carve meets the target: the message states the best any carve reaches.
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

    The least mass goes from the interior's top: a slab from height ``z`` to 0.9 m takes
    ``640 (0.9 − z)`` kg and lowers the centre to 0.45 m when
    ``500 − 320 (0.81 − z²) = 0.45 (1000 − 640 (0.9 − z))``, ``320 z² − 288 z + 50 = 0``:

    >>> z = (288 + np.sqrt(288**2 - 4 * 320 * 50)) / (2 * 320)
    >>> bool(np.isclose(plan.removed_mass, 640 * (0.9 - z), rtol=1e-3))  # aimed a hair inside
    True
    """
    return Hollowing.prepare(body, wall, cell_size=cell_size, step=step).plan(
        target, lightest=lightest, best_effort=best_effort)


class Hollowing:
    """A body's interior made ready to carve (the offset, its cells, its mesh to cut), for
    one target or several (the same body in several poses): :meth:`prepare`, then
    :meth:`plan` — :func:`hollow` does both."""

    def __init__(self, body: Body, wall: float, density, outer_mesh: MeshSolid, own: bool,
                 offset: InwardOffset, interior, problem: _Problem, seconds: float):
        self.body, self.wall, self.density, self.own = body, wall, density, own
        self.outer_mesh, self.before = outer_mesh, outer_mesh.mass_properties()
        self.offset, self.interior, self.problem, self.seconds = (offset, interior, problem,
                                                                  seconds)
        self.size = size_of(outer_mesh.triangles.reshape(-1, 3))

    @classmethod
    def prepare(cls, body: Body, wall: float, *, cell_size: float | None = None,
                step: float | None = None) -> Hollowing:
        """The interior of ``body`` behind walls ``wall`` m thick (see :func:`hollow`)."""
        import time

        clock = time.perf_counter()
        wall = float(wall)
        if not (np.isfinite(wall) and wall > 0):
            raise GeometryError(f"a wall thickness must be a positive length, not {wall!r}")
        if cell_size is not None and not (np.isfinite(cell_size) and cell_size > 0):
            raise GeometryError(f"a cell size must be a positive length, not {cell_size!r}")
        density = _density(body)
        triangles, own = body.surface(256)
        # the plan starts from the mesh that is carved and written (a curved body's
        # faceting), not from the exact body: the written file is what must meet the target
        outer_mesh = MeshSolid(triangles, density)
        before = outer_mesh.mass_properties()
        rho = before.mass / before.measure
        offset, interior, rough = carving_interior(body, wall, step,
                                                   size_of(triangles.reshape(-1, 3)))
        lo, hi = (np.asarray(interior.bounding_box()[:3]),
                  np.asarray(interior.bounding_box()[3:]))
        cell = float(cell_size) if cell_size is not None else float(np.max(hi - lo)) / CELLS_ALONG
        problem = _Problem(interior, rough, rho, before, cell)
        return cls(body, wall, density, outer_mesh, own, offset, interior, problem,
                   time.perf_counter() - clock)

    def plan(self, target, *, lightest: bool = False, best_effort: bool = False) -> HollowResult:
        """The carve that meets ``target`` (see :func:`hollow`)."""
        import time

        clock = time.perf_counter()
        before, wall = self.before, self.wall
        # m of slack: the file's round-off, and the check's contact — more than the ballast
        # plan's own (two contact tolerances, 1e-6 of the size each), so a carve that meets
        # the target needs no ballast after it
        safety = 4e-6 * self.size
        bound, best = hollow_bound(self.problem, target, wall)
        slack = float(np.min(target.slack(before.center_of_mass)))

        def untouched(met: bool) -> HollowResult:
            return HollowResult(self.outer_mesh, None, wall, self.offset, bound, None, before,
                                before, met, lightest, 0,
                                self.seconds + time.perf_counter() - clock)

        if slack >= 0:
            return untouched(True)
        cut = self.problem.least(target, safety, lightest, best) if best.slack >= safety else None
        if cut is None:
            if not best_effort:
                raise TargetNotMet(
                    f"hollowing cannot meet the target: {bound.sentence()}; ask for less, give "
                    "thinner walls (--wall), or add ballast (--wall with --ballast-material "
                    "carves the best and ballasts the rest)")
            if best.slack <= slack:  # no carve does better than none: nothing is emptied
                return untouched(False)
            cut = best
        void_manifold, pieces = _void(self.interior, cut, self.problem.carver, target,
                                      safety if best.slack >= safety else -np.inf)
        if void_manifold.is_empty():
            return untouched(False)
        import manifold3d

        outer = self.outer_mesh.to_geometry() if self.own else self.body.to_geometry(256)
        carved_manifold = outer - void_manifold
        if carved_manifold.status() != manifold3d.Error.NoError or carved_manifold.is_empty():
            raise GeometryError(f"the carved body could not be built ({carved_manifold.status()})")
        carved = MeshSolid(manifold_triangles(carved_manifold), self.density)
        void = MeshSolid(manifold_triangles(void_manifold), self.density)
        after = carved.mass_properties()
        met = bool(np.all(np.asarray(target.slack(after.center_of_mass)) >= -safety / 2))
        return HollowResult(carved, void, wall, self.offset, bound, cut, before, after, met,
                            lightest, pieces, self.seconds + time.perf_counter() - clock)


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

    @property
    def removed_mass(self) -> float:
        """kg taken out, by the body read back from ``out``."""
        return self.plan.before.mass - self.mass_properties.mass

    #: the plan's keys (those after the carving measured from the file), then the files
    #: and the check of the body read back
    KEYS = (
        *(replace(k, attr=f"plan.{k.attr or k.name}") if k.name not in (
            "mass_after", "center_of_mass_after", "removed_mass") else replace(
            k, doc=k.doc + ", read back from the file",
            attr={"mass_after": "mass_properties.mass",
                  "center_of_mass_after": "mass_properties.center_of_mass",
                  "removed_mass": "removed_mass"}[k.name])
          for k in HollowResult.KEYS),
        Key("out", "", "the carved body's file"),
        Key("void", "", "the void's file (`null`: not asked for, or nothing emptied)"),
        Key("verdict", "", "plumbob's check of the body read back", attr="verdict.verdict"),
        Key("margin", "m", "its margin", attr="verdict.margin"),
        Key("critical_tilt_deg", "°", "its critical tilt", attr="verdict.critical_tilt_deg"),
    )


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
