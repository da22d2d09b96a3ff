"""Will it stand under applied loads? Moments about the support's edges.

The seed's reasoning (section 2.2), with forces: a body on a plane tips about an edge
of its support when the moments about that edge of everything pulling and pushing on
it — its weight, forces, hung masses — turn it outward. About an edge through ``a``
with outward horizontal normal ``n`` (``u`` the plane's upward normal), a force ``F``
at ``p`` has the moment

    M = (u · r)(n · F) − (u · F)(n · r),    r = p − a

(``(u × n) · (r × F)`` by the Binet–Cauchy identity; positive turns the body over the
edge): a horizontal push ``F`` at height ``h`` gives ``F h``, a weight ``W`` a distance
``d`` inside the edge ``−W d``. Per edge the **overturning moment** is the sum of the
positive moments, the **resisting moment** the sum of the negative ones (as
magnitudes), and the **factor of safety against overturning** their ratio, resisting /
overturning: the body tips over an edge whose factor is below 1. The critical edge is
the one with the least factor. With a convex support this is exact: the contact
pressure stays on the support if and only if no edge's net moment is positive (and the
loads press the body onto the plane: else it ``lifts``).

On a plane tilted by θ, gravity (the body's weight and every hung mass) leans by θ
toward the descending direction; without a direction given, each edge is judged with
the plane descending toward it, the worst way. With friction μ the body slides when the
force along the plane exceeds μ times the force onto it; growing the applied loads
from nothing, it **slides first** when that happens before the net moment about an edge
turns positive.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from ..errors import StabilityError
from ..loads import Force, Hang, Press, Push
from ..results import Key, Result
from .reach import corners_below, surface_facets
from .requirement import Requirement
from .support import Support

__all__ = ["LoadMoment", "LoadVerdict", "EdgeMoments", "edge_moments", "under_loads",
           "VERDICT_KEY"]

#: how a check's verdict shows this criterion's answer (``Verdict.KEYS`` ends with it)
VERDICT_KEY = Key("under_loads", "", "the verdict under applied loads (see below)",
                  "with loads", attr="loaded")


@dataclass(frozen=True, repr=False)
class LoadMoment(Result):
    """One load and its moment about the critical edge.

    name: the load's name (``"weight"`` for the body's own).
    kind: ``"weight"``, ``"force"``, ``"hang"``, ``"push"`` or ``"press"``.
    at: (dim,) m, body frame: where it acts (for a push or press, the worst point found).
    force: (dim,) N, body frame (for a push, the worst direction found).
    moment: N·m about the critical edge, positive when it overturns.
    outside: whether its point lies outside the body (a handle, a fixture).
    """

    name: str
    kind: str
    at: np.ndarray
    force: np.ndarray
    moment: float
    outside: bool = False

    #: the keys of each of ``under_loads``' ``loads``
    KEYS = (
        Key("name", "", "the load's name (`weight` for the body's own)", type="str"),
        Key("kind", "", "`weight`, `force`, `hang`, `push` or `press`", type="str"),
        Key("at", "m", "where it acts, body frame (a push's or press's worst point)",
            type="xyz"),
        Key("force", "N", "the force, body frame", type="xyz"),
        Key("moment", "N·m", "its moment about the critical edge, positive when it "
                             "overturns", type="float"),
        Key("outside", "", "whether its point lies outside the body", type="bool"),
    )


@dataclass(frozen=True, repr=False)
class LoadVerdict(Result):
    """Whether the body stands under its loads, and by what factor.

    verdict: ``"stands"``, ``"topples"``, ``"slides"`` (with friction, before it
        tips), ``"lifts"`` (the loads pull it off the plane) or ``"neutral"``
        (balanced on the critical edge).
    edge_start, edge_end: (dim,) m, body frame: the critical edge (equal for a lamina's
        corner, or the end of a line of contact).
    edge_normal: (dim,) its outward horizontal unit normal, body frame.
    resisting_moment, overturning_moment: N·m about the critical edge (magnitudes).
    overturning_safety_factor: resisting / overturning moment; None when nothing
        overturns. Below 1 it topples.
    load_factor: how many times the applied loads (all but the body's own weight) may
        be multiplied before it tips; None when they never tip it.
    moments: each load's moment about the critical edge, the body's weight first.
    normal_force: N, the force pressing the body onto the plane.
    tangential_force: N, the force along the plane friction must hold.
    friction: the friction coefficient, or None.
    slides: whether it slides under the loads (None without friction).
    slides_first: whether, the loads growing from nothing, it slides before it tips
        (None without friction).
    tilt_deg: the plane's tilt, degrees (None: level); tilt_direction: (dim,) the
        horizontal unit vector it descends toward.
    notes: what to know about the answer (points outside the body, faceted surfaces).
    """

    verdict: str
    edge_start: np.ndarray
    edge_end: np.ndarray
    edge_normal: np.ndarray
    resisting_moment: float
    overturning_moment: float
    overturning_safety_factor: float | None
    load_factor: float | None
    moments: tuple[LoadMoment, ...]
    normal_force: float
    tangential_force: float
    friction: float | None = None
    slides: bool | None = None
    slides_first: bool | None = None
    tilt_deg: float | None = None
    tilt_direction: np.ndarray | None = None
    notes: tuple[str, ...] = ()

    _repr_fields = ("verdict", "overturning_safety_factor", "resisting_moment",
                    "overturning_moment", "edge_normal")

    @property
    def stands(self) -> bool:
        """Whether the verdict under the loads is ``"stands"``."""
        return self.verdict == "stands"

    @property
    def critical_edge(self) -> dict[str, np.ndarray]:
        """The critical edge's ``start``, ``end`` and ``normal`` (m, body frame)."""
        return {"start": self.edge_start, "end": self.edge_end, "normal": self.edge_normal}

    #: the keys of the ``under_loads`` object of ``plumbob check --json``
    KEYS = (
        Key("verdict", "", "`stands`, `topples`, `slides`, `lifts` or `neutral`", type="str"),
        Key("stands", "", "whether it stands under the loads", type="bool"),
        Key("critical_edge", "m", "`start`, `end`, `normal` of the edge it tips over"),
        Key("resisting_moment", "N·m", "about the critical edge", type="float"),
        Key("overturning_moment", "N·m", "about the critical edge", type="float"),
        Key("overturning_safety_factor", "", "resisting / overturning (`null` when nothing "
                                             "overturns)", type="float"),
        Key("load_factor", "", "how many times the applied loads may grow before it tips "
                               "(`null`: never)", type="float"),
        Key("normal_force", "N", "the force pressing it onto the plane", type="float"),
        Key("tangential_force", "N", "the force along the plane friction must hold",
            type="float"),
        Key("loads", "", "per load: `name`, `kind`, `at`, `force`, `moment`, `outside`",
            attr="moments"),
        Key("friction", "", "the friction coefficient", "with `--friction MU`", type="float"),
        Key("slides", "", "whether it slides under the loads", "with `--friction MU`",
            type="bool"),
        Key("slides_first", "", "whether, the loads growing, it slides before it tips",
            "with `--friction MU`", type="bool"),
        Key("tilt_deg", "°", "the plane's tilt", "with `--tilt DEG`", type="float"),
        Key("tilt_direction", "", "the horizontal unit vector the plane descends toward",
            "with `--tilt DEG`", type="xyz"),
        Key("notes", "", "points outside the body, faceted surfaces", "when there are any",
            type="strings"),
    )


def _moments(points: np.ndarray, forces: np.ndarray, starts: np.ndarray, normals: np.ndarray,
             up: np.ndarray) -> np.ndarray:
    """Moments (L, m), N·m, of forces (L, m, dim) at points (L, m, dim) about the m edges
    through ``starts`` (m, dim) with outward normals (m, dim); positive overturns."""
    r = points - starts[None]
    return (np.einsum("lmd,d->lm", r, up) * np.einsum("lmd,md->lm", forces, normals)
            - np.einsum("lmd,d->lm", forces, up) * np.einsum("lmd,md->lm", r, normals))


def _gravity(sup: Support, req: Requirement, normals: np.ndarray) -> tuple[np.ndarray, Any]:
    """The acceleration of gravity per edge (m, dim), m/s², with the plane's tilt: toward
    the requirement's direction, or toward each edge (the worst way); and that
    direction (None on level ground, (dim,) or per edge (m, dim))."""
    down = sup.frame.down
    if not req.tilt_deg:
        return np.broadcast_to(req.g * down, normals.shape).copy(), None
    theta = np.radians(req.tilt_deg)
    way = normals if req.toward_deg is None else np.broadcast_to(
        sup.frame.direction(req.toward_deg), normals.shape)
    return req.g * (np.cos(theta) * down + np.sin(theta) * way), way


def _placed(body, loads, sup: Support, starts: np.ndarray, normals: np.ndarray
            ) -> tuple[dict[int, tuple[np.ndarray, np.ndarray]], list[str]]:
    """The worst point and force, per edge, of every push and press: {index: (points (m,
    dim), forces (m, dim))}, and the notes."""
    searches = [(i, load) for i, load in enumerate(loads) if isinstance(load, (Push, Press))]
    if not searches:
        return {}, []
    up = sup.frame.up
    floor = float(up @ sup.plane_point)
    facets, exact = surface_facets(body)
    notes = [] if exact else [
        "the worst points were searched on the curved surface cut into 128 facets a turn"]
    tol = sup.tolerance
    placed = {}
    for i, load in searches:
        corners = corners_below(facets, up, floor, load.max_height)
        heights = corners @ up - floor
        reach = normals @ corners.T  # (m, k)
        if isinstance(load, Push):
            top = heights.max()
            # at the highest corner, the one furthest back from the edge (pushed toward it)
            score = np.where(heights >= top - tol, -reach, -np.inf)
            forces = load.force * normals
        else:
            far = reach.max(axis=1, keepdims=True)
            score = np.where(reach >= far - tol, heights[None, :], -np.inf)
            forces = np.broadcast_to(-load.force * up, normals.shape).copy()
        placed[i] = (corners[np.argmax(score, axis=1)], forces)
    return placed, notes


def _first_slide(h_w: np.ndarray, n_w: float, h_l: np.ndarray, n_l: float,
                 mu: float) -> float:
    """The least λ ≥ 0 at which ``|h_w + λ h_l| > μ (n_w + λ n_l)`` (it slides), or inf."""
    a = h_l @ h_l - mu * mu * n_l * n_l
    b = 2 * (h_w @ h_l - mu * mu * n_w * n_l)
    c = h_w @ h_w - mu * mu * n_w * n_w
    if c > 0:
        return 0.0
    if abs(a) < 1e-300:
        roots = [-c / b] if b > 0 else []
    else:
        disc = b * b - 4 * a * c
        roots = [] if disc < 0 else [(-b - np.sqrt(disc)) / (2 * a), (-b + np.sqrt(disc)) / (2 * a)]
    roots = [r for r in roots if r >= 0 and n_w + r * n_l > 0]
    return float(min(roots)) if roots else float("inf")


class EdgeMoments(NamedTuple):
    """Every force's moment about every support edge (see :func:`edge_moments`).

    names, kinds: per force (the body's weight first). points, forces: (L, m, dim), m and
    N, per force and edge (a search's point and force differ by edge). moments: (L, m),
    N·m, positive overturns. starts, ends, normals: (m, dim) the edges (body frame).
    way: the floor's descending direction ((dim,) or per edge), or None when level.
    notes: what to know about the searches.
    """

    names: list
    kinds: list
    points: np.ndarray
    forces: np.ndarray
    moments: np.ndarray
    starts: np.ndarray
    ends: np.ndarray
    normals: np.ndarray
    way: Any
    notes: list


def edge_moments(body, sup: Support, mass: float, req: Requirement) -> EdgeMoments:
    """The moments of the body's weight (``mass`` kg) and of ``req.loads`` about every edge
    of the support ``sup``, with the floor tilted as ``req`` asks."""
    dim = sup.dim
    for load in req.loads:
        if getattr(load, "dim", None) not in (None, dim):
            what = "a lamina (in its own plane)" if dim == 2 else "a solid"
            raise StabilityError(f"the load {load.describe()!r} is given in {load.dim}D but the "
                                 f"body is {what}: give its force and point in {dim}D")
    if len(sup.edge_starts) == 0:
        raise StabilityError("the body rests on a single point: it has no edge to tip over, "
                             "so loads cannot be weighed against it (give another down)")
    frame, up = sup.frame, sup.frame.up
    starts, ends = sup.to_body(sup.edge_starts), sup.to_body(sup.edge_ends)
    normals = frame.from_ground(sup.edge_normals)
    m = len(starts)
    gravity, way = _gravity(sup, req, normals)
    placed, notes = _placed(body, req.loads, sup, starts, normals)
    names, kinds = ["weight"], ["weight"]
    points = [np.broadcast_to(sup.center_of_mass, (m, dim))]
    forces = [mass * gravity]
    for i, load in enumerate(req.loads):
        names.append(load.describe())
        kinds.append(type(load).__name__.lower())
        if i in placed:
            points.append(placed[i][0])
            forces.append(placed[i][1])
        else:
            points.append(np.broadcast_to(load.at, (m, dim)))
            forces.append(np.broadcast_to(load.force, (m, dim)) if isinstance(load, Force)
                          else load.mass * gravity)
    points_arr, forces_arr = np.array(points, dtype=float), np.array(forces, dtype=float)
    moments = _moments(points_arr, forces_arr, starts, normals, up)  # (L, m)
    return EdgeMoments(names, kinds, points_arr, forces_arr, moments, starts, ends, normals,
                       way, notes)


def under_loads(body, sup: Support, mass: float, req: Requirement) -> LoadVerdict:
    """The verdict of ``body`` (``mass`` kg, support ``sup``) under ``req.loads`` (see the
    module's docstring); ``req`` also gives g, the tilt and the friction."""
    em = edge_moments(body, sup, mass, req)
    names, kinds, points_arr, forces_arr, moments = em.names, em.kinds, em.points, em.forces, \
        em.moments
    starts, ends, normals, way, notes = em.starts, em.ends, em.normals, em.way, em.notes
    up = sup.frame.up
    overturning = np.maximum(moments, 0.0).sum(axis=0)
    resisting = np.maximum(-moments, 0.0).sum(axis=0)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        factor = np.where(overturning > 0, resisting / overturning, np.inf)
    k = int(np.argmin(factor)) if np.isfinite(factor).any() else int(
        np.argmax(overturning - resisting))
    # the applied loads alone, grown by λ: the weight's moment W_e + λ L_e turns positive
    weight_m, applied_m = moments[0], moments[1:].sum(axis=0)
    tips = applied_m > 0
    with np.errstate(divide="ignore", over="ignore"):
        lam = np.where(weight_m >= 0, 0.0, -weight_m / np.where(tips, applied_m, 1.0))
    load_factor = float(lam[tips].min()) if tips.any() and len(req.loads) else None
    if load_factor is not None and not np.isfinite(load_factor):
        load_factor = None
    total = forces_arr[:, k].sum(axis=0)
    normal = float(-(total @ up))
    along = total - (total @ up) * up
    tangential = float(np.linalg.norm(along))
    net = float(overturning[k] - resisting[k])
    scale = float(np.abs(forces_arr[:, k]).sum())
    tol = sup.tolerance * scale
    slides = slides_first = None
    if req.friction is not None:
        slides = bool(normal > 0 and tangential > req.friction * normal)
        w = forces_arr[0, k]
        applied = forces_arr[1:, k].sum(axis=0)
        lam_s = _first_slide(w - (w @ up) * up, float(-(w @ up)),
                             applied - (applied @ up) * up, float(-(applied @ up)), req.friction)
        lam_t = load_factor if load_factor is not None else float("inf")
        slides_first = bool(lam_s < lam_t)
    if normal <= tol:
        verdict = "lifts"
    elif slides and (net <= tol or slides_first):
        verdict = "slides"
    elif net > tol:
        verdict = "topples"
    elif net >= -tol:
        verdict = "neutral"
    else:
        verdict = "stands"
    outside = _outside(body, req.loads, sup.tolerance)
    notes += [f"the point of {names[i + 1]!r} lies outside the body (a handle or fixture?)"
              for i in sorted(outside)]
    rows = tuple(LoadMoment(names[j], kinds[j], points_arr[j, k].copy(), forces_arr[j, k].copy(),
                            float(moments[j, k]), (j - 1) in outside)
                 for j in range(len(names)))
    return LoadVerdict(
        verdict, starts[k].copy(), ends[k].copy(), normals[k].copy(), float(resisting[k]),
        float(overturning[k]), float(factor[k]) if np.isfinite(factor[k]) else None,
        load_factor, rows, normal, tangential, req.friction, slides, slides_first,
        req.tilt_deg if req.tilt_deg else None,
        None if way is None else np.array(way[k], dtype=float), tuple(notes))


def _outside(body, loads, tolerance: float) -> set[int]:
    """Indices of the forces and hung masses whose point lies outside the body."""
    fixed = [(i, load.at) for i, load in enumerate(loads) if isinstance(load, (Force, Hang))]
    if not fixed:
        return set()
    contains = getattr(body, "contains", None)
    if not callable(contains):
        return set()
    inside = np.asarray(contains(np.array([p for _, p in fixed]), tolerance), dtype=bool)
    return {i for (i, _), ok in zip(fixed, inside) if not ok}
