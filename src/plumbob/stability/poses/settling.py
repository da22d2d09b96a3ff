"""Where a body released in a given orientation comes to rest.

A body set down with gravity along ``down`` but touching the ground only at a
point or along a line (a curved or finely faceted bottom, a rim) is not in a
pose: released there, it rolls quasi-statically downhill on the height function
``h(u)`` of :mod:`plumbob.stability.poses` until it rests on a stable face. The
pose it ends in is the one whose basin holds ``down``; :func:`settle` follows
that roll on the same exact hull the poses are computed on (so the answer names
the pose ``plumbob poses`` lists, by its rank), and reports how far the body turns.

Where it comes to rest:

* on a flat face (of a polytope, or a primitive's flat end): that face's normal,
  exact;
* at the bottom of a curved bowl (a ``"rocking"`` pose) of a body with curved
  surfaces: the sampled hull's lowest facet is only near the true bottom (by up to
  the facet's angular size), so the bottom is found again on the exact surface —
  the minimum of ``h(u) = max_p (p − c)·u`` with the body's exact support points,
  where the centre of mass lies straight above the contact (a ball's centre of
  curvature straight above its centre of mass);
* on a rolling surface (a cylinder's side): the sampled facet it lands on; it rolls
  on from there (neutral), so only the angle to the surface matters, and it is
  exact to the facet's angular size (``exact`` is False).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...arrays import unit
from ...errors import StabilityError
from ...massprops import MassProperties
from ...results import Key, Result
from ...tolerances import CONTACT, HULL_ROUND_OFF, size_of
from ...units import SEED_GRAVITY
from ..support import body_size, is_polytope, support_points
from .families import ROLL_ANGLE_DEG
from .resting import FALLBACK_SAMPLES, assemble_indexed, body_points, points_landscape
from .result import Poses
from .rolling import Roller, edge_geometry

__all__ = ["Settling", "settle", "SETTLE_STANDS_DEG"]

#: A body that comes to rest within this angle of where it was set down stands there (it
#: settles into the pose); turning further it has left the orientation it was checked in
#: (it rolls or falls onto another face). The poses' roll angle: within it, faces are one
#: pose.
SETTLE_STANDS_DEG = ROLL_ANGLE_DEG
_ON_FACE = 1e-12  # 1 − cos of the angle within which a down direction is a face's normal
_NUDGES = (0.0, 1e-9, 1e-7, 1e-5)  # rad: a roll lost on an edge is followed from aside
_NUDGE_DIRECTION = unit(np.array([[0.5773, 0.2245, 0.7853]]))[0]  # no axis's special


@dataclass(frozen=True, repr=False)
class Settling(Result):
    """Where a body set down with gravity along ``down_from`` comes to rest.

    contact: what it touches the ground with where it was set down: ``"point"``,
        ``"line"`` or ``"sliver"`` (a support polygon narrower than
        :data:`plumbob.tolerances.SLIVER` of the body's size: a facet of a fine
        tessellation).
    down_from: (3,) the down direction it was set down with, unit, body frame.
    down: (3,) the down direction it rests with, unit, body frame.
    angle_deg: the angle it turns through from ``down_from`` to ``down``, degrees.
    pose: the rank (1-based) of the pose it rests in, as ``plumbob poses`` lists them
        and ``--pose K`` takes them.
    pose_kind: ``"face"``, ``"rocking"`` (a bowl's bottom) or ``"rolling"`` (a surface
        it rolls along: a cylinder's side).
    verdict: its verdict there: ``"stands"``, or ``"neutral"`` in a rolling pose.
    critical_tilt_deg: the pose's critical tilt, degrees (0 for a rolling pose).
    com_height: height of the centre of mass at rest, m.
    drop: how far the centre of mass falls on the way, m (≥ 0 up to round-off).
    stays: whether it rests within :data:`SETTLE_STANDS_DEG` of where it was set down,
        or rocks back into a bowl's bottom (a weighted ball, a hemisphere on its dome):
        it stands as placed, settling into the pose. False: it rolls or falls away.
    exact: whether ``down`` is exact (a flat face's normal, or a bowl's bottom found on
        the exact surface); False for a landing on a sampled rolling surface, good to
        the sampling's facets.
    own_face: whether it rests on the face ``plumbob poses`` gives for the pose (or
        anywhere on a rolling pose's surface); False when it rests on another face of
        the pose's family (a mace standing on its thin shaft: a tilt of half a degree
        rolls it to the pose's own face, so ``poses`` counts that face in the pose).
    """

    contact: str
    down_from: np.ndarray
    down: np.ndarray
    angle_deg: float
    pose: int
    pose_kind: str
    verdict: str
    critical_tilt_deg: float
    com_height: float
    drop: float
    stays: bool
    exact: bool
    own_face: bool = True

    _repr_fields = ("contact", "angle_deg", "pose", "pose_kind", "verdict", "stays")

    #: the keys of the ``settles`` object of ``plumbob check --json``
    KEYS = (
        Key("contact", "", "what it touches the ground with as set down: `point`, `line` or "
                           "`sliver`", type="str"),
        Key("down_from", "", "the down it was set down with, body frame (unit vector)",
            type="xyz"),
        Key("down", "", "the down it rests with", type="xyz"),
        Key("angle_deg", "°", "how far it turns", type="float"),
        Key("pose", "", "the rank of the pose it rests in (`plumbob poses`, `--pose K`)",
            type="int"),
        Key("pose_kind", "", "`face`, `rocking` or `rolling`", type="str"),
        Key("verdict", "", "its verdict where it rests", type="str"),
        Key("critical_tilt_deg", "°", "the critical tilt where it rests", type="float"),
        Key("com_height", "m", "the centre of mass's height at rest", type="float"),
        Key("drop", "m", "how far its centre of mass falls", type="float"),
        Key("stays", "", "whether it rests within 15° of where it was set down (it stands as "
                         "placed, settling)", type="bool"),
        Key("exact", "", "false where it lands on a sampled rolling surface", type="bool"),
        Key("own_face", "", "false where it rests on another face of the pose's family",
            type="bool"),
    )

    @property
    def phrase(self) -> str:
        """The settling in words: ``"settles 0.05° into pose 3"``, ``"rolls 80° onto pose 2,
        where it rolls"`` (angles to 3 significant digits)."""
        angle = f"{self.angle_deg:.3g}°"
        where = f"pose {self.pose}" if self.own_face else f"a face of pose {self.pose}"
        if self.stays:
            return f"settles {angle} {'into' if self.own_face else 'onto'} {where}"
        there = "where it rolls" if self.verdict == "neutral" else (
            f"where it stands, critical tilt {self.critical_tilt_deg:.3g}°")
        return f"rolls {angle} onto {where}, {there}"


def _height(body, u: np.ndarray, com: np.ndarray, tol: float) -> tuple[float, np.ndarray]:
    """``h(u)`` with the body's exact support points, m, and the contact point (3,) m."""
    pts = support_points(body, u, tol)
    k = int(np.argmax(pts @ u))
    return float((pts[k] - com) @ u), pts[k]


def _bowl_bottom(body, start: np.ndarray, com: np.ndarray, size: float) -> np.ndarray:
    """The minimum of ``h`` on the exact surface near ``start`` (3,), unit: where the centre
    of mass lies straight above the contact. ``h``'s gradient on the sphere is the contact
    point's offset from the centre (the envelope theorem), exact with exact support
    points."""
    from scipy.optimize import minimize, root

    tol = HULL_ROUND_OFF * size  # a curved surface's exact lowest point, not its samples
    helper = np.eye(3)[np.argmin(np.abs(start))]
    t1 = unit(np.cross(start, helper)[None])[0]
    t2 = np.cross(start, t1)
    basis = np.array([t1, t2])

    def fun(x: np.ndarray) -> tuple[float, np.ndarray]:
        v = start + x @ basis
        norm = float(np.linalg.norm(v))
        u = v / norm
        h, p = _height(body, u, com, tol)
        grad_u = p - com  # dh/du
        grad_x = basis @ (grad_u - (grad_u @ u) * u) / norm
        return h / size, grad_x / size

    found = minimize(fun, np.zeros(2), jac=True, method="BFGS",
                     options={"gtol": 1e-12, "maxiter": 200})
    # h is flat to second order at its bottom: function values stop BFGS about 1e-8 rad
    # short; the gradient (exact) goes on to zero with a root finder
    polished = root(lambda x: fun(x)[1], found.x, method="hybr", options={"xtol": 1e-15})
    x = polished.x if polished.success else found.x
    u = start + x @ basis
    return u / np.linalg.norm(u)


def _angle_deg(a: np.ndarray, b: np.ndarray) -> float:
    """The angle between unit vectors, degrees, accurate near 0 and 180°."""
    return float(np.degrees(2 * np.arctan2(np.linalg.norm(a - b), np.linalg.norm(a + b))))


def _on_circle(u0: np.ndarray, axis: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """The direction nearest ``u0`` on the circle of a rolling surface's normals about
    ``axis`` through ``normal``: where a body of revolution set down on its rim lands on its
    side (it turns in the plane of its axis and ``down``)."""
    k = float(normal @ axis)
    across = u0 - (u0 @ axis) * axis
    norm = float(np.linalg.norm(across))
    if norm <= _ON_FACE:  # down along the axis: every side direction alike
        return normal.copy()
    return k * axis + np.sqrt(max(0.0, 1.0 - k * k)) * across / norm


def settle(body, down, *, contact: str = "point", g: float = SEED_GRAVITY,
           sampling_tolerance: float | None = None, props: MassProperties | None = None,
           rolls_here: bool = False) -> tuple[Settling, Poses]:
    """Where ``body`` (a solid), set down with gravity along ``down`` (3,), comes to rest,
    and its resting poses (those of :func:`~.resting.resting_poses`).

    contact: what it touches the ground with there (``"point"``, ``"line"``,
    ``"sliver"``), carried into the result. rolls_here: the caller knows the body rolls
    where it was set down (a ball, a cylinder on its side): should the roll end in a
    rolling pose, it rests (rolls) where it is.

    >>> from plumbob.bodies.primitives import hemisphere
    >>> s, poses = settle(hemisphere(1.0), [0.5, 0.0, 0.8660254037844386])  # on its dome
    >>> s.pose, s.pose_kind, round(s.angle_deg, 6), s.stays
    (1, 'rocking', 30.0, True)
    """
    props = body.mass_properties() if props is None else props
    u0 = np.asarray(down, dtype=float).reshape(-1)
    if u0.shape != (3,):
        raise StabilityError("settling is worked out for solids: down needs 3 components")
    u0 = u0 / np.linalg.norm(u0)
    pts, com, neutral_height, surface = body_points(body, props, sampling_tolerance)
    land, com = points_landscape(pts, com, tolerance=None, roll_angle_deg=ROLL_ANGLE_DEG,
                                 neutral_height=neutral_height, samples=FALLBACK_SAMPLES,
                                 surface=surface)
    poses, pose_of = assemble_indexed(land, com, float(props.mass), float(g), ROLL_ANGLE_DEG,
                                      neutral_height, [])
    h = land.hull
    face = _rest_face(h, u0, HULL_ROUND_OFF * size_of(land.points))
    normal = h.normals[face]
    candidate = int(np.argmax(land.normals @ normal))  # the landed face among the poses'
    index = int(pose_of[candidate])
    pose = poses[index]
    rest, exact = normal.copy(), True
    size = body_size(body)
    polytope = is_polytope(body, size)
    # a rocking pose's facets near its bottom (within the roll angle) are the bowl's: it
    # rocks down to the bottom (a tilt of a hundredth of a degree rolls a fine mesh from
    # facet to facet); a face far from it (a mace on its shaft's end) is a face to stand on
    bowl = pose.kind == "rocking" and _angle_deg(normal, pose.down) <= SETTLE_STANDS_DEG
    if bowl and not polytope and _touches_at_a_point(body, normal, size):
        rest = _bowl_bottom(body, normal, com, size)  # a sampled curved bowl: its true bottom
    elif bowl:
        rest = pose.down.copy()  # the bowl's lowest face
    elif pose.kind == "rolling" and rolls_here:
        rest = u0.copy()  # on its rolling surface already: it rolls, from where it is
    elif pose.kind == "rolling" and not polytope:  # a sampled surface's facet: near it
        exact = False
        if pose.axis is not None:
            rest = _on_circle(u0, pose.axis, normal)
    height = _height(body, rest, com, CONTACT * size)[0]
    start = _height(body, u0, com, CONTACT * size)[0]
    angle = _angle_deg(u0, rest)
    own = bowl or pose.kind == "rolling" or bool(np.array_equal(normal, pose.down))
    stays = angle <= SETTLE_STANDS_DEG or bowl
    verdict = "neutral" if pose.kind == "rolling" else "stands"
    return Settling(contact, u0, rest, angle, index + 1, pose.kind, verdict,
                    float(pose.critical_tilt_deg), height, start - height, bool(stays),
                    exact, own), poses


def _touches_at_a_point(body, down: np.ndarray, size: float) -> bool:
    """Whether the body's exact surface touches the ground at a point with ``down`` (3,)
    (a curved bowl's facet), not on a face or along a line (a flat end among them)."""
    pts = support_points(body, down, CONTACT * size)
    return size_of(pts) <= 4.0 * np.sqrt(2.0 * CONTACT) * size  # a sphere's contact spread


def _rest_face(h, u0: np.ndarray, eps: float) -> int:
    """The stable face of hull ``h`` a quasi-static roll from direction ``u0`` ends on."""
    roller = Roller(h, edge_geometry(h, eps), unit(h.X), eps)
    on = np.flatnonzero(roller.stable & (h.normals @ u0 >= 1.0 - _ON_FACE))
    if len(on):  # set down on a stable face already
        return int(on[np.argmax(h.normals[on] @ u0)])
    real = np.flatnonzero(h.degree > 0)
    for nudge in _NUDGES:  # down exactly on an edge's arc or at a corner: by a hair aside
        u = unit((u0 + nudge * _NUDGE_DIRECTION)[None])[0]
        start = real[np.argmax(h.X[real] @ u)]
        try:
            face = int(roller.roll(vertex=np.array([start]), point=u[None])[0])
        except StabilityError:
            face = -1
        if face >= 0:
            return face
    raise StabilityError("the roll from the given down direction could not be followed to a "
                         "resting pose (a degenerate hull)")
