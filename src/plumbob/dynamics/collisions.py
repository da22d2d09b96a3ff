"""Collisions of smooth, non-rotating bodies modelled as particles (seed sections 3 and 4).

Newton's law of restitution along the common normal ``n``:

* the velocity components parallel to the common tangent plane are unchanged;
* the relative normal velocity is reversed and scaled by ``e``:
  ``(V₁ − V₂)·n = −e (v₁ − v₂)·n``;
* the total linear momentum is conserved: ``m₁V₁ + m₂V₂ = m₁v₁ + m₂v₂``.

Solved in closed form with the impulse ``J = (1 + e) μ (v₁ − v₂)·n`` on body 2
(``−J`` on body 1), where ``μ = m₁m₂/(m₁ + m₂)`` is the reduced mass; the
kinetic energy lost is ``½ μ (1 − e²) ((v₁ − v₂)·n)²``. A fixed surface is body 2
with infinite mass (``μ = m₁``): it takes up the impulse without moving.

Units: kg, m/s, kg·m/s, J. Vectors have 1, 2 or 3 components.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..arguments import finite_result, vector
from ..errors import DynamicsError
from ..results import Key, Result

__all__ = [
    "CollisionResult",
    "ImpactCheck",
    "collide",
    "check_impact",
    "restitution_from_bounces",
    "bounce_heights",
    "ELASTIC_RTOL",
]

#: A collision is reported elastic when it loses at most this fraction of its
#: kinetic energy (round-off allowance; any e < 1 − 1e-9 is inelastic).
ELASTIC_RTOL = 1e-9

Vector = Sequence[float] | np.ndarray | float


@dataclass(frozen=True, eq=False, repr=False)
class CollisionResult(Result):
    """The outcome of one instantaneous collision between body 1 and body 2.

    m1, m2: masses, kg (``m2`` is ``inf`` for a fixed surface).
    e: coefficient of restitution, 0 ≤ e ≤ 1.
    normal: (d,) unit common normal, pointing from body 1 towards body 2.
    v1_before, v2_before, v1_after, v2_after: (d,) velocities, m/s.
    impulse: the impulse on body 2 along ``normal``, N·s (body 1 gets the opposite).
    ke_before, ke_after, ke_loss: kinetic energy, J. For a fixed surface these are
        the kinetic energies of body 1 relative to the surface (its rest frame).
    momentum_before, momentum_after: (d,) total linear momentum, kg·m/s. For a
        fixed surface: the momentum of body 1 alone (the surface takes up the change).
    elastic: True when no kinetic energy is lost (to ``ELASTIC_RTOL``).
    """

    m1: float
    m2: float
    e: float
    normal: np.ndarray
    v1_before: np.ndarray
    v2_before: np.ndarray
    v1_after: np.ndarray
    v2_after: np.ndarray
    impulse: float
    ke_before: float
    ke_after: float
    ke_loss: float
    momentum_before: np.ndarray
    momentum_after: np.ndarray
    elastic: bool

    _repr_fields = ("m1", "m2", "e", "normal", "v1_after", "v2_after", "ke_loss", "elastic")

    @property
    def wall(self) -> bool:
        """True when body 2 is a fixed surface (infinite mass)."""
        return math.isinf(self.m2)

    @property
    def m2_json(self) -> float | str:
        """``m2``, or the string ``"inf"`` for a fixed surface (JSON has no such number)."""
        return "inf" if self.wall else self.m2

    #: the keys of ``plumbob collide --json`` (SI units)
    KEYS = (
        Key("m1", "kg", "body 1's mass"),
        Key("m2", "kg", "body 2's mass (`\"inf\"`: a fixed surface)", attr="m2_json"),
        Key("e", "", "the coefficient of restitution"),
        Key("normal", "", "the unit common normal, from body 1 toward body 2"),
        Key("v1_before", "m/s", "body 1's velocity before"),
        Key("v2_before", "m/s", "body 2's velocity before"),
        Key("v1_after", "m/s", "body 1's velocity after"),
        Key("v2_after", "m/s", "body 2's velocity after"),
        Key("impulse", "N·s", "on body 2 along the normal"),
        Key("ke_before", "J", "kinetic energy before (a fixed surface: body 1's)"),
        Key("ke_after", "J", "kinetic energy after"),
        Key("ke_loss", "J", "what the collision takes"),
        Key("elastic", "", "whether no kinetic energy is lost"),
        Key("momentum_before", "kg·m/s", "total linear momentum before"),
        Key("momentum_after", "kg·m/s", "total linear momentum after"),
    )


@dataclass(frozen=True, eq=False, repr=False)
class ImpactCheck(Result):
    """Before/after bookkeeping of a collision whose outcome is given (seed Exercise 26).

    ke_before, ke_after, ke_loss: J. momentum_before, momentum_after: (d,) kg·m/s.
    momentum_conserved: the two momenta agree to 1e-9 relative.
    elastic: the kinetic energy is unchanged to ``ELASTIC_RTOL``.
    """

    ke_before: float
    ke_after: float
    ke_loss: float
    momentum_before: np.ndarray
    momentum_after: np.ndarray
    momentum_conserved: bool
    elastic: bool


# --------------------------------------------------------------------- checks
def _mass(value: float, label: str, *, infinite_ok: bool = False) -> float:
    try:
        mass = float(value)
    except (TypeError, ValueError):
        raise DynamicsError(f"mass {label} must be a number (got {value!r})") from None
    if math.isnan(mass) or mass <= 0:
        raise DynamicsError(f"mass {label} must be positive (got {value!r} kg); "
                            "give the mass in kilograms")
    if math.isinf(mass) and not infinite_ok:
        raise DynamicsError(f"mass {label} must be finite; to model a fixed surface "
                            "make it body 2 with m2 = inf")
    return mass


def _vector(value: Vector, label: str) -> np.ndarray:
    """One velocity or normal of 1 to 3 finite components (a (1, 3) array is refused)."""
    return vector(value, label, (1, 2, 3), error=DynamicsError)


def _restitution(e: float) -> float:
    try:
        e = float(e)
    except (TypeError, ValueError):
        raise DynamicsError(f"the coefficient of restitution must be a number (got {e!r})"
                            ) from None
    if not 0.0 <= e <= 1.0:
        raise DynamicsError(f"the coefficient of restitution e must lie in [0, 1] (got {e}); "
                            "e = 1 is elastic, e = 0 coalescing")
    return e


def _ke(mass: float, v: np.ndarray) -> float:
    return 0.5 * mass * float(v @ v)


# ------------------------------------------------------------------ collide
def collide(m1: float, v1: Vector, m2: float, v2: Vector | None = None,
            normal: Vector | None = None, e: float = 1.0) -> CollisionResult:
    """Velocities after an instantaneous collision by Newton's law of restitution.

    Parameters
    ----------
    m1, m2 : float
        Masses, kg; ``m2 = inf`` is a fixed (or uniformly moving) surface.
    v1, v2 : array_like or float
        Velocities just before impact, m/s, 1 to 3 components (``v2`` defaults to rest).
    normal : array_like, optional
        The common normal, pointing from body 1 towards body 2 (any length). Default:
        the direction of the relative velocity ``v1 − v2`` (a head-on impact).
    e : float, default 1
        Coefficient of restitution in [0, 1]: 1 elastic, 0 coalescing along the normal.

    Returns
    -------
    CollisionResult
        The velocities after, the impulse on body 2, the kinetic energy and momentum
        before and after, and whether it was elastic; ``as_dict()`` gives the keys of
        ``plumbob collide --json``.

    Raises
    ------
    DynamicsError
        For a non-positive mass, ``e`` outside [0, 1], a zero normal, mismatched
        dimensions, or bodies not approaching along the normal.

    Examples
    --------
    Seed Example 6 (snooker balls, elastic, head-on): A stops, B takes A's 5 m/s.

    >>> r = collide(0.17, [5, 0], 0.17, [0, 0])
    >>> r.v1_after.round(12) + 0, r.v2_after.round(12) + 0, r.elastic
    (array([0., 0.]), array([5., 0.]), True)

    Seed Example 5 (railway trucks coupling, e = 0): 1.25 m/s.

    >>> float(collide(50_000, 2, 30_000, 0, e=0).v1_after[0])
    1.25

    A ball bouncing on a floor (normal from the ball into the floor, i.e. down):

    >>> collide(0.1, [3, -4], float("inf"), [0, 0], normal=[0, -1], e=0.5)
    CollisionResult(m1=0.1 kg, m2=inf kg, e=0.5, normal=[0, -1], v1_after=[3, 2] m/s, \
v2_after=[0, 0] m/s, ke_loss=0.6 J, elastic=False)

    Bodies moving apart do not collide:

    >>> collide(1.0, [-1.0], 1.0, [1.0], normal=[1.0])
    Traceback (most recent call last):
    ...
    plumbob.errors.DynamicsError: no collision: the bodies are not approaching along the \
normal (closing speed -2 m/s). The normal points from body 1 towards body 2; reverse it \
if you meant the other side
    """
    m1 = _mass(m1, "m1")
    m2 = _mass(m2, "m2", infinite_ok=True)
    e = _restitution(e)
    v1 = _vector(v1, "v1")
    v2 = np.zeros_like(v1) if v2 is None else _vector(v2, "v2")
    if v2.shape != v1.shape:
        raise DynamicsError(f"v1 and v2 must have the same number of components "
                            f"(got {v1.size} and {v2.size})")
    with np.errstate(over="ignore", invalid="ignore"):  # overflow is refused below
        relative = v1 - v2
        if normal is None:
            norm = float(np.linalg.norm(relative))
            if norm == 0.0:
                raise DynamicsError("no collision: the bodies have the same velocity, so they "
                                    "never meet; check v1 and v2")
            n = relative / norm
        else:
            n = _vector(normal, "normal")
            if n.shape != v1.shape:
                raise DynamicsError(f"the normal must have {v1.size} components like the "
                                    f"velocities (got {n.size})")
            norm = float(np.linalg.norm(n))
            if norm == 0.0:
                raise DynamicsError("the collision normal is the zero vector; give a direction "
                                    "perpendicular to the common tangent plane")
            n = n / norm
        approach = float(relative @ n)  # closing speed along the normal, m/s
        scale = max(float(np.linalg.norm(v1)), float(np.linalg.norm(v2)))
        if approach <= 1e-12 * scale:
            raise DynamicsError(
                f"no collision: the bodies are not approaching along the normal (closing speed "
                f"{approach:.6g} m/s). The normal points from body 1 towards body 2; reverse it "
                "if you meant the other side")
        reduced = m1 / (1.0 + m1 / m2)  # m1 m2 / (m1 + m2); m1 for a wall
        impulse = (1.0 + e) * reduced * approach
        v1_after = v1 - (impulse / m1) * n
        v2_after = v2 + (impulse / m2) * n  # unchanged for a wall (impulse / inf == 0)
        if math.isinf(m2):
            ke_before = _ke(m1, v1 - v2)
            ke_after = _ke(m1, v1_after - v2_after)
            momentum_before, momentum_after = m1 * v1, m1 * v1_after
        else:
            ke_before = _ke(m1, v1) + _ke(m2, v2)
            ke_after = _ke(m1, v1_after) + _ke(m2, v2_after)
            momentum_before = m1 * v1 + m2 * v2
            momentum_after = m1 * v1_after + m2 * v2_after
        ke_loss = ke_before - ke_after
        elastic = abs(ke_loss) <= ELASTIC_RTOL * ke_before
    finite_result([ke_before, ke_after, impulse, *momentum_before, *momentum_after,
                   *v1_after, *v2_after], "the collision's energy or momentum",
                  error=DynamicsError)
    return CollisionResult(m1, m2, e, n, v1, v2, v1_after, v2_after, impulse, ke_before,
                           ke_after, ke_loss, momentum_before, momentum_after, bool(elastic))


def check_impact(m1: float, v1: Vector, m2: float, v2: Vector,
                 v1_after: Vector, v2_after: Vector) -> ImpactCheck:
    """Kinetic energy and momentum of a collision whose outcome is known.

    Masses kg, velocities m/s. Answers the seed's "is this collision elastic?".

    Seed Exercise 26(b): inelastic, 1.5 J lost.

    >>> c = check_impact(1, [2, 1], 3, [0, 1], [0.5, 1], [0.5, 1])
    >>> c.ke_before, c.ke_after, c.ke_loss, c.elastic, c.momentum_conserved
    (4.0, 2.5, 1.5, False, True)
    """
    m1, m2 = _mass(m1, "m1"), _mass(m2, "m2")
    vs = [_vector(v, label) for v, label in
          ((v1, "v1"), (v2, "v2"), (v1_after, "v1_after"), (v2_after, "v2_after"))]
    if len({v.size for v in vs}) != 1:
        raise DynamicsError("all four velocities must have the same number of components")
    a, b, c, d = vs
    ke_before = _ke(m1, a) + _ke(m2, b)
    ke_after = _ke(m1, c) + _ke(m2, d)
    p_before, p_after = m1 * a + m2 * b, m1 * c + m2 * d
    scale = m1 * np.linalg.norm(a) + m2 * np.linalg.norm(b) + m1 * np.linalg.norm(c) + \
        m2 * np.linalg.norm(d)
    conserved = float(np.linalg.norm(p_after - p_before)) <= 1e-9 * max(scale, 1e-300)
    loss = ke_before - ke_after
    return ImpactCheck(ke_before, ke_after, loss, p_before, p_after, bool(conserved),
                       bool(abs(loss) <= ELASTIC_RTOL * ke_before))


# -------------------------------------------------------------------- bounces
def restitution_from_bounces(h0: float, hn: float, bounces: int = 1) -> float:
    """Coefficient of restitution of a ball dropped from ``h0`` that rises to ``hn``
    after ``bounces`` bounces on a fixed floor: ``hₙ = e²ⁿ h₀`` (heights in m).

    Seed Exercise 30: half the height after two bounces, e = 2^(−1/4).

    >>> round(restitution_from_bounces(1.0, 0.5, 2), 4)
    0.8409
    >>> restitution_from_bounces(2.0, 0.0)   # no bounce at all
    0.0
    """
    try:
        h0, hn = float(h0), float(hn)
    except (TypeError, ValueError):
        raise DynamicsError("bounce heights must be numbers") from None
    if not (math.isfinite(h0) and h0 > 0):
        raise DynamicsError(f"the drop height must be positive (got {h0} m)")
    if not (math.isfinite(hn) and 0 <= hn <= h0):
        raise DynamicsError(f"the rebound height must lie between 0 and the drop height "
                            f"{h0} m (got {hn} m)")
    if int(bounces) != bounces or bounces < 1:
        raise DynamicsError(f"the number of bounces must be a positive integer (got {bounces})")
    return (hn / h0) ** (1.0 / (2 * int(bounces)))


def bounce_heights(h0: float, e: float, bounces: int) -> np.ndarray:
    """Heights (m) reached after 0, 1, …, ``bounces`` bounces: ``hₖ = e²ᵏ h₀``.

    >>> bounce_heights(1.0, 0.5, 3)
    array([1.      , 0.25    , 0.0625  , 0.015625])
    """
    e = _restitution(e)
    if not (math.isfinite(float(h0)) and h0 > 0):
        raise DynamicsError(f"the drop height must be positive (got {h0} m)")
    if int(bounces) != bounces or bounces < 0:
        raise DynamicsError(f"the number of bounces must be a whole number (got {bounces})")
    return float(h0) * (e * e) ** np.arange(int(bounces) + 1)
