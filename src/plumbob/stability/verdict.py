"""Will it stand? The toppling condition, stability margins and tilt limits.

The seed's toppling condition (section 2.2): a body on a horizontal plane
topples if and only if its centre of mass is not vertically above its base —
here, the support polygon (:mod:`plumbob.stability.support`). On top of the
yes/no answer:

* the **static stability margin** (McGhee and Frank): the distance from the foot
  of the centre of mass to the support boundary, negative outside;
* per support edge, the **tipping angle** ``atan(d/h)`` — how far the plane may
  tilt toward that edge before the body goes over it — and the **energy** to tip
  it over the edge, ``Mg(√(d² + h²) − h)`` (Messuri and Klein's energy stability
  margin is the least of these), ``d`` the edge's distance from the foot and
  ``h`` the height of the centre of mass;
* the **critical tilt**: the least tipping angle over every direction, and the
  direction it is reached in (the outward normal of the nearest edge);
* on a plane tilted by θ toward a direction: does it topple (θ above the tipping
  angle in that direction), and with friction coefficient μ does it slide first
  (``μ < s/h``, ``s`` the distance to the boundary along that direction)?
* a design check over every direction, as product-safety standards require
  (IEC 62368-1 and IEC 60065: no overturning when tilted 10° in any direction).

Verdicts: ``"stands"`` (margin above the contact tolerance), ``"topples"``
(below minus the tolerance), ``"neutral"`` (the centre of mass over the
support's boundary: a cylinder on its side in the rolling direction, a sphere,
a box balanced on an edge; whether a curved body then rocks back or rolls away
depends on its curvature, which this verdict does not judge).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..arguments import answering, finite_result, instance
from ..errors import StabilityError
from ..massprops import MassProperties
from ..results import Key, Result, Source
from ..tolerances import sampling_tolerance
from ..units import SEED_GRAVITY
from .checks import DesignCheck, SlopeCheck, slope_check, tipping_toward
from .keys import VERDICT_KEYS
from .loaded import VERDICT_KEY as LOADED_KEY
from .loaded import LoadVerdict
from .requirement import Requirement
from .rocking import rocking
from .rocking_result import Rocking
from .support import Support, contact_kind, hull_points, is_polytope, support_polygon
from .tipping import tipping_angle_deg, tipping_angles_deg

if TYPE_CHECKING:  # the settling loads the poses: only for a point, a line or a sliver
    from .poses.settling import Settling

__all__ = [
    "DesignCheck",
    "EdgeGroup",
    "TippingEdge",
    "SlopeCheck",
    "Verdict",
    "check",
    "verdict_from_support",
]


@dataclass(frozen=True, repr=False)
class TippingEdge(Result):
    """One edge of the support boundary a body can tip over.

    start, end: the edge's ends, points of the plane in the body frame (dim,) m
        (equal for the end of a segment or of a lamina's interval).
    normal: outward horizontal unit normal, body frame (dim,).
    distance: signed distance from the foot of the centre of mass to the edge's line, m.
    tipping_angle_deg: ``atan(distance / h)``, degrees.
    energy: ``Mg(√(d² + h²) − h)``, J (0 for an edge the centre of mass is already beyond).
    """

    start: np.ndarray
    end: np.ndarray
    normal: np.ndarray
    distance: float
    tipping_angle_deg: float
    energy: float

    #: the keys of each of ``plumbob check --json``'s ``edges``
    KEYS = (
        Key("start", "m", "the edge's first end, body frame", type="xyz"),
        Key("end", "m", "its other end", type="xyz"),
        Key("normal", "", "its outward horizontal unit normal", type="xyz"),
        Key("distance", "m", "from the foot of the centre of mass to the edge's line, signed",
            type="float"),
        Key("tipping_angle_deg", "°", "atan(distance / h): the tilt that tips it over the edge",
            type="float"),
        Key("energy", "J", "Mg(√(d² + h²) − h), the energy to tip it over", type="float"),
    )


#: an edge shorter than this share of the support's perimeter may be part of an arc
_ARC_EDGE_SHARE = 1 / 16
#: consecutive short edges turning by less than this (degrees) run along one arc
_ARC_TURN_DEG = 30.0
#: an arc has at least this many edges
_ARC_MIN_EDGES = 3


@dataclass(frozen=True, repr=False)
class EdgeGroup(Result):
    """Support edges as a report lists them: one edge, or an ``"arc"`` — a run of short
    edges of a round base turning a little each (a tessellated circle's 64 edges are
    one thing to tip over, not 64).

    kind: ``"edge"`` or ``"arc"``.
    start, end: (dim,) m, body frame: the first edge's start and the last edge's end.
    count: the number of edges in the group.
    normal: (dim,) the outward normal of its weakest edge.
    distance, tipping_angle_deg, energy: its weakest edge's (m, degrees, J).
    """

    kind: str
    start: np.ndarray
    end: np.ndarray
    count: int
    normal: np.ndarray
    distance: float
    tipping_angle_deg: float
    energy: float


def _arc_runs(starts: np.ndarray, ends: np.ndarray, normals: np.ndarray) -> list[np.ndarray]:
    """Indices of the edges of a closed polygon in runs: each arc's edges, in order, and
    every other edge alone."""
    n = len(starts)
    lengths = np.linalg.norm(ends - starts, axis=1)
    short = lengths < _ARC_EDGE_SHARE * lengths.sum()
    cos = np.einsum("ij,ij->i", normals, np.roll(normals, -1, axis=0))
    link = short & np.roll(short, -1) & (cos > np.cos(np.radians(_ARC_TURN_DEG)))
    if link.all():  # a whole circle
        return [np.arange(n)]
    first = int(np.argmin(link)) + 1  # start just after a break
    order = (np.arange(n) + first) % n
    # edge order[k] begins a new run unless the edge before it links to it
    begins = ~link[np.roll(order, 1)]
    runs = np.split(order, np.flatnonzero(begins)[1:])  # begins[0]: order starts after a break
    split: list[np.ndarray] = []
    for run in runs:
        split += [run] if len(run) >= _ARC_MIN_EDGES else [np.array([i]) for i in run]
    return split


@dataclass(frozen=True, repr=False)
class Verdict(Result):
    """Whether a body stands on a horizontal plane, and how far from toppling it is.

    Four concerns, each in its place: how it stands on level ground (the fields below
    down to ``rocking``), what it was asked (``requirement``: orientation, g, tilt,
    friction, design checks, loads), the tilted plane (``slope``) and the design checks
    (``design``).

    verdict: ``"stands"``, ``"topples"`` or ``"neutral"``.
    margin: static stability margin (McGhee and Frank), m, negative when the foot of
        the centre of mass lies outside the support.
    critical_tilt_deg: the least tilt of the plane, over every direction, that topples
        it, degrees; 0 when neutral, negative when it topples already.
    critical_direction: the horizontal unit vector (body frame) it topples toward
        first — or the way it falls when it topples.
    energy_to_topple: the least energy to tip it over an edge, J (Messuri and Klein).
    com_height: height of the centre of mass above the plane, m.
    center_of_mass: (dim,) m, body frame.
    mass: kg.
    support: the support polygon and its edges.
    edges: per edge, the tipping angle and energy.
    rocking: for a body over a point or line of a curved surface, how it rocks.
    requirement: what was asked (g, m/s², is ``requirement.g``).
    slope: the check on a tilted plane, when asked for.
    design: the design checks, when asked for.
    settling: set down on a point, a line or a sliver, where it comes to rest (see
        :mod:`~plumbob.stability.settled`; the other fields are where it rests if it stays).
    """

    verdict: str
    margin: float
    critical_tilt_deg: float
    critical_direction: np.ndarray
    energy_to_topple: float
    com_height: float
    center_of_mass: np.ndarray
    mass: float
    support: Support
    edges: tuple[TippingEdge, ...]
    rocking: Rocking | None = None
    requirement: Requirement = Requirement()
    slope: SlopeCheck | None = None
    design: DesignCheck | None = None
    settling: Settling | None = None
    loaded: LoadVerdict | None = None
    source: Source | None = field(default=None, compare=False)

    _repr_fields = ("verdict", "margin", "critical_tilt_deg", "critical_direction",
                    "energy_to_topple", "com_height", "mass", "passes")

    @property
    def g(self) -> float:
        """Gravitational acceleration, m/s²."""
        return self.requirement.g

    @property
    def friction(self) -> float | None:
        """The friction coefficient, when given."""
        return self.requirement.friction

    @property
    def slides_first(self) -> bool | None:
        """With friction, whether it slides before it topples whichever way the plane is
        tilted (``μ < margin / h``) — or along the slope's direction."""
        if self.friction is None:
            return None
        if self.slope is not None:
            return self.slope.slides_first
        return bool(self.verdict == "stands"
                    and self.friction < np.tan(np.radians(self.critical_tilt_deg)))

    @property
    def required_tilt_deg(self) -> float | None:
        """The tilt it must withstand in every direction, degrees, when asked."""
        return self.requirement.require_tilt_deg

    @property
    def passes(self) -> bool | None:
        """The tilt design check: it stands and its critical tilt is at least the required
        one (None when not asked)."""
        return None if self.design is None else self.design.passes

    @property
    def required_margin(self) -> float | None:
        """The static stability margin it must have, m, when asked."""
        return self.requirement.margin

    @property
    def margin_passes(self) -> bool | None:
        """The margin design check: it stands with at least the required margin."""
        return None if self.design is None else self.design.margin_passes

    @property
    def meets_requirement(self) -> bool | None:
        """Whether every design check asked is met, and it stands under its loads (None
        when nothing is asked)."""
        asked = [] if self.design is None or self.design.met is None else [self.design.met]
        if self.loaded is not None:
            asked.append(self.loaded.stands)
        return all(asked) if asked else None

    @property
    def stands(self) -> bool:
        """Whether the verdict is ``"stands"``."""
        return self.verdict == "stands"

    @property
    def down(self) -> np.ndarray:
        """The direction of gravity in the body's frame, unit vector (dim,)."""
        return self.support.frame.down

    @property
    def overhang(self) -> float | None:
        """For a body that topples: how far its centre's foot lies beyond the support, m."""
        return -self.margin if self.verdict == "topples" else None

    @property
    def over_by_deg(self) -> float | None:
        """For a body that topples: the tilt by which it is over, ``atan(overhang / h)``,
        degrees (the plane would have to tilt this much the other way to hold it)."""
        return -self.critical_tilt_deg if self.verdict == "topples" else None

    @property
    def shortfall_deg(self) -> float | None:
        """For a failed design check: how many degrees the critical tilt falls short of the
        required one (for a body that topples, the required tilt plus how far it is over)."""
        if self.passes is not False:
            return None
        return float(self.required_tilt_deg - self.critical_tilt_deg)

    def edge_groups(self) -> list[EdgeGroup]:
        """The support's edges grouped for a report (runs of short edges of a round base as
        one arc), weakest first."""
        sup = self.support
        if not self.edges:
            return []
        if sup.kind == "polygon" and sup.dim == 3:
            runs = _arc_runs(sup.edge_starts, sup.edge_ends, sup.edge_normals)
        else:
            runs = [np.array([i]) for i in range(len(self.edges))]
        groups = []
        for run in sorted(runs, key=lambda r: int(r[0])):
            weakest = self.edges[run[np.argmin([self.edges[i].distance for i in run])]]
            groups.append(EdgeGroup("arc" if len(run) > 1 else "edge", self.edges[run[0]].start,
                                    self.edges[run[-1]].end, len(run), weakest.normal,
                                    weakest.distance, weakest.tipping_angle_deg,
                                    weakest.energy))
        return sorted(groups, key=lambda g: g.distance)

    #: the keys of :meth:`as_dict`, in order: :mod:`.keys`', then each criterion's own
    #: (declared beside its answer); docs/cli.md's check table is made from them
    KEYS = VERDICT_KEYS + (LOADED_KEY,)

    @property
    def summary(self) -> str:
        """The verdict in words, with where it settles: ``"stands (settles 0.05° into pose
        3)"``, ``"topples (rolls 80° onto pose 2, where it stands, critical tilt 45°)"``."""
        return self.verdict + ("" if self.settling is None else f" ({self.settling.phrase})")

    def plot(self, ax=None, *, body=None, **options):
        """Draw the verdict (with ``body``'s outline if given); returns the matplotlib figure.
        See :func:`plumbob.plot.plot_check`."""
        from ..plot.check import plot_check

        return plot_check(self, body, ax, **options)

    def _repr_png_(self) -> bytes:  # notebooks show the picture
        from ..plot.files import png_bytes

        return png_bytes(self.plot())

    def text(self, units=None, *, edges: int | None = 4, solution=None, standard=None) -> str:
        """The report ``plumbob check`` prints (``str(verdict)``): lengths and masses in
        ``units`` (a :class:`~plumbob.report.ReportUnits` or ``"mm,g"``; default the
        part's own, from its :class:`~plumbob.results.Source`, else SI), the ``edges``
        weakest tipping edges (None: all), a parameter ``solution``'s line and a
        ``standard``'s bundle."""
        from ..report import units_for
        from ..report.check import check_text

        s = self.source or Source()
        kind = s.kind or ("lamina" if self.support.frame.dim == 2 else "solid")
        return check_text(self, s.path or "body", kind, s.notes, units_for(units, s.length_unit),
                          edges=edges, solution=solution, standard=standard)

    def tipping_angle_deg(self, direction) -> float:
        """The tilt, degrees, that topples the body when the plane descends toward the
        horizontal ``direction`` (body frame, (dim,)); ≤ 0 when it does not stand."""
        return tipping_toward(self.support, self.verdict, self.margin, self.rocking, direction)

    def tipping_over_deg(self, direction) -> float:
        """The tilt, degrees, that tips it over the edge it faces, the plane descending toward
        ``direction`` (body frame): :meth:`tipping_angle_deg`, but on a line it rolls across
        the tilt over the line's ends (:func:`~.settled.tipping_over_line`)."""
        sup = self.support
        if not (sup.kind == "segment" and sup.dim == 3 and self.verdict == "neutral"):
            return self.tipping_angle_deg(direction)
        from .settled import tipping_over_line

        return tipping_over_line(sup, direction)

    @property
    def rolls(self) -> str | None:
        """How a neutral body rolls: ``"across its line"`` or ``"every way"`` (else None)."""
        if self.verdict == "neutral":
            return "across its line" if self.support.kind == "segment" else "every way"
        return None


def _energy(weight: float, d: np.ndarray | float, h: float) -> np.ndarray:
    d = np.maximum(np.asarray(d, dtype=float), 0.0)
    # √(d² + h²) − h without cancellation: d² / (√(d² + h²) + h)
    return weight * d * d / (np.hypot(d, h) + h)


def verdict_from_support(sup: Support, mass: float, requirement: Requirement | None = None,
                         *, rocked: tuple[Rocking, float] | None = None,
                         loaded: LoadVerdict | None = None) -> Verdict:
    """The verdict for a body of ``mass`` kg with support ``sup`` under ``requirement``
    (g, tilted plane, friction, design checks; see :func:`check`).

    rocked: for a body on a curved surface, how it responds to being turned and the
        height noise (m) of its sampling: a centre of mass over a point or line of
        contact then rocks back (stands), rolls (neutral) or topples by curvature.
    loaded: the verdict under the requirement's loads (:func:`~.loaded.under_loads`).
    """
    req = Requirement() if requirement is None else requirement
    h, tol = sup.com_height, sup.tolerance
    frame = sup.frame
    distances = sup.edge_distances
    inside = len(distances) > 0 and bool(np.all(distances >= -tol))
    if inside:
        k = int(np.argmin(distances))
        margin = float(distances[k])
        direction = frame.from_ground(sup.edge_normals[k])
    else:
        margin = -sup.distance_to_boundary()
        nearest = sup.nearest_point()
        away = -nearest
        norm = np.linalg.norm(away)
        if norm > 0:
            direction = frame.from_ground(away / norm)
        else:  # a point support right below the centre: every direction alike
            direction = frame.axes[0].copy()
    if margin > tol:
        verdict = "stands"
    elif margin < -tol:
        verdict = "topples"
    else:
        verdict = "neutral"
    weight = finite_result(mass * req.g, "the weight M g", error=StabilityError)
    angle = tipping_angle_deg(margin, h) if verdict != "neutral" else 0.0
    energy = float(_energy(weight, margin, h)) if verdict == "stands" else 0.0
    roll = None
    if verdict == "neutral" and rocked is not None:
        roll, noise = rocked
        verdict = roll.kind(noise)
        k = int(np.argmin(roll.tilts_deg if verdict == "stands" else roll.rise()))
        direction = -roll.directions[k]  # the plane descends this way to turn it
        if verdict == "stands":
            angle, energy = float(roll.tilts_deg[k]), weight * roll.barrier()
    angles = tipping_angles_deg(distances, h)
    energies = _energy(weight, distances, h)
    edges = tuple(
        TippingEdge(sup.to_body(a), sup.to_body(b), frame.from_ground(n), float(d), float(t),
                    float(e))
        for a, b, n, d, t, e in zip(sup.edge_starts, sup.edge_ends, sup.edge_normals,
                                    distances, angles, energies))
    slope = None
    if req.tilt_deg is not None or req.toward_deg is not None:
        slope = slope_check(sup, verdict, margin, roll, direction, req)
    design = None
    if req.asks_design:
        design = DesignCheck(
            req.require_tilt_deg,
            None if req.require_tilt_deg is None else bool(
                verdict == "stands" and angle >= req.require_tilt_deg),
            req.margin,
            None if req.margin is None else bool(verdict == "stands" and margin >= req.margin))
    return Verdict(verdict, margin, angle, direction, energy, h, sup.center_of_mass, mass,
                   sup, edges, roll, req, slope, design, loaded=loaded)


def check(body, down=None, *, g: float = SEED_GRAVITY, tilt_deg: float | None = None,
          toward_deg: float | None = None, friction: float | None = None,
          require_tilt_deg: float | None = None, margin: float | None = None,
          loads=(), tolerance: float | None = None, props: MassProperties | None = None,
          requirement: Requirement | None = None) -> Verdict:
    """Will ``body`` stand on a horizontal plane with gravity along ``down``?

    Parameters
    ----------
    body : Body
        Any plumbob body.
    down : array_like, shape (dim,), optional
        The direction of gravity in the body's frame (any length); default −z for
        solids, −y for a lamina (in its own plane).
    g : float, default 9.81
        Gravitational acceleration, m/s².
    tilt_deg, toward_deg : float, optional
        Also check it on a plane tilted by ``tilt_deg`` degrees, descending toward
        ``toward_deg`` (in the ground plane, from e1 toward e2 — for ``down = −z``
        from +x toward +y); without ``toward_deg`` the worst direction.
    friction : float, optional
        Friction coefficient μ: does it slide (tan θ > μ) before it topples?
    require_tilt_deg : float, optional
        The design check: it must not topple when tilted this much in any direction
        (IEC 62368-1: 10°).
    margin : float, optional
        The design check: its static stability margin must be at least this, m.
    loads : sequence of Force, Hang, Push or Press, optional
        Applied loads: the verdict under them (``loaded``: the critical edge, the
        resisting and overturning moments about it, the factor of safety against
        overturning), with the tilt and friction above.
    requirement : Requirement, optional
        All of the above (``down`` to ``loads``) as one value, instead of the keywords.
    tolerance : float, optional
        Contact tolerance, m (default 1e-6 of the body's size).
    props : MassProperties, optional
        The body's mass properties, when already computed.

    Returns
    -------
    Verdict
        ``verdict`` (``"stands"``, ``"topples"``, ``"neutral"``), the margin, the
        critical tilt and its direction, the energy to topple, per support edge the
        tipping angle and energy, and the slope, friction and design checks asked
        for; ``as_dict()`` gives the keys of ``plumbob check --json``.

    Raises
    ------
    StabilityError
        For a body with nothing to stand on along ``down`` (particles in one plane),
        a tilt outside [0°, 90°) or a negative friction coefficient.

    Examples
    --------
    The seed's block, h × h × 4h upright, h = 1 m:

    >>> from plumbob.bodies.primitives import box, sphere
    >>> block = box(1, 1, 4, density=1000.0)
    >>> v = check(block)
    >>> v.verdict, round(v.critical_tilt_deg, 2), round(v.energy_to_topple / (4000 * 9.81), 6)
    ('stands', 14.04, 0.061553)

    On a 20° slope it goes over before it slides, and it fails a 15° design check:

    >>> check(block, tilt_deg=20, friction=0.3).slope
    SlopeCheck(tilt_deg=20°, toward_deg=-90°, verdict='topples', tipping_angle_deg=14.0362°, \
friction=0.3, slides_first=False)
    >>> check(block, require_tilt_deg=15).passes
    False

    Balanced on an edge it topples; a ball rolls (neutral):

    >>> check(block, down=[1, 0, -1]).verdict, check(sphere(1.0)).verdict
    ('topples', 'neutral')
    """
    body = answering(body, "body", "mass_properties")
    if requirement is None:
        requirement = Requirement(down, g, tilt_deg, toward_deg, friction, margin,
                                  require_tilt_deg, tuple(loads or ()))
    else:
        requirement = instance(requirement, "requirement", Requirement, error=StabilityError)
        given = (down, tilt_deg, toward_deg, friction, require_tilt_deg, margin)
        if any(v is not None for v in given) or g != SEED_GRAVITY or loads:
            raise StabilityError("give a requirement or its keywords (down, g, tilt_deg, ...), "
                                 "not both")
    props = body.mass_properties() if props is None else instance(props, "props", MassProperties)
    return _check(body, requirement, tolerance, props, settle=True)


def _check(body, requirement: Requirement, tolerance: float | None, props: MassProperties,
           settle: bool) -> Verdict:
    """:func:`check` of a checked body; with ``settle``, where a solid set down on a point,
    a line or a sliver comes to rest."""
    sup = support_polygon(body, requirement.down, tolerance=tolerance, props=props)
    loaded = None
    if requirement.loads:
        from .loaded import under_loads

        loaded = under_loads(body, sup, props.mass, requirement)
    result = verdict_from_support(sup, props.mass, requirement, loaded=loaded)
    size = sup.size  # measured once, by support_polygon
    if result.verdict == "neutral" and not is_polytope(body, size):
        # Over a point or line of contact on a curved surface: judge by curvature.
        sampling = sampling_tolerance(size)
        points = hull_points(body, sampling)[:, : sup.frame.dim] - sup.center_of_mass
        rocked = (rocking(points, sup.frame.down, 2 * sampling), 3 * sampling)
        result = verdict_from_support(sup, props.mass, requirement, rocked=rocked,
                                      loaded=loaded)
    contact = contact_kind(sup, size) if settle else None
    if contact is None:
        return result
    from .settled import settled_verdict  # the poses: only for a point, a line or a sliver

    return settled_verdict(body, result, contact, requirement.g, props, lambda down: _check(
        body, requirement.replace(down=down), tolerance, props, settle=False))
